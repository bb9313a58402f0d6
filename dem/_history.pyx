# cython: language_level=3
"""Contact history kept per particle between neighbor-list builds.

Before a rebuild, each listed pair's history values are copied into the per-particle arrays of the owner
of the pair (the smaller tag), keyed by the partner's tag; these arrays migrate with the particle. After
the build, each new pair looks its partner's tag up and takes its values back."""
cimport numpy as cnp

ctypedef cnp.int64_t i64


def pack(const i64[::1] offsets, const int[::1] neigh, const i64[::1] tag, const double[:, ::1] values,
         int nlocal, int[::1] npartner, i64[:, ::1] partner, double[:, ::1] store):
    """Returns 0, or the number of partner slots needed when `partner` has too few columns."""
    cdef int i, k, m, c, nv = values.shape[1], maxp = partner.shape[1], need = 0, nonzero
    with nogil:
        for i in range(nlocal):
            m = 0
            for k in range(offsets[i], offsets[i + 1]):
                nonzero = 0
                for c in range(nv):
                    if values[k, c] != 0.0:
                        nonzero = 1
                        break
                if not nonzero:
                    continue
                if m < maxp:
                    partner[i, m] = tag[neigh[k]]
                    for c in range(nv):
                        store[i, m * nv + c] = values[k, c]
                m += 1
            npartner[i] = m if m < maxp else maxp
            if m > need:
                need = m
    return need if need > maxp else 0


def unpack(const i64[::1] offsets, const int[::1] neigh, const i64[::1] tag, double[:, ::1] values,
           int nlocal, const int[::1] npartner, const i64[:, ::1] partner, const double[:, ::1] store):
    cdef int i, k, m, c, nv = values.shape[1]
    cdef i64 tj
    with nogil:
        for i in range(nlocal):
            if npartner[i] == 0:
                for k in range(offsets[i], offsets[i + 1]):
                    for c in range(nv):
                        values[k, c] = 0.0
                continue
            for k in range(offsets[i], offsets[i + 1]):
                tj = tag[neigh[k]]
                for c in range(nv):
                    values[k, c] = 0.0
                for m in range(npartner[i]):
                    if partner[i, m] == tj:
                        for c in range(nv):
                            values[k, c] = store[i, m * nv + c]
                        break
