"""Coefficients of the law against walls, shared by every wall fix (wall/plane, wall/drum, wall/mesh): given
on the fix line for every type (the same words as pair_coeff), taken from `pair_coeff I I`, or, with `type
T`, from `pair_coeff T I`: the wall is then of type T (its material mixed with each particle type's, its
parts and coefficients those of the pair lines). The per-particle history the walls need, and the shortest
contact time (m_ij = m_i against a wall). A Hertz-family row on the fix line: the wall is of the particles'
material (E, nu of the fix line) and R* = R_i (a plane; inside a drum of radius R_d the exact 1 / (1 / R_i -
1 / R_d) is larger by R_i / R_d, left out), R_i the radius of the particle's sphere of equal volume for a
shaped particle (a sphere's own)."""
import numpy as np

from dem.args import parse_types
from dem.errors import DemError

from . import (H_BOND, NCOEFF, WIDE_HISTORY, XI_WIDTH, check_speed, descantes, frictionless, is_hertz_row, parse,
               prepare, row, row_contact_time, warn_frictionless)


class WallCoefficients:
    """Mixin of a wall Fix. `self.table[w, t]` is the coefficient row (row.pxd) of wall w and particle type
    t; `self.history()` the per-particle history array (self.law_width values per wall and per piece of a
    glued composite) or a dummy. `self.contact_law`: "grains3d" (default) or "descantes" (no spring, no
    history)."""
    contact_law = "grains3d"
    max_history = XI_WIDTH          # the history per contact this wall's kernel has room for (None: any)

    def parse_law(self, words):
        what = f"fix {self.id} {self.style}"
        self.where = self.sim.input.location      # this line, for errors found at the run (init_table)
        self.wall_type = None
        words = list(words)
        if "type" in words[::2]:
            k = 2 * words[::2].index("type")
            if k + 1 >= len(words):
                raise DemError(f"{what}: type needs the particle type whose material the wall is of")
            self.wall_type = parse_types(words[k + 1], self.sim.atom.ntypes, "wall type")
            if len(self.wall_type) != 1:
                raise DemError(f"{what}: type takes one type, got '{words[k + 1]}'")
            self.wall_type = self.wall_type[0]
            del words[k:k + 2]
            if words:
                raise DemError(f"{what}: a wall of type {self.wall_type} takes its law from pair_coeff "
                               f"{self.wall_type} I; it takes no coefficients of its own ({' '.join(words)})")
        law = parse(words, what, required=()) if words else {}
        if law.get("normal", "hooke") != "hooke":
            if self.contact_law in ("descantes", "volume"):
                raise DemError(f"{what}: law {self.contact_law} is a Hooke law (kn, en); it does not take normal "
                               f"{law['normal']}")
        elif law and not {"kn", "en"} <= set(law):
            raise DemError(f"{what}: give both kn and en (or neither, to use pair_coeff I I)")
        if frictionless(law):
            warn_frictionless(self.sim, self, what)
        elif (self.contact_law == "descantes" and law.get("mu", 0.0) > 0 and not law.get("gamma_t", 0.0) > 0
              and not law.get("beta_t", 0.0) > 0):
            self.sim.warning(f"{what}: law descantes has no tangential spring: with gamma_t = beta_t = 0 the "
                             f"tangential force is zero whatever mu and ks are (give gamma_t or beta_t for "
                             f"friction)")
        self.law = law

    def init_table(self, nwalls):
        sim = self.sim
        nt = sim.atom.ntypes
        self.table = np.zeros((nwalls, nt + 1, NCOEFF))
        for t in range(1, nt + 1):
            if self.law:
                self.table[:, t] = row(self.law)
            elif sim.pair is not None and hasattr(sim.pair, "coefficients"):
                self.table[:, t] = sim.pair.coefficients(t if self.wall_type is None else self.wall_type, t)
            else:
                raise DemError(f"fix {self.id} {self.style}: no coefficients given and no pair style to "
                               f"take them from")
        self.check_hertz()
        if self.contact_law == "descantes":      # Descantes' law has no spring: no history
            self.table[:] = descantes(self.table)
        self.law_width = prepare(self.table[:, 1:])
        if self.max_history is not None and self.law_width > self.max_history:
            raise DemError(f"{self._where()}fix {self.id} {self.style}: {WIDE_HISTORY} keep history this wall has "
                           f"no room for yet",
                           hint="fix wall/plane and wall/drum have them")
        self.use_history = self.law_width > 0
        self.bonds = bool(np.any(self.table[:, 1:, H_BOND] >= 0))     # a row acts beyond contact
        if self.use_history:
            sim.atom.add_field(self.history_name, (self.history_width(nwalls),), np.float64, 0.0)

    def history_width(self, nwalls):
        """History values per particle: law_width per wall and per piece of a composite (piece c of wall w
        at law_width (c nwalls + w))."""
        return self.law_width * nwalls * self.sim.shapes.max_components

    @property
    def history_name(self):
        return f"fix_{self.id}_xi"

    def history(self):
        return self.sim.atom.data[self.history_name] if self.use_history else np.zeros((1, XI_WIDTH))

    def _where(self):
        return f"{self.where}: " if getattr(self, "where", None) else ""

    def check_hertz(self):
        """Hertz rows (R* = R_i, the radius of the particle's sphere of equal volume) are refused with law
        descantes, a Hooke law."""
        if not np.any(is_hertz_row(self.table[:, 1:])):
            return
        if self.contact_law in ("descantes", "volume"):
            raise DemError(f"{self._where()}fix {self.id} {self.style}: law {self.contact_law} is a Hooke law (kn, "
                           f"en); it does not take the model hertz of pair_coeff (give kn and en on the fix line)")

    def min_contact_time(self):
        atom = self.sim.atom
        n = atom.nlocal
        types = atom.data["type"][:n]
        tmin = np.inf
        # collective (every rank, with or without particles): decided on the table, the same everywhere
        speed = check_speed(self.sim) if np.any(is_hertz_row(self.table[0, 1:])) else None
        req = self.sim.shapes.equivalent_radius(atom.data["shape"][:n], atom.data["radius"][:n])
        for t in np.unique(types):
            sel = types == t
            m = float(atom.data["rmass"][:n][sel].min())
            radius = float(req[sel].min())
            tmin = min(tmin, row_contact_time(self.table[0, t], m, radius, speed))
        tmin = self.sim.comm.min(tmin)     # collective: every rank, with or without particles
        return tmin if np.isfinite(tmin) else None

    def unfix(self):
        self.sim.atom.remove_field(self.history_name)
