"""The Grains3D contact law (Part III eq. 10-16), shared by every contact geometry (spheres, walls, and
later convex bodies, glued composites, polyhedra): coefficients, their table per type pair, and contact
times. The force itself is computed by the inline nogil functions of `law.pxd`, applied at a contact
record by `apply.pxd`. Two elastic models per type pair: Hooke (kn, en: the Grains3D law) and Hertz-Mindlin
from material parameters (`model hertz E .. nu .. en .. mu ..`: `hertz.py`)."""
import math

import numpy as np

from dem.args import float_error, number
from dem.errors import DemError, did_you_mean

from . import hertz
from .law import COLUMNS

# columns of a coefficient row: defined once, in law.pxd
KN, BETA, MU, GAMMA_T, KS, MU_ROLL, EN, BETA_T, NCOEFF, XI_WIDTH = (
    COLUMNS[k] for k in ("KN", "BETA", "MU", "GAMMA_T", "KS", "MU_ROLL", "EN", "BETA_T", "NCOEFF", "XI_WIDTH"))
KEYWORDS = {"kn": "normal stiffness (N/m)",
            "en": "normal restitution coefficient (0 <= en <= 1; 0: critical damping, no rebound)",
            "mu": "Coulomb friction coefficient", "gamma_t": "tangential dissipative coefficient (1/s)",
            "beta_t": "tangential damping as a fraction of critical, nu_t += 2 beta_t sqrt(kn m_ij) "
                      "(1: gamma_t = gamma_n at en 0, Descantes 2022 Table 2)",
            "ks": "tangential spring stiffness (N/m), needs contact history",
            "mu_roll": "rolling resistance coefficient (dimensionless, times R_eff |F_n|)"}
MODEL, YSTAR, GSTAR, MODEL_HOOKE, MODEL_HERTZ = (
    COLUMNS[k] for k in ("MODEL", "YSTAR", "GSTAR", "MODEL_HOOKE", "MODEL_HERTZ"))
KEYWORDS.update({k: hertz.KEYWORDS[k] for k in ("model", "E", "nu")})    # Hertz words (hertz.py)
DEFAULTS = {"mu": 0.0, "gamma_t": 0.0, "beta_t": 0.0, "ks": 0.0, "mu_roll": 0.0}


def parse(words, what, required=("kn", "en")):
    """Parse `kn X en X [mu X] [gamma_t X] [beta_t X] [ks X] [mu_roll X]` into a dict (missing optional -> default),
    or `model hertz ...` (hertz.parse: its dict has "model": "hertz"); `model hooke` is the default said aloud."""
    out = {}
    if len(words) % 2:
        raise DemError(f"{what}: coefficients come as 'keyword value' pairs, got {' '.join(words)}")
    if hertz.is_hertz(words):
        return hertz.parse(words, what)
    for key, value in zip(words[::2], words[1::2]):
        if key == "model":
            if value != "hooke":
                raise DemError(f"{what}: model must be hertz or hooke, got '{value}'")
            continue
        if key in ("E", "nu"):
            raise DemError(f"{what}: '{key}' is a material parameter of 'model hertz' (add it, or give kn and "
                           f"en for the Hooke law)")
        if key not in KEYWORDS:
            raise DemError(f"{what}: unknown coefficient '{key}'{did_you_mean(key, KEYWORDS)}; "
                           f"known: {', '.join(KEYWORDS)}")
        try:
            out[key] = number(value)
        except ValueError:
            raise DemError(f"{what}: {float_error(value, key)}") from None
    missing = [k for k in required if k not in out]
    if missing:
        raise DemError(f"{what}: missing {', '.join(missing)} ({'; '.join(KEYWORDS[k] for k in missing)})")
    check(out, what)
    return out


def check(c, what):
    if "kn" in c and c["kn"] <= 0:
        raise DemError(f"{what}: kn must be > 0")
    if "en" in c and not 0 <= c["en"] <= 1:
        raise DemError(f"{what}: en must be in [0, 1] (0: critical damping)")
    for k in ("mu", "gamma_t", "beta_t", "ks", "mu_roll"):
        if c.get(k, 0.0) < 0:
            raise DemError(f"{what}: {k} must be >= 0")


def frictionless(c):
    """True when mu is given but none of ks, gamma_t, beta_t: the tangential force is then zero whatever mu
    is (the law caps a trial force of -nu_t U_rt - ks xi). LAMMPS's granular styles take
    Kt = 2/7 Kn for a NULL Kt; dem keeps its coefficients explicit and warns instead."""
    if c.get("model") == "hertz":          # its tangential spring comes from G*
        return False
    return c.get("mu", 0.0) > 0 and not any(c.get(k, 0.0) > 0 for k in ("ks", "gamma_t", "beta_t"))


def warn_frictionless(sim, owner, what):
    """Warn once per style instance (at the line that set such coefficients) that mu has no effect."""
    if getattr(owner, "_warned_frictionless", False):
        return
    owner._warned_frictionless = True
    where = sim.input.location
    sim.warning(f"{where + ': ' if where else ''}{what}: mu is given but ks, gamma_t and beta_t are 0, so the "
                f"tangential force is zero (give ks, gamma_t or beta_t for friction)")


def beta(en):
    """gamma_n = beta * omega0 with omega0 = sqrt(kn / m_ij) (eq. 16 with the reduced mass); en = 0 is its
    limit, critical damping (beta = 1: Descantes 2022 Table 1, gamma_n = 2 sqrt(m_ij kn))."""
    if en == 0:
        return 1.0
    ln = math.log(en)
    return -ln / math.sqrt(math.pi ** 2 + ln * ln)


def row(c):
    if c.get("model") == "hertz":
        return hertz.row(c, COLUMNS, beta)
    r = np.zeros(NCOEFF)
    r[KN], r[BETA], r[EN] = c["kn"], beta(c["en"]), c["en"]
    r[MU], r[GAMMA_T] = c.get("mu", 0.0), c.get("gamma_t", 0.0)
    r[KS], r[MU_ROLL] = c.get("ks", 0.0), c.get("mu_roll", 0.0)
    r[BETA_T] = c.get("beta_t", 0.0)
    return r


def contact_time(kn, en, meff):
    """T_c = pi / sqrt(omega0^2 - gamma_n^2) (eq. 12). At critical damping (en = 0) the pair never parts:
    the undamped half period pi / omega0 is returned as the contact's time scale (the time step check)."""
    w0 = math.sqrt(kn / meff)
    g = beta(en) * w0
    if g >= w0:
        return math.pi / w0
    return math.pi / math.sqrt(w0 * w0 - g * g)


def needs_history(rows):
    """Whether coefficient rows (any array of them, last axis the columns) need tangential history: a Hooke
    spring (ks > 0), or a Hertz row with friction (its spring kt is always there)."""
    rows = np.asarray(rows)
    return bool(np.any(rows[..., KS] > 0) or np.any((rows[..., MODEL] == MODEL_HERTZ) & (rows[..., MU] > 0)))


def is_hertz_row(r):
    """Whether a coefficient row is of the Hertz model (elementwise over an array of rows)."""
    return np.asarray(r)[..., MODEL] == MODEL_HERTZ


def row_contact_time(r, meff, reff, speed):
    """Contact time of a coefficient row for a pair of reduced mass meff and radius reff: the Hooke one
    (contact_time) or, for a Hertz row, the elastic Hertz impact at `speed` (hertz.contact_time)."""
    if is_hertz_row(r):
        return hertz.contact_time(r[YSTAR], meff, reff, speed)
    return contact_time(r[KN], r[EN], meff)


def check_speed(sim):
    """The impact speed the time-step check assumes for Hertz rows: twice the largest particle speed at
    setup (a head-on meeting), at least hertz.CHECK_SPEED (1 m/s; particles often start at rest)."""
    atom = sim.atom
    v = atom.data["v"][:atom.nlocal]
    vmax = sim.comm.max(float(np.sqrt((v * v).sum(axis=1)).max()) if len(v) else 0.0)
    return max(2.0 * vmax, hertz.CHECK_SPEED)
