# cython: language_level=3
"""Kernels of the fixes: planar walls (shared Grains3D law, m_ij = m_i against a wall) and gravity."""
from libc.math cimport sqrt
from dem_contact.law cimport hooke


def plane_walls(const double[:, ::1] x, const double[:, ::1] v, const double[:, ::1] omega,
                double[:, ::1] f, double[:, ::1] torque, const double[::1] radius, const double[::1] rmass,
                const int[::1] type_, const int[::1] mask, int groupbit, int nlocal,
                const int[::1] axis, const double[::1] position, const double[::1] side,
                const double[:, :, ::1] coeff, double[:, ::1] xi, bint use_history, double dt, bint advance,
                double[::1] stats):
    """Walls w: the plane axis[w] = position[w], particles on the side where side[w] * (x - position) > 0.
    xi holds 3 history values per wall per particle. stats: [contacts, max overlap / diameter]."""
    cdef int i, w, d, a, nw = axis.shape[0], ncont = 0
    cdef double gap, delta, ci, ov, maxov = 0.0
    cdef double n[3]
    cdef double vr[3]
    cdef double fn[3]
    cdef double ft[3]
    cdef double* h
    with nogil:
        for i in range(nlocal):
            if not (mask[i] & groupbit):
                continue
            for w in range(nw):
                a = axis[w]
                gap = side[w] * (x[i, a] - position[w])
                if gap >= radius[i]:
                    # a contact that ended forgets its history (written only when set: saves bandwidth)
                    if use_history and advance and (xi[i, 3 * w] != 0.0 or xi[i, 3 * w + 1] != 0.0
                                                    or xi[i, 3 * w + 2] != 0.0):
                        xi[i, 3 * w] = 0.0
                        xi[i, 3 * w + 1] = 0.0
                        xi[i, 3 * w + 2] = 0.0
                    continue
                delta = radius[i] - gap
                ncont += 1
                ov = delta / (2.0 * radius[i])
                if ov > maxov:
                    maxov = ov
                n[0] = 0.0
                n[1] = 0.0
                n[2] = 0.0
                n[a] = side[w]
                ci = radius[i] - 0.5 * delta
                # velocity of the particle surface at the contact point (lever -ci n); the wall is at rest
                vr[0] = v[i, 0] - ci * (omega[i, 1] * n[2] - omega[i, 2] * n[1])
                vr[1] = v[i, 1] - ci * (omega[i, 2] * n[0] - omega[i, 0] * n[2])
                vr[2] = v[i, 2] - ci * (omega[i, 0] * n[1] - omega[i, 1] * n[0])
                h = &xi[i, 3 * w] if use_history else NULL
                hooke(&coeff[w, type_[i], 0], delta, n, vr, rmass[i], h, dt, advance, fn, ft)
                for d in range(3):
                    f[i, d] += fn[d] + ft[d]
                torque[i, 0] -= ci * (n[1] * ft[2] - n[2] * ft[1])
                torque[i, 1] -= ci * (n[2] * ft[0] - n[0] * ft[2])
                torque[i, 2] -= ci * (n[0] * ft[1] - n[1] * ft[0])
    stats[0] = ncont
    stats[1] = maxov


def gravity(double[:, ::1] f, const double[::1] rmass, const int[::1] mask, int groupbit, int nlocal,
            double gx, double gy, double gz):
    """f += m g for the particles of the group."""
    cdef int i
    with nogil:
        for i in range(nlocal):
            if mask[i] & groupbit:
                f[i, 0] += rmass[i] * gx
                f[i, 1] += rmass[i] * gy
                f[i, 2] += rmass[i] * gz
