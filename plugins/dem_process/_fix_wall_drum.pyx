# cython: language_level=3
"""Particle-wall contacts with a rotating cylinder (particles inside) and its optional flat end walls,
with the shared Grains3D law (m_ij = m_i against a wall). The wall surface moves: its velocity at the
contact point, Omega e_axis x (p - centre), enters the relative velocity, so friction drives the bed.

Shaped particles (shape table rows that are not spheres) touch a wall at their deepest point: against a
flat end, the support point along the outward normal; against the cylinder, the point of the body
farthest from the axis: the farthest vertex of a polytope; on a curved body, found by iterating
p = support(radial direction of p) from the radial direction of the centre (a fixed point is where the
body's normal is radial; each iteration shrinks the error by about size / R_drum). The contact point lies
midway in the overlap, the lever runs from the centre of mass to it (Grains3D: one point per contact, no
rolling resistance); `point centroid` moves it to the depth-weighted centroid of the vertices beyond."""
cimport numpy as cnp
from libc.math cimport sqrt
from dem_contact.law cimport forget, hooke, push_at, rolling_torque
from dem.shapes._support cimport (ShapeRef, Surface, BOX, POLYHEDRON, candidate_point, centroid_beyond,
                                  plane_touch, pose_shape, support_world)

ctypedef cnp.int64_t i64


cdef inline void _contact(int i, int w, const double[:, ::1] x, const double[:, ::1] v,
                          const double[:, ::1] omega, double[:, ::1] f, double[:, ::1] torque,
                          const double[::1] radius, const double[::1] rmass, const int[::1] type_,
                          const double[:, :, ::1] coeff, double[:, ::1] xi, bint use_history, double dt,
                          bint advance, double delta, const double* n, const double* e,
                          const double* centre, double wall_omega, double* stats) noexcept nogil:
    """One contact of particle i with wall w: overlap delta, unit normal n from the wall into the particle;
    the wall moves as a rigid body rotating at wall_omega about the axis e through centre."""
    cdef double ci = radius[i] - 0.5 * delta
    cdef double p[3]
    cdef double vw[3]
    cdef double vr[3]
    cdef double fn[3]
    cdef double ft[3]
    cdef double ftot[3]
    cdef double ww[3]
    cdef double tr[3]
    cdef double* h
    cdef const double* c = &coeff[w, type_[i], 0]
    cdef int d
    for d in range(3):
        p[d] = x[i, d] - ci * n[d] - centre[d]          # contact point relative to the axis point
    vw[0] = wall_omega * (e[1] * p[2] - e[2] * p[1])
    vw[1] = wall_omega * (e[2] * p[0] - e[0] * p[2])
    vw[2] = wall_omega * (e[0] * p[1] - e[1] * p[0])
    # velocity of the particle surface at the contact point (lever -ci n) minus that of the wall
    vr[0] = v[i, 0] - ci * (omega[i, 1] * n[2] - omega[i, 2] * n[1]) - vw[0]
    vr[1] = v[i, 1] - ci * (omega[i, 2] * n[0] - omega[i, 0] * n[2]) - vw[1]
    vr[2] = v[i, 2] - ci * (omega[i, 0] * n[1] - omega[i, 1] * n[0]) - vw[2]
    h = &xi[i, 3 * w] if use_history else NULL
    stats[3] += hooke(c, delta, n, vr, rmass[i], h, dt, advance, fn, ft)
    for d in range(3):
        ftot[d] = fn[d] + ft[d]
        f[i, d] += ftot[d]
    torque[i, 0] -= ci * (n[1] * ft[2] - n[2] * ft[1])
    torque[i, 1] -= ci * (n[2] * ft[0] - n[0] * ft[2])
    torque[i, 2] -= ci * (n[0] * ft[1] - n[1] * ft[0])
    # torque of the wall on the particles about the axis: e . (p x F)
    stats[2] += (e[0] * (p[1] * ftot[2] - p[2] * ftot[1]) + e[1] * (p[2] * ftot[0] - p[0] * ftot[2])
                 + e[2] * (p[0] * ftot[1] - p[1] * ftot[0]))
    # rolling resistance (as pair sphere, R_eff = r_i) against the spin relative to the wall
    for d in range(3):
        ww[d] = wall_omega * e[d]
    if rolling_torque(c, &omega[i, 0], ww, fn, radius[i], tr):
        for d in range(3):
            torque[i, d] += tr[d]
        stats[2] += tr[0] * e[0] + tr[1] * e[1] + tr[2] * e[2]
    stats[0] += 1.0
    if delta / (2.0 * radius[i]) > stats[1]:
        stats[1] = delta / (2.0 * radius[i])


cdef inline void _contact_shaped(int i, int w, const double[:, ::1] x, const double[:, ::1] v,
                                 const double[:, ::1] omega, double[:, ::1] f, double[:, ::1] torque,
                                 const double[::1] radius, const double[::1] rmass, const int[::1] type_,
                                 const double[:, :, ::1] coeff, double[:, ::1] xi, bint use_history, double dt,
                                 bint advance, double delta, const double* n, const double* q,
                                 const double* e, const double* centre, double wall_omega,
                                 double* stats) noexcept nogil:
    """One contact of shaped particle i with wall w at point q (absolute), overlap delta, unit normal n from
    the wall into the particle; lever from the centre of mass to q."""
    cdef double l[3]
    cdef double p[3]
    cdef double vw[3]
    cdef double F[3]
    cdef int d
    for d in range(3):
        l[d] = q[d] - x[i, d]
        p[d] = q[d] - centre[d]
    vw[0] = wall_omega * (e[1] * p[2] - e[2] * p[1])
    vw[1] = wall_omega * (e[2] * p[0] - e[0] * p[2])
    vw[2] = wall_omega * (e[0] * p[1] - e[1] * p[0])
    stats[3] += push_at(&coeff[w, type_[i], 0], delta, n, l, &v[i, 0], &omega[i, 0], vw, rmass[i],
                        &xi[i, 3 * w] if use_history else NULL, dt, advance, &f[i, 0], &torque[i, 0], F)
    stats[2] += (e[0] * (p[1] * F[2] - p[2] * F[1]) + e[1] * (p[2] * F[0] - p[0] * F[2])
                 + e[2] * (p[0] * F[1] - p[1] * F[0]))
    stats[0] += 1.0
    if delta / (2.0 * radius[i]) > stats[1]:
        stats[1] = delta / (2.0 * radius[i])


cdef inline void _farthest_from_axis(const ShapeRef* S, const double* R, const double* xi, int b, int c,
                                     const double* centre, double* u, double* p) noexcept nogil:
    """p: the point of the posed body farthest from the axis (the axis is normal to b, c), u: the unit
    radial direction at p. On entry u is the radial direction of the centre. Polytopes: their farthest
    vertex. Curved bodies: p = support(radial direction of p), iterated from u."""
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
    for it in range(40):              # the error shrinks by ~ size / R_drum per iteration
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


def drum_walls(const double[:, ::1] x, const double[:, ::1] v, const double[:, ::1] omega,
               double[:, ::1] f, double[:, ::1] torque, const double[::1] radius, const double[::1] rmass,
               const int[::1] type_, const int[::1] mask, int groupbit, int nlocal, int axis,
               const double[::1] centre, double rdrum, double wall_omega, int nends,
               double end_lo, double end_hi, bint ends_rotate, const double[:, :, ::1] coeff,
               double[:, ::1] xi, bint use_history, double dt, bint advance, double[::1] stats,
               const double[:, ::1] quat, const int[::1] shape, const int[::1] is_sphere,
               const int[::1] skind, const double[:, ::1] sparams, const i64[::1] svoff,
               const int[::1] snv, const double[:, ::1] verts, const double[::1] srad, bint centroid=False):
    """Wall 0: the cylinder of radius rdrum about axis (0, 1, 2) through centre (3 values, the axis
    component unused). Walls 1 and 2 (nends = 2): flat ends at axis = end_lo (facing +) and end_hi (facing
    -), rotating with the drum when ends_rotate. xi: 3 history values per wall per particle.
    stats: [contacts, max overlap / diameter, torque of the walls on the particles about the axis,
    elastic energy stored in the wall contacts]. Shape table arrays (body, not core): see
    dem.shape_command.SimShapes.kernel_arrays. centroid: contact points of shaped particles at the
    depth-weighted centroid of their candidate points beyond the wall (fix wall/plane point centroid)."""
    cdef int i, d, w, b = (axis + 1) % 3, c = (axis + 2) % 3
    cdef double rho, gap, delta, endw = wall_omega if ends_rotate else 0.0
    cdef double e[3]
    cdef double n[3]
    cdef double cen[3]
    cdef double st[4]
    cdef double u[3]
    cdef double q[3]
    cdef double R[9]
    cdef double rho_q
    cdef int s
    cdef bint posed
    cdef ShapeRef S
    cdef Surface drum, end
    drum.cylinder = True
    drum.b = b
    drum.c = c
    drum.r = rdrum
    end.cylinder = False
    end.a = axis
    st[3] = 0.0
    for d in range(3):
        e[d] = 0.0
        cen[d] = centre[d]
        st[d] = 0.0
    e[axis] = 1.0
    for d in range(3):
        drum.centre[d] = centre[d]
    with nogil:
        for i in range(nlocal):
            if not (mask[i] & groupbit):
                continue
            cen[axis] = x[i, axis]
            s = shape[i]
            if s >= 0 and not is_sphere[s]:
                posed = False
                n[b] = x[i, b] - centre[b]
                n[c] = x[i, c] - centre[c]
                rho = sqrt(n[b] * n[b] + n[c] * n[c])
                if rdrum - rho >= radius[i]:                      # bounding sphere clear of the drum
                    if use_history and advance:
                        forget(&xi[i, 0])
                else:
                    pose_shape(&S, skind[s], &sparams[s, 0], snv[s], &verts[svoff[s], 0], &quat[i, 0],
                               radius[i] / srad[s], R)
                    posed = True
                    u[axis] = 0.0
                    u[b] = n[b] / rho if rho > 0.0 else 1.0
                    u[c] = n[c] / rho if rho > 0.0 else 0.0
                    _farthest_from_axis(&S, R, &x[i, 0], b, c, cen, u, q)
                    rho_q = sqrt((q[b] - cen[b]) ** 2 + (q[c] - cen[c]) ** 2)
                    if rho_q <= rdrum:
                        if use_history and advance:
                            forget(&xi[i, 0])
                    else:
                        delta = rho_q - rdrum
                        if centroid:                              # keep the overlap, move the point
                            centroid_beyond(&S, R, &x[i, 0], u, &drum, 1e-9 * radius[i], q)
                            rho_q = sqrt((q[b] - cen[b]) ** 2 + (q[c] - cen[c]) ** 2)
                            u[b] = (q[b] - cen[b]) / rho_q
                            u[c] = (q[c] - cen[c]) / rho_q
                        for d in range(3):                        # midway in the overlap, radially
                            n[d] = -u[d]
                        q[b] = cen[b] + (rdrum + 0.5 * delta) * u[b]
                        q[c] = cen[c] + (rdrum + 0.5 * delta) * u[c]
                        _contact_shaped(i, 0, x, v, omega, f, torque, radius, rmass, type_, coeff, xi,
                                        use_history, dt, advance, delta, n, q, e, cen, wall_omega, st)
                for w in range(1, nends + 1):
                    gap = x[i, axis] - end_lo if w == 1 else end_hi - x[i, axis]
                    if gap >= radius[i]:
                        if use_history and advance:
                            forget(&xi[i, 3 * w])
                        continue
                    if not posed:
                        pose_shape(&S, skind[s], &sparams[s, 0], snv[s], &verts[svoff[s], 0], &quat[i, 0],
                                   radius[i] / srad[s], R)
                        posed = True
                    end.side = 1.0 if w == 1 else -1.0
                    end.pos = end_lo if w == 1 else end_hi
                    delta = plane_touch(&S, R, &x[i, 0], &end, centroid, 1e-9 * radius[i], n, q)
                    if delta <= 0.0:
                        if use_history and advance:
                            forget(&xi[i, 3 * w])
                        continue
                    _contact_shaped(i, w, x, v, omega, f, torque, radius, rmass, type_, coeff, xi,
                                    use_history, dt, advance, delta, n, q, e, cen, endw, st)
                continue
            # cylinder: the gap is R - rho, the normal points to the axis
            n[b] = x[i, b] - centre[b]
            n[c] = x[i, c] - centre[c]
            rho = sqrt(n[b] * n[b] + n[c] * n[c])
            gap = rdrum - rho
            if gap >= radius[i] or rho == 0.0:
                if use_history and advance:
                    forget(&xi[i, 0])
            else:
                n[axis] = 0.0
                n[b] = -n[b] / rho
                n[c] = -n[c] / rho
                _contact(i, 0, x, v, omega, f, torque, radius, rmass, type_, coeff, xi, use_history, dt,
                         advance, radius[i] - gap, n, e, cen, wall_omega, st)
            for w in range(1, nends + 1):
                gap = x[i, axis] - end_lo if w == 1 else end_hi - x[i, axis]
                if gap >= radius[i]:
                    if use_history and advance:
                        forget(&xi[i, 3 * w])
                    continue
                n[0] = 0.0
                n[1] = 0.0
                n[2] = 0.0
                n[axis] = 1.0 if w == 1 else -1.0
                _contact(i, w, x, v, omega, f, torque, radius, rmass, type_, coeff, xi, use_history, dt,
                         advance, radius[i] - gap, n, e, cen, endw, st)
    for d in range(4):
        stats[d] = st[d]
