# cython: language_level=3, boundscheck=False, wraparound=False, cdivision=True, initializedcheck=False
"""The overlap volume V of two sharp convex polytopes A and B (or of A and a half-space), and its gradient
with respect to A's pose, by clipping faces (nogil).

The intersection A n B is a convex polytope whose boundary is the part of A's boundary inside B plus the
part of B's boundary inside A. Moving A by dx changes V by S . dx and turning it by dtheta about its centre
x_A by M . dtheta, with
    S = integral over (dA n B) of n_A dS,        M = integral over (dA n B) of (x - x_A) x n_A dS,
n_A the outward normal of A (the boundary of A inside B moves, the rest does not count). So a potential
U(V) gives A the exact force -U'(V) S and torque -U'(V) M, and B the opposite force and the torque that
keeps the total angular momentum (the closed boundary of A n B has zero area vector and zero moment of
n). Every face of A is clipped by B's face planes (Sutherland-Hodgman: a convex polygon stays convex and
keeps its orientation), and its area vector and first moment are summed; V and the centroid come from the
tetrahedra of every boundary polygon of A n B (A's faces clipped by B, B's faces clipped by A) with a
common apex. With a half-space the apex lies on its plane, so the cap (the section of A by the plane) adds
nothing and is never built.

Everything is computed in A's rotated frame centred on x_A (as _polytope.pyx), then turned to world.
Faces of one body whose plane the other body does not reach are skipped (they cannot touch it), and so are
the planes that cut nothing of it.
V, S and M are continuous functions of the poses through every change of contact type (vertex/face,
edge/edge, edge/face, face/face), unlike the depth of the separating axes, whose normal jumps between
axes: this is what makes a law of V conserve energy. Cost: O(nf_A nf_B) clipped polygons at worst."""
import numpy as np
from libc.math cimport fabs

from dem._math cimport mat_vec, mat_tvec, cross3, dot3
from dem.contact._polytope cimport TopologyView, polytope_ref
from dem.contact._polytope import _pose, _poses

cdef enum:
    POLY_BUF = VOL_MAXFV + VOL_MAXF     # a clipped face gains at most one vertex per plane
cdef double COPLANAR_TOL = 1e-12     # relative (to the bounding radii): faces this close share a plane
MAXF = VOL_MAXF
MAXFV = VOL_MAXFV


cdef struct Sums:
    double V               # volume (tetrahedra with apex o)
    double c[3]            # integral of (x - o) dV
    double S[3]            # area vector of A's faces inside the other body
    double M[3]            # first moment of it about A's centre (the frame's origin)


cdef inline void _zero(Sums* s) noexcept nogil:
    cdef int d
    s.V = 0.0
    for d in range(3):
        s.c[d] = 0.0
        s.S[d] = 0.0
        s.M[d] = 0.0


cdef inline int _clip(const double* P, int n, const double* m, double d, double* out) noexcept nogil:
    """The part of polygon P (n points) where m.x <= d, into out; returns its point count (0 when none)."""
    cdef int k, e, c = 0
    cdef double dp, dq, t
    cdef const double* p
    cdef const double* q
    if n == 0:
        return 0
    p = P + 3 * (n - 1)
    dp = dot3(m, p) - d
    for k in range(n):
        q = P + 3 * k
        dq = dot3(m, q) - d
        if dq <= 0.0:
            if dp > 0.0:                       # entering: the crossing first
                t = dp / (dp - dq)
                for e in range(3):
                    out[3 * c + e] = p[e] + t * (q[e] - p[e])
                c += 1
            for e in range(3):
                out[3 * c + e] = q[e]
            c += 1
        elif dp <= 0.0:                        # leaving: the crossing only
            t = dp / (dp - dq)
            for e in range(3):
                out[3 * c + e] = p[e] + t * (q[e] - p[e])
            c += 1
        p = q
        dp = dq
    return c


cdef inline void _add_polygon(const double* P, int n, const double* nf, const double* o, bint moments,
                              Sums* s) noexcept nogil:
    """Adds a boundary polygon of the intersection (counter-clockwise seen along its outward normal nf):
    its tetrahedra with apex o to V and c, and (moments: a face of A) its area vector and first moment
    about the origin to S and M."""
    cdef double a[3]
    cdef double b[3]
    cdef double ab[3]
    cdef double q0[3]
    cdef double qi[3]
    cdef double qj[3]
    cdef double cen[3]
    cdef double cxn[3]
    cdef double area, vol
    cdef int i, d
    for d in range(3):
        q0[d] = P[d] - o[d]
    for i in range(1, n - 1):
        for d in range(3):
            qi[d] = P[3 * i + d] - o[d]
            qj[d] = P[3 * i + 3 + d] - o[d]
        cross3(qi, qj, ab)
        vol = dot3(q0, ab) / 6.0
        s.V += vol
        for d in range(3):
            s.c[d] += vol * 0.25 * (q0[d] + qi[d] + qj[d])
        if moments:
            for d in range(3):
                a[d] = P[3 * i + d] - P[d]
                b[d] = P[3 * i + 3 + d] - P[d]
            cross3(a, b, ab)
            area = 0.5 * dot3(nf, ab)
            for d in range(3):
                cen[d] = (P[d] + P[3 * i + d] + P[3 * i + 3 + d]) / 3.0
            cross3(cen, nf, cxn)
            for d in range(3):
                s.S[d] += area * nf[d]
                s.M[d] += area * cxn[d]


cdef inline int _clip_faces(const Polytope* P, const double* M, double sc, const double* t,
                            const double* planes, int nplanes, const int* faces_on, const int* planes_on,
                            const int* same, bint own, const double* o, bint moments, double* buf_a,
                            double* buf_b, Sums* s) noexcept nogil:
    """Clips the faces of P (posed in the frame as t + sc M v) by the planes (nplanes rows m, d: keep m.x <=
    d) and adds the pieces to s. faces_on, planes_on (or NULL: all): the faces and planes that take part
    (_reached: a face the other body does not reach cannot meet it, a plane P does not reach cuts none of
    its faces). `same` (or NULL) pairs coplanar faces of like orientation (_coplanar): with `own`, P's face
    same[g] is not clipped by plane g (P's face holds that piece of the common boundary); without, P's face
    g is skipped when same[g] >= 0 (the other body holds it), so the piece counts once whatever the
    round-off. Returns -1 when a face has more than VOL_MAXFV vertices."""
    cdef int f, k, e, n, g
    cdef double nf[3]
    cdef double v[3]
    cdef double* cur
    cdef double* nxt
    cdef double* tmp
    for f in range(P.nf):
        n = P.fcount[f]
        if n > VOL_MAXFV:
            return -1
        if (faces_on != NULL and not faces_on[f]) or (same != NULL and not own and same[f] >= 0):
            continue
        mat_vec(M, P.fnormal + 3 * f, nf)
        cur = buf_a
        nxt = buf_b
        for k in range(n):
            mat_vec(M, P.verts + 3 * P.fverts[P.ffirst[f] + k], v)
            for e in range(3):
                cur[3 * k + e] = t[e] + sc * v[e]
        for g in range(nplanes):
            if (planes_on != NULL and not planes_on[g]) or (same != NULL and own and same[g] == f):
                continue
            n = _clip(cur, n, &planes[4 * g], planes[4 * g + 3], nxt)
            if n < 3:
                break
            tmp = cur
            cur = nxt
            nxt = tmp
        if n >= 3:
            _add_polygon(cur, n, nf, o, moments, s)
    return 0


cdef inline void _reached(const double* planes, int nplanes, const double* verts, int nverts, double tol,
                         int* on) noexcept nogil:
    """on[g]: whether a vertex of the other body comes within tol of plane g (or beyond). Where none does,
    the other body lies wholly inside that half-space: face g cannot meet it, and plane g cuts nothing of
    it (in a shallow contact, most planes). tol keeps faces that share a plane, whichever way round-off
    puts the other's vertices."""
    cdef int g, k
    for g in range(nplanes):
        on[g] = False
        for k in range(nverts):
            if dot3(&planes[4 * g], &verts[3 * k]) >= planes[4 * g + 3] - tol:
                on[g] = True
                break


cdef inline void _coplanar(const double* pa, const int* on_a, int na, const double* pb, const int* on_b, int nb,
                           double tol, int* same) noexcept nogil:
    """same[g]: the face of A in the plane of B's face g with the same outward normal (within tol, a length;
    the normals within tol per unit length), or -1. Such faces (aligned bodies, a lattice, a stack) bound
    the intersection together: clipped by each other's planes, round-off alone would decide whether the
    piece counts twice or not at all. Only faces the other body reaches can share a plane with it."""
    cdef int f, g
    cdef double c = 1.0 - 1e-12
    for g in range(nb):
        same[g] = -1
        if not on_b[g]:
            continue
        for f in range(na):
            if on_a[f] and (pa[4 * f] * pb[4 * g] + pa[4 * f + 1] * pb[4 * g + 1] + pa[4 * f + 2] * pb[4 * g + 2] >= c
                            and fabs(pa[4 * f + 3] - pb[4 * g + 3]) <= tol):
                same[g] = f
                break


cdef inline void _to_world(const Sums* s, const double* Ra, const double* xa, const double* o,
                           OverlapVolume* out) noexcept nogil:
    cdef double c[3]
    cdef int d
    out.volume = s.V
    mat_vec(Ra, s.S, out.area)
    mat_vec(Ra, s.M, out.moment)
    for d in range(3):
        c[d] = o[d] + s.c[d] / s.V
    mat_vec(Ra, c, out.centroid)
    for d in range(3):
        out.centroid[d] += xa[d]


cdef int overlap_volume(const Polytope* A, const double* Ra, double sa, const double* xa,
                        const Polytope* B, const double* Rb, double sb, const double* xb,
                        OverlapVolume* out) noexcept nogil:
    """V, S, M and the centroid of A n B (module docstring); returns 1 when V > 0, 0 when they do not
    overlap (out.volume 0), -1 when a body has more than VOL_MAXF faces or VOL_MAXV vertices, or a face
    more than VOL_MAXFV vertices."""
    cdef double MB[9]
    cdef double I[9]
    cdef double t[3]
    cdef double dx[3]
    cdef double zero[3]
    cdef double mb[3]
    cdef double planes_a[4 * VOL_MAXF]
    cdef double planes_b[4 * VOL_MAXF]
    cdef double buf_a[3 * POLY_BUF]
    cdef double buf_b[3 * POLY_BUF]
    cdef double va[3 * VOL_MAXV]
    cdef double vb[3 * VOL_MAXV]
    cdef int same[VOL_MAXF]
    cdef int on_a[VOL_MAXF]
    cdef int on_b[VOL_MAXF]
    cdef Sums s
    cdef double tol
    cdef int i, j, f
    out.volume = 0.0
    if A.nf > VOL_MAXF or B.nf > VOL_MAXF or A.nv > VOL_MAXV or B.nv > VOL_MAXV:
        return -1
    for i in range(3):                         # B in A's frame: t + sb MB v
        for j in range(3):
            MB[3 * i + j] = Ra[i] * Rb[j] + Ra[3 + i] * Rb[3 + j] + Ra[6 + i] * Rb[6 + j]
            I[3 * i + j] = 1.0 if i == j else 0.0
        dx[i] = xb[i] - xa[i]
        zero[i] = 0.0
    mat_tvec(Ra, dx, t)
    for f in range(A.nf):
        for i in range(3):
            planes_a[4 * f + i] = A.fnormal[3 * f + i]
        planes_a[4 * f + 3] = sa * A.foffset[f]
    for f in range(B.nf):
        mat_vec(MB, B.fnormal + 3 * f, mb)
        for i in range(3):
            planes_b[4 * f + i] = mb[i]
        planes_b[4 * f + 3] = sb * B.foffset[f] + dot3(mb, t)
    for f in range(A.nv):                      # both bodies' vertices in the frame, for the culls
        for i in range(3):
            va[3 * f + i] = sa * A.verts[3 * f + i]
    for f in range(B.nv):
        mat_vec(MB, B.verts + 3 * f, mb)
        for i in range(3):
            vb[3 * f + i] = t[i] + sb * mb[i]
    tol = COPLANAR_TOL * (sa * A.radius + sb * B.radius)
    _reached(planes_a, A.nf, vb, B.nv, 2.0 * tol, on_a)
    _reached(planes_b, B.nf, va, A.nv, 2.0 * tol, on_b)
    _coplanar(planes_a, on_a, A.nf, planes_b, on_b, B.nf, tol, same)
    _zero(&s)
    # the tetrahedra's apex: B's centre (any point would do; a near one keeps them small)
    if _clip_faces(A, I, sa, zero, planes_b, B.nf, on_a, on_b, same, True, t, True, buf_a, buf_b, &s) < 0:
        return -1
    if _clip_faces(B, MB, sb, t, planes_a, A.nf, on_b, on_a, same, False, t, False, buf_a, buf_b, &s) < 0:
        return -1
    if not s.V > 0.0:
        return 0
    _to_world(&s, Ra, xa, t, out)
    return 1


cdef int overlap_halfspace(const Polytope* A, const double* Ra, double sa, const double* xa,
                           const double* n, double d, OverlapVolume* out) noexcept nogil:
    """V, S, M and the centroid of the part of A in the half-space n.x <= d (world; n unit): a plane wall
    whose solid is that side. Returns as overlap_volume."""
    cdef double I[9]
    cdef double zero[3]
    cdef double plane[4]
    cdef double o[3]
    cdef double buf_a[3 * POLY_BUF]
    cdef double buf_b[3 * POLY_BUF]
    cdef Sums s
    cdef int i, j
    out.volume = 0.0
    mat_tvec(Ra, n, plane)
    plane[3] = d - dot3(n, xa)
    for i in range(3):
        for j in range(3):
            I[3 * i + j] = 1.0 if i == j else 0.0
        zero[i] = 0.0
        o[i] = plane[3] * plane[i]             # the apex on the plane: the cap adds no tetrahedron
    _zero(&s)
    # no face is culled (one plane clips fast, and a face wholly outside the half-space ends empty)
    if _clip_faces(A, I, sa, zero, plane, 1, NULL, NULL, NULL, True, o, True, buf_a, buf_b, &s) < 0:
        return -1
    if not s.V > 0.0:
        return 0
    _to_world(&s, Ra, xa, o, out)
    return 1


# ---------------------------------------------------------------- Python entries (tests, tools)
cdef _result(int hit, OverlapVolume* r):
    """overlap_volume's answer for Python: (V, S, M, centroid), zeros and nan when apart."""
    if hit < 0:
        raise ValueError("a body has more than %d faces or a face more than %d vertices" % (VOL_MAXF, VOL_MAXFV))
    if hit == 0:
        r.area[:] = [0.0, 0.0, 0.0]
        r.moment[:] = [0.0, 0.0, 0.0]
        r.centroid[:] = [np.nan, np.nan, np.nan]
    return (r.volume, np.array([r.area[0], r.area[1], r.area[2]]),
            np.array([r.moment[0], r.moment[1], r.moment[2]]),
            np.array([r.centroid[0], r.centroid[1], r.centroid[2]]))


def pair(TopologyView tv, int ia, int ib, xa, qa, xb, qb, double sa=1.0, double sb=1.0):
    """Rows ia, ib of the packed topology at poses (x, unit quaternion (w, x, y, z), scale): (V, S, M,
    centroid) as OverlapVolume (zeros and nan when apart)."""
    if not (0 <= ia < tv.t.nrows and 0 <= ib < tv.t.nrows) or not (tv.t.poly[ia] and tv.t.poly[ib]):
        raise ValueError("rows %d, %d are not polytopes of this table" % (ia, ib))
    cdef Polytope A, B
    cdef OverlapVolume r
    cdef double[::1] Ra = _pose(qa), Rb = _pose(qb)
    cdef double[::1] xa_ = np.ascontiguousarray(xa, float), xb_ = np.ascontiguousarray(xb, float)
    cdef int hit
    polytope_ref(&tv.t, ia, &A)
    polytope_ref(&tv.t, ib, &B)
    with nogil:
        hit = overlap_volume(&A, &Ra[0], sa, &xa_[0], &B, &Rb[0], sb, &xb_[0], &r)
    return _result(hit, &r)


def halfspace(TopologyView tv, int ia, xa, qa, n, double d, double sa=1.0):
    """Row ia posed at (x, q, scale) against the half-space n.x <= d: (V, S, M, centroid)."""
    if not (0 <= ia < tv.t.nrows) or not tv.t.poly[ia]:
        raise ValueError("row %d is not a polytope of this table" % ia)
    cdef Polytope A
    cdef OverlapVolume r
    cdef double[::1] Ra = _pose(qa)
    cdef double[::1] xa_ = np.ascontiguousarray(xa, float)
    cdef double[::1] n_ = np.ascontiguousarray(n, float) / np.linalg.norm(n)
    cdef int hit
    polytope_ref(&tv.t, ia, &A)
    with nogil:
        hit = overlap_halfspace(&A, &Ra[0], sa, &xa_[0], &n_[0], d, &r)
    return _result(hit, &r)


def time_pairs(TopologyView tv, int[::1] ia, int[::1] ib, double[:, ::1] xa, double[:, ::1] qa,
               double[:, ::1] xb, double[:, ::1] qb, int reps):
    """overlap_volume on the m pairs, reps times in one nogil loop (benchmarks): (seconds per query, hits)."""
    import time
    cdef int m = ia.shape[0], r, k, hits = 0
    cdef Polytope A, B
    cdef OverlapVolume ov
    cdef double[:, ::1] Ra = _poses(qa)
    cdef double[:, ::1] Rb = _poses(qb)
    t0 = time.perf_counter()
    with nogil:
        for r in range(reps):
            for k in range(m):
                polytope_ref(&tv.t, ia[k], &A)
                polytope_ref(&tv.t, ib[k], &B)
                hits += overlap_volume(&A, &Ra[k, 0], 1.0, &xa[k, 0], &B, &Rb[k, 0], 1.0, &xb[k, 0], &ov) > 0
    return (time.perf_counter() - t0) / (reps * m), hits
