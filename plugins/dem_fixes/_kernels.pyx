# cython: language_level=3
"""Kernels of the fixes: planar walls (shared Grains3D law, m_ij = m_i against a wall) and gravity.

Shaped particles meet a plane through their support function: the deepest point of the (scaled) body
along the inward wall normal n is s(-n); overlap = its depth below the plane, contact point midway in the
overlap, lever from the centre of mass to that point. The true (sharp) body is used: a plane needs no
crust. Spheres keep the analytic path.

`centroid` points: the overlap is the same, but the contact point is the centroid of the body's
candidate points below the plane weighted by their depth (vertices of boxes and polyhedra, the deepest
rim point of each end disc of a cylinder, apex and base rim point of a cone; smooth bodies have one):
a face or an edge lying on the wall gets its middle instead of one arbitrary corner, and the point
moves continuously as the body tilts (a single corner below the plane is the deepest point again)."""
cimport numpy as cnp
from dem_contact.law cimport forget, hooke, push_at
from dem.shapes._support cimport ShapeRef, Surface, plane_touch, pose_shape

ctypedef cnp.int64_t i64


cdef double ZERO[3]      # the velocity of a fixed wall
ZERO[:] = [0.0, 0.0, 0.0]


def plane_walls(const double[:, ::1] x, const double[:, ::1] v, const double[:, ::1] omega,
                double[:, ::1] f, double[:, ::1] torque, const double[::1] radius, const double[::1] rmass,
                const int[::1] type_, const int[::1] mask, int groupbit, int nlocal,
                const int[::1] axis, const double[::1] position, const double[::1] side,
                const double[:, :, ::1] coeff, double[:, ::1] xi, bint use_history, double dt, bint advance,
                double[::1] stats, const double[:, ::1] quat, const int[::1] shape, const int[::1] is_sphere,
                const int[::1] skind, const double[:, ::1] sparams, const i64[::1] svoff,
                const int[::1] snv, const double[:, ::1] verts, const double[::1] srad, bint centroid=False):
    """Walls w: the plane axis[w] = position[w], particles on the side where side[w] * (x - position) > 0.
    xi holds 3 history values per wall per particle. stats: [contacts, max overlap / diameter, elastic
    energy]. Shape table arrays (body, not core): see dem.shape_command.SimShapes.kernel_arrays.
    centroid: contact points of shaped particles by the depth-weighted centroid (module docstring)."""
    cdef int i, w, d, a, s, nw = axis.shape[0], ncont = 0
    cdef double gap, delta, ci, ov, maxov = 0.0, energy = 0.0, sc
    cdef double n[3]
    cdef double vr[3]
    cdef double fn[3]
    cdef double ft[3]
    cdef double p[3]
    cdef double l[3]
    cdef double F[3]
    cdef double R[9]
    cdef ShapeRef S
    cdef Surface wall
    cdef bint posed
    wall.cylinder = False
    cdef double* h
    with nogil:
        for i in range(nlocal):
            if not (mask[i] & groupbit):
                continue
            s = shape[i]
            if s >= 0 and not is_sphere[s]:
                posed = False
                for w in range(nw):
                    a = axis[w]
                    if side[w] * (x[i, a] - position[w]) >= radius[i]:     # bounding sphere clear
                        if use_history and advance:
                            forget(&xi[i, 3 * w])
                        continue
                    if not posed:
                        pose_shape(&S, skind[s], &sparams[s, 0], snv[s], &verts[svoff[s], 0], &quat[i, 0],
                                   radius[i] / srad[s], R)
                        posed = True
                    wall.a = a
                    wall.side = side[w]
                    wall.pos = position[w]
                    delta = plane_touch(&S, R, &x[i, 0], &wall, centroid, 1e-9 * radius[i], n, p)
                    if delta <= 0.0:
                        if use_history and advance:
                            forget(&xi[i, 3 * w])
                        continue
                    ncont += 1
                    ov = delta / (2.0 * radius[i])
                    if ov > maxov:
                        maxov = ov
                    for d in range(3):
                        l[d] = p[d] - x[i, d]
                    h = &xi[i, 3 * w] if use_history else NULL
                    energy += push_at(&coeff[w, type_[i], 0], delta, n, l, &v[i, 0], &omega[i, 0], ZERO, rmass[i],
                                      h, dt, advance, &f[i, 0], &torque[i, 0], F)
                continue
            for w in range(nw):
                a = axis[w]
                gap = side[w] * (x[i, a] - position[w])
                if gap >= radius[i]:
                    if use_history and advance:
                        forget(&xi[i, 3 * w])
                    continue
                delta = radius[i] - gap
                ncont += 1
                ov = delta / (2.0 * radius[i])
                if ov > maxov:
                    maxov = ov
                n[0] = 0.0
                n[1] = 0.0
                n[2] = 0.0
                n[a] = side[w]
                ci = radius[i] - 0.5 * delta
                # velocity of the particle surface at the contact point (lever -ci n); the wall is at rest
                vr[0] = v[i, 0] - ci * (omega[i, 1] * n[2] - omega[i, 2] * n[1])
                vr[1] = v[i, 1] - ci * (omega[i, 2] * n[0] - omega[i, 0] * n[2])
                vr[2] = v[i, 2] - ci * (omega[i, 0] * n[1] - omega[i, 1] * n[0])
                h = &xi[i, 3 * w] if use_history else NULL
                energy += hooke(&coeff[w, type_[i], 0], delta, n, vr, rmass[i], h, dt, advance, fn, ft)
                for d in range(3):
                    f[i, d] += fn[d] + ft[d]
                torque[i, 0] -= ci * (n[1] * ft[2] - n[2] * ft[1])
                torque[i, 1] -= ci * (n[2] * ft[0] - n[0] * ft[2])
                torque[i, 2] -= ci * (n[0] * ft[1] - n[1] * ft[0])
    stats[0] = ncont
    stats[1] = maxov
    stats[2] = energy


def gravity(double[:, ::1] f, const double[::1] rmass, const int[::1] mask, int groupbit, int nlocal,
            double gx, double gy, double gz):
    """f += m g for the particles of the group."""
    cdef int i
    with nogil:
        for i in range(nlocal):
            if mask[i] & groupbit:
                f[i, 0] += rmass[i] * gx
                f[i, 1] += rmass[i] * gy
                f[i, 2] += rmass[i] * gz
