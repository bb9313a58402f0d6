# cython: language_level=3
"""The shape table as kernels see it: one struct of row-indexed pointers (TableView), built in one place
(ShapeView, from dem.shapes.table.ShapeTable.kernel_arrays), and the functions that turn a row into the
ShapeRef a support query needs. Row s: body `kind[s]`, `params[NPARAM s:]`, vertices `verts[3 voff[s]:]`
(nv[s] of them); its core (the body shrunk by its crust) alike; the crust at scale 1 and per unit
bounding radius; the bounding radius at scale 1.

Planned rows (same table, no other kernel argument): a glued composite lists its components as further
rows (first component, count, and per component an offset and an orientation in the composite frame),
with the union's mass properties in the row itself; a polyhedron adds its faces and edges as offsets and
counts into shared face/edge arrays, as the vertices are today."""
cimport numpy as cnp
from dem.shapes._support cimport ShapeRef, NPARAM, quat_to_rot

ctypedef cnp.int64_t i64


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


cdef class ShapeView:
    cdef TableView t
    cdef readonly dict arrays       # the arrays the pointers point into (kept alive with the view)


cdef inline bint round_body(const TableView* t, int s) noexcept nogil:
    """A particle of shape index s is a sphere of its own radius (s = -1, or a sphere row)."""
    return s < 0 or t.is_sphere[s] != 0


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
