# cython: language_level=3
"""nogil GJK distance, EPA penetration and Grains3D crust contact between posed convex shapes.

A posed shape is a ShapeRef (dem/shapes/_support.pxd) with a row-major rotation R (body -> world) and a
position x (the centre of mass). Normals point from B to A. See _gjk.pyx for the algorithms.
"""
from dem.shapes._support cimport ShapeRef

cdef enum:
    GJK_SEPARATED = 0
    GJK_INTERSECT = 1
    NFEAT = 18             # warm-start values per pair (crust_contact's feat)

cpdef enum ContactCode:    # crust_contact return codes (Python: dem.contact.geometry)
    CONTACT_NONE = 0
    CONTACT_CRUST = 1      # cores apart by less than crust_a + crust_b: overlap from the GJK distance
    CONTACT_EPA = 2        # cores overlap: EPA on the cores + both crusts
    CONTACT_FALLBACK = 3   # EPA failed (degenerate); overlap = crusts, normal along the centres

cdef struct Simplex:
    int n
    double w[4][3]         # Minkowski difference points a - b
    double a[4][3]         # support points on A
    double b[4][3]         # support points on B
    double lam[4]          # barycentric coordinates of the closest point
    int fa[4]              # vertex index of a[i] on a polytope (support_world_id), -1 on a curved shape
    int fb[4]

cdef int gjk_distance(const ShapeRef* A, const double* Ra, const double* xa,
                      const ShapeRef* B, const double* Rb, const double* xb,
                      double tol, double sep, double* v, Simplex* S, bint warm, double* pa,
                      double* pb) noexcept nogil

cdef int epa_penetration(const ShapeRef* A, const double* Ra, const double* xa,
                         const ShapeRef* B, const double* Rb, const double* xb,
                         Simplex* S, double tol, double* depth, double* normal,
                         double* pa, double* pb) noexcept nogil

cdef int signed_distance(const ShapeRef* A, const double* Ra, const double* xa,
                         const ShapeRef* B, const double* Rb, const double* xb,
                         double tol, double* guess, double* dist, double* pa, double* pb) noexcept nogil

cdef int crust_contact(const ShapeRef* Acore, double crust_a, const double* Ra, const double* xa,
                       const ShapeRef* Bcore, double crust_b, const double* Rb, const double* xb,
                       double tol, double* guess, double* feat, double* overlap, double* normal,
                       double* point) noexcept nogil
