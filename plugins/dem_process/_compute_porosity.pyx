# cython: language_level=3
"""Solid fraction of a region by structured-lattice voxelisation (Part III sec 4.1): a grid point is solid
when it lies inside a particle (spheres: inside any sphere, periodic images included). Points are the
centres of the cells of a regular grid; spheres are binned in cells at least one largest radius wide,
so that a point tests only the spheres of the 27 cells around it (and first the last sphere that held
the previous point of its row)."""
import numpy as np
cimport numpy as cnp
from libc.math cimport floor

from dem_process._cells cimport cell_of, dist2, stencil

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


def voxel_count(const double[:, ::1] x, const double[::1] radius, const double[::1] glo, const double[::1] h,
                const i64[::1] npts, const double[::1] boxlo, const double[::1] prd, const int[::1] periodic,
                int region_kind, const double[::1] region_params, int iz_start=0, int iz_stride=1):
    """Grid points glo + (i + 1/2) h, i < npts, per axis, in the z-layers iz_start, iz_start + iz_stride,
    ... (ranks share the layers), against the spheres (x, radius) of the group. Returns (points inside the
    region, solid ones)."""
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
                    if last >= 0 and dist2(p, &x[last, 0], &prd[0], &periodic[0]) < radius[last] * radius[last]:
                        solid += 1
                        continue
                    hit = False
                    for d in range(3):
                        cc[d] = cell_of(p[d], lo[d], size[d], ncell[d], periodic[d])
                    for m in range(stencil(cc, ncell, &periodic[0], cells)):
                        q = head[cells[m]]
                        while q >= 0:
                            if dist2(p, &x[q, 0], &prd[0], &periodic[0]) < radius[q] * radius[q]:
                                hit = True
                                last = q
                                break
                            q = nxt[q]
                        if hit:
                            break
                    if hit:
                        solid += 1
    return inside, solid
