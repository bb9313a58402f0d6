"""Mass properties of glued convex composites: lattice integration over the union (Part III sec 2.3), exact
sums, the overlap test and the shape database (dem/shapes/glued_mass.py, _lattice.pyx, shape_db.py)."""
import os
import warnings

import h5py
import numpy as np
import pytest

from dem.contact.geometry import rotation
from dem.shapes import Box, Cone, Cylinder, Ellipsoid, Sphere, Superquadric, pinacoid, tetrahedron
from dem import verified_file
from dem.shapes import _lattice, glued_mass as gm, shape_db
from dem.shapes.base import POLYHEDRON


def random_rotation(rng):
    q = rng.normal(size=4)
    return rotation(q / np.linalg.norm(q))


RZ90 = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])     # exact quarter turns
RY90 = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])     # body z along x (columns: body axes)
RX90 = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])     # body z along -y


def box_moments(lo, hi):
    """(volume, int x, int x x^T) of the axis-aligned box [lo, hi]."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    V = np.prod(hi - lo)
    c = 0.5 * (lo + hi)
    s = (hi - lo) ** 2 / 12.0
    M = V * (np.outer(c, c) + np.diag(s))
    return V, V * c, M


def shape_moments(shape, off, R):
    """(volume, int x, int x x^T) of a posed convex shape, from its closed-form mass properties."""
    V = shape.volume
    I = R @ np.diag(shape.principal_moments) @ R.T
    Mc = 0.5 * np.trace(I) * np.eye(3) - I              # second moment about its centre
    return V, V * np.asarray(off, float), Mc + V * np.outer(off, off)


def from_moments(V, S1, M):
    c = S1 / V
    Mc = M - V * np.outer(c, c)
    return V, c, np.trace(Mc) * np.eye(3) - Mc


def rel_tensor(a, b):
    return np.abs(a - b).max() / np.abs(np.linalg.eigvalsh(b)).max()


def midpoint_deficit(V, cells, lo, hi):
    """The midpoint rule on cells of sides h misses V h_a^2 / 12 of int x_a^2: the inertia it misses."""
    h2 = ((np.asarray(hi) - np.asarray(lo)) / np.asarray(cells)) ** 2 * V / 12.0
    return np.diag([h2[1] + h2[2], h2[0] + h2[2], h2[0] + h2[1]])


# ---- point-in-body tests and the two kernels ---------------------------------------------------------

ALL_SHAPES = [Sphere(1.0), Box(1.0, 2.0, 3.0), Cylinder(0.7, 2.0), Cone(1.0, 2.0), Ellipsoid(1.0, 0.6, 0.4),
              Superquadric(1.0, 0.8, 0.6, 4.0, 3.0), tetrahedron(2.0), pinacoid(2.0, 1.5, 1.0)]


@pytest.mark.parametrize("shape", ALL_SHAPES, ids=lambda s: s.name)
def test_inside_matches_support(shape):
    # a surface point s(d) scaled by 1 -+ 1e-6 about the centre of mass is inside / outside (the body is
    # star-shaped about it; 1e-6 is far above the round-off of the gauges, far below any feature size)
    rng = np.random.default_rng(3)
    d = rng.normal(size=(400, 3))
    surf = shape.support(d)
    planes = np.asarray(shape._planes(), float) if shape.kind == POLYHEDRON else np.zeros((0, 4))
    params = np.ascontiguousarray(shape.params, float)
    assert _lattice.inside(shape.kind, params, planes, np.ascontiguousarray(surf * (1 - 1e-6))).all()
    assert not _lattice.inside(shape.kind, params, planes, np.ascontiguousarray(surf * (1 + 1e-6))).any()


def test_row_kernel_equals_point_kernel():
    # the row-interval kernel must find exactly the cells the point-by-point count finds: same indicator
    rng = np.random.default_rng(7)
    comps = [(s, rng.normal(size=3) * 0.6, random_rotation(rng)) for s in ALL_SHAPES]
    for res in (23, 40):
        a = gm.lattice_integrate(comps, res, method="rows")
        b = gm.lattice_integrate(comps, res, method="points")
        assert a[0] == b[0]                                   # identical counts -> identical volumes
        assert np.allclose(a[1], b[1], rtol=0, atol=1e-13)    # sums in another order: round-off only
        assert np.allclose(a[2], b[2], rtol=0, atol=1e-12)


def test_single_components_converge():
    # one component: the lattice tends to the closed forms. At 120 points the boundary digitisation is
    # ~1/120 of a cell layer: 0.5 % is a safe first-order bound (measured: <= 0.07 %, ellipsoid inertia)
    rng = np.random.default_rng(11)
    for s in ALL_SHAPES:
        R, off = random_rotation(rng), rng.normal(size=3)
        V, c, I = from_moments(*shape_moments(s, off, R))
        p = gm.union_mass_properties([(s, off, R)], 120)
        assert abs(p["volume"] / V - 1) < 5e-3, s.name
        assert np.linalg.norm(p["centre"] - c) < 5e-3 * s.bounding_radius, s.name
        assert rel_tensor(p["inertia"], I) < 5e-3, s.name


# ---- unions with exact answers -----------------------------------------------------------------------

def crossing_boxes(R=np.eye(3), shift=np.zeros(3)):
    # A: 4 x 1 x 1.2 at the origin; B: 3 x 1 x 0.8 turned a quarter about z (so 1 x 3 x 0.8) at
    # (0.5, 0.5, 0.2): every face at a multiple of 0.1 and the union's box 4 x 3 x 1.2, so the lattice of
    # 40 points on the long side has cells of 0.1 and every face on a cell plane
    A = (Box(4.0, 1.0, 1.2), R @ np.zeros(3) + shift, R)
    B = (Box(3.0, 1.0, 0.8), R @ np.array([0.5, 0.5, 0.2]) + shift, R @ RZ90)
    exact_parts = [box_moments([-2, -0.5, -0.6], [2, 0.5, 0.6]), box_moments([0, -1, -0.2], [1, 2, 0.6])]
    inter = box_moments([0, -0.5, -0.2], [1, 0.5, 0.6])
    V = exact_parts[0][0] + exact_parts[1][0] - inter[0]
    S1 = exact_parts[0][1] + exact_parts[1][1] - inter[1]
    M = exact_parts[0][2] + exact_parts[1][2] - inter[2]
    V, c, I = from_moments(V, S1, M)
    return [A, B], V, R @ c + shift, R @ I @ R.T


def test_crossing_boxes_on_lattice_planes_are_exact():
    # inclusion-exclusion: the intersection of the two boxes is a box. With every face on a cell plane the
    # lattice is exact but for the midpoint rule's h^2/12 per cell in x^2, added back, and the 1e-9
    # relative widening of the lattice box (union_bounding_box): 1e-8 covers it
    comps, V, c, I = crossing_boxes()
    assert gm.components_overlap(comps)
    p = gm.union_mass_properties(comps, 40)
    lo, hi = gm.union_bounding_box(comps)
    assert p["cells"] == (40, 30, 12)
    assert p["volume"] == pytest.approx(V, rel=1e-8)
    assert np.allclose(p["centre"], c, rtol=0, atol=1e-8)
    assert rel_tensor(p["inertia"] + midpoint_deficit(V, p["cells"], lo, hi), I) < 1e-8
    # the face-plane grid of boxes with common axes is exact to round-off, turned or not
    assert gm.aligned_boxes(comps)
    for R, shift in ((np.eye(3), np.zeros(3)), (random_rotation(np.random.default_rng(3)), np.array([1.0, 2, 3]))):
        comps, V, c, I = crossing_boxes(R, shift)
        Va, ca, Ia = gm.aligned_boxes_mass_properties(comps)
        assert Va == pytest.approx(V, rel=1e-13) and np.allclose(ca, c, rtol=0, atol=1e-13)
        assert rel_tensor(Ia, I) < 1e-12
    # the exact sums count the intersection twice
    Ve = gm.exact_mass_properties(comps)[0]
    assert Ve == pytest.approx(V + 1.0 * 1.0 * 0.8, rel=1e-14)


def test_crossing_boxes_turned():
    # the same union turned and moved: faces cut cells at random, the digitisation error is ~ area x h / 2
    # of random sign: at 200 points (h = 1/200 of the long side) a first-order bound is ~ area x h / V
    # ~ 0.3 % (measured 3e-5: the signs cancel); the error estimate must cover the true error (measured
    # estimate 3.8e-4) without being wildly above the first-order bound
    rng = np.random.default_rng(5)
    comps, V, c, I = crossing_boxes(random_rotation(rng), np.array([1.0, -2.0, 0.5]))
    p = gm.union_mass_properties(comps, 200)
    ev, ei = abs(p["volume"] / V - 1), rel_tensor(p["inertia"], I)
    assert ev < 3e-3 and ei < 3e-3
    assert np.linalg.norm(p["centre"] - c) < 3e-3
    assert max(ev, ei) <= p["error"] < 3e-3


def test_coaxial_cylinders():
    # r1 = 1, length 2 on [-1, 1] and r2 = 0.6, length 3 on [0.2, 3.2] along z: the intersection is the
    # cylinder r = 0.6 on [0.2, 1] (exact). Faces z = -1, 3.2 are on the lattice box; 0.2 and 1 are interior
    # to the union or on a cell plane (z = 1, h = 0.01). The error is the digitisation of the discs (Gauss
    # circle problem: a lattice count in a disc of R cells is off by ~R^(2/3), relative ~R^(-4/3)/pi):
    # 100 cells on the radius give ~5e-4 (measured -5e-4 for r = 0.6), hence 2e-3 on the volume and inertia
    # and 2e-3 of the length (4.2) on the centre (measured 1e-3: the two discs err with opposite signs)
    c1, c2 = Cylinder(1.0, 2.0), Cylinder(0.6, 3.0)
    comps = [(c1, np.zeros(3), np.eye(3)), (c2, np.array([0.0, 0.0, 1.7]), np.eye(3))]
    ci = Cylinder(0.6, 0.8)
    parts = [shape_moments(c1, np.zeros(3), np.eye(3)), shape_moments(c2, np.array([0, 0, 1.7]), np.eye(3))]
    inter = shape_moments(ci, np.array([0.0, 0.0, 0.6]), np.eye(3))
    V, c, I = from_moments(*(parts[0][k] + parts[1][k] - inter[k] for k in range(3)))
    assert gm.components_overlap(comps)
    p = gm.union_mass_properties(comps, 200)
    assert abs(p["volume"] / V - 1) < 2e-3
    assert np.linalg.norm(p["centre"] - c) < 2e-3 * 4.2
    assert rel_tensor(p["inertia"], I) < 2e-3


def steinmetz(r=1.0, L=3.0, R=np.eye(3), shift=np.zeros(3)):
    """Two equal cylinders (radius r, length L >= 2r) along x and y through the origin: their intersection
    is the Steinmetz bicylinder, volume 16 r^3/3, int z^2 = 16 r^5/15, int x^2 = int y^2 = 64 r^5/45
    (slices z: squares of side 2 sqrt(r^2 - z^2)); the union's moments are the cylinders' minus these."""
    cyl = Cylinder(r, L)
    comps = [(cyl, shift, R @ RY90), (cyl, shift, R @ RX90)]
    Vc = cyl.volume
    V = 2 * Vc - 16 * r ** 3 / 3
    # second moments of the two cylinders (along x: x^2 -> L^2/12, others r^2/4) minus the bicylinder
    mx = Vc * L ** 2 / 12 + Vc * r ** 2 / 4 - 64 * r ** 5 / 45
    mz = 2 * Vc * r ** 2 / 4 - 16 * r ** 5 / 15
    Mc = np.diag([mx, mx, mz])
    I = np.trace(Mc) * np.eye(3) - Mc
    return comps, V, shift, R @ I @ R.T


def test_orthogonal_cylinders_steinmetz():
    # tolerance: curved surfaces only, digitisation errors of random sign: at 200 points < 0.1 %
    # (measured 1.2e-5 volume, 2.1e-4 inertia)
    comps, V, c, I = steinmetz()
    assert gm.components_overlap(comps)
    p = gm.union_mass_properties(comps, 200)
    assert abs(p["volume"] / V - 1) < 1e-3
    assert np.linalg.norm(p["centre"] - c) < 1e-3
    assert rel_tensor(p["inertia"], I) < 1e-3


def test_error_decreases_with_resolution():
    # Fig. 3: the error decreases, "slightly non-monotone but overall linear". Turned Steinmetz union at 50,
    # 100, 200, 400 points: the error at 400 is below the one at 50 and 100 (a factor 2 margin on the
    # trend, against non-monotone steps), and below 0.2 % from 400 points. Measured max(volume, inertia)
    # relative errors 2.0e-4, 3.9e-4 (non-monotone, as in Fig. 3), 3.4e-5, 1.6e-5
    rng = np.random.default_rng(2)
    comps, V, c, I = steinmetz(R=random_rotation(rng), shift=np.array([0.3, 0.1, -0.2]))
    errs = {}
    for n in (50, 100, 200, 400):
        p = gm.union_mass_properties(comps, n, estimate_error=False)
        errs[n] = max(abs(p["volume"] / V - 1), rel_tensor(p["inertia"], I))
    assert errs[400] < 0.5 * errs[50] and errs[400] < errs[100]
    assert errs[400] < 2e-3


# ---- the glued cylinder of Part III (Table 1) --------------------------------------------------------

D, LEN = 8.0e-3, 5.3e-3
RHO = 3.1e-4 / 2.66407e-7          # Table 1: mass 3.1e-4 kg of the true cylinder, volume 2.66407e-7 m^3


def sliced_cylinder(N):
    return [(Cylinder(D / 2, LEN / N), np.array([0.0, 0.0, -LEN / 2 + (k + 0.5) * LEN / N]), np.eye(3))
            for k in range(N)]


def test_sliced_cylinder_exact_sums():
    # N equal slices do not overlap: the exact sums are the true cylinder to round-off (a few ulps)
    cyl = Cylinder(D / 2, LEN)
    for N in (1, 2, 5, 30):
        comps = sliced_cylinder(N)
        assert not gm.components_overlap(comps)
        V, c, I = gm.exact_mass_properties(comps)
        assert V == pytest.approx(cyl.volume, rel=1e-14)
        assert np.abs(c).max() < 1e-15 * LEN
        assert rel_tensor(I, cyl.inertia) < 1e-13


def test_glued_cylinder_table1_at_500_points():
    # Part III: < 0.2 % on volume and inertia from 500 points per direction. The ends are on the lattice
    # box (exact): only the rim is digitised. Measured at 500: volume +7.4e-5, inertia +1.2e-4 (diameter)
    # and +1.5e-4 (axis), error estimate 8.5e-4; Table 1's glued values 2.66413e-7 m^3, 1.9674e-9 and
    # 2.4793e-9 kg m^2 (theirs err by +2.3e-5, +7.5e-4, -2.6e-4 from the true cylinder)
    cyl = Cylinder(D / 2, LEN)
    p = gm.union_mass_properties(sliced_cylinder(6), 500)
    assert p["cells"] == (500, 500, 331)
    assert abs(p["volume"] / cyl.volume - 1) < 2e-3
    assert abs(p["inertia"][0, 0] / cyl.principal_moments[0] - 1) < 2e-3
    assert abs(p["inertia"][2, 2] / cyl.principal_moments[2] - 1) < 2e-3
    assert RHO * p["volume"] == pytest.approx(3.10007e-4, rel=2e-3)       # Table 1 glued mass
    assert RHO * p["inertia"][0, 0] == pytest.approx(1.9674e-9, rel=2e-3)
    assert RHO * p["inertia"][2, 2] == pytest.approx(2.4793e-9, rel=2e-3)
    assert p["error"] < 2e-3


# ---- overlap test ------------------------------------------------------------------------------------

def test_components_overlap():
    # touching faces, edges and vertices are not overlaps: the slices of a cylinder, the 8 cubes of a cube
    # (also turned as a whole); a depth of 1e-6 of the size is (the tolerance is 1e-9 of it)
    rng = np.random.default_rng(4)
    R = random_rotation(rng)
    cubes = [(Box(1.0, 1.0, 1.0), R @ (0.5 * np.array([sx, sy, sz])), R)
             for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    assert not gm.components_overlap(cubes)
    assert not gm.components_overlap(sliced_cylinder(4))
    s = Sphere(1.0)
    assert gm.components_overlap([(s, np.zeros(3), np.eye(3)), (s, np.array([1.9, 0, 0]), np.eye(3))])
    assert not gm.components_overlap([(s, np.zeros(3), np.eye(3)), (s, np.array([2.1, 0, 0]), np.eye(3))])
    b = Box(1.0, 1.0, 1.0)
    gap = 1.0 - 1e-6
    assert gm.components_overlap([(b, np.zeros(3), R), (b, R @ np.array([gap, 0, 0]), R)])
    assert not gm.components_overlap([(b, np.zeros(3), R), (b, R @ np.array([1.0 + 1e-6, 0, 0]), R)])


def test_rotation_to_quaternion_round_trip():
    rng = np.random.default_rng(9)
    mats = [random_rotation(rng) for _ in range(50)] + [np.eye(3), RZ90, RY90, RX90, np.diag([-1.0, -1.0, 1.0]),
                                                          np.diag([1.0, -1.0, -1.0]), np.diag([-1.0, 1.0, -1.0])]
    for R in mats:
        q = gm.rotation_to_quaternion(R)
        assert abs(np.linalg.norm(q) - 1) < 1e-15 and q[0] >= 0
        assert np.allclose(rotation(q), R, atol=1e-14)


# ---- MPI-style slab split ----------------------------------------------------------------------------

class _Recorder:
    """Rank 1 of a fake 2-rank communicator: keeps what it would send."""
    me, nprocs = 1, 2

    def __init__(self):
        self.sent = []

    def sum(self, a):
        self.sent.append(np.array(a, copy=True))
        return a


class _Adder:
    """Rank 0: adds rank 1's shares, in call order."""
    me, nprocs = 0, 2

    def __init__(self, other):
        self.other = list(other)

    def sum(self, a):
        return a + self.other.pop(0)


def test_slab_split_sums_equal_full_sums():
    # each rank's x-slabs, summed, are the full lattice: identical count, sums to round-off
    rng = np.random.default_rng(8)
    comps = [(s, rng.normal(size=3) * 0.5, random_rotation(rng)) for s in ALL_SHAPES[:5]]
    full = gm.union_mass_properties(comps, 60)
    r1 = _Recorder()
    gm.union_mass_properties(comps, 60, comm=r1)
    split = gm.union_mass_properties(comps, 60, comm=_Adder(r1.sent))
    assert split["volume"] == full["volume"]
    assert np.allclose(split["centre"], full["centre"], rtol=0, atol=1e-14)
    assert np.allclose(split["inertia"], full["inertia"], rtol=0, atol=1e-13)
    # the kernel itself: [0, k) + [k, nx) = [0, nx)
    packed = gm._pack(gm._components(comps))
    lo, hi = gm.union_bounding_box(comps)
    n = gm.lattice_cells(lo, hi, 50)
    c = 0.5 * (lo + hi)
    whole = _lattice.lattice_sums(*packed, lo, hi, n, c, 0, n[0])
    parts = _lattice.lattice_sums(*packed, lo, hi, n, c, 0, 17) + _lattice.lattice_sums(*packed, lo, hi, n, c, 17, n[0])
    assert parts[0] == whole[0]
    assert np.allclose(parts, whole, rtol=1e-13, atol=1e-13)


# ---- shape database ----------------------------------------------------------------------------------

def _comps():
    return [(Cylinder(1.0, 2.0), np.zeros(3), np.eye(3)), (Cylinder(0.6, 3.0), np.array([0.1, 0.0, 1.7]), RY90)]


def test_cache_returns_identical_numbers(tmp_path):
    db = shape_db.ShapeDB(tmp_path / "shapes.h5")
    first = shape_db.cached_union_mass_properties(_comps(), 40, db=db)
    assert first["cached"] is False
    again = shape_db.cached_union_mass_properties(_comps(), 40, db=db)
    assert again["cached"] is True
    assert again["volume"] == first["volume"] and again["error"] == first["error"]
    assert np.array_equal(again["centre"], first["centre"]) and np.array_equal(again["inertia"], first["inertia"])


def test_cache_invalidated_by_definition_or_resolution(tmp_path):
    db = shape_db.ShapeDB(tmp_path / "shapes.h5")
    comps = _comps()
    text = shape_db.definition_text(comps)
    db.put(text, 40, gm.union_mass_properties(comps, 40))
    assert db.get(text, 40) is not None
    assert db.get(text, 41) is None
    s, off, R = comps[1]
    moved = [comps[0], (s, off + np.array([np.spacing(0.1), 0, 0]), R)]           # one ulp
    assert shape_db.definition_text(moved) != text and db.get(shape_db.definition_text(moved), 40) is None
    grown = [comps[0], (Cylinder(0.6, 3.0 + 1e-15), off, R)]
    assert db.get(shape_db.definition_text(grown), 40) is None
    turned = [comps[0], (s, off, RX90)]
    assert db.get(shape_db.definition_text(turned), 40) is None
    # crusts do not matter
    crusted = [comps[0], (s.with_crust(0.01), off, R)]
    assert shape_db.definition_text(crusted) == text
    assert shape_db.cached_union_mass_properties(moved, 40, db=db)["cached"] is False


def _edited(path):
    """h5py.File of the shape database `path` to change, its whole-file checksum remade when closed (a
    whole file with a wrong entry: for the checks of each entry)."""
    class Edit(h5py.File):
        def __exit__(self, *exc):
            super().__exit__(*exc)
            verified_file.seal(path, shape_db.KIND)
    return Edit(path, "r+")


def test_cache_ignores_tampered_and_foreign_entries(tmp_path):
    path = tmp_path / "shapes.h5"
    db = shape_db.ShapeDB(path)
    comps = _comps()
    text = shape_db.definition_text(comps)
    props = gm.union_mass_properties(comps, 40)
    db.put(text, 40, props)
    key = shape_db._key(text, 40)
    with _edited(path) as f:                 # tampered number: fails the checksum
        f["entries/%s/volume" % key][0] = 2.0 * props["volume"]
    with pytest.warns(shape_db.ShapeDBWarning, match="checksum"):
        assert db.get(text, 40) is None
    with pytest.warns(shape_db.ShapeDBWarning, match="checksum"):
        fresh = shape_db.cached_union_mass_properties(comps, 40, db=db)     # recomputed and replaced
    assert fresh["cached"] is False and fresh["volume"] == props["volume"]
    assert db.get(text, 40)["volume"] == props["volume"]
    with _edited(path) as f:                 # foreign entry under this key: another definition
        f["entries/%s" % key].attrs["definition"] = text.replace("component", "komponent")
    with pytest.warns(shape_db.ShapeDBWarning, match="another definition"):
        assert db.get(text, 40) is None
    with _edited(path) as f:                 # stale version
        g = f["entries/%s" % key]
        g.attrs["definition"] = text
        g.attrs["version"] = shape_db.ALGORITHM_VERSION - 1
    with pytest.warns(shape_db.ShapeDBWarning):
        assert db.get(text, 40) is None


def test_corrupt_file_warns_and_recomputes(tmp_path):
    path = tmp_path / "shapes.h5"
    path.write_bytes(b"\x89HDF\r\n\x1a\n" + b"damaged" * 10)      # an HDF5 file, damaged
    db = shape_db.ShapeDB(path)
    with pytest.warns(shape_db.ShapeDBWarning, match="it is an HDF5 file without dem's checksum"):
        p = shape_db.cached_union_mass_properties(_comps(), 30, db=db)
    assert p["cached"] is False
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert shape_db.cached_union_mass_properties(_comps(), 30, db=db)["cached"] is True
    assert os.path.exists(str(path) + ".corrupt")


def test_a_file_that_is_not_hdf5_is_left_as_it_is(tmp_path):
    path = tmp_path / "shapes.h5"
    path.write_bytes(b"somebody's notes")
    db = shape_db.ShapeDB(path)
    with pytest.warns(shape_db.ShapeDBWarning) as caught:           # unreadable, then not written
        assert shape_db.cached_union_mass_properties(_comps(), 30, db=db)["cached"] is False
    assert any("is not a dem shape database: left as it is" in str(w.message) for w in caught)
    assert path.read_bytes() == b"somebody's notes" and not os.path.exists(str(path) + ".corrupt")


def test_a_damaged_database_never_reaches_hdf5(tmp_path, monkeypatch):
    """The whole file is checked before h5py opens it: a changed byte is found, the file set aside unopened
    (many damaged copies, in subprocesses: test_damaged_files.py)."""
    path = tmp_path / "shapes.h5"
    db = shape_db.ShapeDB(path)
    shape_db.cached_union_mass_properties(_comps(), 20, db=db)
    with h5py.File(path, "r") as f:                  # an HDF5 file as any other (the header: a user block)
        assert len(f["entries"]) == 1
    data = bytearray(path.read_bytes())
    data[len(data) // 2] ^= 0x10
    path.write_bytes(bytes(data))
    monkeypatch.setattr(h5py, "File", None)
    with pytest.warns(shape_db.ShapeDBWarning, match="not read: it is damaged: checksum mismatch"):
        assert db.get(shape_db.definition_text(_comps()), 20) is None
    monkeypatch.undo()
    with pytest.warns(shape_db.ShapeDBWarning, match="checksum mismatch") as caught:
        assert shape_db.cached_union_mass_properties(_comps(), 20, db=db)["cached"] is False
    assert "moved to %s.corrupt" % path in str(caught[-1].message)
    assert shape_db.cached_union_mass_properties(_comps(), 20, db=db)["cached"] is True


def test_default_path_and_disabling(tmp_path, monkeypatch):
    monkeypatch.setenv("DEM_SHAPE_DB", "none")
    assert shape_db.default_db() is None
    p = shape_db.cached_union_mass_properties(_comps(), 20)
    assert p["cached"] is False
    monkeypatch.setenv("DEM_SHAPE_DB", str(tmp_path / "x" / "db.h5"))
    assert shape_db.default_db().path == str(tmp_path / "x" / "db.h5")
    shape_db.cached_union_mass_properties(_comps(), 20)
    assert shape_db.cached_union_mass_properties(_comps(), 20)["cached"] is True
    monkeypatch.delenv("DEM_SHAPE_DB")
    assert shape_db.default_db().path == os.path.expanduser("~/.cache/dem/shapes.h5")


class _RankComm:
    """Rank ``me`` of a fake communicator whose bcast hands out rank 0's object."""

    def __init__(self, me, root_value=None):
        self.me, self.nprocs = me, 2
        self.root_value = root_value

    def sum(self, a):
        return a

    def bcast(self, obj):
        return obj if self.me == 0 else self.root_value


def test_only_rank_zero_writes(tmp_path):
    path = tmp_path / "shapes.h5"
    shape_db.cached_union_mass_properties(_comps(), 20, db=shape_db.ShapeDB(path), comm=_RankComm(1))
    assert not path.exists()
    shape_db.cached_union_mass_properties(_comps(), 20, db=shape_db.ShapeDB(path), comm=_RankComm(0))
    assert path.exists()
