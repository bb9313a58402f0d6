"""compute coord: the coordination number of a group from the per-particle contact count (dem/tally.py),
which every pair style fills.

Three bodies in a row, each overlapping its neighbour by 1 um (and nothing else), for each pair style:
the middle body has 2 contacts, the two ends 1 each, so Z = 2 for the middle, 1 for the ends and 4/3 for
all. These are counts, exact; a pair of polyhedra touching face to face (4 points) or of composites
counts once. A floor under the row (wall/plane) adds its contacts to W and Z_walls only: one per body,
one per touching component for the dumbbells (wall/plane counts a composite's component contacts).
`coord points` counts contact points instead: the same for spheres, convex bodies and the dumbbells of the
row (one component pair touches), 4 per face/face contact of two cubes with polyhedron/multipoint, and 2
for two dumbbells side by side (both component pairs touch)."""
import numpy as np
import pytest

import dem

A = 0.002      # size of every body (m)
OV = 1e-6      # overlap of neighbours (m)

STYLES = {
    "sphere": ("", "radius 0.001", "sphere", A / 2),
    "convex/gjk": ("shape c cube 0.002\n", "shape c", "convex/gjk", A / 2),
    "glued/convex": ("shape c glued component sphere 0.0005 at -0.0005 0 0 component sphere 0.0005 at 0.0005 0 0\n",
                     "shape c", "glued/convex", A / 4),          # 2 mm long, 1 mm tall
    "polyhedron/multipoint": ("shape c cube 0.002\n", "shape c", "polyhedron/multipoint", A / 2),
}


def row(style):
    shape, what, pair, half = STYLES[style]
    text = f"""units si
boundary p p f
region box block -0.01 0.01 -0.01 0.01 0 0.02
create_box 1 box
{shape}"""
    for k in range(3):
        text += f"create_atoms 1 single {k * (A - OV)!r} 0 {half - OV!r} {what} density 2500\n"
    return text + f"""pair_style {pair}
pair_coeff * * kn 1e5 en 0.5 mu 0.3
fix integ all {'nve/sphere' if style == 'sphere' else 'nve/shape'}
fix floor all wall/plane zplane 0 NULL kn 1e5 en 0.5 mu 0.3
group ends id 1 3
group middle id 2
compute za all coord
compute ze ends coord
compute zm middle coord
compute pa all coord points
compute pm middle coord points
timestep 1e-7
thermo 0
run 1
"""


@pytest.mark.parametrize("style", list(STYLES))
def test_coordination_of_groups(style):
    sim = dem.Simulation(screen=False)
    sim.commands(row(style))
    za, ze, zm = (sim.computes[c] for c in ("za", "ze", "zm"))
    assert za.scalar() == pytest.approx(4 / 3, abs=1e-12)
    assert zm.scalar() == 2.0
    assert ze.scalar() == 1.0
    w = 6.0 if style == "glued/convex" else 3.0
    assert list(za.vector()) == pytest.approx([4 / 3, (4 + w) / 3, 2, w])   # 2 pair contacts
    assert list(zm.vector()) == [2.0, 2.0 + w, 1.0, w]                       # W: every wall contact
    assert list(ze.vector()) == [1.0, (2.0 + w) / 2, 1.0, w]
    per = 4.0 if style == "polyhedron/multipoint" else 1.0          # points per contact
    assert sim.computes["pm"].scalar() == 2.0 * per
    assert list(sim.computes["pa"].vector()) == pytest.approx([4 / 3 * per, (4 * per + w) / 3, 2 * per, w])


def test_points_of_composites_side_by_side():
    """Two dumbbells side by side (1 um overlap across their length): one pair contact, two points."""
    shape, what, _, half = STYLES["glued/convex"]
    sim = dem.Simulation(screen=False)
    sim.commands(f"""units si
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01
create_box 1 box
{shape}create_atoms 1 single 0 0 0 {what} density 2500
create_atoms 1 single 0 {2 * half - OV!r} 0 {what} density 2500
pair_style glued/convex
pair_coeff * * kn 1e5 en 0.5 mu 0.3
fix integ all nve/shape
compute z all coord
compute p all coord points
timestep 1e-7
thermo 0
run 1
""")
    assert sim.computes["z"].scalar() == 1.0
    assert sim.computes["p"].scalar() == 2.0


def test_lattice_groups():
    """A 4 x 4 x 4 cubic lattice of spheres, neighbours overlapping by 1 um: 144 contacts; the 8 inner
    spheres have 6 each; a group of every sphere gives what `all` gives (2 C / N = 4.5)."""
    r, n = 0.001, 4
    text = """units si
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01
create_box 1 box
"""
    inner = []
    for k in range(n ** 3):
        i, j, l = k % n, (k // n) % n, k // n ** 2
        text += f"create_atoms 1 single {i * (2 * r - OV)!r} {j * (2 * r - OV)!r} {l * (2 * r - OV)!r} radius {r} density 2500\n"
        if all(0 < c < n - 1 for c in (i, j, l)):
            inner.append(str(k + 1))
    sim = dem.Simulation(screen=False)
    sim.commands(text + f"""pair_style sphere
pair_coeff * * kn 1e4 en 0.3 mu 0.5
fix integ all nve/sphere
group every type 1
group inner id {' '.join(inner)}
compute za all coord
compute zg every coord
compute zi inner coord
timestep 1e-7
thermo 0
run 1
""")
    za, zg, zi = (sim.computes[c] for c in ("za", "zg", "zi"))
    assert sim.pair.ncontacts == 3 * n * n * (n - 1)
    assert za.scalar() == 2 * 144 / 64
    assert list(zg.vector()) == list(za.vector())
    assert zi.scalar() == 6.0


def test_tally_reverse_sums_ghosts_in_ghost_order():
    """The serial reverse of tallies (every step when one is in use) adds ghost rows to their owners in
    ghost order: bit for bit the sums of np.add.at, for the widths of the tallies."""
    from dem.comm import _serial
    rng = np.random.default_rng(1)
    for width in (2, 5, 9):
        a = rng.random((500, width))
        owner = rng.integers(0, 200, 300).astype(np.int64)       # owners repeat: several images of one
        b = a.copy()
        np.add.at(a, owner, a[200:500])
        _serial.reverse_rows(b, owner, 200)
        assert np.array_equal(a, b)
