# cython: language_level=3
"""Twisting parts: the torque tau n on body a (-tau n on body b) against the relative spin about the normal,
Omega = (wa - wb) . n, as LAMMPS's `pair granular ... twisting sds|marshall` (Marshall, J. Comput. Phys.
228 (2009) 1541, eq. 30-34): a spring-dashpot-slider on the twist angle xi = int Omega dt (the contact's
history, one value at c[C_H_TWIST]; a scalar, so no frame to rotate),

    tau = -k_tw xi - gamma_tw Omega,   capped at mu_tw |F_n + shift| (the load of the Coulomb caps),

and while it slides the spring holds exactly the cap minus the dashpot (as the tangential spring).
TW_SDS: k_tw, gamma_tw, mu_tw the row's own (k_twist, gamma_twist, mu_twist).
TW_MARSHALL (eq. 32-33): the tangential part's spring kt, dashpot nu_t and friction mu spread over the
    contact disc of radius a: k_tw = kt a^2 / 2, gamma_tw = nu_t a^2 / 2, mu_tw = 2/3 mu a. a is the normal
    part's contact radius, sqrt(R* delta) for Hooke (its geometric one, as LAMMPS takes it).
Apart (only a bridge holds the pair) nothing twists and the angle is forgotten. Kept small (kt and nu_t
come from the tangential part, compose.pxd): the law inlined into the sphere kernel sits at the compiler's
inlining limit (docs/contact_law.md, Cost)."""
from libc.math cimport sqrt
from dem.law.row cimport (C_NORMAL, C_MU, C_TWISTING, C_K_TWIST, C_GAMMA_TWIST, C_MU_TWIST, C_H_TWIST, N_HOOKE,
                          TW_SDS)
from dem.law.compose cimport ForCouples


cdef inline bint twisting_torque(const double* c, const double* n, const double* wa, const double* wb,
                                 const ForCouples* R, double reff, double delta, double* h,
                                 double dt, bint advance, double* tau) noexcept nogil:
    """tau (module docstring) for the row's twisting part; False, tau untouched, without history or
    contact."""
    cdef double k, g, mu, a, t, cap
    cdef double omega = (wa[0] - wb[0]) * n[0] + (wa[1] - wb[1]) * n[1] + (wa[2] - wb[2]) * n[2]
    cdef double* xi
    if h == NULL:
        return False
    xi = h + <int>c[C_H_TWIST]
    if R.apart:
        if advance:
            xi[0] = 0.0
        return False
    if <int>c[C_TWISTING] == TW_SDS:
        k = c[C_K_TWIST]
        g = c[C_GAMMA_TWIST]
        mu = c[C_MU_TWIST]
    else:
        a = R.a
        if <int>c[C_NORMAL] == N_HOOKE:
            a = sqrt(reff * delta) if delta > 0.0 else 0.0
        k = 0.5 * R.kt * a * a             # the tangential part's, as it acted on this contact
        g = 0.5 * R.nu_t * a * a
        mu = 2.0 / 3.0 * c[C_MU] * a
    if advance:
        xi[0] += omega * dt
    t = -k * xi[0] - g * omega
    cap = mu * R.load
    if t > cap or t < -cap:
        t = cap if t > 0.0 else -cap
        if advance and k > 0.0:
            xi[0] = -(t + g * omega) / k
    tau[0] = t
    return True
