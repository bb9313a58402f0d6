# cython: language_level=3
"""Sphere-sphere contacts: analytic geometry (contact point midway in the overlap, levers along the line of
centres), then the shared law (dem_contact/apply.pxd)."""
cimport numpy as cnp
from libc.math cimport sqrt
from dem._particles cimport ParticleView, Particles, count_contact
from dem.contact.record cimport Contact
from dem_contact.apply cimport Body, apply_pair
from dem_contact.law cimport forget

ctypedef cnp.int64_t i64


def compute(ParticleView view, const i64[::1] offsets, const int[::1] neigh, const double[:, :, ::1] coeff,
            double[:, ::1] xi, bint use_history, double dt, bint advance, double[::1] stats, i64[::1] worst):
    """Adds contact forces and torques to f and torque (owned and ghost rows). stats receives
    [contacts, max overlap / smaller diameter, elastic energy]; worst the (i, j) of the largest overlap."""
    cdef Particles particles = view.p          # local copies: no call can change them (kept in registers)
    cdef const Particles* P = &particles
    cdef int i, j, k, d, ncont = 0
    cdef double dx[3]
    cdef double out[6]
    cdef double r2, r, rinv, rsum, meff, energy = 0.0, ov, maxov = 0.0
    cdef Contact con
    cdef Body A, B
    con.central = True
    con.key = 0
    con.weight = 1.0
    with nogil:
        for i in range(P.nlocal):
            A.x = &P.x[3 * i]
            A.v = &P.v[3 * i]
            A.w = &P.omega[3 * i]
            A.f = &P.f[3 * i]
            A.t = &P.torque[3 * i]
            A.s = &P.stress[9 * i] if P.stress != NULL else NULL
            for k in range(offsets[i], offsets[i + 1]):
                j = neigh[k]
                dx[0] = P.x[3 * i] - P.x[3 * j]
                dx[1] = P.x[3 * i + 1] - P.x[3 * j + 1]
                dx[2] = P.x[3 * i + 2] - P.x[3 * j + 2]
                r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]
                rsum = P.radius[i] + P.radius[j]
                if r2 >= rsum * rsum:
                    if use_history and advance:
                        forget(&xi[k, 0])
                    continue
                r = sqrt(r2)
                rinv = 1.0 / r
                for d in range(3):
                    con.n[d] = dx[d] * rinv
                con.delta = rsum - r
                ncont += 1
                count_contact(P, i, j, 1)
                ov = con.delta / (2.0 * (P.radius[i] if P.radius[i] < P.radius[j] else P.radius[j]))
                if ov > maxov:
                    maxov = ov
                    worst[0] = i
                    worst[1] = j
                meff = P.rmass[i] * P.rmass[j] / (P.rmass[i] + P.rmass[j])
                # contact point in the middle of the overlap: levers -arm_a n (from i) and +arm_b n (from j)
                con.arm_a = P.radius[i] - 0.5 * con.delta
                con.arm_b = P.radius[j] - 0.5 * con.delta
                B.x = &P.x[3 * j]
                B.v = &P.v[3 * j]
                B.w = &P.omega[3 * j]
                B.f = &P.f[3 * j]
                B.t = &P.torque[3 * j]
                B.s = &P.stress[9 * j] if P.stress != NULL else NULL
                energy += apply_pair(&coeff[P.type[i], P.type[j], 0], &con, &A, &B, meff,
                                    P.radius[i] * P.radius[j] / rsum, &xi[k, 0] if use_history else NULL,
                                    dt, advance, out)
    stats[0] = ncont
    stats[1] = maxov
    stats[2] = energy
