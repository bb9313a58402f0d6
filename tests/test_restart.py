"""Restarts continue a run bit for bit (one rank), and so does a run split in two.

The system is a frictional bed (240 polydisperse spheres of two types, ks > 0: tangential springs with
history) flowing down a tilted gravity against walls that keep their own history, with the default spatial
sort (every 1000 steps) on: by the restart step it has ~50 loaded springs between particles and ~40 against
the walls, rebuilds every ~100 steps, and (periodic case) particles crossing the periodic faces.
Compared, bit for bit with np.array_equal: positions, velocities, angular velocities and momenta, image
counters, the wall histories (per particle) and the pair histories (per pair, by particle ids), and the
step, the time and the time step (the restarted scripts set no `timestep`: dt comes from the restart; time
is a sum of dt, the same additions in the same order, so it is bitwise equal too).
"""
import numpy as np
import pytest

import dem
from flowing_bed import CASES, FORCES, bed

N = 5000


def restarted(case, path):
    sim = dem.Simulation(screen=False)
    sim.command(f"read_restart {path}")
    sim.commands("thermo 0\n" + FORCES.format(walls=CASES[case][1]))
    return sim


def state(sim):
    names = ("x", "v", "omega", "angmom", "image") + (("fix_walls_xi",) if "fix_walls_xi" in sim.atom.fields else ())
    out = {name: sim.gather(name) for name in names}
    i, j = sim.neighbor.pairs()
    tag = sim.atom.data["tag"]
    h = sim.pair.history.values
    out["pair_history"] = {(int(tag[a]), int(tag[b])): tuple(h[k])
                           for k, (a, b) in enumerate(zip(i, j)) if np.any(h[k])}
    out["step"] = sim.update.ntimestep
    out["time"] = sim.update.time
    out["dt"] = sim.update.dt
    return out


def assert_identical(a, b):
    assert a["step"] == b["step"]
    assert a["dt"] == b["dt"], f"dt {b['dt']!r} instead of {a['dt']!r}"
    assert a["time"] == b["time"], f"time {b['time']!r} instead of {a['time']!r}"
    for name in ("x", "v", "omega", "angmom", "image", "fix_walls_xi"):
        assert np.array_equal(a[name], b[name]), (
            f"{name} differs (max {np.max(np.abs(a[name] - b[name])):.3g})")
    assert a["pair_history"] == b["pair_history"]


@pytest.fixture(scope="module", params=sorted(CASES))
def reference(request):
    """The uninterrupted run: 2N steps in one `run`."""
    sim = bed(request.param)
    sim.run(2 * N)
    s = state(sim)
    # the run exercises what a restart must carry
    assert len(s["pair_history"]) > 50 and np.count_nonzero(s["fix_walls_xi"].any(axis=1)) > 20
    assert sim.neighbor.nbuilds > 50
    if request.param == "periodic":
        assert np.abs(s["image"]).sum() > 10
    return request.param, s


def test_run_split_in_two_is_identical(reference):
    case, ref = reference
    sim = bed(case)
    sim.run(N)
    sim.run(N)
    assert_identical(ref, state(sim))


def test_restart_continues_bitwise(reference, tmp_path):
    case, ref = reference
    sim = bed(case)
    sim.run(N)
    at_restart = state(sim)
    assert len(at_restart["pair_history"]) > 20         # springs loaded at the restart step
    path = tmp_path / "bed.restart"
    sim.command(f"write_restart {path}")
    new = restarted(case, path)
    assert new.update.ntimestep == N
    assert new.update.dt == at_restart["dt"] == 1.5e-6
    assert new.update.time == at_restart["time"] > 0.0
    new.run(N)
    assert_identical(ref, state(new))
    # and the writer itself continues unchanged after writing
    sim.run(N)
    assert_identical(ref, state(sim))


SHELL = """
boundary f f f
region box block -3 3 -3 3 -3 3
create_box 1 box
create_atoms 1 single 0 0 0 radius 1.0 density 1 omega 0.3 0.2 5
"""
SHELL_FORCES = """
pair_style sphere
pair_coeff * * kn 1e4 en 0.9 mu 0.5 ks 2000
fix 1 all nve/sphere
"""


def shell():
    """A big sphere (id 1) spinning inside a shell of 20 small ones: 20 loaded springs in one row, more than
    the 8 per-particle history slots the store starts with (it grows, and the restart must carry the
    larger store)."""
    sim = dem.Simulation(screen=False)
    sim.commands(SHELL)
    k = np.arange(20) + 0.5                                  # Fibonacci points
    polar, azim = np.arccos(1 - 2 * k / 20), np.pi * (1 + 5 ** 0.5) * k
    pts = 1.199 * np.stack([np.sin(polar) * np.cos(azim), np.sin(polar) * np.sin(azim), np.cos(polar)], 1)
    for p in pts:
        sim.command("create_atoms 1 single %r %r %r radius 0.2 density 1" % tuple(float(c) for c in p))
    sim.commands(SHELL_FORCES + "timestep 1e-4\nthermo 0\n")
    return sim


def test_restart_with_grown_history_store(tmp_path):
    # the contacts last about T_c / 2 = 28 steps (initial overlap, no approach velocity): 10 + 10 steps
    ref = shell()
    ref.run(20)
    ref_state = state(ref)
    sim = shell()
    sim.run(10)
    assert sim.atom.data["pair_xi_tag"].shape[1] < 20
    sim.command(f"write_restart {tmp_path / 'shell.restart'}")    # packs: the store grows to 20 slots
    assert sim.atom.data["pair_xi_tag"].shape[1] >= 20
    new = dem.Simulation(screen=False)
    new.command(f"read_restart {tmp_path / 'shell.restart'}")
    new.commands("thermo 0\n" + SHELL_FORCES)
    assert new.update.dt == 1e-4 and new.update.time == sim.update.time
    new.run(10)
    s = state(new)
    assert s["time"] == ref_state["time"] and s["dt"] == ref_state["dt"]
    assert len([p for p in s["pair_history"] if p[0] == 1]) == 20
    for name in ("x", "v", "omega"):
        assert np.array_equal(ref_state[name], s[name]), name
    assert ref_state["pair_history"] == s["pair_history"]
