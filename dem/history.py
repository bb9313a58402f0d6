"""Per-pair contact history (e.g. the tangential spring) that survives neighbor-list rebuilds, restarts and
migration between ranks: stored per pair while a list lives, per particle (keyed by partner tag) across a
rebuild. No history is advanced by a setup pass.

`History`: one record per pair, a dense row per list entry (the pair styles of today). `KeyedHistory`:
any number of records per pair, each with a key (composites, polyhedra)."""
import numpy as np

from . import _history
from .errors import DemError


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
        nlocal = min(atom.nlocal, len(nb.offsets) - 1)     # particles added since the build have no row
        while True:
            need = _history.pack(nb.offsets, nb.neigh, atom.data["tag"], self.values, nlocal,
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


MIN_RECORDS = 64        # first size of a keyed next buffer
GROWTH = 1.5            # growth of a full buffer or per-particle store


class KeyedHistory:
    """Several records per neighbor pair, each with an int64 key (0: a single contact point; the component
    pair for composites; a geometric feature key for polyhedra), `width` values each.

    Records of list entry k: rows `offsets[k]:offsets[k+1]` of `keys` and `values`. A pair kernel takes
    `self.buffers` (a `_history.KeyedBuffers`; in Cython `&buffers.view`, the API of `dem/_history.pxd`)
    and is driven by `step()`. Across a rebuild, restarts and migration the records are kept per particle
    by (partner tag, key) in the atom fields `{name}_n, _tag, _key, _val`; a store without `_key` (a
    single-record history, or a restart of version 1) reads as key-0 records."""

    keyed = True

    def __init__(self, sim, name, width, slots=8):
        self.sim = sim
        self.name = name
        self.width = width
        self.buffers = _history.KeyedBuffers(width)
        self.nresumes = 0           # kernel calls that stopped on a full buffer (for tests and tuning)
        pending = sim.atom.pending
        tags, vals = pending.get(f"{name}_tag"), pending.get(f"{name}_val")
        if tags is not None:        # a restart: take its store as it is
            slots = tags.shape[1]
            if vals is not None and vals.shape[1] != slots * width:
                raise DemError(f"contact history '{name}': the restart holds {vals.shape[1] // max(slots, 1)} "
                               f"values per record, this pair style {width}")
        self._declare(slots)

    def _declare(self, slots):
        atom = self.sim.atom
        atom.add_field(f"{self.name}_n", (), np.int32, 0)
        atom.add_field(f"{self.name}_tag", (slots,), np.int64, 0)
        atom.add_field(f"{self.name}_key", (slots,), np.int64, 0)
        atom.add_field(f"{self.name}_val", (slots * self.width,), np.float64, 0.0)

    def _store(self):
        d = self.sim.atom.data
        return (d[f"{self.name}_n"], d[f"{self.name}_tag"], d[f"{self.name}_key"], d[f"{self.name}_val"])

    # ----- around rebuilds -----------------------------------------------------------------------
    def pack(self):
        """Copy the live records into the per-particle store."""
        atom, nb = self.sim.atom, self.sim.neighbor
        if nb.offsets is None or self.buffers.nentries != nb.nentries:
            return
        nlocal = min(atom.nlocal, len(nb.offsets) - 1)     # particles added since the build have no row
        while True:
            need = _history.pack_keyed(nb.offsets, nb.neigh, atom.data["tag"], self.buffers, nlocal,
                                       *self._store())
            if not need:
                return
            self._declare(int(need * GROWTH) + 1)

    def unpack(self):
        """Give the pairs of a freshly built list their records back, matched by partner tag and key."""
        atom, nb = self.sim.atom, self.sim.neighbor
        offsets = np.zeros(nb.nentries + 1, np.int64)
        cap = int(self._store()[0][:atom.nlocal].sum())
        while True:
            keys, values = np.zeros(cap, np.int64), np.zeros((cap, self.width))
            total = _history.unpack_keyed(nb.offsets, nb.neigh, atom.data["tag"], atom.nlocal, *self._store(),
                                          offsets, keys, values)
            if total <= cap:
                break
            cap = total
        self.buffers.set_old(offsets, keys, values)

    def discard(self):
        """Forget every record (the pair style that owned this history was replaced)."""
        for suffix in ("_n", "_tag", "_key", "_val"):
            self.sim.atom.remove_field(self.name + suffix)
        self.buffers = _history.KeyedBuffers(self.width)

    # ----- one step ------------------------------------------------------------------------------
    def step(self, kernel, advance=True):
        """Drive a keyed kernel over the list: `kernel(start)` handles the entries from `start` on and
        returns -1, or the entry it stopped before because the next buffer was full; the buffer then
        grows (what was appended for that entry is dropped) and the kernel is called again from there.
        With `advance` False (setup passes) the old records stay as they were."""
        b = self.buffers
        b.begin(max(b.nrec, MIN_RECORDS))
        start = 0
        while True:
            resume = kernel(start)
            if b.error:
                raise RuntimeError(f"keyed history '{self.name}': a kernel broke the append protocol "
                                   f"(code {b.error})")
            if resume < 0:
                break
            if resume < start:
                raise RuntimeError(f"keyed history '{self.name}': a kernel resumed at {resume} < {start}")
            self.nresumes += 1
            b.rollback(resume)
            b.grow(max(b.want, int(GROWTH * b.next_n) + 1))
            start = resume
        b.finish()
        if advance:
            b.swap()

    # ----- Python access (tests, tools; never per step) ------------------------------------------
    @property
    def offsets(self):
        return self.buffers.offsets[:self.buffers.nentries + 1]

    @property
    def keys(self):
        return self.buffers.keys[:self.buffers.nrec]

    @property
    def values(self):
        return self.buffers.values[:self.buffers.nrec]

    def records(self, k):
        """(keys, values) of list entry k (copies)."""
        o = self.buffers.offsets
        return self.buffers.keys[o[k]:o[k + 1]].copy(), self.buffers.values[o[k]:o[k + 1]].copy()

    def set_records(self, k, keys, values):
        """Replace the records of list entry k (keys unique)."""
        keys = np.asarray(keys, dtype=np.int64).reshape(-1)
        values = np.asarray(values, dtype=np.float64).reshape(len(keys), self.width)
        if len(np.unique(keys)) != len(keys):
            raise ValueError(f"keyed history '{self.name}': keys of one pair must be unique")
        o, n = self.offsets.copy(), self.buffers.nrec
        lo, hi = o[k], o[k + 1]
        new_keys = np.concatenate([self.buffers.keys[:lo], keys, self.buffers.keys[hi:n]])
        new_values = np.concatenate([self.buffers.values[:lo], values, self.buffers.values[hi:n]])
        o[k + 1:] += len(keys) - (hi - lo)
        self.buffers.set_old(o, new_keys, new_values)

    def by_tags(self):
        """{(tag i, tag j, key): values} of this rank's records."""
        nb, tag = self.sim.neighbor, self.sim.atom.data["tag"]
        i, j = nb.pairs()
        entry = np.repeat(np.arange(len(i)), np.diff(self.offsets))
        ti, tj = tag[i[entry]], tag[j[entry]]
        return {(int(a), int(b), int(c)): tuple(v) for a, b, c, v in zip(ti, tj, self.keys, self.values)}
