# cython: language_level=3
"""The one path from a contact record (dem/contact/record.pxd) to forces and torques, shared by every pair
style and wall: the relative velocity of the two surfaces at the contact point, the law of the row (law.pxd:
its normal, damping and tangential parts, with the contact's history), the force on both bodies, the
torques about both centres of mass, all times the record's weight, then the rolling part (rolling.pxd)
and the twisting part (twisting.pxd), couples on both bodies.

A Body is one side of a contact. Pair styles call apply_pair, walls apply_wall, where the wall
is the Body b: `v` is its velocity at the contact point and `w` its spin (for rolling resistance); it takes no force
(its x, f, t are not read). Both are one function, _apply, whose `wall` flag is a constant at each call.
Rolling resistance acts when reff > 0 (spheres: R_eff; Grains3D applies none to shaped bodies). A row of
the Hertz family (c[C_NORMAL] other than Hooke) takes reff as R* too; `contact_radius` gives every style
the reff to pass: R_i R_j / (R_i + R_j) of two spheres, or of the spheres of equal volume for a Hertz row
between shaped bodies (their R* is not a local curvature: sharp edges have none), else 0.

A Body's `s` (9 doubles, or NULL) receives F (x) l, the force it takes times its lever from its centre of
mass: the per-particle contact stress tally of dem/tally.py (a rolling couple adds only an antisymmetric
part and is left out)."""
from dem._math cimport cross3
from dem._particles cimport Particles
from dem.contact.record cimport Contact
from dem.law.row cimport C_NORMAL, C_TWISTING, N_HOOKE, TW_NONE
from dem.law.law cimport ForCouples, evaluate
from dem.law.rolling cimport rolling_torque
from dem.law.twisting cimport twisting_torque

cdef extern from *:
    bint unlikely(bint) nogil        # Cython's __builtin_expect: the seed models never twist


cdef inline double contact_radius(const double* c, bint spheres, double ri, double rj) noexcept nogil:
    """reff of a pair (see above): ri, rj are the radii of the bodies' spheres of equal volume (a sphere's own
    radius), rj < 0 for a wall (R* = ri); `spheres` says both bodies are spheres."""
    if not spheres and c[C_NORMAL] == N_HOOKE:
        return 0.0
    return ri if rj < 0.0 else ri * rj / (ri + rj)


cdef struct Body:
    const double* x     # centre of mass (unused for a wall)
    const double* v     # velocity of the centre (a wall: its velocity at the contact point)
    const double* w     # angular velocity (a wall: its spin)
    double* f           # force and torque sums (unused for a wall)
    double* t
    double* s           # stress tally F (x) lever, row-major 3x3, or NULL (dem/tally.py; unused for a wall)


cdef inline void bind_body(Body* b, const Particles* P, int i) noexcept nogil:
    """b: particle i of P (owned or ghost), its stress tally when one is kept."""
    b.x = &P.x[3 * i]
    b.v = &P.v[3 * i]
    b.w = &P.omega[3 * i]
    b.f = &P.f[3 * i]
    b.t = &P.torque[3 * i]
    b.s = &P.stress[9 * i] if P.stress != NULL else NULL


cdef inline void _point_velocity(const Body* b, const double* l, double* u) noexcept nogil:
    """u = v + w x l: the velocity of body b's material point at lever l from its centre."""
    u[0] = b.v[0] + b.w[1] * l[2] - b.w[2] * l[1]
    u[1] = b.v[1] + b.w[2] * l[0] - b.w[0] * l[2]
    u[2] = b.v[2] + b.w[0] * l[1] - b.w[1] * l[0]


cdef inline double apply_pair(const double* c, const Contact* k, const Body* a, const Body* b, double meff,
                              double reff, double* h, double dt, bint advance, double* out) noexcept nogil:
    """The law at contact k between bodies a and b (reduced mass meff, coefficient row c, history h or
    NULL): adds the force to a and minus it to b, and the torques about both centres; out receives the
    force on a (0-2) and the couple on a, rolling and twisting (3-5, zero if none). Returns the elastic
    energy (times the weight)."""
    return _apply(c, k, a, b, meff, reff, h, dt, advance, out, False)


cdef inline double apply_wall(const double* c, const Contact* k, const Body* a, const Body* wall, double m,
                              double reff, double* h, double dt, bint advance, double* out) noexcept nogil:
    """apply_pair against a wall (m_ij = m, a's mass): only a takes the force and the torque."""
    return _apply(c, k, a, wall, m, reff, h, dt, advance, out, True)


cdef inline void _tally(double* s, const double* f, const double* l, double sign) noexcept nogil:
    cdef int r, c
    for r in range(3):
        for c in range(3):
            s[3 * r + c] += sign * f[r] * l[c]


cdef inline double _apply(const double* c, const Contact* k, const Body* a, const Body* b, double meff,
                          double reff, double* h, double dt, bint advance, double* out,
                          bint wall) noexcept nogil:
    cdef double vr[3]
    cdef double ua[3]
    cdef double ub[3]
    cdef double li[3]
    cdef double lj[3]
    cdef double ws[3]
    cdef double fn[3]
    cdef double ft[3]
    cdef double lxf[3]
    cdef double tr[3]
    cdef double energy, tw, s = k.weight
    cdef bint couple
    cdef ForCouples R
    cdef const double* n = k.n
    cdef const double* wa = a.w
    cdef const double* wb = b.w
    cdef int d
    # relative velocity of a's surface with respect to b's at the contact point (the central forms: the same
    # v_a - v_b - (arm_a w_a + arm_b w_b) x n, summed in the order each geometry always used, bit for bit)
    if k.central:
        if wall:
            vr[0] = a.v[0] - k.arm_a * (wa[1] * n[2] - wa[2] * n[1]) - b.v[0]
            vr[1] = a.v[1] - k.arm_a * (wa[2] * n[0] - wa[0] * n[2]) - b.v[1]
            vr[2] = a.v[2] - k.arm_a * (wa[0] * n[1] - wa[1] * n[0]) - b.v[2]
        else:
            for d in range(3):
                ws[d] = k.arm_a * wa[d] + k.arm_b * wb[d]
            vr[0] = a.v[0] - b.v[0] - (ws[1] * n[2] - ws[2] * n[1])
            vr[1] = a.v[1] - b.v[1] - (ws[2] * n[0] - ws[0] * n[2])
            vr[2] = a.v[2] - b.v[2] - (ws[0] * n[1] - ws[1] * n[0])
    else:
        for d in range(3):
            li[d] = k.p[d] - a.x[d]
        _point_velocity(a, li, ua)
        if wall:
            for d in range(3):
                ub[d] = b.v[d]
        else:
            for d in range(3):
                lj[d] = k.p[d] - b.x[d]
            _point_velocity(b, lj, ub)
        for d in range(3):
            vr[d] = ua[d] - ub[d]
    energy = evaluate(c, k.delta, n, vr, meff, reff, h, dt, advance, fn, ft, &R)
    if s != 1.0:
        energy *= s
        for d in range(3):
            fn[d] *= s
            ft[d] *= s
    for d in range(3):
        out[d] = fn[d] + ft[d]
        a.f[d] += out[d]
    if not wall:
        for d in range(3):
            b.f[d] -= out[d]
    # torques about the centres of mass
    if k.central:
        # levers -arm_a n and +arm_b n: only the tangential force turns the bodies
        cross3(n, ft, lxf)
        for d in range(3):
            a.t[d] -= k.arm_a * lxf[d]
        if not wall:
            for d in range(3):
                b.t[d] -= k.arm_b * lxf[d]
    else:
        cross3(li, out, lxf)
        for d in range(3):
            a.t[d] += lxf[d]
        if not wall:
            cross3(lj, out, lxf)
            for d in range(3):
                b.t[d] -= lxf[d]
    if a.s != NULL or (not wall and b.s != NULL):
        if k.central:
            for d in range(3):
                li[d] = -k.arm_a * n[d]
                lj[d] = k.arm_b * n[d]
        if a.s != NULL:
            _tally(a.s, out, li, 1.0)
        if not wall and b.s != NULL:
            _tally(b.s, out, lj, -1.0)
    out[3] = out[4] = out[5] = 0.0
    couple = reff > 0.0 and rolling_torque(c, n, wa, wb, fn, R.kn, s * R.load, reff, k.inertia, h, dt,
                                           advance, tr)
    if unlikely(<int>c[C_TWISTING] != TW_NONE) and twisting_torque(c, n, wa, wb, &R, reff, k.delta, h, dt,
                                                                   advance, &tw):
        for d in range(3):       # onto the rolling couple: both applied by one loop (less inlined code)
            tr[d] = (tr[d] if couple else 0.0) + s * tw * n[d]
        couple = True
    if couple:
        for d in range(3):
            out[3 + d] = tr[d]
            a.t[d] += tr[d]
        if not wall:
            for d in range(3):
                b.t[d] -= tr[d]
    return energy
