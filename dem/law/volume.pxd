# cython: language_level=3
"""The overlap-volume law of sharp polytopes (`law volume`; Feng, Han & Owen, CMAME 205-208 (2012)
169-177: a contact potential that is a function of the overlap volume conserves energy). The potential is
the Hooke energy of an equivalent depth,

    U = 1/2 kn delta_V^2,   delta_V = V / A_ref,   A_ref = pi r_a r_b

(r the radii of the bodies' spheres of equal volume; a wall: A_ref = pi r_a^2): a flat face-to-face
contact of area A_ref is exactly Hooke's kn, as Descantes' law. Its exact gradient (dem/contact/_volume.pyx:
S = dV/dx_a, M = dV/dtheta_a) gives body a the force -kn V / A_ref^2 S and the torque -kn V / A_ref^2 M.

This is handed to the shared law as one contact record: the normal n = -S/|S|, the depth h = V/|S| (the
depth of a flat overlap of the same volume and area: exact for face/face) and a row whose stiffness is the
contact's own, kn |S|^2 / A_ref^2, so that the row's Hooke force is kn_c h = kn V |S| / A_ref^2 and its
energy 1/2 kn_c h^2 = U; damping (from en, on kn_c) and friction (capped by Coulomb) act at the point p on
the force's line of action nearest the overlap's centroid. A force along S at p gives the torque M minus
its part along S; that part, a couple about n, is added by volume_couple. So with en = 1 and mu = 0 the
force is the exact gradient of U and a collision keeps the energy to the integrator's error (second order
in dt), through every change of contact type.

One point has no grip against a relative spin about the normal, which a contact area has: volume_twist
adds the twisting friction of the overlap taken as a disc of area |S| under uniform pressure, a dashpot
on the relative spin (the tangential dashpot of the row, 2 (gamma_t m* + beta_t sqrt(kn_c m*)), over the
disc's polar radius of gyration squared, |S| / (2 pi)) capped by its Coulomb moment 2/3 mu |F_n| a,
a = sqrt(|S| / pi). It only dissipates, and vanishes with mu = 0."""
from libc.math cimport sqrt, fabs, M_PI

from dem._math cimport cross3, dot3
from dem.contact._volume cimport OverlapVolume
from dem.contact.record cimport Contact
from dem.law.apply cimport Body
from dem.law.row cimport C_KN, C_MU, C_GAMMA_T, C_BETA_T, NCOEFF


cdef inline double reference_area(double ra, double rb) noexcept nogil:
    """A_ref of two bodies whose spheres of equal volume have radii ra, rb (rb < 0: a wall)."""
    return M_PI * ra * (ra if rb < 0.0 else rb)


cdef inline bint volume_record(const OverlapVolume* ov, const double* xa, Contact* k, double* couple,
                               double* area) noexcept nogil:
    """Fills k (delta, n, p; one point of weight 1, lever p - x) from the overlap of body a (centre xa);
    couple receives the unit part of M along S, (s . M) s with s = S/|S| (times -kn V / A_ref^2 it is the
    couple on a), area |S|. False when S vanishes (one body wholly inside the other: no direction)."""
    cdef double s[3]
    cdef double sxm[3]
    cdef double p0[3]
    cdef double a2 = dot3(ov.area, ov.area), a, lam, sm
    cdef int d
    if not a2 > 0.0:
        return False
    a = sqrt(a2)
    for d in range(3):
        s[d] = ov.area[d] / a
    cross3(ov.area, ov.moment, sxm)
    for d in range(3):
        p0[d] = xa[d] + sxm[d] / a2
    lam = (ov.centroid[0] - p0[0]) * s[0] + (ov.centroid[1] - p0[1]) * s[1] + (ov.centroid[2] - p0[2]) * s[2]
    sm = dot3(s, ov.moment)
    for d in range(3):
        k.n[d] = -s[d]
        k.p[d] = p0[d] + lam * s[d]
        couple[d] = sm * s[d]
    k.delta = ov.volume / a
    k.central = False
    k.weight = 1.0
    k.inertia = 0.0
    area[0] = a
    return True


cdef inline void volume_row(const double* c, double area, double aref, double* row) noexcept nogil:
    """The contact's row: c with the stiffness kn |S|^2 / A_ref^2."""
    cdef int d
    cdef double r = area / aref
    for d in range(NCOEFF):
        row[d] = c[d]
    row[C_KN] = c[C_KN] * r * r


cdef inline void volume_couple(const double* c, double volume, double aref, const double* couple, Body* a,
                               Body* b, bint wall) noexcept nogil:
    """Adds the couple about the normal that the force at p leaves out of the exact torque: -kn V / A_ref^2
    times `couple` on a, the opposite on b (not on a wall)."""
    cdef double g = c[C_KN] * volume / (aref * aref)
    cdef int d
    for d in range(3):
        a.t[d] -= g * couple[d]
    if not wall:
        for d in range(3):
            b.t[d] += g * couple[d]


cdef inline void volume_twist(const double* c, double area, double meff, const Contact* k, const double* out,
                              Body* a, Body* b, bint wall) noexcept nogil:
    """Adds the twisting friction (module docstring) of the contact's row c (volume_row) at contact k, whose
    force on a is out (apply_pair/apply_wall)."""
    cdef double fn = fabs(out[0] * k.n[0] + out[1] * k.n[1] + out[2] * k.n[2])
    cdef double cap = 2.0 / 3.0 * c[C_MU] * fn * sqrt(area / M_PI)
    cdef double spin, m
    cdef int d
    if not cap > 0.0:
        return
    spin = (a.w[0] - b.w[0]) * k.n[0] + (a.w[1] - b.w[1]) * k.n[1] + (a.w[2] - b.w[2]) * k.n[2]
    m = 2.0 * (c[C_GAMMA_T] * meff + c[C_BETA_T] * sqrt(c[C_KN] * meff)) * area / (2.0 * M_PI) * spin
    if fabs(m) > cap:
        m = cap if m > 0.0 else -cap
    for d in range(3):
        a.t[d] -= m * k.n[d]
    if not wall:
        for d in range(3):
            b.t[d] += m * k.n[d]
