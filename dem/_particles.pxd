# cython: language_level=3
"""The particle arrays as kernels see them: one struct of pointers (Particles) into the atom store,
rebuilt at every kernel call (arrays grow and move: never kept across calls). Row i of a 3-vector field
is x[3 i:3 i + 3]; ghosts follow the owned rows. `stress` (9 per row), `ctypes` (5 per row) and `ccount`
(2 per row: pair contacts, contact points) are the contact tallies of dem/tally.py, NULL unless an analysis
style asked for them."""

cdef struct Particles:
    int nlocal
    int nall
    const double* x
    const double* v
    const double* omega
    const double* quat
    double* f
    double* torque
    const double* radius
    const double* rmass
    const int* type
    const int* shape
    const int* mask
    double* stress
    double* ctypes
    double* ccount


cdef inline void count_contact(const Particles* P, int i, int j, int npoints) noexcept nogil:
    """One more pair contact, touching at npoints points, for particles i and j in the `count` tally
    (dem/tally.py), when asked for."""
    if P.ccount != NULL:
        P.ccount[2 * i] += 1.0
        P.ccount[2 * j] += 1.0
        P.ccount[2 * i + 1] += npoints
        P.ccount[2 * j + 1] += npoints


cdef class ParticleView:
    cdef Particles p
    cdef tuple _keep
