# cython: language_level=3
"""The contact law at one contact point, composed of the parts its coefficient row names (row.pxd): a
normal part (normal.pxd: Hooke, Hertz, JKR, DMT), a cohesion part that adds its pull (cohesion.pxd: a
liquid bridge), a damping part (damping.pxd), a tangential part (tangential.pxd: history spring, Mindlin,
viscous) and, applied by apply.pxd after the weight, a rolling part (rolling.pxd) and a twisting part
(twisting.pxd). Apart (delta < 0) only
JKR and a bridge act, without friction. The seed models are combinations: Grains3D (Part III eq. 10-16)
is Hooke + restitution damping + spring; LIGGGHTS's Hertz-Mindlin is Hertz + Hertz damping + Mindlin;
Descantes 2022 eq. 3 is Hooke + restitution damping that never attracts (C_LIMIT) + viscous friction.

    F_n = (F_el(delta) - gamma_n U_rn) n,     F_t from the tangential part, capped by mu |F_n + shift|

`vr` is the velocity of body a relative to body b at the contact point, `n` the unit normal from b to a,
`h` the contact's history (NULL when the pair style keeps none): the tangential spring xi first
(XI_WIDTH values), the rolling spring, the twist angle and the bond flag at the row's offsets. With
`advance` false (setup passes) history is read but never changed. Returns the elastic energy; R receives what the rolling and
twisting parts need."""
from dem.law.row cimport C_H_BOND, C_NORMAL, C_COHESION, N_JKR, K_NONE, XI_WIDTH
from dem.law.normal cimport jkr_reach
from dem.law.cohesion cimport cohesion_reach
from dem.law.compose cimport ForCouples, compose


cdef inline double evaluate(const double* c, double delta, const double* n, const double* vr, double meff,
                            double reff, double* h, double dt, bint advance, double* fn, double* ft,
                            ForCouples* R) noexcept nogil:
    """The row's law at one contact (module docstring; compose.pxd)."""
    return compose(c, delta, n, vr, meff, reff, h, dt, advance, fn, ft, R)


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


cdef inline bint holds(const double* c, const double* h, double gap, double reff) noexcept nogil:
    """Whether a contact apart by gap (> 0) still acts: bonded, and within its reach."""
    return bonded(c, h) and gap < reach(c, reff)


cdef inline void forget(double* h, int width) noexcept nogil:
    """A contact that ended forgets its history (written only when set: saves bandwidth)."""
    cdef int d
    if h[0] != 0.0 or h[1] != 0.0 or h[2] != 0.0:     # the tangential spring, first of every record
        h[0] = 0.0
        h[1] = 0.0
        h[2] = 0.0
    if width > XI_WIDTH:
        for d in range(XI_WIDTH, width):
            if h[d] != 0.0:
                h[d] = 0.0
