# cython: language_level=3, boundscheck=False, wraparound=False, cdivision=True, initializedcheck=False
"""GJK distance, EPA penetration depth and the Grains3D crust contact, nogil.

GJK (Gilbert-Johnson-Keerthi) on the Minkowski difference M = A - B with the signed-volume sub-simplex
solver of Montanari, Petrinic & Barbieri (ACM TOG 2017): the closest point of a simplex to the origin is
found from signed volumes/areas projected on the best-conditioned coordinate plane, which stays robust for
flat or thin simplices where Johnson's determinant recursion breaks down. Termination: the upper bound |v|
and the best lower bound v.w/|v| agree to a relative tol, a repeated support point, or no progress for a
few iterations. A run that stalls with the gap open (a curved body against an edge, where new support
points land beside old ones) is restarted once from its best direction. Accuracy: relative 1e-10 at the
default tol on nearly all pairs, 1e-9 on all of 10^4 random pairs of the tests.

EPA (expanding polytope) starts from the final GJK tetrahedron (blown up to a tetrahedron if GJK ended on a
lower simplex with the origin on its boundary) and refines the face of M closest to the origin; horizon by
depth-first search over face adjacency, so the polytope stays a closed 2-manifold. It stops when the face
distance (a lower bound of the depth) and the support along that face normal (an upper bound) agree to
tol plus a round-off floor; if it runs out of vertices first (a curved core centred on the origin) or
round-off breaks the polytope, it answers its best upper bound, a translation that does separate.

crust_contact: Grains3D contact on shrunk bodies. Each body is core (+) ball(crust). While the cores are
apart, distance d < crust_a + crust_b gives overlap = crust_a + crust_b - d, the normal along the closest
points and the contact point midway between the two swollen surfaces; deeper overlaps (cores intersecting)
use EPA on the cores, depth + crust_a + crust_b (exact for the rounded bodies, continuous at the switch).
"""
import numpy as np
cimport numpy as cnp
from libc.math cimport sqrt, fabs, cos, sin, INFINITY
from dem._math cimport cross3, det3, dot3, sub3
from dem.shapes._support cimport (ShapeRef, support_world, support_world_id, box_support_id, box_corners,
                                  corner_box, vertex_world, posed_point, quat_to_rot, polytope_core, MARGIN,
                                  NCORNER)
from dem.shapes._table cimport ShapeView, TableView, body_ref, core_ref

cdef enum:
    GJK_MAXIT = 128
    EPA_MAXV = 128
    EPA_MAXF = 1024      # faces are never reused: a run stops refining when it could run out
cdef double EPS_ZERO = 1e-26      # |v|^2 <= EPS_ZERO * max|w|^2: origin on the boundary (distance ~1e-13 size)
cdef double EPS_DUP = 1e-28       # repeated support point
cdef double EPA_FLOOR = 1e-11     # EPA stops when the depth is bracketed to this * size: faces with tiny
#                                   edges (curved bodies) carry plane errors of about eps * size / edge


cdef inline void _minkowski(const ShapeRef* A, const double* Ra, const double* xa,
                            const ShapeRef* B, const double* Rb, const double* xb,
                            const double* d, double* a, double* b, double* w) noexcept nogil:
    """Support of A - B in direction d: s_A(d) - s_B(-d)."""
    cdef double nd[3]
    nd[0] = -d[0]
    nd[1] = -d[1]
    nd[2] = -d[2]
    support_world(A, Ra, xa, d, a)
    support_world(B, Rb, xb, nd, b)
    sub3(a, b, w)


cdef inline void _minkowski_id(const ShapeRef* A, const double* Ra, const double* xa,
                               const ShapeRef* B, const double* Rb, const double* xb,
                               const double* d, double* a, double* b, double* w, int* fa, int* fb) noexcept nogil:
    """_minkowski, with the vertex indices of the two support points (-1 on curved shapes)."""
    cdef double nd[3]
    nd[0] = -d[0]
    nd[1] = -d[1]
    nd[2] = -d[2]
    fa[0] = support_world_id(A, Ra, xa, d, a)
    fb[0] = support_world_id(B, Rb, xb, nd, b)
    sub3(a, b, w)


# ---------------------------------------------------------------- signed-volume sub-simplex solver
# Each routine gets the simplex points in ``s`` (rows) and the indices ``idx`` of the sub-simplex to solve,
# writes barycentric weights into lam (indexed like s, zero for dropped points) and returns |v|^2.

cdef double _s1d(double (*s)[3], int i0, int i1, double* lam) noexcept nogil:
    cdef double t[3]
    cdef double tt, mu
    cdef double v[3]
    sub3(s[i1], s[i0], t)
    tt = dot3(t, t)
    lam[i0] = 1.0
    lam[i1] = 0.0
    if tt > 0.0:
        mu = -dot3(s[i0], t) / tt
        if mu >= 1.0:
            lam[i0] = 0.0
            lam[i1] = 1.0
        elif mu > 0.0:
            lam[i0] = 1.0 - mu
            lam[i1] = mu
    v[0] = lam[i0] * s[i0][0] + lam[i1] * s[i1][0]
    v[1] = lam[i0] * s[i0][1] + lam[i1] * s[i1][1]
    v[2] = lam[i0] * s[i0][2] + lam[i1] * s[i1][2]
    return dot3(v, v)


cdef inline double _area2(const double* p, const double* q, const double* r, int J, int K) noexcept nogil:
    return (q[J] - p[J]) * (r[K] - p[K]) - (q[K] - p[K]) * (r[J] - p[J])


cdef double _s2d(double (*s)[3], int i0, int i1, int i2, double* lam) noexcept nogil:
    cdef double e1[3]
    cdef double e2[3]
    cdef double n[3]
    cdef double p0[3]
    cdef double C[3]
    cdef double tl[4]
    cdef double nn, k, best, dd
    cdef double mu = 0.0
    cdef int I, J, K, j
    cdef int ids[3]
    cdef bint inside
    ids[0] = i0
    ids[1] = i1
    ids[2] = i2
    sub3(s[i1], s[i0], e1)
    sub3(s[i2], s[i0], e2)
    cross3(e1, e2, n)
    nn = dot3(n, n)
    inside = False
    C[0] = C[1] = C[2] = 0.0
    if nn > 0.0:
        k = dot3(s[i0], n) / nn
        p0[0] = k * n[0]
        p0[1] = k * n[1]
        p0[2] = k * n[2]
        I = 0
        if fabs(n[1]) > fabs(n[I]):
            I = 1
        if fabs(n[2]) > fabs(n[I]):
            I = 2
        J = (I + 1) % 3
        K = (I + 2) % 3
        mu = _area2(s[i0], s[i1], s[i2], J, K)
        C[0] = _area2(p0, s[i1], s[i2], J, K)
        C[1] = _area2(s[i0], p0, s[i2], J, K)
        C[2] = _area2(s[i0], s[i1], p0, J, K)
        inside = C[0] * mu > 0.0 and C[1] * mu > 0.0 and C[2] * mu > 0.0
        if inside:
            k = C[0] + C[1] + C[2]        # = mu up to round-off; dividing by the sum keeps sum(lam) = 1
            lam[i0] = C[0] / k
            lam[i1] = C[1] / k
            lam[i2] = C[2] / k
            for j in range(3):
                p0[j] = lam[i0] * s[i0][j] + lam[i1] * s[i1][j] + lam[i2] * s[i2][j]
            return dot3(p0, p0)
    # outside: the closest of the edges opposite the vertices whose sign test failed (all if degenerate)
    best = -1.0
    for j in range(3):
        if nn > 0.0 and C[j] * mu > 0.0:
            continue
        tl[0] = tl[1] = tl[2] = tl[3] = 0.0
        dd = _s1d(s, ids[(j + 1) % 3], ids[(j + 2) % 3], tl)
        if best < 0.0 or dd < best:
            best = dd
            lam[i0] = tl[i0]
            lam[i1] = tl[i1]
            lam[i2] = tl[i2]
    if best < 0.0:      # cannot happen, keep the first vertex
        lam[i0] = 1.0
        lam[i1] = lam[i2] = 0.0
        best = dot3(s[i0], s[i0])
    return best


cdef double _s3d(double (*s)[3], double* lam, bint* inside) noexcept nogil:
    # cofactors of the last row of [[s1 s2 s3 s4], [1 1 1 1]]: lam_j = C_j / det
    cdef double C[4]
    cdef double tl[4]
    cdef double det, best, dd, sc
    cdef int j, f0, f1, f2
    C[0] = -det3(s[1], s[2], s[3])
    C[1] = det3(s[0], s[2], s[3])
    C[2] = -det3(s[0], s[1], s[3])
    C[3] = det3(s[0], s[1], s[2])
    det = C[0] + C[1] + C[2] + C[3]
    sc = 0.0
    for j in range(4):
        dd = dot3(s[j], s[j])
        if dd > sc:
            sc = dd
    # origin inside only if the tetrahedron is not flat to round-off (|det| ~ 6 volume vs eps size^3)
    if (C[0] * det > 0.0 and C[1] * det > 0.0 and C[2] * det > 0.0 and C[3] * det > 0.0
            and fabs(det) > 1e-13 * sc * sqrt(sc)):
        for j in range(4):
            lam[j] = C[j] / det
        inside[0] = True
        return 0.0
    inside[0] = False
    best = -1.0
    for j in range(4):
        if C[j] * det > 0.0 and fabs(det) > 1e-13 * sc * sqrt(sc):
            continue                   # origin on the inner side of face j: not the closest face
        f0 = (j + 1) % 4
        f1 = (j + 2) % 4
        f2 = (j + 3) % 4
        tl[0] = tl[1] = tl[2] = tl[3] = 0.0
        dd = _s2d(s, f0, f1, f2, tl)
        if best < 0.0 or dd < best:
            best = dd
            lam[0] = tl[0]
            lam[1] = tl[1]
            lam[2] = tl[2]
            lam[3] = tl[3]
    return best


cdef void _reduce(Simplex* S) noexcept nogil:
    """Solve the sub-simplex problem, drop points of zero weight (keeps order)."""
    cdef double lam[4]
    cdef bint inside = False
    cdef int i, k, c
    lam[0] = lam[1] = lam[2] = lam[3] = 0.0
    if S.n == 1:
        lam[0] = 1.0
    elif S.n == 2:
        _s1d(S.w, 0, 1, lam)
    elif S.n == 3:
        _s2d(S.w, 0, 1, 2, lam)
    else:
        _s3d(S.w, lam, &inside)
    k = 0
    for i in range(S.n):
        if lam[i] > 0.0 or (inside and S.n == 4):
            if k != i:
                for c in range(3):
                    S.w[k][c] = S.w[i][c]
                    S.a[k][c] = S.a[i][c]
                    S.b[k][c] = S.b[i][c]
                S.fa[k] = S.fa[i]
                S.fb[k] = S.fb[i]
            S.lam[k] = lam[i]
            k += 1
    if k == 0:       # all weights underflowed: keep the point closest to the origin
        S.lam[0] = 1.0
        k = 1
    S.n = k


cdef inline bint _solve(Simplex* S, double* v, double* pa, double* pb) noexcept nogil:
    """Reduce S to the sub-simplex nearest the origin and set v to its closest point; True (v = 0, pa and pb
    the witnesses) when S is a tetrahedron holding the origin."""
    _reduce(S)
    if S.n == 4:
        v[0] = v[1] = v[2] = 0.0
        _witness(S, pa, pb)
        return True
    _closest(S, v)
    return False


cdef inline void _set_point(Simplex* S, int k, const double* w, const double* a, const double* b, int ia,
                            int ib) noexcept nogil:
    cdef int c
    for c in range(3):
        S.w[k][c] = w[c]
        S.a[k][c] = a[c]
        S.b[k][c] = b[c]
    S.fa[k] = ia
    S.fb[k] = ib


cdef inline void _copy_simplex(Simplex* dst, const Simplex* src) noexcept nogil:
    """Copy the live points only (a whole-struct copy costs more than a GJK iteration's arithmetic)."""
    cdef int i, c
    dst.n = src.n
    for i in range(src.n):
        for c in range(3):
            dst.w[i][c] = src.w[i][c]
            dst.a[i][c] = src.a[i][c]
            dst.b[i][c] = src.b[i][c]
        dst.lam[i] = src.lam[i]
        dst.fa[i] = src.fa[i]
        dst.fb[i] = src.fb[i]


cdef inline void _closest(const Simplex* S, double* v) noexcept nogil:
    cdef int i, c
    for c in range(3):
        v[c] = 0.0
        for i in range(S.n):
            v[c] += S.lam[i] * S.w[i][c]


cdef inline void _witness(const Simplex* S, double* pa, double* pb) noexcept nogil:
    cdef int i, c
    for c in range(3):
        pa[c] = 0.0
        pb[c] = 0.0
        for i in range(S.n):
            pa[c] += S.lam[i] * S.a[i][c]
            pb[c] += S.lam[i] * S.b[i][c]


cdef int gjk_distance(const ShapeRef* A, const double* Ra, const double* xa,
                      const ShapeRef* B, const double* Rb, const double* xb,
                      double tol, double sep, double* v, Simplex* S, bint warm, double* pa,
                      double* pb) noexcept nogil:
    """Closest points of A and B (see _gjk_run). sep: stop as soon as the distance is proved >= sep (a contact
    test needs no more; v then has the best upper bound's length, pa and pb are not the closest points). A run that stops without closing the duality gap (a stall:
    on a curved body against an edge, new support points can land beside old ones and progress becomes
    quadratically small) is run once more from a fresh simplex along its best direction, which resumes
    linear convergence; the smaller upper bound is kept."""
    cdef Simplex S2
    cdef double v2[3]
    cdef double pa2[3]
    cdef double pb2[3]
    cdef bint closed, closed2
    cdef int c
    cdef int r = _gjk_run(A, Ra, xa, B, Rb, xb, tol, sep, v, S, warm, pa, pb, &closed)
    if r != GJK_SEPARATED or closed:
        return r
    for c in range(3):
        v2[c] = v[c]
    if (_gjk_run(A, Ra, xa, B, Rb, xb, tol, sep, v2, &S2, False, pa2, pb2, &closed2) == GJK_SEPARATED
            and dot3(v2, v2) < dot3(v, v)):
        _copy_simplex(S, &S2)
        for c in range(3):
            v[c] = v2[c]
            pa[c] = pa2[c]
            pb[c] = pb2[c]
    return r


cdef int _gjk_run(const ShapeRef* A, const double* Ra, const double* xa,
                  const ShapeRef* B, const double* Rb, const double* xb,
                  double tol, double sep, double* v, Simplex* S, bint warm, double* pa, double* pb,
                  bint* closed) noexcept nogil:
    """Closest points of A and B. On entry v is a guess of pa - pb (zero: use xa - xb), or, if warm, S holds a
    start simplex (S.n >= 1 points a, b, w = a - b, e.g. the last step's vertices at the new pose: a steady
    contact then ends after one support query); on exit v = pa - pb.
    Returns GJK_SEPARATED (|v| is the distance) or GJK_INTERSECT (origin inside or on the boundary of
    A - B within ~1e-13 of the size; S holds the last simplex for EPA).

    |v| of any iterate is an upper bound of the distance and v.w/|v| a lower bound; the loop stops when
    the best bounds agree to tol (relative), on a repeated support point, or after a few iterations
    without a better upper bound (round-off floor); the best simplex is returned (pa, pb), and v has the
    length of the best upper bound and the direction of the best lower bound. closed: the bounds agree."""
    cdef double d[3]
    cdef double a[3]
    cdef double b[3]
    cdef double w[3]
    cdef double nlb[3]
    cdef double vv, vw, maxw2, ww, dx, best_vv, lb = 0.0, lbi, rs, gap2
    cdef Simplex best
    cdef int it, i, c, stall = 0, ia, ib
    cdef bint dup, cur_best
    closed[0] = False
    if warm and S.n > 0:
        maxw2 = 0.0
        for i in range(S.n):
            ww = dot3(S.w[i], S.w[i])
            if ww > maxw2:
                maxw2 = ww
        if _solve(S, v, pa, pb):
            return GJK_INTERSECT
    else:
        if dot3(v, v) == 0.0:
            sub3(xa, xb, v)
            if dot3(v, v) == 0.0:
                v[0] = 1.0
        d[0] = -v[0]
        d[1] = -v[1]
        d[2] = -v[2]
        _minkowski_id(A, Ra, xa, B, Rb, xb, d, a, b, w, &ia, &ib)
        _set_point(S, 0, w, a, b, ia, ib)
        S.n = 1
        S.lam[0] = 1.0
        for c in range(3):
            v[c] = w[c]
        maxw2 = dot3(w, w)
    best_vv = dot3(v, v)
    cur_best = True                 # S is the best simplex so far (best is only written before S changes)
    gap2 = (1.0 - tol) * (1.0 - tol)
    for it in range(GJK_MAXIT):
        vv = dot3(v, v)
        if vv <= EPS_ZERO * maxw2:
            _witness(S, pa, pb)
            return GJK_INTERSECT
        d[0] = -v[0]
        d[1] = -v[1]
        d[2] = -v[2]
        _minkowski_id(A, Ra, xa, B, Rb, xb, d, a, b, w, &ia, &ib)
        vw = dot3(v, w)
        if vw > 0.0:
            rs = 1.0 / sqrt(vv)
            lbi = vw * rs
            if lbi > lb:
                lb = lbi
                for c in range(3):
                    nlb[c] = v[c] * rs
        if vv - vw <= tol * vv or lb * lb >= gap2 * best_vv or lb >= sep:  # duality gap, or far enough
            closed[0] = True
            break
        dup = False
        for i in range(S.n):
            dx = (w[0] - S.w[i][0]) ** 2 + (w[1] - S.w[i][1]) ** 2 + (w[2] - S.w[i][2]) ** 2
            if dx <= EPS_DUP * maxw2:
                dup = True
        if dup:
            break
        if cur_best:
            _copy_simplex(&best, S)
        _set_point(S, S.n, w, a, b, ia, ib)
        S.n += 1
        ww = dot3(w, w)
        if ww > maxw2:
            maxw2 = ww
        if _solve(S, v, pa, pb):
            return GJK_INTERSECT
        vv = dot3(v, v)
        if vv < best_vv:
            best_vv = vv
            cur_best = True
            stall = 0
        else:
            cur_best = False
            stall += 1
            if stall >= 4:                      # round-off floor
                break
    if not cur_best:
        _copy_simplex(S, &best)
    _witness(S, pa, pb)
    sub3(pa, pb, v)
    if lb > 0.0:
        # the distance is the best upper bound |v|; its direction the one of the best lower bound: on a stall
        # the last simplices agree on |v| but their normals wander, the dual direction does not
        vv = sqrt(dot3(v, v))
        for c in range(3):
            v[c] = vv * nlb[c]
    return GJK_SEPARATED


# ---------------------------------------------------------------- EPA
cdef struct Polytope:
    int nv, nf
    double w[EPA_MAXV][3]
    double a[EPA_MAXV][3]
    double b[EPA_MAXV][3]
    int fv[EPA_MAXF][3]       # vertex indices, counter-clockwise seen from outside
    int adj[EPA_MAXF][3]      # face across edge k = (fv[k], fv[k+1])
    int adje[EPA_MAXF][3]     # that edge's index in the neighbour
    double n[EPA_MAXF][3]     # unit outward normal
    double dist[EPA_MAXF]     # n . w_i (signed distance of the plane from the origin)
    bint alive[EPA_MAXF]
    int nh                    # horizon: (face, edge) pairs
    int hf[EPA_MAXF]
    int he[EPA_MAXF]


cdef void _face_plane(Polytope* P, int f) noexcept nogil:
    cdef double e1[3]
    cdef double e2[3]
    cdef double nn
    cdef int* v = P.fv[f]
    sub3(P.w[v[1]], P.w[v[0]], e1)
    sub3(P.w[v[2]], P.w[v[0]], e2)
    cross3(e1, e2, P.n[f])
    nn = sqrt(dot3(P.n[f], P.n[f]))
    if nn > 0.0:
        P.n[f][0] /= nn
        P.n[f][1] /= nn
        P.n[f][2] /= nn
        P.dist[f] = (dot3(P.n[f], P.w[v[0]]) + dot3(P.n[f], P.w[v[1]]) + dot3(P.n[f], P.w[v[2]])) / 3.0
    else:
        P.dist[f] = 1e300      # degenerate sliver: never the closest face


cdef int _add_face(Polytope* P, int i, int j, int k) noexcept nogil:
    cdef int f = P.nf
    if f >= EPA_MAXF:
        return -1
    P.nf += 1
    P.fv[f][0] = i
    P.fv[f][1] = j
    P.fv[f][2] = k
    P.adj[f][0] = P.adj[f][1] = P.adj[f][2] = -1
    P.alive[f] = True
    _face_plane(P, f)
    return f


cdef void _link_new(Polytope* P, int first) noexcept nogil:
    """Adjacency among faces first..nf-1 (and towards older faces already set) by matching edges."""
    cdef int f, g, k, l, a, b
    for f in range(first, P.nf):
        for k in range(3):
            if P.adj[f][k] >= 0:
                continue
            a = P.fv[f][k]
            b = P.fv[f][(k + 1) % 3]
            for g in range(first, P.nf):
                if g == f or not P.alive[g]:
                    continue
                for l in range(3):
                    if P.fv[g][l] == b and P.fv[g][(l + 1) % 3] == a:
                        P.adj[f][k] = g
                        P.adje[f][k] = l
                        P.adj[g][l] = f
                        P.adje[g][l] = k


cdef void _silhouette(Polytope* P, int f, int e, const double* w, double eps) noexcept nogil:
    """Depth-first search from a removed face across edge e into face f."""
    cdef int k, g, ge
    if f < 0 or not P.alive[f]:
        return
    if dot3(P.n[f], w) - P.dist[f] <= eps:   # f not visible: (f, e) is a horizon edge
        if P.nh < EPA_MAXF:
            P.hf[P.nh] = f
            P.he[P.nh] = e
            P.nh += 1
        return
    P.alive[f] = False
    for k in range(1, 3):
        g = P.adj[f][(e + k) % 3]
        ge = P.adje[f][(e + k) % 3]
        if g >= 0:
            _silhouette(P, g, ge, w, eps)


cdef int _blow_up(const ShapeRef* A, const double* Ra, const double* xa,
                  const ShapeRef* B, const double* Rb, const double* xb, Simplex* S) noexcept nogil:
    """Grow a GJK simplex that ended with fewer than 4 points (origin on its boundary) to a tetrahedron."""
    cdef double d[3]
    cdef double e[3]
    cdef double u[3]
    cdef double t[3]
    cdef double a[3]
    cdef double b[3]
    cdef double w[3]
    cdef double v2[3]
    cdef double scale2 = 0.0, x, cs, sn, ang
    cdef int i, k, c, m
    for i in range(S.n):
        x = dot3(S.w[i], S.w[i])
        if x > scale2:
            scale2 = x
    if S.n == 1:
        for k in range(6):
            d[0] = d[1] = d[2] = 0.0
            d[k % 3] = 1.0 if k < 3 else -1.0
            _minkowski(A, Ra, xa, B, Rb, xb, d, a, b, w)
            sub3(w, S.w[0], e)
            x = dot3(w, w)
            if x > scale2:
                scale2 = x
            if dot3(e, e) > 1e-20 * scale2:
                break
        else:
            return -1
        _set_point(S, 1, w, a, b, -1, -1)
        S.n = 2
    if S.n == 2:
        sub3(S.w[1], S.w[0], e)
        x = sqrt(dot3(e, e))
        if x == 0.0:
            return -1
        e[0] /= x
        e[1] /= x
        e[2] /= x
        m = 0                          # axis least aligned with the segment
        if fabs(e[1]) < fabs(e[m]):
            m = 1
        if fabs(e[2]) < fabs(e[m]):
            m = 2
        t[0] = t[1] = t[2] = 0.0
        t[m] = 1.0
        cross3(e, t, u)
        x = sqrt(dot3(u, u))
        u[0] /= x
        u[1] /= x
        u[2] /= x
        cross3(e, u, v2)
        for k in range(6):             # directions perpendicular to the segment, 60 degrees apart
            ang = k * 1.0471975511965976
            cs = cos(ang)
            sn = sin(ang)
            for c in range(3):
                d[c] = cs * u[c] + sn * v2[c]
            _minkowski(A, Ra, xa, B, Rb, xb, d, a, b, w)
            sub3(w, S.w[0], t)
            cross3(t, e, d)
            if dot3(d, d) > 1e-20 * scale2:
                break
        else:
            return -1
        _set_point(S, 2, w, a, b, -1, -1)
        S.n = 3
    if S.n == 3:
        sub3(S.w[1], S.w[0], e)
        sub3(S.w[2], S.w[0], t)
        cross3(e, t, d)
        if dot3(d, d) == 0.0:
            return -1
        for k in range(2):
            _minkowski(A, Ra, xa, B, Rb, xb, d, a, b, w)
            sub3(w, S.w[0], t)
            x = dot3(t, d)
            if x * x > 1e-20 * scale2 * dot3(d, d):
                break
            d[0] = -d[0]
            d[1] = -d[1]
            d[2] = -d[2]
        else:
            return -1
        _set_point(S, 3, w, a, b, -1, -1)
        S.n = 4
    return 0


cdef int epa_penetration(const ShapeRef* A, const double* Ra, const double* xa,
                         const ShapeRef* B, const double* Rb, const double* xb,
                         Simplex* S, double tol, double* depth, double* normal,
                         double* pa, double* pb) noexcept nogil:
    """Penetration depth of A and B (origin inside A - B), from the GJK simplex S. normal points from B to A
    (the direction to move A by ``depth`` to separate), pa/pb the deepest points (pa - pb = -depth*normal).
    Returns the number of EPA iterations, or -1 on a degenerate start (flat Minkowski difference)."""
    cdef Polytope P
    cdef double d[3]
    cdef double a[3]
    cdef double b[3]
    cdef double w[3]
    cdef double p[3]
    cdef double e1[3]
    cdef double e2[3]
    cdef double N[3]
    cdef double l[3]
    cdef double scale, gap, best, x, NN
    cdef int i, c, f, it, k, first, nv, g, ge, ia, ib, fprev
    cdef double lprev, floor, ub
    cdef double nub[3]
    cdef double aub[3]
    cdef double bub[3]
    cdef bint converged
    if S.n < 4 and _blow_up(A, Ra, xa, B, Rb, xb, S) < 0:
        return -1
    P.nv = 4
    P.nf = 0
    scale = 0.0
    for i in range(4):
        for c in range(3):
            P.w[i][c] = S.w[i][c]
            P.a[i][c] = S.a[i][c]
            P.b[i][c] = S.b[i][c]
        x = dot3(S.w[i], S.w[i])
        if x > scale:
            scale = x
    scale = sqrt(scale)
    sub3(P.w[1], P.w[0], e1)
    sub3(P.w[2], P.w[0], e2)
    sub3(P.w[3], P.w[0], d)
    x = det3(e1, e2, d)
    if x == 0.0:
        return -1
    if x > 0.0:         # make (0, 1, 2) face away from vertex 3
        for c in range(3):
            w[c] = P.w[1][c]; P.w[1][c] = P.w[2][c]; P.w[2][c] = w[c]
            w[c] = P.a[1][c]; P.a[1][c] = P.a[2][c]; P.a[2][c] = w[c]
            w[c] = P.b[1][c]; P.b[1][c] = P.b[2][c]; P.b[2][c] = w[c]
    _add_face(&P, 0, 1, 2)
    _add_face(&P, 0, 3, 1)
    _add_face(&P, 0, 2, 3)
    _add_face(&P, 1, 3, 2)
    _link_new(&P, 0)
    it = 0
    f = 0
    fprev = -1
    ub = 1e300
    converged = False
    lprev = 0.0
    floor = EPA_FLOOR * scale
    while True:
        it += 1
        f = -1
        best = 0.0
        for i in range(P.nf):
            if P.alive[i] and (f < 0 or P.dist[i] < best):
                f = i
                best = P.dist[i]
        if f < 0 or best >= 1e299:
            return -1
        if fprev >= 0 and best < lprev - floor:    # the lower bound must not drop: round-off breakdown
            f = fprev
            best = lprev
            break
        _minkowski(A, Ra, xa, B, Rb, xb, P.n[f], a, b, w)
        x = dot3(P.n[f], w)
        if x < ub:                                  # h_M(n) >= depth for every n: keep the smallest
            ub = x
            for c in range(3):
                nub[c] = P.n[f][c]
                aub[c] = a[c]
                bub[c] = b[c]
        gap = x - best
        if gap <= tol * (best if best > 0.0 else 0.0) + floor:
            converged = True
            break
        if P.nv >= EPA_MAXV or P.nf + P.nv + 8 > EPA_MAXF:
            break
        fprev = f
        lprev = best
        nv = P.nv
        for c in range(3):
            P.w[nv][c] = w[c]
            P.a[nv][c] = a[c]
            P.b[nv][c] = b[c]
        P.nv += 1
        P.nh = 0
        P.alive[f] = False
        for k in range(3):
            _silhouette(&P, P.adj[f][k], P.adje[f][k], w, 1e-14 * scale)
        if P.nh < 3:
            break
        first = P.nf
        for k in range(P.nh):
            g = P.hf[k]
            ge = P.he[k]
            ia = P.fv[g][ge]
            ib = P.fv[g][(ge + 1) % 3]
            i = _add_face(&P, ib, ia, nv)
            if i < 0:
                return -1
            P.adj[i][0] = g
            P.adje[i][0] = ge
            P.adj[g][ge] = i
            P.adje[g][ge] = 0
        _link_new(&P, first)
        for i in range(first, P.nf):
            if P.adj[i][1] < 0 or P.adj[i][2] < 0:
                i = -1
                break
        if i < 0:                   # horizon not a simple loop (round-off): keep the current best face
            break
    if not converged and ub - best > tol * (best if best > 0.0 else 0.0) + floor:
        # stopped early (capacity on a curved body, e.g. concentric spheres; round-off): answer with the best
        # upper bound, a translation that does separate the bodies, and its support points as witnesses
        depth[0] = ub if ub > 0.0 else 0.0
        for c in range(3):                      # witnesses above each other, midway between a and b
            normal[c] = -nub[c]
            x = 0.5 * (aub[c] + bub[c])
            pa[c] = x + 0.5 * ub * nub[c]
            pb[c] = x - 0.5 * ub * nub[c]
        return it
    # witness: projection of the origin on face f, barycentric in that face
    depth[0] = best if best > 0.0 else 0.0
    for c in range(3):
        p[c] = best * P.n[f][c]
    sub3(P.w[P.fv[f][1]], P.w[P.fv[f][0]], e1)
    sub3(P.w[P.fv[f][2]], P.w[P.fv[f][0]], e2)
    cross3(e1, e2, N)
    NN = dot3(N, N)
    for k in range(3):
        sub3(P.w[P.fv[f][(k + 1) % 3]], p, e1)
        sub3(P.w[P.fv[f][(k + 2) % 3]], p, e2)
        cross3(e1, e2, d)
        l[k] = dot3(d, N) / NN
    for c in range(3):
        pa[c] = 0.0
        pb[c] = 0.0
        for k in range(3):
            pa[c] += l[k] * P.a[P.fv[f][k]][c]
            pb[c] += l[k] * P.b[P.fv[f][k]][c]
        normal[c] = -P.n[f][c]
    return it


# ---------------------------------------------------------------- distance and contact
cdef int signed_distance(const ShapeRef* A, const double* Ra, const double* xa,
                         const ShapeRef* B, const double* Rb, const double* xb,
                         double tol, double* guess, double* dist, double* pa, double* pb) noexcept nogil:
    """Signed distance of two posed bodies: > 0 apart (GJK), < 0 minus the penetration depth (EPA).
    guess (in/out) warm-starts GJK with a previous pa - pb. Returns GJK_SEPARATED, GJK_INTERSECT, or -1 if
    EPA failed (dist = 0 then)."""
    cdef Simplex S
    cdef double depth
    cdef double n[3]
    cdef int r = gjk_distance(A, Ra, xa, B, Rb, xb, tol, INFINITY, guess, &S, False, pa, pb)
    if r == GJK_SEPARATED:
        dist[0] = sqrt(dot3(guess, guess))
        return r
    if epa_penetration(A, Ra, xa, B, Rb, xb, &S, tol, &depth, n, pa, pb) < 0:
        dist[0] = 0.0
        return -1
    dist[0] = -depth
    sub3(pa, pb, guess)
    return GJK_INTERSECT


cdef inline bint _inside(const double* p0, const double* p1, const double* p2, double* lam,
                         double* v, double* u) noexcept nogil:
    """Projection of the origin on the plane of the triangle (p0, p1, p2): True, with its barycentric
    weights and the point, if it falls strictly inside a triangle that is not thin. u (if not NULL): the
    point times a positive factor, without the divisions (a support direction need not wait for them),
    and u[3] the longer edge's squared length (the triangle's scale)."""
    cdef double e1[3]
    cdef double e2[3]
    cdef double d00, d01, d11, d20, d21, den, ns, nt, s, t
    cdef int c
    sub3(p1, p0, e1)
    sub3(p2, p0, e2)
    d00 = dot3(e1, e1)
    d01 = dot3(e1, e2)
    d11 = dot3(e2, e2)
    den = d00 * d11 - d01 * d01            # |e1 x e2|^2
    if not den > 1e-6 * d00 * d11:        # thin: left to the signed-volume solver
        return False
    d20 = -dot3(p0, e1)
    d21 = -dot3(p0, e2)
    ns = d11 * d20 - d01 * d21             # s and t times den
    nt = d00 * d21 - d01 * d20
    if not (ns > 0.0 and nt > 0.0 and ns + nt < den):
        return False
    if u != NULL:
        for c in range(3):
            u[c] = den * p0[c] + ns * e1[c] + nt * e2[c]
        u[3] = d00 if d00 > d11 else d11
    t = 1.0 / den
    s = ns * t
    t = nt * t
    lam[0] = 1.0 - s - t
    lam[1] = s
    lam[2] = t
    for c in range(3):
        v[c] = p0[c] + s * e1[c] + t * e2[c]
    return True


cdef int _warm_triangle(const ShapeRef* A, const double* Ra, const double* xa,
                        const ShapeRef* B, const double* Rb, const double* xb, double tol, double sep,
                        Simplex* S, double* v, double* pa, double* pb) noexcept nogil:
    """GJK for the common case of a lasting contact between polytopes, in straight-line code: the closest
    point stays inside a triangle. The stored triangle is checked by one support query; when the gap stays
    open (the touching vertex changed), the new point w and two old ones make the next triangle: the face of
    the tetrahedron that the origin sees and on which it projects inside holds its closest point. Returns
    GJK_SEPARATED (v = pa - pb, as gjk_distance), or -1 with S ready for gjk_distance(warm): the current
    triangle, plus the last support point if the gap was open."""
    cdef double d[3]
    cdef double a[3]
    cdef double b[3]
    cdef double w[3]
    cdef double n[3]
    cdef double e1[3]
    cdef double e2[3]
    cdef double lam[3]
    cdef double vn[3]
    cdef double vv, vw, maxw2
    cdef int c, ia, ib, it, e, i, j, k
    if not _inside(S.w[0], S.w[1], S.w[2], S.lam, v, NULL):
        return -1
    maxw2 = 0.0
    for k in range(3):
        vv = dot3(S.w[k], S.w[k])
        if vv > maxw2:
            maxw2 = vv
    for it in range(4):
        vv = dot3(v, v)
        if vv <= EPS_ZERO * maxw2:
            return -1
        for c in range(3):
            d[c] = -v[c]
        _minkowski_id(A, Ra, xa, B, Rb, xb, d, a, b, w, &ia, &ib)
        vw = dot3(v, w)
        if vv - vw <= tol * vv or (vw > 0.0 and vw * vw >= sep * sep * vv):   # converged, or >= sep apart
            _witness(S, pa, pb)
            sub3(pa, pb, v)
            return GJK_SEPARATED
        vw = dot3(w, w)
        if vw > maxw2:
            maxw2 = vw
        for e in range(3):             # faces (w, S_i, S_j) of the tetrahedron, S_k opposite
            i = e
            j = (e + 1) % 3
            k = (e + 2) % 3
            sub3(S.w[i], w, e1)
            sub3(S.w[j], w, e2)
            cross3(e1, e2, n)
            sub3(S.w[k], w, e1)
            if dot3(n, e1) > 0.0:       # outward normal: away from S_k
                n[0] = -n[0]
                n[1] = -n[1]
                n[2] = -n[2]
            if -dot3(n, w) <= 0.0:      # the origin does not see this face
                continue
            if _inside(S.w[i], S.w[j], w, lam, vn, NULL):
                break
        else:
            _set_point(S, 3, w, a, b, ia, ib)
            S.n = 4
            return -1
        if dot3(vn, vn) >= vv:          # no progress (round-off): the general loop decides
            _set_point(S, 3, w, a, b, ia, ib)
            S.n = 4
            return -1
        _set_point(S, k, w, a, b, ia, ib)     # new triangle (S_i, S_j, w): w replaces S_k
        S.lam[i] = lam[0]
        S.lam[j] = lam[1]
        S.lam[k] = lam[2]
        for c in range(3):
            v[c] = vn[c]
    return -1


# Warm start of a lasting contact: the last separated simplex, kept in NFEAT values per pair. Between two
# polytopes, its vertex pairs: feat[2k] = ia + 1, feat[2k + 1] = ib + 1 (0: none). Otherwise (a
# curved or rounded body), its points in the two body frames: feat[6k:6k+3] on A, feat[6k+3:6k+6] on B
# (unscaled shape coordinates; both zero: none). Re-posed, these are points of the bodies (body-fixed) near
# the new closest points: a lasting contact starts from a simplex that already surrounds them. (Support
# directions would not do: on a flat cap or along a cylinder's side the support jumps with the direction.)
WARM_START_VALUES = NFEAT               # (for Python callers of contact_batch)


cdef inline void _body_point(const double* R, const double* x, const double* p, double* q) noexcept nogil:
    """q = R^-1 (p - x) for R = scale x rotation: R^T (p - x) / scale^2."""
    cdef double r[3]
    cdef double s = 1.0 / (R[0] * R[0] + R[3] * R[3] + R[6] * R[6])
    sub3(p, x, r)
    q[0] = (R[0] * r[0] + R[3] * r[1] + R[6] * r[2]) * s
    q[1] = (R[1] * r[0] + R[4] * r[1] + R[7] * r[2]) * s
    q[2] = (R[2] * r[0] + R[5] * r[1] + R[8] * r[2]) * s


cdef bint _load_features(const ShapeRef* A, const double* Ra, const double* xa,
                         const ShapeRef* B, const double* Rb, const double* xb,
                         const double* feat, bint polytopes, Simplex* S) noexcept nogil:
    """The stored simplex at the current poses; False if there is none."""
    cdef int k, ia, ib
    cdef const double* q
    S.n = 0
    for k in range(3):
        if polytopes:
            if feat[2 * k] <= 0.0:
                break
            ia = <int>feat[2 * k] - 1
            ib = <int>feat[2 * k + 1] - 1
            if not vertex_world(A, Ra, xa, ia, S.a[k]) or not vertex_world(B, Rb, xb, ib, S.b[k]):
                S.n = 0
                return False
            S.fa[k] = ia
            S.fb[k] = ib
        else:
            q = &feat[6 * k]
            if q[0] == 0.0 and q[1] == 0.0 and q[2] == 0.0 and q[3] == 0.0 and q[4] == 0.0 and q[5] == 0.0:
                break
            posed_point(Ra, xa, q, S.a[k])
            posed_point(Rb, xb, &q[3], S.b[k])
            S.fa[k] = S.fb[k] = -1
        sub3(S.a[k], S.b[k], S.w[k])
        S.n = k + 1
    return S.n > 0


cdef int _warm_corners(const ShapeRef* A, const double* Ra, const double* xa,
                       const ShapeRef* B, const double* Rb, const double* xb, double tol, double sep,
                       const double* feat, Simplex* S, double* v, double* pa, double* pb) noexcept nogil:
    """The usual call of a lasting contact between two boxes posed as corners (ShapeRef.corners), three
    stored vertex pairs, in straight-line code: the stored triangle, its closest point, one support query.
    Returns GJK_SEPARATED (converged on the stored triangle: v = pa - pb as gjk_distance, the features stay
    as they are), -1 (S holds the stored triangle: _warm_triangle goes on), or -2 (no usable features)."""
    cdef double w[3]
    cdef double d[4]
    cdef double vv, vw
    cdef const double* ca
    cdef const double* cb
    cdef int k, c, ia, ib
    for k in range(3):
        ia = <int>feat[2 * k] - 1
        ib = <int>feat[2 * k + 1] - 1
        if <unsigned int>ia > 7 or <unsigned int>ib > 7:      # (none, or made for other shapes)
            S.n = 0
            return -2
        ca = &A.corners[3 * ia]
        cb = &B.corners[3 * ib]
        for c in range(3):
            S.a[k][c] = ca[c]
            S.b[k][c] = cb[c]
            S.w[k][c] = ca[c] - cb[c]
        S.fa[k] = ia
        S.fb[k] = ib
    S.n = 3
    if not _inside(S.w[0], S.w[1], S.w[2], S.lam, v, d):
        return -1
    vv = dot3(v, v)
    if vv <= EPS_ZERO * d[3]:        # the origin on the triangle (to round-off): the general path decides
        return -1
    cb = &B.corners[3 * box_support_id(Rb, d)]       # supports along v (B) and -v (A): d is v scaled
    for c in range(3):
        d[c] = -d[c]
    ca = &A.corners[3 * box_support_id(Ra, d)]
    for c in range(3):
        w[c] = ca[c] - cb[c]
    vw = dot3(v, w)
    if vv - vw <= tol * vv or (vw > 0.0 and vw * vw >= sep * sep * vv):   # as _warm_triangle
        _witness(S, pa, pb)
        sub3(pa, pb, v)
        return GJK_SEPARATED
    return -1


cdef void _store_features(const Simplex* S, bint separated, bint polytopes, const double* Ra, const double* xa,
                          const double* Rb, const double* xb, double* feat) noexcept nogil:
    cdef int k
    if polytopes:
        for k in range(6):
            feat[k] = 0.0
        if not separated or S.n > 3:
            return
        for k in range(S.n):
            if S.fa[k] < 0 or S.fb[k] < 0:
                break
        else:
            for k in range(S.n):
                feat[2 * k] = S.fa[k] + 1.0
                feat[2 * k + 1] = S.fb[k] + 1.0
        return
    for k in range(NFEAT):
        feat[k] = 0.0
    if not separated or S.n > 3:
        return
    for k in range(S.n):
        _body_point(Ra, xa, S.a[k], &feat[6 * k])
        _body_point(Rb, xb, S.b[k], &feat[6 * k + 3])


cdef int crust_contact(const ShapeRef* Acore, double crust_a, const double* Ra, const double* xa,
                       const ShapeRef* Bcore, double crust_b, const double* Rb, const double* xb,
                       double tol, double* guess, double* feat, double* overlap, double* normal,
                       double* point) noexcept nogil:
    """Grains3D contact of the rounded bodies core (+) ball(crust). Returns CONTACT_NONE (outputs untouched
    except guess and feat), CONTACT_CRUST, CONTACT_EPA or CONTACT_FALLBACK. overlap > 0, normal unit from B to
    A, point midway between the two swollen surfaces along the normal. Warm start (in/out): guess, the last
    core separation; feat (NFEAT values, or NULL), the last separated GJK simplex (see _load_features)."""
    cdef Simplex S
    cdef double pa[3]
    cdef double pb[3]
    cdef double d, depth, h, csum = crust_a + crust_b
    cdef int c, code
    cdef bint polytopes = True
    cdef bint warm
    cdef int r = -1
    if feat != NULL and Acore.corners != NULL and Bcore.corners != NULL and feat[4] > 0.0:   # two boxes
        r = _warm_corners(Acore, Ra, xa, Bcore, Rb, xb, tol, csum, feat, &S, guess, pa, pb)
        if r == GJK_SEPARATED:
            feat = NULL                  # (kept as they are)
        warm = r == -1
    else:
        polytopes = (polytope_core(Acore.kind, Acore.params[MARGIN])
                     and polytope_core(Bcore.kind, Bcore.params[MARGIN]))
        warm = feat != NULL and _load_features(Acore, Ra, xa, Bcore, Rb, xb, feat, polytopes, &S)
    if warm and S.n == 3:
        r = _warm_triangle(Acore, Ra, xa, Bcore, Rb, xb, tol, csum, &S, guess, pa, pb)
    if r < 0:
        r = gjk_distance(Acore, Ra, xa, Bcore, Rb, xb, tol, csum, guess, &S, warm, pa, pb)
    if feat != NULL:
        _store_features(&S, r == GJK_SEPARATED, polytopes, Ra, xa, Rb, xb, feat)
    if r == GJK_SEPARATED:
        d = sqrt(dot3(guess, guess))
        if d >= csum:
            return CONTACT_NONE
        if d > 0.0:
            for c in range(3):
                normal[c] = guess[c] * (1.0 / d)
            depth = -d
            code = CONTACT_CRUST
        else:
            r = GJK_INTERSECT
    if r != GJK_SEPARATED:
        code = CONTACT_EPA
        if epa_penetration(Acore, Ra, xa, Bcore, Rb, xb, &S, tol, &depth, normal, pa, pb) < 0:
            code = CONTACT_FALLBACK      # degenerate cores: push along the centres
            depth = 0.0
            sub3(xa, xb, normal)
            d = sqrt(dot3(normal, normal))
            if d == 0.0:
                normal[0] = 1.0
                normal[1] = normal[2] = 0.0
            else:
                for c in range(3):
                    normal[c] /= d
            for c in range(3):
                pa[c] = pb[c] = 0.5 * (xa[c] + xb[c])
        sub3(pa, pb, guess)
    overlap[0] = csum + depth
    h = 0.5 * (crust_b - crust_a)
    for c in range(3):
        point[c] = 0.5 * (pa[c] + pb[c]) + h * normal[c]
    return code


# ---------------------------------------------------------------- Python entry points
cdef void _pose_pair(const double[::1] qa, double* Ra, const double[::1] qb, double* Rb, guess, double* g):
    """Rotations of a single-pair query and the warm start (zero without a guess)."""
    quat_to_rot(&qa[0], Ra)
    quat_to_rot(&qb[0], Rb)
    g[0] = g[1] = g[2] = 0.0
    if guess is not None:
        g[0], g[1], g[2] = guess[0], guess[1], guess[2]


def pair_distance(ShapeView pair, const double[::1] xa, const double[::1] qa, const double[::1] xb,
                  const double[::1] qb, double tol=1e-10, guess=None):
    """Signed distance of the bodies of rows 0 and 1 of a table, posed: (dist, point_a, point_b, status);
    dist < 0 is -penetration."""
    cdef ShapeRef A, B
    cdef double Ra[9]
    cdef double Rb[9]
    cdef double g[3]
    cdef double d = 0.0
    cdef int r
    cdef cnp.ndarray[double, ndim=1] pa = np.zeros(3), pb = np.zeros(3)
    body_ref(&pair.t, 0, &A)
    body_ref(&pair.t, 1, &B)
    _pose_pair(qa, Ra, qb, Rb, guess, g)
    with nogil:
        r = signed_distance(&A, Ra, &xa[0], &B, Rb, &xb[0], tol, g, &d, <double*>pa.data, <double*>pb.data)
    return d, pa, pb, r


def pair_contact(ShapeView pair, const double[::1] xa, const double[::1] qa, const double[::1] xb,
                 const double[::1] qb, double tol=1e-10, guess=None):
    """Crust contact of the cores of rows 0 and 1 of a table, posed: (code, overlap, normal, point); code 0
    means no contact."""
    cdef ShapeRef A, B
    cdef double Ra[9]
    cdef double Rb[9]
    cdef double g[3]
    cdef double ov = 0.0
    cdef int r
    cdef cnp.ndarray[double, ndim=1] n = np.zeros(3), p = np.zeros(3)
    core_ref(&pair.t, 0, &A)
    core_ref(&pair.t, 1, &B)
    _pose_pair(qa, Ra, qb, Rb, guess, g)
    with nogil:
        r = crust_contact(&A, pair.t.crust[0], Ra, &xa[0], &B, pair.t.crust[1], Rb, &xb[0], tol, g, NULL, &ov,
                          <double*>n.data, <double*>p.data)
    return r, ov, n, p


def contact_batch(ShapeView shapes, const int[::1] shape, const double[:, ::1] x, const double[:, ::1] quat,
                  const int[::1] pi, const int[::1] pj, double tol, double[:, ::1] guess, int[::1] code,
                  double[::1] overlap, double[:, ::1] normal, double[:, ::1] point, double[:, ::1] feat=None,
                  bint corners=False):
    """Crust contacts of the pairs (pi[k], pj[k]) of particles with shapes shape[i] (rows of a ShapeTable,
    at scale 1: the cores and crusts of the table): the nogil batch loop a pair style runs. guess[k] (and
    feat[k], NFEAT values, if given) warm-start pair k. corners: box cores posed as their corners, as pair
    convex/gjk poses them. Returns the contact count."""
    cdef TableView table = shapes.t
    cdef const TableView* T = &table
    cdef Py_ssize_t k, m = pi.shape[0]
    cdef int i, j, si, sj, nc = 0
    cdef ShapeRef A, B
    cdef double Ra[9]
    cdef double Rb[9]
    cdef double ca[NCORNER]
    cdef double cb[NCORNER]
    cdef double* fp = NULL
    if feat is not None and (feat.shape[0] < m or feat.shape[1] != NFEAT):
        raise ValueError(f"feat must have shape (len(pi), {NFEAT})")
    with nogil:
        for k in range(m):
            i = pi[k]
            j = pj[k]
            si = shape[i]
            sj = shape[j]
            core_ref(T, si, &A)
            core_ref(T, sj, &B)
            quat_to_rot(&quat[i, 0], Ra)
            quat_to_rot(&quat[j, 0], Rb)
            if corners and corner_box(A.kind, A.params[MARGIN]):
                box_corners(Ra, &x[i, 0], A.params, ca)
                A.corners = ca
            if corners and corner_box(B.kind, B.params[MARGIN]):
                box_corners(Rb, &x[j, 0], B.params, cb)
                B.corners = cb
            if feat is not None:
                fp = &feat[k, 0]
            code[k] = crust_contact(&A, T.crust[si], Ra, &x[i, 0], &B, T.crust[sj], Rb, &x[j, 0], tol,
                                    &guess[k, 0], fp, &overlap[k], &normal[k, 0], &point[k, 0])
            if code[k] != CONTACT_NONE:
                nc += 1
    return nc


def distance_batch(ShapeView shapes, const int[::1] shape, const double[:, ::1] x, const double[:, ::1] quat,
                   const int[::1] pi, const int[::1] pj, double tol, double[:, ::1] guess, double[::1] dist,
                   double[:, ::1] pa, double[:, ::1] pb):
    """Signed distances of the true bodies (rows of a ShapeTable, scale 1) for the pairs (pi[k], pj[k]);
    nogil loop. Returns 0."""
    cdef TableView table = shapes.t
    cdef const TableView* T = &table
    cdef Py_ssize_t k, m = pi.shape[0]
    cdef int i, j
    cdef ShapeRef A, B
    cdef double Ra[9]
    cdef double Rb[9]
    with nogil:
        for k in range(m):
            i = pi[k]
            j = pj[k]
            body_ref(T, shape[i], &A)
            body_ref(T, shape[j], &B)
            quat_to_rot(&quat[i, 0], Ra)
            quat_to_rot(&quat[j, 0], Rb)
            signed_distance(&A, Ra, &x[i, 0], &B, Rb, &x[j, 0], tol, &guess[k, 0], &dist[k],
                            &pa[k, 0], &pb[k, 0])
    return 0
