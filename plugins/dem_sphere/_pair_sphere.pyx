# cython: language_level=3
"""Sphere-sphere contacts: analytic geometry (contact point midway in the overlap, levers along the line of
centres), then the shared law (dem/law/apply.pxd). A pair whose row acts beyond contact (JKR, a liquid
bridge) keeps its contact after the surfaces part, while bonded and within the row's reach (dem/law/law.pxd)."""
cimport numpy as cnp
from libc.math cimport sqrt
from dem._particles cimport ParticleView, Particles, count_contact
from dem.contact.record cimport Contact
from dem.law.apply cimport Body, apply_pair, bind_body
from dem.law.law cimport forget, holds
from dem.law.rolling cimport sphere_rolling_inertia
from dem.law.row cimport C_ETA_ROLL

ctypedef cnp.int64_t i64


def compute(ParticleView view, const i64[::1] offsets, const int[::1] neigh, const double[:, :, ::1] coeff,
            double[:, ::1] hist, bint use_history, bint bonds, double dt, bint advance, double[::1] stats,
            i64[::1] worst):
    """Adds contact forces and torques to f and torque (owned and ghost rows). hist: each listed pair's
    history (the law's width); bonds: whether a row of the table acts beyond contact once touched (the
    pairs apart are then asked). stats receives [contacts, max overlap / smaller diameter, elastic energy];
    worst the (i, j) of the largest overlap."""
    cdef Particles particles = view.p          # local copies: no call can change them (kept in registers)
    cdef const Particles* P = &particles
    cdef int i, j, k, d, ncont = 0
    cdef int width = hist.shape[1]
    cdef double dx[3]
    cdef double out[6]
    cdef double r2, r, rinv, rsum, meff, reff, energy = 0.0, ov, maxov = 0.0
    cdef double* h = NULL
    cdef const double* cf
    cdef Contact con
    cdef Body A, B
    con.central = True
    con.key = 0
    con.weight = 1.0
    con.inertia = 0.0
    with nogil:
        for i in range(P.nlocal):
            bind_body(&A, P, i)
            for k in range(offsets[i], offsets[i + 1]):
                j = neigh[k]
                dx[0] = P.x[3 * i] - P.x[3 * j]
                dx[1] = P.x[3 * i + 1] - P.x[3 * j + 1]
                dx[2] = P.x[3 * i + 2] - P.x[3 * j + 2]
                r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]
                rsum = P.radius[i] + P.radius[j]
                if r2 >= rsum * rsum:
                    # apart: a bonded pair holds until its reach, any other forgets its history
                    if not (bonds and holds(&coeff[P.type[i], P.type[j], 0], &hist[k, 0],
                                                     sqrt(r2) - rsum, P.radius[i] * P.radius[j] / rsum)):
                        if use_history and advance:
                            forget(&hist[k, 0], width)
                        continue
                cf = &coeff[P.type[i], P.type[j], 0]
                h = &hist[k, 0] if use_history else NULL
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
                reff = P.radius[i] * P.radius[j] / rsum
                if cf[C_ETA_ROLL] > 0.0:
                    con.inertia = 1.0 / (1.0 / sphere_rolling_inertia(P.rmass[i], P.radius[i])
                                         + 1.0 / sphere_rolling_inertia(P.rmass[j], P.radius[j]))
                # contact point in the middle of the overlap: levers -arm_a n (from i) and +arm_b n (from j)
                con.arm_a = P.radius[i] - 0.5 * con.delta
                con.arm_b = P.radius[j] - 0.5 * con.delta
                bind_body(&B, P, j)
                energy += apply_pair(cf, &con, &A, &B, meff, reff, h, dt, advance, out)
    stats[0] = ncont
    stats[1] = maxov
    stats[2] = energy
