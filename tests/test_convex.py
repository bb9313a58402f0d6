"""Shapes in the simulation (`shape` command, create_atoms/set ... shape, dem.shapes.command), pair style
convex/gjk (spheres and convex bodies mixed), plane walls for shaped particles, true-shape dumps,
restarts and MPI with shapes."""
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import dem
from dem.contact import geometry
from dem_convex._pair_convex import FEAT_SLOT, TAG_SLOT
from dem.errors import DemError
from dem.shapes import command as shape_command
from dem.shapes import cube, Cylinder
from dem.thermo import quat_to_matrix

from conftest import MPIEXEC

BOX = """
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01
create_box {ntypes} box
"""






def make(script, ntypes=1):
    sim = dem.Simulation(screen=False)
    sim.commands(BOX.format(ntypes=ntypes) + script)
    return sim


# ----- shapes and particles -------------------------------------------------------------------------
def test_shape_command_and_particle_properties():
    sim = make("""
shape c cube 0.002 crust 0.00005
shape cyl cylinder 0.001 0.003
shape tet tetrahedron 0.003
shape poly polyhedron 0 0 0 0.002 0 0 0 0.002 0 0 0 0.002
create_atoms 1 single 0 0 0 shape c density 2000
create_atoms 1 single 0.005 0 0 shape c scale 1.5 density 2000 quat 1 1 0 0
create_atoms 1 single -0.005 0 0 shape cyl density 1000
create_atoms 1 single 0 0.005 0 radius 0.001 density 1000
""")
    t = sim.shapes
    assert t.names == ["c", "cyl", "tet", "poly"] and len(t) == 4
    assert t.crust[0] == 0.00005
    d = sim.atom.data
    assert list(d["shape"][:4]) == [0, 0, 1, -1]
    m0 = 2000 * 0.002 ** 3
    assert d["rmass"][0] == pytest.approx(m0, rel=1e-14)
    assert d["rmass"][1] == pytest.approx(m0 * 1.5 ** 3, rel=1e-14)
    np.testing.assert_allclose(d["inertia"][0], m0 * 0.002 ** 2 / 6, rtol=1e-13)
    np.testing.assert_allclose(d["inertia"][1], m0 * 1.5 ** 3 * (0.003) ** 2 / 6, rtol=1e-13)
    assert d["radius"][0] == pytest.approx(0.001 * math.sqrt(3))
    assert d["radius"][1] == pytest.approx(0.0015 * math.sqrt(3))
    np.testing.assert_allclose(d["quat"][1], [2 ** -0.5, 2 ** -0.5, 0, 0])
    cyl = Cylinder(0.001, 0.003)
    assert d["rmass"][2] == pytest.approx(1000 * cyl.volume)
    np.testing.assert_allclose(d["inertia"][2], 1000 * cyl.principal_moments)
    assert d["radius"][3] == 0.001 and d["inertia"][3][0] == pytest.approx(0.4 * d["rmass"][3] * 1e-6)
    # the helpers for insertion fixes
    p = shape_command.properties(sim, "c", radius=np.array([d["radius"][1]]), density=2000)
    assert p["rmass"][0] == pytest.approx(d["rmass"][1]) and p["shape"][0] == 0
    shape_command.assign(sim, slice(3, 4), "cyl", scale=2.0)
    assert d["shape"][3] == 1 and d["rmass"][3] == pytest.approx(1000 * cyl.volume * 8)
    assert d["radius"][3] == pytest.approx(2 * cyl.bounding_radius)


def test_shape_errors():
    sim = make("shape c cube 0.002\n")
    with pytest.raises(DemError, match="shape 'c' already exists"):
        sim.command("shape c cube 0.003")
    with pytest.raises(DemError, match=r"shape kind box needs 3 number\(s\): A B C"):
        sim.command("shape b box 0.1 0.2")
    with pytest.raises(DemError, match=r"unknown shape style 'cubee' \(did you mean 'cube'\?\)"):
        sim.command("shape b cubee 0.1")
    with pytest.raises(DemError, match="unknown shape 'cc'"):
        sim.command("create_atoms 1 single 0 0 0 shape cc")
    with pytest.raises(DemError, match=r"box: crust 0.002 must be in \[0, 0.001\)"):
        sim.command("shape d cube 0.002 crust 0.002")
    with pytest.raises(DemError, match="give either 'scale' or 'radius' for shaped particles"):
        sim.command("create_atoms 1 single 0 0 0 shape c scale 2 radius 0.001")


def test_set_shape_scale_density_and_random_orientations():
    sim = make("""
shape c cube 0.002
region all block -0.008 0.008 -0.008 0.008 -0.008 0.008
create_atoms 1 random 20 77 all radius 0.001 density 1000
set group all shape c scale 0.5
""")
    d = sim.atom.data
    n = sim.atom.nlocal
    assert np.all(d["shape"][:n] == 0)
    np.testing.assert_allclose(d["rmass"][:n], 1000 * 0.001 ** 3)           # density kept
    np.testing.assert_allclose(d["radius"][:n], 0.0005 * math.sqrt(3))
    sim.command("set atom 1 scale 2")
    assert d["rmass"][0] == pytest.approx(1000 * 0.004 ** 3)
    sim.command("set atom 2 radius 0.002")                                  # the bounding radius
    assert d["rmass"][1] == pytest.approx(1000 * (0.004 / math.sqrt(3)) ** 3)
    sim.command("set atom 3 density 3000")
    assert d["rmass"][2] == pytest.approx(3000 * 0.001 ** 3)
    np.testing.assert_allclose(d["inertia"][2], 3000 * 0.001 ** 5 / 6)
    sim.command("set group all quat random seed 4")
    q1 = sim.gather("quat").copy()
    assert np.allclose(np.linalg.norm(q1, axis=1), 1) and np.std(q1[:, 0]) > 0.1
    sim.command("set group all quat random seed 4")
    assert np.array_equal(sim.gather("quat"), q1)
    # create_atoms random with shapes keeps the bounding spheres apart; scale distributions
    sim2 = make("""
shape c cube 0.002
region all block -0.008 0.008 -0.008 0.008 -0.008 0.008
create_atoms 1 random 30 5 all shape c scale uniform 0.5 1.0 quat random density 2500
""")
    x, r = sim2.gather("x"), sim2.gather("radius")
    s = r / sim2.shapes.radius[0]
    assert s.min() >= 0.5 and s.max() <= 1.0 and s.std() > 0.05
    np.testing.assert_allclose(sim2.gather("rmass"), 2500 * (0.002 * s) ** 3)
    dist = np.linalg.norm(x[:, None] - x[None], axis=-1) + np.eye(len(x))
    assert np.all(dist >= r[:, None] + r[None] - 1e-15)


# ----- pair style ------------------------------------------------------------------------------------
SPHERES = """
create_atoms 1 single 0 0 0 radius 0.001 density 2500 v 0.2 0 0 omega 10 0 30
create_atoms 2 single 0.00205 0.0005 0 radius 0.0012 density 2000 v -0.3 0 0.05
create_atoms 1 single 0.0001 0.0025 0.0003 radius 0.0009 density 2500 v 0 -0.4 0 omega 0 50 0
pair_coeff * * kn 1e4 en 0.6 mu 0.4 gamma_t 50 ks 3000 mu_roll 0.05
pair_coeff 1 2 kn 2e4 en 0.8 mu 0.3 ks 5000
fix 1 all nve/sphere
timestep 1e-6
thermo 0
"""


def test_spheres_through_convex_gjk_match_pair_sphere():
    """Spheres only: convex/gjk is pair sphere (analytic geometry, same law, history, rolling)."""
    ref = make("pair_style sphere\n" + SPHERES, ntypes=2)
    new = make("pair_style convex/gjk\n" + SPHERES, ntypes=2)
    ref.run(3000)
    new.run(3000)
    assert ref.pair.ncontacts + new.pair.ncontacts >= 0
    for name in ("x", "v", "omega"):
        np.testing.assert_allclose(new.gather(name), ref.gather(name), rtol=1e-9, atol=1e-12)
    # and through the shape table: table spheres are spheres
    tab = make("pair_style convex/gjk\nshape s sphere 0.001\n" + SPHERES + "set atom 1 shape s\n", ntypes=2)
    tab.run(3000)
    np.testing.assert_allclose(tab.gather("x"), ref.gather("x"), rtol=1e-9, atol=1e-12)


def cube_pair(extra="", en=1.0, mu=0.0, steps=4000):
    sim = make(f"""
shape c cube 0.002
create_atoms 1 single -0.002 0 0 shape c density 2500 v 1 0 0 quat 0.3 0.5 0.1 0.7
create_atoms 1 single 0.002 0.0003 0.0002 shape c density 2500 v -1 0 0 quat 0.9 0.1 0.2 0.3
create_atoms 1 single 0.0 0.0033 0.0002 radius 0.001 density 2500 v 0 -1 0
{extra}
pair_style convex/gjk
pair_coeff * * kn 1e5 en {en} mu {mu} gamma_t 100 ks 20000
fix 1 all nve/shape
timestep 1e-7
thermo 0
""")
    return sim


def momenta(sim):
    m = sim.gather("rmass")
    x, v = sim.gather("x"), sim.gather("v")
    p = (m[:, None] * v).sum(0)
    # angular momentum about the origin: orbital + spin (J = R I R^T omega)
    rot = quat_to_matrix(sim.gather("quat"))
    w_b = np.einsum("nji,nj->ni", rot, sim.gather("omega"))
    spin = np.einsum("nij,nj->ni", rot, w_b * sim.gather("inertia"))
    return p, (np.cross(x, m[:, None] * v) + spin).sum(0)


def test_elastic_collisions_conserve_energy_and_momenta():
    sim = cube_pair()
    sim.run(0)
    e0 = sim.thermo_keyword("etotal")
    p0, l0 = momenta(sim)
    sim.run(40000)
    assert sim.pair.ngjk > 0 and sim.pair.nepa == 0
    e1 = sim.thermo_keyword("etotal")
    p1, l1 = momenta(sim)
    assert sim.thermo_keyword("erot") > 0.2 * e0          # the corners made them spin
    assert abs(e1 / e0 - 1) < 1e-4
    np.testing.assert_allclose(p1, p0, atol=1e-12 * np.abs(p0).max())
    # angular momentum: the half-step velocities of the leap-frog conserve it to O(dt^2)
    assert np.linalg.norm(l1 - l0) < 1e-4 * np.linalg.norm(l0) + 1e-13


def two_bodies(shape, x2):
    """Two particles of `shape` (a shape command's arguments), at the origin and at x2, turned."""
    return make(f"""
shape c {shape}
create_atoms 1 single 0 0 0 shape c density 2500 quat 0.9 0.2 0.1 0.3
create_atoms 1 single {x2} shape c density 2500 quat 0.8 -0.1 0.4 0.2
pair_style convex/gjk
pair_coeff * * kn 1e5 en 1.0
fix 1 all nve/shape
timestep 1e-7
thermo 0
""")


def test_contact_matches_geometry_and_newton_third_law():
    """Forces of one cube-cube contact: overlap/normal/point from dem.contact.geometry, equal and opposite
    forces, torques = lever x force about each centre of mass."""
    sim = two_bodies("cube 0.002", "0.00185 0.0004 0.0003")
    sim.run(0)
    d = sim.atom.data
    shape = sim.shapes.shapes[0]
    ov, n, p = geometry.contact(shape, d["x"][0], d["quat"][0], shape, d["x"][1], d["quat"][1])
    assert sim.pair.ncontacts == 1 and ov > 0
    np.testing.assert_allclose(d["f"][0], 1e5 * ov * n, rtol=1e-6)
    np.testing.assert_allclose(d["f"][1], -d["f"][0], rtol=1e-14)
    np.testing.assert_allclose(d["torque"][0], np.cross(p - d["x"][0], d["f"][0]), rtol=1e-6, atol=1e-15)
    np.testing.assert_allclose(d["torque"][1], np.cross(p - d["x"][1], d["f"][1]), rtol=1e-6, atol=1e-15)
    assert sim.pair.energy == pytest.approx(0.5 * 1e5 * ov ** 2, rel=1e-6)


def test_curved_warm_start_belongs_to_the_pair_shapes():
    """A curved pair keeps its last GJK simplex as points in the two body frames, tagged with the two shapes.
    Points that do not belong to the bodies would fool GJK: all at one world point (a - b = 0), the pair
    reads as overlapping. With the tag of other shapes (a particle given another shape) the kernel drops
    them: the forces are the cold start's, bit for bit."""
    sim = two_bodies("cylinder 0.001 0.002", "0.0024 0.0006 0.0003")
    sim.run(10)
    h = sim.pair.history.values
    k = np.flatnonzero(np.any(h[:, FEAT_SLOT:] != 0, axis=1))
    assert len(k) == 1 and sim.pair.ncontacts == 1
    d = sim.atom.data

    def forces(values):
        sim.pair.history.values[:] = values
        d["f"][:] = 0.0
        d["torque"][:] = 0.0
        sim.pair.compute(advance=False)
        return d["f"][:2].copy()

    cold = h.copy()
    cold[:, 6:] = 0.0
    fooled = h.copy()                        # every simplex point at the midpoint of the two centres
    mid = 0.5 * (d["x"][0] + d["x"][1])
    for slot, i in ((0, 0), (3, 1)):
        body = quat_to_matrix(d["quat"][i:i + 1])[0].T @ (mid - d["x"][i])
        for p in range(3):
            fooled[k, FEAT_SLOT + 6 * p + slot:FEAT_SLOT + 3 + 6 * p + slot] = body
    other = fooled.copy()
    other[k, TAG_SLOT] += 1.0                # made for other shapes
    f_cold = forces(cold)
    assert np.linalg.norm(forces(fooled)[0]) > 2.0 * np.linalg.norm(f_cold[0])
    assert np.array_equal(forces(other), f_cold)
    np.testing.assert_allclose(forces(h.copy()), f_cold, rtol=1e-6)


def test_touching_pair_skips_the_pretest_and_still_separates():
    """A pair that touched at its last call goes to GJK without the separating-axis pre-test (its shape tag
    is stored negative); moved apart it has no force, and the next call pre-tests it again. Moved back, the
    contact is the geometry's."""
    sim = two_bodies("cube 0.002", "0.00268 0.0004 0.0003")     # overlap ~1 % of the edge
    p, d = sim.pair, sim.atom.data
    sim.run(2)
    assert p.ncontacts == 1 and p.nsep == 0 and p.history.values[0, TAG_SLOT] < 0
    touching = d["x"][1].copy()
    d["x"][1] = touching + [0.0004, 0.0, 0.0]       # cores apart, bounding spheres still overlapping
    d["v"][:] = 0.0
    sim.run(1)
    assert p.ncontacts == 0 and p.nsep == 0 and not d["f"][:2].any()
    assert p.history.values[0, TAG_SLOT] > 0
    sim.run(1)
    assert p.nsep == 2              # pre-tested again and rejected (the run's setup pass, then its step)
    d["x"][1] = touching
    sim.run(0)
    ov, n, _ = geometry.contact(sim.shapes.shapes[0], d["x"][0], d["quat"][0], sim.shapes.shapes[0],
                                d["x"][1], d["quat"][1])
    assert p.ncontacts == 1 and ov > 0
    np.testing.assert_allclose(d["f"][0], 1e5 * ov * n, rtol=1e-6)


def test_scale_is_the_same_as_a_bigger_shape():
    a = make("""
shape c cube 0.001
create_atoms 1 single -0.002 0 0 shape c scale 2 density 2500 v 1 0 0 quat 0.3 0.5 0.1 0.7
create_atoms 1 single 0.002 0.0003 0.0002 shape c scale 2 density 2500 v -1 0 0 quat 0.9 0.1 0.2 0.3
pair_style convex/gjk
pair_coeff * * kn 1e5 en 0.7
fix 1 all nve/shape
timestep 1e-7
thermo 0
""")
    b = make("""
shape c cube 0.002 crust 0.00005
create_atoms 1 single -0.002 0 0 shape c density 2500 v 1 0 0 quat 0.3 0.5 0.1 0.7
create_atoms 1 single 0.002 0.0003 0.0002 shape c density 2500 v -1 0 0 quat 0.9 0.1 0.2 0.3
pair_style convex/gjk
pair_coeff * * kn 1e5 en 0.7
fix 1 all nve/shape
timestep 1e-7
thermo 0
""")
    assert a.shapes.crust[0] == 0.000025          # the default crust scales with the shape
    a.run(30000)
    b.run(30000)
    assert a.pair.ngjk > 0
    for name in ("x", "v", "omega"):
        np.testing.assert_allclose(a.gather(name), b.gather(name), rtol=1e-7, atol=1e-10)


def test_sphere_on_cube_face_and_mixed_types():
    """A sphere hits the centre of a cube face head-on: the normal restitution of the law, no torque."""
    sim = make("""
shape c cube 0.002
create_atoms 1 single 0 0 0 shape c density 2500
create_atoms 2 single 0 0 0.00202 radius 0.001 density 2500 v 0 0 -0.5
pair_style convex/gjk
pair_coeff * * kn 1e5 en 0.7
pair_coeff 1 2 kn 1e5 en 0.8
fix 1 all nve/shape
timestep 5e-8
thermo 0
""", ntypes=2)
    sim.run(3000)
    v = sim.gather("v")
    m = sim.gather("rmass")
    # relative velocity reversed with e = 0.8 (to the time-step accuracy), momentum conserved
    assert (v[1, 2] - v[0, 2]) / 0.5 == pytest.approx(0.8, rel=5e-3)
    assert (m * v[:, 2]).sum() == pytest.approx(-m[1] * 0.5, rel=1e-12)
    assert np.abs(sim.gather("omega")).max() < 1e-9


def test_pair_sphere_refuses_shapes():
    sim = make("shape c cube 0.002\ncreate_atoms 1 single 0 0 0 shape c\npair_style sphere\n"
               "pair_coeff * * kn 1e4 en 0.5\nfix 1 all nve/shape\ntimestep 1e-6\nthermo 0\n")
    with pytest.raises(DemError, match=r"some particles have a shape\n  hint: use pair_style convex/gjk for shaped particles"):
        sim.run(1)


# ----- walls -----------------------------------------------------------------------------------------
def test_cube_corner_on_wall_impulse_solution():
    """A cube falls corner first (tilted 30 deg about x then 20 deg about y) on a frictionless floor: the
    wall force acts at the deepest corner; stiff contact: the impulse solution of a point impact with the
    contact-point restitution of the law (see test_cylinder_impact)."""
    import dem.law
    from dem.shapes._support import rotation_matrix
    a, rho, en, kn = 0.002, 2500.0, 0.8, 1e8
    cx, sx, cy, sy = math.cos(math.radians(15)), math.sin(math.radians(15)), math.cos(math.radians(10)), math.sin(math.radians(10))
    q = np.array([cx * cy, sx * cy, cx * sy, -sx * sy])
    R = rotation_matrix(q)
    corner = cube(a).support(R.T @ np.array([0, 0, -1.0]))
    lever = R @ corner
    z0 = float(-lever[2]) + 2e-7
    sim = make(f"""
shape c cube {a}
create_atoms 1 single 0 0 {z0!r} shape c density {rho} v 0 0 -0.5 quat {' '.join(repr(float(v)) for v in q)}
fix 1 all nve/shape
fix w all wall/plane zplane 0 NULL kn {kn} en {en}
timestep 1e-8
thermo 0
""")
    sim.run(2000)
    m = rho * a ** 3
    inertia = m * a * a / 6
    r = lever
    # effective mass at the corner along z and its restitution under the law (gamma_n from m)
    k = np.cross(r, [0, 0, 1.0])
    meff = 1.0 / (1.0 / m + k @ k / inertia)
    z = dem.law.beta(en) * math.sqrt(m / meff)
    e = math.exp(-math.pi * z / math.sqrt(1 - z * z))
    P = (1 + e) * 0.5 * meff
    v_exp = np.array([0, 0, -0.5 + P / m])
    w_exp = np.cross(r, [0, 0, P]) / inertia
    assert sim.modify.find("w").ncontacts == 0
    np.testing.assert_allclose(sim.gather("v")[0], v_exp, atol=2e-3 * 0.5)
    np.testing.assert_allclose(sim.gather("omega")[0], w_exp, atol=2e-3 * np.abs(w_exp).max())


# ----- output, restart, MPI --------------------------------------------------------------------------
def test_dumps_write_true_shapes(tmp_path):
    import h5py
    sim = make(f"""
shape c cube 0.002
shape cy cylinder 0.001 0.003
create_atoms 1 single -0.004 0 0 shape c density 2500 quat 0.9 0.1 0.2 0.3
create_atoms 1 single 0.004 0 0 shape c scale 1.5 density 2500
create_atoms 1 single 0 0.004 0 radius 0.001 density 2500
create_atoms 1 single 0 -0.004 0 shape cy density 2500 quat 0.5 0.5 0.5 0.5
pair_style convex/gjk
pair_coeff * * kn 1e5 en 0.9
fix 1 all nve/shape
dump h all h5 10 {tmp_path}/out.h5
dump v all vtk 10 {tmp_path}/out_*.vtu
timestep 1e-6
thermo 0
run 10
""")
    sim.close()
    with h5py.File(tmp_path / "out.h5", "r") as f:
        s = f["shapes"]
        assert [x.decode() for x in s["name"][:]] == ["c", "cy"]
        assert list(s["kind"][:]) == [1, 2]
        assert s["mesh_0/vertices"].shape == (8, 3) and s["mesh_0/faces"].shape == (12, 3)
        g = f["frames/0000000010"]
        pts, ids = g["surface/points"][:], g["surface/id"][:]
        assert g["surface/triangles"].shape[0] == 12 + 12 + len(s["mesh_1/faces"])
        big = pts[ids == 2]                       # the scaled cube: edge 3 mm, axis-aligned
        np.testing.assert_allclose(big.max(0) - big.min(0), [0.003] * 3, rtol=1e-12)
    text = (tmp_path / "out.xdmf").read_text()
    assert 'TopologyType="Triangle"' in text and 'CollectionType="Spatial"' in text
    vtk = pytest.importorskip("vtk")
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(str(tmp_path / "out_10.vtu"))
    r.Update()
    out = r.GetOutput()
    ntri = 12 + 12 + len(sim.shapes.mesh(1)[1])
    assert out.GetNumberOfCells() == ntri + 1       # triangles of the three bodies + the sphere's point
    x = vtk.vtkXdmfReader()
    x.SetFileName(str(tmp_path / "out.xdmf"))
    x.Update()
    blocks = x.GetOutputDataObject(0)
    assert blocks.GetNumberOfBlocks() == 2


def test_restart_continues_bitwise(tmp_path):
    """Cubes, tetrahedra and cylinders: the contact history (springs, vertex pairs of polytopes, body-frame
    simplices of curved pairs) crosses a restart exactly."""
    script = """
shape c cube 0.002
shape t tetrahedron 0.003
shape y cylinder 0.001 0.002
region fill block -0.0098 0.0098 -0.0098 0.0098 -0.0098 0.0098
create_atoms 1 random 25 11 fill shape c quat random density 2500
set atom 1:8 shape t
set atom 9:14 shape y
pair_style convex/gjk
pair_coeff * * kn 1e4 en 0.5 mu 0.5 gamma_t 100 ks 3000
fix 1 all nve/shape
fix g all gravity 9.81 vector 0.2 0.1 -1
fix w all wall/plane zplane -0.01 NULL xplane -0.01 0.01 yplane -0.01 0.01 kn 1e4 en 0.5 mu 0.5 ks 3000
timestep 5e-6
thermo 0
"""
    ref = make(script)

    def held():      # pair and wall contacts and a curved pair's simplex: the history that crosses the restart
        return (ref.pair.ncontacts, ref.modify.find("w").ncontacts,
                np.count_nonzero(np.any(ref.pair.history.values[:, FEAT_SLOT + 3:] != 0, axis=1)))

    ref.run(14000)
    while ref.update.ntimestep < 30000 and not (held()[0] >= 3 and held()[1] >= 3 and held()[2] >= 1):
        ref.run(1000)    # curved contacts come and go while the pile settles
    ref.command(f"write_restart {tmp_path}/r.bin")
    *at_restart, curved = held()
    ref.run(3000)
    sim = dem.Simulation(screen=False)
    sim.commands(f"read_restart {tmp_path}/r.bin\n"     # the shapes come back from the restart
                 + script.split("set atom 9:14 shape y")[1])
    sim.run(3000)
    assert at_restart[0] >= 3 and at_restart[1] >= 3 and curved >= 1
    for name in ("x", "v", "omega", "angmom", "quat"):
        assert np.array_equal(sim.gather(name), ref.gather(name)), name


def test_pair_margins_change_no_result():
    """Pairs proved apart by the pre-test are skipped while their margin lasts (a cache of the neighbor list,
    cleared on every rebuild). A rebuild every step (no margin ever used) against the default: the same
    trajectory bit for bit (no sort, no periodic axis: see test_neighbor.py), so no contact was missed."""
    script = """
atom_modify sort 0 0
shape c cube 0.002
shape t tetrahedron 0.003
shape p pinacoid 0.003 0.0015 0.001 60
region fill block -0.0098 0.0098 -0.0098 0.0098 -0.0098 0.0098
create_atoms 1 random 40 7 fill shape c quat random density 2500
set atom 1:10 shape t
set atom 11:16 shape p
shape s sphere 0.001
set atom 17:20 shape s
pair_style convex/gjk
pair_coeff * * kn 1e4 en 0.5 mu 0.5 ks 3000
fix 1 all nve/shape
fix g all gravity 9.81 vector 0.2 0.1 -1
fix w all wall/plane zplane -0.01 NULL xplane -0.01 0.01 yplane -0.01 0.01 kn 1e4 en 0.5 mu 0.5
timestep 5e-6
thermo 0
"""
    a = make(script)
    b = make(script + "neigh_modify every 1 check no\n")
    a.run(40000)
    b.run(40000)
    assert b.neighbor.nbuilds == 40001 and a.neighbor.nbuilds < 2000
    assert a.pair.nskip > 10000 and b.pair.nskip == 0 and a.pair.ncontacts > 20
    for name in ("x", "v", "omega", "angmom", "quat"):
        assert np.array_equal(a.gather(name), b.gather(name)), name


def test_pair_move_bound_covers_every_point():
    """The margins rest on move[i] (pair convex/gjk's poses): no point of the scaled body moves farther
    between two calls. Random orientations turned by 1e-12 to 1 rad and shifted: the farthest moving vertex
    of a box (its corners are the farthest points from the centre) stays within the bound, and the rotation
    part is tight (the corner on the rotation's equator moves by nearly all of it)."""
    from dem_convex import _pair_convex
    rng = np.random.default_rng(5)
    n = 2000
    half = np.array([0.3, 0.2, 0.1])                   # box half-sizes; bounding radius |half|
    srad = np.array([np.linalg.norm(half)])
    q0 = rng.normal(size=(n, 4))
    q0 /= np.linalg.norm(q0, axis=1)[:, None]
    angle = 10.0 ** rng.uniform(-12, 0, n)
    axis = rng.normal(size=(n, 3))
    axis /= np.linalg.norm(axis, axis=1)[:, None]
    w, v = np.cos(angle / 2), np.sin(angle / 2)[:, None] * axis
    q1 = np.column_stack([w * q0[:, 0] - (v * q0[:, 1:]).sum(1),
                          w[:, None] * q0[:, 1:] + q0[:, :1] * v + np.cross(v, q0[:, 1:])])
    x0 = rng.normal(size=(n, 3))
    x1 = x0 + rng.normal(size=(n, 3)) * 10.0 ** rng.uniform(-12, -2, (n, 1))
    radius = srad[0] * rng.uniform(0.5, 2.0, n)        # scaled bodies
    from types import SimpleNamespace
    from dem._particles import ParticleView
    from dem.shapes._table import ShapeView
    core_params = np.zeros((1, 8))                      # a box core
    core_params[0, :3] = half
    one = {"kind": np.ones(1, np.int32), "params": core_params, "voff": np.zeros(1, np.int64),
           "nv": np.zeros(1, np.int32), "core_kind": np.ones(1, np.int32), "core_params": core_params,
           "core_voff": np.zeros(1, np.int64), "core_nv": np.zeros(1, np.int32), "crust": np.zeros(1),
           "crust_rel": np.zeros(1), "radius": srad, "is_sphere": np.zeros(1, np.int32), "verts": np.zeros((1, 3))}
    table = ShapeView(one)
    work = _pair_convex.ConvexWork()
    work.fit(n, 0)

    def particles(x, q):
        data = {"x": x, "quat": q, "radius": radius, "shape": np.zeros(n, np.int32)}
        for k in ("v", "omega", "f", "torque"):
            data[k] = np.zeros((n, 3))
        data.update(rmass=np.ones(n), type=np.ones(n, np.int32), mask=np.ones(n, np.int32))
        return ParticleView(SimpleNamespace(data=data, nlocal=n, nall=n))

    _pair_convex.poses(particles(x0, q0), table, work, True)
    r0 = work.rot[:n].copy()
    _pair_convex.poses(particles(x1, q1), table, work, False)
    rot, move = work.rot[:n], work.move[:n]
    corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * half
    p0 = np.einsum("nij,kj->nki", r0.reshape(n, 3, 3), corners) + x0[:, None, :]
    p1 = np.einsum("nij,kj->nki", rot.reshape(n, 3, 3), corners) + x1[:, None, :]
    moved = np.linalg.norm(p1 - p0, axis=2).max(axis=1)
    assert np.all(moved <= move)
    turn = 2.0 * np.sin(angle / 2) * radius            # the farthest a point at the bounding radius turns
    shift = np.linalg.norm(x1 - x0, axis=1)
    assert np.allclose(move - shift, turn, rtol=1e-6, atol=1e-13 * radius.max())


MPI_DRIVER = """
import sys
sys.path[:0] = {paths!r}
import numpy as np
import dem
sim = dem.Simulation(screen=False)
sim.commands('''
boundary p f fm
region box block 0 0.024 0 0.012 0 0.03
create_box 1 box
shape c cube 0.002
shape y cylinder 0.0009 0.002
region fill block 0 0.024 0 0.012 0 0.02
create_atoms 1 random 60 3 fill shape c quat random density 2500
set atom 1:15 shape y
set atom 16:25 radius 0.0011
pair_style convex/gjk
pair_coeff * * kn 1e4 en 0.5 mu 0.5 gamma_t 100 ks 3000
fix 1 all nve/shape
fix g all gravity 9.81 vector 0.3 0 -1
fix w all wall/plane zplane 0 NULL yplane 0 0.012 kn 1e4 en 0.5 mu 0.5 ks 3000
timestep 5e-6
thermo 0
run 8000
''')
out = {{k: sim.gather(k) for k in ("tag", "x", "v", "omega", "quat")}}
out["ngjk"] = np.array([sim.comm.sum(sim.pair.ngjk)])
if sim.comm.me == 0:
    np.savez(sys.argv[1], **out)
"""


@pytest.mark.skipif(MPIEXEC is None, reason="mpiexec not found")
def test_mpi_two_ranks_match_one(tmp_path):
    """Shapes on two ranks: ghosts carry shape, radius (scale) and orientation; the table is the same."""
    import dem_sphere
    paths = [str(Path(dem.__file__).resolve().parents[1]), str(Path(dem_sphere.__file__).resolve().parents[1])]
    (tmp_path / "drive.py").write_text(MPI_DRIVER.format(paths=paths, testdir=os.path.dirname(__file__)))
    env = dict(os.environ, OMP_NUM_THREADS="1")
    for n in (1, 2):
        cmd = [sys.executable, "drive.py", f"out{n}.npz"]
        if n > 1:
            cmd = [MPIEXEC, "-n", str(n)] + cmd
        res = subprocess.run(cmd, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=180)
        assert res.returncode == 0, res.stderr[-3000:]
    a, b = np.load(tmp_path / "out1.npz"), np.load(tmp_path / "out2.npz")
    assert np.array_equal(a["tag"], b["tag"])
    assert a["ngjk"][0] > 1000
    np.testing.assert_allclose(b["x"], a["x"], atol=1e-9 * 0.002)
    np.testing.assert_allclose(b["v"], a["v"], atol=1e-8 * np.abs(a["v"]).max())
    np.testing.assert_allclose(b["omega"], a["omega"], atol=1e-8 * np.abs(a["omega"]).max())
