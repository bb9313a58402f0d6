# cython: language_level=3
"""The overlap volume of two posed sharp convex polytopes, or of one and a half-space (a plane wall), with
its first derivatives: what an energy-conserving volume law needs (dem/law/volume.pxd). See _volume.pyx."""
from dem.contact._polytope cimport Polytope

cdef enum:
    VOL_MAXF = 256         # faces of one body at most (larger bodies: overlap_volume returns -1)
    VOL_MAXFV = 64         # vertices of one face at most
    VOL_MAXV = 2 * VOL_MAXF    # vertices of one body at most (a convex body of F faces has <= 2F - 4)

cdef struct OverlapVolume:
    double volume          # V of the intersection (m^3)
    double area[3]         # S = dV/dx_A: the area vector of A's boundary inside B (outward of A, world)
    double moment[3]       # M = dV/dtheta_A: the integral of (x - x_A) x n_A over that boundary (world)
    double centroid[3]     # of the intersection (world)

cdef int overlap_volume(const Polytope* A, const double* Ra, double sa, const double* xa,
                        const Polytope* B, const double* Rb, double sb, const double* xb,
                        OverlapVolume* out) noexcept nogil

cdef int overlap_halfspace(const Polytope* A, const double* Ra, double sa, const double* xa,
                           const double* n, double d, OverlapVolume* out) noexcept nogil
