"""dump png of shaped particles: the true section of each convex piece by the slice plane, or the outline of
its projection (dem_process.render.shaped_polygons, convex_hulls_2d), and the pixels drawn."""
import math

import numpy as np
import pytest

import dem
from dem_process.render import PAD, convex_hulls_2d, shaped_polygons, view_basis

A = 0.002          # cube edge
BASIS = view_basis(1)          # seen from the +y side, z up: right = -x, up = +z


def _quat(axis, angle):
    axis = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    return np.r_[math.cos(angle / 2), math.sin(angle / 2) * axis]


IDENTITY = np.array([1.0, 0.0, 0.0, 0.0])
R45_Y = _quat([0, 1, 0], math.pi / 4)                                    # 45 deg about the view axis
DIAGONAL_Y = _quat(np.cross([1, 1, 1], [0, 1, 0]), math.acos(1 / math.sqrt(3)))   # body (1,1,1) -> +y


def _shapes(*commands):
    sim = dem.Simulation(screen=False)
    sim.commands("\n".join(commands))
    return sim.shapes


def _area(p):
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def _polygons(quat, section, rel=(0.0, 0.0, 0.0), scale=1.0, shapes=None):
    shapes = shapes or _shapes(f"shape c cube {A}")
    return shaped_polygons(shapes, [0], [rel], [quat], [scale * shapes.radius[0]], BASIS, section=section)


def _same_points(p, expected):
    """p (k, 2) and expected (k, 2) hold the same points, in any order."""
    assert len(p) == len(expected)
    d = np.linalg.norm(p[:, None, :] - np.asarray(expected)[None, :, :], axis=2)
    assert d.min(axis=1).max() < 1e-12 and d.min(axis=0).max() < 1e-12


def test_convex_hulls_2d_matches_scipy():
    from scipy.spatial import ConvexHull
    rng = np.random.default_rng(3)
    pts = rng.normal(size=(50, 30, 2))
    valid = rng.random((50, 30)) < 0.7
    valid[:, :3] = True
    hull, count = convex_hulls_2d(pts, valid)
    for i in range(50):
        ref = ConvexHull(pts[i][valid[i]])
        h = hull[i, :count[i]]
        _same_points(h, pts[i][valid[i]][ref.vertices])
        assert _area(h) == pytest.approx(ref.volume, rel=1e-12)        # counter-clockwise
    # a point, a segment (with repeats), nothing: no polygon
    degenerate = np.array([[[1.0, 1.0]] * 4, [[0.0, 0.0], [1.0, 1.0], [0.5, 0.5], [1.0, 1.0]], [[0.0, 0.0]] * 4])
    _, count = convex_hulls_2d(degenerate, np.array([[True] * 4, [True] * 4, [False] * 4]))
    assert np.all(count < 3)


def test_cube_section_through_its_centre_is_a_square_of_its_edge():
    owner, polys = _polygons(IDENTITY, 0.0)
    assert list(owner) == [0]
    h = A / 2
    _same_points(polys[0], [[h, h], [-h, h], [-h, -h], [h, -h]])
    assert _area(polys[0]) == pytest.approx(A * A, rel=1e-12)
    # off the centre but still through the cube: the same square, moved with the particle
    owner, polys = _polygons(IDENTITY, 0.3 * A + 0.01, rel=(0.001, 0.01, -0.002))
    _same_points(polys[0], np.array([[h, h], [-h, h], [-h, -h], [h, -h]]) + [-0.001, -0.002])


def test_cube_turned_45_degrees_about_the_slice_normal_gives_a_square_turned_45_degrees():
    owner, polys = _polygons(R45_Y, 0.1 * A)
    d = A / math.sqrt(2)
    _same_points(polys[0], [[d, 0], [0, d], [-d, 0], [0, -d]])


def test_cube_section_across_its_diagonal_is_a_regular_hexagon():
    owner, polys = _polygons(DIAGONAL_Y, 0.0)
    p = polys[0]
    assert len(p) == 6
    np.testing.assert_allclose(np.linalg.norm(p, axis=1), A / math.sqrt(2), rtol=1e-12)     # side a/sqrt2
    assert _area(p) == pytest.approx(3 * math.sqrt(3) / 4 * A * A, rel=1e-12)
    # near a corner: a triangle
    owner, polys = _polygons(DIAGONAL_Y, 0.4 * A)
    assert len(polys[0]) == 3


def test_slice_missing_a_particle_draws_nothing_and_scale_follows_the_radius():
    for section in (0.51 * A, -0.51 * A, 0.5 * A):       # beyond it, or only touching a face
        owner, polys = _polygons(IDENTITY, section)
        assert len(owner) == 0 and polys == []
    owner, polys = _polygons(IDENTITY, 0.9 * A, scale=2.0)
    assert _area(polys[0]) == pytest.approx(4 * A * A, rel=1e-12)


def test_projected_outline_is_the_hull_of_the_projected_vertices():
    owner, polys = _polygons(IDENTITY, None, rel=(0.0, 0.5, 0.0))      # depth does not matter
    assert _area(polys[0]) == pytest.approx(A * A, rel=1e-12) and len(polys[0]) == 4
    owner, polys = _polygons(DIAGONAL_Y, None)           # seen along a body diagonal: a regular hexagon
    np.testing.assert_allclose(np.linalg.norm(polys[0], axis=1), A * math.sqrt(2 / 3), rtol=1e-12)
    assert _area(polys[0]) == pytest.approx(math.sqrt(3) * A * A, rel=1e-12)
    # a cylinder (axis z) seen side on: its rectangle, 2R x L
    shapes = _shapes("shape y cylinder 0.001 0.003")
    owner, polys = _polygons(IDENTITY, None, shapes=shapes)
    lo, hi = polys[0].min(axis=0), polys[0].max(axis=0)
    np.testing.assert_allclose([hi - lo], [[0.002, 0.003]], rtol=1e-9)
    assert _area(polys[0]) == pytest.approx(0.002 * 0.003, rel=1e-9)


class _TwoCubes:
    """A glued body as the shape table will give it: two convex pieces (unit cubes at x = -0.5 and +0.5)."""

    def __init__(self):
        sim = dem.Simulation(screen=False)
        sim.commands("shape c cube 1")
        V, F = sim.shapes.mesh(0)
        self.pieces = [(V - [0.5, 0, 0], F), (V + [0.5, 0, 0], F)]
        self.radius = np.array([math.sqrt(2.25 + 0.5)])

    def __len__(self):
        return 1

    def convex_pieces(self, idx):
        return self.pieces


def test_each_convex_piece_is_its_own_polygon():
    shapes = _TwoCubes()
    owner, polys = shaped_polygons(shapes, [0, 0], [[0, 0, 0], [5, 0, 0]], [IDENTITY, IDENTITY],
                                   np.repeat(shapes.radius, 2), BASIS, section=0.0)
    assert list(owner) == [0, 0, 1, 1]
    # (h = -x seen from +y)
    _same_points(polys[0], [[1, 0.5], [0, 0.5], [0, -0.5], [1, -0.5]])
    _same_points(polys[3], [[-5, 0.5], [-6, 0.5], [-6, -0.5], [-5, -0.5]])
    # a plane through one piece only
    owner, polys = shaped_polygons(shapes, [0], [[0, 0, 0]], [R45_Y], shapes.radius, BASIS, section=0.0)
    assert len(polys) == 2
    owner, polys = shaped_polygons(shapes, [0], [[0, 0, 0]], [_quat([0, 0, 1], math.pi / 2)], shapes.radius,
                                   BASIS, section=0.7)
    assert len(polys) == 1 and _area(polys[0]) == pytest.approx(1.0)


# ----- the pictures ------------------------------------------------------------------------------------
SIZE, VIEW = 400, 0.004


def _picture(tmp_path, atoms, keywords, name="p.png"):
    """The blue pixels (particles at rest, vmax 1) of a dump png picture and the size of one pixel (m)."""
    from matplotlib.image import imread
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary f f f
        region box block -0.01 0.01 -0.01 0.01 -0.01 0.01
        create_box 1 box
        shape c cube {A}
        {atoms}
        dump p all png 1 {tmp_path / name} axis y centre 0 0 radius {VIEW} vmax 1 size {SIZE} {keywords}
        timestep 1e-6
        run 0
    """)
    sim.close()
    img = imread(tmp_path / name)[..., :3]
    img = img[:, :int(0.84 * SIZE)]            # the colour bar (from 0.86 of the width) is not counted
    blue = (img[..., 2] > 0.3) & (img[..., 0] < 0.2) & (img[..., 1] < 0.2)
    return blue, 2 * PAD * VIEW / (0.82 * SIZE)


def test_png_draws_the_section_of_a_cube(tmp_path):
    q = " ".join(str(c) for c in R45_Y)
    blue, px = _picture(tmp_path, f"create_atoms 1 single 0 0 0 shape c density 2500 quat {q}", "slice 0.0003")
    assert blue.sum() * px * px == pytest.approx(A * A, rel=0.06)
    rows, cols = np.nonzero(blue)
    # turned 45 deg: a diamond as wide and high as the square's diagonal
    assert (cols.max() - cols.min() + 1) * px == pytest.approx(A * math.sqrt(2), rel=0.05)
    assert (rows.max() - rows.min() + 1) * px == pytest.approx(A * math.sqrt(2), rel=0.05)
    # the plane misses the cube: nothing drawn; the projection draws it (the same outline seen along y)
    blue, px = _picture(tmp_path, f"create_atoms 1 single 0 0 0 shape c density 2500 quat {q}", "slice 0.0011")
    assert blue.sum() == 0
    blue, px = _picture(tmp_path, f"create_atoms 1 single 0 0 0 shape c density 2500 quat {q}", "")
    assert blue.sum() * px * px == pytest.approx(A * A, rel=0.06)


def test_png_sphere_section_and_shapes_mixed_with_spheres(tmp_path):
    atoms = ("create_atoms 1 single 0.002 0 0 radius 0.001 density 2500\n"
             "create_atoms 1 single -0.002 0 0 shape c density 2500")
    blue, px = _picture(tmp_path, atoms, "slice 0.0006")
    # seen from +y, x points left: the sphere (x > 0) left of the picture's centre (0.43 of its width)
    left, right = blue[:, :int(SIZE * 0.43)], blue[:, int(SIZE * 0.43):]
    assert left.sum() * px * px == pytest.approx(math.pi * (0.001 ** 2 - 0.0006 ** 2), rel=0.06)
    assert right.sum() * px * px == pytest.approx(A * A, rel=0.06)
    blue, px = _picture(tmp_path, atoms, "")
    left, right = blue[:, :int(SIZE * 0.43)], blue[:, int(SIZE * 0.43):]
    assert left.sum() * px * px == pytest.approx(math.pi * 0.001 ** 2, rel=0.06)
    assert right.sum() * px * px == pytest.approx(A * A, rel=0.06)


def test_png_sphere_of_the_shape_table_is_drawn_as_its_section_disc(tmp_path):
    blue, px = _picture(tmp_path, "shape b sphere 0.001\ncreate_atoms 1 single 0 0 0 shape b density 2500",
                        "slice 0.0006")
    assert blue.sum() * px * px == pytest.approx(math.pi * (0.001 ** 2 - 0.0006 ** 2), rel=0.06)


def test_scale_bar_is_one_two_or_five_times_a_power_of_ten_within_a_fifth_of_the_view():
    from dem_process.render import scale_length
    for span, expected in ((0.1124, 0.02), (0.1, 0.02), (0.0999, 0.01), (0.26, 0.05), (3.0, 0.5), (0.0049, 0.0005)):
        assert math.isclose(scale_length(span), expected, rel_tol=1e-12), span
        assert scale_length(span) <= span / 5 * (1 + 1e-12)


def test_drum_arrow_follows_the_turning_direction(tmp_path):
    """The rim arrow is drawn for a turning drum only, and mirrored when the drum turns the other way."""
    from PIL import Image
    from dem_process.render import render_cross_section
    x = np.array([[0.0, 0.0, -0.04]])
    pics = {}
    for spin in (0.0, 4.0, -4.0):
        path = tmp_path / f"spin{spin}.png"
        render_cross_section(str(path), x, np.zeros((1, 3)), [0.002], axis=1, drum_radius=0.05, spin=spin)
        pics[spin] = np.asarray(Image.open(path).convert("L"), dtype=int)
    top_right = (slice(60, 260), slice(380, 560))         # where the arrow goes (700 px picture)
    dark = {s: int((p[top_right] < 128).sum()) for s, p in pics.items()}
    assert dark[4.0] > dark[0.0] + 50 and dark[-4.0] > dark[0.0] + 50
    assert np.any(pics[4.0] != pics[-4.0])
