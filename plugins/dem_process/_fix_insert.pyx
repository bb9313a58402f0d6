# cython: language_level=3
"""Overlap tests of insertion candidates (spheres: bounding spheres) against particles and against each
other, on a linked-cell grid, periodic images included (minimum image along periodic axes)."""
import numpy as np
cimport numpy as cnp
from libc.math cimport floor

from dem_process._cells cimport cell_of, dist2, stencil


def clash(const double[:, ::1] ax, const double[::1] ar, int na,
          const double[:, ::1] cx, const double[::1] cr, int nc,
          const double[::1] boxlo, const double[::1] prd, const int[::1] periodic,
          bint sequential, char[::1] reject):
    """reject[k] = 1 for candidates k (cx, cr) that overlap one of the na particles (ax, ar); with
    `sequential`, candidates are taken in order and each one kept (reject[k] == 0 on return) also blocks
    the later ones. Candidates already rejected on entry are skipped. Returns the number kept."""
    cdef int i, k, d, q, m, nkept = 0, nt = na + (nc if sequential else 0)
    cdef int cells[27]
    cdef double rmax = 0.0, s
    cdef double lo[3]
    cdef double hi[3]
    cdef double size[3]
    cdef int ncell[3]
    cdef int cc[3]
    if nc == 0:
        return 0
    for i in range(na):
        if ar[i] > rmax:
            rmax = ar[i]
    for k in range(nc):
        if cr[k] > rmax:
            rmax = cr[k]
    for d in range(3):
        if periodic[d]:
            lo[d] = boxlo[d]
            hi[d] = boxlo[d] + prd[d]
        else:
            lo[d] = cx[0, d]
            hi[d] = cx[0, d]
            for k in range(nc):
                lo[d] = min(lo[d], cx[k, d])
                hi[d] = max(hi[d], cx[k, d])
            for i in range(na):
                lo[d] = min(lo[d], ax[i, d])
                hi[d] = max(hi[d], ax[i, d])
        # cells at least one largest diameter wide: neighbours within the 27 surrounding cells
        ncell[d] = <int>floor((hi[d] - lo[d]) / (2.0 * rmax)) if rmax > 0.0 else 1
        if ncell[d] < 1:
            ncell[d] = 1
    # sparse systems: fewer, larger cells keep the grid memory bounded (still correct: cells only grow)
    while ncell[0] * ncell[1] * ncell[2] > 8 * (na + nc) + 4096:
        d = 0
        if ncell[1] > ncell[d]:
            d = 1
        if ncell[2] > ncell[d]:
            d = 2
        ncell[d] = (ncell[d] + 1) // 2
    for d in range(3):
        size[d] = (hi[d] - lo[d]) / ncell[d] if hi[d] > lo[d] else 1.0
    cdef int ntot = ncell[0] * ncell[1] * ncell[2]
    cdef int[::1] head = np.full(ntot, -1, dtype=np.int32)
    cdef int[::1] nxt = np.full(max(nt, 1), -1, dtype=np.int32)
    cdef double[:, ::1] px = np.empty((max(nt, 1), 3))
    cdef double[::1] pr = np.empty(max(nt, 1))
    cdef int np_ = 0, b
    with nogil:
        for i in range(na):
            for d in range(3):
                px[np_, d] = ax[i, d]
                cc[d] = cell_of(ax[i, d], lo[d], size[d], ncell[d], periodic[d])
            pr[np_] = ar[i]
            b = (cc[2] * ncell[1] + cc[1]) * ncell[0] + cc[0]
            nxt[np_] = head[b]
            head[b] = np_
            np_ += 1
        for k in range(nc):
            if reject[k]:
                continue
            for d in range(3):
                cc[d] = cell_of(cx[k, d], lo[d], size[d], ncell[d], periodic[d])
            for m in range(stencil(cc, ncell, &periodic[0], cells)):
                q = head[cells[m]]
                while q >= 0:
                    s = cr[k] + pr[q]
                    if dist2(&cx[k, 0], &px[q, 0], &prd[0], &periodic[0]) < s * s:
                        reject[k] = 1
                        break
                    q = nxt[q]
                if reject[k]:
                    break
            if reject[k]:
                continue
            nkept += 1
            if sequential:
                for d in range(3):
                    px[np_, d] = cx[k, d]
                pr[np_] = cr[k]
                b = (cc[2] * ncell[1] + cc[1]) * ncell[0] + cc[0]
                nxt[np_] = head[b]
                head[b] = np_
                np_ += 1
    return nkept
