# cython: language_level=3
"""Ghost refresh (forward) and ghost force return (reverse) for ghosts that are periodic images of owned
particles of this process."""
cimport numpy as cnp

ctypedef cnp.int64_t i64


def forward(double[:, ::1] x, double[:, ::1] v, double[:, ::1] omega, double[:, ::1] quat,
            const i64[::1] owner, const double[:, ::1] shift, int nlocal):
    cdef int g, i, d, n = owner.shape[0]
    with nogil:
        for g in range(n):
            i = owner[g]
            for d in range(3):
                x[nlocal + g, d] = x[i, d] + shift[g, d]
                v[nlocal + g, d] = v[i, d]
                omega[nlocal + g, d] = omega[i, d]
            for d in range(4):
                quat[nlocal + g, d] = quat[i, d]


def reverse(double[:, ::1] f, double[:, ::1] torque, const i64[::1] owner, int nlocal):
    """Adds ghost rows to their owners in ghost order (deterministic sums)."""
    cdef int g, i, d, n = owner.shape[0]
    with nogil:
        for g in range(n):
            i = owner[g]
            for d in range(3):
                f[i, d] += f[nlocal + g, d]
                torque[i, d] += torque[nlocal + g, d]


def reverse_rows(double[:, ::1] a, const i64[::1] owner, int nlocal):
    """Adds the ghost rows of a float field (n, width) to their owners in ghost order: the sums of
    np.add.at, without its per-element dispatch (the contact tallies, every step)."""
    cdef int g, i, d, n = owner.shape[0], w = a.shape[1]
    with nogil:
        for g in range(n):
            i = owner[g]
            for d in range(w):
                a[i, d] += a[nlocal + g, d]
