# cython: language_level=3
"""Sphere-sphere contacts: analytic geometry, then the shared Grains3D law (dem_contact/law.pxd)."""
cimport numpy as cnp
from libc.math cimport sqrt
from dem_contact.law cimport forget, hooke, rolling_torque

ctypedef cnp.int64_t i64


def compute(const double[:, ::1] x, const double[:, ::1] v, const double[:, ::1] omega,
            double[:, ::1] f, double[:, ::1] torque, const double[::1] radius, const double[::1] rmass,
            const int[::1] type_, int nlocal, const i64[::1] offsets, const int[::1] neigh,
            const double[:, :, ::1] coeff, double[:, ::1] xi, bint use_history, double dt, bint advance,
            double[::1] stats, i64[::1] worst):
    """Adds contact forces and torques to f and torque (owned and ghost rows). stats receives
    [contacts, max overlap / smaller diameter, elastic energy]; worst the (i, j) of the largest overlap."""
    cdef int i, j, k, d, ncont = 0
    cdef double dx[3]
    cdef double n[3]
    cdef double vr[3]
    cdef double w[3]
    cdef double fn[3]
    cdef double ft[3]
    cdef double nxft[3]
    cdef double tr[3]
    cdef double r2, r, rinv, rsum, delta, meff, ci, cj, energy = 0.0, ov, maxov = 0.0
    cdef const double* c
    cdef double* h
    with nogil:
        for i in range(nlocal):
            for k in range(offsets[i], offsets[i + 1]):
                j = neigh[k]
                dx[0] = x[i, 0] - x[j, 0]
                dx[1] = x[i, 1] - x[j, 1]
                dx[2] = x[i, 2] - x[j, 2]
                r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]
                rsum = radius[i] + radius[j]
                if r2 >= rsum * rsum:
                    if use_history and advance:
                        forget(&xi[k, 0])
                    continue
                r = sqrt(r2)
                rinv = 1.0 / r
                for d in range(3):
                    n[d] = dx[d] * rinv
                delta = rsum - r
                ncont += 1
                ov = delta / (2.0 * (radius[i] if radius[i] < radius[j] else radius[j]))
                if ov > maxov:
                    maxov = ov
                    worst[0] = i
                    worst[1] = j
                meff = rmass[i] * rmass[j] / (rmass[i] + rmass[j])
                # contact point in the middle of the overlap: levers -ci n (from i) and +cj n (from j)
                ci = radius[i] - 0.5 * delta
                cj = radius[j] - 0.5 * delta
                for d in range(3):
                    w[d] = ci * omega[i, d] + cj * omega[j, d]
                vr[0] = v[i, 0] - v[j, 0] - (w[1] * n[2] - w[2] * n[1])
                vr[1] = v[i, 1] - v[j, 1] - (w[2] * n[0] - w[0] * n[2])
                vr[2] = v[i, 2] - v[j, 2] - (w[0] * n[1] - w[1] * n[0])
                c = &coeff[type_[i], type_[j], 0]
                h = &xi[k, 0] if use_history else NULL
                energy += hooke(c, delta, n, vr, meff, h, dt, advance, fn, ft)
                for d in range(3):
                    f[i, d] += fn[d] + ft[d]
                    f[j, d] -= fn[d] + ft[d]
                nxft[0] = n[1] * ft[2] - n[2] * ft[1]
                nxft[1] = n[2] * ft[0] - n[0] * ft[2]
                nxft[2] = n[0] * ft[1] - n[1] * ft[0]
                for d in range(3):
                    torque[i, d] -= ci * nxft[d]
                    torque[j, d] -= cj * nxft[d]
                # rolling resistance: a torque mu_roll R_eff |F_n| against the relative rolling
                if rolling_torque(c, &omega[i, 0], &omega[j, 0], fn, radius[i] * radius[j] / rsum, tr):
                    for d in range(3):
                        torque[i, d] += tr[d]
                        torque[j, d] -= tr[d]
    stats[0] = ncont
    stats[1] = maxov
    stats[2] = energy
