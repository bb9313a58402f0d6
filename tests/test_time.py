"""The simulated time is step x dt from the step where dt last changed, rounded once: a sum of dt over the
steps gathers round-off (0.020000000000000788 after 10,000 steps of 2e-6), which showed in thermo, in every
dump's time and in ParaView's list of times."""
from fractions import Fraction

import dem


def exact(*terms):
    """The sum of the products step x dt, computed exactly, rounded once to a float."""
    return float(sum(Fraction(n) * Fraction(dt) for n, dt in terms))


def one_sphere(tmp_path=None):
    sim = dem.Simulation(screen=False)
    sim.commands("""
        region box block 0 1 0 1 0 1
        create_box 1 box
        create_atoms 1 single 0.5 0.5 0.5 radius 0.01 density 1000
        pair_style sphere
        pair_coeff * * kn 1e5 en 0.5 mu 0.5
        fix integ all nve/sphere
        timestep 2e-6
        thermo 0
    """)
    return sim


def test_time_after_a_million_steps_and_a_change_of_dt():
    """1e6 steps of 2e-6 (12 s of CPU): the time is 2.0 to the last digit, in thermo too; after a change
    of dt it goes on from there, and reset_timestep keeps it."""
    sim = one_sphere()
    sim.command("run 1000000")
    assert sim.update.time == exact((10 ** 6, 2e-6)) and sim.thermo_keyword("time") == sim.update.time
    sim.commands("timestep 3e-7\nrun 1000")
    assert sim.update.time == exact((10 ** 6, 2e-6)) + exact((1000, 3e-7))
    before = sim.update.time
    sim.commands("reset_timestep 0\nrun 10")
    assert sim.update.ntimestep == 10 and sim.update.time == before + exact((10, 3e-7))


def test_time_through_a_restart(tmp_path):
    """A restart keeps the time and dt; the run read from it counts on from the restart's step."""
    sim = one_sphere()
    sim.commands(f"run 10000\nwrite_restart {tmp_path / 'a.restart'}")
    assert sim.update.time == exact((10000, 2e-6)) == 0.02
    b = dem.Simulation(screen=False)
    b.commands(f"""
        read_restart {tmp_path / 'a.restart'}
        pair_style sphere
        pair_coeff * * kn 1e5 en 0.5 mu 0.5
        fix integ all nve/sphere
        thermo 0
        run 5000
    """)
    assert b.update.time == 0.02 + exact((5000, 2e-6))


def test_series_output_leaves_the_time_exact(tmp_path, monkeypatch):
    """fix print/series and ave/vector evaluate as of the step just done (Update.as_output_of_step): the
    time they see is that step's, and the run's time stays step x dt (they set the time by a sum
    before, moving the anchor at every line)."""
    monkeypatch.chdir(tmp_path)
    sim = one_sphere()
    sim.commands("fix s all print/series 1000 s.dat time\nrun 20000")
    assert sim.update.time == exact((20000, 2e-6))
    rows = [line.split() for line in (tmp_path / "s.dat").read_text().splitlines() if not line.startswith("#")]
    assert [float(r[2]) for r in rows] == [float(f"{exact((int(r[0]), 2e-6)):.10g}") for r in rows]
