"""The elastic-plastic spring-dashpot rolling resistance (`rolling epsd`, dem/law/rolling.pxd; Ai, Chen,
Rotter & Ooi, Powder Technol. 206 (2011) 269, model C) against its closed form.

Without friction (mu 0) a spinning sphere does not roll: it turns about its centre, and the rolling torque
is the only torque. Below the plastic limit that is a damped torsional oscillator,
    I theta'' = -k_r theta - C_r theta',   k_r = 2.25 kn mu_r^2 R*^2,  C_r = eta_r 2 sqrt(I_r k_r),
with I = 2/5 m r^2 the sphere's inertia about its centre and I_r = 1 / sum 1 / (I + m r^2) the model's
rolling inertia about the contact (7/5 m r^2 on a wall): the spin follows
    omega(t) = omega0 e^(-z w0 t) (cos(wd t) - z / sqrt(1 - z^2) sin(wd t)),  w0^2 = k_r / I,
    z = C_r / (2 sqrt(k_r I)), wd = w0 sqrt(1 - z^2).
The incremental spring (M += -k_r omega dt with the stored spin) is leap-frog with the stored spin half a
step ahead of the spring's angle: undamped, the error is O((w0 dt)^2), w0 dt = 2.6e-3 here, measured
3e-6 omega0. The dashpot reads the same stored spin, half a step from the angle, a first-order error of
about z w0 dt: measured 5.6e-4 omega0 at eta_r 0.3 (z = 0.56). Tolerance 1e-3 omega0.
Beyond the limit the spring holds M_m = mu_r R* |F_n| and the dashpot is off (model C): the spin falls
linearly at M_m / I (measured to 1e-9; tolerance 1e-6)."""
import math

import numpy as np
import pytest

import dem

R, RHO, KN = 0.002, 2500.0, 1e4
M = RHO * 4.0 / 3.0 * math.pi * R ** 3
I = 0.4 * M * R * R


def oscillator(omega0, kr, cr, inertia, t):
    w0 = math.sqrt(kr / inertia)
    z = cr / (2 * math.sqrt(kr * inertia))
    wd = w0 * math.sqrt(1 - z * z)
    return omega0 * math.exp(-z * w0 * t) * (math.cos(wd * t) - z / math.sqrt(1 - z * z) * math.sin(wd * t))


def bonded_jkr_pair(r, rho, E, nu, w, dt, couple):
    """Two JKR spheres of radius r touching along x at zero net load (contact radius a0 = (9 pi w R*^2 /
    (2 Y*))^(1/3), overlap a0^2 / (3 R*)), at rest, with `couple` (the rolling or twisting words) after
    `normal jkr ... en 1 mu 0`: (sim, a0)."""
    ystar, rs = E / (2 * (1 - nu * nu)), 0.5 * r
    a0 = (9 * math.pi * w * rs ** 2 / (2 * ystar)) ** (1.0 / 3.0)
    delta0 = a0 * a0 / (3 * rs)
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
boundary f f f
region box block -0.001 0.001 -0.001 0.001 -0.001 0.001
create_box 1 box
create_atoms 1 single {-r + 0.5 * delta0!r} 0 0 radius {r} density {rho}
create_atoms 1 single {r - 0.5 * delta0!r} 0 0 radius {r} density {rho}
pair_style sphere
pair_coeff * * normal jkr E {E} nu {nu} w {w} en 1 mu 0 {couple}
fix 1 all nve/sphere
timestep {dt!r}
thermo 0
""")
    return sim, a0


def sphere_on_floor(mu_r, eta, g, omega0, dt):
    """A sphere resting on a Hooke floor at its static overlap m g / kn, spun about x."""
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
boundary f f f
region box block -0.01 0.01 -0.01 0.01 0 0.01
create_box 1 box
create_atoms 1 single 0 0 {R - M * g / KN!r} radius {R} density {RHO}
pair_style sphere
pair_coeff * * kn {KN} en 0.5
fix floor all wall/plane zplane 0 NULL kn {KN} en 0.5 mu 0 rolling epsd mu_roll {mu_r} eta_roll {eta}
fix g all gravity {g} vector 0 0 -1
fix 1 all nve/sphere
timestep {dt!r}
thermo 0
""")
    sim.atom.local("omega")[0] = [omega0, 0, 0]
    return sim


@pytest.mark.parametrize("eta", [0.0, 0.3])
def test_epsd_spring_and_damping_on_a_wall(eta):
    mu_r, g, omega0, dt = 0.1, 9.81, 0.1, 1e-6
    kr = 2.25 * KN * mu_r ** 2 * R ** 2
    cr = eta * 2 * math.sqrt(1.4 * M * R * R * kr)
    sim = sphere_on_floor(mu_r, eta, g, omega0, dt)
    sim.run(0)
    period = 2 * math.pi / math.sqrt(kr / I)
    # below the limit all along: the largest spring torque ~ sqrt(k_r I) omega0 < M_m
    assert math.sqrt(kr * I) * omega0 < 0.5 * mu_r * R * M * g
    t = 0.0
    worst = 0.0
    for _ in range(8):
        n = int(0.25 * period / dt)
        sim.run(n)
        t += n * dt
        w = sim.atom.local("omega")[0, 0]
        # the incremental spring takes the stored spin as the one half a step ahead of its angle
        worst = max(worst, abs(w - oscillator(omega0, kr, cr, I, t + 0.5 * dt)))
    assert worst < 1e-3 * omega0, worst
    assert np.allclose(sim.atom.local("omega")[0, 1:], 0.0)


def test_epsd_plastic_limit_decelerates_at_the_limit_torque():
    mu_r, g, omega0, dt = 0.5, 98.1, 30.0, 1e-6
    mmax = mu_r * R * M * g
    sim = sphere_on_floor(mu_r, 0.3, g, omega0, dt)
    sim.run(100)
    w1 = sim.atom.local("omega")[0, 0]
    sim.run(200)
    w2 = sim.atom.local("omega")[0, 0]
    slope = (w2 - w1) / (200 * dt)
    assert abs(slope / (-mmax / I) - 1) < 1e-6, (slope, -mmax / I)


def test_epsd_between_two_adhesive_spheres_at_zero_load():
    """Two JKR spheres bonded at zero net load spun in opposite senses: the limit is mu_r R* |F_n + 2 F_c|
    = mu_r R* 3 pi w R* (the adhesion resists rolling), the relative spin a torsional oscillator with
    I / 2 (both spheres turn), I_r = 7/10 m r^2 and kn = 4/3 Y* a0 at the zero-load contact radius."""
    r, rho, E, nu, w, mu_r, eta, omega0, dt = 1e-4, 2500.0, 1e7, 0.3, 0.05, 0.1, 0.3, 20.0, 2e-7
    m = rho * 4.0 / 3.0 * math.pi * r ** 3
    inertia = 0.4 * m * r * r
    ystar, rs = E / (2 * (1 - nu * nu)), 0.5 * r
    sim, a0 = bonded_jkr_pair(r, rho, E, nu, w, dt, f"rolling epsd mu_roll {mu_r} eta_roll {eta}")
    kr = 2.25 * (4.0 / 3.0 * ystar * a0) * mu_r ** 2 * rs ** 2
    cr = eta * 2 * math.sqrt(0.7 * m * r * r * kr)
    assert math.sqrt(2 * kr * inertia) * omega0 < 0.5 * mu_r * rs * 3 * math.pi * w * rs
    sim.atom.local("omega")[:] = [[0, omega0, 0] if t == 1 else [0, -omega0, 0] for t in sim.atom.local("tag")]
    sim.run(0)
    period = 2 * math.pi / math.sqrt(2 * kr / inertia)
    t, worst = 0.0, 0.0
    for _ in range(8):
        n = int(0.25 * period / dt)
        sim.run(n)
        t += n * dt
        om = sim.atom.local("omega")[np.argsort(sim.atom.local("tag"))]
        rel = om[0, 1] - om[1, 1]
        worst = max(worst, abs(rel - oscillator(2 * omega0, kr, cr, 0.5 * inertia, t + 0.5 * dt)))
    assert worst < 1e-3 * 2 * omega0, worst
    assert sim.pair.ncontacts == 1
