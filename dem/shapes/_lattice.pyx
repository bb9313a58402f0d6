# cython: language_level=3, boundscheck=False, wraparound=False, cdivision=True, initializedcheck=False
"""Structured-lattice integration over a union of posed convex components (Grains3D Part III sec 2.3).

Point-in-body tests
-------------------
Each kind has a *gauge* g(p) of a body-frame point p, convex in p, with p inside the body iff g(p) <= 0
(the same inequalities as dem/shapes/primitives.py; polyhedra by their face half-spaces):

  SPHERE        |p|^2 - r^2
  BOX           max_i |p_i| - h_i
  CYLINDER      max((x^2 + y^2)/r^2 - 1, |z|/hh - 1)
  CONE          max(rho/r - (za - z)/H, (zb - z)/H)               H = za - zb, rho = sqrt(x^2 + y^2)
  ELLIPSOID     (x/a)^2 + (y/b)^2 + (z/c)^2 - 1
  SUPERQUADRIC  (|x/a|^n2 + |y/b|^n2)^(n1/n2) + |z/c|^n1 - 1
  POLYHEDRON    max_f n_f . p + off_f                              (unit outward normals)

The lattice
-----------
Cell centres of the box [lo, hi] cut into n = (nx, ny, nz) cells: X_ijk = lo + (ijk + 1/2) h, h = (hi - lo)/n.
A cell counts when its centre is inside ANY component. The kernels return the raw sums, relative to a
reference point c0 (the box centre: keeps second moments free of cancellation),

  [N, sum X, sum Y, sum Z, sum XX, sum YY, sum ZZ, sum XY, sum XZ, sum YZ]       (X = x - c0)

over the x-slabs i in [start, stop) (MPI ranks split them; the sums of the shares are the full sums).

Two kernels give identical counts:

* ``lattice_sums`` (method "rows"): a lattice row (i, j fixed, k along z) meets a convex component in an
  interval of k. Per row and component: reject by the component's frame bounding box, clip the row to its
  body-frame bounding box, find an inside point by a ternary search on the convex g(k) (stopped at the first
  g <= 0), then the two ends by bisection: O(log nz) point tests per row and component instead of nz.
  The union of the intervals of one row is merged and summed in closed form:
  sum_{k=a}^{b-1} (k+1/2) = (b^2 - a^2)/2, sum_{k=a}^{b-1} (k+1/2)^2 = (b^3 - a^3)/3 - (b - a)/12.
* ``lattice_sums_points`` (method "points"): the plain point-by-point count (same row rejection), the
  reference the row kernel is checked against.

Every point test evaluates the same expression of (i, j, k), so both kernels see the same indicator.
"""
import numpy as np
cimport numpy as cnp
from libc.math cimport sqrt, pow, fabs, ceil, floor, INFINITY
from libc.stdlib cimport malloc, free

from ._support cimport POLYHEDRON, NPARAM
from ._gauge cimport gauge

NSUMS = 10


cdef struct Comp:
    int kind
    const double* p          # params[NPARAM]
    const double* R          # body -> frame, row major
    const double* off        # centre of mass in the frame
    const double* planes     # polyhedron: nplanes rows (nx, ny, nz, off)
    int nplanes
    double flo[3]            # frame bounding box
    double fhi[3]
    double blo[3]            # body-frame bounding box
    double bhi[3]


cdef inline double comp_gauge(const Comp* c, double x, double y, double z) noexcept nogil:
    """Gauge of the frame point (x, y, z) for component c (body point = R^T (X - off))."""
    cdef double dx = x - c.off[0], dy = y - c.off[1], dz = z - c.off[2]
    cdef const double* R = c.R
    return gauge(c.kind, c.p, c.planes, c.nplanes,
                 R[0] * dx + R[3] * dy + R[6] * dz,
                 R[1] * dx + R[4] * dy + R[7] * dz,
                 R[2] * dx + R[5] * dy + R[8] * dz)


cdef inline bint row_range(const Comp* c, double x, double y, double z0, double hz, int nz,
                           int* kmin, int* kmax) noexcept nogil:
    """Range [kmin, kmax] of the row (x, y, z0 + (k + 1/2) hz) inside c's bounding boxes; False if empty."""
    cdef double b0[3]
    cdef double d[3]
    cdef double tmin = 0.0, tmax = nz - 1.0, t0, t1, tt
    cdef double dx, dy, dz
    cdef const double* R = c.R
    cdef int a
    if x < c.flo[0] or x > c.fhi[0] or y < c.flo[1] or y > c.fhi[1]:
        return False
    # frame z slab
    t0 = (c.flo[2] - z0) / hz - 0.5
    t1 = (c.fhi[2] - z0) / hz - 0.5
    if t0 > tmin:
        tmin = t0
    if t1 < tmax:
        tmax = t1
    # body slabs: body point = b0 + t d
    dx = x - c.off[0]
    dy = y - c.off[1]
    dz = z0 + 0.5 * hz - c.off[2]
    for a in range(3):
        b0[a] = R[a] * dx + R[3 + a] * dy + R[6 + a] * dz
        d[a] = R[6 + a] * hz
        if fabs(d[a]) < 1e-300:
            if b0[a] < c.blo[a] or b0[a] > c.bhi[a]:
                return False
        else:
            t0 = (c.blo[a] - b0[a]) / d[a]
            t1 = (c.bhi[a] - b0[a]) / d[a]
            if t0 > t1:
                tt = t0
                t0 = t1
                t1 = tt
            if t0 > tmin:
                tmin = t0
            if t1 < tmax:
                tmax = t1
    if tmin > tmax:
        return False
    kmin[0] = <int>ceil(tmin - 1e-9)       # the boxes are padded: a safe (wider) range is enough
    kmax[0] = <int>floor(tmax + 1e-9)
    if kmin[0] < 0:
        kmin[0] = 0
    if kmax[0] > nz - 1:
        kmax[0] = nz - 1
    return kmin[0] <= kmax[0]


cdef inline double zk(double z0, double hz, int k) noexcept nogil:
    return z0 + (k + 0.5) * hz


cdef bint row_interval(const Comp* c, double x, double y, double z0, double hz, int kmin, int kmax,
                       int* a_out, int* b_out) noexcept nogil:
    """The inside cells [a, b] of row (x, y) in [kmin, kmax] (an interval: c is convex); False if none."""
    cdef int lo = kmin, hi = kmax, m1, m2, kin = -1, a, b, m
    cdef double g1, g2
    # an inside point: ternary search on the convex g(k), stopped at the first g <= 0
    while hi - lo > 2:
        m1 = lo + (hi - lo) // 3
        m2 = hi - (hi - lo) // 3
        g1 = comp_gauge(c, x, y, zk(z0, hz, m1))
        if g1 <= 0.0:
            kin = m1
            break
        g2 = comp_gauge(c, x, y, zk(z0, hz, m2))
        if g2 <= 0.0:
            kin = m2
            break
        if g1 < g2:
            hi = m2 - 1
        elif g1 > g2:
            lo = m1 + 1
        else:
            lo = m1
            hi = m2
    if kin < 0:
        for m in range(lo, hi + 1):
            if comp_gauge(c, x, y, zk(z0, hz, m)) <= 0.0:
                kin = m
                break
        if kin < 0:
            return False
    # first inside in [kmin, kin]: g(kin) <= 0, bisection on the inside suffix
    a = kmin
    b = kin
    while a < b:
        m = (a + b) // 2
        if comp_gauge(c, x, y, zk(z0, hz, m)) <= 0.0:
            b = m
        else:
            a = m + 1
    a_out[0] = a
    # last inside in [kin, kmax]
    a = kin
    b = kmax
    while a < b:
        m = (a + b + 1) // 2
        if comp_gauge(c, x, y, zk(z0, hz, m)) <= 0.0:
            a = m
        else:
            b = m - 1
    b_out[0] = a
    return True


cdef int setup_comps(Comp* comps, int K, const int[::1] kinds, const double[:, ::1] params,
                     const double[:, :, ::1] rot, const double[:, ::1] off, const double[:, ::1] planes,
                     const long[::1] plane_start, const double[:, ::1] fbox,
                     const double[:, ::1] bbox) except -1:
    cdef int c, a
    for c in range(K):
        comps[c].kind = kinds[c]
        comps[c].p = &params[c, 0]
        comps[c].R = &rot[c, 0, 0]
        comps[c].off = &off[c, 0]
        comps[c].nplanes = <int>(plane_start[c + 1] - plane_start[c])
        if kinds[c] == POLYHEDRON:
            if comps[c].nplanes < 4:
                raise ValueError("a polyhedron component needs its face planes")
            comps[c].planes = &planes[plane_start[c], 0]
        else:
            comps[c].planes = NULL
        for a in range(3):
            comps[c].flo[a] = fbox[c, a]
            comps[c].fhi[a] = fbox[c, 3 + a]
            comps[c].blo[a] = bbox[c, a]
            comps[c].bhi[a] = bbox[c, 3 + a]
    return 0


def _check(kinds, params, rot, off, plane_start, fbox, bbox, n, start, stop):
    K = len(kinds)
    if params.shape[0] != K or params.shape[1] < NPARAM or rot.shape[0] != K or off.shape[0] != K \
            or plane_start.shape[0] != K + 1 or fbox.shape[0] != K or bbox.shape[0] != K:
        raise ValueError("lattice: component arrays of inconsistent lengths")
    if min(n) < 1:
        raise ValueError("lattice: at least one cell per direction")
    if not 0 <= start <= stop <= n[0]:
        raise ValueError("lattice: x-slabs [%d, %d) outside [0, %d)" % (start, stop, n[0]))


def lattice_sums(const int[::1] kinds, const double[:, ::1] params, const double[:, :, ::1] rot,
                 const double[:, ::1] off, const double[:, ::1] planes, const long[::1] plane_start,
                 const double[:, ::1] fbox, const double[:, ::1] bbox, lo, hi, n, centre,
                 int start=0, int stop=-1):
    """Sums over the cells of x-slabs [start, stop) (stop -1: nx) whose centre is inside any component, by
    row intervals. Components: kinds (K,), params (K, NPARAM), rot (K, 3, 3) body -> frame, off (K, 3),
    planes (P, 4) with component c's rows plane_start[c]:plane_start[c+1], fbox (K, 6) frame bounding boxes
    (lo, hi), bbox (K, 6) body-frame bounding boxes (both padded). Returns float64[10] (module doc)."""
    cdef int K = kinds.shape[0]
    cdef int nx = int(n[0]), ny = int(n[1]), nz = int(n[2])
    if stop < 0:
        stop = nx
    _check(kinds, params, rot, off, plane_start, fbox, bbox, (nx, ny, nz), start, stop)
    cdef double hx = (float(hi[0]) - float(lo[0])) / nx, hy = (float(hi[1]) - float(lo[1])) / ny
    cdef double hz = (float(hi[2]) - float(lo[2])) / nz
    cdef double x0 = float(lo[0]), y0 = float(lo[1]), z0 = float(lo[2])
    cdef double cx = float(centre[0]), cy = float(centre[1]), cz = float(centre[2])
    cdef Comp* comps = <Comp*>malloc(max(K, 1) * sizeof(Comp))
    cdef int* ia = <int*>malloc(max(K, 1) * sizeof(int))
    cdef int* ib = <int*>malloc(max(K, 1) * sizeof(int))
    cdef double S[10]
    cdef int i, j, c, m, q, ta, tb, kmin, kmax, ka, kb, cura, curb
    cdef double x, y, X, Y, zr, rn, rk, rkk, fa, fb
    cdef long long count = 0
    for q in range(10):
        S[q] = 0.0
    try:
        setup_comps(comps, K, kinds, params, rot, off, planes, plane_start, fbox, bbox)
        zr = z0 - cz              # Z_k = zr + (k + 1/2) hz
        with nogil:
            for i in range(start, stop):
                x = x0 + (i + 0.5) * hx
                X = x - cx
                for j in range(ny):
                    y = y0 + (j + 0.5) * hy
                    Y = y - cy
                    m = 0
                    for c in range(K):
                        if not row_range(&comps[c], x, y, z0, hz, nz, &kmin, &kmax):
                            continue
                        if not row_interval(&comps[c], x, y, z0, hz, kmin, kmax, &ka, &kb):
                            continue
                        # insertion by start (K is small)
                        q = m
                        while q > 0 and ia[q - 1] > ka:
                            ia[q] = ia[q - 1]
                            ib[q] = ib[q - 1]
                            q -= 1
                        ia[q] = ka
                        ib[q] = kb + 1        # half open
                        m += 1
                    if m == 0:
                        continue
                    # merge and sum: rn = cells, rk = sum (k + 1/2), rkk = sum (k + 1/2)^2
                    rn = 0.0
                    rk = 0.0
                    rkk = 0.0
                    cura = ia[0]
                    curb = ib[0]
                    for q in range(1, m + 1):
                        if q < m and ia[q] <= curb:
                            if ib[q] > curb:
                                curb = ib[q]
                            continue
                        fa = cura
                        fb = curb
                        rn += fb - fa
                        rk += 0.5 * (fb * fb - fa * fa)
                        rkk += (fb * fb * fb - fa * fa * fa) / 3.0 - (fb - fa) / 12.0
                        count += curb - cura
                        if q < m:
                            cura = ia[q]
                            curb = ib[q]
                    # Z sums of the row: sum Z = rn zr + hz rk, sum Z^2 = rn zr^2 + 2 zr hz rk + hz^2 rkk
                    S[1] += rn * X
                    S[2] += rn * Y
                    S[3] += rn * zr + hz * rk
                    S[4] += rn * X * X
                    S[5] += rn * Y * Y
                    S[6] += rn * zr * zr + 2.0 * zr * hz * rk + hz * hz * rkk
                    S[7] += rn * X * Y
                    S[8] += X * (rn * zr + hz * rk)
                    S[9] += Y * (rn * zr + hz * rk)
    finally:
        free(comps)
        free(ia)
        free(ib)
    out = np.empty(10)
    out[0] = count
    for q in range(1, 10):
        out[q] = S[q]
    return out


def lattice_sums_points(const int[::1] kinds, const double[:, ::1] params, const double[:, :, ::1] rot,
                        const double[:, ::1] off, const double[:, ::1] planes, const long[::1] plane_start,
                        const double[:, ::1] fbox, const double[:, ::1] bbox, lo, hi, n, centre,
                        int start=0, int stop=-1):
    """``lattice_sums`` by testing every cell centre (rows still rejected per component by its bounding
    boxes): the reference for the row kernel, same arguments and result."""
    cdef int K = kinds.shape[0]
    cdef int nx = int(n[0]), ny = int(n[1]), nz = int(n[2])
    if stop < 0:
        stop = nx
    _check(kinds, params, rot, off, plane_start, fbox, bbox, (nx, ny, nz), start, stop)
    cdef double hx = (float(hi[0]) - float(lo[0])) / nx, hy = (float(hi[1]) - float(lo[1])) / ny
    cdef double hz = (float(hi[2]) - float(lo[2])) / nz
    cdef double x0 = float(lo[0]), y0 = float(lo[1]), z0 = float(lo[2])
    cdef double cx = float(centre[0]), cy = float(centre[1]), cz = float(centre[2])
    cdef Comp* comps = <Comp*>malloc(max(K, 1) * sizeof(Comp))
    cdef int* cand = <int*>malloc(max(K, 1) * sizeof(int))
    cdef int* ka = <int*>malloc(max(K, 1) * sizeof(int))
    cdef int* kb = <int*>malloc(max(K, 1) * sizeof(int))
    cdef double S[10]
    cdef int i, j, k, c, m, q, kmin, kmax
    cdef double x, y, z, X, Y, Z
    cdef long long count = 0
    for q in range(10):
        S[q] = 0.0
    try:
        setup_comps(comps, K, kinds, params, rot, off, planes, plane_start, fbox, bbox)
        with nogil:
            for i in range(start, stop):
                x = x0 + (i + 0.5) * hx
                X = x - cx
                for j in range(ny):
                    y = y0 + (j + 0.5) * hy
                    Y = y - cy
                    m = 0
                    for c in range(K):
                        if row_range(&comps[c], x, y, z0, hz, nz, &kmin, &kmax):
                            cand[m] = c
                            ka[m] = kmin
                            kb[m] = kmax
                            m += 1
                    if m == 0:
                        continue
                    for k in range(nz):
                        z = zk(z0, hz, k)
                        for q in range(m):
                            if ka[q] <= k <= kb[q] and comp_gauge(&comps[cand[q]], x, y, z) <= 0.0:
                                Z = z - cz
                                count += 1
                                S[1] += X
                                S[2] += Y
                                S[3] += Z
                                S[4] += X * X
                                S[5] += Y * Y
                                S[6] += Z * Z
                                S[7] += X * Y
                                S[8] += X * Z
                                S[9] += Y * Z
                                break
    finally:
        free(comps)
        free(cand)
        free(ka)
        free(kb)
    out = np.empty(10)
    out[0] = count
    for q in range(1, 10):
        out[q] = S[q]
    return out


def inside(int kind, const double[::1] params, const double[:, ::1] planes, const double[:, ::1] points):
    """Point-in-body tests of body-frame points (n, 3) for one shape (planes (P, 4) for a polyhedron):
    bool array (n,)."""
    cdef Py_ssize_t i, n = points.shape[0]
    cdef int nplanes = planes.shape[0]
    cdef const double* pl = &planes[0, 0] if nplanes > 0 else NULL
    if params.shape[0] < NPARAM:
        raise ValueError("params needs NPARAM values")
    if kind == POLYHEDRON and nplanes < 4:
        raise ValueError("a polyhedron needs its face planes")
    out = np.zeros(n, dtype=bool)
    cdef cnp.npy_bool[::1] o = out
    with nogil:
        for i in range(n):
            o[i] = gauge(kind, &params[0], pl, nplanes, points[i, 0], points[i, 1], points[i, 2]) <= 0.0
    return out
