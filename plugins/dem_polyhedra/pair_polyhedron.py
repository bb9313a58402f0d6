"""pair_style polyhedron/multipoint: sharp polyhedra with multipoint contacts, and plain spheres."""
import numpy as np

from dem.shapes import command as shape_command
from dem._particles import ParticleView
from dem.contact import _volume
from dem.errors import DemError, did_you_mean
from dem.history import KeyedHistory
from dem.law.pair_coeffs import PairCoefficients
from dem.pair import Pair
from dem_convex import _pair_convex

from . import _pair_polyhedron

TYPES = ("vertex_face", "edge_edge", "edge_face", "face_face", "sphere")   # "sphere": a pair with a sphere
LAWS = ("grains3d", "descantes", "volume")    # the `law` keyword (dem.law.descantes, dem/law/volume.pxd)
FTOL = 1e-9      # contacting-feature tolerance, per unit of the two bounding radii (dem.contact.polytope)


class PairPolyhedronMultipoint(PairCoefficients, Pair):
    """pair_style polyhedron/multipoint [law grains3d|descantes|volume] [ftol FTOL]

    pair_coeff I J kn KN en EN [mu MU] [gamma_t GT] [beta_t BT] [ks KS]
    or `model hertz E .. nu .. en .. mu ..`: R* from the spheres of equal volume (docs/hertz.md)

    Contacts of sharp polytopes (`box`, `cube`, `polyhedron`, `tetrahedron`, `pinacoid`: no rounding, no
    crust) and plain spheres, with as many contact points as the contact has (Descantes 2022 sec. 2):
    vertex/face and edge/edge 1, edge/face 2, face/face the corners of the overlap polygon (at most 16).
    Depth and normal are exact (separating axes, dem/contact/_polytope.pyx). A body's contacting feature
    is its vertices within ftol (r_i + r_j) + delta of its deepest one along the normal (every vertex
    inside the overlap slab; ftol default 1e-9). Every point carries the shared maximum overlap and weight
    1/alpha (alpha the number of points) through the Grains3D law (as `convex/gjk`; Model B averaging on
    the points), with the reduced mass of the pair and levers from the centres of mass. A sphere touches a
    polytope at one point (GJK on the sharp body and the sphere's centre), two spheres analytically (with
    rolling resistance mu_roll, as `pair_style sphere`).

    `law descantes`: Descantes' eq. 3 at every point instead, F_n = max(0, kn delta - nu_n U_n) / alpha
    (no attraction; nu_n from en as in the Grains3D law) and F_t = -min(nu_t |U_t|, mu F_n) t / alpha
    (viscous, nu_t = 2 gamma_t m_ij + 2 beta_t sqrt(kn m_ij), capped by Coulomb; beta_t 1 with en 0 gives
    Descantes' Table 2, gamma_t = gamma_n critical; no spring: ks is not used, no history). Walls choose
    their own law: `fix ... wall/plane ... point multipoint law descantes` for the same law at the wall.

    `law volume` (energy-conserving, for collisional flows; dem/law/volume.pxd, docs/polyhedra.md): two
    polytopes touch at one point through the overlap volume V of the two bodies, the potential
    U = 1/2 kn (V / A_ref)^2 with A_ref = pi r_i r_j (r: radii of the spheres of equal volume), so a flat
    contact of area A_ref has Hooke's kn; the force and torque are its exact gradient (the area vector and
    moment of the overlap's surface), damping from en and friction (the row's tangential part, capped by
    Coulomb) at the point on the force's line nearest the overlap's centroid, plus a twisting friction of
    the overlap area. Walls: `fix ... wall/plane ... law volume` (and wall/drum). Spheres keep one point
    and the Hooke law.
    With a tangential spring (ks > 0, law grains3d) every point keeps its own history, matched from step
    to step by its position in the body frame of the list's owner (not by index), so that it survives a
    face/face contact turning edge/face and back (dem_polyhedra/_pair_polyhedron.pyx). Other shapes
    (curved bodies, glued composites) are refused. Particles with a shape need `fix ID group nve/shape`;
    walls touch polytopes at every vertex with `fix ... wall/plane ... point multipoint`. Faces and edges
    come from the shape table (dem/shapes/topology.py). After each step (Python):
    `ncontacts` (pairs), `npoints`, `contact_types` (pairs per type: vertex_face, edge_edge, edge_face,
    face_face, sphere); `stats` sums them over the run, with `face_face_points`.

    Example::

        shape c cube 0.002
        pair_style polyhedron/multipoint
        pair_coeff * * kn 1e5 en 0.5 mu 0.5 ks 2e4
    """

    style = "polyhedron/multipoint"
    tallies = ("stress", "types", "count")    # per-particle contact tallies for analysis (dem/tally.py)

    def __init__(self, sim, args):
        super().__init__(sim, args)
        self.ftol = FTOL
        self.law = "grains3d"
        usage = "pair_style polyhedron/multipoint [law grains3d|descantes|volume] [ftol FTOL]"
        i = 0
        while i < len(args):
            if i + 1 >= len(args) or args[i] not in ("ftol", "law"):
                raise DemError(f"pair_style polyhedron/multipoint: unknown or incomplete argument '{args[i]}'; "
                               f"usage: {usage}")
            if args[i] == "law":
                if args[i + 1] not in LAWS:
                    raise DemError(f"pair_style polyhedron/multipoint: law is {', '.join(LAWS)}, got '{args[i + 1]}'"
                                   f"{did_you_mean(args[i + 1], LAWS)}")
                self.law = args[i + 1]
            else:
                try:
                    self.ftol = float(args[i + 1])
                except ValueError:
                    raise DemError(f"pair_style polyhedron/multipoint: ftol must be a number, got '{args[i + 1]}'") from None
                if not 0 <= self.ftol < 1e-2:
                    raise DemError("pair_style polyhedron/multipoint: ftol must be in [0, 1e-2)")
            i += 2
        self.init_coefficients()
        self.history = None
        self.use_xi = False
        self.stats = dict.fromkeys(_pair_polyhedron.STATS, 0.0)     # sums over the run
        self.step_stats = np.zeros(len(_pair_polyhedron.STATS))
        self.npoints = 0
        self.contact_types = dict.fromkeys(TYPES, 0)
        self.work = _pair_convex.ConvexWork()   # per-step poses and per-entry margins (as convex/gjk)
        self._cert, self._cert_for = None, None
        self._rec, self._rec_ij = _NO_POINTS, _NO_POINTS_IJ   # contact points, on the steps a dump writes
        self._nrec = np.zeros(2, np.int64)
        self.contact_points = None
        self.contact_points_step = None

    @property
    def multipoint_average(self):
        """Walls weigh the points of a particle by 1/N (as this pair style)."""
        return True

    def init(self):
        self.use_xi = self.check_coefficients()       # Descantes' rows keep none (dem.law.descantes)
        sim = self.sim
        atom = sim.atom
        self.shape_view = shape_command.pair_shape_view(sim)
        rows = sim.shapes.rows
        poly = self.shape_view.arrays["topology"]["poly"]       # polytope rows (dem/shapes/topology.py)
        used = np.unique(atom.data["shape"][:atom.nlocal])
        sphere = self.shape_view.arrays["is_sphere"] if "is_sphere" in self.shape_view.arrays else None
        for s in used:
            if s < 0:
                continue
            shp = rows[s]
            if poly[s]:
                if self.law == "volume":
                    _volume_fits(shp, sim.shapes.names[s])
                continue
            if sphere is not None and sphere[s]:
                continue
            raise DemError(f"pair_style polyhedron/multipoint: shape '{getattr(shp, 'name', s)}' is neither a "
                           "sharp polytope (box, cube, polyhedron, tetrahedron, pinacoid) nor a sphere")
        if self.use_xi and self.history is None:
            self.history = KeyedHistory(sim, "pair_polyhedron", _pair_polyhedron.RECORD)
            sim.neighbor.histories.append(self.history)

    def _kernel(self, view, st, buffers, use_xi, advance):
        nb = self.sim.neighbor
        w = self.work

        def run(start):
            resume = _pair_polyhedron.compute(
                view, nb.offsets, nb.neigh, self.table, self.shape_view, w.rot, w.move, w.margin, *self._certs(w),
                st, buffers, use_xi, self.law == "volume", self.ftol, self.sim.update.dt, advance, self._rec,
                self._rec_ij, self._nrec, start)
            if self._nrec[1]:                  # the points buffer was full: grow it, resume at that entry
                self._nrec[1] = 0
                self._grow_points(2 * len(self._rec) + 16 * MAXP)
            return resume
        return run

    def _certs(self, w):
        """Per-entry certificates of the separating axis (_pair_polyhedron.compute), zeroed whenever
        ConvexWork gives fresh margins (a new list)."""
        if self._cert_for is not w.margin:
            self._cert_for = w.margin
            self._cert = (np.zeros(len(w.margin), np.int32), np.zeros(len(w.margin)))
        return self._cert

    def _grow_points(self, rows):
        rec, ij = np.empty((rows, _pair_polyhedron.RECW)), np.empty((rows, 3), np.int64)
        n = int(self._nrec[0])
        rec[:n], ij[:n] = self._rec[:n], self._rec_ij[:n]
        self._rec, self._rec_ij = rec, ij

    def recording(self, step):
        """True when a `dump ... contacts` (dump_contacts.py) writes `step`: the points are then kept
        (`contact_points`)."""
        sim = self.sim
        return any(getattr(d, "records_contact_points", False) and step % d.every == 0
                   for d in sim.output.dumps.values())

    def _points(self):
        """The recorded points as arrays (ids from the local indices)."""
        n = int(self._nrec[0])
        rec, ij = self._rec[:n], self._rec_ij[:n]
        tag = self.sim.atom.data["tag"]
        return {"point": rec[:, 0:3].copy(), "normal": rec[:, 3:6].copy(), "force": rec[:, 6:9].copy(),
                "overlap": rec[:, 9].copy(), "type": ij[:, 2].astype(np.int32),
                "ids": np.column_stack([tag[ij[:, 0]], tag[ij[:, 1]]]).astype(np.int64)}

    def compute(self, advance=True):
        sim = self.sim
        view = ParticleView(sim.atom)
        self.work.step(sim, view, self.shape_view)
        st = self.step_stats
        st[:] = 0.0
        # a step's dumps follow its force pass and the drift: the pass of step n writes frame n + 1 (a
        # setup pass, advance False, frame n)
        frame = sim.update.ntimestep + (1 if advance else 0)
        record = self.recording(frame)
        if record:
            if len(self._rec) == 0:
                self._grow_points(max(64, 2 * self.npoints))
        elif len(self._rec):
            self._rec, self._rec_ij = _NO_POINTS, _NO_POINTS_IJ
        self._nrec[:] = 0
        if self.use_xi:
            self.history.step(self._kernel(view, st, self.history.buffers, True, advance), advance)
        else:
            run, start = self._kernel(view, st, _EMPTY, False, advance), 0
            while start != -1:                 # stops only to grow the points buffer
                start = run(start)
        s = dict(zip(_pair_polyhedron.STATS, st))
        self.ncontacts = int(s["contacts"])
        self.npoints = int(s["points"])
        self.max_overlap = float(s["max_overlap"])
        self.energy = float(s["energy"])
        self.contact_types = {k: int(s[k]) for k in TYPES}     # pairs of each type at the last compute
        self.contact_points = self._points() if record else None
        self.contact_points_step = frame if record else None
        if advance:
            for key, v in s.items():
                if key != "max_overlap":
                    self.stats[key] += v


def _volume_fits(shape, name):
    """law volume clips faces in fixed buffers (dem/contact/_volume.pyx)."""
    topo = shape.topology
    if topo.nf > _volume.MAXF or max(len(f) for f in topo.faces) > _volume.MAXFV:
        raise DemError(f"pair_style polyhedron/multipoint law volume: shape '{name}' has {topo.nf} faces "
                       f"(at most {_volume.MAXF}) or a face of more than {_volume.MAXFV} vertices",
                       hint="law grains3d or descantes take it")


from dem import _history  # noqa: E402
_EMPTY = _history.KeyedBuffers(_pair_polyhedron.RECORD)
_NO_POINTS = np.empty((0, _pair_polyhedron.RECW))
_NO_POINTS_IJ = np.empty((0, 3), np.int64)
MAXP = _pair_polyhedron.MAXP
