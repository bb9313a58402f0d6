"""Shapes: mass properties against closed forms, recentring/alignment of polyhedra, cores, supports, table.

Tolerances: closed-form values are compared at 1e-12 relative (a few ulps of float64 arithmetic on O(1)
numbers); mesh (divergence theorem) integrals of curved shapes at the stated mesh-resolution error
(O(h^2) chord error of a 400 x 200 UV mesh: ~1e-4 relative), polyhedra exactly (1e-12).
"""
import numpy as np
import pytest
from scipy.special import beta
from scipy.spatial.transform import Rotation

from dem.shapes import (Box, Cone, Cylinder, Ellipsoid, Polyhedron, ShapeTable, Sphere, Superquadric, cube,
                        mesh_volume, pinacoid, pinacoid_volume, tetrahedron)
from dem.shapes.polyhedron import mesh_mass_properties, inertia_from_second_moment

RTOL = 1e-12      # closed forms evaluated in float64
MESH_RTOL = 2e-4  # 400-segment UV meshes of curved surfaces: chord error ~ (pi/200)^2 / 8 ~ 3e-5 of R


def all_shapes():
    rng = np.random.default_rng(3)
    return [Sphere(0.7), Box(0.4, 1.0, 1.7), cube(1.3), Cylinder(0.5, 1.6), Cone(0.6, 1.5),
            Ellipsoid(1.0, 0.6, 0.35), Superquadric(1.0, 0.7, 0.5, 4.0, 3.0), Superquadric(0.5, 0.5, 1.0, 2.0, 8.0),
            tetrahedron(1.2), pinacoid(1.0, 1.0, 1.0), Polyhedron(rng.normal(size=(25, 3)))]


def mesh_props(shape, res=400):
    V, F = shape.mesh(res)
    vol, com, M = mesh_mass_properties(V, F)
    return vol, com, inertia_from_second_moment(M - vol * np.outer(com, com))


# ---------------------------------------------------------------- closed forms
def test_sphere():
    r = 0.7
    s = Sphere(r)
    V = 4 / 3 * np.pi * r ** 3
    assert s.volume == pytest.approx(V, rel=RTOL)
    np.testing.assert_allclose(s.principal_moments, 0.4 * V * r * r, rtol=RTOL)
    assert s.bounding_radius == r and s.inradius == r


def test_box_and_cube():
    a, b, c = 0.4, 1.0, 1.7
    s = Box(a, b, c)
    V = a * b * c
    assert s.volume == pytest.approx(V, rel=RTOL)
    np.testing.assert_allclose(s.principal_moments, V / 12 * np.array([b * b + c * c, a * a + c * c, a * a + b * b]),
                               rtol=RTOL)
    assert s.bounding_radius == pytest.approx(0.5 * np.sqrt(a * a + b * b + c * c), rel=RTOL)
    k = cube(2.0)
    assert k.volume == pytest.approx(8.0, rel=RTOL) and k.name == "cube"
    np.testing.assert_allclose(k.principal_moments, 8.0 * 8.0 / 12, rtol=RTOL)


def test_cylinder():
    r, L = 0.5, 1.6
    s = Cylinder(r, L)
    V = np.pi * r * r * L
    assert s.volume == pytest.approx(V, rel=RTOL)
    np.testing.assert_allclose(s.principal_moments, [V * (3 * r * r + L * L) / 12] * 2 + [V * r * r / 2], rtol=RTOL)


def test_cone_centre_of_mass_and_inertia():
    r, h = 0.6, 1.5
    s = Cone(r, h)
    V = np.pi * r * r * h / 3
    assert s.volume == pytest.approx(V, rel=RTOL)
    # textbook: about the apex I_perp = 3/5 m h^2 + 3/20 m r^2, centre of mass 3h/4 below the apex
    i_apex = V * (0.6 * h * h + 0.15 * r * r)
    np.testing.assert_allclose(s.principal_moments[:2], i_apex - V * (0.75 * h) ** 2, rtol=RTOL)
    assert s.principal_moments[2] == pytest.approx(0.3 * V * r * r, rel=RTOL)
    vol, com, I = mesh_props(s)            # independent check through the mesh integrator
    assert abs(com).max() < 1e-4 * h       # chord error of the 400-gon base
    np.testing.assert_allclose(np.diag(I), s.principal_moments, rtol=MESH_RTOL)


def test_ellipsoid():
    a, b, c = 1.0, 0.6, 0.35
    s = Ellipsoid(a, b, c)
    V = 4 / 3 * np.pi * a * b * c
    assert s.volume == pytest.approx(V, rel=RTOL)
    np.testing.assert_allclose(s.principal_moments, V / 5 * np.array([b * b + c * c, a * a + c * c, a * a + b * b]),
                               rtol=RTOL)
    assert s.max_crust == pytest.approx(c * c / a, rel=RTOL)


@pytest.mark.parametrize("n1,n2", [(2.0, 2.0), (4.0, 3.0), (3.0, 8.0), (10.0, 10.0)])
def test_superquadric(n1, n2):
    a, b, c = 1.0, 0.7, 0.5
    s = Superquadric(a, b, c, n1, n2)
    e1, e2 = 2 / n1, 2 / n2
    # Jaklic, Leonardis & Solina (2000), eq. for the volume of a superellipsoid with eps = 2 / n
    V = 2 * a * b * c * e1 * e2 * beta(e1 / 2 + 1, e1) * beta(e2 / 2, e2 / 2)
    assert s.volume == pytest.approx(V, rel=RTOL * 10)     # Gamma functions: a few 1e-13
    vol, com, I = mesh_props(s)
    assert vol == pytest.approx(s.volume, rel=MESH_RTOL)
    np.testing.assert_allclose(np.diag(I), s.principal_moments, rtol=MESH_RTOL)
    if n1 == n2 == 2.0:
        e = Ellipsoid(a, b, c)
        np.testing.assert_allclose(s.principal_moments, e.principal_moments, rtol=1e-12)
    # the bounding radius is the farthest mesh vertex (up to the mesh's sampling)
    Vm, _ = s.mesh(400)
    r = np.linalg.norm(Vm, axis=1).max()
    assert r <= s.bounding_radius * (1 + 1e-9) and r >= s.bounding_radius * (1 - 1e-4)


def test_superquadric_tends_to_box():
    s = Superquadric(0.5, 0.5, 0.5, 200.0, 200.0)
    assert s.volume == pytest.approx(1.0, rel=0.02)       # |x|^200 corners: ~1 % rounding
    with pytest.raises(ValueError):
        Superquadric(1, 1, 1, 1.5, 3.0)                     # not smooth: margin rule invalid


def test_tetrahedron():
    e = 1.2
    s = tetrahedron(e)
    V = e ** 3 / (6 * np.sqrt(2))
    assert s.volume == pytest.approx(V, rel=RTOL)
    np.testing.assert_allclose(s.principal_moments, V * e * e / 20, rtol=RTOL)   # isotropic
    np.testing.assert_allclose(s.rotation, np.eye(3), atol=1e-15)                 # degenerate: keep axes
    assert s.bounding_radius == pytest.approx(e * np.sqrt(6) / 4, rel=RTOL)


@pytest.mark.parametrize("L,G,E,alpha", [(1.0, 1.0, 1.0, 60.0), (2.0, 1.2, 0.7, 45.0), (1.5, 0.8, 1.0, 75.0)])
def test_pinacoid(L, G, E, alpha):
    s = pinacoid(L, G, E, alpha)
    assert s.volume == pytest.approx(pinacoid_volume(L, G, E, alpha), rel=RTOL)
    assert len(s.vertices) == 8
    nfaces = len(s._planes())
    assert nfaces == 8 and len(s.vertices) + nfaces - 2 == 14     # Euler: 14 edges
    np.testing.assert_allclose(s.centroid, 0, atol=1e-15)
    np.testing.assert_allclose(s.rotation, np.eye(3), atol=1e-12)   # already principal: axes kept


def test_pinacoid_table1():
    d = 1.0
    s = pinacoid(d / np.sqrt(2), d / np.sqrt(2), d / np.sqrt(2), 60.0)
    assert 2 * s.bounding_radius == pytest.approx(d, rel=RTOL)       # circumscribed sphere d_sph
    assert s.volume == pytest.approx(0.143 * d ** 3, abs=5e-4)       # Table 1 rounds to 3 digits


def test_polyhedron_off_centre_rotated():
    rng = np.random.default_rng(7)
    P = rng.normal(size=(30, 3)) * [1.0, 0.6, 0.3]
    ref = Polyhedron(P)
    Q = Rotation.random(random_state=11).as_matrix()
    t = np.array([3.0, -2.0, 5.0])
    moved = Polyhedron(P @ Q.T + t)
    assert moved.volume == pytest.approx(ref.volume, rel=RTOL)
    np.testing.assert_allclose(moved.centroid, Q @ ref.centroid + t, atol=1e-12)
    np.testing.assert_allclose(np.sort(moved.principal_moments), np.sort(ref.principal_moments), rtol=1e-10)
    # body frame: centred, diagonal inertia, and the stored transform maps it back onto the input
    vol, com, M = mesh_mass_properties(moved.vertices, moved.faces)
    np.testing.assert_allclose(com, 0, atol=1e-13)
    I = inertia_from_second_moment(M - vol * np.outer(com, com))
    assert abs(I - np.diag(np.diag(I))).max() < 1e-12 * abs(I).max()
    back = moved.centroid + moved.vertices @ moved.rotation.T
    hull_in = (P @ Q.T + t)[np.unique(np.r_[[np.argmin(np.linalg.norm(P @ Q.T + t - b, axis=1)) for b in back]])]
    np.testing.assert_allclose(np.sort(back, axis=0), np.sort(hull_in, axis=0), atol=1e-12)
    assert np.linalg.det(moved.rotation) == pytest.approx(1.0, abs=1e-12)


def test_box_as_polyhedron_rotated():
    a, b, c = 0.4, 1.0, 1.7
    corners = np.array([[x, y, z] for x in (0, a) for y in (0, b) for z in (0, c)])
    Q = Rotation.from_euler("xyz", [0.3, -1.1, 2.0]).as_matrix()
    p = Polyhedron(corners @ Q.T + [1.0, 2.0, 3.0])
    np.testing.assert_allclose(p.centroid, Q @ [a / 2, b / 2, c / 2] + [1.0, 2.0, 3.0], atol=1e-13)
    np.testing.assert_allclose(np.sort(p.principal_moments), np.sort(Box(a, b, c).principal_moments), rtol=1e-12)
    # body frame = principal frame: the vertices are the centred box, up to axis order and signs
    np.testing.assert_allclose(np.sort(abs(p.vertices).max(0)), np.sort([a / 2, b / 2, c / 2]), atol=1e-12)


def test_cube_polyhedron_keeps_axes():
    p = Polyhedron(np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float) + 5.0)
    np.testing.assert_allclose(p.rotation, np.eye(3), atol=1e-15)


# ---------------------------------------------------------------- meshes, scaling, files
@pytest.mark.parametrize("shape", all_shapes(), ids=lambda s: s.name)
def test_mesh_closed_outward(shape):
    V, F = shape.mesh(200)
    vol = mesh_volume(V, F)
    rtol = RTOL if shape.name in ("box", "cube", "tetrahedron", "pinacoid", "polyhedron") else 2e-3
    assert vol == pytest.approx(shape.volume, rel=rtol)     # positive: outward; equal: closed
    # every edge used twice (once each way): a closed 2-manifold
    e = np.r_[F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]
    key = set(map(tuple, e))
    assert all((b, a) in key for a, b in key)


@pytest.mark.parametrize("shape", all_shapes(), ids=lambda s: s.name)
def test_scaled(shape):
    f = 1.7
    s = shape.scaled(f)
    assert s.volume == pytest.approx(shape.volume * f ** 3, rel=1e-12)
    np.testing.assert_allclose(s.principal_moments, shape.principal_moments * f ** 5, rtol=1e-10)
    assert s.bounding_radius == pytest.approx(shape.bounding_radius * f, rel=1e-6)  # numeric for superquadrics
    assert s.crust == pytest.approx(shape.crust * f, rel=1e-12)
    assert s.kind == shape.kind and s.name == shape.name


def test_mesh_files(tmp_path):
    s = pinacoid(1.0, 0.8, 0.6)
    V, F = s.mesh()
    Vin = V @ Rotation.from_euler("z", 0.4).as_matrix().T + 2.0
    obj = tmp_path / "p.obj"
    obj.write_text("".join("v %.17g %.17g %.17g\n" % tuple(v) for v in Vin)
                   + "".join("f %d %d %d\n" % tuple(f + 1) for f in F))
    stl = tmp_path / "p.stl"
    lines = ["solid p"]
    for f in F:
        lines += ["facet normal 0 0 0", "outer loop"] + ["vertex %.17g %.17g %.17g" % tuple(Vin[i]) for i in f] + \
                 ["endloop", "endfacet"]
    stl.write_text("\n".join(lines + ["endsolid p"]))
    bstl = tmp_path / "b.stl"
    rec = np.zeros(len(F), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    rec["v"] = Vin[F]
    bstl.write_bytes(b"\0" * 80 + np.uint32(len(F)).tobytes() + rec.tobytes())
    for path, tol in ((obj, 1e-12), (stl, 1e-12), (bstl, 1e-6)):       # binary STL is float32
        p = Polyhedron.from_file(path)
        assert p.volume == pytest.approx(s.volume, rel=tol)
        np.testing.assert_allclose(p.principal_moments, s.principal_moments, rtol=10 * tol)
    with pytest.raises(ValueError):
        Polyhedron.from_file(tmp_path / "x.ply")


# ---------------------------------------------------------------- supports and cores
@pytest.mark.parametrize("shape", all_shapes(), ids=lambda s: s.name)
def test_support_is_farthest_surface_point(shape):
    """s(d) beats every mesh vertex (all on the surface) in direction d and is itself on the body."""
    rng = np.random.default_rng(1)
    D = rng.normal(size=(400, 3))
    S = shape.support(D)
    V, _ = shape.mesh(160)
    h = np.einsum("ij,ij->i", S, D)
    best = (D @ V.T).max(1)
    scale = shape.bounding_radius * np.linalg.norm(D, axis=1)
    assert np.all(h >= best - 1e-12 * scale)
    # and no farther than the finest mesh could show: within the chord error of a 160-segment mesh
    assert np.all(h <= best + 2e-3 * scale)
    np.testing.assert_allclose(shape.support(3.0 * D), S, atol=1e-14 * shape.bounding_radius)   # 0-homogeneous


@pytest.mark.parametrize("shape", all_shapes(), ids=lambda s: s.name)
def test_core_plus_crust_is_body(shape):
    """h_core(n) + crust = h_body(n) along face normals (sharp kinds) or all directions (smooth kinds)."""
    rng = np.random.default_rng(2)
    c = shape.crust
    assert 0 < c < shape.max_crust
    if shape.name in ("sphere", "ellipsoid", "superquadric"):
        D = rng.normal(size=(200, 3))
    elif shape.name in ("box", "cube"):
        D = np.r_[np.eye(3), -np.eye(3)]
    elif shape.name == "cylinder":
        t = rng.uniform(0, 2 * np.pi, 50)
        D = np.r_[np.c_[np.cos(t), np.sin(t), 0 * t], [[0, 0, 1], [0, 0, -1]]]
    elif shape.name == "cone":
        r, h = shape.radius, shape.height
        t = rng.uniform(0, 2 * np.pi, 50)
        D = np.r_[np.c_[h * np.cos(t), h * np.sin(t), np.full(50, r)], [[0, 0, -1]]]
    else:
        D = shape._planes()[:, :3]
    D = D / np.linalg.norm(D, axis=1)[:, None]
    hb = np.einsum("ij,ij->i", shape.support(D), D)
    hc = np.einsum("ij,ij->i", shape.support(D, core=True), D)
    np.testing.assert_allclose(hc + c, hb, atol=1e-12 * shape.bounding_radius)


def test_crust_limits():
    with pytest.raises(ValueError):
        Box(1, 1, 1, crust=0.5)
    with pytest.raises(ValueError):
        Ellipsoid(1.0, 0.5, 0.5, crust=0.3)     # above the smallest radius of curvature 0.25
    assert Sphere(1.0, crust=0.0).crust == 0.0
    s = cube(1.0).with_crust(0.1)
    np.testing.assert_allclose(s.core_params[:3], 0.4)


def test_polyhedron_core_non_simple_vertices():
    s = pinacoid(1.0, 1.0, 1.0, crust=0.02)      # the equator corners join 4 faces
    assert len(s.core_vertices) >= 8
    p = Polyhedron(s.core_vertices)
    assert p.volume < s.volume


def test_shape_table():
    shapes = all_shapes()
    t = ShapeTable(shapes)
    t2 = ShapeTable(shapes)
    for k, v in t.arrays().items():
        assert v.flags.c_contiguous
        assert np.array_equal(v, getattr(t2, k))      # bitwise identical on every rank
    for i, s in enumerate(shapes):
        assert t.kind[i] == s.kind and np.array_equal(t.params[i], s.params)
        np.testing.assert_array_equal(t.verts[t.voff[i]:t.voff[i] + t.nv[i]], np.asarray(s.vertices).reshape(-1, 3))
        np.testing.assert_array_equal(t.verts[t.core_voff[i]:t.core_voff[i] + t.core_nv[i]],
                                      np.asarray(s.core_vertices).reshape(-1, 3))
    assert t.kind.dtype == np.int32 and t.voff.dtype == np.int64 and t.params.dtype == np.float64
