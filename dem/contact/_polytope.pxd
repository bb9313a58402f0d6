# cython: language_level=3
"""nogil penetration depth, normal and multipoint contact of two posed sharp convex polytopes (no crust).

A body is a Polytope (its topology in the body frame, from dem/shapes/topology.py through a TopoTable row:
the shape table's `TableView.topo`, dem/shapes/_table.pxd; `polytope_ref`) posed by a pure rotation R (row-major, body -> world), a uniform scale s and the position
x of its centre of mass: world point = x + s R v. Normals point from B to A, as in the contact record
(dem/contact/record.pxd). See _polytope.pyx for the algorithms.
"""
cimport numpy as cnp
from dem.shapes._table cimport TopoTable

ctypedef cnp.int64_t i64

cdef enum:
    POLY_MAXP = 16         # contact points of a pair at most
    POLY_MAXFEAT = 64      # vertices of one contacting feature at most (the first ones by vertex id)

cpdef enum AxisKind:       # which candidate axis gave the minimum penetration (SatResult.axis)
    AXIS_NONE = -1
    AXIS_FACE_A = 0        # a face normal of A (SatResult.fa)
    AXIS_FACE_B = 1        # a face normal of B (SatResult.fb)
    AXIS_EDGE = 2          # the cross product of edge fa of A and edge fb of B

cpdef enum PolyContactType:   # PolyContact.type: the dimension of the contact region
    PC_NONE = 0
    PC_VERTEX_FACE = 1     # one point (vertex/face, also vertex/edge and vertex/vertex)
    PC_EDGE_EDGE = 2       # one point: two crossing edges
    PC_EDGE_FACE = 3       # two points: a segment (edge/face, also two collinear edges)
    PC_FACE_FACE = 4       # three or more points: the corners of the overlap polygon

cdef struct Polytope:      # one body's topology in its body frame (all ids local to the body)
    int nv
    int nf
    int ne
    double radius          # largest vertex norm (scale 1)
    const double* verts    # 3 nv
    const double* fnormal  # 3 nf, unit outward
    const double* foffset  # nf: the body is n.v <= d
    const int* ffirst      # nf: face f's vertex ids are fverts[ffirst[f] + k], k < fcount[f], CCW from outside
    const int* fcount
    const int* fverts
    const int* edges       # 2 ne: vertex ids (v0, v1)
    const int* efaces      # 2 ne: face f0 (runs v0 -> v1), face f1 (runs v1 -> v0)
    const double* half     # 3: half sides when laid out as topology.box_topology's (the box path), else NULL

cdef class TopologyView:
    cdef TopoTable t
    cdef readonly dict arrays      # the arrays the pointers point into (kept alive with the view)

cdef struct SatResult:
    double depth           # min over the candidate axes u of h_A(u) + h_B(-u); > 0 when the bodies overlap
    double n[3]            # unit world normal from B to A (-u: A moves along n by depth to separate)
    int axis               # AxisKind
    int fa                 # face of A (AXIS_FACE_A) or edge of A (AXIS_EDGE), else -1
    int fb                 # face of B (AXIS_FACE_B) or edge of B (AXIS_EDGE), else -1

cdef struct PolyContact:
    double depth           # the shared (maximum) overlap of all points: SatResult.depth
    double n[3]            # SatResult.n
    int type               # PolyContactType
    int npoints            # 1 .. POLY_MAXP
    int nfa                # vertices in A's contacting feature (1 vertex, 2 edge, >= 3 face), after projection
    int nfb                # alike for B
    double p[48]           # 3 * POLY_MAXP: the points on the contact plane (world), in a canonical order


cdef inline void polytope_ref(const TopoTable* t, int s, Polytope* p) noexcept nogil:
    """Row s of the packed topology as a Polytope (nv = nf = ne = 0 on a row without topology)."""
    cdef i64 f0 = t.foff[s], e0 = t.eoff[s]
    p.nv = t.nv[s]
    p.nf = t.nf[s]
    p.ne = t.ne[s]
    p.radius = t.radius[s]
    p.verts = t.verts + 3 * t.voff[s]
    p.fnormal = t.face_normal + 3 * f0
    p.foffset = t.face_offset + f0
    p.ffirst = t.face_first + f0
    p.fcount = t.face_count + f0
    p.fverts = t.face_verts + t.fvoff[s]
    p.edges = t.edge_verts + 2 * e0
    p.efaces = t.edge_faces + 2 * e0
    p.half = t.box_half + 3 * s if t.box_half[3 * s] > 0.0 else NULL


cdef int sat_penetration(const Polytope* A, const double* Ra, double sa, const double* xa,
                         const Polytope* B, const double* Rb, double sb, const double* xb,
                         SatResult* out) noexcept nogil

cdef int contact_points(const Polytope* A, const double* Ra, double sa, const double* xa,
                        const Polytope* B, const double* Rb, double sb, const double* xb,
                        const SatResult* sat, double ftol, PolyContact* out) noexcept nogil

cdef int polytope_contact(const Polytope* A, const double* Ra, double sa, const double* xa,
                          const Polytope* B, const double* Rb, double sb, const double* xb,
                          double ftol, double ftol_depth, SatResult* sat, PolyContact* out,
                          int* code, double* budget, double moved) noexcept nogil
