# cython: language_level=3
"""The shape table as kernels see it: one struct of row-indexed pointers (TableView), built in one place
(ShapeView, from dem.shapes.table.ShapeTable.kernel_arrays), and the functions that turn a row into the
ShapeRef a support query needs. Row s: body `kind[s]`, `params[NPARAM s:]`, vertices `verts[3 voff[s]:]`
(nv[s] of them); its core (the body shrunk by its crust) alike; the crust at scale 1 and per unit
bounding radius; the bounding radius at scale 1.

A glued composite (kind GLUED) lists its components, further rows of the same table: `comp_count[s]` of
them from `comp_first[s]` in the component arrays, `comp_row[c]` the component's row and `comp_pose[12 c:]`
its rotation (row-major) and offset in the composite's body frame at scale 1 (see table.py). Every other
row has comp_count 0: it is its own single component (`ncomponents`, `component_row`, `pose_component`).

A sharp polytope row (box, cube, polyhedron, tetrahedron, pinacoid) also has its topology in `topo`
(TopoTable: faces, edges and adjacency, dem/shapes/topology.py pack_topology, row for row): offsets and
counts into shared face and edge arrays, as the vertices; `topo.poly[s]` is 0 on the other rows."""
cimport numpy as cnp
from dem.shapes._support cimport ShapeRef, NPARAM, quat_to_rot

ctypedef cnp.int64_t i64

cdef enum:
    COMP_POSE = 12         # values of a component pose: rotation (9, row-major) then offset (3)


cdef struct TopoTable:     # pack_topology's arrays (dem/shapes/topology.py) as pointers, row for row
    int nrows
    const int* poly
    const i64* voff
    const int* nv
    const i64* foff
    const int* nf
    const i64* eoff
    const int* ne
    const i64* fvoff
    const double* radius
    const double* verts
    const double* face_normal
    const double* face_offset
    const int* face_first
    const int* face_count
    const int* face_verts
    const int* edge_verts
    const int* edge_faces
    const double* box_half # 3 nrows, zeros on rows that are not boxes


cdef struct TableView:
    int nrows
    const int* kind
    const double* params
    const i64* voff
    const int* nv
    const int* core_kind
    const double* core_params
    const i64* core_voff
    const int* core_nv
    const double* crust
    const double* crust_rel
    const double* radius
    const int* is_sphere
    const double* verts
    const int* comp_first
    const int* comp_count
    const int* comp_row
    const double* comp_pose
    const double* half         # half sides of a centred bounding box on the body axes, at scale 1 (3 per row)
    const double* req_rel      # radius of the sphere of the row's volume over its bounding radius
    TopoTable topo             # the polytope rows' topology


cdef dict topology_pointers(dict packed, TopoTable* t)


cdef class ShapeView:
    cdef TableView t
    cdef readonly dict arrays       # the arrays the pointers point into (kept alive with the view)


cdef inline bint round_body(const TableView* t, int s) noexcept nogil:
    """A particle of shape index s is a sphere of its own radius (s = -1, or a sphere row)."""
    return s < 0 or t.is_sphere[s] != 0


cdef inline double equivalent_radius(const TableView* t, int s, double radius) noexcept nogil:
    """Radius of the sphere of a particle's volume (shape index s, bounding radius `radius`): a sphere's own."""
    return radius if s < 0 or t.is_sphere[s] != 0 else radius * t.req_rel[s]


cdef inline void body_ref(const TableView* t, int s, ShapeRef* r) noexcept nogil:
    """Row s's body (the true, sharp shape: walls)."""
    r.kind = t.kind[s]
    r.params = t.params + NPARAM * s
    r.nverts = t.nv[s]
    r.verts = t.verts + 3 * t.voff[s]
    r.corners = NULL


cdef inline void core_ref(const TableView* t, int s, ShapeRef* r) noexcept nogil:
    """Row s's core (the body shrunk by its crust: GJK's crust contact)."""
    r.kind = t.core_kind[s]
    r.params = t.core_params + NPARAM * s
    r.nverts = t.core_nv[s]
    r.verts = t.verts + 3 * t.core_voff[s]
    r.corners = NULL


cdef inline void pose_body(const TableView* t, int s, const double* quat, double radius, ShapeRef* r,
                           double* R) noexcept nogil:
    """Row s's body for a particle of orientation quat and bounding radius `radius`: r, and R its rotation
    (body -> world) times the scale radius / radius[s]."""
    cdef double sc = radius / t.radius[s]
    cdef int k
    body_ref(t, s, r)
    quat_to_rot(quat, R)
    for k in range(9):
        R[k] *= sc


cdef inline int ncomponents(const TableView* t, int s) noexcept nogil:
    """Convex pieces of a particle of shape index s: its components (a composite) or itself (1)."""
    if s < 0 or t.comp_count[s] == 0:
        return 1
    return t.comp_count[s]


cdef inline int component_row(const TableView* t, int s, int c) noexcept nogil:
    """The row of piece c of shape index s (s itself when it is not a composite; -1 stays a sphere)."""
    if s < 0 or t.comp_count[s] == 0:
        return s
    return t.comp_row[t.comp_first[s] + c]


cdef inline void pose_component(const TableView* t, int s, int c, const double* R, const double* x,
                                double* Rc, double* xc) noexcept nogil:
    """Piece c of a particle of shape index s posed at (R, x), R its scaled rotation (body -> world times
    the scale): Rc = R Q_c and xc = x + R o_c, (Q_c, o_c) the component's pose in the composite frame."""
    cdef const double* q
    cdef int a, b
    if s < 0 or t.comp_count[s] == 0:
        for a in range(9):
            Rc[a] = R[a]
        for a in range(3):
            xc[a] = x[a]
        return
    q = t.comp_pose + COMP_POSE * (t.comp_first[s] + c)
    for a in range(3):
        for b in range(3):
            Rc[3 * a + b] = R[3 * a] * q[b] + R[3 * a + 1] * q[3 + b] + R[3 * a + 2] * q[6 + b]
        xc[a] = x[a] + R[3 * a] * q[9] + R[3 * a + 1] * q[10] + R[3 * a + 2] * q[11]
