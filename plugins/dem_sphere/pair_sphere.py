"""pair_style sphere: spheres with the Grains3D contact law."""
import numpy as np

import dem_contact
from dem.args import parse_types
from dem.errors import DemError
from dem.history import History
from dem.pair import Pair

from . import _pair_sphere


class PairSphere(Pair):
    """pair_style sphere

    pair_coeff I J kn KN en EN [mu MU] [gamma_t GT] [ks KS] [mu_roll MUR]

    Spheres in contact when their surfaces overlap (overlap delta, normal n along the line of centres,
    contact point in the middle of the overlap). The Grains3D law (Part III eq. 10-16) per contact:
    normal force kn delta - 2 gamma_n m_ij U_rn with gamma_n from the restitution coefficient en and the
    reduced mass m_ij (eq. 16); tangential force -min(mu |F_n|, |-2 gamma_t m_ij U_rt - ks xi|) along
    the trial force, xi the tangential displacement kept as contact history while ks > 0 (it survives
    neighbor-list rebuilds and restarts). Optional rolling resistance: a torque mu_roll R_eff |F_n|
    opposing the relative angular velocity. Defaults: mu 0, gamma_t 0 (1/s), ks 0 (N/m), mu_roll 0.

    Example::

        pair_style sphere
        pair_coeff * * kn 1e5 en 0.73 mu 0.55 gamma_t 0 ks 0
    """

    style = "sphere"

    def __init__(self, sim, args):
        super().__init__(sim, args)
        if args:
            raise DemError(f"pair_style sphere takes no arguments (coefficients go in pair_coeff), got "
                           f"{' '.join(args)}")
        nt = sim.atom.ntypes
        self.table = np.zeros((nt + 1, nt + 1, dem_contact.NCOEFF))
        self.set = np.zeros((nt + 1, nt + 1), dtype=bool)
        self.history = None
        self.stats = np.zeros(3)
        self.worst = np.zeros(2, dtype=np.int64)

    def coeff(self, words):
        if len(words) < 2:
            raise DemError("pair_coeff needs: pair_coeff I J kn KN en EN [mu ..] [gamma_t ..] [ks ..] [mu_roll ..]")
        nt = self.sim.atom.ntypes
        ti = parse_types(words[0], nt, "type I")
        tj = parse_types(words[1], nt, "type J")
        c = dem_contact.parse(words[2:], "pair_coeff")
        r = dem_contact.row(c)
        for a in ti:
            for b in tj:
                self.table[a, b] = r
                self.table[b, a] = r
                self.set[a, b] = self.set[b, a] = True

    def coefficients(self, ti, tj):
        return self.table[ti, tj]

    def init(self):
        nt = self.sim.atom.ntypes
        missing = [(a, b) for a in range(1, nt + 1) for b in range(a, nt + 1) if not self.set[a, b]]
        if missing:
            a, b = missing[0]
            raise DemError(f"pair_coeff missing for types {a} {b}")
        need_history = bool(np.any(self.table[1:, 1:, dem_contact.KS] > 0))
        if need_history and self.history is None:
            self.history = History(self.sim, "pair_xi", 3)
            self.sim.neighbor.histories.append(self.history)

    def compute(self, advance=True):
        sim = self.sim
        a = sim.atom.data
        nb = sim.neighbor
        h = self.history
        xi = h.values if h is not None else np.zeros((1, 3))
        _pair_sphere.compute(a["x"], a["v"], a["omega"], a["f"], a["torque"], a["radius"], a["rmass"],
                             a["type"], sim.atom.nlocal, nb.offsets, nb.neigh, self.table, xi,
                             h is not None, sim.update.dt, advance, self.stats, self.worst)
        self.ncontacts = int(self.stats[0])
        self.max_overlap = float(self.stats[1])
        self.energy = float(self.stats[2])
        if self.ncontacts:
            self.max_overlap_tags = (int(a["tag"][self.worst[0]]), int(a["tag"][self.worst[1]]))

    def min_contact_time(self):
        """Shortest T_c over type pairs, with the lightest particles present."""
        atom = self.sim.atom
        n = atom.nlocal
        tmin = np.inf
        types = atom.data["type"][:n]
        masses = {t: float(atom.data["rmass"][:n][types == t].min()) for t in np.unique(types)}
        for ta, ma in masses.items():
            for tb, mb in masses.items():
                r = self.table[ta, tb]
                t = dem_contact.contact_time(r[dem_contact.KN], r[dem_contact.EN], ma * mb / (ma + mb))
                tmin = min(tmin, t)
        tmin = self.sim.comm.min(tmin)     # collective: every rank, with or without particles
        return tmin if np.isfinite(tmin) else None
