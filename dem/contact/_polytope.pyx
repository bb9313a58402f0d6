# cython: language_level=3, boundscheck=False, wraparound=False, cdivision=True, initializedcheck=False
"""Exact penetration of two sharp convex polytopes (separating axes on the Gauss map) and their multipoint
contact (features projected on the contact plane and clipped), nogil.

Penetration (sat_penetration)
-----------------------------
For two overlapping convex bodies the penetration depth is  delta = min over unit u of h_{A-B}(u), with
h_{A-B}(u) = h_A(u) + h_B(-u) the support function of the Minkowski difference: the distance from the
origin to the boundary of A - B, reached at the facet of A - B closest to the origin. That facet is the
point P that Descantes' GJK-TD relocates onto the hull of A - B (Descantes 2022 sec. 2.3.1), so both give
the same depth and normal; GJK-TD gets there by iterating simplices, this kernel by enumerating the
candidate facets: for polytopes every facet of A - B has as normal a face normal of A, minus a face
normal of B, or the cross product of an edge of A and an edge of B. The edge pairs that do build a facet
are those whose arcs on the Gauss map cross (Gregorius, GDC 2013: arc (a, b) of A's edge, with a, b its
two face normals, against (-c, -d) of B's); for them the facet normal u = eA x eB is oriented into arc
(a, b) and h_{A-B}(u) = u . (vA - vB) from one vertex of each edge. Every candidate value is >= delta
(h_{A-B}(u) >= delta for every unit u when the origin is inside), and the true facet is a candidate, so
the minimum is delta exactly (to round-off); unlike EPA there is no iteration and no tolerance.

Degenerate cases (dense packings): parallel edges (|eA x eB| <= SAT_PARALLEL |eA| |eB|) are skipped: their
facet, when it exists, has the normal of a face of A or B, which is a candidate anyway. For nearly parallel
edges (|sin| < SAT_SMALLSIN) the computed u carries a relative error eps / |sin|; the value is then taken
from the full supports h_A(u) + h_B(-u), an upper bound that stays >= delta. Ties: a candidate replaces the
best one of its family only if lower by more than SAT_TIE * L (L = the two bounding radii, scaled): so the
lowest index wins within that tolerance; then the faces of A win over those of B, and faces over edge
pairs, within the same tolerance. The depth returned is the chosen axis' value, within SAT_TIE * L of the
minimum. Everything is computed in A's rotated frame centred on A (relative position first), so large
coordinates cost no digits. Cost: O(nf_A nv_B + nf_B nv_A) for the faces, then edge pairs only among the
edges that reach into the overlap slab of the best face axis (exact, see _sat_frame): O(ne_A ne_B) at
worst, a few pairs for the shallow contacts of a packing. Two boxes take the closed-form 15 axes of
_sat_box instead (the same candidates, values and tie rules; tests/test_polytope.py compares the two).

Lasting contacts (polytope_contact with a certificate): the full test also bounds how far the two bodies
may move with its winning axis staying the strict minimum (_budget: a gap to every other facet of A - B
that outlasts their motion, including facets that turn fast or appear); while the moves since then stay
within it, only that axis is evaluated, by the same code, so the answer is the one the full test would
give, bit for bit.

Contact points (contact_points)
-------------------------------
With u = -n (from A towards B) and the depth, the contacting feature of A is its vertices whose support
u . v is within ftol of h_A(u), that of B its vertices within ftol of h_B(-u) along -u: a vertex (1), an
edge (2), a face (>= 3). Both are projected on the contact plane (normal n, midway between the two
extreme planes u.x = h_A(u) and u.x = -h_B(-u), i.e. through the midpoint of Descantes' P_A and P_B),
reduced to their 2D convex hull (monotone chain: vertices sorted by their plane coordinates, collinear and
repeated points dropped), and clipped: polygon by polygon (Sutherland-Hodgman), segment by polygon
(Cyrus-Beck), segment by segment (crossing point, or the common interval when parallel); a single vertex
gives itself (both single: their midpoint). The type is the dimension of the result: one point
(vertex/face, or edge/edge when two edges cross), two (edge/face), three or more (face/face); at most
POLY_MAXP points (a larger overlap polygon keeps POLY_MAXP of its corners, evenly spaced). The order is
canonical: the point with the lowest plane coordinates first, then counter-clockwise about u, so the same
input gives the same bits. All points share the maximum overlap (Descantes' law, eq. 3).
"""
import numpy as np
from libc.math cimport sqrt, fabs, sin, cos, INFINITY

from dem._math cimport mat_vec, mat_tvec
from dem.shapes._support cimport quat_to_rot
from dem.shapes._table cimport topology_pointers

cdef double SAT_TIE = 1e-12        # relative (to the bounding radii) tolerance of axis ties
cdef double SAT_PARALLEL = 1e-12   # |sin| of two edges below which they are parallel (skipped)
cdef double SAT_SMALLSIN = 1e-4    # below this |sin| an edge axis is evaluated from the full supports
cdef double CERT_SLAB = 0.005      # edge slab widening (relative to L) when a certificate is computed (_budget)
cdef enum:
    EDGE_BUF = 256                 # edges of A pruned by the overlap slab in _sat_frame (a larger A pairs them all)
    SUPPORT_BUF = 256              # support values kept per body in _feature (larger bodies recompute)
cdef double HULL_TOL = 1e-12       # relative (to L) distance below which plane points coincide / are collinear

MAXP = POLY_MAXP


cdef class TopologyView:
    """The arrays of dem.shapes.topology.pack_topology behind one TopoTable struct (tests and tools: the
    kernels read the shape table's, TableView.topo)."""

    def __cinit__(self, dict arrays):
        self.arrays = topology_pointers(arrays, &self.t)

    @property
    def nrows(self):
        return self.t.nrows


# ---------------------------------------------------------------- small helpers
cdef inline double _dot(const double* a, const double* b) noexcept nogil:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


cdef inline void _cross(const double* a, const double* b, double* o) noexcept nogil:
    o[0] = a[1] * b[2] - a[2] * b[1]
    o[1] = a[2] * b[0] - a[0] * b[2]
    o[2] = a[0] * b[1] - a[1] * b[0]


cdef struct Frame:         # B seen in A's rotated frame centred on A: point of B = t + sb M v
    double M[9]            # Ra^T Rb
    double t[3]            # Ra^T (xb - xa)
    double sa
    double sb
    double L               # sa radius_A + sb radius_B


cdef inline void _frame(const Polytope* A, const double* Ra, double sa, const double* xa,
                        const Polytope* B, const double* Rb, double sb, const double* xb, Frame* F) noexcept nogil:
    cdef int i, j
    cdef double d[3]
    for i in range(3):
        for j in range(3):
            F.M[3 * i + j] = Ra[i] * Rb[j] + Ra[3 + i] * Rb[3 + j] + Ra[6 + i] * Rb[6 + j]
        d[i] = xb[i] - xa[i]
    mat_tvec(Ra, d, F.t)
    F.sa = sa
    F.sb = sb
    F.L = sa * A.radius + sb * B.radius


cdef inline double _hA(const Polytope* A, double sa, const double* w) noexcept nogil:
    """Support value of A (A's frame) along w."""
    cdef double best = -INFINITY, s
    cdef const double* v
    cdef int k
    for k in range(A.nv):
        v = A.verts + 3 * k
        s = w[0] * v[0] + w[1] * v[1] + w[2] * v[2]
        if s > best:
            best = s
    return sa * best


cdef inline double _hB(const Polytope* B, const Frame* F, const double* w) noexcept nogil:
    """Support value of B (in A's frame) along w: w.t + sb max (M^T w).v."""
    cdef double wb[3]
    cdef double best = -INFINITY, s
    cdef const double* v
    cdef int k
    mat_tvec(F.M, w, wb)
    for k in range(B.nv):
        v = B.verts + 3 * k
        s = wb[0] * v[0] + wb[1] * v[1] + wb[2] * v[2]
        if s > best:
            best = s
    return _dot(w, F.t) + F.sb * best


cdef inline void _b_point(const Polytope* B, const Frame* F, int k, double* o) noexcept nogil:
    """Vertex k of B in A's frame."""
    mat_vec(F.M, B.verts + 3 * k, o)
    o[0] = F.t[0] + F.sb * o[0]
    o[1] = F.t[1] + F.sb * o[1]
    o[2] = F.t[2] + F.sb * o[2]


# ---------------------------------------------------------------- penetration
cdef int BOX_EDGE[24]               # edge id of box_topology for corner c (bit i clear) and axis i: [3 c + i]


def _box_edges():
    from dem.shapes.topology import box_topology
    for e, (v0, v1) in enumerate(box_topology([1.0, 1.0, 1.0]).edges):
        d = int(v0) ^ int(v1)
        BOX_EDGE[3 * (int(v0) & ~d) + d.bit_length() - 1] = e


_box_edges()


cdef inline int _box_edge(const Polytope* P, int i, const double* w) noexcept nogil:
    """The edge of box P along its axis i that supports direction w (P's frame): its end corners differ in
    bit i and share bit k = (w_k > 0) for the other axes (box_corners order)."""
    cdef int k, c = 0
    for k in range(3):
        c |= ((k != i) & (w[k] > 0.0)) << k
    return BOX_EDGE[3 * c + i]


cdef int _sat_box(const Polytope* A, const Polytope* B, const Frame* F, double* u_out, SatResult* out) noexcept nogil:
    """_sat_frame for two boxes: the 15 axes of the box-box separating-axis test in closed form (the classic
    OBB identities of an orthonormal M: the edge axis e_i x M e_j has length sqrt(1 - M_ij^2) and projects
    the boxes on sums of two |M| terms), with the same candidates, values, orientation (u from A towards B)
    and tie rules as the general loop and no vertex loop. Returns at the first axis that separates the boxes
    (depth < 0 is then that axis' gap, a lower bound of their distance)."""
    cdef double tie = SAT_TIE * F.L
    cdef double a[3]
    cdef double b[3]
    cdef double Ab[9]              # |M_ij|
    cdef double rA[3]              # A's radius along B's axis j: sum_i a_i |M_ij|
    cdef double rB[3]              # B's radius along A's axis i: sum_j b_j |M_ij|
    cdef double tb[3]              # t along B's axes: M^T t
    cdef double u[3]
    cdef double uE[3]
    cdef double w[3]
    cdef double bestA = INFINITY, bestB = INFINITY, bestE = INFINITY, d, l2, tu, sgn, inv, lim
    cdef int fa = -1, fb = -1, ea = -1, eb = -1, i, j, k, sd, i1, i2, j1, j2
    cdef const double* t = F.t
    cdef const double* M = F.M
    for k in range(3):
        a[k] = F.sa * A.half[k]
        b[k] = F.sb * B.half[k]
    for k in range(9):
        Ab[k] = fabs(M[k])
    for k in range(3):
        rB[k] = b[0] * Ab[3 * k] + b[1] * Ab[3 * k + 1] + b[2] * Ab[3 * k + 2]
        rA[k] = a[0] * Ab[k] + a[1] * Ab[3 + k] + a[2] * Ab[6 + k]
        tb[k] = M[k] * t[0] + M[3 + k] * t[1] + M[6 + k] * t[2]
    # faces of A, in box_topology's order (face 2i + sd has normal (2 sd - 1) e_i)
    for i in range(3):
        for sd in range(2):
            sgn = 2.0 * sd - 1.0
            d = a[i] + rB[i] - sgn * t[i]
            if d < 0.0:
                out.axis, out.fa, out.fb, out.depth = AXIS_FACE_A, 2 * i + sd, -1, d
                u_out[0], u_out[1], u_out[2] = 0.0, 0.0, 0.0
                u_out[i] = sgn
                return 0
            if d < bestA - tie:
                bestA = d
                fa = 2 * i + sd
    # faces of B: outward m = sgn M e_j, u = -m
    for j in range(3):
        for sd in range(2):
            sgn = 2.0 * sd - 1.0
            d = rA[j] + sgn * tb[j] + b[j]
            if d < 0.0:
                out.axis, out.fa, out.fb, out.depth = AXIS_FACE_B, -1, 2 * j + sd, d
                u_out[0], u_out[1], u_out[2] = -sgn * M[j], -sgn * M[3 + j], -sgn * M[6 + j]
                return 0
            if d < bestB - tie:
                bestB = d
                fb = 2 * j + sd
    # edge directions u = e_i x M e_j (length sqrt(1 - M_ij^2)), oriented towards B; an edge value at or
    # above the best face value cannot be chosen (faces win within the tie tolerance)
    lim = bestA if bestA < bestB else bestB
    for j in range(3):
        j1 = j + 1 if j < 2 else 0
        j2 = j1 + 1 if j1 < 2 else 0
        for i in range(3):
            i1 = i + 1 if i < 2 else 0
            i2 = i1 + 1 if i1 < 2 else 0
            tu = t[i2] * M[3 * i1 + j] - t[i1] * M[3 * i2 + j]
            d = a[i1] * Ab[3 * i2 + j] + a[i2] * Ab[3 * i1 + j] + b[j1] * Ab[3 * i + j2] + b[j2] * Ab[3 * i + j1] - fabs(tu)
            if d >= 0.0 and (d >= bestE or d >= lim):
                continue               # |u| <= 1: d / |u| >= d cannot win (nor tie within the family)
            l2 = M[3 * i1 + j] * M[3 * i1 + j] + M[3 * i2 + j] * M[3 * i2 + j]
            if l2 <= SAT_PARALLEL * SAT_PARALLEL:
                continue
            inv = 1.0 / sqrt(l2)
            d *= inv
            if d < 0.0 or d < bestE - tie:
                sgn = inv if tu >= 0.0 else -inv
                u[i] = 0.0
                u[i1] = -sgn * M[3 * i2 + j]
                u[i2] = sgn * M[3 * i1 + j]
                if d < 0.0:
                    out.axis, out.fa, out.fb, out.depth = AXIS_EDGE, -1, -1, d
                    u_out[0], u_out[1], u_out[2] = u[0], u[1], u[2]
                    return 0
                bestE = d
                ea = i
                eb = j
                uE[0], uE[1], uE[2] = u[0], u[1], u[2]
    if bestB < bestA - tie:
        sgn = 2.0 * (fb % 2) - 1.0
        out.axis, out.fa, out.fb, out.depth = AXIS_FACE_B, -1, fb, bestB
        j = fb // 2
        u_out[0], u_out[1], u_out[2] = -sgn * M[j], -sgn * M[3 + j], -sgn * M[6 + j]
    else:
        sgn = 2.0 * (fa % 2) - 1.0
        out.axis, out.fa, out.fb, out.depth = AXIS_FACE_A, fa, -1, bestA
        u_out[0], u_out[1], u_out[2] = 0.0, 0.0, 0.0
        u_out[fa // 2] = sgn
    if ea >= 0 and bestE < out.depth - tie:
        out.axis, out.depth = AXIS_EDGE, bestE
        u_out[0], u_out[1], u_out[2] = uE[0], uE[1], uE[2]
        out.fa = _box_edge(A, ea, uE)
        mat_tvec(M, uE, w)
        w[0], w[1], w[2] = -w[0], -w[1], -w[2]
        out.fb = _box_edge(B, eb, w)
    return 1 if out.depth > 0.0 else 0


cdef inline double _face_a_value(const Polytope* A, const Polytope* B, const Frame* F, int f) noexcept nogil:
    """Value of A's face f: h_A(n_f) + h_B(-n_f) = sa d_f + h_B(-n_f)."""
    cdef double w[3]
    cdef const double* a = A.fnormal + 3 * f
    w[0] = -a[0]
    w[1] = -a[1]
    w[2] = -a[2]
    return F.sa * A.foffset[f] + _hB(B, F, w)


cdef inline double _face_b_value(const Polytope* A, const Polytope* B, const Frame* F, int g,
                                 const double* m) noexcept nogil:
    """Value of B's face g, m = M n_g (its outward normal in A's frame): h_A(-m) + m.t + sb d_g."""
    cdef double w[3]
    w[0] = -m[0]
    w[1] = -m[1]
    w[2] = -m[2]
    return _hA(A, F.sa, w) + _dot(m, F.t) + F.sb * B.foffset[g]


cdef inline double _edge_value(const Polytope* A, const Polytope* B, const Frame* F, int i, const double* qb0,
                               const double* eB, double eb2, const double* a, const double* b, double* u,
                               double* d) noexcept nogil:
    """Axis u (unit, oriented into arc (a, b) of A's edge i) and value d of A's edge i against B's edge from
    qb0 along eB (A's frame, eb2 = eB.eB) when their arcs cross; returns the squared sine of their angle (no
    axis when <= SAT_PARALLEL^2)."""
    cdef const double* va0 = A.verts + 3 * A.edges[2 * i]
    cdef const double* va1 = A.verts + 3 * A.edges[2 * i + 1]
    cdef double eA[3]
    cdef double w[3]
    cdef double ea2, l2, s2
    eA[0] = F.sa * (va1[0] - va0[0])
    eA[1] = F.sa * (va1[1] - va0[1])
    eA[2] = F.sa * (va1[2] - va0[2])
    ea2 = _dot(eA, eA)
    _cross(eA, eB, u)
    l2 = _dot(u, u)
    s2 = l2 / (ea2 * eb2)
    if s2 <= SAT_PARALLEL * SAT_PARALLEL:
        return s2
    l2 = 1.0 / sqrt(l2)
    u[0] *= l2
    u[1] *= l2
    u[2] *= l2
    if u[0] * (a[0] + b[0]) + u[1] * (a[1] + b[1]) + u[2] * (a[2] + b[2]) < 0.0:
        u[0] = -u[0]
        u[1] = -u[1]
        u[2] = -u[2]
    if s2 < SAT_SMALLSIN * SAT_SMALLSIN:
        w[0] = -u[0]
        w[1] = -u[1]
        w[2] = -u[2]
        d[0] = _hA(A, F.sa, u) + _hB(B, F, w)
    else:
        d[0] = (u[0] * (F.sa * va0[0] - qb0[0]) + u[1] * (F.sa * va0[1] - qb0[1])
                + u[2] * (F.sa * va0[2] - qb0[2]))
    return s2


cdef inline bint _arcs_cross(const double* a, const double* b, const double* c, const double* dd) noexcept nogil:
    """Gregorius' test: arc (a, b) of A and arc (c, d) of B (B's normals negated) cross (the edge loop of
    _sat_frame runs the same products, split to reuse them)."""
    cdef double DxC[3]
    cdef double BxA[3]
    cdef double ADC, BDC, CBA, DBA
    _cross(dd, c, DxC)
    ADC = _dot(a, DxC)
    BDC = _dot(b, DxC)
    if not ADC * BDC < 0.0:
        return False
    _cross(b, a, BxA)
    CBA = _dot(c, BxA)
    DBA = _dot(dd, BxA)
    return CBA * DBA < 0.0 and CBA * BDC > 0.0


cdef inline void _keep2(double* m1, double* m2, double x) noexcept nogil:
    """The two smallest values seen."""
    if x < m1[0]:
        m2[0] = m1[0]
        m1[0] = x
    elif x < m2[0]:
        m2[0] = x


cdef int _sat_frame(const Polytope* A, const Polytope* B, const Frame* F, double* u_out, SatResult* out,
                    double* cert) noexcept nogil:
    """The separating-axis minimum in A's frame: out (depth, axis, fa, fb) and u_out (from A towards B).
    Returns 1 when depth > 0 (overlap). Two boxes take the closed-form path _sat_box. With cert (not
    NULL), cert[0] receives how far the two bodies may move (sum of their `move`) with this axis staying
    the minimum (_budget; 0: no such certificate), the edge slab then widened by CERT_SLAB L."""
    if A.half != NULL and B.half != NULL:
        return _sat_box(A, B, F, u_out, out)
    cdef double tie = SAT_TIE * F.L
    cdef double bestA = INFINITY, bestB = INFINITY, bestE = INFINITY, d, l2, ea2, eb2
    cdef int fa = -1, fb = -1, ea = -1, eb = -1, f, g, i, j
    cdef double u[3]
    cdef double m[3]
    cdef double uA[3]
    cdef double uB[3]
    cdef double uE[3]
    cdef double c[3]
    cdef double dd[3]
    cdef double DxC[3]
    cdef double eB[3]
    cdef double eA[3]
    cdef double w[3]
    cdef const double* a
    cdef const double* b
    cdef const double* va0
    cdef const double* va1
    cdef const double* qb0
    cdef const double* qb1
    cdef const double* bxa
    cdef double CBA, DBA, ADC, BDC, s2, lim, slab, hwA, hwB, pa, pb
    cdef double sw[3]              # the best face axis (the slab's direction)
    cdef int cand[EDGE_BUF]
    # per pair, computed once rather than per edge: B's vertices and face normals in A's frame (qb, mb), and
    # for A's candidate edges their face normals a, b and b x a, side by side (AC)
    cdef double qb[3 * SUPPORT_BUF]
    cdef double mb[3 * SUPPORT_BUF]
    cdef double AC[9 * EDGE_BUF]
    cdef double lv[SUPPORT_BUF]    # vertex levels along the slab's direction
    cdef double qt0[3]
    cdef double qt1[3]
    cdef bint keep_qb = B.nv <= SUPPORT_BUF, keep_mb = B.nf <= SUPPORT_BUF, small_a = A.ne <= EDGE_BUF
    cdef int nca, ne_b, ii, k, na
    cdef double pq[3]              # A's vertex farthest towards B's centre (scaled), and B's towards A's
    cdef double qp[3]
    cdef double x, xbest
    cdef double min1 = INFINITY, min2 = INFINITY    # the two smallest candidate values (or bounds), for cert
    # A face's value is at least what one vertex of B gives instead of B's support (and alike for B's
    # faces): with the vertex of each body that reaches farthest towards the other's centre, that bound
    # skips the faces turned away, whose value cannot replace the best of their family (bound >= best, a
    # whole tie above the round-off of the bound: same answer as evaluating them)
    if keep_qb:
        xbest = INFINITY
        for k in range(B.nv):
            _b_point(B, F, k, &qb[3 * k])
            x = _dot(F.t, &qb[3 * k])
            if x < xbest:
                xbest = x
                qp[0], qp[1], qp[2] = qb[3 * k], qb[3 * k + 1], qb[3 * k + 2]
        xbest = -INFINITY
        for k in range(A.nv):
            x = _dot(F.t, A.verts + 3 * k)
            if x > xbest:
                xbest = x
                pq[0], pq[1], pq[2] = F.sa * A.verts[3 * k], F.sa * A.verts[3 * k + 1], F.sa * A.verts[3 * k + 2]
    # faces of A: u = n_f, h_A(u) = sa d_f
    for f in range(A.nf):
        a = A.fnormal + 3 * f
        w[0] = -a[0]
        w[1] = -a[1]
        w[2] = -a[2]
        if keep_qb:
            d = F.sa * A.foffset[f] + _dot(w, qp)
            if d >= bestA:
                if cert != NULL:
                    _keep2(&min1, &min2, d)
                continue
        d = _face_a_value(A, B, F, f)
        if cert != NULL:
            _keep2(&min1, &min2, d)
        if d < bestA - tie:
            bestA = d
            fa = f
            uA[0] = a[0]
            uA[1] = a[1]
            uA[2] = a[2]
    # faces of B: m = M n_g (outward of B, in A's frame), u = -m, h_B(-u) = m.t + sb d_g
    for g in range(B.nf):
        mat_vec(F.M, B.fnormal + 3 * g, m)
        if keep_mb:
            mb[3 * g], mb[3 * g + 1], mb[3 * g + 2] = m[0], m[1], m[2]
        w[0] = -m[0]
        w[1] = -m[1]
        w[2] = -m[2]
        if keep_qb:
            d = _dot(w, pq) + _dot(m, F.t) + F.sb * B.foffset[g]
            if d >= bestB:
                if cert != NULL:
                    _keep2(&min1, &min2, d)
                continue
        d = _face_b_value(A, B, F, g, m)
        if cert != NULL:
            _keep2(&min1, &min2, d)
        if d < bestB - tie:
            bestB = d
            fb = g
            uB[0] = w[0]
            uB[1] = w[1]
            uB[2] = w[2]
    # edge pairs whose Gauss-map arcs cross: (a, b) of A against (c, d) = (-M n_f0, -M n_f1) of B. A face
    # axis with a value <= 0 separates the bodies: no edge pair is needed. Otherwise the depth delta is at
    # most lim, the best face value, along the axis w (sw) with h_A(w) + h_B(-w) = lim; at the minimum facet
    # the two edges touch once A is moved out by delta, so A's edge reaches w.x >= h_A(w) - lim - delta
    # and B's edge w.x <= -h_B(-w) + lim + delta: only edges reaching into that slab (2 lim deep, plus the
    # tie tolerance) are paired (exact; dense packings have shallow contacts, so few edges qualify)
    if bestA <= bestB:
        lim = bestA
        sw[0], sw[1], sw[2] = uA[0], uA[1], uA[2]
        hwA = F.sa * A.foffset[fa]
    else:
        lim = bestB
        sw[0], sw[1], sw[2] = uB[0], uB[1], uB[2]
        hwA = _hA(A, F.sa, sw)
    ne_b = B.ne if lim > 0.0 else 0
    slab = 2.0 * lim + 4.0 * tie
    if cert != NULL and ne_b:             # pruned pairs are then above lim + CERT_SLAB L + 4 tie
        slab += CERT_SLAB * F.L
        _keep2(&min1, &min2, lim + CERT_SLAB * F.L + 4.0 * tie)
    nca = 0
    if ne_b and small_a:                  # (a larger A pairs all its edges)
        if A.nv <= SUPPORT_BUF:           # each vertex's level along w once, not per edge
            for k in range(A.nv):
                lv[k] = F.sa * _dot(sw, A.verts + 3 * k)
        for i in range(A.ne):
            if A.nv <= SUPPORT_BUF:
                pa = lv[A.edges[2 * i]]
                pb = lv[A.edges[2 * i + 1]]
            else:
                pa = F.sa * _dot(sw, A.verts + 3 * A.edges[2 * i])
                pb = F.sa * _dot(sw, A.verts + 3 * A.edges[2 * i + 1])
            if (pa if pa > pb else pb) >= hwA - slab:
                cand[nca] = i
                a = A.fnormal + 3 * A.efaces[2 * i]
                b = A.fnormal + 3 * A.efaces[2 * i + 1]
                for k in range(3):
                    AC[9 * nca + k] = a[k]
                    AC[9 * nca + 3 + k] = b[k]
                _cross(b, a, &AC[9 * nca + 6])
                nca += 1
    na = nca if small_a else A.ne
    hwB = hwA - lim                       # -h_B(-w): B's lowest value along w
    if ne_b and keep_qb:
        for k in range(B.nv):
            lv[k] = _dot(sw, &qb[3 * k])
    for j in range(ne_b):
        if keep_qb:
            qb0 = &qb[3 * B.edges[2 * j]]
            qb1 = &qb[3 * B.edges[2 * j + 1]]
            pa = lv[B.edges[2 * j]]
            pb = lv[B.edges[2 * j + 1]]
        else:
            _b_point(B, F, B.edges[2 * j], qt0)
            _b_point(B, F, B.edges[2 * j + 1], qt1)
            qb0 = qt0
            qb1 = qt1
            pa = _dot(sw, qb0)
            pb = _dot(sw, qb1)
        if (pa if pa < pb else pb) > hwB + slab:
            continue
        if keep_mb:
            c[0], c[1], c[2] = mb[3 * B.efaces[2 * j]], mb[3 * B.efaces[2 * j] + 1], mb[3 * B.efaces[2 * j] + 2]
            dd[0], dd[1], dd[2] = (mb[3 * B.efaces[2 * j + 1]], mb[3 * B.efaces[2 * j + 1] + 1],
                                   mb[3 * B.efaces[2 * j + 1] + 2])
        else:
            mat_vec(F.M, B.fnormal + 3 * B.efaces[2 * j], c)
            mat_vec(F.M, B.fnormal + 3 * B.efaces[2 * j + 1], dd)
        for i in range(3):
            c[i] = -c[i]
            dd[i] = -dd[i]
        _cross(dd, c, DxC)
        eB[0] = qb1[0] - qb0[0]
        eB[1] = qb1[1] - qb0[1]
        eB[2] = qb1[2] - qb0[2]
        eb2 = _dot(eB, eB)
        for ii in range(na):
            if small_a:
                a = &AC[9 * ii]
                b = &AC[9 * ii + 3]
            else:
                a = A.fnormal + 3 * A.efaces[2 * ii]
                b = A.fnormal + 3 * A.efaces[2 * ii + 1]
            ADC = _dot(a, DxC)
            BDC = _dot(b, DxC)
            if not ADC * BDC < 0.0:
                continue
            if small_a:
                i = cand[ii]
                bxa = &AC[9 * ii + 6]
            else:
                i = ii
                _cross(b, a, m)
                bxa = m
            CBA = _dot(c, bxa)
            DBA = _dot(dd, bxa)
            if not (CBA * DBA < 0.0 and CBA * BDC > 0.0):
                continue
            s2 = _edge_value(A, B, F, i, qb0, eB, eb2, a, b, u, &d)
            if s2 <= SAT_PARALLEL * SAT_PARALLEL:
                continue
            if cert != NULL:
                _keep2(&min1, &min2, d)
            if d < bestE - tie:
                bestE = d
                ea = i
                eb = j
                uE[0] = u[0]
                uE[1] = u[1]
                uE[2] = u[2]
    # faces of A over faces of B, faces over edges, within the tie tolerance
    if fb >= 0 and (fa < 0 or bestB < bestA - tie):
        out.axis, out.fa, out.fb, out.depth = AXIS_FACE_B, -1, fb, bestB
        u_out[0], u_out[1], u_out[2] = uB[0], uB[1], uB[2]
    elif fa >= 0:
        out.axis, out.fa, out.fb, out.depth = AXIS_FACE_A, fa, -1, bestA
        u_out[0], u_out[1], u_out[2] = uA[0], uA[1], uA[2]
    else:
        out.axis, out.fa, out.fb, out.depth = AXIS_NONE, -1, -1, -INFINITY
        u_out[0], u_out[1], u_out[2] = 0.0, 0.0, 1.0
        return 0
    if ea >= 0 and bestE < out.depth - tie:
        out.axis, out.fa, out.fb, out.depth = AXIS_EDGE, ea, eb, bestE
        u_out[0], u_out[1], u_out[2] = uE[0], uE[1], uE[2]
    if cert != NULL:
        cert[0] = 0.0
        if keep_qb and out.depth > 0.0 and min1 == out.depth and min2 > min1:
            cert[0] = _budget(A, B, F, out, u_out, min2 - min1, qb)
    return 1 if out.depth > 0.0 else 0


cdef inline int _lead(const double* pts, int n, double s, const double* u, double* lead) noexcept nogil:
    """The point of largest s u.p among n points (3 values each); lead receives its margin over the next."""
    cdef double top = -INFINITY, sec = -INFINITY, x
    cdef int k, best = -1
    for k in range(n):
        x = s * _dot(u, pts + 3 * k)
        if x > top:
            sec = top
            top = x
            best = k
        elif x > sec:
            sec = x
    lead[0] = top - sec
    return best


cdef double _budget(const Polytope* A, const Polytope* B, const Frame* F, const SatResult* out,
                    const double* u0, double gap, const double* qb) noexcept nogil:
    """How far the bodies may move (mu = the sum of their `move`, dem_convex.poses: how far any point of
    each moved) with the winning axis of out staying the strict minimum, its value below every other
    facet's by more than 8 ties: then the full test would choose it again, with the same value and normal
    (_sat_cached computes them by the same code). At the minimum (value V0 > 0, normal u0, gap = the next
    candidate's value or bound minus V0):
    * B's points move in A's frame by D <= kappa mu, kappa = 2.5 + 2 r_max / r_min, and the bodies turn
      relative to each other by phi <= 1.6 mu / r_min; a facet whose normal turns by w changes by at most
      D + 2 L w: faces of A (w = 0), faces of B (phi), edge pairs (2 phi / sin, fast for parallel edges);
      the winner itself by at most D + w (V0 + D) (its value is u.y at the pair of material points whose
      difference y was the foot V0 u0; mu is kept below r_min / (100 kappa), so that w D <= 0.016 w mu);
    * every facet other than the winner: either its normal lies outside the cap of angle alpha around
      u0, where the support function at the start is >= min(V0 + gap, V0 cos alpha + rho sin alpha)
      (its minima are facet normals, or on the cap's rim, where the disk of radius rho around the foot of
      the origin in the winning facet bounds it), so it stays above that minus D; or inside the cap, where
      the winning features stay each body's only support (their lead eps over the other vertices exceeds
      2 r alpha + 2 D), so that no other arc, face normal or crossing enters: only slow faces, bounded
      by the gap.
    Returns the smallest mu allowed by these conditions (0: none)."""
    cdef double ra = F.sa * A.radius, rb = F.sb * B.radius, rmin, kappa, w, m, V0 = out.depth
    cdef double rho = INFINITY, eps, epsA = INFINITY, epsB = INFINITY, alpha, c3 = INFINITY, x, sec
    cdef double p[3]
    cdef double e[3]
    cdef double y[3]
    cdef double eA[3]
    cdef double eB[3]
    cdef double nn[3]
    cdef double ab, aa, bb, ay, by, det, sr, rr, sn, budget
    cdef const double* v0
    cdef const double* v1
    cdef int k, n, vtop = -1, i, j, first
    rmin = ra if ra < rb else rb
    kappa = 2.5 + 2.0 * (ra if ra > rb else rb) / rmin
    m = 8.0 * SAT_TIE * F.L
    if out.axis == AXIS_FACE_A:
        vtop = _lead(qb, B.nv, -1.0, u0, &epsB)     # B's support along -u0 and its lead
        for k in range(3):             # the vertex projected on face fa, and its inset in that polygon
            p[k] = qb[3 * vtop + k] + V0 * u0[k]
        first = A.ffirst[out.fa]
        n = A.fcount[out.fa]
        for k in range(n):
            v0 = A.verts + 3 * A.fverts[first + k]
            v1 = A.verts + 3 * A.fverts[first + (k + 1) % n]
            for i in range(3):
                e[i] = F.sa * (v1[i] - v0[i])
                y[i] = p[i] - F.sa * v0[i]
            _cross(u0, e, nn)          # inward in the face's plane (counter-clockwise from outside)
            x = _dot(nn, y) / sqrt(_dot(e, e))
            if x < rho:
                rho = x
        w = 0.0
    elif out.axis == AXIS_FACE_B:
        vtop = _lead(A.verts, A.nv, F.sa, u0, &epsA)     # A's support along u0 and its lead
        for k in range(3):
            p[k] = F.sa * A.verts[3 * vtop + k] - V0 * u0[k]
            nn[k] = -u0[k]             # B's outward normal
        first = B.ffirst[out.fb]
        n = B.fcount[out.fb]
        for k in range(n):
            v0 = &qb[3 * B.fverts[first + k]]
            v1 = &qb[3 * B.fverts[first + (k + 1) % n]]
            for i in range(3):
                e[i] = v1[i] - v0[i]
                y[i] = p[i] - v0[i]
            _cross(nn, e, eA)
            x = _dot(eA, y) / sqrt(_dot(e, e))
            if x < rho:
                rho = x
        w = 1.0
    else:
        i = out.fa
        j = out.fb
        sec = -INFINITY                # A's lead of edge i along u0, B's of edge j along -u0
        for k in range(A.nv):
            if k != A.edges[2 * i] and k != A.edges[2 * i + 1]:
                x = F.sa * _dot(u0, A.verts + 3 * k)
                if x > sec:
                    sec = x
        epsA = F.sa * _dot(u0, A.verts + 3 * A.edges[2 * i]) - sec
        x = F.sa * _dot(u0, A.verts + 3 * A.edges[2 * i + 1]) - sec
        if x < epsA:
            epsA = x
        sec = -INFINITY
        for k in range(B.nv):
            if k != B.edges[2 * j] and k != B.edges[2 * j + 1]:
                x = -_dot(u0, &qb[3 * k])
                if x > sec:
                    sec = x
        epsB = -_dot(u0, &qb[3 * B.edges[2 * j]]) - sec
        x = -_dot(u0, &qb[3 * B.edges[2 * j + 1]]) - sec
        if x < epsB:
            epsB = x
        v0 = A.verts + 3 * A.edges[2 * i]
        v1 = A.verts + 3 * A.edges[2 * i + 1]
        for k in range(3):             # the foot V0 u0 = (a0 + s eA) - (b0 + r eB): s, r in (0, 1)
            eA[k] = F.sa * (v1[k] - v0[k])
            eB[k] = qb[3 * B.edges[2 * j + 1] + k] - qb[3 * B.edges[2 * j] + k]
            y[k] = V0 * u0[k] - F.sa * v0[k] + qb[3 * B.edges[2 * j] + k]
        aa = _dot(eA, eA)
        bb = _dot(eB, eB)
        ab = _dot(eA, eB)
        ay = _dot(eA, y)
        by = _dot(eB, y)
        det = ab * ab - aa * bb
        if not det < 0.0:
            return 0.0
        sr = (ab * by - bb * ay) / det
        rr = (aa * by - ab * ay) / det
        sn = sqrt(-det / (aa * bb))    # sin of the edges' angle
        rho = sqrt(aa) * (sr if sr < 1.0 - sr else 1.0 - sr)
        x = sqrt(bb) * (rr if rr < 1.0 - rr else 1.0 - rr)
        rho = sn * (rho if rho < x else x)
        w = 2.25 / sn                  # (2 / sin, with the sine kept above 0.9 its start: c3 below)
        c3 = 0.1 * sn * rmin / 1.6
    # the cap: A's lead (fixed in A's frame) bounds it alone; B's lead is shared between the cap and B's
    # motion, split where the rim term and B's term allow the same budget
    alpha = 0.5
    if epsA < INFINITY:
        alpha = 0.45 * epsA / ra
    if epsB < INFINITY:
        x = epsB / (2.0 * rb + 2.0 * kappa * rho / (2.0 * kappa + 1.6 * w * V0 / rmin + 0.016 * w))
        if x < alpha:
            alpha = x
    if alpha > 0.5:
        alpha = 0.5
    if not (rho > 0.0 and alpha > 0.0):
        return 0.0
    if epsB < INFINITY:                # B's lead also pays for B's motion in A's frame (2 D)
        x = (epsB - 2.0 * rb * alpha) / (2.0 * kappa)
        if x < c3:
            c3 = x
    x = 1.6 * w * V0 / rmin + 0.016 * w             # the winner's turn, per mu
    budget = (gap - m) / (2.0 * kappa + 3.2 * F.L / rmin + x)
    if 0.01 * rmin / kappa < budget:
        budget = 0.01 * rmin / kappa
    x = (rho * sin(alpha) - V0 * (1.0 - cos(alpha)) - m) / (2.0 * kappa + x)
    if x < budget:
        budget = x
    if c3 < budget:
        budget = c3
    return budget if budget > 0.0 else 0.0


cdef int _sat_cached(const Polytope* A, const Polytope* B, const Frame* F, int code, double* u_out,
                     SatResult* out) noexcept nogil:
    """The axis of a pair's certificate (code: 1 + face of A, 1 + nf_A + face of B, 1 + nf_A + nf_B + edge
    of A + ne_A edge of B) evaluated alone, by the code of _sat_frame (same value and normal); returns 0
    when the code does not fit these bodies or the edges' arcs no longer cross (then run _sat_frame)."""
    cdef double m[3]
    cdef double c[3]
    cdef double dd[3]
    cdef double qb0[3]
    cdef double qb1[3]
    cdef double eB[3]
    cdef double d
    cdef const double* a
    cdef const double* b
    cdef int i, j, k = code - 1
    if A.half != NULL and B.half != NULL:
        return 0
    if 0 <= k < A.nf:
        out.axis, out.fa, out.fb, out.depth = AXIS_FACE_A, k, -1, _face_a_value(A, B, F, k)
        a = A.fnormal + 3 * k
        u_out[0], u_out[1], u_out[2] = a[0], a[1], a[2]
        return 1
    k -= A.nf
    if 0 <= k < B.nf:
        mat_vec(F.M, B.fnormal + 3 * k, m)
        out.axis, out.fa, out.fb, out.depth = AXIS_FACE_B, -1, k, _face_b_value(A, B, F, k, m)
        u_out[0], u_out[1], u_out[2] = -m[0], -m[1], -m[2]
        return 1
    k -= B.nf
    if not 0 <= k < A.ne * B.ne:
        return 0
    i = k % A.ne
    j = k // A.ne
    a = A.fnormal + 3 * A.efaces[2 * i]
    b = A.fnormal + 3 * A.efaces[2 * i + 1]
    mat_vec(F.M, B.fnormal + 3 * B.efaces[2 * j], c)
    mat_vec(F.M, B.fnormal + 3 * B.efaces[2 * j + 1], dd)
    for k in range(3):
        c[k] = -c[k]
        dd[k] = -dd[k]
    if not _arcs_cross(a, b, c, dd):
        return 0
    _b_point(B, F, B.edges[2 * j], qb0)
    _b_point(B, F, B.edges[2 * j + 1], qb1)
    eB[0] = qb1[0] - qb0[0]
    eB[1] = qb1[1] - qb0[1]
    eB[2] = qb1[2] - qb0[2]
    if _edge_value(A, B, F, i, qb0, eB, _dot(eB, eB), a, b, u_out, &d) <= SAT_PARALLEL * SAT_PARALLEL:
        return 0
    out.axis, out.fa, out.fb, out.depth = AXIS_EDGE, i, j, d
    return 1


cdef int sat_penetration(const Polytope* A, const double* Ra, double sa, const double* xa,
                         const Polytope* B, const double* Rb, double sb, const double* xb,
                         SatResult* out) noexcept nogil:
    """Minimum-penetration axis of A and B (pure rotations Ra, Rb, scales sa, sb, centres xa, xb): fills
    out (depth, n from B to A in the world, axis, fa, fb); returns 1 when they overlap (depth > 0), else 0
    (then -depth >= 0 is the gap along a candidate axis that separates them: a lower bound of their distance)."""
    cdef Frame F
    cdef double u[3]
    cdef int hit
    _frame(A, Ra, sa, xa, B, Rb, sb, xb, &F)
    hit = _sat_frame(A, B, &F, u, out, NULL)
    mat_vec(Ra, u, out.n)
    out.n[0] = -out.n[0]
    out.n[1] = -out.n[1]
    out.n[2] = -out.n[2]
    return hit


# ---------------------------------------------------------------- contact points
cdef inline double _orient(const double* o, const double* a, const double* b) noexcept nogil:
    """2D cross (a - o) x (b - o)."""
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


cdef int _hull2(double* P, int n, double tol) noexcept nogil:
    """Convex hull of the 2D points P[2k], P[2k+1] (k < n), in place, counter-clockwise from the
    lexicographically lowest point; points closer than tol to the hull's sides or to each other are dropped.
    Returns the hull size (1, 2 or >= 3)."""
    cdef double H[2 * (2 * POLY_MAXFEAT + 2)]
    cdef int i, j, k, m, lo
    cdef double x, y, dx, dy
    # insertion sort by (x, y): deterministic, n small
    for i in range(1, n):
        x = P[2 * i]
        y = P[2 * i + 1]
        j = i - 1
        while j >= 0 and (P[2 * j] > x or (P[2 * j] == x and P[2 * j + 1] > y)):
            P[2 * j + 2] = P[2 * j]
            P[2 * j + 3] = P[2 * j + 1]
            j -= 1
        P[2 * j + 2] = x
        P[2 * j + 3] = y
    # drop repeated points
    m = 1
    for i in range(1, n):
        dx = P[2 * i] - P[2 * (m - 1)]
        dy = P[2 * i + 1] - P[2 * (m - 1) + 1]
        if fabs(dx) + fabs(dy) > tol:
            P[2 * m] = P[2 * i]
            P[2 * m + 1] = P[2 * i + 1]
            m += 1
    n = m
    if n <= 2:
        return n
    # Andrew's monotone chain; a turn counts only if the point is farther than tol from the chord
    k = 0
    for i in range(n):
        while k >= 2 and _orient(&H[2 * (k - 2)], &H[2 * (k - 1)], &P[2 * i]) <= tol * (
                fabs(P[2 * i] - H[2 * (k - 2)]) + fabs(P[2 * i + 1] - H[2 * (k - 2) + 1])):
            k -= 1
        H[2 * k] = P[2 * i]
        H[2 * k + 1] = P[2 * i + 1]
        k += 1
    lo = k + 1
    for i in range(n - 2, -1, -1):
        while k >= lo and _orient(&H[2 * (k - 2)], &H[2 * (k - 1)], &P[2 * i]) <= tol * (
                fabs(P[2 * i] - H[2 * (k - 2)]) + fabs(P[2 * i + 1] - H[2 * (k - 2) + 1])):
            k -= 1
        H[2 * k] = P[2 * i]
        H[2 * k + 1] = P[2 * i + 1]
        k += 1
    k -= 1                      # the last point is the first again
    if k < 2:
        k = 2 if n >= 2 else 1  # all collinear: the two extreme points
        if k == 2:
            H[2] = P[2 * (n - 1)]
            H[3] = P[2 * (n - 1) + 1]
    for i in range(2 * k):
        P[i] = H[i]
    return k


cdef int _clean_ring(double* P, int n, double tol) noexcept nogil:
    """The counter-clockwise convex ring P (n >= 3, as clipping leaves it) without its repeated corners
    (closer than tol, wrap-around included) and its straight ones (within tol of the chord, as _hull2):
    _hull2's result up to the starting point (which _canonical sets) in a linear pass. A ring that does not
    stay a proper polygon (round-off) goes through _hull2."""
    cdef double Q[2 * (4 * POLY_MAXFEAT + 4)]
    cdef int i, m = 0, k, changed
    for i in range(n):
        if m == 0 or fabs(P[2 * i] - Q[2 * m - 2]) + fabs(P[2 * i + 1] - Q[2 * m - 1]) > tol:
            Q[2 * m] = P[2 * i]
            Q[2 * m + 1] = P[2 * i + 1]
            m += 1
    while m > 1 and fabs(Q[0] - Q[2 * m - 2]) + fabs(Q[1] - Q[2 * m - 1]) <= tol:
        m -= 1
    changed = 1
    while changed and m >= 3:
        changed = 0
        for i in range(m):
            k = (i + m - 1) % m
            if _orient(&Q[2 * k], &Q[2 * i], &Q[2 * ((i + 1) % m)]) <= tol * (
                    fabs(Q[2 * ((i + 1) % m)] - Q[2 * k]) + fabs(Q[2 * ((i + 1) % m) + 1] - Q[2 * k + 1])):
                for k in range(i, m - 1):
                    Q[2 * k] = Q[2 * k + 2]
                    Q[2 * k + 1] = Q[2 * k + 3]
                m -= 1
                changed = 1
                break
    if m < 3:
        return _hull2(P, n, tol)
    for i in range(2 * m):
        P[i] = Q[i]
    return m


cdef int _clip_poly(const double* S, int ns, const double* C, int nc, double* out, double tol) noexcept nogil:
    """Sutherland-Hodgman: the convex polygon S (ns, CCW) clipped by the convex polygon C (nc, CCW);
    returns the count written to out (room for ns + nc points)."""
    cdef double buf0[2 * (4 * POLY_MAXFEAT + 4)]
    cdef double buf1[2 * (4 * POLY_MAXFEAT + 4)]
    cdef double dist[4 * POLY_MAXFEAT + 4]
    cdef double* src = buf0
    cdef double* dst = buf1
    cdef double* tmp
    cdef int n = ns, m, i, e, k
    cdef double ex, ey, ln, dp, dq, s
    cdef const double* c0
    cdef const double* c1
    cdef const double* p
    cdef const double* q
    for i in range(2 * ns):
        src[i] = S[i]
    for e in range(nc):
        c0 = C + 2 * e
        c1 = C + 2 * ((e + 1) % nc)
        ex = c1[0] - c0[0]
        ey = c1[1] - c0[1]
        ln = sqrt(ex * ex + ey * ey)
        if ln == 0.0:
            continue
        m = 0
        # signed distances to the clip line, > 0 inside (left of c0 -> c1); inside within tol, the
        # crossing on the line itself
        for i in range(n):
            p = src + 2 * i
            dist[i] = (ex * (p[1] - c0[1]) - ey * (p[0] - c0[0])) / ln
        for i in range(n):
            p = src + 2 * i
            q = src + 2 * ((i + 1) % n)
            dp = dist[i]
            dq = dist[(i + 1) % n]
            if dp >= -tol:
                dst[2 * m] = p[0]
                dst[2 * m + 1] = p[1]
                m += 1
                if dq < -tol:
                    s = dp / (dp - dq) if dp > 0.0 else 0.0
                    if s > 0.0:
                        dst[2 * m] = p[0] + s * (q[0] - p[0])
                        dst[2 * m + 1] = p[1] + s * (q[1] - p[1])
                        m += 1
            elif dq > 0.0:             # (q within tol of the line: q itself is the crossing, kept next)
                s = dp / (dp - dq)
                dst[2 * m] = p[0] + s * (q[0] - p[0])
                dst[2 * m + 1] = p[1] + s * (q[1] - p[1])
                m += 1
        n = m
        tmp = src
        src = dst
        dst = tmp
        if n == 0:
            return 0
    for i in range(2 * n):
        out[i] = src[i]
    return n


cdef int _clip_segment(const double* S, const double* C, int nc, double* out, double tol) noexcept nogil:
    """Cyrus-Beck: the segment S[0..1] -> S[2..3] clipped by the convex polygon C (nc, CCW); 0 or 2 points."""
    cdef double t0 = 0.0, t1 = 1.0, ex, ey, ln, dp, dq, s
    cdef int e
    cdef const double* c0
    cdef const double* c1
    for e in range(nc):
        c0 = C + 2 * e
        c1 = C + 2 * ((e + 1) % nc)
        ex = c1[0] - c0[0]
        ey = c1[1] - c0[1]
        ln = sqrt(ex * ex + ey * ey)
        if ln == 0.0:
            continue
        dp = (ex * (S[1] - c0[1]) - ey * (S[0] - c0[0])) / ln
        dq = (ex * (S[3] - c0[1]) - ey * (S[2] - c0[0])) / ln
        if dp < -tol and dq < -tol:
            return 0
        if dp < -tol:
            s = dp / (dp - dq) if dq > 0.0 else 1.0
            if s > t0:
                t0 = s
        elif dq < -tol:
            s = dp / (dp - dq) if dp > 0.0 else 0.0
            if s < t1:
                t1 = s
    if t0 > t1:
        return 0
    out[0] = S[0] + t0 * (S[2] - S[0])
    out[1] = S[1] + t0 * (S[3] - S[1])
    out[2] = S[0] + t1 * (S[2] - S[0])
    out[3] = S[1] + t1 * (S[3] - S[1])
    return 2


cdef int _segments(const double* S, const double* T, double* out, double tol, bint* crossing) noexcept nogil:
    """Two 2D segments: their crossing point (1, crossing set) or, parallel, their common interval (2 or 1;
    0 when apart). A crossing outside the segments (tolerance of the features) is clamped into both."""
    cdef double dx = S[2] - S[0], dy = S[3] - S[1], ex = T[2] - T[0], ey = T[3] - T[1]
    cdef double den = dx * ey - dy * ex, ls = sqrt(dx * dx + dy * dy), lt = sqrt(ex * ex + ey * ey)
    cdef double s, t, a0, a1, lo, hi, ll
    crossing[0] = False
    if ls == 0.0 or lt == 0.0:
        return 0
    if fabs(den) > 1e-9 * ls * lt:
        s = ((T[0] - S[0]) * ey - (T[1] - S[1]) * ex) / den
        t = ((T[0] - S[0]) * dy - (T[1] - S[1]) * dx) / den
        s = 0.0 if s < 0.0 else (1.0 if s > 1.0 else s)
        t = 0.0 if t < 0.0 else (1.0 if t > 1.0 else t)
        out[0] = 0.5 * (S[0] + s * dx + T[0] + t * ex)
        out[1] = 0.5 * (S[1] + s * dy + T[1] + t * ey)
        crossing[0] = True
        return 1
    # parallel: T's ends as parameters along S
    ll = ls * ls
    a0 = ((T[0] - S[0]) * dx + (T[1] - S[1]) * dy) / ll
    a1 = ((T[2] - S[0]) * dx + (T[3] - S[1]) * dy) / ll
    lo = a0 if a0 < a1 else a1
    hi = a1 if a0 < a1 else a0
    if lo < 0.0:
        lo = 0.0
    if hi > 1.0:
        hi = 1.0
    if hi < lo - tol / ls:
        return 0
    if hi < lo:
        hi = lo
    out[0] = S[0] + lo * dx
    out[1] = S[1] + lo * dy
    if (hi - lo) * ls <= tol:
        return 1
    out[2] = S[0] + hi * dx
    out[3] = S[1] + hi * dy
    return 2


cdef int _canonical(double* P, int n) noexcept nogil:
    """Rotate the (CCW) point list to start at its lexicographically lowest point; keep at most POLY_MAXP,
    evenly spaced; returns the count."""
    cdef double Q[2 * (4 * POLY_MAXFEAT + 4)]
    cdef int i, k = 0, m
    for i in range(1, n):
        if P[2 * i] < P[2 * k] or (P[2 * i] == P[2 * k] and P[2 * i + 1] < P[2 * k + 1]):
            k = i
    for i in range(n):
        Q[2 * i] = P[2 * ((i + k) % n)]
        Q[2 * i + 1] = P[2 * ((i + k) % n) + 1]
    m = n if n <= POLY_MAXP else POLY_MAXP
    for i in range(m):
        k = (i * n) // m
        P[2 * i] = Q[2 * k]
        P[2 * i + 1] = Q[2 * k + 1]
    return m


cdef inline void _corner(const double* half, int c, double* o) noexcept nogil:
    """Corner c of a box (bit k set: +half_k; box_topology's order)."""
    o[0] = (<double>(c & 1) * 2.0 - 1.0) * half[0]          # (times +-1: exact, and no branch on c)
    o[1] = (<double>((c >> 1) & 1) * 2.0 - 1.0) * half[1]
    o[2] = (<double>((c >> 2) & 1) * 2.0 - 1.0) * half[2]


cdef int FREE_COUNT[8]               # of a 3-bit mask: its set bits, the lowest, the second lowest
cdef int FREE_FIRST[8]
cdef int FREE_SECOND[8]
for _k in range(8):
    _bits = [_m for _m in range(3) if _k >> _m & 1]
    FREE_COUNT[_k] = len(_bits)
    FREE_FIRST[_k] = _bits[0] if _bits else -1
    FREE_SECOND[_k] = _bits[1] if len(_bits) > 1 else -1


cdef inline int _box_feature(const double* half, double s, const double* w, double ftol, int* c) noexcept nogil:
    """The corners of the box (half sides s half) within ftol of its support along w (box frame), as the
    general vertex loop selects them, in cyclic order: 1 (corner), 2 (edge) or 4 (face) corners. A corner
    falls short of the support by 2 s half_k |w_k| for each bit k it does not share with the supporting
    corner. Returns 0 for any other set (3 corners, or more than a face: a box thinner than ftol), which
    the general loop then takes."""
    cdef double d[3]
    cdef int k, c0 = 0, free = 0, a, b
    for k in range(3):                 # (no branches on the data: the bits are set from comparisons)
        c0 |= (w[k] > 0.0) << k
        d[k] = 2.0 * s * half[k] * fabs(w[k])
        free |= (d[k] <= ftol) << k
    c[0] = c0
    if free == 0:
        return 1
    a = FREE_FIRST[free]
    if FREE_COUNT[free] == 1:
        c[1] = c0 ^ (1 << a)
        return 2
    b = FREE_SECOND[free]
    if FREE_COUNT[free] == 2 and d[a] + d[b] <= ftol:
        c[1] = c0 ^ (1 << a)
        c[2] = c0 ^ (1 << a) ^ (1 << b)
        c[3] = c0 ^ (1 << b)
        return 4
    return 0


cdef int _box_ring(double* P, int n, double tol) noexcept nogil:
    """A box's feature projected on the contact plane (2 or 4 points in cyclic order) in _hull2's order:
    two points sorted by (x, y); a quadrilateral counter-clockwise from its lowest point. A feature seen
    edge-on (points or a corner within tol, a box thinner than tol) goes through _hull2."""
    cdef double Q[8]
    cdef double o
    cdef int i, k = 0, step
    if n == 2:
        if fabs(P[2] - P[0]) + fabs(P[3] - P[1]) <= tol:
            return _hull2(P, n, tol)
        if P[2] < P[0] or (P[2] == P[0] and P[3] < P[1]):
            Q[0], Q[1] = P[0], P[1]
            P[0], P[1] = P[2], P[3]
            P[2], P[3] = Q[0], Q[1]
        return 2
    for i in range(1, n):
        if P[2 * i] < P[2 * k] or (P[2 * i] == P[2 * k] and P[2 * i + 1] < P[2 * k + 1]):
            k = i
    for i in range(n):             # each corner farther than tol from the chord of its neighbours
        o = _orient(&P[2 * ((i + n - 1) % n)], &P[2 * i], &P[2 * ((i + 1) % n)])
        if fabs(o) <= tol * (fabs(P[2 * ((i + 1) % n)] - P[2 * ((i + n - 1) % n)])
                             + fabs(P[2 * ((i + 1) % n) + 1] - P[2 * ((i + n - 1) % n) + 1])):
            return _hull2(P, n, tol)
    step = 1 if o > 0.0 else n - 1
    for i in range(n):
        Q[2 * i] = P[2 * ((k + i * step) % n)]
        Q[2 * i + 1] = P[2 * ((k + i * step) % n) + 1]
    for i in range(2 * n):
        P[i] = Q[i]
    return n


cdef inline int _feature(const Polytope* P, double s, const double* w, double w0, const double* p1, double o1,
                         const double* p2, double o2, double ftol, double* out, double* h, bint* hull) noexcept nogil:
    """The contacting feature of body P (scale s) along w (its frame): the vertices whose support
    w0 + s w.v is within ftol of the largest, h, as plane points (o1 + s p1.v, o2 + s p2.v) in out; returns
    their count. A box takes them from its corner bits (_box_feature: in cyclic order, hull false), any
    other body from its vertex loop (hull true: _hull2 orders them)."""
    cdef double sv[SUPPORT_BUF]
    cdef double c[3]
    cdef double best = -INFINITY, x
    cdef int corners[4]
    cdef int k, n = 0
    cdef const double* v
    if P.half != NULL:
        n = _box_feature(P.half, s, w, ftol, corners)
        if n:
            h[0] = w0 + s * (P.half[0] * fabs(w[0]) + P.half[1] * fabs(w[1]) + P.half[2] * fabs(w[2]))
            for k in range(n):
                _corner(P.half, corners[k], c)
                out[2 * k] = o1 + s * _dot(p1, c)
                out[2 * k + 1] = o2 + s * _dot(p2, c)
            hull[0] = False
            return n
    for k in range(P.nv):
        x = w0 + s * _dot(w, P.verts + 3 * k)
        if k < SUPPORT_BUF:
            sv[k] = x
        if x > best:
            best = x
    for k in range(P.nv):
        v = P.verts + 3 * k
        x = sv[k] if k < SUPPORT_BUF else w0 + s * _dot(w, v)
        if x >= best - ftol and n < POLY_MAXFEAT:
            out[2 * n] = o1 + s * _dot(p1, v)
            out[2 * n + 1] = o2 + s * _dot(p2, v)
            n += 1
    h[0] = best
    hull[0] = True
    return n


cdef int _contact_frame(const Polytope* A, const Polytope* B, const Frame* F, const double* u, double depth,
                        double ftol, double* pts, int* nfa, int* nfb, double* t1, double* t2,
                        double* cplane) noexcept nogil:
    """The contact points in plane coordinates (pts, 2 per point) in A's frame; returns the type, sets the
    count in nfa[1]... (see contact_points)."""
    cdef double PA[2 * (2 * POLY_MAXFEAT + 2)]
    cdef double PB[2 * (2 * POLY_MAXFEAT + 2)]
    cdef double W[2 * (4 * POLY_MAXFEAT + 4)]
    cdef double ub[3]
    cdef double t1b[3]
    cdef double t2b[3]
    cdef double e[3]
    cdef double hA, hB, s, ln, tol = HULL_TOL * F.L
    cdef int k, na, nb, n, ax
    cdef bint crossing, hullA, hullB
    # basis of the plane: t1 from the world axis least aligned with u, t2 = u x t1 (t1, t2, u right-handed)
    ax = 0
    if fabs(u[1]) < fabs(u[ax]):
        ax = 1
    if fabs(u[2]) < fabs(u[ax]):
        ax = 2
    e[0] = 0.0
    e[1] = 0.0
    e[2] = 0.0
    e[ax] = 1.0
    _cross(u, e, t1)
    ln = 1.0 / sqrt(_dot(t1, t1))
    t1[0] *= ln
    t1[1] *= ln
    t1[2] *= ln
    _cross(u, t1, t2)
    # each body's contacting feature: the vertices within ftol of its support along u (A) and -u (B),
    # projected on the plane; B is read in its own frame (directions rotated once by M^T) rather than
    # posed vertex by vertex: support -u.t + sb (-M^T u).v, plane point (t1.t + sb (M^T t1).v, ...)
    mat_tvec(F.M, u, ub)
    mat_tvec(F.M, t1, t1b)
    mat_tvec(F.M, t2, t2b)
    ub[0], ub[1], ub[2] = -ub[0], -ub[1], -ub[2]
    na = _feature(A, F.sa, u, 0.0, t1, 0.0, t2, 0.0, ftol, PA, &hA, &hullA)
    nb = _feature(B, F.sb, ub, -_dot(u, F.t), t1b, _dot(t1, F.t), t2b, _dot(t2, F.t), ftol, PB, &hB, &hullB)
    cplane[0] = 0.5 * (hA - hB)
    if na > 1 and nb > 1:                  # (a single vertex makes the contact: no hull needed)
        na = _hull2(PA, na, tol) if hullA else _box_ring(PA, na, tol)
        nb = _hull2(PB, nb, tol) if hullB else _box_ring(PB, nb, tol)
    nfa[0] = na
    nfb[0] = nb
    if na == 1 or nb == 1:
        if na == 1 and nb == 1:
            pts[0] = 0.5 * (PA[0] + PB[0])
            pts[1] = 0.5 * (PA[1] + PB[1])
        elif na == 1:
            pts[0] = PA[0]
            pts[1] = PA[1]
        else:
            pts[0] = PB[0]
            pts[1] = PB[1]
        return PC_VERTEX_FACE * 100 + 1
    if na == 2 and nb == 2:
        n = _segments(PA, PB, W, tol, &crossing)
        if crossing:
            pts[0] = W[0]
            pts[1] = W[1]
            return PC_EDGE_EDGE * 100 + 1
    elif na == 2:
        n = _clip_segment(PA, PB, nb, W, tol)
    elif nb == 2:
        n = _clip_segment(PB, PA, na, W, tol)
    else:
        n = _clip_poly(PA, na, PB, nb, W, tol)
        if n >= 3:
            n = _clean_ring(W, n, tol)     # drop the repeated / collinear corners clipping leaves
    if n == 0:                             # features apart in the plane (round-off): midpoint of centroids
        W[0] = 0.0
        W[1] = 0.0
        for k in range(na):
            W[0] += 0.5 * PA[2 * k] / na
            W[1] += 0.5 * PA[2 * k + 1] / na
        for k in range(nb):
            W[0] += 0.5 * PB[2 * k] / nb
            W[1] += 0.5 * PB[2 * k + 1] / nb
        n = 1
    elif n == 2:
        if fabs(W[0] - W[2]) + fabs(W[1] - W[3]) <= tol:
            n = 1
        elif W[2] < W[0] or (W[2] == W[0] and W[3] < W[1]):
            s = W[0]
            W[0] = W[2]
            W[2] = s
            s = W[1]
            W[1] = W[3]
            W[3] = s
    elif n >= 3:
        n = _canonical(W, n)
    for k in range(2 * n):
        pts[k] = W[k]
    if n == 1:
        return PC_VERTEX_FACE * 100 + 1
    if n == 2:
        return PC_EDGE_FACE * 100 + 2
    return PC_FACE_FACE * 100 + n


cdef int _points_world(const Polytope* A, const Polytope* B, const Frame* F, const double* Ra,
                       const double* xa, const double* u, double depth, double ftol,
                       PolyContact* out) noexcept nogil:
    cdef double pts[2 * POLY_MAXP]
    cdef double t1[3]
    cdef double t2[3]
    cdef double p[3]
    cdef double c
    cdef int code, n, k, i
    code = _contact_frame(A, B, F, u, depth, ftol, pts, &out.nfa, &out.nfb, t1, t2, &c)
    out.type = code // 100
    n = code % 100
    out.npoints = n
    for k in range(n):
        for i in range(3):
            p[i] = pts[2 * k] * t1[i] + pts[2 * k + 1] * t2[i] + c * u[i]
        mat_vec(Ra, p, out.p + 3 * k)
        for i in range(3):
            out.p[3 * k + i] += xa[i]
    return n


cdef int contact_points(const Polytope* A, const double* Ra, double sa, const double* xa,
                        const Polytope* B, const double* Rb, double sb, const double* xb,
                        const SatResult* sat, double ftol, PolyContact* out) noexcept nogil:
    """Contact points of A and B for the axis of sat (see the module doc); ftol (a length) is the support
    tolerance that selects each body's contacting feature. Fills out; returns npoints (0 if sat has no
    overlap)."""
    cdef Frame F
    cdef double u[3]
    cdef double nw[3]
    out.depth = sat.depth
    out.n[0], out.n[1], out.n[2] = sat.n[0], sat.n[1], sat.n[2]
    if not sat.depth > 0.0:
        out.type = PC_NONE
        out.npoints = 0
        out.nfa = out.nfb = 0
        return 0
    _frame(A, Ra, sa, xa, B, Rb, sb, xb, &F)
    nw[0], nw[1], nw[2] = -sat.n[0], -sat.n[1], -sat.n[2]
    mat_tvec(Ra, nw, u)
    return _points_world(A, B, &F, Ra, xa, u, sat.depth, ftol, out)


cdef int polytope_contact(const Polytope* A, const double* Ra, double sa, const double* xa,
                          const Polytope* B, const double* Rb, double sb, const double* xb,
                          double ftol, double ftol_depth, SatResult* sat, PolyContact* out,
                          int* code, double* budget, double moved) noexcept nogil:
    """sat_penetration then contact_points with the feature tolerance ftol + ftol_depth depth, sharing the
    frame; returns npoints (0: no overlap). code, budget (or NULL): the pair's certificate, kept by the
    caller between calls (zeroed at first) with moved = the sum of both bodies' moves since the last call:
    while the budget covers the moves, only the certified axis is evaluated (_budget: the same answer as
    the full test); else the full test, which renews the certificate."""
    cdef Frame F
    cdef double u[3]
    cdef int hit
    _frame(A, Ra, sa, xa, B, Rb, sb, xb, &F)
    if code != NULL and code[0] > 0 and budget[0] > moved and _sat_cached(A, B, &F, code[0], u, sat):
        budget[0] -= moved
        hit = sat.depth > 0.0
        if not hit:                    # (the caller's margin then skips it: its moves would go uncounted)
            code[0] = 0
    else:
        if code != NULL:
            budget[0] = 0.0            # (two boxes leave it: no certificate)
        hit = _sat_frame(A, B, &F, u, sat, budget if code != NULL else NULL)
        if code != NULL:
            code[0] = 0
            if budget[0] > 0.0:
                if sat.axis == AXIS_FACE_A:
                    code[0] = 1 + sat.fa
                elif sat.axis == AXIS_FACE_B:
                    code[0] = 1 + A.nf + sat.fb
                else:
                    code[0] = 1 + A.nf + B.nf + sat.fa + A.ne * sat.fb
    if not hit:
        mat_vec(Ra, u, sat.n)
        sat.n[0], sat.n[1], sat.n[2] = -sat.n[0], -sat.n[1], -sat.n[2]
        out.depth = sat.depth
        out.n[0], out.n[1], out.n[2] = sat.n[0], sat.n[1], sat.n[2]
        out.type = PC_NONE
        out.npoints = 0
        out.nfa = out.nfb = 0
        return 0
    mat_vec(Ra, u, sat.n)
    sat.n[0], sat.n[1], sat.n[2] = -sat.n[0], -sat.n[1], -sat.n[2]
    out.depth = sat.depth
    out.n[0], out.n[1], out.n[2] = sat.n[0], sat.n[1], sat.n[2]
    return _points_world(A, B, &F, Ra, xa, u, sat.depth, ftol + ftol_depth * sat.depth, out)


# ---------------------------------------------------------------- Python entries (tests, tools)
def _pose(q):
    cdef double[::1] qq = np.ascontiguousarray(q, float)
    R = np.empty(9)
    cdef double[::1] r = R
    quat_to_rot(&qq[0], &r[0])
    return R


def _poses(q):
    """The rotations (rows of 9) of an array of unit quaternions (benchmarks' batches)."""
    return np.array([_pose(x) for x in np.asarray(q)]).reshape(-1, 9)


def pair(TopologyView tv, int ia, int ib, xa, qa, xb, qb, double sa=1.0, double sb=1.0, double ftol=-1.0,
         bint points=True, bint box_path=True):
    """One pair (rows ia, ib of the packed topology) at poses (x, unit quaternion q (w, x, y, z), scale s).
    Returns (overlap, depth, normal from B to A, axis, fa, fb, type, points (npoints, 3), nfa, nfb);
    ftol < 0 means 1e-9 (sa radius_a + sb radius_b). With points false only the first six are computed
    (type 0, no points). box_path false sends two boxes through the general loop (tests compare both)."""
    if not (0 <= ia < tv.t.nrows and 0 <= ib < tv.t.nrows) or not (tv.t.poly[ia] and tv.t.poly[ib]):
        raise ValueError("rows %d, %d are not polytopes of this table" % (ia, ib))
    cdef Polytope A, B
    cdef SatResult sat
    cdef PolyContact pc
    cdef double[::1] Ra = _pose(qa), Rb = _pose(qb)
    cdef double[::1] xa_ = np.ascontiguousarray(xa, float), xb_ = np.ascontiguousarray(xb, float)
    cdef int hit
    polytope_ref(&tv.t, ia, &A)
    polytope_ref(&tv.t, ib, &B)
    if not box_path:
        A.half = B.half = NULL
    if ftol < 0:
        ftol = 1e-9 * (sa * A.radius + sb * B.radius)
    with nogil:
        if points:
            polytope_contact(&A, &Ra[0], sa, &xa_[0], &B, &Rb[0], sb, &xb_[0], ftol, 0.0, &sat, &pc, NULL, NULL, 0.0)
        else:
            sat_penetration(&A, &Ra[0], sa, &xa_[0], &B, &Rb[0], sb, &xb_[0], &sat)
            pc.type = PC_NONE
            pc.npoints = 0
            pc.nfa = pc.nfb = 0
    hit = 1 if sat.depth > 0.0 else 0
    pts = np.array([[pc.p[3 * k], pc.p[3 * k + 1], pc.p[3 * k + 2]] for k in range(pc.npoints)]).reshape(-1, 3)
    return (bool(hit), sat.depth, np.array([sat.n[0], sat.n[1], sat.n[2]]), int(sat.axis), sat.fa, sat.fb,
            int(pc.type), pts, pc.nfa, pc.nfb)


def time_pairs(TopologyView tv, int[::1] ia, int[::1] ib, double[:, ::1] xa, double[:, ::1] qa,
               double[:, ::1] xb, double[:, ::1] qb, int reps, double ftol, bint points=True):
    """Run the m pairs reps times in one nogil loop (benchmarks); returns (seconds per query, hits)."""
    import time
    cdef int m = ia.shape[0], r, k, hits = 0
    cdef Polytope A, B
    cdef SatResult sat
    cdef PolyContact pc
    cdef double[:, ::1] Ra = _poses(qa)
    cdef double[:, ::1] Rb = _poses(qb)
    t0 = time.perf_counter()
    with nogil:
        for r in range(reps):
            for k in range(m):
                polytope_ref(&tv.t, ia[k], &A)
                polytope_ref(&tv.t, ib[k], &B)
                if points:
                    hits += polytope_contact(&A, &Ra[k, 0], 1.0, &xa[k, 0], &B, &Rb[k, 0], 1.0, &xb[k, 0],
                                             ftol, 0.0, &sat, &pc, NULL, NULL, 0.0) > 0
                else:
                    hits += sat_penetration(&A, &Ra[k, 0], 1.0, &xa[k, 0], &B, &Rb[k, 0], 1.0, &xb[k, 0], &sat)
    return (time.perf_counter() - t0) / (reps * m), hits


def _hull2_py(pts, double tol=1e-12):
    """2D hull as the kernels compute it (tests)."""
    cdef double P[2 * (2 * POLY_MAXFEAT + 2)]
    a = np.ascontiguousarray(pts, float).reshape(-1)
    cdef int n = a.shape[0] // 2, k, i
    for i in range(2 * n):
        P[i] = a[i]
    k = _hull2(P, n, tol)
    return np.array([P[i] for i in range(2 * k)]).reshape(-1, 2)
