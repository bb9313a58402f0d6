# cython: language_level=3
"""Point-in-body tests of the convex kinds (the gauges of dem/shapes/_lattice.pyx's docstring), shared by
the lattice mass properties and compute porosity."""
from libc.math cimport sqrt, pow, fabs, INFINITY

from ._support cimport SPHERE, BOX, CYLINDER, CONE, ELLIPSOID, SUPERQUADRIC


cdef inline double gauge(int kind, const double* p, const double* planes, int nplanes,
                         double x, double y, double z) noexcept nogil:
    """<= 0 iff the body-frame point (x, y, z) is inside the body."""
    cdef double a, b, c, r, H
    cdef int f
    if kind == SPHERE:
        return x * x + y * y + z * z - p[0] * p[0]
    elif kind == BOX:
        a = fabs(x) - p[0]
        b = fabs(y) - p[1]
        c = fabs(z) - p[2]
        if b > a:
            a = b
        return c if c > a else a
    elif kind == CYLINDER:
        a = (x * x + y * y) / (p[0] * p[0]) - 1.0
        b = fabs(z) / p[1] - 1.0
        return b if b > a else a
    elif kind == CONE:
        H = p[2] - p[1]
        a = sqrt(x * x + y * y) / p[0] - (p[2] - z) / H
        b = (p[1] - z) / H
        return b if b > a else a
    elif kind == ELLIPSOID:
        a = x / p[0]
        b = y / p[1]
        c = z / p[2]
        return a * a + b * b + c * c - 1.0
    elif kind == SUPERQUADRIC:
        a = pow(fabs(x / p[0]), p[4]) + pow(fabs(y / p[1]), p[4])
        return pow(a, p[3] / p[4]) + pow(fabs(z / p[2]), p[3]) - 1.0
    else:   # POLYHEDRON
        r = -INFINITY
        for f in range(nplanes):
            a = planes[4 * f] * x + planes[4 * f + 1] * y + planes[4 * f + 2] * z + planes[4 * f + 3]
            if a > r:
                r = a
        return r
