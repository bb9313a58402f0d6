# cython: language_level=3
"""Support functions of convex shapes, nogil, for GJK/EPA and the pair styles.

A shape is (kind, params[NPARAM], verts, nverts) in its body frame (centre of mass at the origin, axes
along the principal axes). ``params[MARGIN]`` erodes any kind by a ball: support(d) - margin*d/|d|, used
for the cores of smooth shapes (see dem/shapes/base.py). Kind codes are the enum Kind (Python: dem.shapes.base reads them from here).
"""
from libc.math cimport signbit, sqrt

cpdef enum Kind:           # shape kinds (the one source: dem.shapes.base reads them from _support)
    SPHERE = 0
    BOX = 1
    CYLINDER = 2
    CONE = 3
    ELLIPSOID = 4
    SUPERQUADRIC = 5
    POLYHEDRON = 6
    GLUED = 7              # a composite: its components are further rows (dem/shapes/_table.pxd); no support

cdef enum:                 # a shape row's parameters (Python: _support.LAYOUT): NPARAM values,
    NPARAM = 8             # params[MARGIN] the erosion margin
    MARGIN = 7
    NCORNER = 24           # values of a box posed as its 8 corners (box_corners)

cdef struct ShapeRef:
    int kind
    int nverts
    const double* params
    const double* verts      # this shape's first vertex (x, y, z, x, y, z, ...), NULL if none
    const double* corners    # a box posed once per step: its 8 world corners (corner id k at 3k), or NULL

cdef void support(int kind, const double* params, const double* verts, int nverts,
                  const double* d, double* out) noexcept nogil
cdef void support_world(const ShapeRef* s, const double* R, const double* x, const double* d,
                        double* out) noexcept nogil


cdef inline void quat_to_rot(const double* q, double* R) noexcept nogil:
    """Row-major rotation matrix (body -> world) of the quaternion (w, x, y, z); not normalised inputs are
    tolerated (the quaternion is scaled by 1/|q|^2 implicitly)."""
    cdef double w = q[0], x = q[1], y = q[2], z = q[3]
    cdef double s = 2.0 / (w * w + x * x + y * y + z * z)
    R[0] = 1.0 - s * (y * y + z * z)
    R[1] = s * (x * y - w * z)
    R[2] = s * (x * z + w * y)
    R[3] = s * (x * y + w * z)
    R[4] = 1.0 - s * (x * x + z * z)
    R[5] = s * (y * z - w * x)
    R[6] = s * (x * z - w * y)
    R[7] = s * (y * z + w * x)
    R[8] = 1.0 - s * (x * x + y * y)


cdef inline bint polytope_core(int kind, double margin) noexcept nogil:
    """A body with vertices (box or polyhedron, not eroded by a margin): supports are vertices, which GJK
    can name by index (support_world_id) and warm-start from."""
    return (kind == BOX or kind == POLYHEDRON) and margin == 0.0


# inline: GJK's hot path on polytopes (defined here so that the compiler can inline them into the kernels)
cdef inline void posed_point(const double* R, const double* x, const double* p, double* out) noexcept nogil:
    """out = R p + x: a body-frame point posed at (R, x)."""
    out[0] = R[0] * p[0] + R[1] * p[1] + R[2] * p[2] + x[0]
    out[1] = R[3] * p[0] + R[4] * p[1] + R[5] * p[2] + x[1]
    out[2] = R[6] * p[0] + R[7] * p[1] + R[8] * p[2] + x[2]


cdef inline bint corner_box(int kind, double margin) noexcept nogil:
    """A box core without margin: the pair style poses it once per step as its corners (box_corners)."""
    return kind == BOX and margin == 0.0


cdef inline void box_corners(const double* R, const double* x, const double* h, double* out) noexcept nogil:
    """The 8 corners of the box of half-sides h posed at (R, x), corner k at out[3k] (bit j of k set: +h_j),
    rounded as posed_point rounds R p + x (((R0 p0 + R1 p1) + R2 p2) + x; sign flips are exact), so that
    GJK's vertex pairs get the same points whether they come from here or from the shape."""
    cdef double a, b, c, p, m
    cdef int d
    for d in range(3):
        a = R[3 * d] * h[0]
        b = R[3 * d + 1] * h[1]
        c = R[3 * d + 2] * h[2]
        p = a + b                  # s0 = s1: +-p; s0 = -s1: +-m
        m = a - b
        out[d] = x[d] - (p + c)
        out[3 + d] = x[d] + (m - c)
        out[6 + d] = x[d] - (m + c)
        out[9 + d] = x[d] + (p - c)
        out[12 + d] = x[d] - (p - c)
        out[15 + d] = x[d] + (m + c)
        out[18 + d] = x[d] - (m - c)
        out[21 + d] = x[d] + (p + c)


cdef inline int _corner_bits(const double* db) noexcept nogil:
    """The box corner that is farthest along the body-frame direction db (bit k set: +h_k)."""
    return (0 if signbit(db[0]) else 1) | (0 if signbit(db[1]) else 2) | (0 if signbit(db[2]) else 4)


cdef inline int box_support_id(const double* R, const double* d) noexcept nogil:
    """support_world_id of a box posed at R, for the world direction d: its corner index."""
    cdef double db[3]
    db[0] = R[0] * d[0] + R[3] * d[1] + R[6] * d[2]
    db[1] = R[1] * d[0] + R[4] * d[1] + R[7] * d[2]
    db[2] = R[2] * d[0] + R[5] * d[1] + R[8] * d[2]
    return _corner_bits(db)


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
    if not polytope_core(sh.kind, sh.params[MARGIN]):
        support(sh.kind, sh.params, sh.verts, sh.nverts, db, p)
    elif sh.kind == BOX:
        # copysign(h, db) from the corner bits: gcc spills copysign's operand through memory (a stalled
        # store-to-load forward in GJK's hottest loop)
        best_k = _corner_bits(db)
        if sh.corners != NULL:
            out[0] = sh.corners[3 * best_k]
            out[1] = sh.corners[3 * best_k + 1]
            out[2] = sh.corners[3 * best_k + 2]
            return best_k
        p[0] = sh.params[0] * <double>((best_k & 1) * 2 - 1)
        p[1] = sh.params[1] * <double>((best_k & 2) - 1)
        p[2] = sh.params[2] * <double>(((best_k & 4) >> 1) - 1)
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
    posed_point(R, x, p, out)
    return best_k


cdef inline bint vertex_world(const ShapeRef* sh, const double* R, const double* x, int vid, double* out) noexcept nogil:
    """World position of the vertex index returned by support_world_id; False if there is no such vertex."""
    cdef double p[3]
    if vid < 0 or sh.params[MARGIN] != 0.0:
        return False
    if sh.kind == BOX and vid < 8:
        if sh.corners != NULL:
            out[0] = sh.corners[3 * vid]
            out[1] = sh.corners[3 * vid + 1]
            out[2] = sh.corners[3 * vid + 2]
            return True
        p[0] = sh.params[0] * <double>((vid & 1) * 2 - 1)      # branchless (random bits)
        p[1] = sh.params[1] * <double>((vid & 2) - 1)
        p[2] = sh.params[2] * <double>(((vid & 4) >> 1) - 1)
    elif sh.kind == POLYHEDRON and vid < sh.nverts:
        p[0] = sh.verts[3 * vid]
        p[1] = sh.verts[3 * vid + 1]
        p[2] = sh.verts[3 * vid + 2]
    else:
        return False
    posed_point(R, x, p, out)
    return True
