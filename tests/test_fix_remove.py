"""fix remove (deletion of the particles inside a region: an outlet) and fix insert's `massrate` feed.

The removal tests drop spheres in free fall, one per column of a 4 x 4 grid 10 mm apart (no contacts),
from known heights onto a sink region at the bottom of the box. With the leap-frog scheme of dem
(velocities at half steps, v(-1/2) = 0 from create_atoms), after n steps of gravity g a sphere has fallen

    d(n) = g dt^2 (1 + 2 + ... + n) = g dt^2 n (n + 1) / 2      (continuous: g (n dt)^2 / 2)

exactly up to round-off (checked on the spheres left). Heights are chosen so that every crossing of the
sink's top happens millimetres away from the end of a run (the two formulas then give the same set, and
round-off cannot move a sphere across), so the removed set is exact; counts and tags are compared exactly,
masses to 1e-12 relative (a sum of at most 16 terms in another order: ~1e-16).
"""
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import dem
import dem_process
from dem.errors import DemError

from conftest import MPIEXEC

G, DT = 9.81, 1e-4
TOP = 0.02                                         # top of the sink region (z)
COLUMNS = [(0.005 + 0.01 * (k % 4), 0.005 + 0.01 * (k // 4)) for k in range(16)]
HEIGHTS = [0.035 + 0.01 * k for k in range(16)]
RADII = [0.001 + 0.0001 * (k % 3) for k in range(16)]
DENSITIES = [1000.0 + 100.0 * k for k in range(16)]


def fall(n):
    return G * DT * DT * n * (n + 1) / 2


def entry_step(z0):
    """First step n after which a sphere dropped from z0 has its centre in the sink (z <= TOP)."""
    n = 0
    while z0 - fall(n) > TOP:
        n += 1
    return n


def mass(k):
    return DENSITIES[k] * 4.0 / 3.0 * math.pi * RADII[k] ** 3


def script(heights=HEIGHTS, fix="fix out all remove sink", steps=None):
    atoms = "\n".join(f"create_atoms 1 single {x!r} {y!r} {z!r} radius {r!r} density {rho!r}"
                      for (x, y), z, r, rho in zip(COLUMNS, heights, RADII, DENSITIES))
    return f"""
boundary p p f
region box block 0 0.04 0 0.04 0 0.2
create_box 1 box
region sink block EDGE EDGE EDGE EDGE 0 {TOP!r}
{atoms}
pair_style sphere
pair_coeff * * kn 1e4 en 0.5
fix integ all nve/sphere
fix g all gravity {G!r} vector 0 0 -1
{fix}
timestep {DT!r}
thermo 0
""" + (f"run {steps}\n" if steps is not None else "")


def simulation(text):
    sim = dem.Simulation(screen=False)
    sim.commands(text)
    return sim


def expected_removed(steps, heights=HEIGHTS):
    """Indices of the spheres whose centre has reached the sink by the end of `steps` steps; asserts the
    margins that make this set exact (no crossing within 1 mm of the end, continuous fall agrees)."""
    gone = [k for k, z in enumerate(heights) if z - fall(steps) <= TOP]
    continuous = [k for k, z in enumerate(heights) if z - 0.5 * G * (steps * DT) ** 2 <= TOP]
    assert gone == continuous
    assert min(abs(z - fall(steps) - TOP) for z in heights) > 1e-3
    return gone


def test_free_fall_removes_exactly_the_spheres_that_reached_the_sink():
    """1500 steps (0.15 s, d = 0.1104 m): the spheres from z0 <= 0.1304 m reach the sink (z <= 0.02 m):
    the ten lowest, ids 1-10. Particle count, removed count, removed mass, the ids left and the masses
    and positions of the spheres left (the fields moved together with their particles) are checked."""
    steps = 1500
    sim = simulation(script(steps=steps))
    gone = expected_removed(steps)
    assert gone == list(range(10))
    removed = sim.thermo_keyword("f_out[removed]")
    assert removed == len(gone) == 10
    assert sim.atom.natoms == 16 - removed == sim.thermo_keyword("atoms")
    expected_mass = math.fsum(mass(k) for k in gone)
    assert sim.thermo_keyword("f_out[mass]") == pytest.approx(expected_mass, rel=1e-12, abs=0)
    tags = sim.gather("tag")
    left = [k for k in range(16) if k not in gone]
    assert tags.tolist() == [k + 1 for k in left]
    np.testing.assert_allclose(sim.gather("rmass"), [mass(k) for k in left], rtol=1e-12)
    np.testing.assert_array_equal(sim.gather("radius"), [RADII[k] for k in left])
    # premise: free fall without contacts, as in the formula (round-off of 1500 additions: 1e-12 m)
    z = sim.gather("x")[:, 2]
    np.testing.assert_allclose(z, [HEIGHTS[k] - fall(steps) for k in left], rtol=0, atol=1e-12)


def test_only_the_fix_group_is_removed():
    """Group ids 1-4: after 1200 steps (d = 0.0707 m) spheres 1-6 have reached the sink; 1-4 are deleted,
    5 and 6 (outside the group) are still in it, above the floor."""
    steps = 1200
    assert expected_removed(steps) == list(range(6))
    sim = simulation(script(fix="group low id 1:4\nfix out low remove sink", steps=steps))
    assert sim.thermo_keyword("f_out[removed]") == 4 and sim.atom.natoms == 12
    assert sim.gather("tag").tolist() == list(range(5, 17))
    assert np.all(sim.gather("x")[:2, 2] <= TOP)
    assert sim.thermo_keyword("f_out[mass]") == pytest.approx(math.fsum(mass(k) for k in range(4)), rel=1e-12)


def test_every_m_checks_on_multiples_of_m_and_deletes_at_the_next_step():
    """`every 7`: spheres that enter the sink after steps 100, 105 and 106 (heights half a step's fall
    past the crossing, so no round-off can move them) are found at the end of steps 105, 105 and 112
    (the first multiple of 7 at or after their entry), still shown by the output of that step, and
    deleted at the start of the next one: in one uninterrupted run and in runs of one step alike."""
    heights = list(HEIGHTS)
    for k, n in ((0, 100), (1, 105), (2, 106)):
        heights[k] = TOP + 0.5 * (fall(n - 1) + fall(n))
        assert entry_step(heights[k]) == n
    for k in range(3, 16):
        assert entry_step(heights[k]) > 130
    fix = "fix out all remove sink every 7"
    # uninterrupted runs: found at the end of step 105, deleted during step 106
    a = simulation(script(heights, fix, steps=105))
    assert a.atom.natoms == 16 and a.thermo_keyword("f_out[removed]") == 0
    b = simulation(script(heights, fix, steps=106))
    assert b.atom.natoms == 14 and b.thermo_keyword("f_out[removed]") == 2
    b.run(6)                                          # step 112: found, not yet deleted
    assert b.atom.natoms == 14
    b.run(1)
    assert b.atom.natoms == 13 and b.thermo_keyword("f_out[removed]") == 3
    assert b.gather("tag").tolist() == list(range(4, 17))
    # one step at a time: a deletion found at the end of a run happens at the setup of the next one
    c = simulation(script(heights, fix))
    drops = {}
    for _ in range(120):
        step, before = c.update.ntimestep, c.atom.natoms
        c.run(1)
        if c.atom.natoms != before:
            drops[step] = before - c.atom.natoms
    assert drops == {105: 2, 112: 1}
    np.testing.assert_array_equal(c.gather("x"), simulation(script(heights, fix, steps=120)).gather("x"))


def test_restart_continues_the_totals_and_a_pending_deletion(tmp_path):
    """800 + 700 steps through a restart equal 1500 steps in one run: same totals, same ids, bitwise the
    same positions. Sphere 3 enters the sink during step 800, the last before the restart: it is found
    at the end of that step and deleted at the start of the next; the restart keeps that pending
    deletion, so a `run 0` after read_restart already removes it (it would stay without the saved state)."""
    n1, n2 = 800, 700
    heights = list(HEIGHTS)
    heights[2] = TOP + 0.5 * (fall(n1 - 1) + fall(n1))
    assert entry_step(heights[2]) == n1
    gone1 = [k for k, z in enumerate(heights) if entry_step(z) < n1]
    gone = [k for k, z in enumerate(heights) if entry_step(z) <= n1 + n2]
    assert gone1 == [0, 1] and gone == list(range(10))
    ref = simulation(script(heights, steps=n1 + n2))
    a = simulation(script(heights, steps=n1))
    assert a.thermo_keyword("f_out[removed]") == 2 and a.atom.natoms == 14
    a.command(f"write_restart {tmp_path / 'r.h5'}")
    b = simulation(f"""
read_restart {tmp_path / 'r.h5'}
region sink block EDGE EDGE EDGE EDGE 0 {TOP!r}
pair_style sphere
pair_coeff * * kn 1e4 en 0.5
fix integ all nve/sphere
fix g all gravity {G!r} vector 0 0 -1
fix out all remove sink
timestep {DT!r}
thermo 0
""")
    assert b.thermo_keyword("f_out[removed]") == 2
    b.run(0)
    assert b.thermo_keyword("f_out[removed]") == 3 and b.atom.natoms == 13
    np.testing.assert_allclose(b.thermo_keyword("f_out[mass]"), math.fsum(mass(k) for k in (0, 1, 2)),
                               rtol=1e-12)
    b.run(n2)
    assert b.thermo_keyword("f_out[removed]") == ref.thermo_keyword("f_out[removed]") == len(gone)
    assert b.thermo_keyword("f_out[mass]") == pytest.approx(math.fsum(mass(k) for k in gone), rel=1e-12)
    assert b.atom.natoms == ref.atom.natoms == 16 - len(gone)
    np.testing.assert_array_equal(b.gather("tag"), ref.gather("tag"))
    np.testing.assert_array_equal(b.gather("x"), ref.gather("x"))
    # the same pending deletion within one simulation: `run 0` deletes it at its setup
    a.run(0)
    assert a.thermo_keyword("f_out[removed]") == 3 and a.atom.natoms == 13


BAD = [
    ("fix out all remove", "fix out remove: expected at least 1 argument(s), got 0"),
    ("fix out all remove sinc", "fix out remove: unknown region ID 'sinc' (did you mean 'sink'?)"),
    ("fix out all remove nowhere", "fix out remove: unknown region ID 'nowhere'"),
    ("fix out all remove sink evry 5", "fix out remove: unknown keyword 'evry' (did you mean 'every'?)"),
    ("fix out all remove sink every", "fix out remove: keyword 'every' needs 1 value(s)"),
    ("fix out all remove sink every 0", "fix out remove: every must be >= 1, got 0"),
    ("fix out all remove sink every 2.5", "fix out remove: every must be an integer, got '2.5'"),
    ("fix ins all insert 1 sink count 5 per 2 massrate 0.1", "give either 'per K' or 'massrate Q', not both"),
    ("fix ins all insert 1 sink count 5 massrate 0", "massrate must be > 0 (kg/s), got 0"),
    ("fix ins all insert 1 sink count 5 massrate fast", "massrate must be a number, got 'fast'"),
]


@pytest.mark.parametrize("line, message", BAD, ids=[b[0].split(" ", 4)[-1] for b in BAD])
def test_bad_input_is_a_clear_error_on_its_line(line, message):
    text = """boundary p p f
region box block 0 0.04 0 0.04 0 0.2
create_box 1 box
region sink block EDGE EDGE EDGE EDGE 0 0.02
""" + line + "\n"
    sim = dem.Simulation(screen=False)
    with pytest.raises(DemError) as err:
        sim.commands(text)
    assert err.value.where == "<string>:5", str(err.value)
    assert message in str(err.value)


def test_bad_input_from_the_command_line_has_no_traceback(tmp_path):
    (tmp_path / "in.bad").write_text(script(fix="fix out all remove nowhere every 3"))
    res = subprocess.run([sys.executable, "-m", "dem", "-in", "in.bad", "-log", "none"], cwd=tmp_path,
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 1 and "Traceback" not in res.stderr, res.stderr
    assert "in.bad:" in res.stderr and "fix out remove: unknown region ID 'nowhere'" in res.stderr, res.stderr


# ----- fix insert massrate -------------------------------------------------------------------------------

def _feed(fix, steps, chunk):
    """Insertion into an empty 5 cm box without gravity (spheres stay where they are put), advanced in
    runs of `chunk` steps; yields (step of the insertion, sim) after each run."""
    sim = simulation(f"""
boundary p p f
region box block 0 0.05 0 0.05 0 0.05
create_box 1 box
pair_style sphere
pair_coeff * * kn 1e4 en 0.5
fix integ all nve/sphere
{fix}
timestep 1e-5
thermo 0
""")
    for _ in range(steps // chunk):
        step = sim.update.ntimestep
        sim.run(chunk)
        yield step, sim


def test_massrate_equal_spheres_follow_floor_q_t_over_m_plus_one():
    """Equal spheres (r 0.5 mm, 2500 kg/m^3: m = 1.309e-6 kg) fed at Q = 0.01 kg/s every 10 steps of
    1e-5 s from t0 = 0: at an insertion step at time t the particles taken are those whose predecessors
    weigh at most Q t, i.e. the j-th goes in when (j - 1) m <= Q t: n(t) = min(N, floor(Q t / m) + 1)
    (one at t = 0, 0.76 more per insertion step, 50 reached at t = 6.4 ms). Exact counts: the test checks
    that Q t / m stays 1e-6 away from integers (round-off in t and in the mass sums is ~1e-15). The box is
    0.02 % full, so every candidate fits at once (checked: attempts == inserted)."""
    q, m, count = 0.01, 2500 * 4 / 3 * math.pi * 0.0005 ** 3, 50
    seen = []
    for step, sim in _feed(f"fix ins all insert 7 box count {count} every 10 massrate {q} radius 0.0005 "
                           f"density 2500", 1000, 10):
        t = step * 1e-5
        ratio = q * t / m
        assert step == 0 or abs(ratio - round(ratio)) > 1e-6
        expect = min(count, math.floor(ratio) + 1)
        assert sim.atom.natoms == expect == sim.thermo_keyword("f_ins[inserted]"), (step, ratio)
        assert sim.thermo_keyword("f_ins[mass]") == pytest.approx(expect * m, rel=1e-12)
        seen.append(expect)
    assert seen[0] == 1 and seen[1] == 1 and seen[2] == 2 and seen[-1] == count     # 0.76 m per step
    fix = sim.modify.find("ins")
    assert fix.attempts == fix.inserted == count


def test_massrate_slow_feed_rebuilds_only_when_a_particle_is_due():
    """Q = 0.002 kg/s every step (1e-5 s) with m = 1.309e-6 kg: one sphere every 65.4 steps; after 500
    steps (last insertion step t = 499e-5 s) floor(Q t / m) + 1 = 8 spheres. Nothing moves (no gravity),
    so the neighbor list is built only by the setup and at the 8 steps that inserted a sphere: 9 builds
    (a rebuild forced at every insertion step would make 501)."""
    q, m = 0.002, 2500 * 4 / 3 * math.pi * 0.0005 ** 3
    fix = f"fix ins all insert 5 box count 50 massrate {q} radius 0.0005 density 2500"
    sim = list(_feed(fix, 500, 500))[-1][1]
    assert sim.atom.natoms == math.floor(q * 499e-5 / m) + 1 == 8
    assert sim.neighbor.nbuilds == 1 + 8


def test_massrate_mixed_sizes_keep_draw_order_and_the_mass_bound():
    """Sizes uniform in 0.3-0.9 mm (masses over a factor 27) at Q = 0.03 kg/s from step START = 200:
    after each insertion step at time t the inserted particles are the first k drawn, with
    M(k - 1) <= Q (t - t0) < M(k), M(j) the mass of the first j (the bound of the docstring: never more
    than Q (t - t0) plus one particle); nothing is inserted before START; the masses of the particles
    in the box are those of the first k drawn, in id order."""
    q, t0 = 0.03, 200 * 1e-5
    ks = []
    for step, sim in _feed(f"fix ins all insert 3 box count 40 every 5 start 200 massrate {q} "
                           f"radius uniform 0.0003 0.0009 density 2500", 700, 5):
        fix = sim.modify.find("ins")
        k = sim.atom.natoms
        if step < 200:
            assert k == 0
            continue
        cum = np.concatenate([[0.0], np.cumsum(fix.masses())])
        budget = q * (step * 1e-5 - t0)
        assert cum[k - 1] <= budget + 1e-15
        if k < 40:
            assert budget < cum[k]
        np.testing.assert_allclose(sim.gather("rmass"), fix.masses()[:k], rtol=1e-12)
        assert sim.thermo_keyword("f_ins[mass]") == pytest.approx(cum[k], rel=1e-12)
        ks.append(k)
    assert ks[0] == 1 and len(set(ks)) > 10 and ks[-1] == 40 and fix.attempts == 40


def test_massrate_continues_through_a_restart(tmp_path):
    """The feed's clock (t0) and the pending list are in the restart: 150 + 150 steps through a restart
    insert the same particles at the same places as 300 steps in one run (a clock restarted at the
    restart would insert fewer: one at once, then 0.76 per insertion step from scratch)."""
    fix = "fix ins all insert 7 box count 80 every 10 massrate 0.01 radius 0.0005 density 2500"
    ref = list(_feed(fix, 300, 300))[-1][1]
    a = list(_feed(fix, 150, 150))[-1][1]
    a.command(f"write_restart {tmp_path / 'r.h5'}")
    b = simulation(f"""
read_restart {tmp_path / 'r.h5'}
region box block 0 0.05 0 0.05 0 0.05
pair_style sphere
pair_coeff * * kn 1e4 en 0.5
fix integ all nve/sphere
{fix}
timestep 1e-5
thermo 0
run 150
""")
    assert ref.atom.natoms == math.floor(0.01 * 290e-5 / (2500 * 4 / 3 * math.pi * 0.0005 ** 3)) + 1 == 23
    assert b.atom.natoms == ref.atom.natoms
    np.testing.assert_array_equal(b.gather("tag"), ref.gather("tag"))
    np.testing.assert_array_equal(b.gather("x"), ref.gather("x"))


# ----- MPI -------------------------------------------------------------------------------------------------

MPI_SCRIPT = """
import sys
import numpy as np
import dem
sim = dem.Simulation(screen=False)
sim.commands(open(sys.argv[2]).read())
before = sim.comm.allgather(sim.atom.nlocal)
sim.run(1500)
after = sim.comm.allgather(sim.atom.nlocal)
removed, mass = sim.thermo_keyword("f_out[removed]"), sim.thermo_keyword("f_out[mass]")
tags = sim.gather("tag")
if sim.comm.me == 0:
    np.savez(sys.argv[1], removed=removed, mass=mass, tags=tags, before=before, after=after,
             natoms=sim.atom.natoms)
"""


@pytest.mark.skipif(MPIEXEC is None, reason="mpiexec not found (pip install 'dem[mpi]')")
def test_two_ranks_remove_the_same_spheres(tmp_path):
    """The free-fall case on 1 and 2 ranks: the same count, mass (to 1e-12: the per-rank sums are added
    in another order) and ids; both ranks owned spheres and both deleted some (the count is a sum over
    ranks that every rank takes part in)."""
    pytest.importorskip("mpi4py")
    (tmp_path / "rm.py").write_text(MPI_SCRIPT)
    (tmp_path / "in.rm").write_text(script())
    env = dict(os.environ, OMP_NUM_THREADS="1")
    paths = [str(Path(mod.__file__).resolve().parents[1]) for mod in (dem, dem_process)]
    env["PYTHONPATH"] = os.pathsep.join(paths + [p for p in [env.get("PYTHONPATH")] if p])
    out = {}
    for n in (1, 2):
        cmd = [sys.executable, "rm.py", f"r{n}.npz", "in.rm"]
        if n > 1:
            cmd = [MPIEXEC, "-n", str(n)] + cmd
        res = subprocess.run(cmd, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)
        assert res.returncode == 0, res.stderr[-3000:]
        out[n] = np.load(tmp_path / f"r{n}.npz")
    gone = expected_removed(1500)
    for n in (1, 2):
        assert int(out[n]["removed"]) == len(gone) == 16 - int(out[n]["natoms"])
        assert float(out[n]["mass"]) == pytest.approx(math.fsum(mass(k) for k in gone), rel=1e-12)
        assert out[n]["tags"].tolist() == [k + 1 for k in range(16) if k not in gone]
    per_rank = out[2]["before"] - out[2]["after"]
    assert len(per_rank) == 2 and np.all(out[2]["before"] > 0) and np.all(per_rank > 0)
    assert per_rank.sum() == len(gone)
