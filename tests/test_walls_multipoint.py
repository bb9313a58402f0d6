"""fix wall/plane ... point multipoint: a polytope touches a wall at every vertex beyond it, each point with
the deepest overlap and a weight 1/alpha (Descantes 2022 eq. 3, alpha the number of points), instead of one
point. A face lying on the floor then pushes at its 4 corners, an edge at its 2 ends: no spurious torque,
no spin (the single deepest point of `point deepest` makes a cube landing flat spin up, Part III Fig. 12).
Bounds: symmetric points give torques that cancel to round-off (1e-20 N m here, where one point at a corner
would give 1e-5); the cube stays exactly unturned."""
import numpy as np
import pytest

import dem

BOX = """units si
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.001 0.02
create_box 1 box
shape c {shape}
create_atoms 1 single 0 0 {z} shape c density 1250 quat {quat}
pair_style convex/gjk
pair_coeff * * kn 1e5 en 0.5
fix integrate all nve/shape
fix gravity all gravity 9.81 vector 0 0 -1
fix floor all wall/plane zplane 0 NULL kn 1e5 en 0.5 point {point}
timestep 2e-6
"""


def cube_on_floor(point, quat="1 0 0 0", z=0.00101, shape="cube 0.002", steps=20000):
    sim = dem.Simulation(screen=False)
    sim.commands(BOX.format(point=point, quat=quat, z=z, shape=shape))
    sim.run(steps)
    return sim


def test_cube_resting_face_down_four_points_no_spin():
    """A cube dropped 10 um onto the floor, face down, left for 1e5 steps (0.2 s): it settles at rest on 4
    points; angular velocity exactly 0 throughout. The single deepest point spins it up."""
    sim = cube_on_floor("multipoint", steps=100000)
    wall = sim.modify.find("floor")
    assert wall.ncontacts == 4
    assert np.array_equal(sim.atom.local("omega")[0], np.zeros(3))
    assert np.array_equal(sim.atom.local("quat")[0], np.array([1.0, 0, 0, 0]))
    # at rest on the floor: the weight carried by the 4 points (overlap m g / kn)
    m = float(sim.atom.local("rmass")[0])
    assert sim.atom.local("x")[0, 2] == pytest.approx(0.001 - m * 9.81 / 1e5 + 0.0, rel=1e-6)
    single = cube_on_floor("deepest", steps=20000)
    assert np.abs(single.atom.local("omega")[0]).max() > 1e-3     # measured 5e-3 rad/s after 10 um


def test_cube_on_an_edge_two_points():
    """Turned 45 deg about x: the lowest edge (along x) touches at its 2 ends; the cube tips about x (a
    real rotation: it is balanced on the edge only in theory) and never about y or z."""
    c, s = float(np.cos(np.pi / 8)), float(np.sin(np.pi / 8))
    sim = cube_on_floor("multipoint", quat=f"{c!r} {s!r} 0 0", z=0.002 / 2 ** 0.5 - 1e-6, steps=1)
    assert sim.modify.find("floor").ncontacts == 2
    for _ in range(30):
        sim.run(100)
        w = sim.atom.local("omega")[0]
        assert w[1] == 0.0 and w[2] == 0.0


def test_tetrahedron_vertex_down_one_point():
    """A tetrahedron turned so that one vertex is lowest by far (0.4 mm below the next), 1 um into the
    floor: one point, the lowest vertex."""
    from dem.thermo import quat_to_matrix
    sim = dem.Simulation(screen=False)
    sim.commands(BOX.format(point="multipoint", quat="0.9 0.3 0.2 0.1", z=0.005, shape="tetrahedron 0.004"))
    V = sim.shapes.shapes[0].vertices @ quat_to_matrix(sim.atom.local("quat"))[0].T
    assert np.sort(V[:, 2])[1] - V[:, 2].min() > 4e-4
    sim.atom.local("x")[0, 2] = -V[:, 2].min() - 1e-6
    sim.run(1)
    assert sim.modify.find("floor").ncontacts == 1


def test_point_keyword_errors():
    with pytest.raises(dem.errors.DemError, match="deepest, centroid, multipoint"):
        dem.Simulation(screen=False).commands(BOX.format(point="vertices", quat="1 0 0 0", z=0.002,
                                                         shape="cube 0.002"))
