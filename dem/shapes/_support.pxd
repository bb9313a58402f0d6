# cython: language_level=3
"""Support functions of convex shapes, nogil, for GJK/EPA and the pair styles.

A shape is (kind, params[NPARAM], verts, nverts) in its body frame (centre of mass at the origin, axes
along the principal axes). ``params[MARGIN]`` erodes any kind by a ball: support(d) - margin*d/|d|, used
for the cores of smooth shapes (see dem/shapes/base.py). Kind codes match dem/shapes/base.py.
"""
from libc.math cimport copysign, signbit

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


# inline: GJK's hot path on polytopes (defined here so that the compiler can inline them into the kernels)
cdef inline int support_world_id(const ShapeRef* sh, const double* R, const double* x, const double* d,
                          double* out) noexcept nogil:
    """support_world, returning the vertex index of the support point on a polytope (a box without margin:
    bit k set for +h_k; a polyhedron: its vertex), -1 on curved shapes. vertex_world(id) gives the point back,
    so GJK can rebuild a simplex from the indices at a new pose."""
    cdef double db[3]
    cdef double p[3]
    cdef int k, best_k = -1
    cdef double best, s
    db[0] = R[0] * d[0] + R[3] * d[1] + R[6] * d[2]
    db[1] = R[1] * d[0] + R[4] * d[1] + R[7] * d[2]
    db[2] = R[2] * d[0] + R[5] * d[1] + R[8] * d[2]
    if sh.params[MARGIN] != 0.0 or (sh.kind != BOX and sh.kind != POLYHEDRON):
        support(sh.kind, sh.params, sh.verts, sh.nverts, db, p)
    elif sh.kind == BOX:
        p[0] = copysign(sh.params[0], db[0])
        p[1] = copysign(sh.params[1], db[1])
        p[2] = copysign(sh.params[2], db[2])
        best_k = (0 if signbit(db[0]) else 1) | (0 if signbit(db[1]) else 2) | (0 if signbit(db[2]) else 4)
    else:
        best_k = 0
        best = db[0] * sh.verts[0] + db[1] * sh.verts[1] + db[2] * sh.verts[2]
        for k in range(1, sh.nverts):
            s = db[0] * sh.verts[3 * k] + db[1] * sh.verts[3 * k + 1] + db[2] * sh.verts[3 * k + 2]
            if s > best:
                best = s
                best_k = k
        p[0] = sh.verts[3 * best_k]
        p[1] = sh.verts[3 * best_k + 1]
        p[2] = sh.verts[3 * best_k + 2]
    out[0] = R[0] * p[0] + R[1] * p[1] + R[2] * p[2] + x[0]
    out[1] = R[3] * p[0] + R[4] * p[1] + R[5] * p[2] + x[1]
    out[2] = R[6] * p[0] + R[7] * p[1] + R[8] * p[2] + x[2]
    return best_k


cdef inline bint vertex_world(const ShapeRef* sh, const double* R, const double* x, int vid, double* out) noexcept nogil:
    """World position of the vertex index returned by support_world_id; False if there is no such vertex."""
    cdef double p[3]
    if vid < 0 or sh.params[MARGIN] != 0.0:
        return False
    if sh.kind == BOX and vid < 8:
        p[0] = sh.params[0] * <double>((vid & 1) * 2 - 1)      # branchless (random bits)
        p[1] = sh.params[1] * <double>((vid & 2) - 1)
        p[2] = sh.params[2] * <double>(((vid & 4) >> 1) - 1)
    elif sh.kind == POLYHEDRON and vid < sh.nverts:
        p[0] = sh.verts[3 * vid]
        p[1] = sh.verts[3 * vid + 1]
        p[2] = sh.verts[3 * vid + 2]
    else:
        return False
    out[0] = R[0] * p[0] + R[1] * p[1] + R[2] * p[2] + x[0]
    out[1] = R[3] * p[0] + R[4] * p[1] + R[5] * p[2] + x[1]
    out[2] = R[6] * p[0] + R[7] * p[1] + R[8] * p[2] + x[2]
    return True
