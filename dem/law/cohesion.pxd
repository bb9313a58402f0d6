# cython: language_level=3
"""Cohesion parts: forces added to the normal part's (normal.pxd) that act from touch until a rupture
distance, while the contact's bond holds (law.pxd).

K_CAPILLARY, a pendular liquid bridge of volume V, surface tension gamma and contact angle theta: the
closed form of Willett, Adams, Johnson & Seville, Langmuir 16 (2000) 9396, for two spheres at surface
separation S (0 while they touch),
    F = 2 pi R gamma cos(theta) / (1 + 1.05 S^ + 2.5 S^2),   S^ = S sqrt(R / V),
with R = 2 R* (the sphere radius for two equal spheres, Derjaguin's harmonic mean for two sizes, 2 R_i
against a wall: 4 pi R_i gamma cos(theta) at touch). The bridge forms when the bodies touch and breaks at
S_c = (1 + theta / 2) V^(1/3) (Lian, Thornton & Adams, J. Colloid Interface Sci. 161 (1993) 138). The
force pulls the bodies together; the Coulomb load is the contact's compression without it (the shift).

K_SJKR, the simplified JKR of LIGGGHTS (`cohesion sjkr`): a pull k A while the bodies touch, k the cohesion
energy density (J/m^3) and A = 2 pi R* delta the area of the circle where the two spheres' surfaces cross,
to first order in delta (pi (R delta - delta^2 / 4) for two equal spheres of radius R, pi (2 R delta -
delta^2) for a sphere on a plane); nothing apart."""
from libc.math cimport sqrt, cbrt, cos, atan, M_PI
from dem.law.row cimport C_COHESION, C_LIQUID, C_TENSION, C_ANGLE, C_COHESION_K, K_CAPILLARY, K_SJKR
from dem.law.normal cimport Normal


cdef inline double capillary_rupture(const double* c) noexcept nogil:
    return (1.0 + 0.5 * c[C_ANGLE]) * cbrt(c[C_LIQUID])


cdef inline double _bridge_integral(double u) noexcept nogil:
    """int du / (1 + 1.05 u + 2.5 u^2) (the square root of minus its discriminant: folded at compile time)."""
    cdef double root = sqrt(4.0 * 2.5 - 1.05 * 1.05)
    return 2.0 / root * atan((5.0 * u + 1.05) / root)


cdef inline void capillary(const double* c, double delta, double reff, Normal* N) noexcept nogil:
    """Adds the bridge's pull to N (force, shift) and its energy, -int_S^S_c F dS (minus F0 delta in
    contact), to the elastic energy."""
    cdef double R = 2.0 * reff
    cdef double k = sqrt(R / c[C_LIQUID])
    cdef double s = -delta if delta < 0.0 else 0.0
    cdef double f0 = 2.0 * M_PI * R * c[C_TENSION] * cos(c[C_ANGLE])
    cdef double u = k * s
    cdef double f = f0 / (1.0 + 1.05 * u + 2.5 * u * u)
    N.f -= f
    N.shift += f
    N.energy -= f0 / k * (_bridge_integral(k * capillary_rupture(c)) - _bridge_integral(u))
    if delta > 0.0:
        N.energy -= f0 * delta


cdef inline void sjkr(const double* c, double delta, double reff, Normal* N) noexcept nogil:
    """Adds k A (module docstring) to N while in contact, and its energy -pi R* k delta^2."""
    cdef double f
    if delta <= 0.0:
        return
    f = c[C_COHESION_K] * 2.0 * M_PI * reff * delta
    N.f -= f
    N.shift += f
    N.energy -= 0.5 * f * delta


cdef inline void cohesion_force(const double* c, double delta, double reff, Normal* N) noexcept nogil:
    cdef int part = <int>c[C_COHESION]
    if part == K_CAPILLARY:
        capillary(c, delta, reff, N)
    elif part == K_SJKR:
        sjkr(c, delta, reff, N)


cdef inline double cohesion_reach(const double* c) noexcept nogil:
    if <int>c[C_COHESION] == K_CAPILLARY:
        return capillary_rupture(c)
    return 0.0
