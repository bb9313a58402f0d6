# cython: language_level=3
"""The Grains3D contact law at one contact point (Part III eq. 10), shared by all contact geometries.

    F_n = kn delta n - 2 gamma_n m_ij U_rn,       gamma_n = beta sqrt(kn / m_ij)   (eq. 16)
    F_t = -min(mu |F_n|, |-nu_t U_rt - k_s xi|) t,   xi = integral of U_rt over the contact
    nu_t = 2 gamma_t m_ij + 2 beta_t sqrt(kn m_ij)   (beta_t = 1: the critical value of the normal dashpot)

`c` points at a coefficient row: the columns C_KN ... C_EN below (Python: dem_contact.KN ..., read from
law.COLUMNS; rows made by dem_contact.row).
`vr` is the velocity of body i relative to body j at the contact point, `n` the unit normal from j to i.
`xi` (3 values, may be NULL when ks = 0) is the tangential spring history; with `advance` false (setup
passes) it is read but never changed. Returns the elastic energy 0.5 kn delta^2."""
from libc.math cimport sqrt

cdef enum:                 # columns of a coefficient row
    C_KN = 0               # normal stiffness
    C_BETA = 1             # gamma_n / omega0, from en (eq. 16)
    C_MU = 2               # Coulomb friction
    C_GAMMA_T = 3          # tangential damping (1/s)
    C_KS = 4               # tangential spring
    C_MU_ROLL = 5          # rolling resistance
    C_EN = 6               # restitution (kept for contact times)
    C_BETA_T = 7           # tangential damping as a fraction of critical (Descantes 2022 Table 2: 1)
    C_MODEL = 8            # MODEL_HOOKE (the columns above) or MODEL_HERTZ (hertz below: KN, KS, GAMMA_T unused)
    C_YSTAR = 9            # Hertz: effective Young's modulus Y* (Pa)
    C_GSTAR = 10           # Hertz: effective shear modulus G* (Pa)
    NCOEFF = 11
    XI_WIDTH = 3           # values of the tangential spring history xi


cdef inline double hooke(const double* c, double delta, const double* n, const double* vr, double meff,
                         double* xi, double dt, bint advance, double* fn, double* ft) noexcept nogil:
    cdef double kn = c[C_KN], mu = c[C_MU], gt = c[C_GAMMA_T], ks = c[C_KS]
    cdef double vn = vr[0] * n[0] + vr[1] * n[1] + vr[2] * n[2]
    cdef double w = sqrt(kn * meff)
    cdef double fnmag = kn * delta - 2.0 * c[C_BETA] * w * vn
    cdef double vt[3]
    cdef double dampt = 2.0 * gt * meff + 2.0 * c[C_BETA_T] * w
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


cdef enum:                 # c[C_MODEL]: the elastic model of a row (a value per type pair, read per contact)
    MODEL_HOOKE = 0        # hooke above (every row made from kn, en)
    MODEL_HERTZ = 1        # hertz below (rows made from E, nu, en: dem_contact.hertz)


cdef inline double hertz(const double* c, double delta, const double* n, const double* vr, double meff,
                         double reff, double* xi, double dt, bint advance, double* fn,
                         double* ft) noexcept nogil:
    """Hertz-Mindlin with material parameters, the default model of LIGGGHTS (`model hertz tangential
    history`; doc/gran_model_hertz.html and doc/gran_tangential_history.html of
    https://github.com/CFDEMproject/LIGGGHTS-PUBLIC):

        kn = 4/3 Y* sqrt(R* delta),   kt = 8 G* sqrt(R* delta)
        gamma_n = 2 sqrt(5/6) beta sqrt(Sn m*),  Sn = 2 Y* sqrt(R* delta) = 3/2 kn
        gamma_t = 2 sqrt(5/6) beta sqrt(St m*),  St = 8 G* sqrt(R* delta) = kt
        F_n = (kn delta - gamma_n U_rn) n
        F_t = -min(mu |F_n|, |-gamma_t U_rt - kt xi|) t,   xi = integral of U_rt over the contact

    with beta = -ln(en) / sqrt(ln(en)^2 + pi^2) in c[C_BETA] (LIGGGHTS writes it with the opposite sign and
    a minus in gamma), R* = `reff` and m* = `meff` of the contact. The tangential spring and its sliding rule
    are hooke's (the Coulomb cap holds the spring and the dashpot together, where LIGGGHTS caps the spring
    and drops the dashpot while sliding): only the stiffness now grows with the overlap. Returns the
    elastic energy, the integral of kn delta: 8/15 Y* sqrt(R*) delta^(5/2)."""
    cdef double mu = c[C_MU]
    cdef double a = sqrt(reff * delta)                  # contact radius
    cdef double kn = 4.0 / 3.0 * c[C_YSTAR] * a
    cdef double kt = 8.0 * c[C_GSTAR] * a
    cdef double vn = vr[0] * n[0] + vr[1] * n[1] + vr[2] * n[2]
    cdef double fnmag = kn * delta - 2.0 * sqrt(5.0 / 6.0) * c[C_BETA] * sqrt(1.5 * kn * meff) * vn
    cdef double vt[3]
    cdef double dampt, ft2, cap, scale, xin
    cdef int d
    for d in range(3):
        fn[d] = fnmag * n[d]
        vt[d] = vr[d] - vn * n[d]
    if mu == 0.0 or xi == NULL:          # no friction (the styles keep a history whenever mu > 0)
        ft[0] = 0.0
        ft[1] = 0.0
        ft[2] = 0.0
        return 0.4 * kn * delta * delta
    dampt = 2.0 * sqrt(5.0 / 6.0) * c[C_BETA] * sqrt(kt * meff)
    if advance:
        xin = xi[0] * n[0] + xi[1] * n[1] + xi[2] * n[2]     # stay in the current tangent plane
        for d in range(3):
            xi[d] -= xin * n[d]
        for d in range(3):
            xi[d] += vt[d] * dt
    for d in range(3):
        ft[d] = -kt * xi[d] - dampt * vt[d]
    ft2 = ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]
    cap = mu * (fnmag if fnmag > 0.0 else -fnmag)
    if ft2 > cap * cap:
        scale = cap / sqrt(ft2)
        for d in range(3):
            ft[d] *= scale
        if advance and kt > 0.0:
            for d in range(3):      # sliding: the spring holds the Coulomb force minus the viscous part
                xi[d] = -(ft[d] + dampt * vt[d]) / kt
    return 0.4 * kn * delta * delta


cdef enum:                 # which law apply_pair_law uses (a constant at each call site)
    LAW_GRAINS3D = 0       # hooke above
    LAW_DESCANTES = 1      # descantes below


cdef inline double descantes(const double* c, double delta, const double* n, const double* vr, double meff,
                             double* fn, double* ft) noexcept nogil:
    """Descantes 2022 eq. 3 at one contact point (the caller's weight 1/alpha divides both forces):

        F_n = max(0, kn delta - nu_n U_n) n,          nu_n = 2 beta sqrt(kn m_ij)  (as hooke, from en)
        F_t = -min(nu_t |U_t|, mu |F_n|) t,    nu_t = 2 gamma_t m_ij + 2 beta_t sqrt(kn m_ij), t = U_t / |U_t|

    no attraction (a separating pair whose dashpot exceeds the spring feels no force) and no tangential
    spring: viscous friction capped by Coulomb (no history). Returns the elastic energy 0.5 kn delta^2."""
    cdef double kn = c[C_KN], mu = c[C_MU]
    cdef double vn = vr[0] * n[0] + vr[1] * n[1] + vr[2] * n[2]
    cdef double w = sqrt(kn * meff)
    cdef double fnmag = kn * delta - 2.0 * c[C_BETA] * w * vn
    cdef double vt[3]
    cdef double ut, scale, cap
    cdef int d
    if fnmag < 0.0:
        fnmag = 0.0
    for d in range(3):
        fn[d] = fnmag * n[d]
        vt[d] = vr[d] - vn * n[d]
        ft[d] = 0.0
    ut = sqrt(vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2])
    if mu == 0.0 or ut == 0.0:
        return 0.5 * kn * delta * delta
    scale = 2.0 * c[C_GAMMA_T] * meff + 2.0 * c[C_BETA_T] * w    # nu_t
    cap = mu * fnmag
    if scale * ut > cap:
        scale = cap / ut
    for d in range(3):
        ft[d] = -scale * vt[d]
    return 0.5 * kn * delta * delta


cdef inline void forget(double* xi) noexcept nogil:
    """A contact that ended forgets its tangential history (written only when set: saves bandwidth)."""
    if xi[0] != 0.0 or xi[1] != 0.0 or xi[2] != 0.0:
        xi[0] = 0.0
        xi[1] = 0.0
        xi[2] = 0.0


cdef inline bint rolling_torque(const double* c, const double* wi, const double* wj, const double* fn,
                                double reff, double* t) noexcept nogil:
    """Rolling resistance (c[C_MU_ROLL]): t, the torque on body i, of magnitude mu_roll reff |F_n| against
    the relative spin wi - wj (body j takes -t). False, t untouched, when there is none."""
    cdef double wr[3]
    cdef double wmag, mr
    cdef int d
    if c[C_MU_ROLL] <= 0.0:
        return False
    for d in range(3):
        wr[d] = wi[d] - wj[d]
    wmag = sqrt(wr[0] * wr[0] + wr[1] * wr[1] + wr[2] * wr[2])
    if wmag == 0.0:
        return False
    mr = c[C_MU_ROLL] * reff * sqrt(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2]) / wmag
    for d in range(3):
        t[d] = -mr * wr[d]
    return True
