"""The overlap volume of two sharp polytopes and its gradient (dem/contact/_volume.pyx), the geometry of
`law volume`.

References: the volume of the intersection from scipy's half-space intersection and convex hull (Qhull),
an independent route; the gradients S = dV/dx_a and M = dV/dtheta_a from central differences of the
kernel's own V (step 1e-6 of sizes ~1: truncation ~1e-12, round-off of V ~1e-16 / 1e-6 = 1e-10 relative,
so 1e-8 relative to |S|); closed forms for aligned boxes and a cube's corner. Volumes: Qhull's hull volume is
exact to round-off on these vertex counts, so 1e-12 relative.
"""
import numpy as np
import pytest
from scipy.optimize import linprog
from scipy.spatial import ConvexHull, HalfspaceIntersection

from dem.contact import geometry as G
from dem.contact import polytope as P
from dem.shapes import Box, cube, pinacoid, tetrahedron

ID = np.array([1.0, 0.0, 0.0, 0.0])
SHAPES = [cube(1.0), tetrahedron(1.5), pinacoid(1.1, 1.1, 1.1), Box(1.0, 0.6, 0.4)]


def rquat(rng):
    q = rng.normal(size=4)
    return q / np.linalg.norm(q)


def turned(q, w):
    """q turned by the small world rotation vector w."""
    a = np.linalg.norm(w)
    d = np.r_[np.cos(a / 2), np.sin(a / 2) * w / a]
    return np.r_[d[0] * q[0] - d[1:] @ q[1:], d[0] * q[1:] + q[0] * d[1:] + np.cross(d[1:], q[1:])]


def halfspaces(shape, x, q):
    n = shape.topology.face_normals @ G.rotation(q).T
    return np.column_stack([n, -(shape.topology.face_offsets + n @ x)])     # n.x - d <= 0


def qhull_volume(H):
    """Volume of {x: H[:, :3] x + H[:, 3] <= 0}, 0 when empty (Chebyshev centre by linear programming)."""
    norm = np.linalg.norm(H[:, :3], axis=1)
    lp = linprog(np.r_[0, 0, 0, -1], A_ub=np.column_stack([H[:, :3], norm]), b_ub=-H[:, 3],
                 bounds=[(None, None)] * 3 + [(0, None)])
    if lp.status != 0 or lp.x[3] < 1e-9:
        return 0.0
    return ConvexHull(HalfspaceIntersection(H, lp.x[:3]).intersections).volume


def random_pairs(n, seed=1):
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        a, b = SHAPES[rng.integers(4)], SHAPES[rng.integers(4)]
        xa = rng.normal(size=3) * 0.1
        xb = xa + rng.normal(size=3) * 0.35
        qa, qb = rquat(rng), rquat(rng)
        if P.overlap_volume(a, xa, qa, b, xb, qb).volume > 0:
            out.append((a, xa, qa, b, xb, qb))
    return out


@pytest.fixture(scope="module")
def pairs():
    return random_pairs(40)


def test_volume_matches_qhull(pairs):
    for a, xa, qa, b, xb, qb in pairs:
        v = qhull_volume(np.vstack([halfspaces(a, xa, qa), halfspaces(b, xb, qb)]))
        assert P.overlap_volume(a, xa, qa, b, xb, qb).volume == pytest.approx(v, rel=1e-12)


def test_gradients_are_the_volumes_derivatives(pairs):
    h = 1e-6
    for a, xa, qa, b, xb, qb in pairs:
        r = P.overlap_volume(a, xa, qa, b, xb, qb)

        def vol(x=xa, q=qa):
            return P.overlap_volume(a, x, q, b, xb, qb).volume

        S = [(vol(x=xa + h * e) - vol(x=xa - h * e)) / (2 * h) for e in np.eye(3)]
        M = [(vol(q=turned(qa, h * e)) - vol(q=turned(qa, -h * e))) / (2 * h) for e in np.eye(3)]
        scale = np.linalg.norm(r.area)
        assert np.abs(S - r.area).max() < 1e-8 * scale
        assert np.abs(M - r.moment).max() < 1e-8 * scale


def test_both_sides_agree(pairs):
    """B's view: the same V and centroid, S_B = -S_A, and the moments close: M_B = -(M_A + (x_a - x_b) x S_A)
    (the boundary of the intersection is closed)."""
    for a, xa, qa, b, xb, qb in pairs:
        ra, rb = P.overlap_volume(a, xa, qa, b, xb, qb), P.overlap_volume(b, xb, qb, a, xa, qa)
        scale = np.linalg.norm(ra.area)
        assert rb.volume == pytest.approx(ra.volume, rel=1e-12)
        assert np.abs(rb.centroid - ra.centroid).max() < 1e-12
        assert np.abs(rb.area + ra.area).max() < 1e-12 * scale
        assert np.abs(rb.moment + ra.moment + np.cross(xa - xb, ra.area)).max() < 1e-12 * scale


def test_centroid_matches_qhull_vertices_mean_for_a_box_overlap():
    """Two aligned boxes: the intersection is a box, its centroid the middle of the common ranges."""
    a, b = Box(1.0, 0.6, 0.4), cube(1.0)
    xb = np.array([0.7, 0.2, -0.55])
    r = P.overlap_volume(a, [0, 0, 0], ID, b, xb, ID)
    lo = np.maximum([-0.5, -0.3, -0.2], xb - 0.5)
    hi = np.minimum([0.5, 0.3, 0.2], xb + 0.5)
    assert r.volume == pytest.approx(np.prod(hi - lo), rel=1e-13)
    assert np.abs(r.centroid - (lo + hi) / 2).max() < 1e-14


@pytest.mark.parametrize("depth", [1e-9, 1e-6, 0.01, 0.3])
def test_stacked_cubes_count_the_common_sides_once(depth):
    """Aligned cubes, one on the other: their side faces share planes. V = L^2 depth and S = -L^2 z exactly
    (a side counted twice or not at all, as round-off would decide, changes V by order depth L^2)."""
    c = cube(1.0)
    r = P.overlap_volume(c, [0, 0, 0], ID, c, [0, 0, 1.0 - depth], ID)
    assert r.volume == pytest.approx(depth, rel=1e-9, abs=1e-16)
    assert np.abs(r.area - [0, 0, 1]).max() < 1e-12
    assert np.abs(r.moment).max() < 1e-12
    # the stack turned and moved as a whole: the shared planes now differ by round-off either way
    rng = np.random.default_rng(11)
    for _ in range(20):
        q, x = rquat(rng), rng.normal(size=3) * 10
        R = G.rotation(q)
        r = P.overlap_volume(c, x, q, c, x + R @ [0.3, 0.0, 1.0 - depth], q)    # the y sides shared
        assert r.volume == pytest.approx(0.7 * depth, rel=1e-7 if depth > 1e-7 else 1e-3)
        assert np.abs(r.area - R @ [depth, 0.0, 0.7]).max() < 1e-9


def test_cube_corner_closed_form():
    """A cube's corner pointing straight into a half-space (the solid z >= 0) to depth d: a trirectangular
    tetrahedron of legs sqrt(3) d, V = sqrt(3)/2 d^3; A's faces inside have the area vector of its base,
    3 sqrt(3)/2 d^2 along +z."""
    c = cube(1.0)
    u = np.array([1.0, 1.0, 1.0]) / np.sqrt(3)        # the corner (0.5, 0.5, 0.5) turned onto +z
    axis = np.cross(u, [0, 0, 1.0])
    ang = np.arccos(u[2])
    q = np.r_[np.cos(ang / 2), np.sin(ang / 2) * axis / np.linalg.norm(axis)]
    for d in (1e-4, 0.05, 0.2):
        r = P.overlap_halfspace(c, [0.1, -0.2, d - np.sqrt(3) / 2], q, [0, 0, -1], 0.0)
        assert r.volume == pytest.approx(np.sqrt(3) / 2 * d ** 3, rel=1e-10)
        assert np.abs(r.area - [0, 0, 1.5 * np.sqrt(3) * d * d]).max() < 1e-12


def test_halfspace_matches_qhull():
    rng = np.random.default_rng(4)
    for shape in SHAPES:
        for _ in range(6):
            q, x = rquat(rng), rng.normal(size=3) * 0.3
            n = rng.normal(size=3)
            n /= np.linalg.norm(n)
            r = P.overlap_halfspace(shape, x, q, n, 0.1)
            v = qhull_volume(np.vstack([halfspaces(shape, x, q), np.r_[n, -0.1]]))
            assert r.volume == pytest.approx(v, rel=1e-12, abs=1e-15)
            h = 1e-6
            S = [(P.overlap_halfspace(shape, x + h * e, q, n, 0.1).volume
                  - P.overlap_halfspace(shape, x - h * e, q, n, 0.1).volume) / (2 * h) for e in np.eye(3)]
            assert np.abs(S - r.area).max() < 1e-8 * max(np.linalg.norm(r.area), 1.0)   # S = 0 when A is all in


def test_apart_is_zero():
    c = cube(1.0)
    r = P.overlap_volume(c, [0, 0, 0], ID, c, [0, 0, 1.0 + 1e-12], ID)
    assert r.volume == 0 and not np.any(r.area)
