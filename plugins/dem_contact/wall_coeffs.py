"""Coefficients of the Grains3D law against walls, shared by every wall fix (wall/plane, wall/drum ...):
given on the fix line for every type, or taken from `pair_coeff I I`; the per-particle tangential history
the walls need; and the shortest contact time (m_ij = m_i against a wall). `model hertz` (hertz.py): the
wall is of the particles' material (E, nu of the fix line, or of pair_coeff I I) and R* = R_i (a plane;
inside a drum of radius R_d the exact 1 / (1 / R_i - 1 / R_d) is larger by R_i / R_d, left out), R_i the
radius of the particle's sphere of equal volume for a shaped particle (a sphere's own)."""
import numpy as np

from dem.errors import DemError

from . import (NCOEFF, XI_WIDTH, check_speed, frictionless, is_hertz_row, needs_history, parse, row,
               row_contact_time, warn_frictionless)


class WallCoefficients:
    """Mixin of a wall Fix. `self.table[w, t]` is the coefficient row (law.pxd reads it) of wall w and
    particle type t; `self.history()` the per-particle history array (XI_WIDTH values per wall and per piece of a glued
    composite) or a dummy. `self.contact_law`: "grains3d" (default) or "descantes" (no spring, no history)."""
    contact_law = "grains3d"

    def parse_law(self, words):
        what = f"fix {self.id} {self.style}"
        law = parse(words, what, required=()) if words else {}
        self.where = self.sim.input.location      # this line, for errors found at the run (init_table)
        if law.get("model") == "hertz":
            if self.contact_law == "descantes":
                raise DemError(f"{what}: law descantes is a Hooke law (kn, en); it does not take model hertz")
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
                self.table[:, t] = sim.pair.coefficients(t, t)
            else:
                raise DemError(f"fix {self.id} {self.style}: no coefficients given and no pair style to "
                               f"take them from")
        self.check_hertz()
        # Descantes' law (`law descantes` of the wall fixes) has no spring: no history
        self.use_history = needs_history(self.table[:, 1:]) and self.contact_law == "grains3d"
        if self.use_history:
            sim.atom.add_field(self.history_name, (self.history_width(nwalls),), np.float64, 0.0)

    def history_width(self, nwalls):
        """History values per particle: XI_WIDTH per wall and per piece of a composite (piece c of wall w
        at slot c nwalls + w)."""
        return XI_WIDTH * nwalls * self.sim.shapes.max_components

    @property
    def history_name(self):
        return f"fix_{self.id}_xi"

    def history(self):
        return self.sim.atom.data[self.history_name] if self.use_history else np.zeros((1, XI_WIDTH))

    def check_hertz(self):
        """Hertz rows (R* = R_i, the radius of the particle's sphere of equal volume) are refused with law
        descantes, a Hooke law."""
        if not np.any(is_hertz_row(self.table[:, 1:])):
            return
        where = f"{self.where}: " if getattr(self, "where", None) else ""
        what = f"{where}fix {self.id} {self.style}"
        if self.contact_law == "descantes":
            raise DemError(f"{what}: law descantes is a Hooke law (kn, en); it does not take the model hertz "
                           f"of pair_coeff (give kn and en on the fix line)")

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
