"""fix insert: random insertion without overlap (Part III sec 4.1), reproducible from its seed."""
import numpy as np
import pytest

import dem
import dem_process
from dem.errors import DemError



def min_gap(x, r, lo, prd, periodic):
    """Smallest surface gap over all pairs, minimum image along periodic axes (brute force)."""
    d = x[:, None, :] - x[None, :, :]
    for k in range(3):
        if periodic[k]:
            d[..., k] -= prd[k] * np.round(d[..., k] / prd[k])
    dist = np.sqrt((d ** 2).sum(-1))
    gap = dist - (r[:, None] + r[None, :])
    np.fill_diagonal(gap, np.inf)
    return gap.min()


def _sim(fix, boundary="p p f", steps=1, pre="", box="0 0.01 0 0.01 0 0.03"):
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary {boundary}
        region box block {box}
        create_box 1 box
        {pre}
        pair_style sphere
        pair_coeff * * kn 1e4 en 0.5 mu 0.5
        fix integ all nve/sphere
        {fix}
        timestep 1e-6
        thermo 0
    """)
    sim.run(steps)
    return sim


def test_dense_fill_no_overlap_periodic_images():
    """400 spheres (sizes uniform in 0.4-0.8 mm) in a box periodic in x and y that already holds 100
    spheres from create_atoms: no two spheres overlap (all pairs, periodic images included), ids follow
    the existing ones, masses follow the density. At the final solid fraction, 0.14, a large sphere
    finds room in ~1 of 20 random tries: many candidates are retried at later steps."""
    sim = _sim("fix ins all insert 991 box count 400 radius uniform 0.0004 0.0008 density 2500",
               pre="create_atoms 1 random 100 7 box radius 0.0005 density 1000", steps=1000)
    x, r, tags = sim.gather("x"), sim.gather("radius"), sim.gather("tag")
    assert len(x) == 500 and sim.atom.natoms == 500 and sim.atom.max_tag == 500
    assert sorted(tags.tolist()) == list(range(1, 501))
    dom = sim.domain
    assert min_gap(x, r, dom.lo, dom.prd, dom.periodic) > -1e-9   # particles moved 200 steps: tiny slack
    new = tags > 100
    m = sim.gather("rmass")[new]
    np.testing.assert_allclose(m, 2500 * 4 / 3 * np.pi * r[new] ** 3, rtol=1e-12)
    assert np.all((r[new] >= 0.0004) & (r[new] <= 0.0008))
    q = sim.gather("quat")[new]
    np.testing.assert_allclose(np.linalg.norm(q, axis=1), 1.0, rtol=1e-12)
    assert sim.thermo_keyword("f_ins[inserted]") == 400 and sim.thermo_keyword("f_ins[pending]") == 0


def test_overlap_check_at_insertion_is_exact():
    """Without gravity nor initial velocity, inserted spheres stay where they were put: every pair keeps
    a gap >= 0 exactly, across the periodic boundaries too (a box only 4 diameters wide, so many
    spheres straddle them); 50 spheres fill 16 % of it, retried over many steps."""
    sim = _sim("fix ins all insert 5 box count 50 radius 0.001 density 1000",
               box="0 0.008 0 0.008 0 0.02", steps=500)
    x, r = sim.gather("x"), sim.gather("radius")
    assert len(x) == 50
    assert np.all(sim.gather("v") == 0.0)
    assert min_gap(x, r, sim.domain.lo, sim.domain.prd, sim.domain.periodic) >= 0.0
    near = (x[:, :2] < 0.001) | (x[:, :2] > 0.007)
    assert near.any()                  # some spheres do cross a periodic boundary


def test_same_seed_same_particles_other_seed_differs():
    fix = "fix ins all insert {} box count 120 every 50 per 30 radius gaussian 0.0006 0.0001 density 2500"
    a = _sim(fix.format(4242), steps=220)
    b = _sim(fix.format(4242), steps=220)
    c = _sim(fix.format(4243), steps=220)
    for name in ("x", "radius", "quat", "v"):
        np.testing.assert_array_equal(a.gather(name), b.gather(name))
    ra, rc = a.gather("radius"), c.gather("radius")
    assert not np.array_equal(ra[:50], rc[:50])


def test_schedule_rate_and_rebuild_steps():
    """`every 50 per 30`: 30 candidates at steps 0, 50, 100, 150 (from the first step of the run); the
    particles appear on those steps only, and each of those steps rebuilt the neighbor list. The box
    is roomy (0.1 % solid): every candidate fits at its first try."""
    fix = "fix ins all insert 77 box count 100 every 50 per 30 radius 0.0005 density 2500"
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary p p f
        region box block 0 0.02 0 0.02 0 0.1
        create_box 1 box
        pair_style sphere
        pair_coeff * * kn 1e4 en 0.5
        fix integ all nve/sphere
        {fix}
        timestep 1e-6
        thermo 0
    """)
    changes = {}
    for _ in range(200):
        step, before = sim.update.ntimestep, sim.atom.natoms
        sim.run(1)
        if sim.atom.natoms != before:
            changes[step] = (sim.atom.natoms - before, sim.neighbor.last_build)
    assert changes == {0: (30, 0), 50: (30, 50), 100: (30, 100), 150: (10, 150)}


def _slot(fixes):
    """A box whose insertion region, a slot one sphere wide, holds one sphere of radius 1 mm at a time."""
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary p p f
        region box block 0 0.01 0 0.01 0 0.05
        create_box 1 box
        region slot block 0.0038 0.0062 0.0038 0.0062 0.0448 0.0472
        pair_style sphere
        pair_coeff * * kn 1e4 en 0.5
        fix integ all nve/sphere
        {fixes}
        timestep 1e-5
        thermo 0
    """)
    return sim


def test_no_rebuild_while_nothing_fits():
    """A slot that holds one sphere, kept by it (no gravity, at rest): the four others are drawn and
    tested at every step (`every 1`), none fits, and the neighbor list is not rebuilt for them: the only
    builds are the setup's and the one that inserted the first sphere."""
    sim = _slot("fix ins all insert 3 slot count 5 radius 0.001 density 2500")
    sim.run(200)
    fix = sim.modify.find("ins")
    assert sim.atom.natoms == 1 and len(fix.pending) == 4
    assert fix.attempts == 5 + 4 * 199              # the four were tried at every later step
    assert sim.neighbor.nbuilds == 2                # setup, and step 0 (the first sphere)


def test_retry_when_region_is_full():
    """A region that holds one sphere at a time: the others are retried at later insertion steps, and
    get in only after gravity has moved the previous ones out of the way."""
    sim = _slot("""fix g all gravity 9.81 vector 0 0 -1
        fix ins all insert 3 slot count 5 every 100 per 5 radius 0.001 density 2500
        fix floor all wall/plane zplane 0 NULL kn 1e4 en 0.5""")
    sim.run(1)
    assert sim.atom.natoms == 1                     # the slot is one diameter wide: one at a time
    sim.run(19999)
    assert sim.atom.natoms == 5
    fix = sim.modify.find("ins")
    assert fix.attempts > 5 + 4                     # the four others were retried: 4 failed at step 0
    x, r = sim.gather("x"), sim.gather("radius")
    assert min_gap(x, r, sim.domain.lo, sim.domain.prd, sim.domain.periodic) > -0.05 * 0.002


def test_volfrac_and_max_radius():
    """`volfrac 0.1` of a 1e-6 m^3 region: the inserted volume reaches 0.1e-6 m^3 with the last particle;
    the ghost cutoff covers the largest particle to come before any is inserted."""
    sim = dem.Simulation(screen=False)
    sim.commands("""
        boundary p p f
        region box block 0 0.01 0 0.01 0 0.01
        create_box 1 box
        pair_style sphere
        pair_coeff * * kn 1e4 en 0.5
        fix integ all nve/sphere
        fix ins all insert 9 box volfrac 0.1 radius uniform 0.0003 0.0009 density 1000
        timestep 1e-6
        thermo 0
    """)
    fix = sim.modify.find("ins")
    rmax = float(fix.radii.max())
    sim.run(0)
    assert sim.comm.cutghost >= 2 * rmax
    sim.run(300)
    r = sim.gather("radius")
    vol = np.sum(4 / 3 * np.pi * r ** 3)
    assert vol >= 0.1e-6 and vol - 4 / 3 * np.pi * r.max() ** 3 < 0.1e-6 + 1e-18
    assert len(r) == len(fix.radii)


def test_restart_continues_the_same_stream(tmp_path):
    fix = "fix ins all insert 31 box count 90 every 20 per 10 radius 0.0005 density 2500"
    ref = _sim(fix, steps=200)
    a = _sim(fix, steps=100)
    a.command(f"write_restart {tmp_path / 'r.bin'}")
    b = dem.Simulation(screen=False)
    b.commands(f"""
        read_restart {tmp_path / 'r.bin'}
        region box block 0 0.01 0 0.01 0 0.03
        pair_style sphere
        pair_coeff * * kn 1e4 en 0.5 mu 0.5
        fix integ all nve/sphere
        {fix}
        timestep 1e-6
        thermo 0
    """)
    b.run(100)
    np.testing.assert_array_equal(ref.gather("x"), b.gather("x"))
    np.testing.assert_array_equal(ref.gather("tag"), b.gather("tag"))


def test_errors():
    with pytest.raises(DemError, match="give exactly one of 'count N' or 'volfrac PHI'"):
        _sim("fix ins all insert 1 box radius 0.001", steps=0)
    with pytest.raises(DemError, match=r"insert: unknown keyword 'raduis' \(did you mean 'radius'\?\)"):
        _sim("fix ins all insert 1 box count 3 raduis 0.001", steps=0)
    with pytest.raises(DemError, match="unknown region ID 'nowhere'"):
        _sim("fix ins all insert 1 nowhere count 3", steps=0)


MPI_SCRIPT = """
import sys
import numpy as np
import dem
sim = dem.Simulation(screen=False)
sim.commands('''
    boundary p p f
    region box block 0 0.02 0 0.02 0 0.04
    create_box 1 box
    pair_style sphere
    pair_coeff * * kn 1e4 en 0.5 mu 0.5 gamma_t 100 ks 2857
    fix integ all nve/sphere
    fix g all gravity 9.81 vector 0 0 -1
    fix floor all wall/plane zplane 0 NULL kn 1e4 en 0.5 mu 0.5
    fix ins all insert 4242 box count 400 every 20 per 40 radius uniform 0.0008 0.0012 density 2500
    timestep 1e-5
    thermo 0
    run 1000
''')
x, r, tags = sim.gather("x"), sim.gather("radius"), sim.gather("tag")
if sim.comm.me == 0:
    np.savez(sys.argv[1], x=x, r=r, tags=tags)
"""


def test_same_particles_on_one_and_two_ranks(tmp_path):
    """The candidates come from one random stream drawn identically on every rank; each rank tests its
    own particles and the verdicts are combined: 1 and 2 MPI ranks insert the same particles (same ids,
    sizes and, before they interact differently, positions). After 1000 steps of falling and piling
    the trajectories agree to round-off (forces are summed in another order): 1e-9 of a diameter."""
    import os
    import shutil
    import subprocess
    import sys
    from pathlib import Path
    mpiexec = shutil.which("mpiexec", path=os.path.dirname(sys.executable)) or shutil.which("mpiexec")
    if mpiexec is None:
        pytest.skip("mpiexec not found")
    try:
        import mpi4py  # noqa: F401
    except ImportError:
        pytest.skip("mpi4py not installed")
    script = tmp_path / "ins.py"
    script.write_text(MPI_SCRIPT)
    import dem
    env = dict(os.environ, OMP_NUM_THREADS="1")
    paths = [str(Path(dem.__file__).resolve().parents[1]), str(Path(dem_process.__file__).resolve().parents[1])]
    env["PYTHONPATH"] = os.pathsep.join(paths + [p for p in [env.get("PYTHONPATH")] if p])
    out = {}
    for n in (1, 2):
        cmd = [sys.executable, str(script), str(tmp_path / f"r{n}.npz")]
        if n > 1:
            cmd = [mpiexec, "-n", str(n)] + cmd
        res = subprocess.run(cmd, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)
        assert res.returncode == 0, res.stderr[-3000:]
        out[n] = np.load(tmp_path / f"r{n}.npz")
    np.testing.assert_array_equal(out[1]["tags"], out[2]["tags"])
    np.testing.assert_array_equal(out[1]["r"], out[2]["r"])
    assert len(out[1]["tags"]) == 400
    np.testing.assert_allclose(out[1]["x"], out[2]["x"], rtol=0, atol=1e-9 * 0.002)


def test_insert_shaped_particles():
    """Cubes from the `shape` command: shape index, mass and inertia of the scaled cube, random
    orientations, bounding spheres apart; they then fall and collide through pair_style convex/gjk."""
    sim = dem.Simulation(screen=False)
    sim.commands("""
boundary p p f
region box block 0 0.02 0 0.02 0 0.04
create_box 1 box
shape cube cube 0.002
region top block EDGE EDGE EDGE EDGE 0.01 0.04
pair_style convex/gjk
pair_coeff * * kn 1e4 en 0.5 mu 0.3
fix integrate all nve/shape
fix gravity all gravity 9.81 vector 0 0 -1
fix floor all wall/plane zplane 0 NULL
fix ins all insert 11 top count 60 shape cube scale uniform 0.8 1.2 density 2500
timestep 2e-6
run 300
""")
    a = sim.atom
    assert a.natoms == 60 and np.all(a.local("shape") == 0)     # every cube found room
    scale = a.local("radius") / (0.002 * np.sqrt(3) / 2)      # bounding radius of a cube: half its diagonal
    assert np.all((scale >= 0.8 - 1e-12) & (scale <= 1.2 + 1e-12))
    m = 2500 * (0.002 * scale) ** 3
    assert np.allclose(a.local("rmass"), m, rtol=1e-12)
    assert np.allclose(a.local("inertia"), (m * (0.002 * scale) ** 2 / 6)[:, None], rtol=1e-10)
    q = a.local("quat")
    assert np.allclose(np.linalg.norm(q, axis=1), 1.0) and np.std(q[:, 0]) > 0.1
    sim.run(2000)
    assert sim.atom.natoms == 60
    assert sim.thermo_keyword("maxov") < 0.01
