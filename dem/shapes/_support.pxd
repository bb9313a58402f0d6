# cython: language_level=3
"""Support functions of convex shapes, nogil, for GJK/EPA and the pair styles.

A shape is (kind, params[NPARAM], verts, nverts) in its body frame (centre of mass at the origin, axes
along the principal axes). ``params[MARGIN]`` erodes any kind by a ball: support(d) - margin*d/|d|, used
for the cores of smooth shapes (see dem/shapes/base.py). Kind codes match dem/shapes/base.py.
"""

cdef enum:
    SPHERE = 0
    BOX = 1
    CYLINDER = 2
    CONE = 3
    ELLIPSOID = 4
    SUPERQUADRIC = 5
    POLYHEDRON = 6
    NPARAM = 8
    MARGIN = 7

cdef struct ShapeRef:
    int kind
    int nverts
    const double* params
    const double* verts      # this shape's first vertex (x, y, z, x, y, z, ...), NULL if none

cdef void support(int kind, const double* params, const double* verts, int nverts,
                  const double* d, double* out) noexcept nogil
cdef void quat_to_rot(const double* q, double* R) noexcept nogil
cdef void support_world(const ShapeRef* s, const double* R, const double* x, const double* d,
                        double* out) noexcept nogil
