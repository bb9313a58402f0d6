# cython: language_level=3
"""Contacts between convex particles (shape table rows) and spheres: bounding-sphere broad phase, then
either the analytic sphere geometry (two spheres) or the Grains3D crust contact (dem/_gjk.pyx: GJK on the
shrunk cores, EPA when the cores overlap), one contact point per pair, and the shared Grains3D law
(dem_contact/law.pxd).

A scaled body is handed to GJK as its unscaled shape with the rotation matrix multiplied by the scale s:
the support point of s R K in direction d is s R s_K(R^T d) (support functions ignore the length of the
direction), i.e. the support of the body scaled by s; its crust is s times the shape's crust. A sphere
(shape -1, or a table sphere) is a point core with a crust equal to its radius: exact.

History per pair (values[k, 0:HISTORY]): the tangential spring xi (3, when ks > 0), then the GJK warm
start: the direction of the last core separation pa - pb (3, unit; also the pre-test axis), a tag of the
two shapes it was made for (1 value: a particle given another shape starts cold), negative while the pair
touched at its last GJK call (such a pair goes to GJK without the pre-test), and the last simplex (NFEAT,
see dem/_gjk.pyx: vertex pairs of polytopes, body-frame points otherwise). A lasting contact between
boxes reads the first 13 values only.

Box cores are posed once per step as their 8 world corners (poses); GJK reads its vertex pairs from them.
The rows of the next pair in the list are prefetched while the current one is solved: they are scattered
in memory and the solve is short."""
cimport numpy as cnp
from libc.math cimport sqrt, fabs
from dem_contact.law cimport forget, hooke, rolling_torque
from dem.shapes._support cimport (ShapeRef, quat_to_rot, support_world, polytope_core, box_corners, corner_box,
                                  MARGIN)
from dem._gjk cimport crust_contact, CONTACT_NONE, CONTACT_CRUST, NFEAT

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
    TAG = 6                           # history slots (module docstring): xi 0-2, axis 3-5, tag, simplex
    FEAT = 7
HISTORY = FEAT + NFEAT                # history values per pair
TAG_SLOT, FEAT_SLOT = TAG, FEAT       # (for Python: tests, tools)

cdef double MARGIN_SAFETY = 1e-12     # margins are kept this much (relative) short of the round-off
cdef double SQRT_HALF = 0.7071067811865476   # ||R' - R||_2 = ||R' - R||_F / sqrt(2) between two rotations
cdef double ROT_ROUNDOFF = 4e-15      # bound of what round-off (R not exactly orthonormal) adds to that
cdef double POINT_PARAMS[8]
POINT_PARAMS[:] = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]


cdef inline void _pose(int i, int s, const double[::1] radius, const int[::1] is_sphere,
                       const int[::1] core_kind, const double[:, ::1] core_params, const i64[::1] core_voff,
                       const int[::1] core_nv, const double[::1] crust_rel, const double[:, ::1] verts,
                       const double[:, ::1] corners, ShapeRef* ref, double* c) noexcept nogil:
    """Core and crust of particle i (shape s); its scaled rotation is rot[i], its corners (a box core)
    corners[i]."""
    ref.corners = NULL
    if s < 0 or is_sphere[s]:
        ref.kind = 0          # SPHERE of radius 0: a point
        ref.params = POINT_PARAMS
        ref.nverts = 0
        ref.verts = NULL
        c[0] = radius[i]
        return
    ref.kind = core_kind[s]
    ref.params = &core_params[s, 0]
    ref.nverts = core_nv[s]
    ref.verts = &verts[core_voff[s], 0]
    if corner_box(ref.kind, ref.params[MARGIN]):     # posed by poses
        ref.corners = &corners[i, 0]
    c[0] = crust_rel[s] * radius[i]


cdef inline bint _polytope(int s, const int[::1] is_sphere, const int[::1] core_kind,
                           const double[:, ::1] core_params) noexcept nogil:
    """A shape whose GJK warm start is its vertex pairs (dem/_gjk.pyx)."""
    return s >= 0 and not is_sphere[s] and polytope_core(core_kind[s], core_params[s, MARGIN])


cdef inline void _forget_points(double* h, int si, int sj, const int[::1] is_sphere, const int[::1] core_kind,
                                const double[:, ::1] core_params) noexcept nogil:
    """A pair found apart drops a simplex of body-frame points (curved bodies): GJK from such a simplex ends on
    points of its own within the tolerance, so keeping it across a separation would make the results depend
    on how long the pair stayed listed (margins, rebuilds). Vertex pairs lead to the same final simplex from
    any start and are kept."""
    cdef int d
    if not (_polytope(si, is_sphere, core_kind, core_params) and _polytope(sj, is_sphere, core_kind, core_params)):
        for d in range(NFEAT):
            h[d] = 0.0


cdef inline double _extent(const ShapeRef* ref, const double* R, const double* x, const double* u) noexcept nogil:
    """Support value h(u) = max over the posed core of u.(p - x): closed form for boxes, cylinders and
    points (the common cases of the pre-test), the support function otherwise."""
    cdef double db0, db1, db2
    cdef double sp[3]
    if ref.kind == 0 and ref.params[0] == 0.0 and ref.params[7] == 0.0:
        return 0.0                                     # a point (the core of a sphere particle)
    if (ref.kind == 1 or ref.kind == 2) and ref.params[7] == 0.0:
        db0 = R[0] * u[0] + R[3] * u[1] + R[6] * u[2]  # R^T u (R includes the scale)
        db1 = R[1] * u[0] + R[4] * u[1] + R[7] * u[2]
        db2 = R[2] * u[0] + R[5] * u[1] + R[8] * u[2]
        if ref.kind == 1:
            return ref.params[0] * fabs(db0) + ref.params[1] * fabs(db1) + ref.params[2] * fabs(db2)
        return ref.params[0] * sqrt(db0 * db0 + db1 * db1) + ref.params[1] * fabs(db2)
    support_world(ref, R, x, u, sp)
    return u[0] * (sp[0] - x[0]) + u[1] * (sp[1] - x[1]) + u[2] * (sp[2] - x[2])


def poses(const double[:, ::1] x, const double[:, ::1] quat, const double[::1] radius, const int[::1] shape,
          const int[::1] is_sphere, const int[::1] core_kind, const double[:, ::1] core_params,
          const double[::1] srad, int nall, double[:, ::1] rot, double[:, ::1] corners, double[:, ::1] xprev,
          double[::1] move, bint reset):
    """rot[i] = scale_i R(quat_i), row-major, for the shaped particles (identity for spheres), and the 8
    world corners of box cores (corners[i], see box_corners): computed once per step, used by every pair
    of the particle (a lasting contact between boxes re-reads a few corners at every call). move[i] bounds
    how far any point of particle i's core moved since the last call (zero on reset): |x - xprev| +
    ||R - R_prev||_2 r_shape (a rotation moves a point p by |(R - R_prev) p| <= ||R - R_prev||_2 |p|).
    R_prev^T R is a rotation by some angle t, so the singular values of R - R_prev are 2 sin(t/2) (twice)
    and 0: its spectral norm is its Frobenius norm over sqrt(2)."""
    cdef int i, k, s
    cdef double sc = 1.0, dr, dx
    cdef double R[9]
    with nogil:
        for i in range(nall):
            s = shape[i]
            if s < 0 or is_sphere[s]:
                for k in range(9):
                    R[k] = 0.0
                R[0] = R[4] = R[8] = 1.0
            else:
                sc = radius[i] / srad[s]
                quat_to_rot(&quat[i, 0], R)
                for k in range(9):
                    R[k] *= sc
                if corner_box(core_kind[s], core_params[s, MARGIN]):
                    box_corners(R, &x[i, 0], &core_params[s, 0], &corners[i, 0])
            move[i] = 0.0
            if not reset:
                dr = 0.0
                for k in range(9):
                    dr += (R[k] - rot[i, k]) * (R[k] - rot[i, k])
                dx = ((x[i, 0] - xprev[i, 0]) ** 2 + (x[i, 1] - xprev[i, 1]) ** 2
                      + (x[i, 2] - xprev[i, 2]) ** 2)
                move[i] = sqrt(dx) + ((sqrt(dr) * SQRT_HALF + ROT_ROUNDOFF * sc) * srad[s]
                                      if s >= 0 and not is_sphere[s] else 0.0)
            for k in range(9):
                rot[i, k] = R[k]
            for k in range(3):
                xprev[i, k] = x[i, k]


def compute(const double[:, ::1] x, const double[:, ::1] v, const double[:, ::1] omega,
            double[:, ::1] f, double[:, ::1] torque, const double[:, ::1] rot,
            const double[:, ::1] corners, const double[::1] radius,
            const double[::1] rmass, const int[::1] type_, const int[::1] shape, int nlocal,
            const i64[::1] offsets, const int[::1] neigh, const double[:, :, ::1] coeff,
            const int[::1] is_sphere, const int[::1] core_kind, const double[:, ::1] core_params,
            const i64[::1] core_voff, const int[::1] core_nv, const double[::1] crust_rel,
            const double[:, ::1] verts,
            double[:, ::1] hist, bint use_xi, double tol, double dt, bint advance,
            double[::1] margin, const double[::1] move, int[:, ::1] active, double[::1] stats, i64[::1] worst):
    """Adds contact forces and torques to f and torque (owned and ghost rows). stats receives
    [contacts, max overlap / smaller bounding diameter, elastic energy, GJK calls, EPA/fallback contacts,
    pairs rejected by the separating-axis pre-test, pairs skipped on their margin]; worst the (i, j) of the
    largest overlap.

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
    cdef int i, j, k, d, si, sj, code, ncont = 0, ngjk = 0, nepa = 0
    cdef double dx[3]
    cdef double n[3]
    cdef double p[3]
    cdef double li[3]
    cdef double lj[3]
    cdef double vr[3]
    cdef double fn[3]
    cdef double ft[3]
    cdef double F[3]
    cdef double tr[3]
    cdef double g[3]
    cdef double feat[NFEAT]
    cdef double* fp
    cdef double tag
    cdef double u[3]
    cdef double sb[3]
    cdef double r2, r, rsum, delta, meff, ca, cb, energy = 0.0, maxov = 0.0, rmin, gn
    cdef int nsep = 0, nskip = 0
    cdef double gap
    cdef bint sph_i, sph_j, new_axis
    cdef ShapeRef A, B
    cdef const double* c
    cdef double* h
    cdef int a, na = 0, kn, jn
    cdef double mi, m
    with nogil:
        for i in range(nlocal):          # pass 1: margins (branch-free: the outcome is unpredictable)
            mi = move[i]
            for k in range(offsets[i], offsets[i + 1]):
                m = margin[k] - (mi + move[neigh[k]])
                margin[k] = m
                active[na, 0] = i
                active[na, 1] = k
                na += m <= 0.0
        nskip = <int>(offsets[nlocal] - offsets[0]) - na
        for a in range(na):
            i = active[a, 0]
            k = active[a, 1]
            if a + 1 < na:       # the next pair's rows, scattered in memory: fetched while this one works
                kn = active[a + 1, 1]
                jn = neigh[kn]
                prefetch(&hist[kn, 0])
                prefetch(&hist[kn, FEAT + 2])
                prefetch(&x[jn, 0])
                prefetch(&rot[jn, 0])
                prefetch(&corners[jn, 0])
                prefetch(&corners[jn, 8])
                prefetch(&corners[jn, 16])
            margin[k] = 0.0
            si = shape[i]
            sph_i = si < 0 or is_sphere[si] != 0
            j = neigh[k]
            dx[0] = x[i, 0] - x[j, 0]
            dx[1] = x[i, 1] - x[j, 1]
            dx[2] = x[i, 2] - x[j, 2]
            r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]
            rsum = radius[i] + radius[j]
            sj = shape[j]
            if r2 >= rsum * rsum:
                if advance:
                    margin[k] = sqrt(r2) - rsum - MARGIN_SAFETY * rsum
                    hist[k, TAG] = fabs(hist[k, TAG])
                    _forget_points(&hist[k, FEAT], si, sj, is_sphere, core_kind, core_params)
                    if use_xi:
                        forget(&hist[k, 0])
                continue
            sph_j = sj < 0 or is_sphere[sj] != 0
            if sph_i and sph_j:
                r = sqrt(r2)
                for d in range(3):
                    n[d] = dx[d] / r
                delta = rsum - r
                # contact point in the middle of the overlap
                for d in range(3):
                    p[d] = x[i, d] - (radius[i] - 0.5 * delta) * n[d]
            else:
                _pose(i, si, radius, is_sphere, core_kind, core_params, core_voff, core_nv, crust_rel, verts,
                      corners, &A, &ca)
                _pose(j, sj, radius, is_sphere, core_kind, core_params, core_voff, core_nv, crust_rel, verts,
                      corners, &B, &cb)
                for d in range(3):
                    g[d] = hist[k, 3 + d]
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
                    gap = (u[0] * dx[0] + u[1] * dx[1] + u[2] * dx[2] - _extent(&A, &rot[i, 0], &x[i, 0], sb)
                           - _extent(&B, &rot[j, 0], &x[j, 0], u) - ca - cb)
                if gap >= 0.0:
                    nsep += 1
                    if advance:      # (a setup pass forgets no spring: it must not skip the pair later)
                        margin[k] = gap - MARGIN_SAFETY * rsum
                        if new_axis:            # the axis stays fixed while the pair is apart
                            for d in range(3):
                                hist[k, 3 + d] = g[d]
                        _forget_points(&hist[k, FEAT], si, sj, is_sphere, core_kind, core_params)
                        if use_xi:
                            forget(&hist[k, 0])
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
                code = crust_contact(&A, ca, &rot[i, 0], &x[i, 0], &B, cb, &rot[j, 0], &x[j, 0], tol, g, fp,
                                     &delta, n, p)
                if advance:          # warm start; a setup pass changes no history
                    hist[k, TAG] = tag if code == CONTACT_NONE else -tag
                    if code == CONTACT_CRUST:
                        for d in range(3):   # n is g / |g| already
                            hist[k, 3 + d] = n[d]
                    else:
                        gn = g[0] * g[0] + g[1] * g[1] + g[2] * g[2]
                        gn = 1.0 / sqrt(gn) if gn > 0.0 else 0.0
                        for d in range(3):
                            hist[k, 3 + d] = g[d] * gn
                if code == CONTACT_NONE:
                    if use_xi and advance:
                        forget(&hist[k, 0])
                    continue
                if code > 1:
                    nepa += 1
            ncont += 1
            rmin = radius[i] if radius[i] < radius[j] else radius[j]
            if delta > maxov * (2.0 * rmin):     # (a division only for a new largest overlap)
                maxov = delta / (2.0 * rmin)
                worst[0] = i
                worst[1] = j
            meff = rmass[i] * rmass[j] / (rmass[i] + rmass[j])
            for d in range(3):
                li[d] = p[d] - x[i, d]
                lj[d] = p[d] - x[j, d]
            # velocity of i relative to j at the contact point
            vr[0] = v[i, 0] + omega[i, 1] * li[2] - omega[i, 2] * li[1] - (v[j, 0] + omega[j, 1] * lj[2] - omega[j, 2] * lj[1])
            vr[1] = v[i, 1] + omega[i, 2] * li[0] - omega[i, 0] * li[2] - (v[j, 1] + omega[j, 2] * lj[0] - omega[j, 0] * lj[2])
            vr[2] = v[i, 2] + omega[i, 0] * li[1] - omega[i, 1] * li[0] - (v[j, 2] + omega[j, 0] * lj[1] - omega[j, 1] * lj[0])
            c = &coeff[type_[i], type_[j], 0]
            h = &hist[k, 0] if use_xi else NULL
            energy += hooke(c, delta, n, vr, meff, h, dt, advance, fn, ft)
            for d in range(3):
                F[d] = fn[d] + ft[d]
                f[i, d] += F[d]
                f[j, d] -= F[d]
            # torques about each centre of mass: lever to the contact point
            torque[i, 0] += li[1] * F[2] - li[2] * F[1]
            torque[i, 1] += li[2] * F[0] - li[0] * F[2]
            torque[i, 2] += li[0] * F[1] - li[1] * F[0]
            torque[j, 0] -= lj[1] * F[2] - lj[2] * F[1]
            torque[j, 1] -= lj[2] * F[0] - lj[0] * F[2]
            torque[j, 2] -= lj[0] * F[1] - lj[1] * F[0]
            # rolling resistance between spheres (as pair sphere); none for shaped bodies (Part III)
            if sph_i and sph_j and rolling_torque(c, &omega[i, 0], &omega[j, 0], fn,
                                                  radius[i] * radius[j] / rsum, tr):
                for d in range(3):
                    torque[i, d] += tr[d]
                    torque[j, d] -= tr[d]
    stats[0] = ncont
    stats[1] = maxov
    stats[2] = energy
    stats[3] = ngjk
    stats[4] = nepa
    stats[5] = nsep
    stats[6] = nskip
