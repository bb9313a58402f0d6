# cython: language_level=3
"""A posed body against a wall surface: depth, normal and contact point, nogil. A Surface is a plane
(q[a] = pos facing side, +1 or -1) or the inside of a cylinder (radius r, axis along coordinate a through
centre; b, c the two other coordinates). A surface may turn about the coordinate axis `spin` (-1: at rest)
through centre at omega rad/s: its velocity at a point q is omega e x (q - centre).

Spheres meet a surface analytically (sphere_gap). Shaped bodies (their true, sharp body: a wall needs no
crust) touch at their deepest point beyond it: against a plane the support point along the wall normal;
against the cylinder the point of the body farthest from the axis (farthest vertex of a polytope; on a
curved body the fixed point of p = support(radial direction of p)). `centroid` moves the point to the
depth-weighted centroid of the body's candidate points beyond the surface, keeping the overlap."""
from libc.math cimport sqrt
from dem.shapes._support cimport ShapeRef, BOX, CYLINDER, CONE, POLYHEDRON, posed_point, support_world, vertex_world

cdef enum:                 # columns of a row of the surfaces table the wall kernel takes (float64)
    S_CYLINDER = 0         # 1: the inside of a cylinder, 0: a plane
    S_A = 1                # plane: normal coordinate; cylinder: axis coordinate
    S_SIDE = 2             # plane: +1 faces +a, -1 faces -a
    S_POS = 3              # plane: position along a
    S_R = 4                # cylinder radius
    S_CENTRE = 5           # 3 values: a point of the axis (cylinder, and the turning axis)
    S_SPIN = 8             # coordinate axis the surface turns about, -1: at rest
    S_OMEGA = 9            # turning rate (rad/s, right-hand rule about +spin)
    S_NCOL = 10


cdef struct Surface:
    bint cylinder
    int a, b, c
    double side, pos, r
    double centre[3]
    int spin
    double omega


cdef inline void load_surface(const double* row, Surface* w) noexcept nogil:
    cdef int d
    w.cylinder = row[S_CYLINDER] != 0.0
    w.a = <int>row[S_A]
    w.b = (w.a + 1) % 3
    w.c = (w.a + 2) % 3
    w.side = row[S_SIDE]
    w.pos = row[S_POS]
    w.r = row[S_R]
    for d in range(3):
        w.centre[d] = row[S_CENTRE + d]
    w.spin = <int>row[S_SPIN]
    w.omega = row[S_OMEGA]


cdef inline double bound_gap(const Surface* w, const double* x, double* rho) noexcept nogil:
    """Distance of a centre x to the surface, positive in front of it (cylinder: rho receives the distance
    of x from the axis)."""
    cdef double db, dc
    if w.cylinder:
        db = x[w.b] - w.centre[w.b]
        dc = x[w.c] - w.centre[w.c]
        rho[0] = sqrt(db * db + dc * dc)
        return w.r - rho[0]
    return w.side * (x[w.a] - w.pos)


cdef inline bint sphere_normal(const Surface* w, const double* x, double rho, double* n) noexcept nogil:
    """Unit normal from the surface into a sphere centred at x (rho: from bound_gap); False on the axis of a
    cylinder, where there is none."""
    n[0] = 0.0
    n[1] = 0.0
    n[2] = 0.0
    if not w.cylinder:
        n[w.a] = w.side
        return True
    if rho == 0.0:
        return False
    n[w.b] = -(x[w.b] - w.centre[w.b]) / rho
    n[w.c] = -(x[w.c] - w.centre[w.c]) / rho
    return True


cdef inline bint candidate_point(const ShapeRef* S, const double* R, const double* x, const double* dn, int k,
                                 double* out) noexcept nogil:
    """k-th point of a posed body that can touch a wall lying in the direction dn (world) from it: the
    vertices of a box or polyhedron; for a cylinder its two rim points (bottom, top) and for a cone its
    rim point and apex, at the rim's azimuth towards dn. False past the last one (and for smooth kinds,
    which touch at their support point only). Walls average these over the ones beyond them (`point
    centroid`)."""
    cdef double q[3]
    cdef double db0, db1, nxy
    cdef int kind = S.kind
    if kind == BOX or kind == POLYHEDRON:
        return vertex_world(S, R, x, k, out)
    elif (kind == CYLINDER or kind == CONE) and k < 2:
        db0 = R[0] * dn[0] + R[3] * dn[1] + R[6] * dn[2]
        db1 = R[1] * dn[0] + R[4] * dn[1] + R[7] * dn[2]
        nxy = sqrt(db0 * db0 + db1 * db1)
        if nxy > 1e-12 * sqrt(db0 * db0 + db1 * db1 + (R[2] * dn[0] + R[5] * dn[1] + R[8] * dn[2]) ** 2):
            q[0] = S.params[0] * db0 / nxy
            q[1] = S.params[0] * db1 / nxy
        else:                                               # a disc face-on: its centre
            q[0] = 0.0
            q[1] = 0.0
        if kind == CYLINDER:
            q[2] = -S.params[1] if k == 0 else S.params[1]
        elif k == 0:
            q[2] = S.params[1]
        else:
            q[0] = 0.0
            q[1] = 0.0
            q[2] = S.params[2]
    else:
        return False
    posed_point(R, x, q, out)
    return True


cdef inline double surface_depth(const Surface* w, const double* q) noexcept nogil:
    """How far point q lies beyond the wall (negative: in front of it)."""
    if w.cylinder:
        return sqrt((q[w.b] - w.centre[w.b]) ** 2 + (q[w.c] - w.centre[w.c]) ** 2) - w.r
    return -w.side * (q[w.a] - w.pos)


cdef inline void centroid_beyond(const ShapeRef* S, const double* R, const double* x, const double* dn,
                                 const Surface* w, double tol, double* c) noexcept nogil:
    """Depth-weighted centroid of the candidate points beyond the wall, each weighted by its depth + tol
    (tol, a round-off margin, makes points level with the deepest one count alike when the overlap starts);
    c is left unchanged when there is none. The walls' `point centroid`."""
    cdef double acc[3]
    cdef double q[3]
    cdef double wsum = 0.0, depth
    cdef int k = 0
    acc[0] = acc[1] = acc[2] = 0.0
    while candidate_point(S, R, x, dn, k, q):
        k += 1
        depth = tol + surface_depth(w, q)
        if depth > 0.0:
            acc[0] += depth * q[0]
            acc[1] += depth * q[1]
            acc[2] += depth * q[2]
            wsum += depth
    if wsum > 0.0:
        for k in range(3):
            c[k] = acc[k] / wsum


cdef inline double plane_touch(const ShapeRef* S, const double* R, const double* x, const Surface* w,
                               bint centroid, double tol, const double* bias, double* n,
                               double* q) noexcept nogil:
    """A posed body against the plane w (w.cylinder false): the overlap (<= 0: apart), n the unit normal from
    the wall into the body and q the contact point: the deepest point (support along -n), or the centroid
    of the candidate points beyond the wall, moved midway into the overlap. `bias` (NULL: none), a vector
    of length ~1e-9 added to the support direction, breaks ties between equally deep points (a face or an
    edge parallel to the wall) towards it: a composite's components pick the points away from its centre,
    mirror-symmetrically, instead of the same corner each."""
    cdef double dn[3]
    cdef double delta
    cdef int d
    for d in range(3):
        n[d] = 0.0
    n[w.a] = w.side
    for d in range(3):
        dn[d] = -n[d]
    if bias != NULL:
        for d in range(3):
            dn[d] += bias[d]
    support_world(S, R, x, dn, q)
    delta = -w.side * (q[w.a] - w.pos)
    if delta <= 0.0:
        return delta
    if centroid:
        centroid_beyond(S, R, x, dn, w, tol, q)
    q[w.a] = w.pos - 0.5 * delta * w.side
    return delta


cdef inline void farthest_from_axis(const ShapeRef* S, const double* R, const double* xi, int b, int c,
                                    const double* centre, double* u, double* p) noexcept nogil:
    """p: the point of the posed body farthest from the axis (the axis is normal to b, c), u: the unit
    radial direction at p. On entry u is the radial direction of the centre. Polytopes: their farthest
    vertex. Curved bodies: p = support(radial direction of p), iterated from u (the error shrinks by about
    size / R per iteration)."""
    cdef double rb, rc, rho, best = -1.0
    cdef double q[3]
    cdef int it, k = 0
    if S.kind == BOX or S.kind == POLYHEDRON:
        while candidate_point(S, R, xi, u, k, q):
            k += 1
            rho = (q[b] - centre[b]) ** 2 + (q[c] - centre[c]) ** 2
            if rho > best:
                best = rho
                p[0] = q[0]
                p[1] = q[1]
                p[2] = q[2]
        if best > 0.0:
            rho = sqrt(best)
            u[b] = (p[b] - centre[b]) / rho
            u[c] = (p[c] - centre[c]) / rho
            return
    for it in range(40):
        support_world(S, R, xi, u, p)
        rb = p[b] - centre[b]
        rc = p[c] - centre[c]
        rho = sqrt(rb * rb + rc * rc)
        if rho == 0.0:
            return
        rb /= rho
        rc /= rho
        if (rb - u[b]) * (rb - u[b]) + (rc - u[c]) * (rc - u[c]) <= 1e-28:
            return
        u[b] = rb
        u[c] = rc
    support_world(S, R, xi, u, p)


cdef inline double cylinder_touch(const ShapeRef* S, const double* R, const double* x, const Surface* w,
                                  bint centroid, double tol, double* n, double* q) noexcept nogil:
    """A posed body inside the cylinder w: the overlap (<= 0: apart), n the unit normal from the wall into
    the body (towards the axis) and q the contact point, midway in the overlap radially. The axial
    coordinate of w.centre is taken as x's (the caller's convention for the turning velocity)."""
    cdef double u[3]
    cdef double cen[3]
    cdef double rho, rho_q, delta
    cdef int d, a = w.a, b = w.b, c = w.c
    for d in range(3):
        cen[d] = w.centre[d]
    cen[a] = x[a]
    u[b] = x[b] - cen[b]
    u[c] = x[c] - cen[c]
    rho = sqrt(u[b] * u[b] + u[c] * u[c])
    u[a] = 0.0
    u[b] = u[b] / rho if rho > 0.0 else 1.0
    u[c] = u[c] / rho if rho > 0.0 else 0.0
    farthest_from_axis(S, R, x, b, c, cen, u, q)
    rho_q = sqrt((q[b] - cen[b]) ** 2 + (q[c] - cen[c]) ** 2)
    if rho_q <= w.r:
        return 0.0
    delta = rho_q - w.r
    if centroid:                              # keep the overlap, move the point
        centroid_beyond(S, R, x, u, w, tol, q)
        rho_q = sqrt((q[b] - cen[b]) ** 2 + (q[c] - cen[c]) ** 2)
        u[b] = (q[b] - cen[b]) / rho_q
        u[c] = (q[c] - cen[c]) / rho_q
    for d in range(3):                        # midway in the overlap, radially
        n[d] = -u[d]
    q[b] = cen[b] + (w.r + 0.5 * delta) * u[b]
    q[c] = cen[c] + (w.r + 0.5 * delta) * u[c]
    return delta
