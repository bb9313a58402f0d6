"""pair_style glued/convex: glued composites, convex particles and spheres in one pair style."""
import numpy as np

from dem.shapes import command as shape_command
from dem._particles import ParticleView
from dem.errors import DemError
from dem.history import KeyedHistory
from dem.pair import Pair
from dem.shapes.base import GLUED
from dem.law.pair_coeffs import PairCoefficients

from . import _pair_glued


class PairGluedConvex(PairCoefficients, Pair):
    """pair_style glued/convex [model A|B] [tol TOL]

    pair_coeff I J kn KN en EN [mu MU] [gamma_t GT] [beta_t BT] [ks KS] [mu_roll MUR]
    or `model hertz E .. nu .. en .. mu ..`: R* from the spheres of equal volume (docs/hertz.md)

    Contacts between glued composites (`shape NAME glued ...`, `cross3d`, ...), convex particles of any
    shape of the table and plain spheres: one pair style serves them all. Grains3D Part III sec 2.5: the
    particles' bounding spheres (neighbor list), then the bounding spheres of their convex pieces (a
    composite's components; a convex particle or a sphere is its own single piece) and their bounding
    boxes (separating axes: the spheres of elongated beams are loose, Part III Fig. 29), tested each step
    only for the piece pairs found within the neighbor skin when the list was built, then the crust
    contact (GJK on the pieces shrunk by their crust, EPA for deep overlaps) of each piece pair, or the
    analytic contact of two sphere pieces (multisphere clumps). Each contact point acts through the
    Grains3D law (as `pair_style convex/gjk`) with the reduced mass of the two particles and levers
    from the centres of mass of the whole particles.

    `model B` (default): the force and torque of the N_c contact points of a particle pair are averaged
    (each weighs 1/N_c, Part III eq. 20-21), so the contact time and the damping do not depend on N_c;
    `model A`: they are summed, each point damped with m_ij / N_c (gamma_n / sqrt(N_c), eq. 18) so that
    the restitution stays e_n, and the contact time falls as 1/sqrt(N_c) (eq. 19). Walls use the same
    model for the pieces of a particle touching one wall surface.

    History per piece pair (keyed, survives rebuilds, restarts and migration): the tangential spring
    (ks > 0) and the GJK warm start. Particles with a shape need `fix ID group nve/shape`.

    Example (Part III sec 4.1)::

        shape c cross3d 0.006 aspect 4
        pair_style glued/convex model B
        pair_coeff * * kn 1e5 en 0.73 mu 0.55 gamma_t 2000
    """

    style = "glued/convex"
    tallies = ("stress", "count")    # per-particle contact tallies for analysis (dem/tally.py)

    def __init__(self, sim, args):
        super().__init__(sim, args)
        self.tol = 1e-8
        self.model_b = True
        usage = "pair_style glued/convex [model A|B] [tol TOL]"
        i = 0
        while i < len(args):
            if i + 1 >= len(args) or args[i] not in ("tol", "model"):
                raise DemError(f"pair_style glued/convex: unknown or incomplete argument '{args[i]}'; usage: {usage}")
            if args[i] == "model":
                if args[i + 1] not in ("A", "B"):
                    raise DemError(f"pair_style glued/convex: model is A or B, got '{args[i + 1]}'")
                self.model_b = args[i + 1] == "B"
            else:
                try:
                    self.tol = float(args[i + 1])
                except ValueError:
                    raise DemError(f"pair_style glued/convex: tol must be a number, got '{args[i + 1]}'") from None
                if not 0 < self.tol < 1e-2:
                    raise DemError("pair_style glued/convex: tol must be in (0, 1e-2)")
            i += 2
        self.init_coefficients()
        self.history = None
        self.use_xi = False
        self.work = _pair_glued.GluedWork()
        self.stats = dict.fromkeys(_pair_glued.STATS, 0.0)    # sums over the run (benchmarks, tests)
        self.npoints = 0
        self.piece_margin = None     # margin of the piece candidates; None: the neighbor skin (tests set 0)

    @property
    def multipoint_average(self):
        """Model B (walls read it for the pieces of a particle)."""
        return self.model_b

    def init(self):
        self.use_xi = self.check_coefficients()
        sim = self.sim
        if len(sim.shapes) and int(np.max(sim.shapes.comp_count[:len(sim.shapes)], initial=0)) > _pair_glued.MAX_PIECES:
            raise DemError(f"pair_style glued/convex: a composite has more than {_pair_glued.MAX_PIECES} components")
        if self.history is None:
            self.history = KeyedHistory(sim, "pair_glued", _pair_glued.RECORD)
            sim.neighbor.histories.append(self.history)
        self.shape_view = shape_command.pair_shape_view(sim)

    def compute(self, advance=True):
        sim = self.sim
        nb = sim.neighbor
        w = self.work
        view = ParticleView(sim.atom)
        stale = _pair_glued.poses(view, self.shape_view, w)
        w.stats[:] = 0.0
        w.worst[:] = -1
        margin = nb.skin if self.piece_margin is None else self.piece_margin
        if stale or w.listed is not nb.offsets or w.margin != margin:
            # the piece candidates (issue 39): with each neighbor list, or when a particle has moved too far
            _pair_glued.candidates(view, nb.offsets, nb.neigh, self.shape_view, w, margin)
            w.listed = nb.offsets
        self.history.step(lambda start: _pair_glued.compute(
            view, nb.offsets, nb.neigh, self.table, self.shape_view, w, self.history.buffers, self.use_xi,
            self.tol, sim.update.dt, advance, self.model_b, start), advance)
        st = dict(zip(_pair_glued.STATS, w.stats))
        self.ncontacts = int(st["contacts"])
        self.npoints = int(st["points"])
        self.max_overlap = float(st["max_overlap"])
        self.energy = float(st["energy"])
        if advance:
            for key in ("contacts", "points", "gjk", "epa", "piece_pairs", "piece_listed", "piece_spheres",
                        "piece_candidates", "piece_builds"):
                self.stats[key] += st[key]
        if self.ncontacts:
            a = sim.atom.data
            self.max_overlap_tags = (int(a["tag"][w.worst[0]]), int(a["tag"][w.worst[1]]))
