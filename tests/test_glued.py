"""Glued convex composites (Grains3D Part III): the shape kinds, their mass properties and table rows, and
pair_style glued/convex between composites, convex particles and spheres.

Tolerances: closed forms evaluated in floating point agree to round-off (1e-12 relative unless said);
forces of static overlaps are Hooke's kn delta exactly (the crust contact rebuilds the overlap from the GJK
distance of the cores to its tolerance, 1e-8 relative by default: a bound of 1e-6 on forces covers it)."""
import math

import numpy as np
import pytest

import dem
from dem.errors import DemError
from dem.shapes import Box, Cylinder, Sphere, cube
from dem.shapes import glued_builtins as gb
from dem.shapes.glued import Glued
from dem.shapes.glued_mass import union_mass_properties

L, W = 0.006, 0.0015           # beam length and width of the crosses (aspect 4)


@pytest.fixture(autouse=True)
def shape_db(tmp_path, monkeypatch):
    monkeypatch.setenv("DEM_SHAPE_DB", str(tmp_path / "shapes.h5"))


def sim_with(text):
    sim = dem.Simulation(screen=False)
    sim.commands(text)
    return sim


def box_inertia(a, b, c):
    V = a * b * c
    return V, np.array([b * b + c * c, a * a + c * c, a * a + b * b]) * V / 12.0


# ---- shapes and mass properties --------------------------------------------------------------------------

def test_crosses_exact_by_inclusion_exclusion():
    # cross2d: beams along x and y share the central w^3 cube; cross3d: three beams, the cube counted 3 times
    Vb, Ib = box_inertia(L, W, W)
    Vc, Ic = box_inertia(W, W, W)
    g2 = Glued(gb.cross2d(L))
    g3 = Glued(gb.cross3d(L))
    assert g2.mass_method == g3.mass_method == "exact"
    assert g2.volume == pytest.approx(2 * Vb - Vc, rel=1e-12)
    assert g3.volume == pytest.approx(3 * Vb - 2 * Vc, rel=1e-12)
    I2 = Ib + Ib[[1, 0, 2]] - Ic
    I3 = Ib + Ib[[1, 0, 2]] + Ib[[2, 1, 0]] - 2 * Ic
    assert np.allclose(g2.principal_moments, I2, rtol=1e-12)
    assert np.allclose(g3.principal_moments, I3, rtol=1e-12)
    assert np.allclose(g3.centroid, 0.0, atol=1e-18) and np.allclose(g3.rotation, np.eye(3))
    # bounding radius: the beam's far corner (L/2, W/2, W/2)
    assert g3.bounding_radius == pytest.approx(math.sqrt(L * L / 4 + W * W / 2), rel=1e-12)


@pytest.mark.parametrize("make, res, tol", [(gb.cross2d, 1000, 2e-3), (gb.cross3d, 1000, 3e-3)])
def test_crosses_lattice_converges_to_exact(make, res, tol):
    """The lattice (used when components overlap and are not boxes with common axes) against the exact
    crosses. Beam faces are planes at +-W/2, W = L/4: at 500 points cell centres fall exactly on them
    (125 cells per beam width, centred lattice) and all of a layer is left out, -1.4 % (cross3d); at 1000
    points the faces sit a quarter cell from centres: measured -0.10 % (2D) / -0.14 % (3D) on the volume,
    -0.12 % / -0.17 % on the moments. Sampling error of a face is up to half a cell: W / 250 per face pair
    at 1000 points = 0.4 %, so 0.2-0.3 % bounds are first-order margins above what is measured."""
    comps = make(L)
    exact = Glued(comps)
    p = union_mass_properties(comps, res)
    assert abs(p["volume"] / exact.volume - 1) < tol
    assert np.allclose(np.diag(p["inertia"]), exact.principal_moments, rtol=1.3 * tol)
    assert np.allclose(p["centre"], 0.0, atol=1e-15)          # the widened box keeps the symmetry
    assert p["error"] >= abs(p["volume"] / exact.volume - 1)


def test_cube8_and_slices_are_their_convex_shape():
    a = 0.002
    g, c = Glued(gb.cube_of_cubes(a)), cube(a)
    assert g.mass_method == "exact"
    assert g.volume == pytest.approx(c.volume, rel=1e-13)
    assert np.allclose(g.principal_moments, c.principal_moments, rtol=1e-12)
    assert g.bounding_radius == pytest.approx(c.bounding_radius, rel=1e-12)
    s, cyl = Glued(gb.sliced_cylinder(0.004, 0.0053, 6)), Cylinder(0.004, 0.0053)
    assert s.volume == pytest.approx(cyl.volume, rel=1e-13)
    assert np.allclose(s.principal_moments, cyl.principal_moments, rtol=1e-12)
    # the rim points of the end slices: the true cylinder's bounding radius plus at most the mesh pad
    assert cyl.bounding_radius <= s.bounding_radius <= cyl.bounding_radius * (1 + 2e-3)


def test_glued_command_inline_file_and_principal_frame(tmp_path):
    # two spheres (radii 1 and 2 mm, centres 3 mm apart along the turned axis): no overlap -> exact; the
    # composite is moved to its centre of mass and principal axes (the axis of the two centres becomes z)
    f = tmp_path / "two.txt"
    f.write_text("# a dumbbell\nsphere 0.001 at 0 0 0\nsphere 0.002 at 0.003 0 0  # the big one\n")
    sim = sim_with(f"""units si
shape a glued component sphere 0.001 at 0 0 0 component sphere 0.002 at 0.003 0 0
shape b glued file {f}
shape c glued component box 0.004 0.001 0.001 rotate 0 0 1 90 component sphere 0.0005 at 0 0.0025 0
""")
    a, b, c = sim.shapes.shapes
    v1, v2 = 4 / 3 * math.pi * 1e-9, 4 / 3 * math.pi * 8e-9
    assert a.volume == pytest.approx(v1 + v2, rel=1e-12) and a.mass_method == "exact"
    com = 0.003 * v2 / (v1 + v2)
    assert np.allclose(a.centroid, [com, 0, 0], rtol=1e-12)
    Iax = 0.4 * (v1 * 1e-6 + v2 * 4e-6)
    Iperp = Iax + v1 * com ** 2 + v2 * (0.003 - com) ** 2
    assert sorted(a.principal_moments) == pytest.approx(sorted([Iax, Iperp, Iperp]), rel=1e-12)
    assert np.allclose(a.principal_moments, b.principal_moments, rtol=0, atol=0)
    # the box turned a quarter about z: its long side along y, touching the sphere at y = 2 mm
    assert c.mass_method == "exact"
    assert len(sim.shapes) == 3 and len(sim.shapes.rows) == 3 + 2 + 2 + 2
    # table rows: the composite lists its components, further rows of the table
    t = sim.shapes
    assert list(t.comp_count[:3]) == [2, 2, 2] and list(t.comp_count[3:]) == [0] * 6
    assert list(t.comp_row) == [3, 4, 5, 6, 7, 8]
    assert t.max_components == 2


@pytest.mark.parametrize("line, text", [
    ("shape x glued component sphre 1", "unknown component kind 'sphre'"),
    ("shape x glued component sphere 1 at 0 0", "'at' needs X Y Z"),
    ("shape x glued component box 1 1 at 0 0 0", "box needs 3 number(s)"),
    ("shape x glued component sphere 1 rotate 0 0 0 30", "axis must not be zero"),
    ("shape x glued sphere 1", "glued needs 'component KIND params...'"),
    ("shape x glued file /nonexistent/f.txt", "cannot read component file"),
    ("shape x cross3d 1 aspect 0.5", "aspect"),
    ("shape x cross3d 1 resolution 3", "resolution must be in 8..5000"),
    ("shape x spherecylinder 4 5.3 10", "N is 9 or 54"),
    ("shape x multisphere 0 0 0", "groups of 4 numbers"),
    ("shape x cube8 1 2", "cube8 needs 1 number(s)"),
])
def test_glued_command_errors(line, text):
    with pytest.raises(DemError, match=None) as e:
        sim_with("units si\n" + line)
    assert text in str(e.value) and "line 2" in str(e.value).replace(":2:", " line 2")


def test_component_file_errors_name_the_file_line(tmp_path):
    f = tmp_path / "bad.txt"
    f.write_text("sphere 0.001\n\nbox 0.001 0.001 at 0 0 0\n")
    with pytest.raises(DemError) as e:
        sim_with(f"units si\nshape x glued file {f}")
    assert f"{f} line 3" in str(e.value)


def test_overlapping_spheres_lattice_and_cache(tmp_path):
    """Two spheres of radius r at distance r (a lens of volume 5 pi r^3 / 12 shared): lattice at 500 points
    within 0.2 % of the closed form (Part III sec 2.3; measured 2e-5), the shape database gives the same
    numbers back, and a changed definition is computed anew."""
    r = 0.001
    db = tmp_path / "db.h5"
    text = f"units si\nshape x glued component sphere {r} component sphere {r} at {r} 0 0 db {db}\n"
    exact = 2 * 4 / 3 * math.pi * r ** 3 - 5 * math.pi * r ** 3 / 12
    a = sim_with(text).shapes.shapes[0]
    assert a.mass_method == "lattice" and abs(a.volume / exact - 1) < 2e-3 and not a.mass_cached
    b = sim_with(text).shapes.shapes[0]
    assert b.mass_cached
    assert b.volume == a.volume and np.array_equal(b.principal_moments, a.principal_moments)
    c = sim_with(text.replace(f"at {r} 0 0", f"at {0.9 * r} 0 0")).shapes.shapes[0]
    assert not c.mass_cached and c.volume < a.volume


def test_scaled_composite_and_multisphere():
    g = Glued(gb.cross2d(L))
    s = g.scaled(2.0)
    assert s.volume == pytest.approx(8 * g.volume, rel=1e-13)
    assert np.allclose(s.principal_moments, 32 * g.principal_moments, rtol=1e-13)
    assert s.bounding_radius == pytest.approx(2 * g.bounding_radius, rel=1e-12)
    m = Glued(gb.multisphere([(0, 0, 0, 1.0), (3, 0, 0, 1.0)]))
    assert m.volume == pytest.approx(2 * 4 / 3 * math.pi, rel=1e-12)
    assert m.bounding_radius == pytest.approx(2.5, rel=1e-3)


def test_glued_sphere_cylinder_volumes_against_table2():
    """Part III Table 2 ('our glued-sphere model'): 9 spheres 1.948e-7 m3; our layout (glued_builtins)
    gives 1.94879e-7 (+0.04 %); 54 spheres 2.244e-7, ours 2.1675e-7 (-3.4 %: the paper's Fig. 10 layout is
    not given in numbers). Lattice at 500 points (error estimate < 0.1 %)."""
    s9 = Glued(gb.sphere_cylinder(0.004, 0.0053, 9))
    s54 = Glued(gb.sphere_cylinder(0.004, 0.0053, 54))
    assert s9.volume == pytest.approx(1.948e-7, rel=2e-3)
    assert s54.volume == pytest.approx(2.1675e-7, rel=2e-3)
    assert s9.mass_error < 1e-3 and s54.mass_error < 1e-3


# ---- pair style ------------------------------------------------------------------------------------------

PAIR = """units si
boundary f f f
region box block -0.02 0.02 -0.02 0.02 -0.02 0.02
create_box 1 box
{shapes}
{atoms}
pair_style {pair}
pair_coeff * * kn 1e5 en 0.9
fix integrate all nve/shape
timestep 1e-7
run 0
"""


def pair_forces(shapes, atoms, pair="glued/convex"):
    sim = sim_with(PAIR.format(shapes=shapes, atoms=atoms, pair=pair))
    return sim, sim.atom.local("f").copy(), sim.atom.local("torque").copy()


@pytest.mark.parametrize("model, points", [("B", 1), ("A", 4)])
def test_two_glued_cubes_face_to_face(model, points):
    """Two cubes of 8 cubes, face to face with overlap d: 4 component pairs in contact, each kn d; Model B
    averages them (kn d, as one true cube pair), Model A sums them (4 kn d). Each component pair is one
    GJK point on two parallel faces, a corner of the face (the same corner for the 4 alike pairs): a torque
    of at most F a / 2 remains, the single-point artifact Grains3D has too (Part III sec 3.3); walls break
    that tie away from the composite's centre (see test_glued_cube_impact)."""
    a, d = 0.002, 1e-5
    sim, f, t = pair_forces("shape c cube8 0.002", f"create_atoms 1 single 0 0 0 shape c density 1000\n"
                            f"create_atoms 1 single 0 0 {a - d} shape c density 1000",
                            pair=f"glued/convex model {model}")
    assert sim.pair.ncontacts == 1 and sim.pair.npoints == 4
    assert f[1, 2] == pytest.approx(points * 1e5 * d, rel=1e-6)
    assert np.allclose(f[0], -f[1], rtol=0, atol=1e-12) and abs(f[0, 0]) < 1e-9 * abs(f[1, 2])
    assert np.abs(t).max() <= 0.5 * abs(f[1, 2]) * a * (1 + 1e-9)


def test_convex_and_spheres_as_single_pieces():
    """glued/convex serves convex particles and spheres: the same contact force as convex/gjk and sphere."""
    atoms = ("create_atoms 1 single 0 0 0 shape b density 1000 quat 0.9 0.1 0.3 0.2\n"
             "create_atoms 1 single 0.0001 0.0002 0.00145 radius 0.0008 density 1000")
    _, f1, t1 = pair_forces("shape b box 0.002 0.0015 0.001", atoms, "glued/convex")
    _, f2, t2 = pair_forces("shape b box 0.002 0.0015 0.001", atoms, "convex/gjk")
    assert np.abs(f1[1]).max() > 0
    assert np.allclose(f1, f2, rtol=1e-9, atol=0) and np.allclose(t1, t2, rtol=1e-9, atol=1e-20)
    spheres = ("create_atoms 1 single 0 0 0 radius 0.001 density 1000\n"
               "create_atoms 1 single 0 0 0.00199 radius 0.001 density 1000")
    _, f3, _ = pair_forces("", spheres, "glued/convex")
    assert f3[1, 2] == pytest.approx(1e5 * 1e-5, rel=1e-9)


def test_sphere_on_a_cross_beam():
    """A sphere resting on the +x beam of a cross (lever from the cross's centre of mass: torque = r x F)."""
    r, d, xs = 0.0005, 2e-6, 0.002
    sim, f, t = pair_forces(f"shape x cross3d {L}", f"create_atoms 1 single 0 0 0 shape x density 1000\n"
                            f"create_atoms 1 single {xs} 0 {W / 2 + r - d} radius {r} density 1000")
    assert sim.pair.npoints == 1
    assert f[1, 2] == pytest.approx(1e5 * d, rel=1e-6)
    # on the cross: -F at (xs, 0, W/2): torque about y = z * Fx - x * Fz = xs * F
    assert t[0, 1] == pytest.approx(xs * 1e5 * d, rel=1e-6)


def test_convex_gjk_refuses_composites():
    with pytest.raises(DemError, match="glued/convex"):
        pair_forces(f"shape x cross2d {L}", "create_atoms 1 single 0 0 0 shape x density 1000", "convex/gjk")


def test_elastic_collision_of_two_crosses_conserves_energy():
    """Two 3D crosses thrown at each other, turned, en = 1, no friction, no gravity: kinetic energy
    (translation + rotation) after the collision equals the one before to O(dt^2) of leap-frog with
    Omelyan's rotation (measured 2e-5 relative at 30 steps per contact time; bound 1e-3), momentum exactly."""
    sim = sim_with(f"""units si
boundary f f f
region box block -0.02 0.02 -0.02 0.02 -0.02 0.02
create_box 1 box
shape x cross3d {L}
create_atoms 1 single 0 0 0 shape x density 1000 v 0.2 0 0 quat 0.9 0.2 0.3 0.1
create_atoms 1 single 0.0062 0.0009 0.0007 shape x density 1000 v -0.2 0 0 quat 0.8 -0.1 0.4 0.3
pair_style glued/convex
pair_coeff * * kn 1e3 en 1.0
fix integrate all nve/shape
compute ke all ke
timestep 2e-6
thermo_style custom step ke contacts
run 0
""")
    def energy():
        m, v = sim.atom.local("rmass"), sim.atom.local("v")
        I, w, q = sim.atom.local("inertia"), sim.atom.local("omega"), sim.atom.local("quat")
        from dem.thermo import quat_to_matrix
        e = 0.5 * (m * (v * v).sum(1)).sum()
        for k in range(2):
            R = quat_to_matrix(q[k:k + 1])[0]
            wb = R.T @ w[k]
            e += 0.5 * (I[k] * wb * wb).sum()
        return e, (m[:, None] * v).sum(0)
    e0, p0 = energy()
    touched = 0
    for _ in range(40):
        sim.command("run 100")
        touched = max(touched, sim.pair.ncontacts)
    assert touched == 1 and sim.pair.ncontacts == 0
    e1, p1 = energy()
    assert e1 == pytest.approx(e0, rel=1e-3)
    assert np.allclose(p1, p0, rtol=0, atol=1e-15)
    assert sim.pair.stats["piece_candidates"] > 0 and sim.pair.stats["gjk"] >= sim.pair.stats["points"]


MIXED_BED = """units si
boundary p p f
region box block 0 0.0086 0 0.0086 0 0.03
create_box 2 box
shape x cross3d 0.002
shape c cylinder 0.0004 0.0008
region low block 0 0.0086 0 0.0086 0 0.0065
region mid block 0 0.0086 0 0.0086 0.0065 0.0105
region top block 0 0.0086 0 0.0086 0.0105 0.0145
create_atoms 1 lattice low sc 0.00215 shape x quat random density 2500
create_atoms 1 lattice mid sc 0.00125 shape c quat random density 2500
create_atoms 2 lattice top sc 0.00125 radius 0.0005 density 2500
pair_style glued/convex
pair_coeff * * kn 2000 en 0.3 mu 0.5 gamma_t 2000 ks 571
fix integrate all nve/shape
fix gravity all gravity 98.1 vector 0 0 -1
fix floor all wall/plane zplane 0 NULL
timestep 4e-6
neighbor 0.0002 bin
thermo 0
"""


def test_piece_candidates_change_no_bits():
    """The piece candidates (component pairs within the skin when the neighbor list is built, rebuilt when
    a particle has moved or turned too far) skip only piece pairs proven apart: a bed of crosses, cylinders
    and spheres falling onto a floor is bit for bit the run that tests every piece pair of every listed
    pair each step (margin 0: candidates rebuilt each step from the per-step culls themselves), histories
    included, with a fraction of the pairs tested."""
    runs = []
    for margin in (None, 0.0):
        sim = sim_with(MIXED_BED)
        sim.pair.piece_margin = margin
        sim.run(2500)
        runs.append((sim, {n: sim.atom.local(n).copy() for n in ("x", "v", "omega", "quat", "f", "torque")},
                     sim.pair.history.by_tags(), dict(sim.pair.stats)))
    (a, sa, ha, ta), (b, sb, hb, tb) = runs
    assert ta["contacts"] > 1000 and ta["points"] > ta["contacts"]        # crosses touch crosses, cylinders, spheres
    for name in sa:
        assert np.array_equal(sa[name], sb[name]), name
    assert ha.keys() == hb.keys() and all(np.array_equal(ha[k], hb[k]) for k in ha)
    for key in ("contacts", "points", "gjk", "piece_pairs", "piece_candidates"):
        assert ta[key] == tb[key], key
    # margin 0 lists, each step, just the pairs the culls keep; the skin's lists are rebuilt with the
    # neighbor list and in between when particles move or turn too far (measured 113 builds, 57 lists): they
    # list half of the piece pairs and leave 29 % for the culls (measured 0.51, 0.29)
    assert tb["piece_builds"] > 2490 and tb["piece_listed"] == tb["piece_candidates"]
    assert a.neighbor.nbuilds <= ta["piece_builds"] < 250
    assert ta["piece_listed"] < 0.6 * ta["piece_pairs"] and ta["piece_spheres"] < 0.35 * ta["piece_pairs"]
