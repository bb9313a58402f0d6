"""Per-type-pair coefficients of the law, shared by every pair style (sphere, convex/gjk, ...): `pair_coeff
I J` lines of parts and coefficients (dem.law), the materials of each type mixed for the pairs of two types
whose line leaves them out, the check that every type pair is set, the history the table needs, how far
beyond contact it acts, and the shortest contact time. Hertz-family rows between shaped bodies take R* from
the radii of the bodies' spheres of equal volume (a sphere's own)."""
import numpy as np

from dem.args import parse_types
from dem.errors import DemError

from . import (ADHESIVE, NCOEFF, WIDE_HISTORY, XI_WIDTH, check_speed, descantes, frictionless, has_material,
               is_hertz_row, max_reach, mix_materials, parse, prepare, row, row_contact_time, warn_frictionless)


class PairCoefficients:
    """Mixin of a Pair: `self.table[ti, tj]` is the coefficient row (row.pxd) of types ti, tj; after
    `check_coefficients`, `self.history_width` the values of history each contact keeps (0: none)."""

    coeff_usage = "pair_coeff I J kn KN en EN [mu ..] [gamma_t ..] [beta_t ..] [ks ..] [mu_roll ..]"
    # the history this style's kernel can keep per contact (None: any layout of prepare)
    max_history = XI_WIDTH

    def init_coefficients(self):
        nt = self.sim.atom.ntypes
        self.table = np.zeros((nt + 1, nt + 1, NCOEFF))
        self.rows = np.zeros_like(self.table)      # as the lines make them (table: as the kernel reads them)
        self.set = np.zeros((nt + 1, nt + 1), dtype=bool)
        self.lines = {}          # (a, b), a <= b: (parsed line, where) of the line that set it
        self.history_width = 0

    def coeff(self, words):
        if len(words) < 2:
            raise DemError(f"pair_coeff needs: {self.coeff_usage}")
        nt = self.sim.atom.ntypes
        ti = parse_types(words[0], nt, "type I")
        tj = parse_types(words[1], nt, "type J")
        same = any(a in tj for a in ti)
        law = parse(words[2:], "pair_coeff", same_type=same)
        style_law = getattr(self, "law", "grains3d")
        if law["normal"] != "hooke" and style_law in ("descantes", "volume"):
            raise DemError(f"pair_coeff: pair_style {self.style} law {style_law} is a Hooke law (kn, en); it does "
                           f"not take normal {law['normal']}")
        if frictionless(law):
            warn_frictionless(self.sim, self, "pair_coeff")
        r = row(law) if has_material(law) else np.zeros(NCOEFF)
        where = self.sim.input.location
        for a in ti:
            for b in tj:
                self.table[a, b] = self.table[b, a] = r
                self.rows[a, b] = self.rows[b, a] = r
                self.set[a, b] = self.set[b, a] = True
                self.lines[min(a, b), max(a, b)] = (law, where)

    def coefficients(self, ti, tj):
        """The row of types ti, tj as its line makes it (materials mixed; not this style's `law`): the rows
        a wall takes (dem.law.wall_coeffs)."""
        self._mix()
        return self.rows[ti, tj]

    def _mix(self):
        """The rows of lines that leave their material to their types."""
        for (a, b), (law, where) in self.lines.items():
            if not has_material(law):
                r = row(mix_materials(law, self._material(a, law, where), self._material(b, law, where)))
                self.rows[a, b] = self.rows[b, a] = r

    def check_coefficients(self):
        """Every type pair set, the materials of mixed pairs resolved, the history laid out; returns whether
        contacts keep history."""
        nt = self.sim.atom.ntypes
        missing = [(a, b) for a in range(1, nt + 1) for b in range(a, nt + 1) if not self.set[a, b]]
        if missing:
            a, b = missing[0]
            raise DemError(f"pair_coeff missing for types {a} {b}")
        self._mix()
        self.table[:] = descantes(self.rows) if getattr(self, "law", "grains3d") == "descantes" else self.rows
        self.history_width = prepare(self.table[1:, 1:])
        if self.max_history is not None and self.history_width > self.max_history:
            raise DemError(f"pair_style {self.style}: {WIDE_HISTORY} keep history this pair style has no room "
                           f"for yet", hint="pair_style sphere has them")
        self.reach = max_reach(self.table[1:, 1:], self.sim.modify.max_radius())
        return self.history_width > 0

    def _material(self, t, law, where):
        """The material (E, nu, w) of type t, from its pair_coeff t t line, for a line that leaves it out."""
        own = self.lines.get((t, t))
        adhesive = law["normal"] in ADHESIVE
        if own is None or own[0]["normal"] == "hooke" or (adhesive and "w" not in own[0]):
            need = "E, nu" + (", w" if adhesive else "")
            raise DemError(f"{where + ': ' if where else ''}pair_coeff: this line gives no material ({need}) "
                           f"and type {t} has none of its own (give them here, or on pair_coeff {t} {t} with "
                           f"normal hertz, jkr or dmt)")
        return own[0]

    def min_contact_time(self):
        """Shortest T_c over type pairs, with the lightest (and, for Hertz rows, smallest: T_c grows as the
        radius) particles present; Hertz rows at the impact speed of dem.law.check_speed."""
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
