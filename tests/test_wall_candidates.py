"""The walls test only the (particle, surface) pairs that may touch before the next neighbor rebuild
(plugins/dem_walls/_walls.pyx `candidates`, built at each rebuild): a particle moves less than half the skin
between rebuilds, so the pairs left out are apart until then.

Checked: the pairs listed against distances computed here; and spheres thrown at the walls of a box and a
drum from far away, fast (a particle crosses the skin in a few steps), which do not touch each other: each
particle's trajectory is its own, so it must be bitwise the same with the default rebuilds (candidates
kept for many steps) as with a rebuild at every step (candidates always fresh). A pair missed by the
candidates would let its particle through the wall."""
import numpy as np
import pytest

import dem
from dem._particles import ParticleView
from dem_walls import _walls


def throw(script_walls, rebuild_every_step, steps=3000):
    rng = np.random.default_rng(3)
    sim = dem.Simulation(screen=False)
    lines = ["units si", "boundary f f f", "region box block -0.055 0.055 -0.055 0.055 -0.055 0.055",
             "create_box 1 box"]
    # a 5 x 5 x 5 lattice of pitch 16 mm (radius 1 mm: never touching each other), velocities up to 3 m/s
    for i, p in enumerate(np.stack(np.meshgrid(*[np.arange(-2, 3) * 0.016] * 3), -1).reshape(-1, 3)):
        v = rng.uniform(-3, 3, 3)
        x, y, z, vx, vy, vz = (float(c) for c in (*p, *v))
        lines.append(f"create_atoms 1 single {x!r} {y!r} {z!r} radius 0.001 density 2500 v {vx!r} {vy!r} {vz!r}")
    lines += ["pair_style sphere", "pair_coeff * * kn 1e4 en 0.7 mu 0.5 gamma_t 2000 ks 2857",
              "fix integrate all nve/sphere", script_walls, "timestep 2e-6", "neighbor 0.0002 bin", "thermo 0"]
    if rebuild_every_step:
        lines.append("neigh_modify every 1 delay 0 check no")
    sim.commands("\n".join(lines))
    contacts = [0]
    sim.every(1, lambda s: contacts.__setitem__(0, contacts[0] + s.modify.find("w").ncontacts))
    sim.run(steps)
    tag = sim.atom.data["tag"][:sim.atom.nlocal]
    order = np.argsort(tag)
    state = np.hstack([sim.atom.data[k][:sim.atom.nlocal][order] for k in ("x", "v", "omega")])
    return state, contacts[0], sim.neighbor.nbuilds


@pytest.mark.parametrize("walls", [
    "fix w all wall/plane xplane -0.04 0.04 yplane -0.04 0.04 zplane -0.04 0.04 kn 1e4 en 0.7 mu 0.5 "
    "gamma_t 2000 ks 2857",
    "fix w all wall/drum z 0 0 0.05 rpm 60 ends -0.04 0.04 fixed kn 1e4 en 0.7 mu 0.5 gamma_t 2000 ks 2857",
])
def test_candidates_miss_no_contact(walls):
    fresh, n_fresh, builds_fresh = throw(walls, True)
    kept, n_kept, builds_kept = throw(walls, False)
    assert builds_fresh == 3000 + 1 and builds_kept < 300      # candidates kept for ~10+ steps at a time
    assert n_fresh > 1000                                      # the walls were hit, many times
    assert n_kept == n_fresh and np.array_equal(kept, fresh)


def test_candidates_are_the_pairs_within_reach():
    sim = dem.Simulation(screen=False)
    sim.commands("""units si
boundary f f f
region box block 0 1 0 1 0 1
create_box 1 box
create_atoms 1 single 0.5 0.5 0.05 radius 0.01 density 1
create_atoms 1 single 0.5 0.5 0.5 radius 0.01 density 1
create_atoms 1 single 0.008 0.985 0.5 radius 0.01 density 1
group some id 2 3
pair_style sphere
pair_coeff * * kn 1 en 1
fix w all wall/plane xplane 0 1 zplane 0 NULL kn 1 en 1
""")
    surfaces = sim.modify.find("w").surfaces()        # x = 0, x = 1, z = 0
    view = ParticleView(sim.atom)
    everyone = sim.groups.bit("all")
    part, off, wall = _walls.candidates(view, int(everyone), surfaces, 0.045)
    listed = {(int(sim.atom.data["tag"][i]), int(w)) for k, i in enumerate(part) for w in wall[off[k]:off[k + 1]]}
    assert listed == {(1, 2), (3, 0)}     # z = 0 at 0.05 < 0.045 + 0.01; x = 0 at 0.008 (x = 1 at 0.992: out)
    part, off, wall = _walls.candidates(view, int(everyone), surfaces, 0.0)
    assert len(part) == 1 and int(sim.atom.data["tag"][part[0]]) == 3   # only the overlapping one
    part, off, wall = _walls.candidates(view, int(sim.groups.bit("some")), surfaces, 0.045)
    assert [int(sim.atom.data["tag"][i]) for i in part] == [3]         # the wall's group only
