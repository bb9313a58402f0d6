"""Hertz-Mindlin with material parameters (LIGGGHTS's `model hertz tangential history`): the effective
moduli of the Hertz family's rows (normal.pxd: hertz, jkr, dmt; tangential.pxd: mindlin), the closed-form
Hertz impact (contact time, largest overlap) that the time-step check and the tests use, and the Hooke
stiffness equivalent to Hertz at an impact speed (for Grains3D-style tables, `dem-hooke-from-hertz`).

Two materials: Y* = 1 / ((1 - nu1^2) / E1 + (1 - nu2^2) / E2), G* = 1 / ((2 - nu1) / G1 + (2 - nu2) / G2),
G = E / (2 (1 + nu)) (LIGGGHTS, doc/gran_model_hertz.html of github.com/CFDEMproject/LIGGGHTS-PUBLIC);
one material (both bodies of a line that gives E and nu, and a wall of that line): Y* = E / (2 (1 - nu^2)),
G* = G / (2 (2 - nu))."""
import math

from dem.errors import DemError

# 2 times the integral of dx / sqrt(1 - x^(5/2)) over [0, 1]: an elastic Hertz impact lasts this times
# delta_max / v (the familiar t_c = 2.87 (m*^2 / (R* Y*^2 v))^(1/5) is 2.8682... rounded)
IMPACT_TIME = 2.0 * math.gamma(1.4) * math.sqrt(math.pi) / math.gamma(0.9)
CHECK_SPEED = 1.0    # m/s: the least impact speed the time-step check assumes (particles at rest at setup)


def moduli(E, nu):
    """(Y*, G*) of two bodies of the same material (module docstring)."""
    G = E / (2.0 * (1.0 + nu))
    return E / (2.0 * (1.0 - nu * nu)), G / (2.0 * (2.0 - nu))


def mixed_moduli(E1, nu1, E2, nu2):
    """(Y*, G*) of bodies of two materials (module docstring)."""
    G1, G2 = E1 / (2.0 * (1.0 + nu1)), E2 / (2.0 * (1.0 + nu2))
    return 1.0 / ((1.0 - nu1 * nu1) / E1 + (1.0 - nu2 * nu2) / E2), 1.0 / ((2.0 - nu1) / G1 + (2.0 - nu2) / G2)


def max_overlap(ystar, meff, reff, v):
    """Largest overlap of an elastic Hertz impact at speed v: (15 m* v^2 / (16 Y* sqrt(R*)))^(2/5)."""
    return (15.0 * meff * v * v / (16.0 * ystar * math.sqrt(reff))) ** 0.4


def contact_time(ystar, meff, reff, v):
    """Duration of an elastic Hertz impact at speed v: IMPACT_TIME delta_max / v, i.e. 2.868 (m*^2 / (R*
    Y*^2 v))^(1/5). The dashpot lengthens it (measured: +1.1 % at en 0.9, +9.4 % at en 0.5): the time-step
    check uses this, the shortest."""
    return IMPACT_TIME * max_overlap(ystar, meff, reff, v) / v


def rayleigh_time(radius, density, E, nu):
    """Rayleigh time pi R sqrt(rho / G) / (0.1631 nu + 0.8766), the shear-wave transit LIGGGHTS and EDEM
    size time steps on (20 % of it is their usual bound)."""
    G = E / (2.0 * (1.0 + nu))
    return math.pi * radius * math.sqrt(density / G) / (0.1631 * nu + 0.8766)


def hooke_equivalent(E, nu, density, diameter, v, en=1.0, wall=False, steps=50):
    """The Hooke kn that gives the same largest overlap as Hertz for two equal spheres of diameter d
    (or one sphere on a wall of the same material: wall=True) meeting at speed v, and a time step.

    Undamped Hooke reaches delta = v sqrt(m* / kn); equal to Hertz's max_overlap when kn = m* v^2 /
    delta_max^2. The time step is the Hooke contact time (dem.law.contact_time, with en) / steps.
    Returns a dict: kn (N/m), dt (s), tc_hooke, tc_hertz (elastic), delta_max (m), rayleigh (s), meff, reff."""
    from . import contact_time as hooke_time
    for name, value in (("E", E), ("density", density), ("diameter", diameter), ("v", v)):
        if not value > 0:
            raise DemError(f"hooke_equivalent: {name} must be > 0, got {value:g}")
    if not -1.0 < nu <= 0.5:
        raise DemError(f"hooke_equivalent: nu must be in (-1, 0.5], got {nu:g}")
    if not 0 <= en <= 1:
        raise DemError(f"hooke_equivalent: en must be in [0, 1], got {en:g}")
    radius = 0.5 * diameter
    m = density * math.pi * diameter ** 3 / 6.0
    meff, reff = (m, radius) if wall else (0.5 * m, 0.5 * radius)
    ystar = moduli(E, nu)[0]
    delta = max_overlap(ystar, meff, reff, v)
    kn = meff * v * v / (delta * delta)
    tc = hooke_time(kn, en, meff)
    return {"kn": kn, "dt": tc / steps, "tc_hooke": tc, "tc_hertz": contact_time(ystar, meff, reff, v),
            "delta_max": delta, "rayleigh": rayleigh_time(radius, density, E, nu), "meff": meff, "reff": reff}
