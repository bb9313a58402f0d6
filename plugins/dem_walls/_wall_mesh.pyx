# cython: language_level=3
"""The kernel of `fix wall/mesh`: particles of a group against a rigid triangle mesh, nogil.

The mesh is kept in its reference frame (where it was read and placed) with a uniform grid of cells over
its bounding box, each cell listing the triangles whose plane crosses it (MeshIndex, built once: a rigid
motion never re-bins). A moving mesh is posed by a rotation M about a point C0 and a displacement D:
world = M (X - C0) + C0 + D. Each particle is taken into the reference frame, meets the triangles of the
cells its bounding sphere overlaps, and its contacts go back to the world frame for the shared law
(dem/law/apply.pxd) with m_ij = m_i and the mesh's velocity V + omega x (p - C0 - D) at the point.

One contact per touched feature, not per triangle: a sphere over a plane cut into triangles overlaps many
of them but meets the surface once. A sphere meets a triangle at its closest point, inside the triangle
(a face), on an edge or at a vertex. The hits of a particle (of each piece of a composite) are taken
deepest first; one on an edge or a vertex is no contact when a closer (earlier) hit's triangle has that
feature (the surface's closest point lies elsewhere: a sphere near a shared edge or over a fan; or, as
close, on a convex ridge or apex seen from both sides: one is kept); one at a kept hit's point, or, for
shaped bodies, in a kept hit's plane (a flat face over several triangles: one contact per plane) is the
same contact. Every triangle closer than a hit overlaps the particle, so it is a hit too. A sphere crossing from one
triangle to a coplanar neighbour thus feels one contact whose normal and overlap do not jump; one in a
valley touches both of its sides.

Shaped bodies (their true body, as the other walls): GJK against the triangle, EPA for the depth, the
contact point midway in the overlap (a sphere component of a composite: its closest point, as a sphere); `multipoint` (sharp polytopes): every vertex beyond the plane of a
face hit, each with the hit's overlap and weight 1/alpha (Descantes 2022 eq. 3), as wall/plane.

Tangential history: NSLOT slots per particle of (piece + 1, normal in the mesh frame, xi); a contact takes
the slot of the same piece whose normal is nearest its own (within 60 degrees), so that its spring
survives the crossing of an edge between triangles and a change of feature; slots not met are freed."""
import numpy as np
from libc.float cimport DBL_MIN
from libc.math cimport sqrt, floor, fabs
from libc.stdlib cimport malloc, realloc, free
cimport numpy as cnp
from dem._math cimport dot3, mat_vec, mat_tvec
from dem._particles cimport ParticleView, Particles
from dem.contact.record cimport Contact
from dem.contact._gjk cimport gjk_distance, epa_penetration, Simplex, GJK_SEPARATED
from dem.shapes._support cimport ShapeRef, SPHERE, BOX, POLYHEDRON, MARGIN, NPARAM, support_world, vertex_world
from dem.shapes._table cimport (ShapeView, TableView, body_ref, equivalent_radius, pose_body, round_body,
                                ncomponents, component_row, pose_component)
from dem.law.apply cimport Body, apply_wall, bind_body, contact_radius
from dem.law.law cimport forget
from dem.law.row cimport XI_WIDTH

ctypedef cnp.int64_t i64

cdef enum:
    F_FACE = 0
    F_EDGE = 1
    F_VERTEX = 2
    NSLOT = 6                       # history slots per particle
    SLOT = 4 + XI_WIDTH             # piece + 1, normal (3), xi
    POSE_M = 0                      # pose vector: rotation (9, row-major, reference -> world)
    POSE_C = 9                      # the point it turns about (3, reference frame)
    POSE_D = 12                     # displacement (3)
    POSE_V = 15                     # translation velocity (3)
    POSE_W = 18                     # angular velocity (3)
    NPOSE = 21
    M_CONTACTS = 0                  # stats
    M_MAXOV = 1
    M_ENERGY = 2
    M_FORCE = 3                     # force of the particles on the mesh (3)
    M_TORQUE = 6                    # their torque on it about C0 + D (3)
    M_WORST_I = 9
    M_WORST_T = 10
    M_NSTAT = 11

STAT = {"CONTACTS": M_CONTACTS, "MAXOV": M_MAXOV, "ENERGY": M_ENERGY, "FORCE": M_FORCE,
        "TORQUE": M_TORQUE, "WORST_I": M_WORST_I, "WORST_T": M_WORST_T, "NSTAT": M_NSTAT}
POSE = {"M": POSE_M, "C": POSE_C, "D": POSE_D, "V": POSE_V, "W": POSE_W, "N": NPOSE}
HISTORY_WIDTH = NSLOT * SLOT

cdef double ZERO_PARAMS[NPARAM]
for _k in range(NPARAM):
    ZERO_PARAMS[_k] = 0.0
cdef double IDENTITY[9]
IDENTITY[:] = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
cdef double ORIGIN[3]
ORIGIN[:] = [0.0, 0.0, 0.0]


cdef struct Hit:
    int tri, piece, fkind, fid, npts
    bint keep
    double key                      # order: smaller first (sphere: distance; shaped: minus the depth)
    double delta
    double n[3]                     # reference frame, from the mesh into the particle
    double p[3]                     # reference frame, midway in the overlap


cdef class MeshIndex:
    """The mesh in its reference frame and its grid of cells of side `cell` (see the module doc)."""
    cdef readonly object verts, tris, edges, normals, cell_start, cell_tris, stamp, balls
    cdef readonly double lo0, lo1, lo2, h
    cdef readonly int n0, n1, n2

    def __init__(self, mesh, double cell):
        lo, hi = mesh.vertices.min(axis=0), mesh.vertices.max(axis=0)
        self.verts, self.tris, self.edges, self.normals = mesh.vertices, mesh.triangles, mesh.edges, mesh.normals
        self.h = cell
        self.lo0, self.lo1, self.lo2 = lo
        self.n0, self.n1, self.n2 = [max(1, int((hi[d] - lo[d]) / cell) + 1) for d in range(3)]
        counts = np.zeros(self.n0 * self.n1 * self.n2 + 1, dtype=np.int64)
        _bin(self, counts, None)
        start = np.zeros_like(counts)
        np.cumsum(counts[:len(counts) - 1], out=start[1:])
        self.cell_start = start
        self.cell_tris = np.empty(int(start[len(start) - 1]), dtype=np.int32)
        _bin(self, start.copy(), self.cell_tris)
        self.stamp = np.full(len(mesh.triangles), -1, dtype=np.int64)
        # each triangle's bounding ball (centroid, radius): most triangles near a particle are rejected by it
        corners = mesh.vertices[mesh.triangles]
        centre = corners.mean(axis=1)
        radius = np.linalg.norm(corners - centre[:, None, :], axis=2).max(axis=1) * (1.0 + 1e-12)
        self.balls = np.ascontiguousarray(np.column_stack([centre, radius]))

    @property
    def cells(self):
        return self.n0 * self.n1 * self.n2

    @property
    def entries(self):
        return len(self.cell_tris)


def _bin(MeshIndex g, i64[::1] slot, out):
    """Count (out None) or list the triangles of each cell whose plane crosses it, within the triangle's
    bounding box: slot[c] is the cell's count (counting) or its next free place (listing)."""
    cdef const double[:, ::1] v = g.verts
    cdef const int[:, ::1] t = g.tris
    cdef const double[:, ::1] nrm = g.normals
    cdef int[::1] o = out if out is not None else np.zeros(1, dtype=np.int32)
    cdef bint listing = out is not None
    cdef int k, d, i0, i1, i2, cell
    cdef int a[3]
    cdef int b[3]
    cdef int dims[3]
    cdef double glo[3]
    cdef double c[3]
    cdef double h = g.h, reach, s, lo, hi
    glo[0], glo[1], glo[2] = g.lo0, g.lo1, g.lo2
    dims[0], dims[1], dims[2] = g.n0, g.n1, g.n2
    for k in range(t.shape[0]):
        for d in range(3):
            lo = min(v[t[k, 0], d], v[t[k, 1], d], v[t[k, 2], d])
            hi = max(v[t[k, 0], d], v[t[k, 1], d], v[t[k, 2], d])
            a[d] = _cell(lo, glo[d], h, dims[d])
            b[d] = _cell(hi, glo[d], h, dims[d])
        # a cell is crossed by the plane when its centre is within its half-extent along the normal
        reach = 0.5 * h * (fabs(nrm[k, 0]) + fabs(nrm[k, 1]) + fabs(nrm[k, 2])) * (1.0 + 1e-9)
        for i0 in range(a[0], b[0] + 1):
            for i1 in range(a[1], b[1] + 1):
                for i2 in range(a[2], b[2] + 1):
                    c[0] = glo[0] + (i0 + 0.5) * h
                    c[1] = glo[1] + (i1 + 0.5) * h
                    c[2] = glo[2] + (i2 + 0.5) * h
                    s = 0.0
                    for d in range(3):
                        s += nrm[k, d] * (c[d] - v[t[k, 0], d])
                    if fabs(s) > reach:
                        continue
                    cell = (i0 * dims[1] + i1) * dims[2] + i2
                    if listing:
                        o[slot[cell]] = k
                    slot[cell] += 1


cdef inline int _cell(double x, double lo, double h, int n) noexcept nogil:
    cdef double f = floor((x - lo) / h)
    if f < 0.0:
        return 0
    if f > n - 1:
        return n - 1
    return <int>f


cdef void _closest(const double* a, const double* b, const double* c, const double* p, double* q,
                   int* fkind, int* fidx) noexcept nogil:
    """Closest point q of the triangle (a, b, c) to p and its feature: the face, edge k (from vertex k to
    vertex k+1) or vertex k (the Voronoi regions of Ericson, Real-Time Collision Detection, sec. 5.1.5)."""
    cdef double ab[3]
    cdef double ac[3]
    cdef double ap[3]
    cdef double bp[3]
    cdef double cp[3]
    cdef double d1, d2, d3, d4, d5, d6, va, vb, vc, v, w, den
    cdef int k
    for k in range(3):
        ab[k] = b[k] - a[k]
        ac[k] = c[k] - a[k]
        ap[k] = p[k] - a[k]
    d1 = dot3(ab, ap)
    d2 = dot3(ac, ap)
    if d1 <= 0.0 and d2 <= 0.0:
        fkind[0], fidx[0] = F_VERTEX, 0
        for k in range(3):
            q[k] = a[k]
        return
    for k in range(3):
        bp[k] = p[k] - b[k]
    d3 = dot3(ab, bp)
    d4 = dot3(ac, bp)
    if d3 >= 0.0 and d4 <= d3:
        fkind[0], fidx[0] = F_VERTEX, 1
        for k in range(3):
            q[k] = b[k]
        return
    vc = d1 * d4 - d3 * d2
    if vc <= 0.0 and d1 >= 0.0 and d3 <= 0.0:
        v = d1 / (d1 - d3)
        fkind[0], fidx[0] = F_EDGE, 0
        for k in range(3):
            q[k] = a[k] + v * ab[k]
        return
    for k in range(3):
        cp[k] = p[k] - c[k]
    d5 = dot3(ab, cp)
    d6 = dot3(ac, cp)
    if d6 >= 0.0 and d5 <= d6:
        fkind[0], fidx[0] = F_VERTEX, 2
        for k in range(3):
            q[k] = c[k]
        return
    vb = d5 * d2 - d1 * d6
    if vb <= 0.0 and d2 >= 0.0 and d6 <= 0.0:
        w = d2 / (d2 - d6)
        fkind[0], fidx[0] = F_EDGE, 2
        for k in range(3):
            q[k] = a[k] + w * ac[k]
        return
    va = d3 * d6 - d5 * d4
    if va <= 0.0 and (d4 - d3) >= 0.0 and (d5 - d6) >= 0.0:
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        fkind[0], fidx[0] = F_EDGE, 1
        for k in range(3):
            q[k] = b[k] + w * (c[k] - b[k])
        return
    den = 1.0 / (va + vb + vc)
    v = vb * den
    w = vc * den
    fkind[0], fidx[0] = F_FACE, 0
    for k in range(3):
        q[k] = a[k] + ab[k] * v + ac[k] * w


cdef void _feature_of(const double* a, const double* b, const double* c, const double* p, double eps,
                      int* fkind, int* fidx) noexcept nogil:
    """The feature of the triangle (a, b, c) that a point p of it lies on, a barycentric weight <= eps
    counting as zero."""
    cdef double ab[3]
    cdef double ac[3]
    cdef double ap[3]
    cdef double lam[3]
    cdef double d00, d01, d11, d20, d21, den
    cdef int k, nz = 0, zi = 0, nzi = 0
    for k in range(3):
        ab[k] = b[k] - a[k]
        ac[k] = c[k] - a[k]
        ap[k] = p[k] - a[k]
    d00 = dot3(ab, ab)
    d01 = dot3(ab, ac)
    d11 = dot3(ac, ac)
    d20 = dot3(ap, ab)
    d21 = dot3(ap, ac)
    den = d00 * d11 - d01 * d01
    lam[1] = (d11 * d20 - d01 * d21) / den
    lam[2] = (d00 * d21 - d01 * d20) / den
    lam[0] = 1.0 - lam[1] - lam[2]
    for k in range(3):
        if lam[k] <= eps:
            nz += 1
            zi = k
        else:
            nzi = k
    if nz == 0:
        fkind[0], fidx[0] = F_FACE, 0
    elif nz == 1:          # weight k zero: the edge opposite vertex k, from vertex k+1 to k+2
        fkind[0], fidx[0] = F_EDGE, (zi + 1) % 3
    else:
        fkind[0], fidx[0] = F_VERTEX, nzi


cdef inline bint _contains(const int[:, ::1] tris, const int[:, ::1] edges, int t, int fkind,
                           int fid) noexcept nogil:
    """Triangle t has the edge or vertex fid (fkind)."""
    cdef int m
    if fkind == F_EDGE:
        for m in range(3):
            if edges[t, m] == fid:
                return True
    elif fkind == F_VERTEX:
        for m in range(3):
            if tris[t, m] == fid:
                return True
    return False


cdef int _shaped_hit(const ShapeRef* S, const double* R, const double* x, const double* a, const double* b,
                     const double* c, const double* tn, Hit* hit) noexcept nogil:
    """A posed convex body (reference frame) against the triangle (a, b, c) of unit normal tn: 1 and the hit
    (depth, normal into the body, point midway in the overlap, feature of the triangle) if they overlap."""
    cdef ShapeRef T
    cdef Simplex sx
    cdef double verts[9]
    cdef double v[3]
    cdef double pa[3]
    cdef double pb[3]
    cdef double n[3]
    cdef double q[3]
    cdef double depth, side
    cdef int k
    for k in range(3):
        verts[k] = a[k]
        verts[3 + k] = b[k]
        verts[6 + k] = c[k]
        v[k] = x[k] - (a[k] + b[k] + c[k]) / 3.0
    T.kind = POLYHEDRON
    T.nverts = 3
    T.params = ZERO_PARAMS
    T.verts = verts
    T.corners = NULL
    side = 1.0 if dot3(tn, v) >= 0.0 else -1.0
    # any positive lower bound of the distance proves them apart (sep: the smallest positive double)
    if gjk_distance(S, R, x, &T, IDENTITY, ORIGIN, 1e-10, DBL_MIN, v, &sx, False, pa, pb) == GJK_SEPARATED:
        return 0
    if epa_penetration(S, R, x, &T, IDENTITY, ORIGIN, &sx, 1e-10, &depth, n, pa, pb) < 0 or not depth > 0.0:
        # a degenerate start: the triangle's plane, facing the body's centre
        for k in range(3):
            n[k] = side * tn[k]
            q[k] = -n[k]
        support_world(S, R, x, q, pa)
        for k in range(3):
            q[k] = a[k] - pa[k]
        depth = dot3(n, q)
        if not depth > 0.0:
            return 0
        for k in range(3):
            pb[k] = pa[k] + depth * n[k]
    hit.delta = depth
    hit.key = -depth
    for k in range(3):
        hit.n[k] = n[k]
        hit.p[k] = 0.5 * (pa[k] + pb[k])
    _feature_of(a, b, c, pb, 1e-9, &hit.fkind, &hit.fid)
    return 1


cdef int _room(Hit** buf, int* cap, int n) noexcept nogil:
    """0 when buf has room for hit n (grown if need be), -1 when memory ran out (the hit is skipped)."""
    cdef Hit* more
    if n < cap[0]:
        return 0
    more = <Hit*>realloc(buf[0], 2 * cap[0] * sizeof(Hit))
    if more == NULL:
        return -1
    buf[0] = more
    cap[0] *= 2
    return 0


cdef int _vertices_beyond(const ShapeRef* S, const double* R, const double* x, const double* v0,
                          const double* n, double tol, int k, double* q, double* depth) noexcept nogil:
    """From vertex k on, the first vertex q of a posed polytope beyond the plane through v0 of normal n
    (depth + tol > 0) and its depth; returns the next k to look from, -1 when there is none left."""
    cdef double y[3]
    cdef int d
    while vertex_world(S, R, x, k, q):
        k += 1
        for d in range(3):
            y[d] = v0[d] - q[d]
        depth[0] = dot3(n, y)
        if depth[0] + tol > 0.0:
            return k
    return -1


def mesh_walls(ParticleView view, int groupbit, MeshIndex mesh, const double[::1] pose,
               const double[:, ::1] coeff, ShapeView shapes, double[:, ::1] hist, bint use_history,
               double dt, bint advance, bint multi, bint average, i64 token, double[::1] stats):
    """The mesh's forces on the particles of groupbit (see the module doc). pose: NPOSE values (POSE).
    coeff[type]: the law row. hist: HISTORY_WIDTH values per particle (use_history). multi: multipoint
    polytopes. average: Model B over a composite's contacts with the mesh (else Model A). token: a number
    no earlier call used for its particles (the triangle stamps); the next call takes token + nlocal.
    stats: M_NSTAT sums (STAT)."""
    cdef Particles particles = view.p
    cdef const Particles* P = &particles
    cdef TableView table = shapes.t
    cdef const TableView* Tb = &table
    cdef const double[:, ::1] V = mesh.verts
    cdef const int[:, ::1] tris = mesh.tris
    cdef const int[:, ::1] edges = mesh.edges
    cdef const double[:, ::1] nrm = mesh.normals
    cdef const i64[::1] cstart = mesh.cell_start
    cdef const int[::1] ctris = mesh.cell_tris
    cdef i64[::1] stamp = mesh.stamp
    cdef const double[:, ::1] balls = mesh.balls
    cdef double h = mesh.h
    cdef double glo[3]
    cdef int dims[3]
    glo[0], glo[1], glo[2] = mesh.lo0, mesh.lo1, mesh.lo2
    dims[0], dims[1], dims[2] = mesh.n0, mesh.n1, mesh.n2
    cdef const double* M = &pose[POSE_M]
    cdef const double* C0 = &pose[POSE_C]
    cdef const double* D = &pose[POSE_D]
    cdef double centre[3]
    cdef int i, k, d, t, s, c, npc, row, j, m, nh, nkeep, fk, fi, cap = 64, i0, i1, i2, cell, best
    cdef int a[3]
    cdef int b[3]
    cdef i64 e
    cdef double xr[3]
    cdef double y[3]
    cdef double q[3]
    cdef double R[9]
    cdef double Rr[9]
    cdef double Rc[9]
    cdef double xc[3]
    cdef double vw[3]
    cdef double force[3]
    cdef double torque[3]
    cdef double r, dist, dn, bestdot, ov, sc = 1.0, rc, depth, tol
    cdef double energy = 0.0, ncont = 0.0, maxov = 0.0, worst_i = -1.0, worst_t = -1.0
    cdef bint sphere, keep, posed
    cdef ShapeRef S
    cdef Contact con
    cdef Body A, B
    cdef double* xi
    cdef double* sl
    cdef bint used[NSLOT]
    cdef Hit tmp
    cdef Hit* hits = <Hit*>malloc(cap * sizeof(Hit))
    if hits == NULL:
        raise MemoryError()
    for d in range(3):
        force[d] = 0.0
        torque[d] = 0.0
        centre[d] = C0[d] + D[d]
    con.arm_b = 0.0
    B.s = NULL
    B.w = &pose[POSE_W]
    B.v = vw
    with nogil:
        for i in range(P.nlocal):
            if not (P.mask[i] & groupbit):
                continue
            r = P.radius[i]
            s = P.shape[i]
            sphere = round_body(Tb, s)
            npc = 1 if sphere else ncomponents(Tb, s)
            for d in range(3):                 # the centre in the mesh's reference frame
                y[d] = P.x[3 * i + d] - centre[d]
            mat_tvec(M, y, xr)
            nh = 0
            posed = False
            for d in range(3):
                xr[d] += C0[d]
                a[d] = <int>floor((xr[d] - r - glo[d]) / h)
                b[d] = <int>floor((xr[d] + r - glo[d]) / h)
                if b[d] < 0 or a[d] >= dims[d]:
                    nh = -1                      # the bounding sphere misses the grid
                a[d] = max(a[d], 0)
                b[d] = min(b[d], dims[d] - 1)
            if nh < 0:
                nh = 0
                a[0], b[0] = 0, -1
            for i0 in range(a[0], b[0] + 1):
                for i1 in range(a[1], b[1] + 1):
                    for i2 in range(a[2], b[2] + 1):
                        cell = (i0 * dims[1] + i1) * dims[2] + i2
                        for e in range(cstart[cell], cstart[cell + 1]):
                            t = ctris[e]
                            if stamp[t] == token + i:
                                continue
                            stamp[t] = token + i
                            for d in range(3):
                                y[d] = xr[d] - balls[t, d]
                            if dot3(y, y) >= (r + balls[t, 3]) * (r + balls[t, 3]):   # misses the triangle's ball
                                continue
                            if sphere:
                                for d in range(3):
                                    y[d] = xr[d] - V[tris[t, 0], d]
                                if fabs(dot3(y, &nrm[t, 0])) >= r:     # the sphere misses the plane
                                    continue
                                _closest(&V[tris[t, 0], 0], &V[tris[t, 1], 0], &V[tris[t, 2], 0], xr, q, &fk, &fi)
                                for d in range(3):
                                    y[d] = xr[d] - q[d]
                                dist = sqrt(dot3(y, y))
                                if dist >= r or dist == 0.0 or _room(&hits, &cap, nh) < 0:
                                    continue
                                hits[nh].tri, hits[nh].piece, hits[nh].npts, hits[nh].fkind = t, 0, 1, fk
                                hits[nh].fid = t if fk == F_FACE else (edges[t, fi] if fk == F_EDGE else tris[t, fi])
                                hits[nh].key = dist
                                hits[nh].delta = r - dist
                                for d in range(3):
                                    hits[nh].n[d] = y[d] / dist
                                    hits[nh].p[d] = q[d] - 0.5 * (r - dist) * hits[nh].n[d]
                                nh += 1
                                continue
                            if not posed:             # the body in the reference frame: M^T R
                                pose_body(Tb, s, &P.quat[4 * i], r, &S, R)
                                for j in range(3):
                                    for m in range(3):
                                        Rr[3 * j + m] = M[j] * R[m] + M[3 + j] * R[3 + m] + M[6 + j] * R[6 + m]
                                sc = r / Tb.radius[s]
                                posed = True
                            for c in range(npc):
                                row = component_row(Tb, s, c)
                                body_ref(Tb, row, &S)
                                pose_component(Tb, s, c, Rr, xr, Rc, xc)
                                rc = Tb.radius[row] * sc
                                for d in range(3):
                                    y[d] = xc[d] - V[tris[t, 0], d]
                                dn = dot3(y, &nrm[t, 0])
                                if dn >= rc or dn <= -rc or _room(&hits, &cap, nh) < 0:
                                    continue                # the piece's sphere misses the plane
                                if S.kind == SPHERE:        # a sphere component: as a sphere, exactly
                                    _closest(&V[tris[t, 0], 0], &V[tris[t, 1], 0], &V[tris[t, 2], 0], xc, q, &fk, &fi)
                                    for d in range(3):
                                        y[d] = xc[d] - q[d]
                                    dist = sqrt(dot3(y, y))
                                    if dist >= rc or dist == 0.0:
                                        continue
                                    hits[nh].tri, hits[nh].piece, hits[nh].npts, hits[nh].fkind = t, c, 1, fk
                                    hits[nh].fid = t if fk == F_FACE else (edges[t, fi] if fk == F_EDGE else tris[t, fi])
                                    hits[nh].key = dist - rc
                                    hits[nh].delta = rc - dist
                                    for d in range(3):
                                        hits[nh].n[d] = y[d] / dist
                                        hits[nh].p[d] = q[d] - 0.5 * (rc - dist) * hits[nh].n[d]
                                    nh += 1
                                    continue
                                if not _shaped_hit(&S, Rc, xc, &V[tris[t, 0], 0], &V[tris[t, 1], 0],
                                                   &V[tris[t, 2], 0], &nrm[t, 0], &hits[nh]):
                                    continue
                                hits[nh].tri, hits[nh].piece, hits[nh].npts = t, c, 1
                                fk, fi = hits[nh].fkind, hits[nh].fid
                                hits[nh].fid = t if fk == F_FACE else (edges[t, fi] if fk == F_EDGE else tris[t, fi])
                                nh += 1
            # by piece, deepest first (insertion sort, stable: a few hits)
            for j in range(1, nh):
                tmp = hits[j]
                m = j - 1
                while m >= 0 and (hits[m].piece > tmp.piece or
                                  (hits[m].piece == tmp.piece and hits[m].key > tmp.key)):
                    hits[m + 1] = hits[m]
                    m -= 1
                hits[m + 1] = tmp
            # a hit on an edge or a vertex is no contact when a closer triangle has that feature (any closer
            # triangle overlaps the particle too: it is an earlier hit); a hit at a kept hit's point, or
            # (shaped bodies) in a kept hit's plane, is the same contact
            tol = 1e-9 * r
            for j in range(nh):
                hits[j].keep = True
                for m in range(j):
                    if hits[m].piece != hits[j].piece:
                        continue
                    if _contains(tris, edges, hits[m].tri, hits[j].fkind, hits[j].fid):
                        hits[j].keep = False
                        break
                    if not hits[m].keep:
                        continue
                    for d in range(3):
                        y[d] = hits[j].p[d] - hits[m].p[d]
                    if dot3(y, y) <= tol * tol or (not sphere and dot3(&nrm[hits[m].tri, 0], &nrm[hits[j].tri, 0]) > 1.0 - 1e-9):
                        hits[j].keep = False
                        break
            nkeep = 0
            for j in range(nh):
                if hits[j].keep:
                    hits[nkeep] = hits[j]
                    nkeep += 1
            # multipoint: a sharp polytope touches a face at its vertices beyond the face's plane
            if multi and not sphere:
                for j in range(nkeep):
                    row = component_row(Tb, s, hits[j].piece)
                    body_ref(Tb, row, &S)
                    if hits[j].fkind != F_FACE or not (S.kind == BOX or S.kind == POLYHEDRON) or S.params[MARGIN] != 0.0:
                        continue
                    pose_component(Tb, s, hits[j].piece, Rr, xr, Rc, xc)
                    hits[j].npts = 0
                    k = 0
                    while True:
                        k = _vertices_beyond(&S, Rc, xc, &V[tris[hits[j].tri, 0], 0], hits[j].n, tol, k, q, &depth)
                        if k < 0:
                            break
                        hits[j].npts += 1
                    hits[j].npts = max(hits[j].npts, 1)
            # tangential history: the slot of the same piece with the nearest normal
            for k in range(NSLOT):
                used[k] = False
            for j in range(nkeep):
                xi = NULL
                if use_history:
                    best, bestdot = -1, 0.5
                    for k in range(NSLOT):
                        sl = &hist[i, SLOT * k]
                        if sl[0] == hits[j].piece + 1 and not used[k]:
                            dn = dot3(&sl[1], hits[j].n)
                            if dn > bestdot:
                                best, bestdot = k, dn
                    if best < 0 and advance:
                        for k in range(NSLOT):
                            if hist[i, SLOT * k] == 0.0 and not used[k]:
                                best = k
                                break
                    if best >= 0:
                        used[best] = True
                        sl = &hist[i, SLOT * best]
                        if advance:
                            sl[0] = hits[j].piece + 1
                            for d in range(3):
                                sl[1 + d] = hits[j].n[d]
                        xi = &sl[4]
                _apply_hit(&hits[j], i, s, sphere, P, Tb, M, C0, centre, &pose[0], Rr, xr, &coeff[P.type[i], 0],
                           xi, dt, advance, average, nkeep, tol, &V[tris[hits[j].tri, 0], 0], &A, &B, &con,
                           vw, force, torque, &energy, &ncont)
                ov = hits[j].delta / (2.0 * r)
                if ov > maxov:
                    maxov, worst_i, worst_t = ov, i, hits[j].tri
            if use_history and advance:          # contacts that ended forget their spring
                for k in range(NSLOT):
                    sl = &hist[i, SLOT * k]
                    if not used[k] and sl[0] != 0.0:
                        for d in range(4):
                            sl[d] = 0.0
                        forget(&sl[4], XI_WIDTH)
    free(hits)
    stats[M_CONTACTS] = ncont
    stats[M_MAXOV] = maxov
    stats[M_ENERGY] = energy
    for d in range(3):
        stats[M_FORCE + d] = force[d]
        stats[M_TORQUE + d] = torque[d]
    stats[M_WORST_I] = worst_i
    stats[M_WORST_T] = worst_t


cdef void _apply_hit(const Hit* hit, int i, int s, bint sphere, const Particles* P, const TableView* Tb,
                     const double* M, const double* C0, const double* centre, const double* pose,
                     const double* Rr, const double* xr, const double* cf, double* xi, double dt,
                     bint advance, bint average, int nkeep, double tol, const double* v0,
                     Body* A, Body* B, Contact* con, double* vw, double* force, double* torque,
                     double* energy, double* ncont) noexcept nogil:
    """The law at a kept hit (or at each of its multipoint vertices), in the world frame; the reactions
    summed on the mesh (force, and torque about `centre`, the turning point C0 + D)."""
    cdef ShapeRef S
    cdef double Rc[9]
    cdef double xc[3]
    cdef double q[3]
    cdef double y[3]
    cdef double pr[3]
    cdef double lw[3]
    cdef double out[6]
    cdef double depth = 0.0, weight = 1.0, m = P.rmass[i]
    cdef int k = 0, d
    cdef bint many = hit.npts > 1
    if many:                 # Descantes: the points of one face share its force
        weight = 1.0 / hit.npts
    if nkeep > 1 and not sphere and ncomponents(Tb, s) > 1:
        if average:          # Model B: the composite's contacts with the mesh averaged
            weight /= nkeep
        else:                # Model A: each a full contact, damped with m_i / N_c (Part III eq. 18)
            m /= nkeep
    mat_vec(M, hit.n, con.n)
    con.delta = hit.delta
    con.central = sphere
    con.key = 0
    con.weight = weight
    con.inertia = 0.0        # no rolling dashpot (the mesh keeps no rolling history)
    con.arm_a = P.radius[i] - 0.5 * hit.delta
    bind_body(A, P, i)
    if many:
        body_ref(Tb, component_row(Tb, s, hit.piece), &S)
        pose_component(Tb, s, hit.piece, Rr, xr, Rc, xc)
        xi = NULL            # the points are not tracked: no spring
    while True:
        if many:             # the next vertex beyond the face's plane, moved to the middle of the overlap
            k = _vertices_beyond(&S, Rc, xc, v0, hit.n, tol, k, q, &depth)
            if k < 0:
                break
            for d in range(3):
                pr[d] = q[d] + (depth - 0.5 * hit.delta) * hit.n[d]
        else:
            for d in range(3):
                pr[d] = hit.p[d]
        for d in range(3):   # the point in the world frame and its lever from the turning point
            y[d] = pr[d] - C0[d]
        mat_vec(M, y, lw)
        for d in range(3):
            con.p[d] = lw[d] + centre[d]
        vw[0] = pose[POSE_V] + pose[POSE_W + 1] * lw[2] - pose[POSE_W + 2] * lw[1]
        vw[1] = pose[POSE_V + 1] + pose[POSE_W + 2] * lw[0] - pose[POSE_W] * lw[2]
        vw[2] = pose[POSE_V + 2] + pose[POSE_W] * lw[1] - pose[POSE_W + 1] * lw[0]
        energy[0] += apply_wall(cf, con, A, B, m,
                                contact_radius(cf, sphere, equivalent_radius(Tb, s, P.radius[i]), -1.0),
                                xi, dt, advance, out)
        ncont[0] += 1.0
        for d in range(3):
            force[d] -= out[d]
            torque[d] -= out[3 + d]
        torque[0] -= lw[1] * out[2] - lw[2] * out[1]
        torque[1] -= lw[2] * out[0] - lw[0] * out[2]
        torque[2] -= lw[0] * out[1] - lw[1] * out[0]
        if not many:
            break
