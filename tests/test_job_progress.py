"""jpct and jeta: the progress of the whole job (every run of the script), known where the script's runs
are known before they start; nan (a number still) and a header saying why where they are not."""
import math

import pytest

import dem
from dem.errors import DemError

SETUP = """region box block 0 1 0 1 0 1
create_box 1 box
create_atoms 1 single 0.5 0.5 0.5 radius 0.1 density 1000
fix move all nve/sphere
timestep 0.001
thermo_style custom step pct jpct jeta
thermo 50
"""


def script_file(tmp_path, script):
    path = tmp_path / "in.job"
    path.write_text(SETUP + script)
    return str(path)


def job(tmp_path, script, variables=()):
    """(jpct column, the header notes) of a script run as one job (sim.file, as dem -in reads it)."""
    log = tmp_path / "log.job"
    with dem.Simulation(screen=False, log=str(log), variables=variables) as sim:
        sim.file(script_file(tmp_path, script))
        jpct = sim.thermo_history()["jpct"]
    notes = [ln for ln in log.read_text().splitlines() if ln.startswith("(pct and eta")]
    return jpct, notes


def test_known_runs_count_to_the_whole_job(tmp_path):
    """Plain numbers, a variable, an expression, run 0: 100 + 200 + 300 + 0 steps."""
    jpct, notes = job(tmp_path, "variable n equal 200\nrun 100\nrun ${n}\nrun $(3*v_n/2)\nrun 0\n")
    assert notes[0].endswith("jpct and jeta: of the job (run 1 of 4, 600 steps in all), jeta at this run's speed)")
    assert "run 4 of 4, 600 steps" in notes[3]
    assert list(jpct[:3]) == pytest.approx([0.0, 100 * 50 / 600, 100 * 100 / 600])
    assert jpct[-1] == 100.0


def test_var_overrides_the_script(tmp_path):
    """-var n 50 wins over the script's `variable n index 100`, in the job's length too."""
    jpct, notes = job(tmp_path, "variable n index 100\nrun ${n}\nrun ${n}\n", variables=[("n", ["50"])])
    assert "100 steps in all" in notes[0] and jpct[1] == 50.0


def test_upto_counts_from_the_step_it_starts_at(tmp_path):
    _, notes = job(tmp_path, "run 100\nrun 300 upto\n")
    assert "300 steps in all" in notes[0]
    _, notes = job(tmp_path, "run 100\nreset_timestep 1000\nrun 1200 upto\n")
    assert "300 steps in all" in notes[0]


def test_zero_length_job(tmp_path):
    jpct, notes = job(tmp_path, "run 0\nprint 'JETA $(jeta)'\n")
    assert "run 1 of 1, 0 steps in all" in notes[0] and list(jpct) == [100.0]


def test_run_every_chunks_count_once(tmp_path):
    jpct, notes = job(tmp_path, "run 100 every 50 NULL\nrun 100\n")
    assert "run 1 of 2, 200 steps in all" in notes[0] and "run 2 of 2" in notes[-1]
    assert jpct[-1] == 100.0


@pytest.mark.parametrize("script, why", [
    ("variable n equal 100\nrun ${n}\nvariable n delete\nvariable n equal 200\nrun ${n}\n",
     "line 12 'run ${n}' reads variables that change before it (n)"),
    ("run 100\nvariable n equal step+100\nrun ${n}\n", "'run ${n}' has a length not known before the run"),
    ("variable m equal 10\nrun 100\nrun 100 every 50 'variable m equal 5'\nrun ${m}\n", "reads variables that change before it (m)"),
    ("run 100\nrun abc\n", "line 9 'run abc' has no plain number of steps"),
    ("variable i loop 2\nlabel again\nrun 10\nnext i\njump SELF again\n", "repeats a run in a loop"),
    ("run 10\nif '1 > 0' then 'run 10'\n", "holds 'run 10', which may or may not happen"),
    ("run 10\njump SELF later\nrun 10\nlabel later\n", "jumps forward"),
    ("run 10\ninclude in.other\n", "includes a file"),
    ("run 10\nvariable c string run\n${c} 10\n", "names its command with a variable"),
    ("run 100\nrun 50 upto\n", "runs up to a step, from a step not known now"),
])
def test_unknown_job_length_is_nan_and_said(tmp_path, script, why):
    """The first run's thermo: jpct nan (a number: the columns stay numeric) and the header says why."""
    log = tmp_path / "log.job"
    with dem.Simulation(screen=False, log=str(log)) as sim:
        with pytest.raises(DemError):          # each script's own error (or its end) after the first run
            sim.file(script_file(tmp_path, script + "run -1\n"))
        jpct = sim.thermo_history()["jpct"]
    lines = log.read_text().splitlines()
    note = next(ln for ln in lines if ln.startswith("(pct and eta"))
    assert "jpct and jeta: nan, the job's length is not known" in note and why in note, note
    assert math.isnan(jpct[0])
    row = lines[lines.index(note) + 2].split()           # the first line under the column names
    assert math.isnan(float(row[2])) and math.isnan(float(row[3]))


def test_a_loop_without_runs_is_fine(tmp_path):
    """A loop of create_atoms (inputs/in.drum's rough wall) leaves the runs known."""
    loop = "variable i loop 3\nlabel again\nvariable x equal 0.2*v_i\nnext i\njump SELF again\n"
    _, notes = job(tmp_path, loop + "run 10\nrun 20\n")
    assert "30 steps in all" in notes[0]


def test_bad_run_is_a_clear_error_naming_its_line(tmp_path):
    with dem.Simulation(screen=False) as sim:
        with pytest.raises(DemError) as err:
            sim.file(script_file(tmp_path, "run 10\nrun abc\n"))
    assert err.value.where.endswith("in.job:9") and "abc" in str(err.value)


def test_python_api_runs_are_no_job(tmp_path):
    log = tmp_path / "log.api"
    with dem.Simulation(screen=False, log=str(log)) as sim:
        sim.commands(SETUP)
        sim.run(10)
        sim.command("run 10")
        jpct = sim.thermo_history()["jpct"]
    notes = [ln for ln in log.read_text().splitlines() if ln.startswith("(pct and eta")]
    assert len(notes) == 2 and all("(a run started from Python (sim.run, sim.command), not by a script)" in n
                                     for n in notes)
    assert all(math.isnan(v) for v in jpct)


def test_jeta_uses_this_runs_speed_else_the_jobs():
    """700 steps left: at this run's 50 steps/s, 14 s; before it has a speed, at the job's 100 steps/s."""
    sim = dem.Simulation(screen=False)
    up, job_ = sim.update, sim.job
    job_.total, job_.done, job_.seconds = 1000, 200, 2.0
    up.running, up.first_step, up.ntimestep = True, 0, 100
    up.progress = lambda: (0.0, 50.0, 0.0)
    assert job_.progress() == (30.0, 14.0)
    up.progress = lambda: (0.0, 0.0, math.inf)
    assert job_.progress() == (30.0, 7.0)
    job_.done, job_.seconds, up.ntimestep = 0, 0.0, 0        # no speed at all yet
    assert math.isnan(job_.progress()[1])


def test_the_drum_jobs_runs_are_known():
    """inputs/in.drum (fill, settle, rotate, run 0; a loop of create_atoms before them) is a known job."""
    import pathlib
    from dem.job_scan import scan
    path = pathlib.Path(__file__).parent.parent / "inputs" / "in.drum"
    plan = scan(str(path), path.read_text().splitlines())
    assert plan.reason == "" and len(plan.runs()) == 4
