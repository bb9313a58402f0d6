"""The contact law as parts, shared by every contact geometry (pair styles and walls): the words of a
`pair_coeff` (or wall fix) line, the coefficient row they make (row.pxd: which normal, damping,
tangential and rolling part acts, and their coefficients), the materials of each type mixed per pair, the
history a table of rows needs, and contact times. The force is computed by the inline nogil parts
(normal.pxd, damping.pxd, tangential.pxd, rolling.pxd, twisting.pxd) composed by law.pxd, applied at a
contact record by apply.pxd.

A line names its parts (`normal hooke|hertz|jkr|dmt`, `damping restitution|hertz|tsuji`, `tangential
spring|mindlin|viscous`, `rolling constant|epsd|epsd2`, `twisting none|marshall|sds`) and gives their
coefficients as keyword-value pairs in any order. `model hooke|hertz` is `normal` said as before the parts existed; unnamed parts take
the defaults of the normal part: Hooke goes with restitution damping and the spring (the Grains3D law,
Part III eq. 10-16), the Hertz family (hertz, jkr, dmt) with Hertz damping and Mindlin (LIGGGHTS's model
hertz); rolling is `constant` (mu_roll, 0: none), twisting `none`."""
import math

import numpy as np

from dem.args import float_error, number
from dem.errors import DemError, did_you_mean

from . import hertz
from ._columns import COLUMNS, PARTS, PLANS

# columns of a coefficient row: defined once, in row.pxd
(KN, BETA, MU, GAMMA_T, KS, MU_ROLL, EN, BETA_T, NORMAL, YSTAR, GSTAR, DAMPING, TANGENTIAL, LIMIT, ROLLING,
 ETA_ROLL, W, H_ROLL, H_BOND, COHESION, LIQUID, TENSION, ANGLE, PLAN, COHESION_K, ALPHA, NCOEFF, XI_WIDTH,
 ROLL_WIDTH, BOND_WIDTH) = (COLUMNS[k] for k in (
    "KN", "BETA", "MU", "GAMMA_T", "KS", "MU_ROLL", "EN", "BETA_T", "NORMAL", "YSTAR", "GSTAR", "DAMPING",
    "TANGENTIAL", "LIMIT", "ROLLING", "ETA_ROLL", "W", "H_ROLL", "H_BOND", "COHESION", "LIQUID", "TENSION",
    "ANGLE", "PLAN", "COHESION_K", "ALPHA", "NCOEFF", "XI_WIDTH", "ROLL_WIDTH", "BOND_WIDTH"))
TWISTING, K_TWIST, GAMMA_TWIST, MU_TWIST, H_TWIST, TWIST_WIDTH = (COLUMNS[k] for k in (
    "TWISTING", "K_TWIST", "GAMMA_TWIST", "MU_TWIST", "H_TWIST", "TWIST_WIDTH"))
HERTZ_FAMILY = ("hertz", "jkr", "dmt")
ADHESIVE = ("jkr", "dmt")
KEYWORDS = {"kn": "normal stiffness (N/m) of normal hooke",
            "en": "normal restitution coefficient (0 <= en <= 1; 0: critical damping, no rebound; damping tsuji: "
                  "the e of Tsuji's alpha(e))",
            "mu": "Coulomb friction coefficient", "gamma_t": "tangential dissipative coefficient (1/s)",
            "beta_t": "tangential damping as a fraction of critical, nu_t += 2 beta_t sqrt(kn m_ij) "
                      "(1: gamma_t = gamma_n at en 0, Descantes 2022 Table 2)",
            "ks": "tangential spring stiffness (N/m), needs contact history",
            "mu_roll": "rolling resistance coefficient (dimensionless, times R_eff |F_n|)",
            "E": "Young's modulus (Pa), > 0", "nu": "Poisson's ratio, -1 < nu <= 0.5",
            "w": "work of adhesion (J/m^2), > 0: twice the surface energy of one body",
            "eta_roll": "rolling damping of rolling epsd, a fraction of critical (0 <= eta_roll)",
            "liquid_volume": "volume of a liquid bridge (m^3), > 0",
            "surface_tension": "surface tension of the liquid (N/m), > 0",
            "contact_angle": "contact angle of the liquid on the solid (degrees, 0 <= angle < 90)",
            "cohesion_energy_density": "cohesion sjkr's pull per unit contact area and overlap (J/m^3), > 0",
            "limit_damping": "1: the damping never makes the normal force attractive (LAMMPS's limit_damping; "
                             "0, the default: it may, as the surfaces part)",
            "k_twist": "twisting spring of twisting sds (N m/rad), >= 0",
            "gamma_twist": "twisting dashpot of twisting sds (N m s/rad), >= 0",
            "mu_twist": "twisting friction of twisting sds: the largest torque is mu_twist |F_n| (m), > 0"}
SELECTORS = ("normal", "damping", "tangential", "rolling", "cohesion", "twisting")
# the numbers each part takes: the part's own coefficients and which of them a line must give
PART_WORDS = {("normal", "hooke"): ("kn",), ("normal", "hertz"): ("E", "nu"), ("normal", "jkr"): ("E", "nu", "w"),
              ("normal", "dmt"): ("E", "nu", "w"),
              ("damping", "restitution"): ("en", "gamma_t", "beta_t", "limit_damping"),
              ("damping", "hertz"): ("en", "limit_damping"), ("damping", "tsuji"): ("en", "limit_damping"),
              ("tangential", "spring"): ("mu", "ks"), ("tangential", "mindlin"): ("mu",),
              ("tangential", "viscous"): ("mu",),
              ("rolling", "constant"): ("mu_roll",), ("rolling", "epsd"): ("mu_roll", "eta_roll"),
              ("rolling", "epsd2"): ("mu_roll",), ("cohesion", "none"): (),
              ("cohesion", "capillary"): ("liquid_volume", "surface_tension", "contact_angle"),
              ("cohesion", "sjkr"): ("cohesion_energy_density",), ("twisting", "none"): (),
              ("twisting", "marshall"): (), ("twisting", "sds"): ("k_twist", "gamma_twist", "mu_twist")}
REQUIRED = {"hooke": ("kn", "en"), "hertz": ("E", "nu", "en", "mu"), "jkr": ("E", "nu", "w", "en", "mu"),
            "dmt": ("E", "nu", "w", "en", "mu"), "epsd": ("mu_roll", "eta_roll"), "epsd2": ("mu_roll",),
            "capillary": ("liquid_volume", "surface_tension", "contact_angle"),
            "sjkr": ("cohesion_energy_density",), "sds": ("k_twist", "gamma_twist", "mu_twist")}
# the parts whose history is wider than the tangential spring (styles and walls without room refuse them)
WIDE_HISTORY = "normal jkr, cohesion capillary, rolling epsd/epsd2 and twisting marshall/sds"
WORDS = ("model",) + SELECTORS + tuple(KEYWORDS)      # every word of a law line (for the fixes' parsers)
MATERIAL = ("E", "nu", "w")      # of each type: a line for types I != J may leave them to pair_coeff I I
DEFAULT_PARTS = {"hooke": {"damping": "restitution", "tangential": "spring"},
                 "hertz": {"damping": "hertz", "tangential": "mindlin"}}


def _parts(words, what):
    """The parts a line names (model = normal), the rest of its words as (keyword, value) pairs."""
    parts, rest = {}, []
    for key, value in zip(words[::2], words[1::2]):
        sel = "normal" if key == "model" else key
        if sel not in SELECTORS:
            rest.append((key, value))
            continue
        if sel in parts:
            raise DemError(f"{what}: '{key}' is given twice")
        if value not in PARTS[sel]:
            if key == "model":
                raise DemError(f"{what}: model must be hertz or hooke, got '{value}' (or 'normal "
                               f"{'|'.join(PARTS['normal'])}')")
            raise DemError(f"{what}: {sel} must be one of {', '.join(PARTS[sel])}, got '{value}'"
                           f"{did_you_mean(value, PARTS[sel])}")
        parts[sel] = value
    normal = parts.setdefault("normal", "hooke")
    for sel, value in DEFAULT_PARTS["hooke" if normal == "hooke" else "hertz"].items():
        parts.setdefault(sel, value)
    parts.setdefault("rolling", "constant")
    parts.setdefault("cohesion", "none")
    parts.setdefault("twisting", "none")
    return parts, rest


def parse(words, what, required=("kn", "en"), same_type=True):
    """The words of a pair_coeff or wall line into a dict: its parts ("normal", "damping", "tangential",
    "rolling") and coefficients. `required` is what a Hooke line must give (walls: nothing, so that a bare
    line takes pair_coeff I I); `same_type` false (a line for types I != J only) lets a Hertz-family line
    leave E, nu and w to the types' own lines (mixed at init: mix_materials)."""
    if len(words) % 2:
        raise DemError(f"{what}: coefficients come as 'keyword value' pairs, got {' '.join(words)}")
    parts, rest = _parts(words, what)
    normal = parts["normal"]
    allowed = {k for (sel, part), ks in PART_WORDS.items() if parts[sel] == part for k in ks}
    out = dict(parts)
    for key, value in rest:
        if key not in KEYWORDS:
            raise DemError(f"{what}: unknown coefficient '{key}'{did_you_mean(key, KEYWORDS)}; "
                           f"known: {', '.join(KEYWORDS)}")
        if key not in allowed:
            raise DemError(_not_of_these_parts(what, key, parts))
        if key in out:
            raise DemError(f"{what}: '{key}' is given twice")
        try:
            out[key] = number(value)
        except ValueError:
            raise DemError(f"{what}: {float_error(value, key)}") from None
    if parts["tangential"] == "mindlin" and normal == "hooke":
        raise DemError(f"{what}: tangential mindlin needs the Hertz family (normal hertz, jkr or dmt: its "
                       f"stiffness grows with the contact radius); the Hooke law takes tangential spring")
    if parts["tangential"] == "viscous" and parts["damping"] != "restitution":
        raise DemError(f"{what}: tangential viscous takes its dashpot from damping restitution (gamma_t, "
                       f"beta_t); add 'damping restitution'")
    need = {}                  # part: the words it lacks
    if normal == "hooke":
        need[_name(parts)] = required
    elif same_type or any(k in out for k in MATERIAL):      # a material is given whole
        need[_name(parts)] = REQUIRED[normal]
    else:                      # types I != J only: the material may come from pair_coeff I I and J J
        need[_name(parts)] = [k for k in REQUIRED[normal] if k not in MATERIAL]
    for sel in ("rolling", "cohesion", "twisting"):
        if parts[sel] in REQUIRED:
            need[f"{sel} {parts[sel]}"] = REQUIRED[parts[sel]]
    for name, keys in need.items():
        missing = [k for k in keys if k not in out]
        if missing:
            raise DemError(f"{what}: {name} needs {', '.join(missing)} "
                           f"({'; '.join(KEYWORDS[k] for k in missing)})")
    check(out, what)
    return out


def _name(parts):
    return "model hertz" if parts["normal"] == "hertz" else f"normal {parts['normal']}" if parts[
        "normal"] != "hooke" else "the Hooke law"


def _not_of_these_parts(what, key, parts):
    """The error for a coefficient that none of the line's parts takes, naming the part that does."""
    owners = [f"{sel} {part}" for (sel, part), ks in PART_WORDS.items() if key in ks]
    if key in ("E", "nu") and parts["normal"] == "hooke":
        return (f"{what}: '{key}' is a material parameter of 'model hertz' (add it, or give kn and en for the "
                f"Hooke law)")
    if parts["normal"] in HERTZ_FAMILY and key in ("kn", "ks", "gamma_t", "beta_t"):
        return (f"{what}: {_name(parts)} derives the stiffnesses and the damping from E, nu and en; '{key}' is "
                f"a coefficient of the Hooke law (remove it, or name the part that takes it: "
                f"{', '.join(owners)})")
    return f"{what}: '{key}' is a coefficient of {' or '.join(owners)}, not of this line's parts"


def check(c, what):
    if "kn" in c and not c["kn"] > 0:
        raise DemError(f"{what}: kn must be > 0")
    if "en" in c and not 0 <= c["en"] <= 1:
        raise DemError(f"{what}: en must be in [0, 1] (0: critical damping)")
    if "E" in c and not c["E"] > 0:
        raise DemError(f"{what}: E (Young's modulus) must be > 0, got {c['E']:g}")
    if "nu" in c and not -1.0 < c["nu"] <= 0.5:
        raise DemError(f"{what}: nu (Poisson's ratio) must be in (-1, 0.5], got {c['nu']:g}")
    if "w" in c and not c["w"] > 0:
        raise DemError(f"{what}: w (work of adhesion) must be > 0, got {c['w']:g}")
    for k in ("liquid_volume", "surface_tension", "cohesion_energy_density"):
        if k in c and not c[k] > 0:
            raise DemError(f"{what}: {k} must be > 0, got {c[k]:g}")
    if "contact_angle" in c and not 0 <= c["contact_angle"] < 90:
        raise DemError(f"{what}: contact_angle must be in [0, 90) degrees (a wetting liquid), got "
                       f"{c['contact_angle']:g}")
    for k in ("mu", "gamma_t", "beta_t", "ks", "mu_roll", "eta_roll", "k_twist", "gamma_twist"):
        if c.get(k, 0.0) < 0:
            raise DemError(f"{what}: {k} must be >= 0")
    if c.get("limit_damping", 0) not in (0, 1):
        raise DemError(f"{what}: limit_damping must be 0 or 1, got {c['limit_damping']:g}")
    if c.get("rolling", "constant") != "constant" and not c.get("mu_roll", 0.0) > 0:
        raise DemError(f"{what}: rolling {c['rolling']} needs mu_roll > 0")
    if "mu_twist" in c and not c["mu_twist"] > 0:
        raise DemError(f"{what}: mu_twist must be > 0 (the twisting torque is capped at mu_twist |F_n|), got "
                       f"{c['mu_twist']:g}")
    if c.get("twisting") == "marshall" and not c.get("mu", 0.0) > 0:
        raise DemError(f"{what}: twisting marshall takes its friction from the tangential part's (2/3 mu a): it "
                       f"needs mu > 0")


def frictionless(c):
    """True when mu is given but none of ks, gamma_t, beta_t, with the spring of Grains3D: the tangential
    force is then zero whatever mu is (the law caps a trial force of -nu_t U_rt - ks xi). LAMMPS's granular
    styles take Kt = 2/7 Kn for a NULL Kt; dem keeps its coefficients explicit and warns instead."""
    if c.get("tangential", "spring") != "spring" or c.get("damping", "restitution") != "restitution":
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


# Tsuji et al. (1992)'s alpha(en), the coefficients of en^0 .. en^6 (as LAMMPS's damping tsuji gives them)
TSUJI_ALPHA = (1.2728, -4.2783, 11.087, -22.348, 27.467, -18.022, 4.8218)


def tsuji_alpha(en):
    """gamma_n / sqrt(kn m*) of damping tsuji. The polynomial fits the restitution of a Hertz contact whose
    dashpot is alpha sqrt(2 m* kn) (Tsuji's m, the mass of one of two equal spheres), to 1.1e-3 for en in
    [0.1, 1]; with m* (LAMMPS's meff, as here) the restitution is tsuji_restitution(alpha)."""
    return sum(a * en ** i for i, a in enumerate(TSUJI_ALPHA))


def tsuji_restitution(alpha, normal="hertz"):
    """The restitution of gamma_n = alpha sqrt(kn m*): exp(-pi alpha / sqrt(5 - alpha^2)) with kn = 4/3 Y* a
    (the Hertz ODE whose en depends on alpha alone; damping hertz is alpha = sqrt(5) beta, hertz.md), and
    exp(-pi alpha / sqrt(4 - alpha^2)) with Hooke's kn (a linear oscillator of damping ratio alpha / 2)."""
    return math.exp(-math.pi * alpha / math.sqrt((4.0 if normal == "hooke" else 5.0) - alpha * alpha))


def has_material(c):
    """Whether a parsed line gives its own material (a Hertz-family line may leave it to its types)."""
    return c["normal"] == "hooke" or "E" in c


def mix_materials(c, mat_i, mat_j):
    """The line c with the material of types i and j (their parsed `pair_coeff I I` lines) where it gives
    none: Y* = 1 / ((1 - nu_i^2) / E_i + (1 - nu_j^2) / E_j), G* = 1 / ((2 - nu_i) / G_i + (2 - nu_j) / G_j)
    (hertz.py) and w = sqrt(w_i w_j) (the geometric mean of the surface energies, Berthelot's rule)."""
    out = dict(c)
    out["_mix"] = (mat_i, mat_j)
    if c["normal"] in ADHESIVE:
        out["w"] = math.sqrt(mat_i["w"] * mat_j["w"])
    return out


def row(c):
    """The coefficient row of a parsed line (materials resolved: has_material, or mix_materials)."""
    r = np.zeros(NCOEFF)
    for sel in SELECTORS:
        r[COLUMNS[sel.upper()]] = PARTS[sel][c[sel]]
    r[BETA], r[EN] = beta(c["en"]), c["en"]
    r[ALPHA] = tsuji_alpha(c["en"]) if c["damping"] == "tsuji" else 0.0
    r[MU], r[GAMMA_T] = c.get("mu", 0.0), c.get("gamma_t", 0.0)
    r[KS], r[MU_ROLL] = c.get("ks", 0.0), c.get("mu_roll", 0.0)
    r[BETA_T] = c.get("beta_t", 0.0)
    r[ETA_ROLL] = c.get("eta_roll", 0.0)
    r[W] = c.get("w", 0.0)
    r[LIQUID], r[TENSION] = c.get("liquid_volume", 0.0), c.get("surface_tension", 0.0)
    r[ANGLE] = math.radians(c.get("contact_angle", 0.0))
    r[COHESION_K] = c.get("cohesion_energy_density", 0.0)
    r[K_TWIST], r[GAMMA_TWIST] = c.get("k_twist", 0.0), c.get("gamma_twist", 0.0)
    r[MU_TWIST] = c.get("mu_twist", 0.0)
    r[H_ROLL] = r[H_BOND] = r[H_TWIST] = -1.0
    r[LIMIT] = c.get("limit_damping", 0)
    if c.get("normal", "hooke") == "hooke":
        r[KN] = c["kn"]
    elif "_mix" in c:
        (mi, mj) = c["_mix"]
        r[YSTAR], r[GSTAR] = hertz.mixed_moduli(mi["E"], mi["nu"], mj["E"], mj["nu"])
    else:
        r[YSTAR], r[GSTAR] = hertz.moduli(c["E"], c["nu"])
    return r


def descantes(rows):
    """Rows of Descantes' eq. 3 (the `law descantes` of pair polyhedron/multipoint and the walls): the
    damping never attracts and friction is viscous, capped by Coulomb (no spring, no history)."""
    rows = np.array(rows)
    rows[..., LIMIT] = 1.0
    rows[..., TANGENTIAL] = PARTS["tangential"]["viscous"]
    return rows


def is_hertz_row(r):
    """Whether a coefficient row is of the Hertz family (elementwise over an array of rows)."""
    return np.asarray(r)[..., NORMAL] != PARTS["normal"]["hooke"]


def _needs(rows):
    """(tangential history, rolling spring, twist angle, bond) needed by rows (any array of them)."""
    rows = np.asarray(rows)
    tan = rows[..., TANGENTIAL]
    xi = np.any((tan == PARTS["tangential"]["spring"]) & (rows[..., KS] > 0)) or np.any(
        (tan == PARTS["tangential"]["mindlin"]) & (rows[..., MU] > 0))
    roll = np.any((rows[..., ROLLING] != PARTS["rolling"]["constant"]) & (rows[..., MU_ROLL] > 0))
    twist = np.any(rows[..., TWISTING] != PARTS["twisting"]["none"])
    return bool(xi), bool(roll), bool(twist), bool(np.any(_bonds(rows)))


def _bonds(rows):
    """Which rows act beyond contact once touched (JKR, a liquid bridge): they keep the bond flag."""
    return (rows[..., NORMAL] == PARTS["normal"]["jkr"]) | (rows[..., COHESION] == PARTS["cohesion"]["capillary"])


def _plans(rows):
    """Each row's plan (row.pxd): the common combinations that law.pxd evaluates with constant parts."""
    p = {k: PARTS[k] for k in SELECTORS}
    plain = (rows[..., COHESION] == p["cohesion"]["none"]) & (rows[..., LIMIT] == 0)
    grains3d = plain & (rows[..., NORMAL] == p["normal"]["hooke"]) & (
        rows[..., DAMPING] == p["damping"]["restitution"]) & (rows[..., TANGENTIAL] == p["tangential"]["spring"])
    hertz_mindlin = plain & (rows[..., NORMAL] == p["normal"]["hertz"]) & (
        rows[..., DAMPING] == p["damping"]["hertz"]) & (rows[..., TANGENTIAL] == p["tangential"]["mindlin"])
    return np.where(grains3d, PLANS["grains3d"], np.where(hertz_mindlin, PLANS["hertz_mindlin"], PLANS["general"]))


def prepare(rows):
    """Make a table of rows (any array of them) ready for the kernels, in place: each row's plan and
    history offsets. Returns the history width the table needs (0: none): the tangential spring xi first
    (XI_WIDTH), then the rolling spring (ROLL_WIDTH), the twist angle (TWIST_WIDTH) and the bond flag, each
    only when a row of the table has that part. A table of the seed models keeps XI_WIDTH or nothing."""
    rows[..., PLAN] = _plans(rows)
    xi, roll, twist, bond = _needs(rows)
    if not (xi or roll or twist or bond):
        return 0
    width = XI_WIDTH
    rows[..., H_ROLL] = rows[..., H_BOND] = rows[..., H_TWIST] = -1.0
    if roll:
        rows[..., H_ROLL] = np.where(rows[..., ROLLING] != PARTS["rolling"]["constant"], width, -1.0)
        width += ROLL_WIDTH
    if twist:
        rows[..., H_TWIST] = np.where(rows[..., TWISTING] != PARTS["twisting"]["none"], width, -1.0)
        width += TWIST_WIDTH
    if bond:
        rows[..., H_BOND] = np.where(_bonds(rows), width, -1.0)
        width += BOND_WIDTH
    return width


def max_reach(rows, reff):
    """The largest distance beyond contact at which a row still acts, for contacts of R* up to reff (the
    neighbor list adds it to the pair cutoff): JKR's pull-off distance 3/4 (pi^2 w^2 R* / Y*^2)^(1/3), a
    liquid bridge's rupture distance (1 + theta / 2) V^(1/3)."""
    rows = np.asarray(rows).reshape(-1, NCOEFF)
    jkr = rows[rows[:, NORMAL] == PARTS["normal"]["jkr"]]
    bridge = rows[rows[:, COHESION] == PARTS["cohesion"]["capillary"]]
    reach = [0.75 * np.cbrt(math.pi ** 2 * jkr[:, W] ** 2 * reff / jkr[:, YSTAR] ** 2),
             (1.0 + 0.5 * bridge[:, ANGLE]) * np.cbrt(bridge[:, LIQUID])]
    return float(max((np.max(r) for r in reach if len(r)), default=0.0))


def contact_time(kn, en, meff, zeta=None):
    """T_c = pi / sqrt(omega0^2 - gamma_n^2) (eq. 12), gamma_n here gamma_n / (2 m*) = zeta omega0, zeta =
    beta(en) unless given (damping tsuji: alpha / 2). At critical damping (en = 0) the pair never parts:
    the undamped half period pi / omega0 is returned as the contact's time scale (the time step check)."""
    w0 = math.sqrt(kn / meff)
    g = (beta(en) if zeta is None else zeta) * w0
    if g >= w0:
        return math.pi / w0
    return math.pi / math.sqrt(w0 * w0 - g * g)


def row_contact_time(r, meff, reff, speed):
    """Contact time of a coefficient row for a pair of reduced mass meff and radius reff: the Hooke one
    (contact_time) or, for a Hertz-family row, the elastic Hertz impact at `speed` (hertz.contact_time)."""
    if is_hertz_row(r):
        return hertz.contact_time(r[YSTAR], meff, reff, speed)
    tsuji = r[DAMPING] == PARTS["damping"]["tsuji"]
    return contact_time(r[KN], r[EN], meff, 0.5 * r[ALPHA] if tsuji else None)


def check_speed(sim):
    """The impact speed the time-step check assumes for Hertz rows: twice the largest particle speed at
    setup (a head-on meeting), at least hertz.CHECK_SPEED (1 m/s; particles often start at rest)."""
    atom = sim.atom
    v = atom.data["v"][:atom.nlocal]
    vmax = sim.comm.max(float(np.sqrt((v * v).sum(axis=1)).max()) if len(v) else 0.0)
    return max(2.0 * vmax, hertz.CHECK_SPEED)
