# cython: language_level=3
"""Keyed contact history: the nogil API of pair kernels (several records per neighbor pair, each with a
key: 0 for a single contact point, the component pair for composites, a feature key for polyhedra).

The records of list entry k are rows offsets[k]:offsets[k+1] of `keys` and `values` (old: those of the
last step). During a step a kernel appends this step's records to the *next* buffer, entry after entry
(k never decreases); a record starts as the old record of the same key, or zero when the key is new.
Keys not appended in a step are forgotten when the Python driver swaps the buffers.

Kernels never allocate. Before the first append of entry k the kernel calls `keyed_reserve(h, k, m)`
for all m records of that pair, and before it adds any force of that pair; on False it returns k (the
entry to resume from) and the driver grows the buffer and calls it again from k."""
from libc.stdint cimport int64_t
from libc.string cimport memcpy, memset

ctypedef int64_t i64

cdef enum:
    KEYED_OK = 0
    KEYED_ORDER = 1        # an append for an entry before the current one
    KEYED_FULL = 2         # an append without room (no keyed_reserve before it)


cdef struct KeyedView:
    const i64* offsets     # old records: nentries + 1 offsets, then keys and values rows of `width`
    const i64* keys
    const double* values
    i64 nentries
    int width
    i64* next_offsets      # next buffer: offsets filled for entries below next_k
    i64* next_keys
    double* next_values
    i64 next_n             # records appended so far
    i64 next_cap           # rows the next buffer holds
    i64 next_k
    i64 want               # rows a failed keyed_reserve asked for
    int error


cdef class KeyedBuffers:
    cdef KeyedView view
    cdef readonly object offsets, keys, values, next_offsets, next_keys, next_values
    cdef void _bind(self)


cdef inline const double* keyed_find(const KeyedView* h, i64 k, i64 key) noexcept nogil:
    """The old record of entry k with this key, or NULL."""
    cdef i64 r
    for r in range(h.offsets[k], h.offsets[k + 1]):
        if h.keys[r] == key:
            return h.values + r * h.width
    return NULL


cdef inline bint keyed_reserve(KeyedView* h, i64 k, i64 m) noexcept nogil:
    """Whether m more records fit; if not, the kernel stops before entry k and returns k."""
    if h.next_n + m <= h.next_cap:
        return True
    h.want = h.next_n + m
    return False


cdef inline double* keyed_append(KeyedView* h, i64 k, i64 key) noexcept nogil:
    """This step's record (k, key), initialised from the old record of that key or zero; appending the
    same key twice for one entry returns the same record. NULL (and h.error) when the protocol is broken."""
    cdef i64 r
    cdef const double* old
    cdef double* row
    if k + 1 < h.next_k:
        h.error = KEYED_ORDER
        return NULL
    while h.next_k <= k:                   # entries without a record in between get empty rows
        h.next_offsets[h.next_k] = h.next_n
        h.next_k += 1
    for r in range(h.next_offsets[k], h.next_n):
        if h.next_keys[r] == key:
            return h.next_values + r * h.width
    if h.next_n >= h.next_cap:
        h.error = KEYED_FULL
        return NULL
    r = h.next_n
    h.next_keys[r] = key
    row = h.next_values + r * h.width
    old = keyed_find(h, k, key)
    if old != NULL:
        memcpy(row, old, h.width * sizeof(double))
    else:
        memset(row, 0, h.width * sizeof(double))
    h.next_n += 1
    return row


cdef inline i64 keyed_owner(const i64* offsets, i64 nlocal, i64 k) noexcept nogil:
    """The owned particle whose neighbor row holds list entry k (to resume a kernel at entry k)."""
    cdef i64 lo = 0, hi = nlocal, mid
    while hi - lo > 1:                     # offsets[lo] <= k < offsets[hi]
        mid = (lo + hi) // 2
        if offsets[mid] <= k:
            lo = mid
        else:
            hi = mid
    return lo
