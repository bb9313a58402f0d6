# cython: language_level=3
"""Rolling parts: the torque t on body a (body b takes -t) that resists the relative rotation wa - wb,
for contacts with a rolling radius reff > 0 (R*; apply.pxd's contact_radius).

R_CONSTANT: mu_roll R* |F_n| against the relative spin (today's Grains3D option; none when mu_roll = 0).
R_EPSD, R_EPSD2: the elastic-plastic spring-dashpot of Iwashita & Oda (1998) in the form of Ai, Chen,
    Rotter & Ooi, Powder Technol. 206 (2011) 269, model C. The relative rolling rate w_r is wa - wb
    without its component along n (twisting is not rolling). The spring torque M_k (history, in the
    current tangent plane) changes by -k_r w_r dt, k_r = 2.25 kn mu_roll^2 R*^2 (kn the normal stiffness
    of the contact: kn of Hooke, 4/3 Y* a of the Hertz family), and is held at |M_k| <= M_m = mu_roll R*
    |F_n + shift| (full mobilisation: the plastic limit; the load of the Coulomb caps, law.pxd, so that an
    adhesive contact resists rolling at zero net load, as LAMMPS's rolling sds). R_EPSD adds the dashpot
    -C_r w_r, C_r = eta_roll 2 sqrt(I_r k_r), while the spring is below its limit (f = 0 of model C),
    I_r = 1 / (1 / (I_a + m_a r_a^2) + 1 / (I_b + m_b r_b^2)) the rolling inertia about the contact
    (the geometry's `inertia` of the contact record); R_EPSD2 (LIGGGHTS's epsd2) has no dashpot."""
from libc.math cimport sqrt
from dem.law.row cimport C_MU_ROLL, C_ETA_ROLL, C_ROLLING, C_H_ROLL, R_CONSTANT, R_EPSD


cdef inline double sphere_rolling_inertia(double m, double r) noexcept nogil:
    """I + m r^2 = 7/5 m r^2: a solid sphere's inertia about a point of its surface (the EPSD dashpot's I_r is
    the harmonic sum of the two bodies', a wall's infinite)."""
    return 1.4 * m * r * r


cdef inline bint constant_torque(const double* c, const double* wa, const double* wb, const double* fn,
                                 double reff, double* t) noexcept nogil:
    """mu_roll reff |F_n| (fn: the normal force) against wa - wb; False, t untouched, when there is none."""
    cdef double wr[3]
    cdef double wmag, mr
    cdef int d
    if c[C_MU_ROLL] <= 0.0:
        return False
    for d in range(3):
        wr[d] = wa[d] - wb[d]
    wmag = sqrt(wr[0] * wr[0] + wr[1] * wr[1] + wr[2] * wr[2])
    if wmag == 0.0:
        return False
    mr = c[C_MU_ROLL] * reff * sqrt(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2]) / wmag
    for d in range(3):
        t[d] = -mr * wr[d]
    return True


cdef inline bint epsd(const double* c, const double* n, const double* wa, const double* wb, double load,
                      double kn, double reff, double inertia, double* h, double dt, bint advance,
                      double* t) noexcept nogil:
    """The EPSD torque (module docstring); h the contact's history (the spring at h[c[C_H_ROLL]])."""
    cdef double* m
    cdef double wr[3]
    cdef double mu = c[C_MU_ROLL]
    cdef double kr = 2.25 * kn * mu * mu * reff * reff
    cdef double mmax = mu * reff * load
    cdef double wn, mn, m2, scale, cr
    cdef bint full = False
    cdef int d
    if mu <= 0.0 or h == NULL:
        return False
    m = h + <int>c[C_H_ROLL]
    wn = (wa[0] - wb[0]) * n[0] + (wa[1] - wb[1]) * n[1] + (wa[2] - wb[2]) * n[2]
    for d in range(3):
        wr[d] = wa[d] - wb[d] - wn * n[d]
    if advance:
        mn = m[0] * n[0] + m[1] * n[1] + m[2] * n[2]
        for d in range(3):
            m[d] -= mn * n[d] + kr * wr[d] * dt
    m2 = m[0] * m[0] + m[1] * m[1] + m[2] * m[2]
    scale = 1.0
    if m2 >= mmax * mmax:
        full = True
        scale = mmax / sqrt(m2) if m2 > 0.0 else 0.0
        if advance:
            for d in range(3):
                m[d] *= scale
            scale = 1.0
    for d in range(3):
        t[d] = scale * m[d]
    if not full and <int>c[C_ROLLING] == R_EPSD and c[C_ETA_ROLL] > 0.0:
        cr = c[C_ETA_ROLL] * 2.0 * sqrt(inertia * kr)
        for d in range(3):
            t[d] -= cr * wr[d]
    return True


cdef inline bint rolling_torque(const double* c, const double* n, const double* wa, const double* wb,
                                const double* fn, double kn, double load, double reff, double inertia, double* h,
                                double dt, bint advance, double* t) noexcept nogil:
    """The row's rolling torque; fn the normal force, load |F_n + shift| (both times the contact's weight)."""
    if <int>c[C_ROLLING] == R_CONSTANT:
        return constant_torque(c, wa, wb, fn, reff, t)
    return epsd(c, n, wa, wb, load, kn, reff, inertia, h, dt, advance, t)
