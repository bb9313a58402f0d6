"""Drum analysis computes: repose (dynamic angle of repose of the free surface) and corotate (fraction of
particles in rigid-body rotation with the drum, the centrifuging indicator)."""
import math

import numpy as np

from dem.compute import Compute

from ._common import cross_section_basis, find_drum


SURFACE_GAP = 4.0      # a vertical gap of this many largest radii in a bin's column ends the bed there


def surface_fit(h, u, nbins=20, trim=0.15, gap=math.inf):
    """Free surface of a bed seen in a drum's cross-section: particles at horizontal h and height u. The
    h-range of the particles is cut into nbins bins; in each, the top of the bed marks the surface: the
    highest particle of the column that rises from the bin's lowest particle without a vertical gap
    larger than `gap` (so a particle carried on the wall high above the bed, or one in flight, is not
    taken for the surface). A straight line u = a + b h is fitted to the bins of the central part (trim
    of the range left out at each end, where the surface bends along the wall). Returns (angle in degrees,
    b, a, bins used, roughness: the rms distance of the bins' surface particles from the line, across it)."""
    if len(h) < 3:
        return 0.0, 0.0, 0.0, 0, 0.0
    lo, hi = float(h.min()), float(h.max())
    if hi <= lo:
        return 0.0, 0.0, 0.0, 0, 0.0
    k = np.minimum(((h - lo) / (hi - lo) * nbins).astype(np.int64), nbins - 1)
    order = np.lexsort((u, k))                 # by bin, then upwards
    ks, us = k[order], u[order]
    first = np.r_[True, ks[1:] != ks[:-1]]
    breaks = np.cumsum(~first & (np.diff(us, prepend=-np.inf) > gap))
    column = breaks == np.maximum.accumulate(np.where(first, breaks, 0))   # no gap since the bin's bottom
    kept, kk = order[column], ks[column]
    last = np.r_[kk[1:] != kk[:-1], True]      # the last kept of each bin: its column's top
    which = np.full(nbins, -1, dtype=np.int64)
    which[kk[last]] = kept[last]
    top = np.where(which >= 0, u[which], -np.inf)
    centres = lo + (np.arange(nbins) + 0.5) * (hi - lo) / nbins
    keep = np.isfinite(top) & (centres >= lo + trim * (hi - lo)) & (centres <= hi - trim * (hi - lo))
    if keep.sum() < 2:
        return 0.0, 0.0, 0.0, int(keep.sum()), 0.0
    hs, us = h[which[keep]], top[keep]
    b, a = np.polyfit(hs, us, 1)
    rough = math.sqrt(float(np.mean((us - a - b * hs) ** 2)) / (1.0 + b * b))
    return math.degrees(math.atan(b)), float(b), float(a), int(keep.sum()), rough


class ComputeRepose(Compute):
    """compute ID group repose DRUM-FIX-ID [bins N] [trim F]

    Dynamic angle of repose (degrees) of the free surface of the bed in a rotating drum (fix wall/drum):
    positions are projected on the drum's cross-section, with the vertical opposite to the first fix
    gravity (+z without one); the horizontal extent of the bed is cut into N bins (default 20), the
    top of the bed in each bin marks the free surface (the highest particle of the column that rises
    from the bin's lowest one without a vertical gap of more than 4 of the group's largest bounding
    radii: a particle carried high on the wall or in flight is not the surface), and a least-squares
    line through the surface points of the central bins (leaving out a fraction F = 0.15 of the extent
    at each end, where the surface bends) gives the angle. Scalar: |angle|. Vector: [signed angle
    (positive: the surface rises towards +h, h = up x axis), slope, height of the line at the axis (m),
    surface points used, roughness (m): the rms distance of the surface points from the line (a flat
    surface: ~0)].
    Meaningful in the rolling and cascading regimes (a flat-ish surface); in cataracting or
    centrifuging regimes, flying or wall-borne particles make it a rough indicator only."""

    style = "repose"
    size_vector = 5
    vector_names = ("angle", "slope", "intercept", "points", "roughness")
    usage = "DRUM-FIX-ID [bins N] [trim F]"

    def __init__(self, sim, cid, group, args):
        super().__init__(sim, cid, group, args)
        a = self.parser()
        a.need(1)
        self.drum_id = a[0]
        kw = a.keywords(1, {"bins": 1, "trim": 1})
        self.nbins = a.to_int(kw["bins"][0], "bins") if "bins" in kw else 20
        self.trim = a.to_float(kw["trim"][0], "trim") if "trim" in kw else 0.15
        if self.nbins < 3 or not 0 <= self.trim < 0.5:
            raise a.error("bins must be >= 3 and 0 <= trim < 0.5")

    def compute_vector(self):
        sim = self.sim
        drum = find_drum(sim, self.drum_id, f"compute {self.id} repose")
        _, eh, up = cross_section_basis(sim, drum)
        atom = sim.atom
        sel = self.group_mask()
        # every rank fits the same surface, through all the particles
        _, x = sim.comm.allgather_rows(atom.data["tag"][:atom.nlocal][sel], atom.data["x"][:atom.nlocal][sel])
        r = atom.data["radius"][:atom.nlocal][sel]
        gap = SURFACE_GAP * sim.comm.max(float(r.max()) if len(r) else 0.0)
        x = np.asarray(x).reshape(-1, 3) - drum.centre
        return np.array(surface_fit(x @ eh, x @ up, self.nbins, self.trim, gap), dtype=float)

    def compute_scalar(self):
        return abs(self.vector()[0])


class ComputeCorotate(Compute):
    """compute ID group corotate DRUM-FIX-ID [tol T]

    Fraction of the group's particles in rigid-body rotation with the drum of fix wall/drum: those whose
    velocity differs from the drum's, Omega x r at their centre, by less than T Omega R (default T =
    0.1; Omega the current rate, R the drum radius). 0 while the drum is at rest.

    The centrifuging indicator is the second value: at low rates the bed also rotates as a rigid body in
    its lower, passive part (and the whole bed does while its surface tilts up at start-up), but only
    a centrifuged bed is carried over the top. "Top": within 45 degrees of the top of the drum's
    cross-section and more than R/2 from the axis (near the wall). Vector: [co-rotating fraction,
    fraction that co-rotates at the top (centrifuging: about a quarter of the particles; 0 otherwise),
    fraction at the top]. The vertical is opposite to the first fix gravity (+z without one)."""

    style = "corotate"
    size_vector = 3
    vector_names = ("corotating", "corotating_top", "top")
    usage = "DRUM-FIX-ID [tol T]"

    def __init__(self, sim, cid, group, args):
        super().__init__(sim, cid, group, args)
        a = self.parser()
        a.need(1)
        self.drum_id = a[0]
        kw = a.keywords(1, {"tol": 1})
        self.tol = a.to_float(kw["tol"][0], "tol") if "tol" in kw else 0.1
        if self.tol <= 0:
            raise a.error("tol must be > 0")

    def compute_vector(self):
        sim = self.sim
        drum = find_drum(sim, self.drum_id, f"compute {self.id} corotate")
        _, eh, up = cross_section_basis(sim, drum)
        atom = sim.atom
        sel = self.group_mask()
        x = atom.data["x"][:atom.nlocal][sel]
        v = atom.data["v"][:atom.nlocal][sel]
        comm = sim.comm
        n = comm.sum(len(x))
        w = abs(drum.omega)
        if not n or w == 0.0:
            return np.zeros(3)
        dv = v - drum.wall_velocity(x)
        co = np.einsum("ij,ij->i", dv, dv) < (self.tol * w * drum.radius) ** 2
        rel = x - drum.centre
        h, u = rel @ eh, rel @ up
        top = (u > np.abs(h)) & (h * h + u * u > 0.25 * drum.radius ** 2)
        return np.array([comm.sum(int(co.sum())), comm.sum(int((co & top).sum())),
                         comm.sum(int(top.sum()))], dtype=float) / n

    def compute_scalar(self):
        return self.vector()[0]
