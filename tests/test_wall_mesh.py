"""fix wall/mesh: a triangle mesh wall against the equivalent planes and closed-form answers. A sphere
meets the triangles at their closest points, one contact per touched feature: rolling over a finely cut
floor it follows the plane's trajectory to round-off (crossing the shared edges without a jump), over a
convex edge or a vertex it is pushed along the line from that feature; a cube lies on a mesh floor on 4
points; a moving floor drags a sphere to the rolling speed 2U/7; restarts continue bit for bit."""
import math

import numpy as np
import pytest

import dem
from dem.errors import DemError
from dem_walls.mesh import weld

LAW = "kn 1e5 en 0.5 mu 0.3 gamma_t 2000 ks 28571"
R_SPHERE = 0.005


def floor(path, n, half=0.1, z=0.0):
    """The square [-half, half]^2 at height z cut into n x n squares of 2 triangles each (the diagonals
    alternate, so the sphere crosses edges of three directions)."""
    xs = np.linspace(-half, half, n + 1)
    tris = []
    for i in range(n):
        for j in range(n):
            a, b = (xs[i], xs[j], z), (xs[i + 1], xs[j], z)
            c, d = (xs[i + 1], xs[j + 1], z), (xs[i], xs[j + 1], z)
            tris += [(a, b, c), (a, c, d)] if (i + j) % 2 else [(a, b, d), (b, c, d)]
    weld(np.array(tris, dtype=float)).write_stl(str(path), binary=False)
    return str(path)


def sphere_sim(wall, x0="-0.05 0.0123 0.005", v="0.3 0.05 0", gravity="0.3 0 -1", box="-0.1 0.1 -0.1 0.1 -0.05 0.1"):
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary f f f
        region box block {box}
        create_box 1 box
        create_atoms 1 single {x0} radius {R_SPHERE} density 2500 v {v}
        pair_style sphere
        pair_coeff * * {LAW}
        fix integ all nve/sphere
        fix g all gravity 9.81 vector {gravity}
        {wall}
        timestep 1e-5
        thermo 0
    """)
    return sim


def track(sim, chunks=20, every=500):
    out = []
    for _ in range(chunks):
        sim.run(every)
        out.append(np.r_[sim.atom.local("x")[0], sim.atom.local("v")[0], sim.atom.local("omega")[0]])
    return np.array(out)


def test_sphere_rolls_over_a_cut_floor_as_on_a_plane(tmp_path):
    """A sphere thrown along a floor cut into 98 triangles, under gravity tilted by 0.3: it bounces, slides,
    rolls and crosses ~10 shared edges of three directions. Same trajectory as on `wall/plane` to 1e-12 m
    (measured 9e-14: round-off of a normal that is computed from the closest point instead of given): a
    second contact at an edge, or a normal tilted at it, would change the path by the overlap's order
    (1e-6 m) or more."""
    mesh = floor(tmp_path / "floor.stl", 7)
    plane = track(sphere_sim(f"fix w all wall/plane zplane 0 NULL {LAW}"))
    sim = sphere_sim(f"fix w all wall/mesh file {mesh} {LAW}")
    cut = track(sim)
    assert np.abs(plane[:, :3] - cut[:, :3]).max() < 1e-12
    assert np.abs(plane[:, 3:] - cut[:, 3:]).max() < 1e-9 * np.abs(plane[:, 3:]).max()
    assert abs(plane[-1, 0] - plane[0, 0]) > 0.03                  # it did cross several triangles
    assert sim.thermo_keyword("f_w[contacts]") == 1


def test_inclined_mesh_is_the_tilted_plane(tmp_path):
    """A floor turned by 20 deg about y (`rotate axis 0 1 0 angle 20`) under vertical gravity is the flat
    floor under gravity turned back by 20 deg (R^T g): the sphere's path turned back agrees to 1e-12 m (round-off of
    the turned coordinates)."""
    mesh = floor(tmp_path / "floor.stl", 10)
    th = math.radians(20.0)
    flat = track(sphere_sim(f"fix w all wall/mesh file {mesh} {LAW}", x0="0 0.01 0.005", v="0 0 0",
                            gravity=f"{math.sin(th)!r} 0 {-math.cos(th)!r}"), chunks=30)
    tilted = track(sphere_sim(f"fix w all wall/mesh file {mesh} rotate axis 0 1 0 angle 20 {LAW}",
                              x0=f"{0.005 * math.sin(th)!r} 0.01 {0.005 * math.cos(th)!r}", v="0 0 0",
                              gravity="0 0 -1"), chunks=30)
    rot = np.array([[math.cos(th), 0, math.sin(th)], [0, 1, 0], [-math.sin(th), 0, math.cos(th)]])
    assert np.abs(flat[:, :3] @ rot.T - tilted[:, :3]).max() < 1e-12
    assert abs(flat[-1, 0] - flat[0, 0]) > 0.02                    # it rolled over an edge or two


def test_convex_edge_and_vertex_push_along_the_line_from_the_feature(tmp_path):
    """A roof (two triangles meeting at a ridge along y, 30 deg each side) and a pyramid apex: a sphere
    whose centre lies beyond both faces touches only the ridge (or the apex); the force on it is along the
    line from its closest point on that feature to its centre, of the magnitude kn delta of one contact,
    to round-off."""
    h = 0.02
    roof = np.array([[(-0.05, -0.05, -0.05 * math.tan(math.pi / 6)), (0, -0.05, 0), (0, 0.05, 0)],
                     [(-0.05, -0.05, -0.05 * math.tan(math.pi / 6)), (0, 0.05, 0), (-0.05, 0.05, -0.05 * math.tan(math.pi / 6))],
                     [(0, -0.05, 0), (0.05, -0.05, -0.05 * math.tan(math.pi / 6)), (0.05, 0.05, -0.05 * math.tan(math.pi / 6))],
                     [(0, -0.05, 0), (0.05, 0.05, -0.05 * math.tan(math.pi / 6)), (0, 0.05, 0)]])
    apex = (0.0, 0.0, 0.0)
    base = [(-h, -h, -h), (h, -h, -h), (h, h, -h), (-h, h, -h)]
    pyramid = np.array([(base[k], base[(k + 1) % 4], apex) for k in range(4)])
    dist = R_SPHERE - 2e-6                        # 2 um of overlap, along a direction inside the feature's region
    ridge_dir = np.array([math.sin(math.radians(10)), 0.0, math.cos(math.radians(10))])   # within 30 deg
    apex_dir = np.array([0.1, -0.07, 1.0]) / math.sqrt(1.0149)                             # within 45 deg
    for tris, feature, direction in ((roof, np.array([0.0, 0.003, 0.0]), ridge_dir), (pyramid, np.zeros(3), apex_dir)):
        centre = feature + dist * direction
        path = tmp_path / "m.stl"
        weld(tris.astype(float)).write_stl(str(path), binary=False)
        sim = sphere_sim(f"fix w all wall/mesh file {path} kn 1e5 en 0.5",
                         x0=" ".join(repr(float(c)) for c in centre), v="0 0 0", gravity="0 0 -1")
        sim.run(0)
        sim.modify.find("w").compute(False)       # the forces where the sphere was put
        f = -np.array([sim.thermo_keyword(f"f_w[f{c}]") for c in "xyz"])     # on the sphere
        assert sim.thermo_keyword("f_w[contacts]") == 1
        assert np.abs(f - 1e5 * (R_SPHERE - dist) * direction).max() < 1e-12 * 1e5 * (R_SPHERE - dist)


def test_sphere_in_a_valley_touches_both_faces(tmp_path):
    """The roof upside down (a V): a sphere resting in it touches both faces, 2 contacts, forces
    symmetric about the valley's plane to round-off."""
    s = math.tan(math.pi / 6)
    vee = np.array([[(-0.05, -0.05, 0.05 * s), (0, 0.05, 0), (0, -0.05, 0)],
                    [(-0.05, -0.05, 0.05 * s), (-0.05, 0.05, 0.05 * s), (0, 0.05, 0)],
                    [(0, -0.05, 0), (0.05, 0.05, 0.05 * s), (0.05, -0.05, 0.05 * s)],
                    [(0, -0.05, 0), (0, 0.05, 0), (0.05, 0.05, 0.05 * s)]])
    path = tmp_path / "v.stl"
    weld(vee).write_stl(str(path), binary=False)
    z = R_SPHERE / math.cos(math.pi / 6) - 1e-6
    sim = sphere_sim(f"fix w all wall/mesh file {path} kn 1e5 en 0.5", x0=f"0 0 {z!r}", v="0 0 0",
                     gravity="0 0 -1")
    sim.run(0)
    sim.modify.find("w").compute(False)
    assert sim.thermo_keyword("f_w[contacts]") == 2
    assert abs(sim.thermo_keyword("f_w[fx]")) < 1e-12 * abs(sim.thermo_keyword("f_w[fz]"))


CUBE = """units si
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.001 0.02
create_box 1 box
shape c cube 0.002
create_atoms 1 single 0.0003 0.0002 {z} shape c density 1250 quat {quat}
pair_style convex/gjk
pair_coeff * * kn 1e5 en 0.5
fix integrate all nve/shape
fix gravity all gravity 9.81 vector 0 0 -1
{wall}
timestep 2e-6
"""


def test_cube_rests_on_a_mesh_floor_on_four_points(tmp_path):
    """A cube dropped 10 um face down on a floor of 18 triangles whose edges pass under it, `point
    multipoint`: it rests on its 4 corners, unturned (omega exactly 0), at the height of wall/plane's
    multipoint floor to 1e-12 m. Turned (quaternion 0.9 0.3 0.2 0.1) and dropped 1.5 mm, it lands and
    tips on a corner, then an edge, as on the plane: position to 1e-12 m, spin to 1e-6 relative (the
    contact point of a single-vertex hit comes from EPA here, from the vertex there)."""
    mesh = floor(tmp_path / "f.stl", 3, half=0.01)
    for quat, z, steps, tol_w in (("1 0 0 0", 0.00101, 30000, 0.0), ("0.9 0.3 0.2 0.1", 0.0025, 20000, 1e-6)):
        res = []
        for wall in (f"fix floor all wall/plane zplane 0 NULL kn 1e5 en 0.5 point multipoint",
                     f"fix floor all wall/mesh file {mesh} kn 1e5 en 0.5 point multipoint"):
            sim = dem.Simulation(screen=False)
            sim.commands(CUBE.format(z=z, quat=quat, wall=wall))
            sim.run(steps)
            res.append((sim.atom.local("x")[0].copy(), sim.atom.local("omega")[0].copy(),
                        sim.modify.find("floor").ncontacts))
        (xp, wp, np_), (xm, wm, nm) = res
        assert np.abs(xp - xm).max() < 1e-12
        assert np.abs(wp - wm).max() <= tol_w * max(np.abs(wp).max(), 1e-30)
        assert nm == np_
        if quat == "1 0 0 0":
            assert nm == 4 and np.array_equal(wm, np.zeros(3))


def test_moving_floor_drags_a_sphere_to_two_sevenths_of_its_speed(tmp_path):
    """A sphere set at rest on a floor moving at U along x (`linear U 0 0`): friction mu m g accelerates it
    and spins it up until its contact point moves with the floor: v = mu g t, omega r = (5/2) mu g t,
    no slip when v + omega r = U, then v = 2U/7 for good (I = 2/5 m r^2). Measured within 2e-4 U after
    0.1 s (the tangential spring's small oscillation at the stick transition); a floor that did not pass
    its velocity to the law would leave the sphere at rest."""
    U = 0.2
    mesh = floor(tmp_path / "f.stl", 2, half=0.5)
    sim = sphere_sim(f"fix w all wall/mesh file {mesh} linear {U} 0 0 {LAW}", x0=f"0 0 {R_SPHERE - 1e-6!r}",
                     v="0 0 0", gravity="0 0 -1", box="-0.5 0.5 -0.5 0.5 -0.05 0.1")
    sim.run(10000)
    v = sim.atom.local("v")[0]
    assert v[0] == pytest.approx(2.0 * U / 7.0, abs=2e-4 * U)
    assert abs(v[1]) < 1e-9
    assert sim.thermo_keyword("f_w[fx]") == pytest.approx(0.0, abs=1e-6)   # rolling: no force left
    # the same motion from a table (the floor at 0 at t = 0 and U at t = 1 s): the same run to round-off
    (tmp_path / "motion.txt").write_text(f"# t dx dy dz angle\n0 0 0 0 0\n1.0 {U!r} 0 0 0\n")
    table = sphere_sim(f"fix w all wall/mesh file {mesh} table {tmp_path / 'motion.txt'} {LAW}",
                       x0=f"0 0 {R_SPHERE - 1e-6!r}", v="0 0 0", gravity="0 0 -1", box="-0.5 0.5 -0.5 0.5 -0.05 0.1")
    table.run(10000)
    assert np.abs(table.atom.local("v")[0] - v).max() < 1e-12 * U


def test_turning_mesh_torque_and_drag(tmp_path):
    """A sphere resting on a turntable (the floor turning at 30 rpm about z through the origin), 2 cm from
    the axis: friction carries it round; the torque of the sphere on the table about the axis opposes the
    turning while it is being dragged (negative)."""
    mesh = floor(tmp_path / "f.stl", 2, half=0.1)
    sim = sphere_sim(f"fix w all wall/mesh file {mesh} turn origin 0 0 0 axis 0 0 1 rpm 30 {LAW}",
                     x0=f"0.02 0 {R_SPHERE - 1e-6!r}", v="0 0 0", gravity="0 0 -1")
    sim.run(200)
    assert sim.thermo_keyword("f_w[torque]") < 0.0
    sim.run(20000)
    x, v = sim.atom.local("x")[0], sim.atom.local("v")[0]
    assert np.dot(np.cross([0, 0, 1.0], x), v) > 0.0            # carried in the table's sense
    assert sim.thermo_keyword("f_w[angle]") == pytest.approx(math.pi * sim.update.time, rel=1e-12)


def test_restart_continues_bitwise(tmp_path):
    """Run 6000 steps straight, or 3000 + write_restart + read_restart + 3000: the same bits (the
    tangential springs live in the per-particle history, the mesh's motion in the fix's state)."""
    mesh = floor(tmp_path / "f.stl", 7)
    wall = f"fix w all wall/mesh file {mesh} linear 0.01 0 0 {LAW}"
    straight = sphere_sim(wall)
    straight.run(6000)
    first = sphere_sim(wall)
    first.run(3000)
    first.commands(f"write_restart {tmp_path / 'r.h5'}")
    second = dem.Simulation(screen=False)
    second.commands(f"""
        read_restart {tmp_path / 'r.h5'}
        pair_style sphere
        pair_coeff * * {LAW}
        fix integ all nve/sphere
        fix g all gravity 9.81 vector 0.3 0 -1
        {wall}
        timestep 1e-5
        thermo 0
        run 3000
    """)
    for name in ("x", "v", "omega"):
        assert np.array_equal(straight.atom.local(name), second.atom.local(name))


def test_errors_name_the_problem(tmp_path):
    mesh = floor(tmp_path / "f.stl", 1)
    (tmp_path / "bad.txt").write_text("0 0 0 0 0\n0 1 0 0 0\n")
    with pytest.raises(DemError, match=r"bad.txt:2: times must increase"):
        sphere_sim(f"fix w all wall/mesh file {mesh} table {tmp_path / 'bad.txt'} {LAW}")
    for name, text, message in (("nan.txt", "0 0 0 0 0\n1 nan 0 0 0\n", "nan.txt:2: not a finite number"),
                                ("inf.txt", "0 0 0 0 0\n1 0 0 0 -inf\n", "inf.txt:2: not a finite number"),
                                ("tnan.txt", "nan 0 0 0 0\n", "tnan.txt:1: not a finite number")):
        (tmp_path / name).write_text(text)
        with pytest.raises(DemError, match=message):
            sphere_sim(f"fix w all wall/mesh file {mesh} table {tmp_path / name} {LAW}")
    (tmp_path / "binary.txt").write_bytes(b"\x00\xff\xfe garbage")
    with pytest.raises(DemError, match="binary.txt' is not a text file"):
        sphere_sim(f"fix w all wall/mesh file {mesh} table {tmp_path / 'binary.txt'} {LAW}")
    (tmp_path / "good.txt").write_text("0 0 0 0 0\n1 1 0 0 0\n")
    with pytest.raises(DemError, match="cannot be combined with linear"):
        sphere_sim(f"fix w all wall/mesh file {mesh} table {tmp_path / 'good.txt'} linear 1 0 0 {LAW}")
    with pytest.raises(DemError, match="missing.stl"):
        sphere_sim(f"fix w all wall/mesh file {tmp_path / 'missing.stl'} {LAW}")
    with pytest.raises(DemError, match="unknown keyword 'sclae'.*scale"):
        sphere_sim(f"fix w all wall/mesh file {mesh} sclae 2 {LAW}")
    with pytest.raises(DemError, match="rotate axis AX AY AZ angle DEG"):
        sphere_sim(f"fix w all wall/mesh file {mesh} rotate 0 0 1 30 {LAW}")
    with pytest.raises(DemError, match="expected 'file FILE'"):
        sphere_sim(f"fix w all wall/mesh {mesh} {LAW}")


def open_box(path, lo, hi, n=4):
    """The floor and four sides of the box [lo, hi] as a mesh, each face cut into n x n squares of 2
    triangles (normals inward), written as binary STL."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    tris = []
    for axis, side in ((2, 0), (0, 0), (0, 1), (1, 0), (1, 1)):
        u, v = [d for d in range(3) if d != axis]
        s = np.linspace(0.0, 1.0, n + 1)
        for i in range(n):
            for j in range(n):
                quad = []
                for a, b in ((s[i], s[j]), (s[i + 1], s[j]), (s[i + 1], s[j + 1]), (s[i], s[j + 1])):
                    p = np.empty(3)
                    p[axis] = hi[axis] if side else lo[axis]
                    p[u] = lo[u] + a * (hi[u] - lo[u])
                    p[v] = lo[v] + b * (hi[v] - lo[v])
                    quad.append(p)
                tris += [(quad[0], quad[1], quad[2]), (quad[0], quad[2], quad[3])]
    # ASCII: exact coordinates (binary STL rounds them to float32); the mesh is two-sided: any orientation
    weld(np.array(tris)).write_stl(str(path), binary=False)
    return str(path)


BED = """
units           si
boundary        f f fm
region          box block 0 0.012 0 0.008 0 0.02
create_box      1 box
region          fill block 0 0.012 0 0.008 0 0.012
create_atoms    1 lattice fill bcc 0.00116 radius uniform 0.00045 0.0005 density 2500
pair_style      sphere
pair_coeff      * * kn 2000 en 0.5 mu 0.5 gamma_t 0 ks 571.4
fix             integrate all nve/sphere
fix             gravity all gravity 9.81 vector 0.3 0.2 -1
{walls}
timestep        2e-6
neighbor        0.0001 bin
thermo          0
"""


def test_open_box_of_triangles_holds_a_bed_as_its_planes(tmp_path):
    """A dense bed of 1300 spheres (bcc lattice, radii 0.45-0.5 mm) falling and sliding under tilted gravity
    in a box whose floor and four sides are planes, or a mesh of 160 triangles (edges under the bed, where
    floor and sides meet): after 2000 steps the same particles touch the walls and every position agrees
    within 1e-6 of a diameter (1e-9 m): measured 9e-12 m, the round-off of the normals
    (1e-16 m) grown by the bed's collisions; one contact too many or too few (at a shared edge under a
    sphere) moved the spheres by 1e-4 m. The bed pushes on the floor with its weight's share (fz of the
    mesh)."""
    mesh = open_box(tmp_path / "box.stl", (0, 0, 0), (0.012, 0.008, 0.03))
    runs = []
    for walls in ("fix walls all wall/plane xplane 0 0.012 yplane 0 0.008 zplane 0 NULL",
                  f"fix walls all wall/mesh file {mesh}"):
        sim = dem.Simulation(screen=False)
        sim.commands(BED.format(walls=walls))
        sim.run(2000)
        runs.append(sim)
    a, b = runs
    assert a.atom.natoms == b.atom.natoms > 400
    ta, tb = np.argsort(a.atom.local("tag")), np.argsort(b.atom.local("tag"))
    assert np.abs(a.atom.local("x")[ta] - b.atom.local("x")[tb]).max() < 1e-6 * 1e-3
    assert a.modify.find("walls").ncontacts == b.modify.find("walls").ncontacts > 20    # measured 39
    weight = float(a.atom.local("rmass").sum()) * 9.81
    assert 0.3 * weight < b.thermo_keyword("f_walls[fz]") * -1 < 1.5 * weight


def test_glued_composite_on_a_mesh_floor_as_on_the_plane(tmp_path):
    """A dumbbell of two glued spheres (radii 1 and 2 mm) dropped tilted on a floor of 18 triangles,
    `pair_style glued/convex` (Model B): each sphere component touches the floor, as on `wall/plane`
    (sphere components meet the triangles at their closest points, as spheres do). After bouncing and
    coming to rest on both spheres (60000 steps, 0.12 s), both walls carry 2 contacts and, frictionless,
    the positions agree to 1e-12 m (measured 1e-17). With friction, 1e-6 m (measured 7e-8): wall/plane
    tilts a composite's support direction by 1e-9 to break ties between equal points (dem/contact/
    _surface.pxd), which moves its contact points by 1e-12 m, and the frictional slide to rest grows such
    differences ~2000 times (a 1e-13 change of the start orientation moves the plane's own result 2e-10 m)."""
    mesh = floor(tmp_path / "f.stl", 3, half=0.01)
    for law, tol in (("kn 1e5 en 0.5", 1e-12), ("kn 1e5 en 0.5 mu 0.3 gamma_t 2000", 1e-6)):
        out = []
        for wall in (f"fix floor all wall/plane zplane 0 NULL {law}", f"fix floor all wall/mesh file {mesh} {law}"):
            sim = dem.Simulation(screen=False)
            sim.commands(f"""units si
                boundary f f f
                region box block -0.01 0.01 -0.01 0.01 -0.001 0.02
                create_box 1 box
                shape a glued component sphere 0.001 at 0 0 0 component sphere 0.002 at 0.003 0 0
                create_atoms 1 single 0.0004 0.0003 0.004 shape a density 2500 quat 0.95 0.1 0.25 0.1
                pair_style glued/convex
                pair_coeff * * kn 1e5 en 0.5
                fix integrate all nve/shape
                fix gravity all gravity 9.81 vector 0 0 -1
                {wall}
                timestep 2e-6
                run 60000""")
            out.append((sim.atom.local("x")[0].copy(), sim.modify.find("floor").ncontacts))
        (xp, cp), (xm, cm) = out
        assert np.abs(xp - xm).max() < tol
        assert cp == cm == 2


def test_walls_in_the_dumps(tmp_path, monkeypatch):
    """A turning floor written by dump vtk (a VTU per frame and wall, listed in the .pvd) and dump h5 (the
    XDMF a spatial collection of the particles and the wall), read back with VTK's readers: the wall's
    vertices where the turn has put them (to round-off)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
    xdmf = pytest.importorskip("vtkmodules.vtkIOXdmf2")
    mesh = floor(tmp_path / "f.stl", 2, half=0.05)
    monkeypatch.chdir(tmp_path)
    sim = sphere_sim(f"fix w all wall/mesh file {mesh} turn origin 0 0 0 axis 0 0 1 rpm 60 {LAW}\n"
                     "dump v all vtk 100 out/p_*.vtu\ndump h all h5 100 out/p.h5",
                     x0=f"0.02 0 {R_SPHERE - 1e-6!r}", v="0 0 0", gravity="0 0 -1")
    sim.run(200)
    angle = 2 * math.pi * sim.update.time                    # 60 rpm
    rot = np.array([[math.cos(angle), -math.sin(angle), 0], [math.sin(angle), math.cos(angle), 0], [0, 0, 1]])
    expected = sim.modify.find("w").mesh.vertices @ rot.T
    r = vtkXMLUnstructuredGridReader()
    r.SetFileName("out/p_200_w.vtu")
    r.Update()
    assert r.GetOutput().GetNumberOfCells() == 8
    assert np.abs(vtk_to_numpy(r.GetOutput().GetPoints().GetData()) - expected).max() < 1e-15
    assert 'part="1" file="p_200_w.vtu"' in (tmp_path / "out" / "p.pvd").read_text()
    x = xdmf.vtkXdmfReader()
    x.SetFileName("out/p.xdmf")
    x.UpdateInformation()
    x.UpdateTimeStep(sim.update.time)
    out = x.GetOutputDataObject(0)
    # the reader names the blocks after the grids, with the time index: particles[2], wall_w[2]
    blocks = {out.GetMetaData(k).Get(out.NAME()).split("[")[0]: out.GetBlock(k) for k in range(out.GetNumberOfBlocks())}
    assert set(blocks) == {"particles", "wall_w"}
    assert blocks["particles"].GetNumberOfPoints() == 1
    wall = blocks["wall_w"]
    assert wall.GetNumberOfCells() == 8
    assert np.abs(vtk_to_numpy(wall.GetPoints().GetData()) - expected).max() < 1e-15


@pytest.mark.parametrize("motion, message", [
    ("linear 0 0 1000", "fastest point moves 0.01 m in one step"),              # 1000 m/s x 1e-5 s
    ("turn origin 0 0 0 axis 0 0 1 rpm 60000", "fastest point moves 0.00889 m"),  # the corners at 0.141 m
    ("table TABLE", "fastest point moves 0.03 m in one step"),                  # 0.3 m in 0.1 ms
])
def test_a_mesh_too_fast_for_the_time_step_is_refused(tmp_path, motion, message):
    """A mesh moving more than the smallest radius (5 mm) in one step could pass through particles
    unseen: refused at the run, naming the fix; the same motions 100 times slower run."""
    mesh = floor(tmp_path / "f.stl", 2)
    (tmp_path / "fast.txt").write_text("0 0 0 0 0\n0.0001 0 0 0.3 0\n")
    (tmp_path / "slow.txt").write_text("0 0 0 0 0\n0.01 0 0 0.3 0\n")
    fast = motion.replace("TABLE", str(tmp_path / "fast.txt"))
    sim = sphere_sim(f"fix w all wall/mesh file {mesh} {fast} {LAW}")
    with pytest.raises(DemError, match=f"fix w wall/mesh: its {message}.* than the smallest particle's radius 0.005"):
        sim.run(1)
    slow = motion.replace("1000", "10").replace("60000", "600").replace("TABLE", str(tmp_path / "slow.txt"))
    sphere_sim(f"fix w all wall/mesh file {mesh} {slow} {LAW}").run(1)
