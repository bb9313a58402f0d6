# cython: language_level=3
"""Local non-viscous damping (Potyondy & Cundall 2004, Int. J. Rock Mech. Min. Sci. 41, 1329):
F <- F - alpha |F| sign(v), component by component, and the same for the torque with the angular
velocity. With the leap-frog scheme v is the stored half-step velocity v(n-1/2), as in PFC."""
from libc.math cimport fabs


def damp(double[:, ::1] f, double[:, ::1] torque, const double[:, ::1] v, const double[:, ::1] omega,
         const int[::1] mask, int groupbit, int nlocal, double alpha, double[::1] stats):
    """stats: [work rate of the damping forces and torques, sum F_damp . v + T_damp . omega] (<= 0)."""
    cdef int i, d
    cdef double df, a, power = 0.0
    with nogil:
        for i in range(nlocal):
            if not (mask[i] & groupbit):
                continue
            for d in range(3):
                # sign(v) without branches: (v > 0) - (v < 0), 0 for v = 0
                a = v[i, d]
                df = alpha * fabs(f[i, d]) * (<double>(a > 0.0) - <double>(a < 0.0))
                f[i, d] -= df
                power -= df * a
                a = omega[i, d]
                df = alpha * fabs(torque[i, d]) * (<double>(a > 0.0) - <double>(a < 0.0))
                torque[i, d] -= df
                power -= df * a
    stats[0] = power
