"""The Python API of docs/python.md: its example runs as printed, and `sim.every` / `fix python/every` call
Python every N steps after the step, with the state of that step's output."""
import re
from pathlib import Path

import numpy as np
import pytest

import dem

DOC = Path(__file__).resolve().parents[1] / "docs" / "python.md"
BALL = """
units si
region box block 0 0.01 0 0.01 0 0.02
create_box 1 box
create_atoms 1 single 0.005 0.005 0.01 radius 0.001 density 2500
fix integrate all nve/sphere
fix gravity all gravity 9.81 vector 0 0 -1
timestep 1e-4
thermo 0
"""


def test_the_documented_example_runs(tmp_path, monkeypatch, capsys):
    blocks = re.findall(r"```python\n(.*?)```", DOC.read_text(), re.S)
    example = next(b for b in blocks if "sim.every" in b)
    monkeypatch.chdir(tmp_path)
    namespace = {}
    exec(compile(example, str(DOC), "exec"), namespace)
    history, sim = namespace["history"], namespace["sim"]
    assert [h[0] for h in history] == list(range(250, 3001, 250))
    counts = [h[1] for h in history]
    stop = next(k for k, n in enumerate(counts) if n >= 50)
    assert counts[0] > 0 and counts == sorted(counts) and stop < len(counts) - 2
    assert counts[stop:] == [counts[stop]] * (len(counts) - stop)        # no insertion after the unfix
    assert sim.modify.find("pour") is None and len(namespace["x"]) == counts[stop] < 400
    assert all(h[2] > 0 for h in history) and f"{counts[stop]} particles" in capsys.readouterr().out


def test_the_notebook_example_runs(tmp_path, monkeypatch):
    """docs/python.md's thermo_history example, as printed (matplotlib without a display): the pour's
    kinetic energy, one value per thermo line."""
    import matplotlib
    matplotlib.use("Agg")
    example = next(b for b in re.findall(r"```python\n(.*?)```", DOC.read_text(), re.S) if "thermo_history" in b)
    monkeypatch.chdir(tmp_path)
    namespace = {}
    exec(compile(example, str(DOC), "exec"), namespace)
    h = namespace["h"]
    assert h["step"].tolist() == list(range(0, 20001, 500)) and (h["ke"][1:] > 0).all()
    assert h["atoms"][-1] == 60


def test_every_sees_the_state_of_the_step_just_done():
    seen = []
    sim = dem.Simulation(screen=False).commands(BALL)

    def probe(s):
        z = s.gather("x")[0, 2]
        seen.append((s.update.ntimestep, s.update.time, z, s.thermo_keyword("step")))

    fid = sim.every(10, probe)
    assert fid == "py_probe"
    sim.run(35)
    assert [k[0] for k in seen] == [10, 20, 30] and [k[3] for k in seen] == [10, 20, 30]
    assert seen[-1][1] == pytest.approx(30 * 1e-4)
    sim.run(15)                                           # counts steps, not calls: 40 and 50
    assert [k[0] for k in seen][3:] == [40, 50]
    assert seen[-1][2] == sim.gather("x")[0, 2]          # the state at the end of step 50
    sim.command(f"unfix {fid}")
    sim.run(20)
    assert len(seen) == 5


def test_script_form_and_errors():
    calls = []
    sim = dem.Simulation(screen=False).commands(BALL)
    sim.callback("count", lambda s: calls.append(s.update.ntimestep))
    sim.commands("fix c all python/every 5 count\nrun 12")
    assert calls == [5, 10]
    with pytest.raises(dem.DemError, match="no Python function registered as 'cuont'.*count"):
        sim.command("fix d all python/every 5 cuont")
    with pytest.raises(dem.DemError, match="N must be an integer >= 1"):
        sim.command("fix d all python/every 0 count")


@pytest.mark.parametrize("action, message", [
    (lambda s: s.run(5), "a run cannot be started from inside a run"),
    (lambda s: s.command("run 5"), "a run cannot be started from inside a run"),
    (lambda s: s.command("fix g2 all gravity 1 vector 0 0 -1"), "a fix cannot be defined during a run"),
])
def test_callback_may_not_run_or_define_fixes(action, message):
    sim = dem.Simulation(screen=False).commands(BALL)
    sim.every(5, action)
    with pytest.raises(dem.DemError, match=message):
        sim.run(10)


def test_unfix_from_a_callback_takes_effect_at_once():
    sim = dem.Simulation(screen=False).commands(BALL)
    sim.every(10, lambda s: s.command("unfix gravity") if s.modify.find("gravity") else None)
    sim.run(10)
    v = sim.gather("v").copy()
    sim.run(20)
    assert np.array_equal(sim.gather("v"), v)            # no gravity after step 10, nothing else acts


def test_thermo_history_as_arrays(monkeypatch):
    """sim.thermo_history(): every thermo line printed, one array per keyword; a keyword a later
    thermo_style adds is NaN in the earlier lines. thermo_dataframe() the same as a pandas DataFrame, or
    an error saying pandas is needed."""
    import math
    import sys
    sim = dem.Simulation(screen=False)
    sim.commands("""
        region box block 0 1 0 1 0 1
        create_box 1 box
        create_atoms 1 single 0.5 0.5 0.5 radius 0.01 density 1000 v 1 0 0
        pair_style sphere
        pair_coeff * * kn 1e5 en 0.5 mu 0.5
        fix integ all nve/sphere
        timestep 1e-4
        thermo 100
        run 300
        thermo_style custom step ke atoms
        run 200
    """)
    h = sim.thermo_history()
    assert list(h) == ["step", "time", "atoms", "ke", "erot", "contacts", "cn", "maxov", "pct", "tps", "eta"]
    # run 300: steps 0-300; run 200 prints its first line (300) again, as LAMMPS does
    assert h["step"].tolist() == [0, 100, 200, 300, 300, 400, 500]
    assert h["ke"].tolist() == [sim.thermo_keyword("ke")] * 7     # no contact, no gravity: constant
    assert h["ke"][0] == pytest.approx(0.5 * 1000 * 4 / 3 * math.pi * 0.01 ** 3, rel=1e-15)
    assert h["time"][:4].tolist() == [k * 100 * 1e-4 for k in range(4)] and all(math.isnan(t) for t in h["time"][4:])
    with monkeypatch.context() as m:
        m.setitem(sys.modules, "pandas", None)
        with pytest.raises(dem.DemError, match="thermo_dataframe needs pandas"):
            sim.thermo_dataframe()
    try:
        import pandas
    except ImportError:
        return                                     # pandas is optional: the numpy arrays above are the API
    frame = sim.thermo_dataframe()
    assert isinstance(frame, pandas.DataFrame) and frame["step"].tolist() == h["step"].tolist()
