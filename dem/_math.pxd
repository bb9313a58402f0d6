# cython: language_level=3
"""Small vector and quaternion helpers shared by kernels (inline, nogil). Quaternions are (w, x, y, z),
unit, rotating body-frame vectors into the space frame."""
from libc.math cimport sqrt


cdef inline double dot3(const double* a, const double* b) noexcept nogil:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


cdef inline void cross3(const double* a, const double* b, double* out) noexcept nogil:
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]


cdef inline void sub3(const double* a, const double* b, double* out) noexcept nogil:
    out[0] = a[0] - b[0]
    out[1] = a[1] - b[1]
    out[2] = a[2] - b[2]


cdef inline void mat_vec(const double* M, const double* v, double* out) noexcept nogil:
    """out = M v, M row-major 3x3."""
    out[0] = M[0] * v[0] + M[1] * v[1] + M[2] * v[2]
    out[1] = M[3] * v[0] + M[4] * v[1] + M[5] * v[2]
    out[2] = M[6] * v[0] + M[7] * v[1] + M[8] * v[2]


cdef inline void mat_tvec(const double* M, const double* v, double* out) noexcept nogil:
    """out = M^T v, M row-major 3x3."""
    out[0] = M[0] * v[0] + M[3] * v[1] + M[6] * v[2]
    out[1] = M[1] * v[0] + M[4] * v[1] + M[7] * v[2]
    out[2] = M[2] * v[0] + M[5] * v[1] + M[8] * v[2]


cdef inline double det3(const double* a, const double* b, const double* c) noexcept nogil:
    """a . (b x c)"""
    return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0]))


cdef inline void quat_rotate(const double* q, const double* v, double* out) noexcept nogil:
    """out = R(q) v (body -> space)."""
    cdef double w = q[0], x = q[1], y = q[2], z = q[3]
    cdef double tx = 2.0 * (y * v[2] - z * v[1])
    cdef double ty = 2.0 * (z * v[0] - x * v[2])
    cdef double tz = 2.0 * (x * v[1] - y * v[0])
    out[0] = v[0] + w * tx + (y * tz - z * ty)
    out[1] = v[1] + w * ty + (z * tx - x * tz)
    out[2] = v[2] + w * tz + (x * ty - y * tx)


cdef inline void quat_rotate_inv(const double* q, const double* v, double* out) noexcept nogil:
    """out = R(q)^T v (space -> body)."""
    cdef double qc[4]
    qc[0] = q[0]
    qc[1] = -q[1]
    qc[2] = -q[2]
    qc[3] = -q[3]
    quat_rotate(qc, v, out)


cdef inline void quat_mul(const double* a, const double* b, double* out) noexcept nogil:
    out[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3]
    out[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2]
    out[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1]
    out[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]
