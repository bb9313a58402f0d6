# cython: language_level=3, boundscheck=False, wraparound=False, cdivision=True, initializedcheck=False
"""Support functions s(d) = argmax_{p in shape} d.p in the body frame, for every shape kind.

The direction d need not be unit length. A zero direction returns some boundary point. Parameter
layouts (params[0:7]; params[MARGIN] is an erosion by a ball, see _support.pxd):

  SPHERE        r
  BOX           hx, hy, hz                 (half edge lengths)
  CYLINDER      r, hh                      (axis z, half length)
  CONE          r, zb, za                  (axis z, base disc at z=zb, apex at z=za)
  ELLIPSOID     a, b, c                    (semi-axes)
  SUPERQUADRIC  a, b, c, n1, n2            (|x/a|^n2 + |y/b|^n2)^(n1/n2) + |z/c|^n1 <= 1, n1, n2 >= 2
  POLYHEDRON    (none; verts, nverts)      brute force over the hull vertices
"""
import numpy as np
cimport numpy as cnp
from libc.math cimport sqrt, pow, fabs, copysign, signbit

LAYOUT = {"NPARAM": NPARAM, "MARGIN": MARGIN}     # the enum of _support.pxd, for Python


cdef inline double _sgn1(double x) noexcept nogil:
    # sign with sgn(0) = +1: a zero component of d still picks a boundary point
    return -1.0 if x < 0.0 else 1.0


cdef inline void _superquadric(const double* p, const double* d, double* out) noexcept nogil:
    # Lagrange conditions reduce the two-exponent body to a superellipse of exponent n1 in the variables
    # (rho, w), rho = (|x/a|^n2 + |y/b|^n2)^(1/n2), seen along the direction (||(A, B)||_q2, C) with
    # A = a|dx|, B = b|dy|, C = c|dz| and q = n/(n-1) the conjugate exponents (Hoelder's equality case).
    cdef double a = p[0], b = p[1], c = p[2], n1 = p[3], n2 = p[4]
    cdef double A = a * fabs(d[0]), B = b * fabs(d[1]), C = c * fabs(d[2])
    cdef double m = A
    if B > m:
        m = B
    if C > m:
        m = C
    if m <= 0.0:
        out[0] = a
        out[1] = 0.0
        out[2] = 0.0
        return
    A /= m    # normalised so that the large powers below cannot overflow
    B /= m
    C /= m
    cdef double q1m = 1.0 / (n1 - 1.0), q2m = 1.0 / (n2 - 1.0)     # q - 1
    cdef double Ap = pow(A, q2m) if A > 0.0 else 0.0
    cdef double Bp = pow(B, q2m) if B > 0.0 else 0.0
    cdef double S2 = A * Ap + B * Bp                                 # R^q2
    cdef double R = pow(S2, 1.0 - 1.0 / n2) if S2 > 0.0 else 0.0    # 1/q2 = 1 - 1/n2
    cdef double Rq = pow(R, q1m) if R > 0.0 else 0.0
    cdef double Cq = pow(C, q1m) if C > 0.0 else 0.0
    cdef double den = pow(R * Rq + C * Cq, 1.0 / n1)
    cdef double rho = Rq / den, w = Cq / den, sc
    if R > 0.0:
        sc = rho / pow(S2, 1.0 / n2)                                 # R^(q2-1) = S2^(1/n2)
        out[0] = _sgn1(d[0]) * a * Ap * sc
        out[1] = _sgn1(d[1]) * b * Bp * sc
    else:
        out[0] = 0.0
        out[1] = 0.0
    out[2] = _sgn1(d[2]) * c * w


cdef void support(int kind, const double* p, const double* verts, int nverts,
                  const double* d, double* out) noexcept nogil:
    cdef double n, t, best, s
    cdef int i, k
    if kind == SPHERE:
        n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
        if n > 0.0:
            t = p[0] / n
            out[0] = d[0] * t
            out[1] = d[1] * t
            out[2] = d[2] * t
        else:
            out[0] = p[0]
            out[1] = 0.0
            out[2] = 0.0
    elif kind == BOX:
        # branchless: the signs of d are random across calls (mispredicted branches cost more than the rest)
        out[0] = copysign(p[0], d[0])
        out[1] = copysign(p[1], d[1])
        out[2] = copysign(p[2], d[2])
    elif kind == CYLINDER:
        n = sqrt(d[0] * d[0] + d[1] * d[1])
        if n > 0.0:
            out[0] = d[0] * p[0] / n
            out[1] = d[1] * p[0] / n
        else:
            out[0] = 0.0
            out[1] = 0.0
        out[2] = _sgn1(d[2]) * p[1]
    elif kind == CONE:
        n = sqrt(d[0] * d[0] + d[1] * d[1])
        out[0] = 0.0
        out[1] = 0.0
        if n > 0.0 and n * p[0] + d[2] * p[1] > d[2] * p[2]:
            out[0] = d[0] * p[0] / n       # rim point (r dxy/|dxy|, zb) beats the apex
            out[1] = d[1] * p[0] / n
            out[2] = p[1]
        elif n == 0.0 and d[2] < 0.0:
            out[2] = p[1]                  # base centre
        else:
            out[2] = p[2]                  # apex
    elif kind == ELLIPSOID:
        out[0] = p[0] * p[0] * d[0]
        out[1] = p[1] * p[1] * d[1]
        out[2] = p[2] * p[2] * d[2]
        n = sqrt(out[0] * d[0] + out[1] * d[1] + out[2] * d[2])
        if n > 0.0:
            out[0] /= n
            out[1] /= n
            out[2] /= n
        else:
            out[0] = p[0]
    elif kind == SUPERQUADRIC:
        _superquadric(p, d, out)
    else:  # POLYHEDRON
        k = 0
        best = d[0] * verts[0] + d[1] * verts[1] + d[2] * verts[2]
        for i in range(1, nverts):
            s = d[0] * verts[3 * i] + d[1] * verts[3 * i + 1] + d[2] * verts[3 * i + 2]
            if s > best:
                best = s
                k = i
        out[0] = verts[3 * k]
        out[1] = verts[3 * k + 1]
        out[2] = verts[3 * k + 2]
    if p[MARGIN] != 0.0:
        n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
        if n > 0.0:
            t = p[MARGIN] / n
            out[0] -= d[0] * t
            out[1] -= d[1] * t
            out[2] -= d[2] * t


cdef void support_world(const ShapeRef* sh, const double* R, const double* x, const double* d,
                        double* out) noexcept nogil:
    """World-frame support point of a shape posed at (R, x): R s(R^T d) + x."""
    cdef double db[3]
    cdef double p[3]
    if sh.corners != NULL:        # the same points as GJK's vertex pairs
        support_world_id(sh, R, x, d, out)
        return
    db[0] = R[0] * d[0] + R[3] * d[1] + R[6] * d[2]
    db[1] = R[1] * d[0] + R[4] * d[1] + R[7] * d[2]
    db[2] = R[2] * d[0] + R[5] * d[1] + R[8] * d[2]
    support(sh.kind, sh.params, sh.verts, sh.nverts, db, p)
    out[0] = R[0] * p[0] + R[1] * p[1] + R[2] * p[2] + x[0]
    out[1] = R[3] * p[0] + R[4] * p[1] + R[5] * p[2] + x[1]
    out[2] = R[6] * p[0] + R[7] * p[1] + R[8] * p[2] + x[2]


def support_points(int kind, const double[::1] params, const double[:, ::1] verts, const double[:, ::1] dirs):
    """Body-frame support points of one shape for many directions (testing, meshing, Python-side use)."""
    cdef Py_ssize_t i, n = dirs.shape[0]
    cdef cnp.ndarray[double, ndim=2] out = np.empty((n, 3))
    cdef double[:, ::1] o = out
    cdef const double* vp = &verts[0, 0] if verts.shape[0] > 0 else NULL
    cdef int nv = <int>verts.shape[0]
    if params.shape[0] < NPARAM:
        raise ValueError("params must have %d entries" % NPARAM)
    if kind == POLYHEDRON and nv == 0:
        raise ValueError("a polyhedron needs vertices")
    with nogil:
        for i in range(n):
            support(kind, &params[0], vp, nv, &dirs[i, 0], &o[i, 0])
    return out


def rotation_matrix(const double[::1] q):
    """Rotation matrix (body -> world) of a quaternion (w, x, y, z), as used by the kernels."""
    cdef cnp.ndarray[double, ndim=2] R = np.empty((3, 3))
    cdef double[:, ::1] r = R
    quat_to_rot(&q[0], &r[0, 0])
    return R
