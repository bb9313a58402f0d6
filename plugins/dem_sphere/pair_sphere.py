"""pair_style sphere: spheres with the contact law in parts (dem/law)."""
import numpy as np

from dem._particles import ParticleView
from dem.errors import DemError
from dem.history import History
from dem.law import XI_WIDTH
from dem.law.pair_coeffs import PairCoefficients
from dem.pair import Pair

from . import _pair_sphere


class PairSphere(PairCoefficients, Pair):
    """pair_style sphere

    pair_coeff I J kn KN en EN [mu MU] [gamma_t GT] [beta_t BT] [ks KS] [mu_roll MUR]
    pair_coeff I J model hertz E E nu NU en EN mu MU [mu_roll MUR]
    pair_coeff I J [normal hooke|hertz|jkr|dmt] [cohesion none|capillary|sjkr] [damping restitution|hertz|tsuji]
                   [tangential spring|mindlin|viscous] [rolling constant|epsd|epsd2] [twisting none|marshall|sds]
                   COEFFICIENTS (kn E nu w en mu ks gamma_t beta_t mu_roll eta_roll liquid_volume surface_tension
                   contact_angle cohesion_energy_density k_twist gamma_twist mu_twist)

    Spheres in contact when their surfaces overlap (overlap delta, normal n along the line of centres,
    contact point in the middle of the overlap). The Grains3D law (Part III eq. 10-16) per contact:
    normal force kn delta - 2 gamma_n m_ij U_rn with gamma_n from the restitution coefficient en and the
    reduced mass m_ij (eq. 16); tangential force -min(mu |F_n|, |-nu_t U_rt - ks xi|) along the trial
    force, nu_t = 2 gamma_t m_ij + 2 beta_t sqrt(kn m_ij) (beta_t: a fraction of critical damping), xi the tangential displacement kept as contact history while ks > 0 (it survives
    neighbor-list rebuilds and restarts). Optional rolling resistance: a torque mu_roll R_eff |F_n|
    opposing the relative angular velocity. Defaults: mu 0, gamma_t 0 (1/s), beta_t 0, ks 0 (N/m), mu_roll 0
    (with gamma_t = beta_t = ks = 0 there is no tangential force whatever mu is: give one of them; pair_coeff
    warns once when mu is given without either. LAMMPS's granular styles take Kt = 2/7 Kn for a NULL
    Kt; dem keeps every coefficient explicit and never supplies one).

    Example (Part III Table 6, with ks = 2/7 kn and gamma_t as in inputs/in.drum)::

        pair_style sphere
        pair_coeff * * kn 1e5 en 0.73 mu 0.55 gamma_t 2000 ks 28571

    `model hertz` (keywords in any order): Hertz-Mindlin from material parameters, LIGGGHTS's default
    model (`model hertz tangential history`), with R* = R_i R_j / (R_i + R_j), m* = m_ij and both types
    of the one material E (Pa), nu (-1 < nu <= 0.5): Y* = E / (2 (1 - nu^2)), G* = G / (2 (2 - nu)),
    G = E / (2 (1 + nu)). Normal force kn delta - gamma_n U_rn with kn = 4/3 Y* sqrt(R* delta) and
    gamma_n = 2 sqrt(5/6) beta sqrt(2 Y* sqrt(R* delta) m*), beta = -ln en / sqrt(ln^2 en + pi^2); the
    tangential spring kt = 8 G* sqrt(R* delta) on the history xi (always kept when mu > 0) with the dashpot
    gamma_t = 2 sqrt(5/6) beta sqrt(kt m*), capped by Coulomb as above. kn, ks, gamma_t and beta_t are
    refused with it. The time-step check takes the Hertz contact time at twice the largest speed at setup
    (at least 1 m/s). Formulas and validation: docs/hertz.md. Example (glass beads)::

        pair_coeff * * model hertz E 6.3e10 nu 0.24 en 0.9 mu 0.3

    The law in parts (docs/contact_law.md): `normal jkr E .. nu .. w ..` (Johnson-Kendall-Roberts
    adhesion, w the work of adhesion in J/m^2: the bond forms at touch and holds apart until the pull-off
    distance 3/4 (pi^2 w^2 R* / Y*^2)^(1/3), which the neighbor cutoff includes), `normal dmt` (Hertz
    minus 2 pi w R* in contact), `rolling epsd mu_roll .. eta_roll ..` (elastic-plastic spring-dashpot
    rolling resistance, Ai et al. 2011; `epsd2` without the dashpot), `cohesion capillary liquid_volume ..
    surface_tension .. contact_angle ..` (a liquid bridge, Willett et al. 2000, from touch to its rupture
    distance (1 + theta/2) V^(1/3)), `cohesion sjkr cohesion_energy_density ..` (LIGGGHTS's simplified JKR:
    k times the contact area 2 pi R* delta, in contact only). A line for types I != J may leave
    E, nu and w out: each type's own (pair_coeff I I) is mixed, 1/Y* = (1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j.
    Example (a cohesive powder of two materials)::

        pair_coeff 1 1 normal jkr E 1e8 nu 0.3 w 0.05 en 0.5 mu 0.5 rolling epsd mu_roll 0.1 eta_roll 0.3
        pair_coeff 2 2 normal jkr E 5e8 nu 0.25 w 0.02 en 0.5 mu 0.5 rolling epsd mu_roll 0.1 eta_roll 0.3
        pair_coeff 1 2 normal jkr en 0.5 mu 0.5 rolling epsd mu_roll 0.1 eta_roll 0.3
    """


    style = "sphere"
    max_history = None               # any layout of the law's history (dem.law.prepare)
    tallies = ("stress", "count")    # per-particle contact tallies for analysis (dem/tally.py)

    def __init__(self, sim, args):
        super().__init__(sim, args)
        if args:
            raise DemError(f"pair_style sphere takes no arguments (coefficients go in pair_coeff), got "
                           f"{' '.join(args)}")
        self.init_coefficients()
        self.history = None
        self.stats = np.zeros(3)
        self.worst = np.zeros(2, dtype=np.int64)

    def init(self):
        need_history = self.check_coefficients()
        atom = self.sim.atom
        if self.sim.comm.any(bool(np.any(atom.data["shape"][:atom.nlocal] >= 0))):
            raise DemError("pair_style sphere treats every particle as a sphere, but some particles have a "
                           "shape", hint="use pair_style convex/gjk for shaped particles")
        width = self.history_width
        if self.history is not None and (not need_history or self.history.nvalues != width):
            self.history.discard()          # the law changed: its history has another layout
            self.sim.neighbor.histories.remove(self.history)
            self.history = None
        if need_history and self.history is None:
            # the tangential spring alone keeps the name restarts have always used
            self.history = History(self.sim, "pair_xi" if width == XI_WIDTH else f"pair_law{width}", width)
            self.sim.neighbor.histories.append(self.history)

    def compute(self, advance=True):
        sim = self.sim
        a = sim.atom.data
        nb = sim.neighbor
        h = self.history
        xi = h.values if h is not None else np.zeros((1, XI_WIDTH))
        _pair_sphere.compute(ParticleView(sim.atom), nb.offsets, nb.neigh, self.table, xi, h is not None,
                             self.reach > 0, sim.update.dt, advance, self.stats, self.worst)
        self.ncontacts = int(self.stats[0])
        self.max_overlap = float(self.stats[1])
        self.energy = float(self.stats[2])
        if self.ncontacts:
            self.max_overlap_tags = (int(a["tag"][self.worst[0]]), int(a["tag"][self.worst[1]]))
