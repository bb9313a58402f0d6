# cython: language_level=3
"""Normal parts: the elastic (and adhesive) normal force at overlap delta (> 0 in contact; < 0 only for a
part that acts beyond contact), with R* = reff. Each fills a Normal: the force along n (> 0 repulsive),
the stiffness the damping and the rolling spring scale with, the shift of the Coulomb load (twice the
pull-off force: friction vanishes where the contact would let go, as in Thornton's JKR friction) and the
elastic energy (the work to bring the pair from apart to delta)."""
from libc.math cimport sqrt, cbrt, fabs, M_PI
from dem.law.row cimport C_KN, C_YSTAR, C_W, N_HOOKE, N_HERTZ, N_JKR, N_DMT


cdef struct Normal:
    double f               # elastic + adhesive force along n
    double k               # stiffness (N/m) for the damping and the rolling spring
    double a               # contact radius (Hertz family; 0 for Hooke)
    double shift           # added to the normal force for the Coulomb caps (2 |pull-off|)
    double energy


cdef inline void hooke(const double* c, double delta, Normal* N) noexcept nogil:
    """kn delta (Grains3D eq. 10)."""
    cdef double kn = c[C_KN]
    N.f = kn * delta
    N.k = kn
    N.a = 0.0
    N.shift = 0.0
    N.energy = 0.5 * kn * delta * delta


cdef inline void hertz(const double* c, double delta, double reff, Normal* N) noexcept nogil:
    """kn delta with kn = 4/3 Y* a, a = sqrt(R* delta); energy 8/15 Y* sqrt(R*) delta^(5/2)."""
    cdef double a = sqrt(reff * delta)
    cdef double kn = 4.0 / 3.0 * c[C_YSTAR] * a
    N.f = kn * delta
    N.k = kn
    N.a = a
    N.shift = 0.0
    N.energy = 0.4 * kn * delta * delta


cdef inline double jkr_radius(double ystar, double w, double reff, double delta) noexcept nogil:
    """The contact radius a of the JKR branch that holds at delta (the larger root of
    delta = a^2 / R* - sqrt(2 pi w a / Y*)): with x = sqrt(a), x^4 - p x - R* delta = 0, p = R* sqrt(2 pi w /
    Y*). The quartic is convex for x > 0, so Newton's method from any x above the root falls onto it
    monotonically; x^4 <= p x + |R* delta| bounds the start. Exact to round-off: the loop stops when x no
    longer decreases."""
    cdef double p = reff * sqrt(2.0 * M_PI * w / ystar)
    cdef double q = reff * delta
    cdef double x = cbrt(2.0 * p)
    cdef double y = sqrt(sqrt(2.0 * fabs(q)))
    cdef double step
    cdef int it
    if y > x:
        x = y
    for it in range(100):
        step = (x * x * x * x - p * x - q) / (4.0 * x * x * x - p)
        if not step > 0.0 or x - step == x:
            break
        x -= step
    return x * x


cdef inline double jkr_reach(const double* c, double reff) noexcept nogil:
    """How far apart a JKR contact holds: -delta_c = 3/4 (pi^2 w^2 R* / Y*^2)^(1/3) (where d delta / da = 0,
    the pull-off of a displacement-controlled pair)."""
    cdef double w = c[C_W], y = c[C_YSTAR]
    return 0.75 * cbrt(M_PI * M_PI * w * w * reff / (y * y))


cdef inline void jkr(const double* c, double delta, double reff, Normal* N) noexcept nogil:
    """F = 4 Y* a^3 / (3 R*) - sqrt(8 pi w Y* a^3), a from delta (jkr_radius); stiffness 4/3 Y* a (as Hertz at
    that contact radius) for the damping; Coulomb shift 2 x 3/2 pi w R*. Energy: the integral of F along the
    branch from a = 0, 8 Y* a^5 / (15 R*^2) - 4 sqrt(2)/3 sqrt(pi w Y*) a^(7/2) / R* + pi w a^2 (negative
    while the bond's surface energy outweighs the elastic one)."""
    cdef double ystar = c[C_YSTAR], w = c[C_W]
    cdef double a = jkr_radius(ystar, w, reff, delta)
    cdef double a3 = a * a * a
    cdef double s = sqrt(M_PI * w * ystar)
    N.f = 4.0 * ystar * a3 / (3.0 * reff) - sqrt(8.0 * M_PI * w * ystar * a3)
    N.k = 4.0 / 3.0 * ystar * a
    N.a = a
    N.shift = 3.0 * M_PI * w * reff
    N.energy = (8.0 * ystar * a3 * a * a / (15.0 * reff * reff)
                - 4.0 * sqrt(2.0) / 3.0 * s * a3 * sqrt(a) / reff + M_PI * w * a * a)


cdef inline void dmt(const double* c, double delta, double reff, Normal* N) noexcept nogil:
    """Hertz minus the constant adhesion 2 pi w R* while in contact (pull-off at delta = 0); Coulomb shift
    2 x 2 pi w R*."""
    cdef double fa = 2.0 * M_PI * c[C_W] * reff
    hertz(c, delta, reff, N)
    N.f -= fa
    N.shift = 2.0 * fa
    N.energy -= fa * delta


cdef inline void normal_force(int part, const double* c, double delta, double reff, Normal* N) noexcept nogil:
    """The normal part `part` (the row's c[C_NORMAL], or a constant where law.pxd specialises)."""
    if part == N_HOOKE:
        hooke(c, delta, N)
    elif part == N_HERTZ:
        hertz(c, delta, reff, N)
    elif part == N_JKR:
        jkr(c, delta, reff, N)
    else:
        dmt(c, delta, reff, N)
