# cython: language_level=3
"""Leap-frog Verlet (Grains3D eq. 9) for translation, and for rotation either the isotropic update of
spheres or Omelyan's revised leap-frog on the angular momentum (Descantes eq. 8-11)."""
cimport numpy as cnp
from libc.math cimport sqrt, fabs
from dem._math cimport quat_rotate, quat_rotate_inv, quat_mul, cross3


def nve_sphere(double[:, ::1] x, double[:, ::1] v, const double[:, ::1] f, double[:, ::1] omega,
               const double[:, ::1] torque, const double[::1] rmass, const double[:, ::1] inertia,
               const int[::1] mask, int groupbit, int nlocal, double dt):
    """v(n+1/2) = v(n-1/2) + dt F(n)/m, x(n+1) = x(n) + dt v(n+1/2); omega likewise with the isotropic
    moment of inertia of a sphere."""
    cdef int i, d
    cdef double dtm, dti
    with nogil:
        for i in range(nlocal):
            if not (mask[i] & groupbit):
                continue
            dtm = dt / rmass[i]
            dti = dt / inertia[i, 0]
            for d in range(3):
                v[i, d] += dtm * f[i, d]
                x[i, d] += dt * v[i, d]
                omega[i, d] += dti * torque[i, d]


def nve_shape(double[:, ::1] x, double[:, ::1] v, const double[:, ::1] f, double[:, ::1] omega,
              double[:, ::1] angmom, double[:, ::1] quat, const double[:, ::1] torque,
              const double[::1] rmass, const double[:, ::1] inertia, const int[::1] mask, int groupbit,
              int nlocal, double dt):
    """Translation as nve_sphere. Rotation (Omelyan's revised leap-frog):
        J(n+1/2) = J(n-1/2) + dt T(n)                              (space frame)
        w_b = I^-1 [A J(n+1/2) + dt/2 (I w_b) x w_b]              (body frame, solved by fixed point)
        A(n+1) = (1 - Theta)^-1 (1 + Theta) A(n),  Theta = dt/2 W[w_b]
    The Cayley factor is the rotation by 2 atan(|a|) about a = dt/2 w_b, i.e. the unit quaternion
    (1, a)/sqrt(1 + |a|^2) applied in the body frame: the orientation stays orthonormal by construction.
    For an isotropic body (three equal moments) w = J / I and the same factor acts in the space frame."""
    cdef int i, d, it
    cdef double dtm, h = 0.5 * dt, err, n2
    cdef bint iso
    cdef double jb[3]
    cdef double wb[3]
    cdef double wn[3]
    cdef double inv[3]
    cdef double lw[3]
    cdef double c[3]
    cdef double dq[4]
    cdef double qn[4]
    with nogil:
        for i in range(nlocal):
            if not (mask[i] & groupbit):
                continue
            dtm = dt / rmass[i]
            for d in range(3):
                v[i, d] += dtm * f[i, d]
                x[i, d] += dt * v[i, d]
                angmom[i, d] += dt * torque[i, d]
            iso = inertia[i, 0] == inertia[i, 1] and inertia[i, 1] == inertia[i, 2]
            if iso:
                # isotropic body (cube, regular tetrahedron): w = J / I in both frames and (I w) x w = 0,
                # so the Cayley factor can act in the space frame, A(n+1) = dq(dt/2 w) A(n): no frame change
                inv[0] = 1.0 / inertia[i, 0]
                for d in range(3):
                    omega[i, d] = angmom[i, d] * inv[0]
                    wb[d] = omega[i, d]
            else:
                quat_rotate_inv(&quat[i, 0], &angmom[i, 0], jb)
                for d in range(3):
                    inv[d] = 1.0 / inertia[i, d]
                    wb[d] = jb[d] * inv[d]
                for it in range(50):
                    for d in range(3):
                        lw[d] = inertia[i, d] * wb[d]
                    cross3(lw, wb, c)
                    err = 0.0
                    n2 = 0.0
                    for d in range(3):
                        wn[d] = (jb[d] + h * c[d]) * inv[d]
                        err += (wn[d] - wb[d]) * (wn[d] - wb[d])
                        n2 += wn[d] * wn[d]
                        wb[d] = wn[d]
                    if err <= 1e-30 * n2 or err == 0.0:
                        break
                quat_rotate(&quat[i, 0], wb, &omega[i, 0])
            dq[0] = 1.0
            # a = dt/2 w; the quaternion of rotation 2 atan|a| about a is (1, a)/sqrt(1 + |a|^2)
            dq[1] = h * wb[0]
            dq[2] = h * wb[1]
            dq[3] = h * wb[2]
            n2 = dq[1] * dq[1] + dq[2] * dq[2] + dq[3] * dq[3]
            # 1/sqrt(1 + n2); its series to n2^3 is exact to round-off (35/128 n2^4 < 3e-17) below 1e-4
            n2 = 1.0 + n2 * (-0.5 + n2 * (0.375 - 0.3125 * n2)) if n2 < 1e-4 else 1.0 / sqrt(1.0 + n2)
            for d in range(4):
                dq[d] *= n2
            if iso:
                quat_mul(dq, &quat[i, 0], qn)      # space frame
            else:
                quat_mul(&quat[i, 0], dq, qn)      # body frame
            n2 = qn[0] * qn[0] + qn[1] * qn[1] + qn[2] * qn[2] + qn[3] * qn[3]
            # the product of unit quaternions is unit to round-off: one Newton step for 1/sqrt (error
            # O((n2 - 1)^2)) renormalises it without the latency of a square root and a division
            n2 = 1.5 - 0.5 * n2 if fabs(n2 - 1.0) < 1e-6 else 1.0 / sqrt(n2)
            for d in range(4):
                quat[i, d] = qn[d] * n2


def angmom_from_omega(const double[:, ::1] omega, double[:, ::1] angmom, const double[:, ::1] quat,
                      const double[:, ::1] inertia, int nlocal):
    """J = R I R^T omega for particles given an angular velocity but no angular momentum."""
    cdef int i, d
    cdef double wb[3]
    with nogil:
        for i in range(nlocal):
            if angmom[i, 0] != 0.0 or angmom[i, 1] != 0.0 or angmom[i, 2] != 0.0:
                continue
            quat_rotate_inv(&quat[i, 0], &omega[i, 0], wb)
            for d in range(3):
                wb[d] *= inertia[i, d]
            quat_rotate(&quat[i, 0], wb, &angmom[i, 0])
