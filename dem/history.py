"""Per-pair contact history (e.g. the tangential spring) that survives neighbor-list rebuilds, restarts and
migration between ranks: stored per pair while a list lives, per particle (keyed by partner tag) across a
rebuild. No history is advanced by a setup pass."""
import numpy as np

from . import _history


class History:
    def __init__(self, sim, name, nvalues, slots=8):
        self.sim = sim
        self.name = name
        self.nvalues = nvalues
        self.values = np.zeros((0, nvalues))
        pending = sim.atom.pending.get(f"{name}_tag")     # restart written with more slots
        self._declare(max(slots, pending.shape[1]) if pending is not None else slots)

    def _declare(self, slots):
        atom = self.sim.atom
        self.slots = slots
        atom.add_field(f"{self.name}_n", (), np.int32, 0)
        atom.add_field(f"{self.name}_tag", (slots,), np.int64, 0)
        atom.add_field(f"{self.name}_val", (slots * self.nvalues,), np.float64, 0.0)

    def pack(self):
        """Copy the live per-pair values into the per-particle store."""
        atom, nb = self.sim.atom, self.sim.neighbor
        if nb.offsets is None or len(self.values) != nb.nentries:
            return
        while True:
            need = _history.pack(nb.offsets, nb.neigh, atom.data["tag"], self.values, atom.nlocal,
                                 atom.data[f"{self.name}_n"], atom.data[f"{self.name}_tag"],
                                 atom.data[f"{self.name}_val"])
            if not need:
                return
            self._declare(int(need * 1.5) + 1)

    def unpack(self):
        """Give the pairs of a freshly built list their values back."""
        atom, nb = self.sim.atom, self.sim.neighbor
        self.values = np.zeros((nb.nentries, self.nvalues))
        _history.unpack(nb.offsets, nb.neigh, atom.data["tag"], self.values, atom.nlocal,
                        atom.data[f"{self.name}_n"], atom.data[f"{self.name}_tag"],
                        atom.data[f"{self.name}_val"])

    def discard(self):
        """Forget every stored value (the pair style that owned this history was replaced)."""
        for suffix in ("_n", "_tag", "_val"):
            self.sim.atom.remove_field(self.name + suffix)
        self.values = np.zeros((0, self.nvalues))
