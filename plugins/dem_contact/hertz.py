"""Hertz-Mindlin with material parameters (LIGGGHTS's `model hertz tangential history`): the coefficients
`model hertz E E nu NU en EN mu MU [mu_roll MR]` of pair_coeff and the wall fixes, their row of the law's
table (the force: `hertz` in law.pxd), the closed-form Hertz impact (contact time, largest overlap) that the
time-step check and the tests use, and the Hooke stiffness equivalent to Hertz at an impact speed (for
Grains3D-style tables, `dem-hooke-from-hertz`).

One material per line: both bodies of a pair_coeff I J line, and a wall and its particles, are of the
material E, nu, so that Y* = E / (2 (1 - nu^2)) and G* = G / (2 (2 - nu)) with G = E / (2 (1 + nu)):
the two-material forms Y* = 1 / ((1 - nu1^2) / E1 + (1 - nu2^2) / E2), G* = 1 / ((2 - nu1) / G1 +
(2 - nu2) / G2) (LIGGGHTS, doc/gran_model_hertz.html of github.com/CFDEMproject/LIGGGHTS-PUBLIC) with
equal materials."""
import math

import numpy as np

from dem.args import float_error, number
from dem.errors import DemError, did_you_mean

KEYWORDS = {"model": "elastic model: hertz (material parameters) or hooke (kn, en: the default)",
            "E": "Young's modulus (Pa), > 0", "nu": "Poisson's ratio, -1 < nu <= 0.5",
            "en": "normal restitution coefficient (0 <= en <= 1)", "mu": "Coulomb friction coefficient",
            "mu_roll": "rolling resistance coefficient (dimensionless, times R_eff |F_n|)"}
REQUIRED = ("E", "nu", "en", "mu")
# words of the Hooke law that model hertz derives itself (from E, nu, en) and so refuses
HOOKE_ONLY = ("kn", "ks", "gamma_t", "beta_t")
# 2 times the integral of dx / sqrt(1 - x^(5/2)) over [0, 1]: an elastic Hertz impact lasts this times
# delta_max / v (the familiar t_c = 2.87 (m*^2 / (R* Y*^2 v))^(1/5) is 2.8682... rounded)
IMPACT_TIME = 2.0 * math.gamma(1.4) * math.sqrt(math.pi) / math.gamma(0.9)
CHECK_SPEED = 1.0    # m/s: the least impact speed the time-step check assumes (particles at rest at setup)


def is_hertz(words):
    """True when coefficient words ask for `model hertz` (anywhere: the keyword order is free)."""
    return any(k == "model" and v == "hertz" for k, v in zip(words[::2], words[1::2]))


def parse(words, what):
    """`model hertz E E nu NU en EN mu MU [mu_roll MR]`, keywords in any order, into a dict."""
    if len(words) % 2:
        raise DemError(f"{what}: coefficients come as 'keyword value' pairs, got {' '.join(words)}")
    out = {}
    for key, value in zip(words[::2], words[1::2]):
        if key in HOOKE_ONLY:
            raise DemError(f"{what}: model hertz derives the stiffnesses and the damping from E, nu and en; "
                           f"'{key}' is a coefficient of the Hooke law (remove it, or 'model hertz' for kn en ...)")
        if key not in KEYWORDS:
            raise DemError(f"{what}: unknown coefficient '{key}' for model hertz{did_you_mean(key, KEYWORDS)}; "
                           f"known: {', '.join(KEYWORDS)}")
        if key in out:
            raise DemError(f"{what}: '{key}' is given twice")
        if key == "model":
            out[key] = value
            continue
        try:
            out[key] = number(value)
        except ValueError:
            raise DemError(f"{what}: {float_error(value, key)}") from None
    missing = [k for k in REQUIRED if k not in out]
    if missing:
        raise DemError(f"{what}: model hertz needs {', '.join(missing)} "
                       f"({'; '.join(KEYWORDS[k] for k in missing)})")
    check(out, what)
    return out


def check(c, what):
    if not c["E"] > 0:
        raise DemError(f"{what}: E (Young's modulus) must be > 0, got {c['E']:g}")
    if not -1.0 < c["nu"] <= 0.5:
        raise DemError(f"{what}: nu (Poisson's ratio) must be in (-1, 0.5], got {c['nu']:g}")
    if not 0 <= c["en"] <= 1:
        raise DemError(f"{what}: en must be in [0, 1] (0: critical damping)")
    for k in ("mu", "mu_roll"):
        if c.get(k, 0.0) < 0:
            raise DemError(f"{what}: {k} must be >= 0")


def moduli(E, nu):
    """(Y*, G*) of two bodies of the same material (module docstring)."""
    G = E / (2.0 * (1.0 + nu))
    return E / (2.0 * (1.0 - nu * nu)), G / (2.0 * (2.0 - nu))


def row(c, columns, beta):
    """The coefficient row of the parsed dict c (columns: dem_contact's, beta: dem_contact.beta)."""
    r = np.zeros(columns["NCOEFF"])
    r[columns["MODEL"]] = columns["MODEL_HERTZ"]
    r[columns["YSTAR"]], r[columns["GSTAR"]] = moduli(c["E"], c["nu"])
    r[columns["BETA"]], r[columns["EN"]] = beta(c["en"]), c["en"]
    r[columns["MU"]], r[columns["MU_ROLL"]] = c["mu"], c.get("mu_roll", 0.0)
    return r


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
    delta_max^2. The time step is the Hooke contact time (dem_contact.contact_time, with en) / steps.
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
