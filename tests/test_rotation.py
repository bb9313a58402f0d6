"""Rotation of rigid bodies by Omelyan's revised leap-frog (fix nve/shape, Descantes 2022 eq. 8-11)."""
import numpy as np
import pytest
from scipy.integrate import solve_ivp

import dem
from dem.thermo import quat_to_matrix

SCRIPT = """
boundary f f f
region box block -1 1 -1 1 -1 1
create_box 1 box
create_atoms 1 single 0 0 0 radius 0.1 density 1000
fix rot all nve/shape
timestep {dt}
thermo 0
"""
INERTIA = np.array([1.0, 2.0, 3.0])          # asymmetric top (body frame, principal axes)
OMEGA0 = np.array([1.0, 0.05, 2.0])          # near the unstable intermediate axis: a demanding motion
Q0 = np.array([0.9, 0.1, 0.3, 0.2]) / np.linalg.norm([0.9, 0.1, 0.3, 0.2])


def top(dt):
    sim = dem.Simulation(screen=False)
    sim.commands(SCRIPT.format(dt=dt))
    a = sim.atom.data
    a["inertia"][0] = INERTIA
    a["quat"][0] = Q0
    a["omega"][0] = quat_to_matrix(Q0[None])[0] @ OMEGA0     # space-frame angular velocity
    return sim


def body_energy(a):
    rot = quat_to_matrix(a["quat"][:1])[0]
    lb = rot.T @ a["angmom"][0]
    return 0.5 * np.sum(lb ** 2 / a["inertia"][0])


def test_torque_free_top_conserves_momentum_and_energy_over_a_million_steps():
    sim = top(1e-3)
    sim.run(0)
    a = sim.atom.data
    l0 = a["angmom"][0].copy()
    e0 = body_energy(a)
    worst = 0.0
    for _ in range(10):
        sim.run(100_000)
        worst = max(worst, abs(body_energy(a) - e0) / e0)
    # no torque: J is updated by J += dt * 0, so it is conserved to the last bit; 1e-10 is the bound
    assert np.linalg.norm(a["angmom"][0] - l0) <= 1e-10 * np.linalg.norm(l0)
    # the implicit midpoint rotation conserves the kinetic energy of a free top up to round-off; a
    # drift would show round-off accumulating systematically: 1e-10 over 1e6 steps allows none
    assert worst < 1e-10
    # the Cayley update keeps the orientation a rotation: unit quaternion to round-off
    assert abs(np.linalg.norm(a["quat"][0]) - 1.0) < 1e-12


def reference_orientation(t_end):
    """Euler's equations + quaternion kinematics, integrated to 1e-12 by an adaptive Runge-Kutta."""
    def rhs(t, y):
        w, q = y[:3], y[3:]
        dw = (np.cross(INERTIA * w, w)) / INERTIA
        dq = 0.5 * np.array([-q[1] * w[0] - q[2] * w[1] - q[3] * w[2],
                             q[0] * w[0] + q[2] * w[2] - q[3] * w[1],
                             q[0] * w[1] - q[1] * w[2] + q[3] * w[0],
                             q[0] * w[2] + q[1] * w[1] - q[2] * w[0]])
        return np.concatenate([dw, dq])
    sol = solve_ivp(rhs, (0, t_end), np.concatenate([OMEGA0, Q0]), method="DOP853", rtol=1e-12, atol=1e-13)
    q = sol.y[3:, -1]
    return quat_to_matrix((q / np.linalg.norm(q))[None])[0]


def test_isotropic_body_turns_at_a_constant_rate():
    """A body with three equal moments (a cube, a regular tetrahedron) keeps its space-frame angular
    velocity; each step turns it by the Cayley angle 2 atan(|w| dt / 2) about w (the revised leap-frog's
    rotation, done in the space frame for such bodies). 3000 steps: round-off ~1e-13."""
    dt, n = 1e-3, 3000
    sim = top(dt)
    a = sim.atom.data
    a["inertia"][0] = 2.0
    w = np.array([1.0, -2.0, 0.5])
    a["omega"][0] = w
    sim.run(n)
    angle = n * 2.0 * np.arctan(np.linalg.norm(w) * dt / 2.0)
    axis = w / np.linalg.norm(w)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    turn = np.eye(3) + np.sin(angle) * k + (1.0 - np.cos(angle)) * k @ k
    expected = turn @ quat_to_matrix(Q0[None])[0]
    np.testing.assert_allclose(quat_to_matrix(a["quat"][:1])[0], expected, atol=1e-12)
    np.testing.assert_allclose(a["omega"][0], w, rtol=1e-14)


def test_orientation_converges_at_second_order():
    t_end = 2.0
    ref = reference_orientation(t_end)
    errors = []
    for dt in (1e-2, 5e-3, 2.5e-3):
        sim = top(dt)
        sim.run(int(round(t_end / dt)))
        rot = quat_to_matrix(sim.atom.data["quat"][:1])[0]
        errors.append(np.abs(rot - ref).max())
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    # a second-order scheme divides the error by 4 when dt halves: rate 2 within 0.2 (higher-order terms)
    assert np.all(np.abs(rates - 2.0) < 0.2), (errors, rates)
    assert errors[-1] < 1e-4


ROLL = """
boundary p p f
region box block -0.05 0.05 -0.05 0.05 0 0.05
create_box 1 box
create_atoms 1 single 0 0 0.0049995 v 0.5 0 0 radius 0.005 density 2500
pair_style sphere
pair_coeff * * kn 1e4 en 0.5 mu 0.3 gamma_t 2000
fix integrate all {fix}
fix gravity all gravity 9.81 vector 0 0 -1
fix floor all wall/plane zplane 0 NULL
timestep 1e-5
thermo 0
"""


@pytest.mark.parametrize("fix", ["nve/sphere", "nve/shape"])
def test_sliding_sphere_ends_rolling_at_five_sevenths(fix):
    """A sphere launched without spin on a frictional floor slides, friction spins it up, and it rolls
    at v = 5/7 v0 once the contact point sticks (angular momentum about the contact point is conserved)."""
    sim = dem.Simulation(screen=False)
    sim.commands(ROLL.format(fix=fix))
    sim.run(20000)
    a = sim.atom.data
    v, w = a["v"][0], a["omega"][0]
    # rolling without slip: v_x = omega_y R
    assert v[0] == pytest.approx(w[1] * 0.005, rel=2e-3)
    # 5/7 of 0.5 m/s; the contact is a stiff spring (overlap ~1e-6 m) so the lever differs from R by
    # delta/R ~ 2e-4 and the rolling speed by as much: 0.2 % covers it
    assert v[0] == pytest.approx(0.5 * 5.0 / 7.0, rel=2e-3)


def test_both_integrators_agree_for_spheres():
    """For an isotropic body the revised leap-frog reduces to omega += dt T / I (nve/sphere)."""
    out = []
    for fix in ("nve/sphere", "nve/shape"):
        sim = dem.Simulation(screen=False)
        sim.commands(ROLL.format(fix=fix))
        sim.run(3000)
        out.append((sim.atom.data["x"][0].copy(), sim.atom.data["omega"][0].copy()))
    assert out[0][0] == pytest.approx(out[1][0], rel=1e-12, abs=1e-15)
    assert out[0][1] == pytest.approx(out[1][1], rel=1e-9, abs=1e-12)
