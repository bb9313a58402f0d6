"""Triangle meshes for mesh walls (dem_walls.mesh): STL (ASCII, binary) and OBJ reading, welding into an
indexed mesh, STL writing, the error messages, and the meshes of tools/make_meshes.py (inputs/meshes/).

Tolerances: ASCII STL stores coordinates with repr, which reads back bit for bit, so its round trip is
exact; binary STL stores float32, so it reads back as the float32 rounding of each coordinate, exactly
(compared with astype(float32), no tolerance). Geometric checks on meshes read from binary files allow
1e-6 m: float32 rounds a coordinate below 0.2 m by at most 2^-24 * 0.25 = 1.5e-8 m, and the polygon's
vertices lie exactly on the circle in float64 (cos, sin to 1 ulp), so 1e-6 is far above rounding and far
below any geometric error worth catching (the smallest dimension checked is a 6 mm outlet radius)."""
import importlib.util
import math
import struct
import sys
from pathlib import Path

import numpy as np
import pytest

from dem.errors import DemError
from dem_walls.mesh import Mesh, load, read_triangles, rotation_about, weld

ROOT = Path(__file__).resolve().parents[1]
spec = importlib.util.spec_from_file_location("make_meshes", ROOT / "tools" / "make_meshes.py")
make_meshes = importlib.util.module_from_spec(spec)
PATH_BEFORE = list(sys.path)
spec.loader.exec_module(make_meshes)
PATH_AFTER = list(sys.path)

GEOMETRY_TOL = 1e-6     # m, on meshes read from float32 files (see the module docstring)


def test_make_meshes_leaves_sys_path_alone():
    """With dem installed the tool imports the installed plugins: putting the source tree's plugins/ first
    on sys.path made every later import of a plugin find sources without their compiled kernels."""
    assert PATH_AFTER == PATH_BEFORE


def cube_soup(size=1.0):
    """The 12 triangles (36 corners, not shared) of the cube [0, size]^3, normals outward."""
    return make_meshes.box((0.0, 0.0, 0.0), (size, size, size))


def signed_volume(mesh):
    """Volume enclosed by a closed mesh (divergence theorem): positive when the normals point outward."""
    v = mesh.vertices[mesh.triangles]
    return float(np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6.0)


def check_topology(mesh):
    """Array types and the consistency of edges with triangles, for any mesh."""
    for name, dtype in [("vertices", np.float64), ("triangles", np.int32), ("edges", np.int32),
                        ("normals", np.float64), ("edge_vertices", np.int32)]:
        a = getattr(mesh, name)
        assert a.dtype == dtype and a.flags.c_contiguous, name
    nt = len(mesh.triangles)
    assert mesh.edges.shape == (nt, 3) and mesh.normals.shape == (nt, 3)
    assert mesh.nedges == len(mesh.edge_vertices) == len(np.unique(mesh.edges))
    assert mesh.edges.min() == 0 and mesh.edges.max() == mesh.nedges - 1
    for k in range(3):
        ends = np.sort(np.stack([mesh.triangles[:, k], mesh.triangles[:, (k + 1) % 3]], axis=1), axis=1)
        assert np.array_equal(mesh.edge_vertices[mesh.edges[:, k]], ends)
    # unit normals, by the right-hand rule over v0 v1 v2
    assert np.allclose(np.linalg.norm(mesh.normals, axis=1), 1.0, rtol=0, atol=1e-12)
    v = mesh.vertices[mesh.triangles]
    assert (np.einsum("ij,ij->i", np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), mesh.normals) > 0).all()


# ----------------------------------------------------------------------------------------- file formats

def test_stl_round_trip(tmp_path):
    rng = np.random.default_rng(1)
    mesh = weld(rng.normal(size=(50, 3, 3)) * [0.1, 2.0, 30.0])
    corners = mesh.vertices[mesh.triangles]
    mesh.write_stl(tmp_path / "a.stl", binary=False)
    assert (tmp_path / "a.stl").read_bytes().startswith(b"solid")
    assert np.array_equal(read_triangles(tmp_path / "a.stl"), corners)       # repr: exact
    mesh.write_stl(tmp_path / "b.stl", binary=True)
    assert (tmp_path / "b.stl").stat().st_size == 84 + 50 * len(mesh.triangles)
    back = read_triangles(tmp_path / "b.stl")
    assert back.dtype == np.float64 and back.shape == (50, 3, 3) and back.flags.c_contiguous
    assert np.array_equal(back, corners.astype(np.float32).astype(np.float64))  # float32, exactly
    # the normals stored in the binary file are the mesh's
    record = np.dtype([("normal", "<f4", 3), ("v", "<f4", 9), ("attr", "<u2")])
    records = np.frombuffer((tmp_path / "b.stl").read_bytes(), dtype=record, offset=84)
    assert np.allclose(records["normal"], mesh.normals, rtol=0, atol=1e-7)     # float32 of unit vectors


def test_binary_stl_whose_header_starts_with_solid(tmp_path):
    corners = cube_soup().astype(np.float32)
    body = b"".join(struct.pack("<3f", 0, 0, 0) + c.tobytes() + b"\0\0" for c in corners)
    path = tmp_path / "solid_header.stl"
    path.write_bytes(b"solid cube exported by some CAD program".ljust(80, b" ") +
                     struct.pack("<I", len(corners)) + body)
    tris = read_triangles(path)
    assert np.array_equal(tris, corners.astype(np.float64))
    mesh = weld(tris)
    assert len(mesh.vertices) == 8 and mesh.boundary_edges() == 0


def test_ascii_stl_by_hand(tmp_path):
    """A hand-written ASCII STL: a byte-order mark, upper case keywords, indentation, two solids, facet
    normals ignored."""
    path = tmp_path / "hand.STL"
    path.write_text("""\ufeffsolid first
 FACET NORMAL 0 0 -1
  OUTER LOOP
   VERTEX 0 0 0
   VERTEX 1 0 0
   VERTEX 0 1 0
  ENDLOOP
 ENDFACET
endsolid first
solid second
facet normal 0 0 0
outer loop
vertex 0 0 1e-1
vertex 1.5E0 0 0.1
vertex 0 1 .1
endloop
endfacet
endsolid
""", encoding="utf-8")
    tris = read_triangles(path)
    assert np.array_equal(tris, [[[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 0, 0.1], [1.5, 0, 0.1], [0, 1, 0.1]]])


def test_obj_faces(tmp_path):
    """Quads and a pentagon (fan-triangulated), negative indices, the i/j, i/j/k and i//k forms,
    comments, a continued line and the lines to ignore; extension in capitals."""
    path = tmp_path / "shape.OBJ"
    path.write_text("""# a unit square split in two quads, then a pentagon
mtllib shape.mtl
o square
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vn 0 0 1
usemtl steel
s off
f 1/1/1 2/1/1 3/1/1 4/1/1   # a quad: v/vt/vn
g pentagon
v 0 0 1
v 1 0 1
v 1.5 0.5 1
v 1 1 1
v 0 1 1
f -5//1 -4//1 -3//1 \\
  -2//1 -1//1
f 1/1 2/1 6
l 1 2
""")
    tris = read_triangles(path)
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1.5, 0.5, 1],
                  [1, 1, 1], [0, 1, 1]], dtype=float)
    expected = v[[[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7], [4, 7, 8], [0, 1, 5]]]
    assert np.array_equal(tris, expected)
    mesh = weld(tris)
    assert len(mesh.vertices) == 9 and mesh.dropped == 0
    assert mesh.area() == pytest.approx(1.0 + 1.25 + 0.5, rel=1e-14)
    check_topology(mesh)


# --------------------------------------------------------------------------------------------- welding

def test_weld_cube():
    soup = cube_soup()
    assert soup.shape == (12, 3, 3)
    mesh = weld(soup)
    check_topology(mesh)
    assert len(mesh.vertices) == 8 and len(mesh.triangles) == 12
    assert mesh.nedges == 18 and mesh.boundary_edges() == 0 and mesh.dropped == 0
    assert np.bincount(mesh.edges.ravel()).tolist() == [2] * 18             # every edge between 2 faces
    assert mesh.area() == pytest.approx(6.0, rel=1e-15)
    centroid = mesh.vertices[mesh.triangles].mean(axis=1)
    assert (np.einsum("ij,ij->i", mesh.normals, centroid - 0.5) > 0).all()  # outward
    assert signed_volume(mesh) == pytest.approx(1.0, rel=1e-15)
    lo, hi = mesh.bounds()
    assert lo.tolist() == [0, 0, 0] and hi.tolist() == [1, 1, 1]
    assert np.array_equal(mesh.vertices[mesh.triangles], soup)              # coordinates kept
    direct = Mesh(mesh.vertices, mesh.triangles)                           # from an indexed mesh
    assert np.array_equal(direct.edges, mesh.edges) and np.array_equal(direct.normals, mesh.normals)


@pytest.mark.parametrize("factor, nv", [(0.1, 8), (10.0, 9)])
def test_weld_tolerance(factor, nv):
    """A corner moved by 0.1 tol (of the bounding-box diagonal) still welds, one moved by 10 tol does not;
    the move goes along a diagonal not parallel to a coordinate axis, so that no coordinate rounding grid
    would do. The moved corner keeps the first corner's coordinates when it welds."""
    tol = 1e-6
    soup = cube_soup()
    eps = tol * math.sqrt(3.0)
    soup[7, 1] += factor * eps * np.array([1.0, -2.0, 2.0]) / 3.0     # a unit vector
    mesh = weld(soup, tol=tol)
    assert len(mesh.vertices) == nv
    assert mesh.boundary_edges() == (0 if nv == 8 else 4)      # the moved corner's 2 edges, both sides
    # welded vertices sit at one of the corners that merged (at most 0.1 eps off the exact cube)
    corners = np.unique(cube_soup().reshape(-1, 3), axis=0)
    off = np.linalg.norm(mesh.vertices[:, None] - corners[None], axis=2).min(axis=1)
    assert (off <= min(factor, 1.0) * eps * (1 + 1e-9)).all() if nv == 8 else off.max() > 9 * eps


def test_weld_across_grid_boundary():
    """Two copies of a corner 0.02 eps apart that straddle the boundary of a rounding grid of spacing eps
    (at eps / 2): rounding would split them, the k-d tree does not."""
    tol = 1e-9
    eps = tol * math.sqrt(3.0)
    delta = 0.01 * eps
    soup = cube_soup() + (0.5 * eps - delta)
    first = np.flatnonzero(np.all(soup.reshape(-1, 3) == soup[0, 0], axis=1))
    soup.reshape(-1, 3)[first[1]] += [2 * delta, 0.0, 0.0]
    assert np.round(soup[0, 0, 0] / eps) != np.round(soup.reshape(-1, 3)[first[1], 0] / eps)
    mesh = weld(soup, tol=tol)
    assert len(mesh.vertices) == 8 and mesh.boundary_edges() == 0


def test_weld_drops_degenerate_triangles():
    soup = cube_soup()
    a, b, c = np.eye(3)
    tol = 1e-9
    eps = tol * math.sqrt(3.0)
    bad = np.array([[a, a, b],                                   # two equal corners
                    [a, 0.5 * (a + b), b],                       # collinear
                    [a, b, 0.5 * (a + b) + 0.1 * eps * c],       # height 0.1 eps: flat at this tol
                    [a, b + 0.1 * eps * c, b]])                  # two corners that weld
    mesh = weld(np.concatenate([soup, bad]), tol=tol)
    assert mesh.dropped == 4 and len(mesh.triangles) == 12 and len(mesh.vertices) == 8
    assert mesh.boundary_edges() == 0
    # a thin but genuine triangle (height 10 eps) is kept
    kept = weld(np.concatenate([soup, [[a, b, 0.5 * (a + b) + 10 * eps * c]]]), tol=tol)
    assert kept.dropped == 0 and len(kept.triangles) == 13
    with pytest.raises(DemError, match="all 2 are degenerate"):
        weld(bad[:2])


def test_transformed_and_rotation():
    mesh = weld(cube_soup())
    r = rotation_about((1.0, 1.0, 0.0), 0.7)
    assert np.allclose(r.T @ r, np.eye(3), rtol=0, atol=1e-15) and np.linalg.det(r) == pytest.approx(1.0)
    assert np.allclose(rotation_about((0, 0, 2), math.pi / 2) @ [1, 0, 0], [0, 1, 0], rtol=0, atol=1e-15)
    moved = mesh.transformed(scale=2.0, offset=(1.0, 2.0, 3.0), rotation=r)
    assert moved.triangles is mesh.triangles and moved.edges is mesh.edges
    assert np.allclose(moved.vertices, 2.0 * mesh.vertices @ r.T + [1, 2, 3], rtol=0, atol=1e-15)
    assert np.allclose(moved.normals, mesh.normals @ r.T, rtol=0, atol=1e-15)
    check_topology(moved)      # rotated normals still follow the winding
    assert moved.area() == pytest.approx(24.0, rel=1e-14)
    assert np.array_equal(mesh.transformed(scale=1e-3).bounds()[1], [1e-3] * 3)
    with pytest.raises(DemError, match="rotation matrix"):
        mesh.transformed(rotation=np.diag([1.0, 1.0, -1.0]))   # a reflection would turn faces inside out
    with pytest.raises(DemError, match="positive"):
        mesh.transformed(scale=-1.0)


# ---------------------------------------------------------------------------------------------- errors

def test_errors(tmp_path):
    with pytest.raises(DemError, match=r"mesh file '.*nowhere\.stl': no such file"):
        read_triangles(tmp_path / "nowhere.stl")
    obj = tmp_path / "bad.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 3\nf 1 2 4\n")
    with pytest.raises(DemError, match=r"bad\.obj', line 6: vertex index 4 out of range \(the file has 3"):
        read_triangles(obj)
    obj.write_text("v 0 0 0\nv 1 0 0\nf 1 2 -3\n")
    with pytest.raises(DemError, match=r"line 3: vertex index -3 out of range"):
        read_triangles(obj)
    obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n")
    with pytest.raises(DemError, match=r"line 4: vertex index 0"):
        read_triangles(obj)
    obj.write_text("v 0 0 0\nv 1 0.x 0\n")
    with pytest.raises(DemError, match=r"line 2: bad number '0.x' in vertex"):
        read_triangles(obj)
    obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\n")
    with pytest.raises(DemError, match=r"bad\.obj': no triangles"):
        read_triangles(obj)
    # truncated binary STL, with and without a header starting with "solid"
    good = tmp_path / "good.stl"
    weld(cube_soup()).write_stl(good)
    data = good.read_bytes()
    for header in (b"", b"solid x"):
        cut = tmp_path / "cut.stl"
        cut.write_bytes(header + data[len(header):-30])
        with pytest.raises(DemError, match=r"cut\.stl': truncated binary STL \(its header announces 12 "
                                           r"triangles, 684 bytes, but the file has 654"):
            read_triangles(cut)
    stl = tmp_path / "bad.stl"
    stl.write_text("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 zero\n")
    with pytest.raises(DemError, match=r"bad\.stl', line 5: bad number 'zero' in vertex"):
        read_triangles(stl)
    stl.write_text("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n")
    with pytest.raises(DemError, match=r"line 6: a facet with 2 vertices"):
        read_triangles(stl)
    stl.write_text("solid empty\nendsolid empty\n")
    with pytest.raises(DemError, match=r"bad\.stl': no triangles"):
        read_triangles(stl)
    stl.write_bytes(b"\x01\x02 not a mesh")
    with pytest.raises(DemError, match=r"bad\.stl': not an STL file"):
        read_triangles(stl)
    with pytest.raises(DemError, match=r"mesh file '.*nowhere\.obj': no such file"):
        load(tmp_path / "nowhere.obj")
    # a NaN or infinite vertex, in each format (both checks: the reader's and the mesh's)
    for value in ("nan", "inf", "-inf"):
        obj.write_text(f"v 0 0 0\nv 1 0 0\nv 0 {value} 0\nf 1 2 3\n")
        with pytest.raises(DemError, match=r"triangle 1 has a non-finite coordinate"):
            read_triangles(obj)
        stl.write_text(f"solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex {value} 0 0\nvertex 0 1 0\n"
                       "endloop\nendfacet\nendsolid s\n")
        with pytest.raises(DemError, match=r"triangle 1 has a non-finite coordinate"):
            read_triangles(stl)
    binary = tmp_path / "nan.stl"
    weld(cube_soup()).write_stl(binary)
    data = bytearray(binary.read_bytes())
    data[84 + 12: 84 + 16] = np.float32(np.nan).tobytes()    # the first vertex of the first triangle
    binary.write_bytes(bytes(data))
    with pytest.raises(DemError, match=r"triangle 1 has a non-finite coordinate"):
        read_triangles(binary)


# ------------------------------------------------------------------------------- tools/make_meshes.py

@pytest.fixture(scope="module")
def meshes(tmp_path_factory):
    out = tmp_path_factory.mktemp("meshes")
    assert make_meshes.main(["--outdir", str(out)]) == 0
    return out


def radius(points):
    return np.hypot(points[..., 0], points[..., 1])


@pytest.mark.parametrize("name, outlet", [("hopper.stl", 0.04), ("hopper_d20.stl", 0.02)])
def test_hopper(meshes, tmp_path, name, outlet):
    if name != "hopper.stl":                                       # a hopper of another exit (--outlet)
        assert make_meshes.main(["--outdir", str(tmp_path), "--outlet", str(outlet)]) == 0
        meshes = tmp_path
    path = meshes / name
    assert path.stat().st_size == 84 + 50 * 256 < 100_000
    mesh = load(path)
    check_topology(mesh)
    assert len(mesh.triangles) == 256 and len(mesh.vertices) == 192 and mesh.dropped == 0
    v, tol = mesh.vertices, GEOMETRY_TOL
    # the three rings: the outlet at z = 0, the junction at z = 0.06, the top at z = 0.16
    for z, r in [(0.0, outlet / 2.0), (0.06, 0.05), (0.16, 0.05)]:
        at = np.abs(v[:, 2] - z) < tol
        assert at.sum() == 64
        assert np.allclose(radius(v[at]), r, rtol=0, atol=tol)
    lo, hi = mesh.bounds()
    assert lo[2] == pytest.approx(0.0, abs=tol) and hi[2] == pytest.approx(0.16, abs=tol)
    # normals inward: towards the axis from each triangle's centroid, on the cone and the cylinder
    centroid = v[mesh.triangles].mean(axis=1)
    to_axis = -centroid * [1.0, 1.0, 0.0]
    assert (np.einsum("ij,ij->i", mesh.normals, to_axis) > 0).all()
    cylinder = centroid[:, 2] > 0.06
    assert cylinder.sum() == 128 and np.allclose(mesh.normals[cylinder, 2], 0.0, rtol=0, atol=1e-6)
    # on the cone, the normal rises above the horizontal by the cone's half-angle atan((0.05 - r_out) /
    # 0.06), here of the facets: each quad is a flat trapezoid whose mid-line runs from the outlet chord
    # to the junction chord, (0.05 - r_out) cos(pi / 64) out over 0.06 up
    half_angle = math.atan((0.05 - outlet / 2.0) * math.cos(math.pi / 64) / 0.06)
    cone_normals = mesh.normals[~cylinder]
    elevation = np.arctan2(cone_normals[:, 2], np.hypot(cone_normals[:, 0], cone_normals[:, 1]))
    assert np.allclose(elevation, half_angle, rtol=0, atol=1e-6)     # float32 coordinates
    # open at both ends: the boundary edges are the two rims, all of them and nothing else
    uses = np.bincount(mesh.edges.ravel(), minlength=mesh.nedges)
    assert mesh.boundary_edges() == 128 and set(uses.tolist()) == {1, 2}
    ends = v[mesh.edge_vertices[uses == 1]]
    at_outlet = (np.abs(ends[..., 2]) < tol).all(axis=1)
    at_top = (np.abs(ends[..., 2] - 0.16) < tol).all(axis=1)
    assert at_outlet.sum() == 64 and at_top.sum() == 64
    assert mesh.area() == pytest.approx(
        2 * math.pi * 0.05 * 0.1 + math.pi * (0.05 + outlet / 2) * math.hypot(0.06, 0.05 - outlet / 2),
        rel=2e-3)                      # the inscribed 64-gon's perimeter is 1 - 4e-4 of the circle's


@pytest.mark.parametrize("diameter", [0.015, 0.030])
def test_orifice_plate(meshes, diameter):
    """The hopper's bottom plate: the ring at z = 0 from the orifice to the hopper's exit radius 0.02 m,
    normals up, its two rims the only boundary edges; area pi (0.02^2 - (d/2)^2) for the inscribed
    64-gons, whose area is (64 / 2pi) sin(2pi / 64) = 0.9984 of the circles'."""
    mesh = load(meshes / f"orifice_d{round(diameter * 1000)}.stl")
    check_topology(mesh)
    assert len(mesh.triangles) == 128 and mesh.boundary_edges() == 128
    assert np.allclose(mesh.vertices[:, 2], 0.0, atol=GEOMETRY_TOL)
    assert np.allclose(mesh.normals, [0.0, 0.0, 1.0], rtol=0, atol=1e-7)
    r = np.sort(np.unique(np.round(radius(mesh.vertices), 6)))
    assert np.allclose(r, [diameter / 2, 0.02], atol=GEOMETRY_TOL)
    polygon = 64 / (2 * math.pi) * math.sin(2 * math.pi / 64)
    assert mesh.area() == pytest.approx(polygon * math.pi * (0.02 ** 2 - (diameter / 2) ** 2), rel=1e-6)


def test_mixer(meshes):
    vessel = load(meshes / "mixer_vessel.stl")
    check_topology(vessel)
    assert len(vessel.triangles) == 192 and vessel.boundary_edges() == 64
    centroid = vessel.vertices[vessel.triangles].mean(axis=1)
    bottom = np.abs(centroid[:, 2]) < GEOMETRY_TOL
    assert bottom.sum() == 64 and np.allclose(vessel.normals[bottom], [0, 0, 1], rtol=0, atol=1e-7)
    assert (np.einsum("ij,ij->i", vessel.normals[~bottom], -centroid[~bottom] * [1, 1, 0]) > 0).all()
    lo, hi = vessel.bounds()
    assert np.allclose(lo, [-0.05, -0.05, 0], atol=GEOMETRY_TOL) and np.allclose(hi, [0.05, 0.05, 0.08],
                                                                                     atol=GEOMETRY_TOL)
    blades = load(meshes / "mixer_blades.stl")
    check_topology(blades)
    assert len(blades.triangles) == 60 and len(blades.vertices) == 40 and blades.boundary_edges() == 0
    # closed with outward normals: the signed volume is the boxes' total volume (float32 coordinates:
    # relative error ~1e-6 on a volume made of differences of coordinates ~0.05 apart)
    shaft = 0.006 ** 2 * 0.075
    blade = 0.04 * 0.004 * 0.02
    assert signed_volume(blades) == pytest.approx(shaft + 4 * blade, rel=1e-5)
    lo, hi = blades.bounds()
    assert hi[2] == pytest.approx(0.08, abs=GEOMETRY_TOL) and lo[2] == pytest.approx(0.005, abs=GEOMETRY_TOL)
    assert radius(blades.vertices).max() < 0.05                   # inside the vessel
    # each blade is pitched 45 degrees: its broad faces' normals are 45 degrees from the vertical
    v = blades.vertices[blades.triangles]
    area = 0.5 * np.linalg.norm(np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), axis=1)
    broad = np.isclose(area, 0.5 * 0.04 * 0.02, rtol=1e-4)
    assert broad.sum() == 4 * 2 * 2
    assert np.allclose(np.abs(blades.normals[broad, 2]), math.sin(math.radians(45)), rtol=0, atol=1e-6)


def test_committed_meshes_match_the_tool(meshes):
    """inputs/meshes/ holds what tools/make_meshes.py writes with its defaults (1e-7 m: a float32 rounding
    of coordinates below 0.2 m is at most 1.5e-8 m, if a libm's cos/sin differs in the last bit)."""
    committed = ROOT / "inputs" / "meshes"
    names = sorted(p.name for p in meshes.iterdir())
    assert names == sorted(p.name for p in committed.glob("*.stl"))
    for name in names:
        assert np.allclose(read_triangles(committed / name), read_triangles(meshes / name), rtol=0, atol=1e-7)
