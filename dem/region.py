"""Geometric regions: block, cylinder and sphere (with `side in|out`), used to create boxes, fill
particles, select groups and, later, by insertion and analysis."""
import numpy as np

from .args import Args
from .errors import DemError

BIG = 1e30


class Region:
    """region ID style args [side in|out]"""

    kind = "region"
    style = None
    usage = ""

    def __init__(self, sim, rid, args):
        self.sim = sim
        self.id = rid
        self.side_in = True
        a = Args(args, f"region {rid} {self.style} {self.usage} [side in|out]", f"region {rid}")
        nfixed = self.nargs
        a.need(nfixed)
        self.parse(a)
        kw = a.keywords(nfixed, {"side": 1, "units": 1})
        if "side" in kw:
            if kw["side"][0] not in ("in", "out"):
                raise a.error("side must be in or out")
            self.side_in = kw["side"][0] == "in"
        if "units" in kw and kw["units"][0] != "box":
            raise a.error("only 'units box' is supported (lengths are in box units)")

    def bound(self, a, i, d, lo):
        """A bound: a number, INF/-INF, or EDGE (the box face)."""
        word = a[i]
        if word in ("INF", "-INF", "EDGE"):
            if word == "EDGE":
                self.sim.domain.require_box(f"region {self.id} with EDGE")
                return self.sim.domain.lo[d] if lo else self.sim.domain.hi[d]
            return -BIG if lo else BIG
        return a.float(i, "bound")

    def inside(self, x):
        x = np.atleast_2d(x)
        inside = self._inside(x)
        return inside if self.side_in else ~inside

    def random_points(self, rng, n, margin=0.0):
        """n uniform random points inside the region (rejection sampling in the bounding box),
        `margin` away from the boundary of an `in` region."""
        lo, hi = self.extent(margin)
        if np.any(hi <= lo):
            raise DemError(f"region {self.id} is too small for particles of this size")
        out = np.zeros((0, 3))
        while len(out) < n:
            trial = lo + (hi - lo) * rng.random((max(2 * (n - len(out)), 64), 3))
            keep = self._inside_margin(trial, margin) if self.side_in else self.inside(trial)
            out = np.vstack([out, trial[keep]])
        return out[:n]

    def extent(self, margin=0.0):
        lo, hi = self.bbox()
        if not self.side_in:
            return self.sim.domain.lo.copy(), self.sim.domain.hi.copy()
        return lo + margin, hi - margin


class RegionBlock(Region):
    """region ID block xlo xhi ylo yhi zlo zhi [side in|out]

    Bounds may be numbers, INF/-INF or EDGE (the box face). Example: `region box block 0 0.02 0 0.02 0 0.05`.
    """

    style = "block"
    usage = "xlo xhi ylo yhi zlo zhi"
    nargs = 6

    def parse(self, a):
        self.lo = np.array([self.bound(a, 2 * d, d, True) for d in range(3)])
        self.hi = np.array([self.bound(a, 2 * d + 1, d, False) for d in range(3)])
        if np.any(self.hi <= self.lo):
            raise a.error("each upper bound must exceed the lower bound")

    def _inside(self, x):
        return np.all((x >= self.lo) & (x <= self.hi), axis=1)

    def _inside_margin(self, x, m):
        return np.all((x >= self.lo + m) & (x <= self.hi - m), axis=1)

    def bbox(self):
        return self.lo.copy(), self.hi.copy()

    def volume(self):
        return float(np.prod(self.hi - self.lo))


class RegionCylinder(Region):
    """region ID cylinder dim c1 c2 radius lo hi [side in|out]

    Axis along dim (x, y or z) through (c1, c2) in the other two coordinates (in x, y, z order), from lo
    to hi along the axis (numbers, INF or EDGE). Example: `region drum cylinder y 0 0 0.05 0 0.024`."""

    style = "cylinder"
    usage = "dim c1 c2 radius lo hi"
    nargs = 6

    def parse(self, a):
        if a[0] not in ("x", "y", "z"):
            raise a.error("dim must be x, y or z")
        self.axis = "xyz".index(a[0])
        self.others = [d for d in range(3) if d != self.axis]
        self.c = np.array([a.float(1, "c1"), a.float(2, "c2")])
        self.radius = a.float(3, "radius", positive=True)
        self.lo = self.bound(a, 4, self.axis, True)
        self.hi = self.bound(a, 5, self.axis, False)
        if self.hi <= self.lo:
            raise a.error("hi must exceed lo")

    def _inside_margin(self, x, m):
        r2 = np.sum((x[:, self.others] - self.c) ** 2, axis=1)
        ax = x[:, self.axis]
        return (r2 <= (self.radius - m) ** 2) & (ax >= self.lo + m) & (ax <= self.hi - m)

    def _inside(self, x):
        return self._inside_margin(x, 0.0)

    def bbox(self):
        lo, hi = np.zeros(3), np.zeros(3)
        lo[self.others] = self.c - self.radius
        hi[self.others] = self.c + self.radius
        lo[self.axis], hi[self.axis] = self.lo, self.hi
        return lo, hi

    def volume(self):
        return float(np.pi * self.radius ** 2 * (self.hi - self.lo))


class RegionSphere(Region):
    """region ID sphere x y z radius [side in|out]"""

    style = "sphere"
    usage = "x y z radius"
    nargs = 4

    def parse(self, a):
        self.center = np.array(a.floats(0, 3, "centre"))
        self.radius = a.float(3, "radius", positive=True)

    def _inside_margin(self, x, m):
        return np.sum((x - self.center) ** 2, axis=1) <= (self.radius - m) ** 2

    def _inside(self, x):
        return self._inside_margin(x, 0.0)

    def bbox(self):
        return self.center - self.radius, self.center + self.radius

    def volume(self):
        return float(4.0 / 3.0 * np.pi * self.radius ** 3)


REGIONS = [RegionBlock, RegionCylinder, RegionSphere]
