# cython: language_level=3
"""Solid fraction of a region by structured-lattice voxelisation (Part III sec 4.1): a grid point is solid
when it lies inside a particle, periodic images included: inside a sphere, or inside any convex piece of
a shaped particle (its body, or a glued composite's components: the gauges of dem/shapes/_gauge.pxd in
the piece's body frame). Points are the centres of the cells of a regular grid; particles are binned by
their bounding spheres in cells at least one largest radius wide, so that a point tests only the
particles of the 27 cells around it (and first the last one that held the previous point of its row)."""
import numpy as np
cimport numpy as cnp
from libc.math cimport floor

from dem_process._cells cimport cell_of, dist2, stencil
from dem.shapes._gauge cimport gauge
from dem.shapes._support cimport NPARAM
from dem.shapes._table cimport ShapeView, TableView, COMP_POSE, round_body, ncomponents, component_row

ctypedef cnp.int64_t i64


cdef inline bint _in_region(int kind, const double* p, const double[::1] rp) noexcept nogil:
    """kind 0: everything; 1: cylinder (rp = axis, c_b, c_c, R, lo, hi with b, c the other axes in xyz
    order); 2: sphere (rp = cx, cy, cz, R)."""
    cdef int a, b, c
    cdef double d0, d1, d2
    if kind == 1:
        a = <int>rp[0]
        b = 1 if a == 0 else 0
        c = 1 if a == 2 else 2
        d0 = p[b] - rp[1]
        d1 = p[c] - rp[2]
        return d0 * d0 + d1 * d1 <= rp[3] * rp[3] and p[a] >= rp[4] and p[a] <= rp[5]
    if kind == 2:
        d0 = p[0] - rp[0]
        d1 = p[1] - rp[1]
        d2 = p[2] - rp[2]
        return d0 * d0 + d1 * d1 + d2 * d2 <= rp[3] * rp[3]
    return True


cdef inline bint _in_particle(int q, const double* p, const double* xq, double r, int s, const double* R,
                              const TableView* T, const double* planes, const i64* pstart, const double* prd,
                              const int* periodic) noexcept nogil:
    """Whether point p lies inside particle q (centre xq, bounding radius r, shape index s, R its unit
    rotation body -> world, row-major), minimum image along periodic axes."""
    cdef double d[3]
    cdef double b[3]
    cdef double u[3]
    cdef double r2 = 0.0, sc
    cdef const double* Q
    cdef int k, c, row
    for k in range(3):
        d[k] = p[k] - xq[k]
        if periodic[k]:
            d[k] -= prd[k] * floor(d[k] / prd[k] + 0.5)
        r2 += d[k] * d[k]
    if r2 >= r * r:
        return False
    if round_body(T, s):
        return True
    sc = r / T.radius[s]
    for k in range(3):          # body frame at scale 1
        b[k] = (R[k] * d[0] + R[3 + k] * d[1] + R[6 + k] * d[2]) / sc
    for c in range(ncomponents(T, s)):
        row = component_row(T, s, c)
        if T.comp_count[s] == 0:
            u[0], u[1], u[2] = b[0], b[1], b[2]
        else:                   # the component's frame: Q^T (b - o)
            Q = T.comp_pose + COMP_POSE * (T.comp_first[s] + c)
            for k in range(3):
                u[k] = (Q[k] * (b[0] - Q[9]) + Q[3 + k] * (b[1] - Q[10]) + Q[6 + k] * (b[2] - Q[11]))
        if gauge(T.kind[row], &T.params[NPARAM * row], &planes[4 * pstart[row]],
                 <int>(pstart[row + 1] - pstart[row]), u[0], u[1], u[2]) <= 0.0:
            return True
    return False


def voxel_count(const double[:, ::1] x, const double[::1] radius, const double[::1] glo, const double[::1] h,
                const i64[::1] npts, const double[::1] boxlo, const double[::1] prd, const int[::1] periodic,
                int region_kind, const double[::1] region_params, const int[::1] shape, const double[:, ::1] rot,
                ShapeView shapes, const double[:, ::1] planes, const i64[::1] plane_start, int iz_start=0,
                int iz_stride=1):
    """Grid points glo + (i + 1/2) h, i < npts, per axis, in the z-layers iz_start, iz_start + iz_stride,
    ... (ranks share the layers), against the particles (x, bounding radius, shape index, unit rotation
    rot (n, 9) row-major) of the group; planes (P, 4): the face planes of the polyhedron rows of the shape
    table, row k's at plane_start[k]:plane_start[k + 1]. Returns (points inside the region, solid ones)."""
    cdef TableView table = shapes.t
    cdef const TableView* T = &table
    cdef int i, d, q, m, last = -1, b
    cdef int cells[27]
    cdef int n = <int>radius.shape[0]
    cdef i64 ix, iy, iz, kz, nz = (npts[2] - iz_start + iz_stride - 1) // iz_stride, inside = 0, solid = 0
    cdef double rmax = 0.0
    cdef double lo[3]
    cdef double hi[3]
    cdef double size[3]
    cdef double p[3]
    cdef int ncell[3]
    cdef int cc[3]
    cdef bint hit
    for i in range(n):
        if radius[i] > rmax:
            rmax = radius[i]
    if rmax == 0.0:
        for kz in range(nz):
            iz = iz_start + kz * iz_stride
            for iy in range(npts[1]):
                for ix in range(npts[0]):
                    p[0] = glo[0] + (ix + 0.5) * h[0]
                    p[1] = glo[1] + (iy + 0.5) * h[1]
                    p[2] = glo[2] + (iz + 0.5) * h[2]
                    if _in_region(region_kind, p, region_params):
                        inside += 1
        return inside, 0
    for d in range(3):
        if periodic[d]:
            lo[d] = boxlo[d]
            hi[d] = boxlo[d] + prd[d]
        else:
            lo[d] = glo[d] - rmax
            hi[d] = glo[d] + npts[d] * h[d] + rmax
        ncell[d] = <int>floor((hi[d] - lo[d]) / rmax)
        if ncell[d] < 1:
            ncell[d] = 1
    while ncell[0] * ncell[1] * ncell[2] > 8 * n + 4096:
        d = 0
        if ncell[1] > ncell[d]:
            d = 1
        if ncell[2] > ncell[d]:
            d = 2
        ncell[d] = (ncell[d] + 1) // 2
    for d in range(3):
        size[d] = (hi[d] - lo[d]) / ncell[d]
    cdef int ntot = ncell[0] * ncell[1] * ncell[2]
    cdef int[::1] head = np.full(ntot, -1, dtype=np.int32)
    cdef int[::1] nxt = np.full(max(n, 1), -1, dtype=np.int32)
    with nogil:
        for i in range(n):
            hit = True
            for d in range(3):
                cc[d] = <int>floor((x[i, d] - lo[d]) / size[d])
                if periodic[d]:
                    cc[d] = cc[d] % ncell[d]
                    if cc[d] < 0:
                        cc[d] += ncell[d]
                elif cc[d] < -1 or cc[d] > ncell[d]:
                    hit = False          # too far from the grid to cover any point
                elif cc[d] < 0:
                    cc[d] = 0
                elif cc[d] >= ncell[d]:
                    cc[d] = ncell[d] - 1
            if not hit:
                continue
            b = (cc[2] * ncell[1] + cc[1]) * ncell[0] + cc[0]
            nxt[i] = head[b]
            head[b] = i
        for kz in range(nz):
            iz = iz_start + kz * iz_stride
            p[2] = glo[2] + (iz + 0.5) * h[2]
            for iy in range(npts[1]):
                p[1] = glo[1] + (iy + 0.5) * h[1]
                last = -1
                for ix in range(npts[0]):
                    p[0] = glo[0] + (ix + 0.5) * h[0]
                    if not _in_region(region_kind, p, region_params):
                        continue
                    inside += 1
                    if last >= 0 and _in_particle(last, p, &x[last, 0], radius[last], shape[last], &rot[last, 0],
                                                  T, &planes[0, 0], &plane_start[0], &prd[0], &periodic[0]):
                        solid += 1
                        continue
                    hit = False
                    for d in range(3):
                        cc[d] = cell_of(p[d], lo[d], size[d], ncell[d], periodic[d])
                    for m in range(stencil(cc, ncell, &periodic[0], cells)):
                        q = head[cells[m]]
                        while q >= 0:
                            if _in_particle(q, p, &x[q, 0], radius[q], shape[q], &rot[q, 0], T, &planes[0, 0],
                                            &plane_start[0], &prd[0], &periodic[0]):
                                hit = True
                                last = q
                                break
                            q = nxt[q]
                        if hit:
                            break
                    if hit:
                        solid += 1
    return inside, solid
