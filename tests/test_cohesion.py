"""Cohesive normal parts (dem/law/normal.pxd: `normal jkr`, `normal dmt`) against their closed forms.

JKR (Johnson, Kendall & Roberts 1971; the forms of Johnson's Contact Mechanics with Y* the effective
modulus): the contact radius a gives
    delta(a) = a^2 / R* - sqrt(2 pi w a / Y*),     F(a) = 4 Y* a^3 / (3 R*) - sqrt(8 pi w Y* a^3)
(repulsive > 0). Written here from the textbook: a of a given delta is the largest real root of the
quartic in sqrt(a), found by numpy.roots (the code uses its own Newton iteration). Load-controlled pull-off
at dF/da = 0: F = -3/2 pi w R*; the bond breaks where d delta / da = 0: delta_c = -3/4 (pi^2 w^2 R* /
Y*^2)^(1/3), F = -5/6 pi w R*. A pair with no damping (en 1) at rest feels exactly F(delta): tolerance 1e-6
(the roots and the code's Newton agree to round-off, ~1e-12).

Collisions (Thornton & Ning 1998's model of elastic adhesive spheres): the only loss of an elastic JKR
contact is the hysteresis between touch (the bond forms at delta = 0) and pull-off (it breaks at delta_c):
W = -int_{delta_c}^{0} F d delta along the branch (scipy quadrature here). Below the sticking velocity v_s,
1/2 m* v_s^2 = W, the pair stays bonded; above it rebounds with e = sqrt(1 - (v_s / v)^2). Leap-frog meets
the two force jumps (to -4/3 pi w R* at touch, from -5/6 pi w R* at pull-off) within a step, an error of
order |F| v dt per jump: at 2000 steps per contact the measured e is within 0.3 % (tolerance 2 %, the
issue's).

DMT (Derjaguin, Muller & Toporov 1975): Hertz minus 2 pi w R* while in contact, zero apart: pull-off
-2 pi w R* at delta -> 0+.

Liquid bridge (`cohesion capillary`): Willett, Adams, Johnson & Seville (2000)'s closed form for two
equal spheres of radius R at surface separation S, F = 2 pi R gamma cos(theta) / (1 + 1.05 S^ + 2.5 S^2),
S^ = S sqrt(R / V), with R = 2 R* for other pairs (a wall: 2 R_i), formed at touch and ruptured at
(1 + theta/2) V^(1/3) (Lian, Thornton & Adams 1993). A pair at rest feels exactly F: tolerance 1e-9."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

import dem

R, RHO, E, NU, W = 1e-4, 2500.0, 1e7, 0.3, 0.05
M = RHO * 4.0 / 3.0 * math.pi * R ** 3
YSTAR = E / (2.0 * (1.0 - NU * NU))
RS = 0.5 * R                                       # R* of two equal spheres
MS = 0.5 * M
DELTA_C = -0.75 * (math.pi ** 2 * W ** 2 * RS / YSTAR ** 2) ** (1.0 / 3.0)
JKR = f"normal jkr E {E} nu {NU} w {W} en 1 mu 0"


def jkr_a(delta):
    """The stable branch's contact radius at delta: the largest root x of x^4 - R* sqrt(2 pi w / Y*) x -
    R* delta = 0, a = x^2."""
    p = RS * math.sqrt(2 * math.pi * W / YSTAR)
    roots = np.roots([1.0, 0.0, 0.0, -p, -RS * delta])
    x = max(r.real for r in roots if abs(r.imag) < 1e-9 * abs(r))
    return x * x


def jkr_force(a):
    return 4 * YSTAR * a ** 3 / (3 * RS) - math.sqrt(8 * math.pi * W * YSTAR * a ** 3)


def jkr_delta(a):
    return a * a / RS - math.sqrt(2 * math.pi * W * a / YSTAR)


def pair(law, extra="", radius=R):
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
boundary f f f
region box block {-10 * radius} {10 * radius} {-10 * radius} {10 * radius} {-10 * radius} {10 * radius}
create_box 1 box
create_atoms 1 single {-1.1 * radius!r} 0 0 radius {radius} density {RHO}
create_atoms 1 single {1.1 * radius!r} 0 0 radius {radius} density {RHO}
pair_style sphere
pair_coeff * * {law}
neighbor 0 bin
timestep 1e-9
thermo 0
{extra}""")
    return sim


def on_a_wall(law, radius):
    """A sphere touching a floor of the law `law` (no integrator: it stays where it is put)."""
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
boundary f f f
region box block {-10 * radius} {10 * radius} {-10 * radius} {10 * radius} 0 {20 * radius}
create_box 1 box
create_atoms 1 single 0 0 {radius!r} radius {radius} density {RHO}
pair_style sphere
pair_coeff * * kn 1 en 1
fix w all wall/plane zplane 0 NULL {law}
timestep 1e-9
thermo 0
""")
    return sim, sim.modify.find("w")


def force_at(sim, delta, radius=R):
    """Place the pair at overlap delta (at rest) and return the x force on the particle at +x, and the
    contacts, after one step (no integrator: the particles stay where they are put)."""
    tags = sim.atom.local("tag")
    x = sim.atom.local("x")
    half = radius - 0.5 * delta
    x[:] = [[-half, 0, 0] if t == 1 else [half, 0, 0] for t in tags]
    sim.run(1)
    f = sim.atom.local("f")[np.argsort(sim.atom.local("tag"))]
    assert abs(f[0, 0] + f[1, 0]) <= 1e-12 * abs(f[1, 0]) + 1e-30
    return f[1, 0], sim.pair.ncontacts


def test_jkr_force_follows_the_closed_form_with_hysteresis():
    sim = pair(JKR)
    # apart, never touched: no force even within the pull-off distance
    assert force_at(sim, 0.5 * DELTA_C) == (0.0, 0)
    # loading and unloading along one branch; apart (delta < 0) it holds while bonded
    for delta in [1e-3 * RS, 3e-4 * RS, 1e-5 * RS, 0.0, 0.3 * DELTA_C, 0.9 * DELTA_C, 0.999 * DELTA_C]:
        fx, n = force_at(sim, delta)
        expected = jkr_force(jkr_a(delta))
        assert n == 1
        assert abs(fx / expected - 1) < 1e-6, (delta, fx, expected)
    # beyond delta_c the bond breaks; coming back within reach it does not re-form until touch
    assert force_at(sim, 1.001 * DELTA_C) == (0.0, 0)
    assert force_at(sim, 0.5 * DELTA_C) == (0.0, 0)
    fx, n = force_at(sim, 1e-6 * RS)
    assert n == 1 and fx < 0      # touch: the bond forms, the force jumps to the attractive branch


def test_jkr_pull_off_forces():
    sim = pair(JKR)
    force_at(sim, 1e-4 * RS)                         # touch first
    ap = (9 * math.pi * W * RS ** 2 / (8 * YSTAR)) ** (1.0 / 3.0)     # dF/da = 0
    fx, _ = force_at(sim, jkr_delta(ap))
    assert abs(fx / (-1.5 * math.pi * W * RS) - 1) < 1e-6, fx
    ac = (math.pi * W * RS ** 2 / (8 * YSTAR)) ** (1.0 / 3.0)         # d delta / da = 0
    assert abs(jkr_delta(ac) / DELTA_C - 1) < 1e-12
    fx, _ = force_at(sim, DELTA_C * (1 - 1e-9))
    assert abs(fx / (-5.0 / 6.0 * math.pi * W * RS) - 1) < 1e-4, fx    # sqrt-flat near delta_c


def sticking_velocity():
    a0, ac = jkr_a(0.0), (math.pi * W * RS ** 2 / (8 * YSTAR)) ** (1.0 / 3.0)
    dd = lambda a: 2 * a / RS - 0.5 * math.sqrt(2 * math.pi * W / (YSTAR * a))    # noqa: E731
    loss = -quad(lambda a: jkr_force(a) * dd(a), ac, a0, epsabs=0, epsrel=1e-12)[0]
    return math.sqrt(2 * loss / MS)


def collide(v, steps=2000):
    """Head-on collision at relative speed v; returns (rebound speed / v, still bonded)."""
    vs = sticking_velocity()
    dmax = (15 * MS * max(v, vs) ** 2 / (16 * YSTAR * math.sqrt(RS))) ** 0.4
    dt = 2.87 * dmax / max(v, vs) / steps
    sim = pair(JKR, f"fix 1 all nve/sphere\ntimestep {dt!r}")
    sim.atom.local("x")[:] = [[-R - 1e-8, 0, 0] if t == 1 else [R + 1e-8, 0, 0] for t in sim.atom.local("tag")]
    sim.atom.local("v")[:] = [[0.5 * v, 0, 0] if t == 1 else [-0.5 * v, 0, 0] for t in sim.atom.local("tag")]
    sim.run(40 * steps)
    vel = sim.atom.local("v")[np.argsort(sim.atom.local("tag"))]
    return (vel[1, 0] - vel[0, 0]) / v, sim.pair.ncontacts == 1


@pytest.mark.parametrize("ratio", [1.5, 3.0])
def test_jkr_collision_rebounds_with_thornton_ning_restitution(ratio):
    vs = sticking_velocity()
    e, bonded = collide(ratio * vs)
    assert not bonded
    expected = math.sqrt(1 - 1 / ratio ** 2)
    assert abs(e / expected - 1) < 0.02, (e, expected)


def test_jkr_collision_below_the_sticking_velocity_sticks():
    e, bonded = collide(0.8 * sticking_velocity())
    assert bonded


def test_dmt_pull_off_and_force():
    sim = pair(f"normal dmt E {E} nu {NU} w {W} en 1 mu 0")
    fa = 2 * math.pi * W * RS
    for delta in [1e-12 * RS, 1e-4 * RS, 1e-2 * RS]:
        fx, n = force_at(sim, delta)
        expected = 4.0 / 3.0 * YSTAR * math.sqrt(RS) * delta ** 1.5 - fa
        assert n == 1 and abs(fx / expected - 1) < 1e-9, (delta, fx, expected)
    assert force_at(sim, -1e-9 * RS) == (0.0, 0)    # no force apart, bonded or not


def test_jkr_on_a_wall_holds_until_its_pull_off_distance():
    """A sphere on a JKR wall (R* = R): the same branch with R* = R, held beyond touch until delta_c."""
    dc = -0.75 * (math.pi ** 2 * W ** 2 * R / YSTAR ** 2) ** (1.0 / 3.0)
    sim, wall = on_a_wall(JKR, R)
    p = R * math.sqrt(2 * math.pi * W / YSTAR)

    def at(delta):
        sim.atom.local("x")[0, 2] = R - delta
        sim.run(1)
        return sim.atom.local("f")[0, 2], wall.ncontacts

    assert at(0.5 * dc) == (0.0, 0)
    at(1e-4 * R)
    for delta in (0.5 * dc, 0.99 * dc):
        roots = np.roots([1.0, 0.0, 0.0, -p, -R * delta])
        a = max(r.real for r in roots if abs(r.imag) < 1e-9 * abs(r)) ** 2
        expected = 4 * YSTAR * a ** 3 / (3 * R) - math.sqrt(8 * math.pi * W * YSTAR * a ** 3)
        fz, n = at(delta)
        assert n == 1 and abs(fz / expected - 1) < 1e-6, (delta, fz, expected)
    assert at(1.01 * dc) == (0.0, 0)
    assert at(0.5 * dc) == (0.0, 0)


# a water bridge between glass beads of Willett et al. 2000's size: R = 2.381 mm, V = 74.2 nl
# (V / R^3 = 0.0055), gamma 20.6 mN/m (their silicone oil), contact angle 10 degrees
RB, VB, GAMMA, THETA = 2.381e-3, 74.2e-12, 20.6e-3, 10.0
BRIDGE = (f"kn 1e4 en 1 cohesion capillary liquid_volume {VB} surface_tension {GAMMA} "
          f"contact_angle {THETA}")


def willett(s, radius):
    """Willett et al. (2000), the closed form for two equal spheres of `radius` at surface separation s."""
    sh = s * math.sqrt(radius / VB)
    return 2 * math.pi * radius * GAMMA * math.cos(math.radians(THETA)) / (1 + 1.05 * sh + 2.5 * sh * sh)


def test_capillary_bridge_force_and_rupture_on_a_pair():
    """Two equal spheres (R* = R/2: Willett's R is 2 R*) with a Hooke contact and a bridge: apart, the
    force is Willett's to round-off (tolerance 1e-9); in contact, kn delta minus the bridge at touch. The
    bridge forms at touch and breaks at S_c = (1 + theta/2) V^(1/3) (Lian et al. 1993)."""
    sc = (1 + 0.5 * math.radians(THETA)) * VB ** (1.0 / 3.0)
    sim = pair(BRIDGE, radius=RB)
    assert force_at(sim, -0.5 * sc, RB) == (0.0, 0)          # apart, never touched: no bridge
    fx, n = force_at(sim, 1e-6 * RB, RB)
    assert n == 1 and abs(fx / (1e4 * 1e-6 * RB - willett(0, RB)) - 1) < 1e-9
    for s in (0.0, 0.1 * sc, 0.5 * sc, 0.99 * sc):
        fx, n = force_at(sim, -s, RB)
        assert n == 1 and abs(fx / -willett(s, RB) - 1) < 1e-9, (s, fx, -willett(s, RB))
    assert force_at(sim, -1.01 * sc, RB) == (0.0, 0)         # ruptured
    assert force_at(sim, -0.5 * sc, RB) == (0.0, 0)          # and gone until the next touch


def test_capillary_bridge_on_a_wall():
    """Sphere and plane: Willett's R is 2 R_i (4 pi R gamma cos(theta) at touch), S^ = S sqrt(2 R_i / V)."""
    sc = (1 + 0.5 * math.radians(THETA)) * VB ** (1.0 / 3.0)
    sim, wall = on_a_wall(BRIDGE, RB)

    def at(gap):
        sim.atom.local("x")[0, 2] = RB + gap
        sim.run(1)
        return sim.atom.local("f")[0, 2], wall.ncontacts

    assert at(0.5 * sc) == (0.0, 0)
    at(-1e-7)
    for s in (0.2 * sc, 0.8 * sc):
        fz, n = at(s)
        assert n == 1 and abs(fz / -willett(s, 2 * RB) - 1) < 1e-9, (s, fz)
    assert at(1.01 * sc) == (0.0, 0)


def test_sjkr_pulls_with_the_contact_area_in_contact_only():
    """cohesion sjkr: Hertz minus k A, A = 2 pi R* delta (the crossing circle of the two surfaces to first
    order: pi (R delta - delta^2/4) for equal spheres of radius R = 2 R*); nothing apart. Tolerance 1e-9."""
    k = 2e5
    sim = pair(f"model hertz E {E} nu {NU} en 1 mu 0 cohesion sjkr cohesion_energy_density {k}")
    for delta in (1e-6 * RS, 1e-3 * RS, 1e-2 * RS):
        fx, n = force_at(sim, delta)
        expected = 4.0 / 3.0 * YSTAR * math.sqrt(RS) * delta ** 1.5 - k * 2 * math.pi * RS * delta
        assert n == 1 and abs(fx / expected - 1) < 1e-9, (delta, fx, expected)
        exact = math.pi * (R * delta - delta ** 2 / 4)         # the exact crossing circle: first order agrees
        assert abs(2 * math.pi * RS * delta / exact - 1) < delta / R
    assert force_at(sim, -1e-6 * RS) == (0.0, 0)
