# cython: language_level=3
"""Tangential parts: the friction force ft at a contact with tangential velocity vt (normal n), capped by
mu |load| (load: the normal force plus the normal part's shift).

T_SPRING, T_MINDLIN: -min(mu |load|, |-nu_t vt - kt xi|) along the trial force, xi the integral of vt over
    the contact (history, kept in the current tangent plane; with `advance` false it is read, never
    changed); while sliding the spring holds exactly the Coulomb force minus the viscous part. kt = ks
    (Grains3D) or 8 G* a (Mindlin, a the contact radius). Without history (xi NULL) or spring (kt = 0):
    the dashpot alone, capped.
T_VISCOUS (Descantes 2022 eq. 3): -min(nu_t |vt|, mu |load|) vt / |vt|, no history."""
from libc.math cimport sqrt
from dem.law.row cimport C_MU, C_KS, C_GSTAR, T_SPRING, T_MINDLIN, T_VISCOUS
from dem.law.damping cimport tangential_damping


cdef inline double tangential_stiffness(int part, const double* c, double a) noexcept nogil:
    """kt of the tangential part `part` at contact radius a: ks, 8 G* a (Mindlin), 0 (viscous: no spring)."""
    if part == T_SPRING:
        return c[C_KS]
    if part == T_MINDLIN:
        return 8.0 * c[C_GSTAR] * a
    return 0.0


cdef inline void _zero(double* ft) noexcept nogil:
    ft[0] = 0.0
    ft[1] = 0.0
    ft[2] = 0.0


cdef inline void spring(const double* c, double kt, double dampt, double load, const double* n,
                        const double* vt, double* xi, double dt, bint advance, double* ft) noexcept nogil:
    cdef double ft2, cap, scale, xin
    cdef int d
    if kt > 0.0 and xi != NULL:
        if advance:
            # keep the spring in the current tangent plane (the contact rotates with the bodies)
            xin = xi[0] * n[0] + xi[1] * n[1] + xi[2] * n[2]
            for d in range(3):
                xi[d] -= xin * n[d]
            for d in range(3):
                xi[d] += vt[d] * dt
        for d in range(3):
            ft[d] = -kt * xi[d] - dampt * vt[d]
    else:
        for d in range(3):
            ft[d] = -dampt * vt[d]
    ft2 = ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]
    cap = c[C_MU] * (load if load > 0.0 else -load)
    if ft2 > cap * cap:
        scale = cap / sqrt(ft2)
        for d in range(3):
            ft[d] *= scale
        if kt > 0.0 and xi != NULL and advance:
            # sliding: the spring holds exactly the Coulomb force (minus the viscous part)
            for d in range(3):
                xi[d] = -(ft[d] + dampt * vt[d]) / kt


cdef inline void viscous(double nu_t, double cap, const double* vt, double* ft) noexcept nogil:
    cdef double ut = sqrt(vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2])
    cdef double scale = nu_t
    cdef int d
    if ut == 0.0:
        return
    if scale * ut > cap:
        scale = cap / ut
    for d in range(3):
        ft[d] = -scale * vt[d]


cdef inline void tangential_force(int part, int damping, const double* c, double w, double a, double load,
                                  double meff, const double* n, const double* vt, double* xi, double dt,
                                  bint advance, double* ft, double* kt, double* nu_t) noexcept nogil:
    """ft of the tangential part `part` with the damping part `damping`; w = sqrt(kn m*) (damping.pxd), a
    the contact radius. kt, nu_t receive the spring and the dashpot where friction acts (mu > 0; twisting
    marshall spreads them over the contact)."""
    if c[C_MU] == 0.0:
        _zero(ft)
        return
    if part == T_VISCOUS:
        _zero(ft)
        kt[0] = 0.0
        nu_t[0] = tangential_damping(damping, c, w, 0.0, meff)
        viscous(nu_t[0], c[C_MU] * (load if load > 0.0 else -load), vt, ft)
        return
    kt[0] = tangential_stiffness(part, c, a)
    nu_t[0] = tangential_damping(damping, c, w, kt[0], meff)
    spring(c, kt[0], nu_t[0], load, n, vt, xi, dt, advance, ft)
