"""Coefficients of the Grains3D law against walls, shared by every wall fix (wall/plane, wall/drum ...):
given on the fix line for every type, or taken from `pair_coeff I I`; the per-particle tangential history
the walls need; and the shortest contact time (m_ij = m_i against a wall)."""
import numpy as np

from dem.errors import DemError

from . import EN, KN, KS, NCOEFF, XI_WIDTH, contact_time, frictionless, parse, row, warn_frictionless


class WallCoefficients:
    """Mixin of a wall Fix. `self.table[w, t]` is the coefficient row (law.pxd reads it) of wall w and
    particle type t; `self.history()` the per-particle history array (XI_WIDTH values per wall and per piece of a glued
    composite) or a dummy. `self.contact_law`: "grains3d" (default) or "descantes" (no spring, no history)."""
    contact_law = "grains3d"

    def parse_law(self, words):
        what = f"fix {self.id} {self.style}"
        law = parse(words, what, required=()) if words else {}
        if law and not {"kn", "en"} <= set(law):
            raise DemError(f"{what}: give both kn and en (or neither, to use pair_coeff I I)")
        if frictionless(law):
            warn_frictionless(self.sim, self, what)
        elif self.contact_law == "descantes" and law.get("mu", 0.0) > 0 and not law.get("gamma_t", 0.0) > 0:
            self.sim.warning(f"{what}: law descantes has no tangential spring: with gamma_t = 0 the "
                             f"tangential force is zero whatever mu and ks are (give gamma_t for friction)")
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
        # Descantes' law (`law descantes` of the wall fixes) has no spring: no history
        self.use_history = bool(np.any(self.table[:, 1:, KS] > 0)) and self.contact_law == "grains3d"
        if self.use_history:     # per wall and per piece of a composite (piece c of wall w: slot c nwalls + w)
            pieces = sim.shapes.max_components
            sim.atom.add_field(self.history_name, (XI_WIDTH * nwalls * pieces,), np.float64, 0.0)

    @property
    def history_name(self):
        return f"fix_{self.id}_xi"

    def history(self):
        return self.sim.atom.data[self.history_name] if self.use_history else np.zeros((1, XI_WIDTH))

    def min_contact_time(self):
        atom = self.sim.atom
        n = atom.nlocal
        types = atom.data["type"][:n]
        tmin = np.inf
        for t in np.unique(types):
            m = float(atom.data["rmass"][:n][types == t].min())
            r = self.table[0, t]
            tmin = min(tmin, contact_time(r[KN], r[EN], m))
        tmin = self.sim.comm.min(tmin)     # collective: every rank, with or without particles
        return tmin if np.isfinite(tmin) else None

    def unfix(self):
        self.sim.atom.remove_field(self.history_name)
