"""pair_style convex/gjk: convex particles of the shape table, mixed with spheres."""

from dem.shapes import command as shape_command
from dem._particles import ParticleView
from dem.errors import DemError
from dem.history import History
from dem.pair import Pair
from dem.shapes.base import GLUED
from dem.law.pair_coeffs import PairCoefficients

from . import _pair_convex


class PairConvexGJK(PairCoefficients, Pair):
    """pair_style convex/gjk [tol TOL]

    pair_coeff I J kn KN en EN [mu MU] [gamma_t GT] [beta_t BT] [ks KS] [mu_roll MUR]
    or `model hertz E .. nu .. en .. mu ..`: R* from the spheres of equal volume (docs/hertz.md)

    Contacts between particles of any shape of the shape table (`shape` command) and plain spheres.
    Broad phase on bounding spheres (the core neighbor list); then two spheres meet as in
    `pair_style sphere`, any other pair by the Grains3D crust contact (Part I/III sec 2.5): GJK on the
    bodies shrunk by their crust gives the distance of the cores, from which overlap = crust_i + crust_j -
    distance, the normal and one contact point (midway between the two surfaces) follow; overlaps deeper
    than the crusts use EPA on the cores. One contact point per pair (N_c = 1): flat face-face or
    edge-face contacts get one point chosen by the geometry, which produces a small spurious torque
    exactly as in Grains3D (Part III sec 3.2-3.3). Corners and edges are rounded by the crust radius in
    particle-particle contacts (default crust: 5 % of the inradius).

    The Grains3D law (Part III eq. 10-16, `dem.law`) acts at the contact point with the relative
    velocity of the two surfaces there, the reduced mass m_ij and torques from the lever centre of mass ->
    contact point. Coefficients per type pair as for `pair_style sphere` (rolling resistance applies
    between two spheres only; mu without ks or gamma_t gives no tangential force, with a warning). The
    tangential spring (ks > 0) and the GJK warm start (the last core
    separation and the last simplex: between boxes/polyhedra its vertices, otherwise its points in the
    two body frames; a lasting contact then costs about one support query) are contact history that
    survives rebuilds, restarts and migration.
    Pairs proved apart (bounding spheres, or a projection on the last separating axis) are skipped until
    the particles have moved or turned enough to close that gap, which changes no result.

    `tol`: relative accuracy of the GJK distance (default 1e-8; distances between cores are of the order
    of the crust, so this is far below any overlap that matters).

    Particles with a shape need `fix ID group nve/shape` (rotation of non-spherical bodies).

    Example::

        shape c cube 0.002
        create_atoms 1 random 1000 4821 box shape c quat random density 2500
        pair_style convex/gjk
        pair_coeff * * kn 1e5 en 0.73 mu 0.55 gamma_t 2000 ks 28571
    """

    style = "convex/gjk"
    tallies = ("stress", "count")    # per-particle contact tallies for analysis (dem/tally.py)

    def __init__(self, sim, args):
        super().__init__(sim, args)
        self.tol = 1e-8
        i = 0
        while i < len(args):
            if args[i] == "tol" and i + 1 < len(args):
                try:
                    self.tol = float(args[i + 1])
                except ValueError:
                    raise DemError(f"pair_style convex/gjk: tol must be a number, got '{args[i + 1]}'") from None
                if not 0 < self.tol < 1e-2:
                    raise DemError("pair_style convex/gjk: tol must be in (0, 1e-2)")
                i += 2
            else:
                raise DemError(f"pair_style convex/gjk: unknown argument '{args[i]}'; usage: "
                               f"pair_style convex/gjk [tol TOL]")
        self.init_coefficients()
        self.history = None
        self.use_xi = False
        self.work = _pair_convex.ConvexWork()   # poses and margins (see _pair_convex.compute)
        self.ngjk = 0
        self.nepa = 0
        self.nsep = 0
        self.nskip = 0

    def init(self):
        self.use_xi = self.check_coefficients()
        if any(s.kind == GLUED for s in self.sim.shapes.shapes):
            raise DemError("pair_style convex/gjk: glued composites need pair_style glued/convex (it also "
                           "serves convex particles and spheres)")
        if self.history is None:
            self.history = History(self.sim, "pair_convex", _pair_convex.HISTORY)
            self.sim.neighbor.histories.append(self.history)
        sim = self.sim
        self.shape_view = shape_command.pair_shape_view(sim)

    def compute(self, advance=True):
        sim = self.sim
        nb = sim.neighbor
        w = self.work
        view = ParticleView(sim.atom)
        w.step(sim, view, self.shape_view)
        _pair_convex.compute(view, nb.offsets, nb.neigh, self.table, self.shape_view, w, self.history.values,
                             self.use_xi, self.tol, sim.update.dt, advance)
        st = w.stats
        self.ncontacts = int(st[0])
        self.max_overlap = float(st[1])
        self.energy = float(st[2])
        self.ngjk += int(st[3])
        self.nepa += int(st[4])
        self.nsep += int(st[5])
        self.nskip += int(st[6])
        if self.ncontacts:
            a = sim.atom.data
            self.max_overlap_tags = (int(a["tag"][w.worst[0]]), int(a["tag"][w.worst[1]]))
