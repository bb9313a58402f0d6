# cython: language_level=3
"""The Grains3D contact law at one contact point (Part III eq. 10), shared by all contact geometries.

    F_n = kn delta n - 2 gamma_n m_ij U_rn,       gamma_n = beta sqrt(kn / m_ij)   (eq. 16)
    F_t = -min(mu |F_n|, |-2 gamma_t m_ij U_rt - k_s xi|) t,   xi = integral of U_rt over the contact

`c` points at a coefficient row: kn, beta, mu, gamma_t, ks, mu_roll, en (dem_contact.row).
`vr` is the velocity of body i relative to body j at the contact point, `n` the unit normal from j to i.
`xi` (3 values, may be NULL when ks = 0) is the tangential spring history; with `advance` false (setup
passes) it is read but never changed. Returns the elastic energy 0.5 kn delta^2."""
from libc.math cimport sqrt


cdef inline double hooke(const double* c, double delta, const double* n, const double* vr, double meff,
                         double* xi, double dt, bint advance, double* fn, double* ft) noexcept nogil:
    cdef double kn = c[0], mu = c[2], gt = c[3], ks = c[4]
    cdef double vn = vr[0] * n[0] + vr[1] * n[1] + vr[2] * n[2]
    cdef double fnmag = kn * delta - 2.0 * c[1] * sqrt(kn * meff) * vn
    cdef double vt[3]
    cdef double dampt = 2.0 * gt * meff
    cdef double ft2, cap, scale, xin
    cdef int d
    for d in range(3):
        fn[d] = fnmag * n[d]
        vt[d] = vr[d] - vn * n[d]
    if mu == 0.0:
        ft[0] = 0.0
        ft[1] = 0.0
        ft[2] = 0.0
        return 0.5 * kn * delta * delta
    if ks > 0.0 and xi != NULL:
        if advance:
            # keep the spring in the current tangent plane (the contact rotates with the bodies)
            xin = xi[0] * n[0] + xi[1] * n[1] + xi[2] * n[2]
            for d in range(3):
                xi[d] -= xin * n[d]
            for d in range(3):
                xi[d] += vt[d] * dt
        for d in range(3):
            ft[d] = -ks * xi[d] - dampt * vt[d]
    else:
        for d in range(3):
            ft[d] = -dampt * vt[d]
    ft2 = ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]
    cap = mu * (fnmag if fnmag > 0.0 else -fnmag)
    if ft2 > cap * cap:
        scale = cap / sqrt(ft2)
        for d in range(3):
            ft[d] *= scale
        if ks > 0.0 and xi != NULL and advance:
            # sliding: the spring holds exactly the Coulomb force (minus the viscous part)
            for d in range(3):
                xi[d] = -(ft[d] + dampt * vt[d]) / ks
    return 0.5 * kn * delta * delta


cdef inline void forget(double* xi) noexcept nogil:
    """A contact that ended forgets its tangential history (written only when set: saves bandwidth)."""
    if xi[0] != 0.0 or xi[1] != 0.0 or xi[2] != 0.0:
        xi[0] = 0.0
        xi[1] = 0.0
        xi[2] = 0.0


cdef inline bint rolling_torque(const double* c, const double* wi, const double* wj, const double* fn,
                                double reff, double* t) noexcept nogil:
    """Rolling resistance (c[5] = mu_roll): t, the torque on body i, of magnitude mu_roll reff |F_n| against
    the relative spin wi - wj (body j takes -t). False, t untouched, when there is none."""
    cdef double wr[3]
    cdef double wmag, mr
    cdef int d
    if c[5] <= 0.0:
        return False
    for d in range(3):
        wr[d] = wi[d] - wj[d]
    wmag = sqrt(wr[0] * wr[0] + wr[1] * wr[1] + wr[2] * wr[2])
    if wmag == 0.0:
        return False
    mr = c[5] * reff * sqrt(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2]) / wmag
    for d in range(3):
        t[d] = -mr * wr[d]
    return True


cdef inline double push_at(const double* c, double delta, const double* n, const double* l, const double* v,
                           const double* w, const double* vwall, double m, double* xi, double dt, bint advance,
                           double* f, double* t, double* F) noexcept nogil:
    """A wall pushing a body at the lever l (centre of mass -> contact point): the law with the body's
    velocity there relative to the wall's, v + w x l - vwall; adds the force F to f and l x F to t.
    Returns the elastic energy."""
    cdef double vr[3]
    cdef double fn[3]
    cdef double ft[3]
    cdef double energy
    cdef int d
    vr[0] = v[0] + w[1] * l[2] - w[2] * l[1] - vwall[0]
    vr[1] = v[1] + w[2] * l[0] - w[0] * l[2] - vwall[1]
    vr[2] = v[2] + w[0] * l[1] - w[1] * l[0] - vwall[2]
    energy = hooke(c, delta, n, vr, m, xi, dt, advance, fn, ft)
    for d in range(3):
        F[d] = fn[d] + ft[d]
        f[d] += F[d]
    t[0] += l[1] * F[2] - l[2] * F[1]
    t[1] += l[2] * F[0] - l[0] * F[2]
    t[2] += l[0] * F[1] - l[1] * F[0]
    return energy
