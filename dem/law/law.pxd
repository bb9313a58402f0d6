# cython: language_level=3
"""The contact law at one contact point, composed of the parts its coefficient row names (row.pxd): a
normal part (normal.pxd: Hooke, Hertz, JKR, DMT), a cohesion part that adds its pull (cohesion.pxd: a
liquid bridge), a damping part (damping.pxd), a tangential part (tangential.pxd: history spring, Mindlin,
viscous) and, applied by apply.pxd after the weight, a rolling part (rolling.pxd). Apart (delta < 0) only
JKR and a bridge act, without friction. The seed models are combinations: Grains3D (Part III eq. 10-16)
is Hooke + restitution damping + spring; LIGGGHTS's Hertz-Mindlin is Hertz + Hertz damping + Mindlin;
Descantes 2022 eq. 3 is Hooke + restitution damping that never attracts (C_LIMIT) + viscous friction.

    F_n = (F_el(delta) - gamma_n U_rn) n,     F_t from the tangential part, capped by mu |F_n + shift|

`vr` is the velocity of body a relative to body b at the contact point, `n` the unit normal from b to a,
`h` the contact's history (NULL when the pair style keeps none): the tangential spring xi first
(XI_WIDTH values), the rolling spring and the bond flag at the row's offsets. With `advance` false (setup
passes) history is read but never changed. Returns the elastic energy; R receives what the rolling part
needs."""
from dem.law.row cimport C_LIMIT, C_H_BOND, C_NORMAL, C_COHESION, N_JKR, K_NONE, XI_WIDTH
from dem.law.normal cimport Normal, normal_force, jkr_reach
from dem.law.damping cimport normal_damping
from dem.law.tangential cimport tangential_force
from dem.law.cohesion cimport cohesion_force, cohesion_reach


cdef struct ForRolling:
    double kn              # the normal stiffness (EPSD's k_r scales with it)
    double load            # |F_n + shift|: the normal load of the Coulomb caps (EPSD's plastic limit)


cdef inline double evaluate(const double* c, double delta, const double* n, const double* vr, double meff,
                            double reff, double* h, double dt, bint advance, double* fn, double* ft,
                            ForRolling* R) noexcept nogil:
    cdef Normal N
    cdef double vt[3]
    cdef double vn = vr[0] * n[0] + vr[1] * n[1] + vr[2] * n[2]
    cdef double w, fnmag
    cdef int d
    # apart only a bridge acts, and JKR within its pull-off distance (a bridge may reach further)
    cdef bint apart = delta < 0.0 and (<int>c[C_NORMAL] != N_JKR or delta <= -jkr_reach(c, reff))
    if apart:
        N.f = N.k = N.a = N.shift = N.energy = 0.0
    else:
        normal_force(c, delta, reff, &N)
    if <int>c[C_COHESION] != K_NONE:
        cohesion_force(c, delta, reff, &N)
    fnmag = N.f - normal_damping(c, N.k, meff, &w) * vn
    if c[C_LIMIT] != 0.0 and fnmag < 0.0:
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
        tangential_force(c, w, N.a, fnmag + N.shift, meff, n, vt, h, dt, advance, ft)
    if advance and h != NULL and c[C_H_BOND] >= 0.0:
        h[<int>c[C_H_BOND]] = 1.0          # the bond holds (beyond contact too) until its reach
    R.kn = N.k
    R.load = fnmag + N.shift if fnmag + N.shift > 0.0 else -(fnmag + N.shift)
    return N.energy


cdef inline double reach(const double* c, double reff) noexcept nogil:
    """How far apart (> 0) a contact that has touched keeps acting: JKR's pull-off distance, a liquid
    bridge's rupture distance; 0 otherwise."""
    cdef double r = cohesion_reach(c) if <int>c[C_COHESION] != K_NONE else 0.0
    if <int>c[C_NORMAL] == N_JKR and jkr_reach(c, reff) > r:
        return jkr_reach(c, reff)
    return r


cdef inline bint bonded(const double* c, const double* h) noexcept nogil:
    """Whether a contact's history says it has touched and not yet let go (parts that act beyond contact)."""
    return h != NULL and c[C_H_BOND] >= 0.0 and h[<int>c[C_H_BOND]] != 0.0


cdef inline void forget(double* h, int width) noexcept nogil:
    """A contact that ended forgets its history (written only when set: saves bandwidth)."""
    cdef int d
    for d in range(width):
        if h[d] != 0.0:
            h[d] = 0.0
