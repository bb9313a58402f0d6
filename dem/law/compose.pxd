# cython: language_level=3
"""The composition of a row's parts at one contact (law.pxd evaluates it): F_n from the normal part, a
cohesion part's pull and the damping part, F_t from the tangential part, capped by mu |F_n + shift|; apart
(delta < 0) only JKR and a bridge act, without friction. The parts are read from the row at each contact
(a switch on a small integer each); rows of the common combinations (c[C_PLAN], dem.law.prepare) skip
what none of them has: cohesion, the damping limit, forces apart, the bond."""
from dem.law.row cimport (C_LIMIT, C_H_BOND, C_NORMAL, C_DAMPING, C_TANGENTIAL, C_COHESION, C_PLAN, N_JKR,
                          K_NONE, P_GENERAL, XI_WIDTH)
from dem.law.normal cimport Normal, normal_force, jkr_reach
from dem.law.damping cimport normal_damping
from dem.law.tangential cimport tangential_force
from dem.law.cohesion cimport cohesion_force


cdef struct ForCouples:     # what the rolling and twisting parts (applied after the force) need
    double kn              # the normal stiffness (EPSD's k_r scales with it)
    double load            # |F_n + shift|: the normal load of the Coulomb caps (EPSD's and the twist's limits)
    double a               # the normal part's contact radius (0 for Hooke and apart)
    double kt              # the tangential spring and dashpot (0 where no friction acts)
    double nu_t
    bint apart             # no contact (only a bridge acts): nothing twists


cdef inline double compose(const double* c, double delta, const double* n, const double* vr, double meff,
                           double reff, double* h, double dt, bint advance, double* fn, double* ft,
                           ForCouples* R) noexcept nogil:
    """The row's parts at one contact (module docstring); fn, ft receive the forces on body a, R what the
    rolling and twisting parts need. Returns the elastic energy."""
    cdef Normal N
    cdef double vt[3]
    cdef double vn = vr[0] * n[0] + vr[1] * n[1] + vr[2] * n[2]
    cdef double w, fnmag
    cdef int d
    cdef int normal = <int>c[C_NORMAL], damping = <int>c[C_DAMPING], tangential = <int>c[C_TANGENTIAL]
    cdef bint general = <int>c[C_PLAN] == P_GENERAL
    # apart only a bridge acts, and JKR within its pull-off distance (a bridge may reach further)
    cdef bint apart = general and delta < 0.0 and (normal != N_JKR or delta <= -jkr_reach(c, reff))
    R.kt = R.nu_t = 0.0
    if apart:
        N.f = N.k = N.a = N.shift = N.energy = 0.0
    else:
        normal_force(normal, c, delta, reff, &N)
    if general and <int>c[C_COHESION] != K_NONE:
        cohesion_force(c, delta, reff, &N)
    fnmag = N.f - normal_damping(damping, c, N.k, meff, &w) * vn
    if general and c[C_LIMIT] != 0.0 and fnmag < 0.0:
        fnmag = 0.0
    for d in range(3):
        fn[d] = fnmag * n[d]
        vt[d] = vr[d] - vn * n[d]
    if apart:              # no friction without contact; the tangential spring starts again at touch
        ft[0] = ft[1] = ft[2] = 0.0
        if advance and h != NULL:
            for d in range(XI_WIDTH):
                h[d] = 0.0
    else:
        tangential_force(tangential, damping, c, w, N.a, fnmag + N.shift, meff, n, vt, h, dt, advance, ft,
                         &R.kt, &R.nu_t)
    if general and advance and h != NULL and c[C_H_BOND] >= 0.0:
        h[<int>c[C_H_BOND]] = 1.0          # the bond holds (beyond contact too) until its reach
    R.kn = N.k
    R.a = N.a
    R.apart = apart
    R.load = fnmag + N.shift if fnmag + N.shift > 0.0 else -(fnmag + N.shift)
    return N.energy
