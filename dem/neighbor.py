"""Neighbor lists: linked cells on bounding spheres with a skin, half list in compressed rows (one row per
owned particle: `offsets[i]:offsets[i+1]` index `neigh`), rebuilt only when the largest displacement since
the last build exceeds half the skin (or a fix asks). Contact histories registered here follow the pairs
across rebuilds."""
import numpy as np

from . import _neighbor
from .errors import DemError


def _morton(v):
    """Spread the 21 low bits of v three apart (Z-order curve: close cells stay close in memory)."""
    v = v & np.uint64(0x1FFFFF)
    for shift, mask in ((32, 0x1F00000000FFFF), (16, 0x1F0000FF0000FF), (8, 0x100F00F00F00F00F),
                        (4, 0x10C30C30C30C30C3), (2, 0x1249249249249249)):
        v = (v | (v << np.uint64(shift))) & np.uint64(mask)
    return v


class Neighbor:
    def __init__(self, sim):
        self.sim = sim
        self.skin = None           # default: 10 % of the largest diameter
        self.every = 1
        self.delay = 0
        self.check = True
        self.offsets = None
        self.neigh = np.zeros(1024, dtype=np.int32)
        self.nentries = 0
        self.xhold = np.zeros((0, 3))
        self.hold_valid = False
        self.last_build = -1
        self.nbuilds = 0
        self.ndanger = 0
        self.histories = []
        self.force_rebuild = False
        self.sort_every = 1000     # spatial sort of particles (memory locality), on rebuild steps
        self.sort_binsize = 0.0    # 0: half the largest pair cutoff
        self.last_sort = -10 ** 9

    # ----- settings ------------------------------------------------------------------------------
    def cutmax(self):
        """Largest pair cutoff: two of the largest bounding spheres, the pair style's reach and the skin."""
        return 2.0 * self.sim.modify.max_radius() + self.reach() + self.skin

    def reach(self):
        """How far beyond touch the pair style's contacts act (a cohesive law: dem.pair.Pair.reach)."""
        return self.sim.pair.reach if self.sim.pair is not None else 0.0

    def init(self):
        rmax = self.sim.modify.max_radius()
        if self.skin is None:
            self.skin = 0.2 * rmax if rmax > 0 else 0.0
        self.sim.comm.cutghost = 2.0 * rmax + self.reach() + self.skin

    def invalidate(self):
        """Particles were added, removed or moved by a command: the next setup rebuilds from scratch."""
        self.hold_valid = False

    # ----- per step ------------------------------------------------------------------------------
    def decide(self, step):
        requested = False
        for fix in self.sim.modify.rebuild_requests:     # every one is asked: it may draw and test
            requested = fix.wants_rebuild(step) or requested
        if self.force_rebuild or requested:
            return True
        since = step - self.last_build
        if since < self.delay or since % self.every:
            return False
        if not self.check:
            return True
        atom = self.sim.atom
        d2 = _neighbor.max_displacement_sq(atom.data["x"], self.xhold, atom.nlocal) if atom.nlocal else 0.0
        d2 = self.sim.comm.max(d2 if np.isfinite(d2) else np.inf)     # one reduction: rebuild or NaN
        if d2 == np.inf:
            self.report_nonfinite()
        half = 0.5 * self.skin
        return d2 > half * half

    def rebuild(self, step, wrap=True):
        """The full rebuild sequence of a step; `wrap=False` rebuilds from the positions of the last
        build (a setup pass continuing a run), so that the list and the wrapping schedule are those of
        the uninterrupted run."""
        sim = self.sim
        for h in self.histories:
            h.pack()
        atom = sim.atom
        if wrap:
            sim.modify.pre_exchange()
            sim.domain.pbc()
            sim.comm.exchange()
            if self.sort_every and step - self.last_sort >= self.sort_every:
                self.sort(step)
            sim.comm.borders()
            sim.modify.pre_neighbor()
            self.build()
            self.xhold = atom.data["x"][:atom.nlocal].copy()
            self.hold_valid = True
            self.last_build = step
            self.nbuilds += 1
            self.force_rebuild = False
        else:
            x_now = atom.data["x"][:atom.nlocal].copy()
            atom.data["x"][:atom.nlocal] = self.xhold
            sim.comm.borders()
            self.build()
            atom.data["x"][:atom.nlocal] = x_now
            sim.comm.forward()
        for h in self.histories:
            h.unpack()
        sim.modify.post_neighbor()

    def sort(self, step):
        """Order owned particles by spatial bin so that neighbors are close in memory. Done on rebuild
        steps only, at the same steps in a continued run (the step of the last sort is restarted)."""
        atom = self.sim.atom
        n = atom.nlocal
        self.last_sort = step
        size = self.sort_binsize or 0.5 * self.cutmax()     # collective: before any early return
        if n < 2 or not size > 0:
            return
        x = atom.data["x"][:n]
        lo = x.min(axis=0)
        cells = np.minimum(np.floor((x - lo) / size).astype(np.uint64), 2 ** 21 - 1)
        key = _morton(cells[:, 0]) | (_morton(cells[:, 1]) << np.uint64(1)) | (_morton(cells[:, 2]) << np.uint64(2))
        order = np.argsort(key, kind="stable")
        atom.permute(order)

    def build(self):
        atom = self.sim.atom
        nlocal, nall = atom.nlocal, atom.nall
        self.offsets = np.zeros(nlocal + 1, dtype=np.int64)
        binsize = max(self.cutmax(), 1e-300)
        while True:
            n = _neighbor.build_half(atom.data["x"], atom.data["radius"], atom.data["tag"], nlocal, nall,
                                     self.skin + self.reach(), binsize, self.offsets, self.neigh)
            if n >= 0:
                break
            self.neigh = np.zeros(int(-n * 1.3) + 64, dtype=np.int32)
        self.nentries = n

    def report_nonfinite(self):
        atom = self.sim.atom
        n = atom.nlocal
        bad = ~np.all(np.isfinite(atom.data["x"][:n]) & np.isfinite(atom.data["v"][:n]), axis=1)
        tags = sorted(t for part in self.sim.comm.allgather(atom.data["tag"][:n][bad][:5].tolist()) for t in part)[:5]
        self.sim.update.nan_error(f" (particle ids {', '.join(map(str, tags))})")

    def pairs(self):
        """(i, j) index arrays of the current list (for analysis and tests, not for kernels)."""
        counts = np.diff(self.offsets)
        i = np.repeat(np.arange(len(counts)), counts)
        return i, self.neigh[:self.nentries].copy()

    def settings(self, skin):
        if skin < 0:
            raise DemError("neighbor skin must be >= 0")
        self.skin = skin
