# cython: language_level=3
"""Particle-wall contacts with a rotating cylinder (particles inside) and its optional flat end walls,
with the shared Grains3D law (m_ij = m_i against a wall). The wall surface moves: its velocity at the
contact point, Omega e_axis x (p - centre), enters the relative velocity, so friction drives the bed."""
from libc.math cimport sqrt
from dem_contact.law cimport forget, hooke


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
    cdef double wr[3]
    cdef double* h
    cdef const double* c = &coeff[w, type_[i], 0]
    cdef double wmag, mr
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
    if c[5] > 0.0:
        # rolling resistance (as pair sphere, R_eff = r_i): mu_roll r_i |F_n| against the rolling relative
        # to the wall, which spins at wall_omega about e
        for d in range(3):
            wr[d] = omega[i, d] - wall_omega * e[d]
        wmag = sqrt(wr[0] * wr[0] + wr[1] * wr[1] + wr[2] * wr[2])
        if wmag > 0.0:
            mr = c[5] * radius[i] * sqrt(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2]) / wmag
            for d in range(3):
                torque[i, d] -= mr * wr[d]
            stats[2] -= mr * (wr[0] * e[0] + wr[1] * e[1] + wr[2] * e[2])
    stats[0] += 1.0
    if delta / (2.0 * radius[i]) > stats[1]:
        stats[1] = delta / (2.0 * radius[i])


def drum_walls(const double[:, ::1] x, const double[:, ::1] v, const double[:, ::1] omega,
               double[:, ::1] f, double[:, ::1] torque, const double[::1] radius, const double[::1] rmass,
               const int[::1] type_, const int[::1] mask, int groupbit, int nlocal, int axis,
               const double[::1] centre, double rdrum, double wall_omega, int nends,
               double end_lo, double end_hi, bint ends_rotate, const double[:, :, ::1] coeff,
               double[:, ::1] xi, bint use_history, double dt, bint advance, double[::1] stats):
    """Wall 0: the cylinder of radius rdrum about axis (0, 1, 2) through centre (3 values, the axis
    component unused). Walls 1 and 2 (nends = 2): flat ends at axis = end_lo (facing +) and end_hi (facing
    -), rotating with the drum when ends_rotate. xi: 3 history values per wall per particle.
    stats: [contacts, max overlap / diameter, torque of the walls on the particles about the axis,
    elastic energy stored in the wall contacts]."""
    cdef int i, d, w, b = (axis + 1) % 3, c = (axis + 2) % 3
    cdef double rho, gap, delta, endw = wall_omega if ends_rotate else 0.0
    cdef double e[3]
    cdef double n[3]
    cdef double cen[3]
    cdef double st[4]
    st[3] = 0.0
    for d in range(3):
        e[d] = 0.0
        cen[d] = centre[d]
        st[d] = 0.0
    e[axis] = 1.0
    with nogil:
        for i in range(nlocal):
            if not (mask[i] & groupbit):
                continue
            cen[axis] = x[i, axis]
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
