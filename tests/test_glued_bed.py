"""A bed of 588 3D crosses (glued/convex, frictional with tangential springs per component pair, a floor,
bi-periodic): it settles with no particle lost and bounded overlaps, 1 and 2 ranks agree, and a restart
continues bit for bit.

The crosses (beams 2 x 0.5 x 0.5 mm) start on a simple cubic lattice, turned at random, and fall under a
tenfold gravity (98.1 m/s2, to settle in a test's time) onto the floor: by step 8000 (32 ms) the kinetic
energy has fallen by three orders from its peak (measured 5e-4 J at step 3000, 3e-7 J at 8000) with about
1130 contacts (1970 contact points); the largest overlap stays below 2 % of the component's bounding
diameter (kn = 2000 N/m, weight of a column of 12 crosses 3.6e-3 N: about 2 um static overlap; measured
peak 1.56 % during the impacts).

1 vs 2 ranks: forces are summed in other orders (ghost forces come back by reverse communication), so
states agree to round-off only, and round-off grows in a dense granular flow; compared at step 2000 (the
first hundred contacts): positions within 1e-9 of a beam length, velocities within 1e-7 of the largest
(measured 1e-16 / 1e-13); integer observables (atoms, contacts) equal at every thermo line to 2000.
"""
import numpy as np
import pytest

import dem
from conftest import MPIEXEC
from test_mpi import frame, run_dem, thermo_rows

BEAM = 0.002
BED = """
units           si
boundary        p p f
{processors}
region          box block 0 0.01505 0 0.01505 0 0.05
create_box      1 box
shape           x cross3d 0.002
region          fill block 0 0.01505 0 0.01505 0 0.0258
create_atoms    1 lattice fill sc 0.00215 shape x quat random density 2500
pair_style      glued/convex
pair_coeff      * * kn 2000 en 0.3 mu 0.5 gamma_t 2000 ks 571
fix             integrate all nve/shape
fix             gravity all gravity 98.1 vector 0 0 -1
fix             floor all wall/plane zplane 0 NULL
timestep        4e-6
neighbor        0.0002 bin
thermo_style    custom step atoms contacts ke maxov
thermo          {thermo}
thermo_modify   format float %.17g
"""


@pytest.fixture(autouse=True)
def shape_db(tmp_path, monkeypatch):
    monkeypatch.setenv("DEM_SHAPE_DB", str(tmp_path / "shapes.h5"))


def test_bed_settles_without_loss():
    sim = dem.Simulation(screen=False)
    sim.commands(BED.format(processors="", thermo=1000))
    n0 = sim.atom.natoms
    assert n0 == 588
    ke, worst = [], 0.0
    for _ in range(8):
        sim.run(1000)
        m, v = sim.atom.local("rmass"), sim.atom.local("v")
        ke.append(0.5 * float((m * (v * v).sum(1)).sum()))
        worst = max(worst, sim.pair.max_overlap)
        assert sim.atom.natoms == n0
    x = sim.atom.local("x")
    assert x[:, 2].min() > 0.0 and x[:, 2].max() < 0.0258
    assert worst < 0.02
    assert ke[-1] < 2e-3 * max(ke)                       # settled: translational energy down 500-fold
    assert sim.pair.ncontacts > 900                      # a bed: about 2 contacts per cross and more
    st = sim.pair.stats
    # broad-phase culling: the beams' bounding spheres are those of the crosses (all centred, same radius)
    # and cull nothing; their bounding boxes leave 10 % of the component pairs of touching crosses for GJK
    # (measured 0.102), which finds 3 in 4 of those in contact (0.76); one query per candidate and step.
    # The piece candidates list 42 % of the component pairs (within the skin at the list's build) and leave
    # 15 % to the per-step culls (the others proven still apart: measured 0.42, 0.15)
    assert st["piece_listed"] < 0.5 * st["piece_pairs"] and st["piece_spheres"] < 0.2 * st["piece_pairs"]
    assert 0.0 < st["piece_candidates"] < 0.2 * st["piece_pairs"] and st["gjk"] == st["piece_candidates"]
    assert st["points"] > 0.5 * st["gjk"]


@pytest.mark.skipif(MPIEXEC is None, reason="mpiexec not found (pip install 'dem[mpi]')")
def test_bed_two_ranks_matches_serial(tmp_path):
    script = BED.format(processors="{processors}", thermo=100) + "dump d all h5 2000 bed.h5\nrun 2000\n"
    (tmp_path / "one").mkdir()
    (tmp_path / "two").mkdir()
    run_dem(tmp_path / "one", script.format(processors=""), 1, "log.1", timeout=300)
    run_dem(tmp_path / "two", script.format(processors="processors 2 1 1"), 2, "log.2", timeout=300)
    r1, r2 = thermo_rows(tmp_path / "one" / "log.1"), thermo_rows(tmp_path / "two" / "log.2")
    assert len(r1) == len(r2) == 21
    assert [r[:3] for r in r1] == [r[:3] for r in r2]
    assert int(r1[-1][2]) > 50
    a, b = frame(tmp_path / "one" / "bed.h5", 2000), frame(tmp_path / "two" / "bed.h5", 2000)
    assert np.array_equal(a["id"], b["id"])
    assert np.abs(a["position"] - b["position"]).max() <= 1e-9 * BEAM
    vmax = np.abs(a["velocity"]).max()
    assert np.abs(a["velocity"] - b["velocity"]).max() <= 1e-7 * vmax


def state(sim):
    out = {name: sim.gather(name) for name in ("x", "v", "omega", "angmom", "quat")}
    out["history"] = sim.pair.history.by_tags()
    out["step"], out["time"] = sim.update.ntimestep, sim.update.time
    return out


def test_composite_bed_restart_continues_bitwise(tmp_path):
    sim = dem.Simulation(screen=False)
    sim.commands(BED.format(processors="", thermo=0))
    sim.run(3000)
    at = state(sim)
    assert len(at["history"]) > 100                      # component-pair records with loaded springs
    assert any(abs(v[0]) + abs(v[1]) + abs(v[2]) > 0 for v in at["history"].values())
    path = tmp_path / "bed.restart"
    sim.command(f"write_restart {path}")
    sim.run(500)
    ref = state(sim)
    new = dem.Simulation(screen=False)
    new.command(f"read_restart {path}")
    new.commands("\n".join(line for line in BED.format(processors="", thermo=0).splitlines()
                           if line.split()[:1] and line.split()[0] in ("pair_style", "pair_coeff", "fix", "neighbor",
                                                                      "thermo_style", "thermo")))
    new.run(500)
    got = state(new)
    assert got["step"] == ref["step"] and got["time"] == ref["time"]
    for name in ("x", "v", "omega", "angmom", "quat"):
        assert np.array_equal(got[name], ref[name]), name
    assert got["history"] == ref["history"]
