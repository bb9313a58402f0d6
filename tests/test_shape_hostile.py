"""Hostile shape definitions: each is a clear DemError naming the script line, or a warning, never a
traceback (degenerate or thin polyhedra, non-convex meshes, binary or broken component files, sizes whose
inertia would overflow); and a 20,000-point polyhedron builds (the build is O(N log N): quadratic, it
took about an hour; timings in benchmarks/README.md)."""
import subprocess
import sys

import numpy as np
import pytest

import dem


def shape_error(line, match):
    """The DemError of `units si` then `line` (line 2), checked to name that line."""
    with pytest.raises(dem.DemError, match=match) as err:
        dem.Simulation(screen=False).commands(f"units si\n{line}\n")
    assert err.value.where == "<string>:2", str(err.value)


def points(P):
    return " ".join(f"{x:.17g}" for x in np.ravel(P))


CUBE = 1e-3 * np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)


# ----- degenerate points: a DemError, not a QhullError ----------------------------------------------
@pytest.mark.parametrize("P, match", [
    (CUBE[CUBE[:, 2] == 0], "coplanar: a polyhedron needs volume"),
    (1e-3 * np.c_[np.arange(5.0), 2 * np.arange(5.0), np.zeros(5)], "collinear: a polyhedron needs volume"),
    (np.zeros((4, 3)), "at least 4 distinct points, got 1"),
    (CUBE[:3][[0, 1, 2, 0, 1]], "at least 4 distinct points, got 3"),
    # coplanar but turned: round-off leaves a thickness of ~1e-19 m
    (CUBE[CUBE[:, 2] == 0] @ np.linalg.qr(np.arange(9.0).reshape(3, 3) + np.eye(3))[0], "coplanar"),
], ids=["coplanar", "collinear", "one point", "three distinct", "turned coplanar"])
def test_degenerate_points_are_a_clear_error(P, match):
    shape_error(f"shape p polyhedron {points(P)}", match)


def test_repeated_points_among_good_ones_are_merged():
    sim = dem.Simulation(screen=False).commands(f"shape p polyhedron {points(np.r_[CUBE, CUBE[:3]])}\n")
    assert len(sim.shapes.shapes[0].vertices) == 8
    assert sim.shapes.volume[0] == pytest.approx(1e-9)


def test_a_polyhedron_too_thin_is_an_error():
    slab = CUBE * [1, 1, 2e-10]          # 1 mm x 1 mm x 2e-13 m
    shape_error(f"shape p polyhedron {points(slab)}", r"2e-13 thick for an extent of 0.001: thinner than 1e-06")
    shape_error(f"shape p polyhedron {points(slab)} crust 0", "thinner than 1e-06")
    dem.Simulation(screen=False).commands(f"shape p polyhedron {points(CUBE * [1, 1, 2e-6])}\n")   # 2e-9 m: fine


def test_a_qhull_failure_never_leaves_a_traceback(tmp_path):
    (tmp_path / "in.test").write_text(f"units si\nshape p polyhedron {points(CUBE[CUBE[:, 2] == 0])}\n")
    out = subprocess.run([sys.executable, "-m", "dem", "-in", "in.test", "-log", "none"],
                         capture_output=True, text=True, cwd=tmp_path)
    assert out.returncode == 1 and "Traceback" not in out.stderr, out.stderr
    assert "in.test:2: shape: the points are coplanar" in out.stderr


# ----- non-convex meshes: a warning with the volume the hull adds -------------------------------------
def dented_octahedron(dent=0.2):
    """An octahedron (corners at +-1 mm on the axes) whose top corner is pushed down to `dent` mm below
    the middle plane: closed, outward, not convex. Own volume (2 - 2 dent) / 3 mm^3, its hull 2/3 mm^3."""
    V = 1e-3 * np.array([[1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0], [0, 0, -dent], [0, 0, -1]], float)
    F = [(0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4), (1, 0, 5), (2, 1, 5), (3, 2, 5), (0, 3, 5)]
    return V, np.array(F)


def write_obj(path, V, F):
    path.write_text("".join(f"v {points(v)}\n" for v in V) + "".join(f"f {a + 1} {b + 1} {c + 1}\n"
                                                                       for a, b, c in F))


def write_stl(path, V, F):
    facets = "".join("facet normal 0 0 0\nouter loop\n" + "".join(f"vertex {points(V[k])}\n" for k in f)
                     + "endloop\nendfacet\n" for f in F)
    path.write_text(f"solid dented\n{facets}endsolid dented\n")


def warnings_of(capsys, script):
    sim = dem.Simulation().commands(script)
    return sim, [line for line in capsys.readouterr().out.splitlines() if line.startswith("WARNING")]


@pytest.mark.parametrize("write", [write_obj, write_stl], ids=["obj", "stl"])
def test_a_non_convex_mesh_warns_with_the_volume_the_hull_adds(tmp_path, capsys, write):
    V, F = dented_octahedron(0.2)          # own volume 1.6/3, hull 2/3: +25 %
    path = tmp_path / ("dented" + (".obj" if write is write_obj else ".stl"))
    write(path, V, F)
    sim, warned = warnings_of(capsys, f"units si\nshape p polyhedron file {path}\n")
    assert sim.shapes.volume[0] == pytest.approx(2e-9 / 3)
    assert len(warned) == 1, warned
    assert "<string>:2: shape polyhedron file" in warned[0]
    assert "not convex" in warned[0] and "25 % more than the mesh's own 5.33333e-10" in warned[0]
    assert "shape NAME glued" in warned[0]


def test_an_open_non_convex_mesh_says_its_volume_is_unknown(tmp_path, capsys):
    V, F = dented_octahedron(0.2)
    write_obj(tmp_path / "open.obj", V, F[1:])          # a face missing
    _, warned = warnings_of(capsys, f"shape p polyhedron file {tmp_path / 'open.obj'}\n")
    assert len(warned) == 1 and "not closed, so its own volume is unknown" in warned[0], warned
    assert "1 of its 6 vertices lie inside its convex hull" in warned[0] and "glued" in warned[0]


def test_a_convex_mesh_gives_no_warning(tmp_path, capsys):
    V, F = dented_octahedron(-1.0)         # the regular octahedron
    write_obj(tmp_path / "octa.obj", V, F)
    _, warned = warnings_of(capsys, f"shape p polyhedron file {tmp_path / 'octa.obj'}\n")
    assert warned == []


# ----- the glued component file ---------------------------------------------------------------------
@pytest.mark.parametrize("content, match", [
    (bytes(range(256)) * 4, r"'.*comps' is not a text file \(byte 0 is 0x00\)"),
    (b"box 1e-3 1e-3 1e-3\n\xff\xfe\x00\x01 garbage\n", "is not a text file"),
    (b"box 1e-3 1e-3 1e-3\n\xff\xfebox\n", r"is not a text file \(byte 19 is 0xff\)"),
    (b"box 1e-3 1e-3 1e-3\nbox 1e-3 1e-3 1e-3 at 0 0\n", "comps line 2: 'at' needs X Y Z"),
    (b"box 1e-3 1e-3 1e-3\nbox 1e-3 1e-3\n", "comps line 2: box needs 3 number"),
    (b"box 1e-3 1e-3 1e-3\nbox 1e-3 @@ 1e-3\n", "comps line 2: box parameter must be a number, got '@@'"),
    (b"box 1e-3 1e-3 1e-3\n~~~~ 1 2 3\n", "comps line 2: unknown component kind '~~~~'"),
], ids=["binary", "nul", "latin-1", "truncated at", "truncated numbers", "garbage number", "garbage kind"])
def test_a_broken_component_file_is_a_clear_error(tmp_path, content, match):
    (tmp_path / "comps").write_bytes(content)
    shape_error(f"shape g glued file {tmp_path / 'comps'}", match)


# ----- sizes and coordinates whose inertia would overflow -------------------------------------------
@pytest.mark.parametrize("line, match", [
    ("shape g glued component sphere 1 at 1e308 0 0 component sphere 1 at -1e308 0 0",
     r"component 1: at: 1e\+308 exceeds 1e\+40"),
    ("shape g glued component sphere 1e200 component sphere 1 at 1 0 0",
     r"component 1: sphere parameters: 1e\+200 exceeds 1e\+40"),
    ("shape g multisphere 0 0 0 1 1e300 0 0 1", r"multisphere parameters: 1e\+300 exceeds"),
    ("shape g box 1e300 1 1", r"box parameters: 1e\+300 exceeds 1e\+40"),
    ("shape g polyhedron 0 0 0 1e50 0 0 0 1 0 0 0 1", r"polyhedron parameters: 1e\+50 exceeds"),
    ("shape g cross3d 1e300", r"beam length L: 1e\+300 exceeds"),
])
def test_lengths_whose_inertia_overflows_are_a_clear_error(line, match):
    shape_error(line, match)


def test_a_nan_vertex_in_a_mesh_file_is_a_clear_error(tmp_path):
    V, F = dented_octahedron(-1.0)
    V[2, 1] = np.nan
    write_obj(tmp_path / "nan.obj", V, F)
    shape_error(f"shape p polyhedron file {tmp_path / 'nan.obj'}", "polyhedron points: non-finite number nan")


def test_components_at_the_largest_bound_still_build():
    sim = dem.Simulation(screen=False).commands(
        "shape g glued component sphere 1e3 at 1e39 0 0 component sphere 1e3 at -1e39 0 0\n")
    assert np.all(np.isfinite(sim.shapes.inertia[0]))


# ----- a scanned grain: 20,000 hull points ------------------------------------------------------------
def test_a_20000_point_polyhedron_builds(tmp_path, capsys):
    """Every point a hull vertex (points on a sphere of 1 mm): quadratic in the points, this took about an
    hour; it now builds in well under a second (benchmarks/shape_build.py)."""
    rng = np.random.default_rng(7)
    P = rng.normal(size=(20000, 3))
    P = 1e-3 * P / np.linalg.norm(P, axis=1)[:, None]
    (tmp_path / "grain.obj").write_text("".join(f"v {points(p)}\n" for p in P))
    sim, warned = warnings_of(capsys, f"shape grain polyhedron file {tmp_path / 'grain.obj'}\n")
    s = sim.shapes.shapes[0]
    assert warned == [] and len(s.vertices) == 20000
    assert s.volume == pytest.approx(4.0 / 3.0 * np.pi * 1e-9, rel=1e-3)
    assert len(s.core_vertices) >= 2 * 20000
