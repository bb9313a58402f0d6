"""Per-type-pair coefficients of the Grains3D law, shared by every pair style that uses it (sphere,
convex/gjk, ...): `pair_coeff I J kn KN en EN [mu ..] [gamma_t ..] [beta_t ..] [ks ..] [mu_roll ..]`, the check that
every type pair is set, the need for tangential history, and the shortest contact time. `model hertz E ..
nu .. en .. mu ..` (hertz.py): R* from the radii of the bodies' spheres of equal volume (a sphere's own)."""
import numpy as np

from dem.args import parse_types
from dem.errors import DemError

from . import (NCOEFF, check_speed, frictionless, is_hertz_row, needs_history, parse, row, row_contact_time,
               warn_frictionless)


class PairCoefficients:
    """Mixin of a Pair: `self.table[ti, tj]` is the coefficient row (law.pxd reads it) of types ti, tj."""

    coeff_usage = "pair_coeff I J kn KN en EN [mu ..] [gamma_t ..] [beta_t ..] [ks ..] [mu_roll ..]"

    def init_coefficients(self):
        nt = self.sim.atom.ntypes
        self.table = np.zeros((nt + 1, nt + 1, NCOEFF))
        self.set = np.zeros((nt + 1, nt + 1), dtype=bool)

    def coeff(self, words):
        if len(words) < 2:
            raise DemError(f"pair_coeff needs: {self.coeff_usage}")
        nt = self.sim.atom.ntypes
        ti = parse_types(words[0], nt, "type I")
        tj = parse_types(words[1], nt, "type J")
        law = parse(words[2:], "pair_coeff")
        if law.get("model") == "hertz" and getattr(self, "law", "grains3d") == "descantes":
            raise DemError(f"pair_coeff: pair_style {self.style} law descantes is a Hooke law (kn, en); it does "
                           f"not take model hertz")
        if frictionless(law):
            warn_frictionless(self.sim, self, "pair_coeff")
        r = row(law)
        for a in ti:
            for b in tj:
                self.table[a, b] = r
                self.table[b, a] = r
                self.set[a, b] = self.set[b, a] = True

    def coefficients(self, ti, tj):
        return self.table[ti, tj]

    def check_coefficients(self):
        """Every type pair set; returns whether any pair needs tangential history (ks > 0)."""
        nt = self.sim.atom.ntypes
        missing = [(a, b) for a in range(1, nt + 1) for b in range(a, nt + 1) if not self.set[a, b]]
        if missing:
            a, b = missing[0]
            raise DemError(f"pair_coeff missing for types {a} {b}")
        return needs_history(self.table[1:, 1:])

    def min_contact_time(self):
        """Shortest T_c over type pairs, with the lightest (and, for Hertz rows, smallest: T_c grows as the
        radius) particles present; Hertz rows at the impact speed of dem_contact.check_speed."""
        atom = self.sim.atom
        n = atom.nlocal
        tmin = np.inf
        types = atom.data["type"][:n]
        masses = {t: float(atom.data["rmass"][:n][types == t].min()) for t in np.unique(types)}
        req = self.sim.shapes.equivalent_radius(atom.data["shape"][:n], atom.data["radius"][:n])
        radii = {t: float(req[types == t].min()) for t in np.unique(types)}
        # collective (every rank, with or without particles): decided on the table, the same everywhere
        speed = check_speed(self.sim) if np.any(is_hertz_row(self.table[1:, 1:])) else None
        for ta, ma in masses.items():
            for tb, mb in masses.items():
                ra, rb = radii[ta], radii[tb]
                t = row_contact_time(self.table[ta, tb], ma * mb / (ma + mb), ra * rb / (ra + rb), speed)
                tmin = min(tmin, t)
        tmin = self.sim.comm.min(tmin)     # collective: every rank, with or without particles
        return tmin if np.isfinite(tmin) else None
