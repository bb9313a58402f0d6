# cython: language_level=3
"""Linked-cell half neighbor list on bounding spheres, in compressed rows.

A pair (i, j) is listed once, in the row of the particle with the smaller tag (i owned, j owned or ghost),
when the bounding spheres come closer than the skin. Rows are sorted by partner tag, so the order in which
forces are summed does not depend on when the list was built: a run continues bitwise after a restart.
"""
import numpy as np
cimport numpy as cnp
from libc.math cimport floor

ctypedef cnp.int64_t i64


def build_half(const double[:, ::1] x, const double[::1] radius, const i64[::1] tag,
               int nlocal, int nall, double skin, double binsize,
               i64[::1] offsets, int[::1] neigh):
    """Fill offsets[0..nlocal] and neigh; returns the number of entries, or -(needed) when neigh is too
    small (the caller grows it and calls again)."""
    cdef int i, j, k, d, b, nb, bx, by, bz, ix, iy, iz, jx, jy, jz, n = 0, start, a
    cdef double lo[3]
    cdef double hi[3]
    cdef int nbin[3]
    cdef double dx, dy, dz, rc, inv = 1.0 / binsize
    cdef i64 ti, tj
    if nall == 0:
        offsets[0] = 0
        return 0
    for d in range(3):
        lo[d] = x[0, d]
        hi[d] = x[0, d]
    for i in range(nall):
        for d in range(3):
            if x[i, d] < lo[d]:
                lo[d] = x[i, d]
            if x[i, d] > hi[d]:
                hi[d] = x[i, d]
    for d in range(3):
        nbin[d] = <int>floor((hi[d] - lo[d]) * inv) + 1
        if nbin[d] > 1024:     # very sparse systems: coarser bins keep memory bounded
            nbin[d] = 1024
    cdef double scale[3]
    for d in range(3):
        scale[d] = nbin[d] / ((hi[d] - lo[d]) * (1.0 + 1e-12) + binsize)
    nb = nbin[0] * nbin[1] * nbin[2]
    cdef int[::1] count = np.zeros(nb + 1, dtype=np.int32)
    cdef int[::1] binof = np.empty(nall, dtype=np.int32)
    cdef int[::1] sorted_ = np.empty(nall, dtype=np.int32)
    with nogil:
        for i in range(nall):
            ix = <int>((x[i, 0] - lo[0]) * scale[0])
            iy = <int>((x[i, 1] - lo[1]) * scale[1])
            iz = <int>((x[i, 2] - lo[2]) * scale[2])
            if ix >= nbin[0]: ix = nbin[0] - 1
            if iy >= nbin[1]: iy = nbin[1] - 1
            if iz >= nbin[2]: iz = nbin[2] - 1
            b = (iz * nbin[1] + iy) * nbin[0] + ix
            binof[i] = b
            count[b + 1] += 1
        for b in range(nb):
            count[b + 1] += count[b]
        for i in range(nall):
            sorted_[count[binof[i]]] = i
            count[binof[i]] += 1
        for b in range(nb - 1, 0, -1):     # restore bin starts
            count[b] = count[b - 1]
        count[0] = 0
        # count[b] is now the start of bin b; the end is the start of b + 1 (count[nb] == nall)
        count[nb] = nall
        offsets[0] = 0
        for i in range(nlocal):
            start = n
            ti = tag[i]
            b = binof[i]
            bx = b % nbin[0]
            by = (b // nbin[0]) % nbin[1]
            bz = b // (nbin[0] * nbin[1])
            for jz in range(bz - 1, bz + 2):
                if jz < 0 or jz >= nbin[2]:
                    continue
                for jy in range(by - 1, by + 2):
                    if jy < 0 or jy >= nbin[1]:
                        continue
                    for jx in range(bx - 1, bx + 2):
                        if jx < 0 or jx >= nbin[0]:
                            continue
                        b = (jz * nbin[1] + jy) * nbin[0] + jx
                        for k in range(count[b], count[b + 1]):
                            j = sorted_[k]
                            tj = tag[j]
                            if tj <= ti:
                                continue
                            dx = x[i, 0] - x[j, 0]
                            dy = x[i, 1] - x[j, 1]
                            dz = x[i, 2] - x[j, 2]
                            rc = radius[i] + radius[j] + skin
                            if dx * dx + dy * dy + dz * dz < rc * rc:
                                if n < neigh.shape[0]:
                                    neigh[n] = j
                                n += 1
            if n <= neigh.shape[0]:
                # insertion sort of the row by partner tag: canonical summation order
                for k in range(start + 1, n):
                    a = neigh[k]
                    tj = tag[a]
                    j = k - 1
                    while j >= start and tag[neigh[j]] > tj:
                        neigh[j + 1] = neigh[j]
                        j -= 1
                    neigh[j + 1] = a
            offsets[i + 1] = n
    if n > neigh.shape[0]:
        return -n
    return n


def max_displacement_sq(const double[:, ::1] x, const double[:, ::1] xhold, int n):
    """Largest squared displacement since the last build."""
    cdef int i
    cdef double dx, dy, dz, d2, m = 0.0
    with nogil:
        for i in range(n):
            dx = x[i, 0] - xhold[i, 0]
            dy = x[i, 1] - xhold[i, 1]
            dz = x[i, 2] - xhold[i, 2]
            d2 = dx * dx + dy * dy + dz * dz
            if d2 != d2:
                m = d2             # NaN: the caller reports the broken particle
                break
            if d2 > m:
                m = d2
    return m
