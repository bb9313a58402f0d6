# cython: language_level=3
"""Bounding-volume culls shared by the pair styles (nogil)."""
from libc.math cimport fabs


cdef inline bint boxes_apart(const double* Ra, double na, const double* xa, const double* ha, double sa,
                             const double* Rb, double nb, const double* xb, const double* hb,
                             double sb) noexcept nogil:
    """Whether the bounding boxes of two posed bodies are apart (separating axis test, 15 axes: the faces of
    each and the cross products of their edges). R: rotation (row-major, body -> world) whose columns have
    length n (1 for a pure rotation, the scale when R includes it), h: half sides at scale 1, s: the
    scale. Parallel edges get a 1e-12 slack, so touching boxes are never called apart."""
    return boxes_gap(Ra, na, xa, ha, sa, Rb, nb, xb, hb, sb) > 0.0


cdef inline double boxes_gap(const double* Ra, double na, const double* xa, const double* ha, double sa,
                             const double* Rb, double nb, const double* xb, const double* hb,
                             double sb) noexcept nogil:
    """boxes_apart's test with its outcome as a length: > 0, the gap of the two boxes along the first axis
    that separates them (a lower bound of their distance: an edge-pair axis is not normalised, its length
    is <= 1), else 0 (not proven apart)."""
    cdef double A[3][3]
    cdef double B[3][3]
    cdef double C[3][3]
    cdef double aC[3][3]
    cdef double a[3]
    cdef double b[3]
    cdef double t[3]
    cdef double T[3]
    cdef double ra, rb, u
    cdef int i, j, d
    for i in range(3):
        a[i] = ha[i] * sa
        b[i] = hb[i] * sb
        for d in range(3):
            A[i][d] = Ra[3 * d + i] / na          # unit axis i of a (a column of R)
            B[i][d] = Rb[3 * d + i] / nb
    for d in range(3):
        T[d] = xb[d] - xa[d]
    for i in range(3):
        t[i] = A[i][0] * T[0] + A[i][1] * T[1] + A[i][2] * T[2]
        for j in range(3):
            C[i][j] = A[i][0] * B[j][0] + A[i][1] * B[j][1] + A[i][2] * B[j][2]
            aC[i][j] = fabs(C[i][j]) + 1e-12
    for i in range(3):
        u = fabs(t[i]) - (a[i] + b[0] * aC[i][0] + b[1] * aC[i][1] + b[2] * aC[i][2])
        if u > 0.0:
            return u
    for j in range(3):
        u = t[0] * C[0][j] + t[1] * C[1][j] + t[2] * C[2][j]
        u = fabs(u) - (b[j] + a[0] * aC[0][j] + a[1] * aC[1][j] + a[2] * aC[2][j])
        if u > 0.0:
            return u
    for i in range(3):
        for j in range(3):
            u = t[(i + 2) % 3] * C[(i + 1) % 3][j] - t[(i + 1) % 3] * C[(i + 2) % 3][j]
            ra = a[(i + 1) % 3] * aC[(i + 2) % 3][j] + a[(i + 2) % 3] * aC[(i + 1) % 3][j]
            rb = b[(j + 1) % 3] * aC[i][(j + 2) % 3] + b[(j + 2) % 3] * aC[i][(j + 1) % 3]
            u = fabs(u) - (ra + rb)
            if u > 0.0:
                return u
    return 0.0
