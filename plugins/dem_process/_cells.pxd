# cython: language_level=3
"""Linked-cell helpers shared by the kernels of dem_process (insertion, porosity): the cell of a point and
the (up to) 27 cells around it, periodic axes wrapped, and the minimum-image squared distance."""
from libc.math cimport floor


cdef inline int cell_of(double p, double lo, double size, int n, bint per) noexcept nogil:
    """Cell index of coordinate p along one axis (wrapped when periodic, clamped otherwise)."""
    cdef int c = <int>floor((p - lo) / size)
    if per:
        c = c % n
        if c < 0:
            c += n
    elif c < 0:
        c = 0
    elif c >= n:
        c = n - 1
    return c


cdef inline int stencil(const int* cc, const int* ncell, const int* periodic, int* out) noexcept nogil:
    """Flat indices of the cells around cell cc (itself included) into out[27]; returns their number."""
    cdef int ox, oy, oz, cxx, cyy, czz, m = 0
    for oz in range(-1, 2):
        czz = cc[2] + oz
        if periodic[2]:
            czz = (czz + ncell[2]) % ncell[2]
        elif czz < 0 or czz >= ncell[2]:
            continue
        for oy in range(-1, 2):
            cyy = cc[1] + oy
            if periodic[1]:
                cyy = (cyy + ncell[1]) % ncell[1]
            elif cyy < 0 or cyy >= ncell[1]:
                continue
            for ox in range(-1, 2):
                cxx = cc[0] + ox
                if periodic[0]:
                    cxx = (cxx + ncell[0]) % ncell[0]
                elif cxx < 0 or cxx >= ncell[0]:
                    continue
                out[m] = (czz * ncell[1] + cyy) * ncell[0] + cxx
                m += 1
    return m


cdef inline double dist2(const double* a, const double* b, const double* prd, const int* periodic) noexcept nogil:
    """Squared distance, minimum image along periodic axes."""
    cdef int d
    cdef double dd, r2 = 0.0
    for d in range(3):
        dd = a[d] - b[d]
        if periodic[d]:
            dd -= prd[d] * floor(dd / prd[d] + 0.5)
        r2 += dd * dd
    return r2
