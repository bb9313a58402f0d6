"""Polytope topology, exact penetration of sharp polytopes (separating axes) and their multipoint contacts.

References: closed forms for boxes; Coal's EPA (its most accurate settings, as in test_gjk.py) and dem's own
EPA (dem.contact.geometry.distance) on random sharp polyhedron pairs; support-function certificates computed here
in numpy from the posed vertices.

Tolerances: the separating-axis depth has no stopping rule, only round-off (a few ulps of the bounding
radii L, times the conditioning of an edge cross product); ties between axes are resolved within 1e-12 L.
So depths vs closed forms: 1e-12 L absolute; vs Coal and EPA (which stop on a 1e-10 gap): 1e-9 relative,
the issue's figure. Support certificates (h_{A-B}(n) = depth): 1e-12 L. Normals vs EPA's: 1e-6 rad (EPA's
normal comes from its last face, whose plane is known to about its 1e-10 gap over the face size).
"""
import numpy as np
import pytest

from dem.contact import geometry as G
from dem.contact import _polytope
from dem.contact import polytope as P
from dem.shapes import Box, Cylinder, Polyhedron, Sphere, cube, pinacoid, tetrahedron
from dem.shapes.topology import check, pack_topology

ID = np.array([1.0, 0.0, 0.0, 0.0])


def rquat(rng):
    q = rng.normal(size=4)
    return q / np.linalg.norm(q)


def qaxis(axis, angle):
    a = np.asarray(axis, float)
    a = a / np.linalg.norm(a)
    return np.r_[np.cos(angle / 2), np.sin(angle / 2) * a]


def world_vertices(s, x, q):
    return s.topology.vertices @ G.rotation(q).T + x


def h_diff(A, xa, qa, B, xb, qb, u):
    """h_{A-B}(u) = max_A u.x - min_B u.x from the posed vertices (numpy, independent of the kernel)."""
    return float((world_vertices(A, xa, qa) @ u).max() - (world_vertices(B, xb, qb) @ u).min())


# ---------------------------------------------------------------- topology
@pytest.mark.parametrize("shape, counts", [(cube(1.0), (8, 12, 6)), (Box(0.3, 1.0, 2.0), (8, 12, 6)),
                                           (tetrahedron(1.0), (4, 6, 4)), (pinacoid(1.0, 0.8, 0.6), (8, 14, 8))])
def test_topology_counts_and_faces(shape, counts):
    t = shape.topology
    assert (t.nv, t.ne, t.nf) == counts          # pinacoid: Descantes Fig. 4, 8 vertices, 14 edges, 8 faces
    check(t)
    assert shape.face_normals is t.face_normals and shape.edges is t.edges
    # each edge: its two faces contain it with opposite orientations, f0 running v0 -> v1
    for (v0, v1), (f0, f1) in zip(t.edges, t.edge_faces):
        for f, (a, b) in ((f0, (v0, v1)), (f1, (v1, v0))):
            F = list(t.faces[f])
            k = F.index(a)
            assert F[(k + 1) % len(F)] == b
    # planes agree with the hull equations: every vertex inside, each face's vertices on it
    V = t.vertices
    assert np.all(V @ t.face_normals.T <= t.face_offsets + 1e-12)


def test_topology_merges_coplanar_triangles():
    rng = np.random.default_rng(0)
    # a cube given as its 8 corners plus points on its faces and edges: still 6 quads
    pts = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], float)
    extra = np.c_[rng.uniform(-1, 1, (20, 2)), np.ones(20)]
    s = Polyhedron(np.vstack([pts, extra, [[0, 1, 1], [1, 0, -1]]]))
    t = s.topology
    assert t.nf == 6 and t.ne == 12 and all(len(f) == 4 for f in t.faces)
    check(t)
    for k in range(50):
        p = Polyhedron(rng.normal(size=(rng.integers(4, 40), 3)))
        check(p.topology)
        assert len(p.topology.vertices) - p.topology.ne + p.topology.nf == 2


def test_pack_topology_offsets():
    shapes = [cube(1.0), Sphere(0.5), pinacoid(1.0, 0.8, 0.6), Cylinder(0.3, 1.0), tetrahedron(2.0)]
    a = pack_topology(shapes)
    assert list(a["poly"]) == [1, 0, 1, 0, 1]
    for i, s in enumerate(shapes):
        t = s.topology
        if t is None:
            assert a["nv"][i] == a["nf"][i] == a["ne"][i] == 0
            continue
        np.testing.assert_array_equal(a["verts"][a["voff"][i]:a["voff"][i] + a["nv"][i]], t.vertices)
        for f in range(t.nf):
            j = a["foff"][i] + f
            ids = a["face_verts"][a["fvoff"][i] + a["face_first"][j]:][:a["face_count"][j]]
            np.testing.assert_array_equal(ids, t.faces[f])
            np.testing.assert_array_equal(a["face_normal"][j], t.face_normals[f])
        e = slice(a["eoff"][i], a["eoff"][i] + a["ne"][i])
        np.testing.assert_array_equal(a["edge_verts"][e], t.edges)
        np.testing.assert_array_equal(a["edge_faces"][e], t.edge_faces)
    # a polyhedron keeps GJK's vertex ids
    np.testing.assert_array_equal(shapes[2].topology.vertices, shapes[2].vertices)


# ---------------------------------------------------------------- depth: closed forms for boxes
def box_depth_z_rotated(ha, hb, theta, d):
    """Exact penetration of box A (half sides ha, axis-aligned, at 0) and box B (half sides hb, rotated by
    theta about z, at d): boxes that differ by a rotation about z have only face axes (every edge cross
    product is z or in the plane), so the depth is the minimum over the 5 distinct face axes of the
    projected overlaps, each in closed form."""
    c, s = np.cos(theta), np.sin(theta)
    axes = {"xA": np.array([1.0, 0, 0]), "yA": np.array([0, 1.0, 0]), "z": np.array([0, 0, 1.0]),
            "xB": np.array([c, s, 0]), "yB": np.array([-s, c, 0])}
    RB = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    best = np.inf
    for u in axes.values():
        ra = np.abs(u) @ ha
        rb = np.abs(RB.T @ u) @ hb
        best = min(best, ra + rb - abs(u @ d))
    return best


def test_axis_aligned_boxes_exact():
    rng = np.random.default_rng(1)
    for k in range(300):
        ha, hb = rng.uniform(0.1, 1.0, 3), rng.uniform(0.1, 1.0, 3)
        A, B = Box(*(2 * ha)), Box(*(2 * hb))
        d = (ha + hb) * rng.uniform(-0.999, 0.999, 3)
        xa = rng.normal(size=3) * 10
        pen = P.penetration(A, xa, ID, B, xa + d, ID)
        gaps = ha + hb - np.abs(d)
        k_min = int(np.argmin(gaps))
        L = np.linalg.norm(ha) + np.linalg.norm(hb)
        assert pen.depth == pytest.approx(gaps[k_min], abs=1e-12 * L + 1e-15 * 10 * np.abs(xa).max())
        n_exact = np.zeros(3)
        n_exact[k_min] = -np.sign(d[k_min])          # from B to A
        np.testing.assert_allclose(pen.normal, n_exact, atol=1e-15)


def test_rotated_boxes_exact():
    rng = np.random.default_rng(2)
    for k in range(300):
        ha, hb = rng.uniform(0.1, 1.0, 3), rng.uniform(0.1, 1.0, 3)
        theta = rng.uniform(-np.pi, np.pi)
        u = rng.normal(size=3)
        u /= np.linalg.norm(u)
        lo, hi = 0.0, np.linalg.norm(ha) + np.linalg.norm(hb)
        d = u * rng.uniform(0.2, 1.0) * hi
        exact = box_depth_z_rotated(ha, hb, theta, d)
        if exact <= 1e-6:
            continue
        A, B = Box(*(2 * ha)), Box(*(2 * hb))
        qb = qaxis([0, 0, 1], theta)
        pen = P.penetration(A, np.zeros(3), ID, B, d, qb)
        assert pen.depth == pytest.approx(exact, abs=1e-12 * hi)
        # the normal is certified: A moved by depth along it touches B
        assert h_diff(A, np.zeros(3), ID, B, d, qb, -pen.normal) == pytest.approx(pen.depth, abs=1e-12 * hi)
        # the same pair rotated rigidly as a whole: the same depth, the normal rotated
        q = rquat(rng)
        R = G.rotation(q)
        from dem.shapes._support import rotation_matrix  # noqa: F401  (G.rotation uses it)
        qa2 = q
        qb2 = _qmul(q, qb)
        pen2 = P.penetration(A, np.ones(3), qa2, B, np.ones(3) + R @ d, qb2)
        assert pen2.depth == pytest.approx(exact, abs=1e-12 * hi)
        np.testing.assert_allclose(pen2.normal, R @ pen.normal, atol=1e-9)


def _qmul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2])


def test_edge_edge_boxes_exact():
    """Two unit cubes crossed edge on edge: A rotated 45 deg about x (edge along x down), B 45 deg about y
    (edge along y up): the depth is the imposed overlap along z, on an edge-edge axis, one point."""
    c = cube(1.0)
    r2 = np.sqrt(0.5)
    for ov in (1e-6, 1e-3, 0.05):
        xa = np.array([0.0, 0.0, 2 * r2 - ov])
        qa, qb = qaxis([1, 0, 0], np.pi / 4), qaxis([0, 1, 0], np.pi / 4)
        res = P.contact(c, xa, qa, c, np.zeros(3), qb)
        assert res.depth == pytest.approx(ov, abs=1e-14)
        np.testing.assert_allclose(res.normal, [0, 0, 1], atol=1e-14)
        assert res.axis == P.AXIS_EDGE and res.type == P.PC_EDGE_EDGE and len(res.points) == 1
        np.testing.assert_allclose(res.points[0], [0, 0, r2 - ov / 2], atol=1e-14)


# ---------------------------------------------------------------- depth: random sharp polyhedra vs Coal and EPA
def random_polytope(rng, k):
    if k % 5 == 0:
        return Box(*rng.uniform(0.2, 1.5, 3))
    if k % 5 == 1:
        return [pinacoid(1.0, 0.8, 0.6), tetrahedron(1.0), cube(0.8)][rng.integers(3)]
    return Polyhedron(rng.normal(size=(rng.integers(4, 30), 3)) * rng.uniform(0.3, 1.0, 3))


def place_overlapping(rng, A, B, overlap):
    xa, qa, qb = rng.normal(size=3), rquat(rng), rquat(rng)
    u = rng.normal(size=3)
    u /= np.linalg.norm(u)
    lo, hi = 0.0, A.bounding_radius + B.bounding_radius
    for _ in range(42):
        m = 0.5 * (lo + hi)
        if G.distance(A, xa, qa, B, xa + u * m, qb)[0] > 0:
            hi = m
        else:
            lo = m
    return xa, qa, xa + u * (hi - overlap), qb


def coal_convex(coal, s):
    V, F = s.mesh()
    pts = coal.StdVec_Vec3s()
    for p in V:
        pts.append(np.asarray(p, float))
    tris = coal.StdVec_Triangle()
    for f in F:
        tris.append(coal.Triangle(int(f[0]), int(f[1]), int(f[2])))
    return coal.Convex(pts, tris)


def coal_request(coal):
    req = coal.DistanceRequest()
    req.gjk_variant = coal.GJKVariant.NesterovAcceleration
    req.gjk_convergence_criterion_type = coal.GJKConvergenceCriterionType.Absolute
    req.gjk_tolerance = 1e-11
    req.gjk_max_iterations = 2000
    req.epa_tolerance = 1e-10
    req.epa_max_iterations = 500
    return req


def test_depth_against_coal_and_epa_2000_pairs():
    coal = pytest.importorskip("coal")
    rng = np.random.default_rng(15)
    pool = [random_polytope(rng, k) for k in range(60)]
    geoms = [coal_convex(coal, s) for s in pool]
    req = coal_request(coal)
    worst_coal = worst_epa = worst_cert = worst_angle = 0.0
    axes = {P.AXIS_FACE_A: 0, P.AXIS_FACE_B: 0, P.AXIS_EDGE: 0}
    for k in range(2000):
        i, j = rng.integers(len(pool), size=2)
        A, B = pool[i], pool[j]
        ov = rng.uniform(0.001, 0.1) * min(A.inradius, B.inradius)
        xa, qa, xb, qb = place_overlapping(rng, A, B, ov)
        pen = P.penetration(A, xa, qa, B, xb, qb)
        assert pen.depth > 0
        axes[pen.axis] += 1
        dc = coal.distance(geoms[i], coal.Transform3s(G.rotation(qa), xa), geoms[j],
                           coal.Transform3s(G.rotation(qb), xb), req, coal.DistanceResult())
        d, pa, pb = G.distance(A, xa, qa, B, xb, qb)
        worst_coal = max(worst_coal, abs(pen.depth + dc) / pen.depth)
        worst_epa = max(worst_epa, abs(pen.depth + d) / pen.depth)
        L = A.bounding_radius + B.bounding_radius
        worst_cert = max(worst_cert, abs(h_diff(A, xa, qa, B, xb, qb, -pen.normal) - pen.depth) / L)
        m = (pa - pb) / np.linalg.norm(pa - pb)
        worst_angle = max(worst_angle, np.linalg.norm(np.cross(m, pen.normal)))
        # swapping the bodies: the opposite normal, the same depth
        sw = P.penetration(B, xb, qb, A, xa, qa)
        assert sw.depth == pytest.approx(pen.depth, rel=1e-12, abs=1e-14 * L)
        np.testing.assert_allclose(sw.normal, -pen.normal, atol=1e-9)
    print("worst relative depth error vs coal %.2e, vs EPA %.2e; certificate %.2e L; normal angle vs EPA "
          "%.2e; axes %s" % (worst_coal, worst_epa, worst_cert, worst_angle, axes))
    assert worst_coal <= 1e-9 and worst_epa <= 1e-9
    assert worst_cert <= 1e-12
    assert worst_angle <= 1e-6
    assert min(axes.values()) > 100          # faces of A, of B and edge pairs all exercised


def test_separated_pairs_report_no_overlap():
    rng = np.random.default_rng(4)
    for k in range(200):
        A, B = random_polytope(rng, k), random_polytope(rng, k + 2)
        xa, qa, xb, qb = place_overlapping(rng, A, B, -rng.uniform(1e-6, 0.1))     # apart
        assert P.penetration(A, xa, qa, B, xb, qb).depth <= 0
        assert P.contact(A, xa, qa, B, xb, qb) is None


# ---------------------------------------------------------------- contact points
def test_cube_on_cube_face_face_corners():
    c = cube(1.0)
    for ov in (1e-8, 1e-3, 0.05):
        res = P.contact(c, [0, 0, 1 - ov], ID, c, [0, 0, 0], ID)
        assert res.type == P.PC_FACE_FACE and len(res.points) == 4
        assert res.depth == pytest.approx(ov, abs=1e-15)
        np.testing.assert_allclose(res.normal, [0, 0, 1], atol=0)
        pts = sorted(map(tuple, np.round(res.points, 12)))
        assert pts == sorted((sx * 0.5, sy * 0.5, round(0.5 - ov / 2, 12)) for sx in (-1, 1) for sy in (-1, 1))
        assert res.nfa == res.nfb == 4
    # offset: the clipped rectangle [-0.2, 0.5] x [-0.3, 0.5]
    res = P.contact(c, [0.3, 0.2, 0.95], ID, c, [0, 0, 0], ID)
    assert res.type == P.PC_FACE_FACE and len(res.points) == 4
    got = sorted(map(tuple, np.round(res.points, 12)))
    assert got == sorted((x, y, 0.475) for x in (-0.2, 0.5) for y in (-0.3, 0.5))
    # a smaller cube on a larger one, rotated about the normal: its own 4 corners (inside the big face)
    big, small = cube(2.0), cube(0.5)
    q = qaxis([0, 0, 1], 0.3)
    res = P.contact(small, [0.1, -0.2, 1.25 - 1e-4], q, big, [0, 0, 0], ID)
    assert res.type == P.PC_FACE_FACE and len(res.points) == 4
    corners = world_vertices(small, [0.1, -0.2, 1.25 - 1e-4], q)
    bottom = corners[corners[:, 2] < 1.1]
    for p in res.points:
        assert np.min(np.linalg.norm(bottom[:, :2] - p[:2], axis=1)) < 1e-12
        assert p[2] == pytest.approx(1.0 - 0.5e-4, abs=1e-12)


def test_cube_edge_on_face_two_points():
    c = cube(1.0)
    r2 = np.sqrt(0.5)
    q = qaxis([1, 0, 0], np.pi / 4)            # edge along x down
    res = P.contact(c, [0.2, 0, 0.5 + r2 - 0.01], q, c, [0, 0, 0], ID)
    assert res.type == P.PC_EDGE_FACE and len(res.points) == 2
    assert res.depth == pytest.approx(0.01, abs=1e-14)
    np.testing.assert_allclose(res.points[np.argsort(res.points[:, 0])], [[-0.3, 0, 0.495], [0.5, 0, 0.495]],
                               atol=1e-14)             # (ordered by plane coordinates, here -x first)


def test_cube_vertex_down_one_point():
    c = cube(1.0)
    # the body diagonal (1, 1, 1) turned onto -z: one corner down
    u = np.array([1.0, 1.0, 1.0]) / np.sqrt(3)
    axis = np.cross(u, [0, 0, -1.0])
    q = qaxis(axis, np.arccos(-u[2]))
    h = np.sqrt(3) / 2
    res = P.contact(c, [0.1, 0.05, 0.5 + h - 0.02], q, c, [0, 0, 0], ID)
    assert res.type == P.PC_VERTEX_FACE and len(res.points) == 1
    assert res.depth == pytest.approx(0.02, abs=1e-13)
    np.testing.assert_allclose(res.points[0], [0.1, 0.05, 0.49], atol=1e-13)


def test_points_on_random_pairs_lie_in_both_bodies_and_are_deterministic():
    """Every point lies on the contact plane and, moved by -+depth/2 along the normal, inside both bodies
    (within round-off): it is in the overlap region's shadow. Repeated calls give the same bits; the counts
    match the types (1 / 1 / 2 / >= 3, <= MAXP)."""
    rng = np.random.default_rng(5)
    census = {}
    for k in range(400):
        A, B = random_polytope(rng, k), random_polytope(rng, k + 1)
        ov = rng.uniform(0.001, 0.1) * min(A.inradius, B.inradius)
        xa, qa, xb, qb = place_overlapping(rng, A, B, ov)
        res = P.contact(A, xa, qa, B, xb, qb, ftol=1e-3 * (A.bounding_radius + B.bounding_radius))
        again = P.contact(A, xa, qa, B, xb, qb, ftol=1e-3 * (A.bounding_radius + B.bounding_radius))
        assert res.points.tobytes() == again.points.tobytes() and res.depth == again.depth
        assert res.normal.tobytes() == again.normal.tobytes() and res.type == again.type
        n = len(res.points)
        census[res.type] = census.get(res.type, 0) + 1
        assert {P.PC_VERTEX_FACE: n == 1, P.PC_EDGE_EDGE: n == 1, P.PC_EDGE_FACE: n == 2,
                P.PC_FACE_FACE: 3 <= n <= P.MAXP}[res.type]
        L = A.bounding_radius + B.bounding_radius
        for p in res.points:
            for s, x, q, sign in ((A, xa, qa, -1), (B, xb, qb, +1)):
                # the point moved onto the body's side of the plane by the half overlap plus the tolerance
                R = G.rotation(q)
                pb = R.T @ (p + sign * 0.5 * res.depth * res.normal - x)
                t = s.topology
                assert np.max(t.face_normals @ pb - t.face_offsets) <= 1e-3 * L + 1e-12 * L
    assert census.get(P.PC_FACE_FACE, 0) + census.get(P.PC_EDGE_FACE, 0) > 0
    assert census.get(P.PC_VERTEX_FACE, 0) > 50 and census.get(P.PC_EDGE_EDGE, 0) > 50


def test_swapped_contact_mirrors():
    c = cube(1.0)
    res = P.contact(c, [0.3, 0.2, 0.95], ID, c, [0, 0, 0], ID)
    sw = P.contact(c, [0, 0, 0], ID, c, [0.3, 0.2, 0.95], ID)
    assert sw.depth == res.depth and sw.type == res.type
    np.testing.assert_array_equal(sw.normal, -res.normal)
    assert sorted(map(tuple, np.round(sw.points, 13))) == sorted(map(tuple, np.round(res.points, 13)))


def test_hull2_degenerate():
    h = _polytope._hull2_py
    assert len(h([[0, 0], [0, 0], [0, 1e-14]])) == 1               # one point, repeated
    assert len(h([[0, 0], [1, 0], [2, 0], [0.5, 1e-14]])) == 2      # collinear: the two ends
    np.testing.assert_array_equal(h([[1, 1], [0, 0], [1, 0], [0, 1], [0.5, 0.5]]),
                                  [[0, 0], [1, 0], [1, 1], [0, 1]])


def test_box_features_match_general_loop():
    """A box's contacting feature comes from its corner bits (_box_feature, no vertex loop, no hull); the
    general vertex loop and hull are the reference. Random overlapping pairs (mostly vertex/face and
    edge/edge), and resting ones (face on face, tilted by 0-1e-6 rad: face/face within the feature
    tolerance, edge/face beyond it; offset sideways so that the faces overlap partly): the same type, the
    same feature sizes and the same points (the same corners projected by the same sums, clipped alike:
    round-off, 1e-12 L)."""
    rng = np.random.default_rng(22)
    types = set()
    for k in range(1200):
        A, B = Box(*rng.uniform(0.2, 1.5, 3)), Box(*rng.uniform(0.2, 1.5, 3))
        L = A.bounding_radius + B.bounding_radius
        if k < 600:
            ov = rng.uniform(0.001, 0.1) * min(A.inradius, B.inradius)
            xa, qa, xb, qb = place_overlapping(rng, A, B, ov)
        else:                                   # B's top face under A's bottom face
            qa = rquat(rng)
            qb = qa + 0.5 * rng.choice([0.0, 1e-9, 1e-7, 1e-6]) * rng.uniform() * rng.normal(size=4)
            qb /= np.linalg.norm(qb)            # turned from qa by about the tilt
            R = G.rotation(qa)
            ha, hb = A.size / 2, B.size / 2
            side = rng.uniform(-0.5, 0.5, 2) * (ha[:2] + hb[:2])
            xa = rng.normal(size=3)
            gap = ha[2] + hb[2] - 1e-3 * min(A.inradius, B.inradius)
            xb = xa - R @ np.array([side[0], side[1], gap])
        fast = P.contact(A, xa, qa, B, xb, qb)
        ref = P.contact(A, xa, qa, B, xb, qb, box_path=False)
        assert (fast is None) == (ref is None)
        if fast is None:
            continue
        assert (fast.type, fast.nfa, fast.nfb, len(fast.points)) == (ref.type, ref.nfa, ref.nfb, len(ref.points))
        np.testing.assert_allclose(fast.points, ref.points, rtol=0, atol=1e-12 * L)
        types.add(fast.type)
    assert types == {1, 2, 3, 4}                # every contact type was met


def test_box_path_matches_general_loop():
    """Two boxes take the closed-form 15-axis path (_sat_box); the general loop (vertex supports, Gauss-map
    arcs) is the reference: 2000 random overlapping pairs (aspect up to 7.5, overlaps 0.1-10 % of the
    smaller inradius) and 500 near-contact ones. The two evaluate the same candidate values by different
    sums, so depths agree to round-off (1e-12 L, as the module's tolerances), normals to 1e-12, and the axis
    and features chosen are the same (ties are resolved by the same rules, within 1e-12 L); the overlap
    flag agrees on every near-contact pair."""
    rng = np.random.default_rng(21)
    same_axis = 0
    for k in range(2000):
        A, B = Box(*rng.uniform(0.2, 1.5, 3)), Box(*rng.uniform(0.2, 1.5, 3))
        ov = rng.uniform(0.001, 0.1) * min(A.inradius, B.inradius)
        xa, qa, xb, qb = place_overlapping(rng, A, B, ov)
        fast = P.penetration(A, xa, qa, B, xb, qb)
        ref = P.penetration(A, xa, qa, B, xb, qb, box_path=False)
        L = A.bounding_radius + B.bounding_radius
        assert fast.depth == pytest.approx(ref.depth, abs=1e-12 * L)
        np.testing.assert_allclose(fast.normal, ref.normal, atol=1e-12)
        same_axis += (fast.axis, fast.fa, fast.fb) == (ref.axis, ref.fa, ref.fb)
    assert same_axis == 2000
    for k in range(500):
        A, B = Box(*rng.uniform(0.2, 1.5, 3)), Box(*rng.uniform(0.2, 1.5, 3))
        xa, qa, xb, qb = place_overlapping(rng, A, B, rng.uniform(-1e-3, 1e-3))
        fast = P.penetration(A, xa, qa, B, xb, qb)
        ref = P.penetration(A, xa, qa, B, xb, qb, box_path=False)
        assert (fast.depth > 0) == (ref.depth > 0)
