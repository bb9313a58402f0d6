"""Neighbor lists against brute force, and contact history across rebuilds.

The list (sim.neighbor.pairs(): owned row index i, partner j owned or ghost) must hold exactly the pairs whose
bounding spheres come closer than the skin, |xi - xj| < ri + rj + skin under the minimum-image convention,
each pair once, in the row of the smaller id; it is built from the positions of the last build (xhold).
The tangential spring history (ks > 0) is kept per pair in the list; a rebuild packs it per particle (keyed
by the partner's id) and gives it back to the new list: it must come back bit for bit, also when a spatial
sort permutes the particles and when a particle has more partners than the per-particle slots.
"""
import math

import numpy as np
import pytest

import dem
from flowing_bed import bed


# ----- brute force ----------------------------------------------------------------------------------------
def brute_pairs(x, r, tags, skin, lo, hi, periodic):
    """Set of (smaller id, larger id) with |xi - xj| < ri + rj + skin, minimum image on periodic axes."""
    d = x[:, None, :] - x[None, :, :]
    prd = hi - lo
    for k in range(3):
        if periodic[k]:
            d[:, :, k] -= prd[k] * np.round(d[:, :, k] / prd[k])
    dist = np.sqrt((d ** 2).sum(-1))
    cut = r[:, None] + r[None, :] + skin
    i, j = np.nonzero(np.triu(dist < cut, k=1))
    # pairs within 1e-12 of the cutoff could go either way by rounding (the list computes ghost positions
    # x + L and their difference, brute force the difference and then - L): left out of the comparison
    near = np.abs(dist - cut) < 1e-12 * cut
    ambiguous = {tuple(sorted((int(tags[a]), int(tags[b])))) for a, b in zip(*np.nonzero(np.triu(near, k=1)))}
    return {tuple(sorted((int(tags[a]), int(tags[b])))) for a, b in zip(i, j)}, ambiguous


def listed_pairs(sim):
    i, j = sim.neighbor.pairs()
    tag = sim.atom.data["tag"]
    nl, nall = sim.atom.nlocal, sim.atom.nall
    assert np.all(i < nl) and np.all((j >= 0) & (j < nall))
    ti, tj = tag[i], tag[j]
    # each pair once, in the row of the smaller id (so never a particle with itself or its own image)
    assert np.all(ti < tj)
    pairs = list(zip(ti.tolist(), tj.tolist()))
    assert len(pairs) == len(set(pairs)), "a pair is listed twice"
    return set(pairs)


def check_against_brute_force(sim, x):
    dom, nb = sim.domain, sim.neighbor
    listed = listed_pairs(sim)
    expected, ambiguous = brute_pairs(x, sim.atom.local("radius"), sim.atom.local("tag"), nb.skin,
                                      dom.lo, dom.hi, dom.periodic)
    assert not (listed ^ expected) - ambiguous, (
        f"missing {sorted(expected - listed)[:5]}, extra {sorted(listed - expected)[:5]}")
    return len(listed)


BOXES = [
    # boundary, box (x, y, z), N, radius spec, skin; solid fractions 0.15-0.2
    ("p p p", (7.0, 7.0, 7.0), 200, "radius uniform 0.2 0.6", 0.3),
    ("p p f", (8.0, 3.1, 8.0), 120, "radius uniform 0.2 0.6", 0.3),    # y barely above 2 x ghost cutoff 1.5
    ("p f p", (6.0, 6.0, 6.0), 150, "radius gaussian 0.35 0.1", 0.2),
    ("f p f", (5.0, 9.0, 5.0), 60, "radius uniform 0.1 0.8", 0.05),    # size ratio 8
    ("f f f", (6.0, 6.0, 6.0), 120, "radius uniform 0.2 0.6", 0.4),
]


def random_box(boundary, size, n, radius, skin, seed):
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
boundary {boundary}
region box block 0 {size[0]} 0 {size[1]} 0 {size[2]}
create_box 1 box
create_atoms 1 random {n} {seed} box {radius} density 1
pair_style sphere
pair_coeff * * kn 1e4 en 0.9
fix 1 all nve/sphere
timestep 1e-4
neighbor {skin} bin
thermo 0
""")
    return sim


@pytest.mark.parametrize("boundary,size,n,radius,skin", BOXES)
def test_list_equals_brute_force(boundary, size, n, radius, skin):
    for seed in (11, 12):
        sim = random_box(boundary, size, n, radius, skin, seed)
        # particles right at (and just across) the periodic faces: images and corners
        x = sim.atom.local("x")
        x[:10] = np.where(sim.domain.periodic, sim.domain.lo, x[:10])
        sim.neighbor.invalidate()
        sim.run(0)
        npairs = check_against_brute_force(sim, sim.atom.local("x"))
        assert npairs >= 10
        if sim.domain.periodic.any():          # pairs across the periodic faces are part of the comparison
            assert np.any(sim.neighbor.pairs()[1] >= sim.atom.nlocal)


@pytest.mark.parametrize("boundary,size,n,radius,skin", BOXES[:2] + BOXES[3:4])
def test_list_after_motion(boundary, size, n, radius, skin):
    """After a run: the list is that of the positions of the last build, and holds every pair in contact."""
    sim = random_box(boundary, size, n, radius, skin, 5)
    if "f" in boundary:
        axes = [a for a, b in zip("xyz", boundary.split()) if b == "f"]
        walls = " ".join(f"{a}plane 0 {size['xyz'.index(a)]}" for a in axes)
        sim.command(f"fix walls all wall/plane {walls}")
    rng = np.random.default_rng(3)
    sim.atom.local("v")[:] = 5.0 * rng.normal(size=(n, 3))     # several skins in 800 steps
    sim.run(800)
    nb, dom = sim.neighbor, sim.domain
    assert nb.nbuilds > 3
    check_against_brute_force(sim, nb.xhold)
    # every pair overlapping now (the forces of the last step were computed on x(n) = x - dt v) is listed
    x = sim.atom.local("x") - sim.update.dt * sim.atom.local("v")
    touching, _ = brute_pairs(x, sim.atom.local("radius"), sim.atom.local("tag"), 0.0, dom.lo, dom.hi,
                              dom.periodic)
    assert touching and touching <= listed_pairs(sim)


# ----- contact history across rebuilds ----------------------------------------------------------------------
# (the flowing bed: tests/flowing_bed.py)
def history_map(sim):
    i, j = sim.neighbor.pairs()
    tag = sim.atom.data["tag"]
    h = sim.pair.history.values
    assert len(h) == len(i)
    return {(int(tag[a]), int(tag[b])): tuple(h[k]) for k, (a, b) in enumerate(zip(i, j)) if np.any(h[k])}


def test_history_survives_rebuild_and_sort():
    sim = bed("periodic")
    sim.run(6000)
    before = history_map(sim)
    walls_before = sim.gather("fix_walls_xi")
    assert len(before) > 50                               # many contacts with a loaded spring
    order = sim.atom.local("tag").copy()
    nb = sim.neighbor
    nb.last_sort = -10 ** 9                               # make this rebuild sort the particles too
    nb.rebuild(sim.update.ntimestep)
    assert not np.array_equal(order, sim.atom.local("tag")), "the sort did not permute the particles"
    assert history_map(sim) == before                     # bit for bit, by particle ids
    assert np.array_equal(sim.gather("fix_walls_xi"), walls_before)


def test_history_with_more_partners_than_slots():
    """A big sphere (id 1) spinning inside a shell of 20 small ones: its row holds 20 loaded springs, more than
    the 8 per-particle slots the store starts with."""
    sim = dem.Simulation(screen=False)
    sim.commands("""
boundary f f f
region box block -3 3 -3 3 -3 3
create_box 1 box
create_atoms 1 single 0 0 0 radius 1.0 density 1 omega 0.3 0.2 5
""")
    k = np.arange(20) + 0.5                     # Fibonacci points on the sphere of radius 1.2 - overlap
    polar, azim = np.arccos(1 - 2 * k / 20), math.pi * (1 + 5 ** 0.5) * k
    pts = 1.199 * np.stack([np.sin(polar) * np.cos(azim), np.sin(polar) * np.sin(azim), np.cos(polar)], 1)
    for p in pts:
        sim.command("create_atoms 1 single %r %r %r radius 0.2 density 1" % tuple(float(c) for c in p))
    sim.commands("""
pair_style sphere
pair_coeff * * kn 1e4 en 0.9 mu 0.5 ks 2000
fix 1 all nve/sphere
timestep 1e-4
thermo 0
""")
    sim.run(20)
    before = history_map(sim)
    assert len([p for p in before if p[0] == 1]) == 20
    sim.neighbor.rebuild(sim.update.ntimestep)
    assert sim.atom.data["pair_xi_tag"].shape[1] >= 20    # the store grew
    assert history_map(sim) == before


def test_rebuild_every_step_is_bitwise_identical():
    """`neigh_modify every 1 check no` (a rebuild, with its pack/unpack of the history, every step) against
    the default (a rebuild every ~100 steps here): identical trajectories bit for bit. Rows are sorted by
    partner id, so the summation order does not depend on when the list was built.
    Conditions of bitwise identity: no spatial sort (`atom_modify sort 0 0`: a sort permutes the particles
    on rebuild steps, and a different permutation sums forces in another order) and no periodic axis (a
    particle is wrapped into the box on rebuild steps, x - L + L != x in floating point): with either, the
    two runs agree only to round-off, which the flow then amplifies."""
    a = bed("walled", extra="atom_modify sort 0 0\n")
    b = bed("walled", extra="atom_modify sort 0 0\nneigh_modify every 1 check no\n")
    a.run(6000)
    b.run(6000)
    assert b.neighbor.nbuilds == 6001 and a.neighbor.nbuilds < 100
    for name in ("x", "v", "omega", "fix_walls_xi"):
        assert np.array_equal(a.gather(name), b.gather(name)), name
    ha = history_map(a)
    assert len(ha) > 50 and ha == history_map(b)
