"""run N upto, start/stop, pre/post and every M "commands", as in LAMMPS."""
import pytest

import dem

READY = """units si
boundary p p f
region box block 0 0.01 0 0.01 0 0.01
create_box 1 box
create_atoms 1 random 20 5 box radius 0.0005 density 2500
pair_style sphere
pair_coeff * * kn 1000 en 0.5
fix nve all nve/sphere
timestep 1e-6
thermo 0
"""


def make(tmp_path, text, log=None):
    sim = dem.Simulation(screen=False, log=str(tmp_path / log) if log else None)
    sim.commands(READY + text)
    return sim


def test_upto_stops_at_that_step(tmp_path):
    sim = make(tmp_path, "run 30\nrun 100 upto\n")
    assert sim.update.ntimestep == 100
    sim.command("run 100 upto")          # already there: a run of 0 steps
    assert sim.update.ntimestep == 100
    with pytest.raises(dem.DemError, match="already past step 50"):
        sim.command("run 50 upto")


def test_every_runs_the_commands_between_chunks(tmp_path):
    out = tmp_path / "steps.txt"
    sim = make(tmp_path, f'run 100 every 40 "print $(step) append {out} screen no" NULL\n')
    assert sim.update.ntimestep == 100
    assert out.read_text().split() == ["40", "80", "100"]      # the last chunk is shorter


def test_every_gives_the_same_trajectory_and_frames_once(tmp_path):
    h5py = pytest.importorskip("h5py")
    a = make(tmp_path, f"dump d all h5 20 {tmp_path / 'a.h5'}\nrun 100\n")
    b = make(tmp_path, f'dump d all h5 20 {tmp_path / "b.h5"}\nrun 100 every 20 "print chunk"\n')
    assert (a.gather("x") == b.gather("x")).all() and (a.gather("v") == b.gather("v")).all()
    a.close(), b.close()
    for name in ("a.h5", "b.h5"):
        with h5py.File(tmp_path / name, "r") as h5:
            assert sorted(int(k) for k in h5["frames"]) == [0, 20, 40, 60, 80, 100]


def test_start_stop_are_recorded_and_checked(tmp_path):
    sim = make(tmp_path, "run 10 start 0 stop 1000\n")
    assert (sim.update.beginstep, sim.update.endstep) == (0, 1000)
    sim.command("run 10")
    assert (sim.update.beginstep, sim.update.endstep) == (10, 20)
    with pytest.raises(dem.DemError, match="start 50 must be <= the current step 20"):
        sim.command("run 10 start 50")
    with pytest.raises(dem.DemError, match=r"stop 25 must be >= the last step of this run \(30\)"):
        sim.command("run 10 stop 25")


def test_pre_no_and_post_no_shorten_the_output(tmp_path):
    sim = make(tmp_path, 'run 30 pre no post no every 10 NULL\n', log="log.test")
    sim.close()
    log = (tmp_path / "log.test").read_text()
    assert log.count("Loop time") == 3 and log.count("Section timing") == 1    # full summary after the last
    header = next(line for line in log.splitlines() if line.split()[:1] == ["step"])
    assert log.count(header) == 1                                          # one thermo header


def test_a_run_inside_every_is_refused(tmp_path):
    with pytest.raises(dem.DemError, match="cannot be started from inside a run"):
        make(tmp_path, 'run 10 every 5 "run 3"\n')


@pytest.mark.parametrize("n", [float("nan"), float("inf"), 2.5])
def test_python_run_refuses_a_step_count_that_is_not_whole(tmp_path, n):
    sim = make(tmp_path, "")
    with pytest.raises(dem.DemError, match="run: the number of steps must be a whole number"):
        sim.run(n)
