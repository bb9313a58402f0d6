"""Drum analysis computes: repose (dynamic angle of repose of the free surface) and corotate (fraction of
particles in rigid-body rotation with the drum, the centrifuging indicator)."""
import math

import numpy as np

from dem.comm.serial import Comm
from dem.compute import Compute

from ._common import cross_section_basis, find_drum


SURFACE_GAP = 4.0      # a gap of this many largest radii across the surface, in a bin's column, ends the bed
SURFACE_TURNS = 100    # at most this many turns of the frame
MAX_BINS = 100000      # bins across a drum's bed: far more than its particles along the surface
_ONE = Comm(None)      # the reductions of one process (surface_fit called on arrays: tests, tools)


def _runs(s, n, k, gap, h, u):
    """This process's columns, cut at gaps: rows (bin, n of the lowest, n of the highest, h and u of the
    highest) of every run of particles of one bin sorted outwards with no gap across the surface larger
    than `gap`. Runs are what the processes exchange: a handful per bin, whatever the particles."""
    if len(s) == 0:
        return np.zeros((0, 5))
    order = np.lexsort((n, k))                 # by bin, then outwards
    ks, ns = k[order], n[order]
    new = np.r_[True, (ks[1:] != ks[:-1]) | (np.diff(ns) > gap)]
    first = np.flatnonzero(new)
    last = np.r_[first[1:], len(ks)] - 1
    top = order[last]
    return np.column_stack([ks[first], ns[first], ns[last], h[top], u[top]])


def _column_tops(runs, nbins, gap):
    """Per bin, (h, u) of the top of the column that rises from the bin's innermost particle without a gap
    larger than `gap`, from the runs of every process (_runs): from the lowest run, the next ones join
    while they start within `gap` of the column's top; nan where a bin is empty. The same on every
    process (the same runs in the same order)."""
    tops = np.full((nbins, 2), np.nan)
    if len(runs) == 0:
        return tops
    runs = runs[np.lexsort((runs[:, 1], runs[:, 0]))]
    b, lo, hi = runs[:, 0].astype(np.int64), runs[:, 1], runs[:, 2]
    start = np.r_[True, b[1:] != b[:-1]]
    for i in np.flatnonzero(start):            # a Python loop over bins (runs beyond a gap end it early)
        j, top = i, hi[i]
        best = i
        while j + 1 < len(b) and b[j + 1] == b[i] and lo[j + 1] - top <= gap:
            j += 1
            if hi[j] > top:
                top, best = hi[j], j
        tops[b[i]] = runs[best, 3:5]
    return tops


def _surface_tops(h, u, theta, nbins, trim, gap, comm):
    """(h, u) of the particles marking the surface, in a frame turned by theta where s runs along it and n
    across it (outwards). The s-range of the particles (of every process) is cut into nbins bins; in each,
    the top of the bed is the outermost particle of the column that rises from the bin's innermost
    particle without a gap across the surface larger than `gap` (a particle carried on the wall or in
    flight is not the surface). The bins of the central part are kept (trim of the range left out at each
    end, where the surface meets the wall)."""
    c, sn = math.cos(theta), math.sin(theta)
    s, n = h * c + u * sn, u * c - h * sn
    lo = comm.min(float(s.min()) if len(s) else math.inf)
    hi = comm.max(float(s.max()) if len(s) else -math.inf)
    if not hi > lo:
        return np.zeros((0, 2))
    k = np.minimum(((s - lo) / (hi - lo) * nbins).astype(np.int64), nbins - 1)
    tops = _column_tops(np.concatenate(comm.allgather(_runs(s, n, k, gap, h, u))), nbins, gap)
    centres = lo + (np.arange(nbins) + 0.5) * (hi - lo) / nbins
    keep = ~np.isnan(tops[:, 0]) & (centres >= lo + trim * (hi - lo)) & (centres <= hi - trim * (hi - lo))
    return tops[keep]


def _long_axis(x, y):
    """Angle (radians, within +-90 degrees) of the direction of largest spread of the points (x, y): the
    line through their centroid that is closest to them (total least squares)."""
    dx, dy = x - x.mean(), y - y.mean()
    return 0.5 * math.atan2(2.0 * float(np.mean(dx * dy)), float(np.mean(dx * dx - dy * dy)))


def _start_angle(h, u, comm):
    """Starting angle of the surface (radians): the long axis of the bed's cross-section (the segment
    below a drum's chord is longer along the chord than across it at any filling), turned so that the
    outward normal (-sin, cos) points from the bed's centroid towards the drum's axis at h = u = 0 (the
    empty side of the chord, whatever the filling). From the sums of every process: the centroid first,
    then the spread about it (two reductions keep the digits a one-pass sum of squares would lose)."""
    count, sh, su = comm.sum_values(np.array([len(h), h.sum(), u.sum()], dtype=float))
    mh, mu = sh / count, su / count
    dh, du = h - mh, u - mu
    sxy, sxx_yy = comm.sum_values(np.array([float(np.sum(dh * du)), float(np.sum(dh * dh - du * du))]))
    theta = 0.5 * math.atan2(2.0 * sxy, sxx_yy)
    if mh * math.sin(theta) - mu * math.cos(theta) < 0.0:
        theta += math.pi if theta < 0.0 else -math.pi
    return theta


def surface_fit(h, u, nbins=20, trim=0.15, gap=math.inf, comm=None):
    """Free surface of a bed seen in a drum's cross-section: particles at horizontal h and height u, both
    measured from the drum's axis (this process's: `comm` reduces over the processes; None, one process).
    The surface is found in a frame that follows it, s along the surface
    and n across it: starting from the bed's long axis, the frame is turned to the line closest to the
    tops of its columns (_surface_tops) until the tops no longer change, so that the columns stand across
    the surface at any slope (columns standing vertically read a steep surface wrong: their tops reach
    the bed's side along the wall). A turn that passes the line halves the next ones (bins changing tops
    can make full turns cycle). Returns (angle in degrees, slope, height of the line at h = 0, bins used,
    roughness: the rms distance of the bins' surface particles from the line); zeros with fewer than 3
    particles, or when a frame holds fewer than 2 bins. Each process sends the others a few numbers per
    bin (_runs), never its particles."""
    comm = comm or _ONE
    if comm.sum(len(h)) < 3:
        return 0.0, 0.0, 0.0, 0, 0.0
    theta = _start_angle(h, u, comm)
    step, last, before = 1.0, 0.0, None
    for _ in range(SURFACE_TURNS):
        tops = _surface_tops(h, u, theta, nbins, trim, gap, comm)
        if len(tops) < 2:
            return 0.0, 0.0, 0.0, 0, 0.0
        c, sn = math.cos(theta), math.sin(theta)
        turn = _long_axis(tops[:, 0] * c + tops[:, 1] * sn, tops[:, 1] * c - tops[:, 0] * sn)
        if before is not None and np.array_equal(tops, before):
            theta += turn               # the same tops: their line, exactly
            break
        if turn * last < 0.0:
            step *= 0.5
        theta += step * turn
        last, before = turn, tops
    c, sn = math.cos(theta), math.sin(theta)
    ns = tops[:, 1] * c - tops[:, 0] * sn
    theta = math.remainder(theta, 2.0 * math.pi)
    height = float(ns.mean())
    rough = math.sqrt(float(np.mean((ns - height) ** 2)))
    return math.degrees(theta), math.tan(theta), height / c, len(tops), rough


class ComputeRepose(Compute):
    """compute ID group repose DRUM-FIX-ID [bins N] [trim F]

    Dynamic angle of repose (degrees) of the free surface of the bed in a rotating drum (fix wall/drum):
    positions are projected on the drum's cross-section, with the vertical opposite to the first fix
    gravity (+z without one). The surface is found in a frame that follows it, at any slope: the
    extent of the bed along the surface is cut into N bins (default 20); in each, the top of the bed is
    the particle farthest out across the surface in the column that rises from the bin's innermost one
    without a gap of more than 4 of the group's largest bounding radii (a particle carried on the wall
    or in flight is not the surface); the frame is turned to the line closest to the tops of the central
    bins (leaving out a fraction F = 0.15 of the extent at each end, where the surface meets the wall)
    until the tops no longer change (2 to 5 frames from the long axis of the bed's cross-section).
    Scalar: |angle|. Vector: [signed angle (positive: the surface rises towards +h, h = up x axis),
    slope, height of the line at the axis (m), surface points used, roughness (m): the rms distance of
    the surface points from the line (a flat surface: ~0)].
    Checked on beds of known angle from 0 to 85 degrees (flat and S-shaped surfaces, particles in
    flight and on the wall): within 2.5 degrees with particles 1/25 of the drum radius.
    Meaningful in the rolling and cascading regimes (a flat-ish surface); in cataracting or
    centrifuging regimes, flying or wall-borne particles make it a rough indicator only."""

    style = "repose"
    size_vector = 5
    vector_names = ("angle", "slope", "intercept", "points", "roughness")
    scalar_quantity = ("angle of repose", "deg")
    vector_quantities = (("signed angle of repose", "deg"), ("surface slope", "-"),
                         ("surface height at the axis", "m"), ("surface points", "-"), ("surface roughness", "m"))
    usage = "DRUM-FIX-ID [bins N] [trim F]"

    def __init__(self, sim, cid, group, args):
        super().__init__(sim, cid, group, args)
        a = self.parser()
        a.need(1)
        self.drum_id = a[0]
        kw = a.keywords(1, {"bins": 1, "trim": 1})
        self.nbins = a.to_int(kw["bins"][0], "bins") if "bins" in kw else 20
        self.trim = a.to_float(kw["trim"][0], "trim") if "trim" in kw else 0.15
        if not 3 <= self.nbins <= MAX_BINS or not 0 <= self.trim < 0.5:
            raise a.error(f"bins must be within 3..{MAX_BINS} and 0 <= trim < 0.5")

    def compute_vector(self):
        sim = self.sim
        drum = find_drum(sim, self.drum_id, f"compute {self.id} repose")
        _, eh, up = cross_section_basis(sim, drum)
        atom = sim.atom
        sel = self.group_mask()
        r = atom.data["radius"][:atom.nlocal][sel]
        gap = SURFACE_GAP * sim.comm.max(float(r.max()) if len(r) else 0.0)
        x = atom.data["x"][:atom.nlocal][sel] - drum.centre
        # every rank fits the same surface from its own particles and a few numbers per bin of the others'
        return np.array(surface_fit(x @ eh, x @ up, self.nbins, self.trim, gap, sim.comm), dtype=float)

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
    scalar_quantity = ("fraction co-rotating", "-")
    vector_quantities = (scalar_quantity, ("fraction co-rotating at the top", "-"), ("fraction at the top", "-"))
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
