# cython: language_level=3
"""Contacts between convex particles (shape table rows) and spheres: bounding-sphere broad phase, then
either the analytic sphere geometry (two spheres) or the Grains3D crust contact (dem/contact/_gjk.pyx: GJK
on the shrunk cores, EPA when the cores overlap), one contact point per pair, and the shared law
(dem/law/apply.pxd).

A scaled body is handed to GJK as its unscaled shape with the rotation matrix multiplied by the scale s:
the support point of s R K in direction d is s R s_K(R^T d) (support functions ignore the length of the
direction), i.e. the support of the body scaled by s; its crust is s times the shape's crust. A sphere
(shape -1, or a table sphere) is a point core with a crust equal to its radius: exact.

History per pair (values[k, 0:HISTORY]): the tangential spring xi (3, when ks > 0), then the GJK warm
start: the direction of the last core separation pa - pb (3, unit; also the pre-test axis), a tag of the
two shapes it was made for (1 value: a particle given another shape starts cold), negative while the pair
touched at its last GJK call (such a pair goes to GJK without the pre-test), and the last simplex (NFEAT,
see dem/contact/_gjk.pyx: vertex pairs of polytopes, body-frame points otherwise). A lasting contact
between boxes reads the first 13 values only.

Box cores are posed once per step as their 8 world corners (poses); GJK reads its vertex pairs from them.
The rows of the next pair in the list are prefetched while the current one is solved: they are scattered
in memory and the solve is short."""
cimport numpy as cnp
from libc.math cimport sqrt, fabs
import numpy as np
from dem._particles cimport ParticleView, Particles, count_contact
from dem.contact.record cimport Contact
from dem.contact._gjk cimport crust_contact, CONTACT_NONE, CONTACT_CRUST, NFEAT
from dem.shapes._support cimport (ShapeRef, Kind, quat_to_rot, support_world, polytope_core, box_corners,
                                  corner_box, MARGIN, NPARAM, NCORNER)
from dem.shapes._table cimport ShapeView, TableView, core_ref, equivalent_radius, round_body
from dem.law.apply cimport Body, apply_pair, bind_body, contact_radius
from dem.law.law cimport forget
from dem.law.row cimport XI_WIDTH

ctypedef cnp.int64_t i64

cdef extern from *:
    """
    #if defined(__GNUC__)
    #define DEM_PREFETCH(p) __builtin_prefetch(p)
    #else
    #define DEM_PREFETCH(p) ((void)(p))
    #endif
    """
    void prefetch "DEM_PREFETCH"(const void* p) noexcept nogil

cdef enum:
    AXIS = XI_WIDTH                   # history slots (module docstring): xi 0-2, axis 3-5, tag, simplex
    TAG = AXIS + 3
    FEAT = TAG + 1
HISTORY = FEAT + NFEAT                # history values per pair
TAG_SLOT, FEAT_SLOT = TAG, FEAT       # (for Python: tests, tools)

cdef double MARGIN_SAFETY = 1e-12     # margins are kept this much (relative) short of the round-off
cdef double SQRT_HALF = 0.7071067811865476   # ||R' - R||_2 = ||R' - R||_F / sqrt(2) between two rotations
cdef double ROT_ROUNDOFF = 4e-15      # bound of what round-off (R not exactly orthonormal) adds to that
cdef double POINT_PARAMS[NPARAM]          # a sphere of radius 0 (zero-initialised)


cdef class ConvexWork:
    """Per-particle and per-list-entry work arrays of the pair style (see poses and compute), grown by
    `fit`; kept between steps (they are caches of the list and of the last poses, never history)."""
    cdef public object rot, corners, xprev, move, margin, active, stats, worst, seen_build, seen_nall

    def __init__(self):
        self.seen_build = self.seen_nall = -1
        self.rot, self.xprev, self.move = np.zeros((0, 9)), np.zeros((0, 3)), np.zeros(0)
        self.corners = np.zeros((0, NCORNER))
        self.margin = np.zeros(0)
        self.active = np.zeros((0, 2), dtype=np.int32)
        self.stats = np.zeros(7)
        self.worst = np.zeros(2, dtype=np.int64)

    def step(self, sim, ParticleView view, ShapeView shapes):
        """Once per force evaluation: fresh margins after a list rebuild (or a new particle count), then the
        poses (used by convex/gjk and polyhedron/multipoint)."""
        nb = sim.neighbor
        nall = sim.atom.nall
        reset = nb.nbuilds != self.seen_build or len(self.margin) != nb.nentries or nall != self.seen_nall
        if reset:
            self.seen_build, self.seen_nall = nb.nbuilds, nall
            self.fit(nall, nb.nentries)
        poses(view, shapes, self, reset)

    def fit(self, int nall, int nentries):
        """Fresh margins for a new list (zero: every pair is tested), room for nall particles."""
        self.margin = np.zeros(nentries)
        self.active = np.zeros((nentries, 2), dtype=np.int32)
        if len(self.rot) < nall:
            n = int(nall * 1.2) + 16
            self.rot, self.xprev, self.move = np.zeros((n, 9)), np.zeros((n, 3)), np.zeros(n)
            self.corners = np.zeros((n, NCORNER))


cdef inline void _pose(const Particles* P, const TableView* T, int i, int s, const double* corners,
                       ShapeRef* ref, double* c) noexcept nogil:
    """Core and crust of particle i (shape s); its scaled rotation is rot[i], its corners (a box core)
    corners[NCORNER i:]."""
    if round_body(T, s):
        ref.kind = Kind.SPHERE          # of radius 0: a point
        ref.params = POINT_PARAMS
        ref.nverts = 0
        ref.verts = NULL
        ref.corners = NULL
        c[0] = P.radius[i]
        return
    core_ref(T, s, ref)
    if corner_box(ref.kind, ref.params[MARGIN]):     # posed by poses
        ref.corners = &corners[NCORNER * i]
    c[0] = T.crust_rel[s] * P.radius[i]


cdef inline bint _polytope(const TableView* T, int s) noexcept nogil:
    """A shape whose GJK warm start is its vertex pairs (dem/contact/_gjk.pyx)."""
    return not round_body(T, s) and polytope_core(T.core_kind[s], T.core_params[NPARAM * s + MARGIN])


cdef inline void _forget_points(double* h, const TableView* T, int si, int sj) noexcept nogil:
    """A pair found apart drops a simplex of body-frame points (curved bodies): GJK from such a simplex ends on
    points of its own within the tolerance, so keeping it across a separation would make the results depend
    on how long the pair stayed listed (margins, rebuilds). Vertex pairs lead to the same final simplex from
    any start and are kept."""
    cdef int d
    if not (_polytope(T, si) and _polytope(T, sj)):
        for d in range(NFEAT):
            h[d] = 0.0


cdef inline double _extent(const ShapeRef* ref, const double* R, const double* x, const double* u) noexcept nogil:
    """Support value h(u) = max over the posed core of u.(p - x): closed form for boxes, cylinders and
    points (the common cases of the pre-test), the support function otherwise."""
    cdef double db0, db1, db2
    cdef double sp[3]
    if ref.kind == Kind.SPHERE and ref.params[0] == 0.0 and ref.params[MARGIN] == 0.0:
        return 0.0                                     # a point (the core of a sphere particle)
    if (ref.kind == Kind.BOX or ref.kind == Kind.CYLINDER) and ref.params[MARGIN] == 0.0:
        db0 = R[0] * u[0] + R[3] * u[1] + R[6] * u[2]  # R^T u (R includes the scale)
        db1 = R[1] * u[0] + R[4] * u[1] + R[7] * u[2]
        db2 = R[2] * u[0] + R[5] * u[1] + R[8] * u[2]
        if ref.kind == Kind.BOX:
            return ref.params[0] * fabs(db0) + ref.params[1] * fabs(db1) + ref.params[2] * fabs(db2)
        return ref.params[0] * sqrt(db0 * db0 + db1 * db1) + ref.params[1] * fabs(db2)
    support_world(ref, R, x, u, sp)
    return u[0] * (sp[0] - x[0]) + u[1] * (sp[1] - x[1]) + u[2] * (sp[2] - x[2])


def poses(ParticleView view, ShapeView shapes, ConvexWork work, bint reset):
    """rot[i] = scale_i R(quat_i), row-major, for the shaped particles (identity for spheres), and the 8
    world corners of box cores (corners[i], see box_corners): computed once per step, used by every pair
    of the particle (a lasting contact between boxes re-reads a few corners at every call). move[i] bounds
    how far any point of particle i's core moved since the last call (zero on reset): |x - xprev| +
    ||R - R_prev||_2 r_shape (a rotation moves a point p by |(R - R_prev) p| <= ||R - R_prev||_2 |p|).
    R_prev^T R is a rotation by some angle t, so the singular values of R - R_prev are 2 sin(t/2) (twice)
    and 0: its spectral norm is its Frobenius norm over sqrt(2)."""
    cdef Particles particles = view.p          # local copies: no call can change them (kept in registers)
    cdef const Particles* P = &particles
    cdef TableView table = shapes.t
    cdef const TableView* T = &table
    cdef double[:, ::1] rot = work.rot, corners = work.corners, xprev = work.xprev
    cdef double[::1] move = work.move
    cdef int i, k, s
    cdef double sc = 1.0, dr, dx
    cdef double R[9]
    cdef const double* x
    with nogil:
        for i in range(P.nall):
            s = P.shape[i]
            x = &P.x[3 * i]
            if round_body(T, s):
                for k in range(9):
                    R[k] = 0.0
                R[0] = R[4] = R[8] = 1.0
            else:
                sc = P.radius[i] / T.radius[s]
                quat_to_rot(&P.quat[4 * i], R)
                for k in range(9):
                    R[k] *= sc
                if corner_box(T.core_kind[s], T.core_params[NPARAM * s + MARGIN]):
                    box_corners(R, x, &T.core_params[NPARAM * s], &corners[i, 0])
            move[i] = 0.0
            if not reset:
                dr = 0.0
                for k in range(9):
                    dr += (R[k] - rot[i, k]) * (R[k] - rot[i, k])
                dx = ((x[0] - xprev[i, 0]) ** 2 + (x[1] - xprev[i, 1]) ** 2
                      + (x[2] - xprev[i, 2]) ** 2)
                move[i] = sqrt(dx) + ((sqrt(dr) * SQRT_HALF + ROT_ROUNDOFF * sc) * T.radius[s]
                                      if not round_body(T, s) else 0.0)
            for k in range(9):
                rot[i, k] = R[k]
            for k in range(3):
                xprev[i, k] = x[k]


def compute(ParticleView view, const i64[::1] offsets, const int[::1] neigh, const double[:, :, ::1] coeff,
            ShapeView shapes, ConvexWork work, double[:, ::1] hist, bint use_xi, double tol, double dt,
            bint advance):
    """Adds contact forces and torques to f and torque (owned and ghost rows). work.stats receives
    [contacts, max overlap / smaller bounding diameter, elastic energy, GJK calls, EPA/fallback contacts,
    pairs rejected by the separating-axis pre-test, pairs skipped on their margin]; work.worst the (i, j)
    of the largest overlap.

    Pre-test: before GJK, the bodies are projected on the last separation direction (the warm start, or
    the line of centres): a gap at least crust_i + crust_j there proves there is no contact (most pairs
    of a dense bed whose bounding spheres overlap are apart); costs two support points.
    Margin: a pair rejected by the bounding spheres or the pre-test keeps its gap (minus the crusts) in
    margin[k]; that gap (along the same axis) shrinks by at most move[i] + move[j] per call (see poses), so
    the pair is skipped while its margin lasts: the test would reject it again. A first pass decrements every
    margin and lists the pairs left (active, (i, k) rows), a second treats those. The margins are a cache of
    the list (zero after a rebuild); skipping changes no result: a rejected pair changes no history once its
    axis is stored (the line of centres at the first rejection, or the last GJK separation), so the
    trajectory does not depend on the cache."""
    cdef Particles particles = view.p          # local copies: no call can change them (kept in registers)
    cdef const Particles* P = &particles
    cdef TableView table = shapes.t
    cdef const TableView* T = &table
    cdef const double[:, ::1] rot = work.rot, corners = work.corners
    cdef double[::1] margin = work.margin, stats = work.stats
    cdef const double[::1] move = work.move
    cdef int[:, ::1] active = work.active
    cdef i64[::1] worst = work.worst
    cdef int i, j, k, d, si, sj, code, ncont = 0, ngjk = 0, nepa = 0
    cdef double dx[3]
    cdef double g[3]
    cdef double out[6]
    cdef double feat[NFEAT]
    cdef double* fp
    cdef double tag
    cdef double u[3]
    cdef double sb[3]
    cdef double r2, r, rsum, meff, ca, cb, energy = 0.0, maxov = 0.0, rmin, gn
    cdef int nsep = 0, nskip = 0
    cdef double gap
    cdef bint sph_i, sph_j, new_axis
    cdef ShapeRef SA, SB
    cdef Contact con
    cdef Body A, B
    cdef const double* xi
    cdef const double* xj
    cdef const double* cf
    cdef int a, na = 0, kn, jn
    cdef double mi, m
    con.central = False
    con.key = 0
    con.weight = 1.0
    con.inertia = 0.0
    with nogil:
        for i in range(P.nlocal):        # pass 1: margins (branch-free: the outcome is unpredictable)
            mi = move[i]
            for k in range(offsets[i], offsets[i + 1]):
                m = margin[k] - (mi + move[neigh[k]])
                margin[k] = m
                active[na, 0] = i
                active[na, 1] = k
                na += m <= 0.0
        nskip = <int>(offsets[P.nlocal] - offsets[0]) - na
        for a in range(na):
            i = active[a, 0]
            k = active[a, 1]
            if a + 1 < na:       # the next pair's rows, scattered in memory: fetched while this one works
                kn = active[a + 1, 1]
                jn = neigh[kn]
                prefetch(&hist[kn, 0])
                prefetch(&hist[kn, FEAT + 2])
                prefetch(&P.x[3 * jn])
                prefetch(&rot[jn, 0])
                prefetch(&corners[jn, 0])
                prefetch(&corners[jn, 8])
                prefetch(&corners[jn, 16])
            margin[k] = 0.0
            si = P.shape[i]
            sph_i = round_body(T, si)
            j = neigh[k]
            xi = &P.x[3 * i]
            xj = &P.x[3 * j]
            dx[0] = xi[0] - xj[0]
            dx[1] = xi[1] - xj[1]
            dx[2] = xi[2] - xj[2]
            r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]
            rsum = P.radius[i] + P.radius[j]
            sj = P.shape[j]
            if r2 >= rsum * rsum:
                if advance:
                    margin[k] = sqrt(r2) - rsum - MARGIN_SAFETY * rsum
                    hist[k, TAG] = fabs(hist[k, TAG])
                    _forget_points(&hist[k, FEAT], T, si, sj)
                    if use_xi:
                        forget(&hist[k, 0], XI_WIDTH)
                continue
            sph_j = round_body(T, sj)
            if sph_i and sph_j:
                r = sqrt(r2)
                for d in range(3):
                    con.n[d] = dx[d] / r
                con.delta = rsum - r
                # contact point in the middle of the overlap
                for d in range(3):
                    con.p[d] = xi[d] - (P.radius[i] - 0.5 * con.delta) * con.n[d]
            else:
                _pose(P, T, i, si, &corners[0, 0], &SA, &ca)
                _pose(P, T, j, sj, &corners[0, 0], &SB, &cb)
                for d in range(3):
                    g[d] = hist[k, AXIS + d]
                gn = g[0] * g[0] + g[1] * g[1] + g[2] * g[2]     # a unit axis (stored so: no square root)
                new_axis = gn == 0.0
                if new_axis:                     # no axis yet: the line of centres
                    gn = 1.0 / sqrt(r2)
                    for d in range(3):
                        g[d] = dx[d] * gn
                elif fabs(gn - 1.0) > 1e-9:      # (restart files of older versions)
                    new_axis = True
                    gn = 1.0 / sqrt(gn)
                    for d in range(3):
                        g[d] *= gn
                for d in range(3):
                    u[d] = g[d]
                tag = (si + 1) * 65536.0 + sj + 2.0         # the shapes the warm start was made for
                # separating-axis pre-test along u (from j to i): gap = min_A u.a - max_B u.b; not for a pair
                # that touched at its last call (tag stored negative): it would almost never reject it
                gap = -1.0
                if hist[k, TAG] != -tag:
                    for d in range(3):
                        sb[d] = -u[d]
                    gap = (u[0] * dx[0] + u[1] * dx[1] + u[2] * dx[2] - _extent(&SA, &rot[i, 0], xi, sb)
                           - _extent(&SB, &rot[j, 0], xj, u) - ca - cb)
                if gap >= 0.0:
                    nsep += 1
                    if advance:      # (a setup pass forgets no spring: it must not skip the pair later)
                        margin[k] = gap - MARGIN_SAFETY * rsum
                        if new_axis:            # the axis stays fixed while the pair is apart
                            for d in range(3):
                                hist[k, AXIS + d] = g[d]
                        _forget_points(&hist[k, FEAT], T, si, sj)
                        if use_xi:
                            forget(&hist[k, 0], XI_WIDTH)
                    continue
                ngjk += 1
                if advance:
                    if fabs(hist[k, TAG]) != tag:
                        for d in range(NFEAT):
                            hist[k, FEAT + d] = 0.0
                    fp = &hist[k, FEAT]
                else:                # a setup pass changes no history: a copy
                    for d in range(NFEAT):
                        feat[d] = hist[k, FEAT + d] if fabs(hist[k, TAG]) == tag else 0.0
                    fp = &feat[0]
                code = crust_contact(&SA, ca, &rot[i, 0], xi, &SB, cb, &rot[j, 0], xj, tol, g, fp,
                                     &con.delta, con.n, con.p)
                if advance:          # warm start; a setup pass changes no history
                    hist[k, TAG] = tag if code == CONTACT_NONE else -tag
                    if code == CONTACT_CRUST:
                        for d in range(3):   # n is g / |g| already
                            hist[k, AXIS + d] = con.n[d]
                    else:
                        gn = g[0] * g[0] + g[1] * g[1] + g[2] * g[2]
                        gn = 1.0 / sqrt(gn) if gn > 0.0 else 0.0
                        for d in range(3):
                            hist[k, AXIS + d] = g[d] * gn
                if code == CONTACT_NONE:
                    if use_xi and advance:
                        forget(&hist[k, 0], XI_WIDTH)
                    continue
                if code > 1:
                    nepa += 1
            ncont += 1
            count_contact(P, i, j, 1)
            rmin = P.radius[i] if P.radius[i] < P.radius[j] else P.radius[j]
            if con.delta > maxov * (2.0 * rmin):     # (a division only for a new largest overlap)
                maxov = con.delta / (2.0 * rmin)
                worst[0] = i
                worst[1] = j
            meff = P.rmass[i] * P.rmass[j] / (P.rmass[i] + P.rmass[j])
            bind_body(&A, P, i)
            A.x = xi
            bind_body(&B, P, j)
            B.x = xj
            # rolling resistance between spheres only (as pair sphere); none for shaped bodies (Part III)
            cf = &coeff[P.type[i], P.type[j], 0]
            energy += apply_pair(cf, &con, &A, &B, meff,
                                 contact_radius(cf, sph_i and sph_j, equivalent_radius(T, P.shape[i], P.radius[i]),
                                                equivalent_radius(T, P.shape[j], P.radius[j])),
                                 &hist[k, 0] if use_xi else NULL, dt, advance, out)
    stats[0] = ncont
    stats[1] = maxov
    stats[2] = energy
    stats[3] = ngjk
    stats[4] = nepa
    stats[5] = nsep
    stats[6] = nskip
