# cython: language_level=3
"""Kernel of fix gravity."""


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
