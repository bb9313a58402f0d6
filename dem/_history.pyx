# cython: language_level=3
"""Contact history kept per particle between neighbor-list builds.

Before a rebuild, each listed pair's history values are copied into the per-particle arrays of the owner
of the pair (the smaller tag), keyed by the partner's tag; these arrays migrate with the particle. After
the build, each new pair looks its partner's tag up and takes its values back. Single-record histories
(`pack`, `unpack`) keep one dense row per list entry; keyed ones (`KeyedBuffers`, `pack_keyed`,
`unpack_keyed`) keep several records per entry, stored per particle by (partner tag, key)."""
import numpy as np

cimport numpy as cnp

cnp.import_array()


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


# ----- keyed records ---------------------------------------------------------------------------------
cdef inline i64* _i64(object a):
    return <i64*> cnp.PyArray_DATA(a)


cdef inline double* _f64(object a):
    return <double*> cnp.PyArray_DATA(a)


cdef class KeyedBuffers:
    """The old records (last step's) and the next buffer of a keyed history, and the view kernels take
    (`&buffers.view`), re-pointed whenever an array is replaced. Old and next swap, so that a steady run
    allocates nothing."""

    def __init__(self, int width):
        self.view.width = width
        self.offsets = np.zeros(1, np.int64)
        self.keys = np.zeros(0, np.int64)
        self.values = np.zeros((0, width))
        self.next_offsets = np.zeros(1, np.int64)
        self.next_keys = np.zeros(0, np.int64)
        self.next_values = np.zeros((0, width))
        self.view.nentries = 0
        self._bind()

    cdef void _bind(self):
        cdef KeyedView* h = &self.view
        h.offsets, h.keys, h.values = _i64(self.offsets), _i64(self.keys), _f64(self.values)
        h.next_offsets, h.next_keys = _i64(self.next_offsets), _i64(self.next_keys)
        h.next_values = _f64(self.next_values)
        h.next_cap = min(len(self.next_keys), len(self.next_values))

    def set_old(self, offsets, keys, values):
        """Replace the old records (offsets: nentries + 1 values; keys, values: at least offsets[-1] rows)."""
        offsets = np.ascontiguousarray(offsets, dtype=np.int64)
        keys = np.ascontiguousarray(keys, dtype=np.int64)
        values = np.ascontiguousarray(values, dtype=np.float64).reshape(-1, self.view.width)
        if len(offsets) < 1 or offsets[0] != 0 or np.any(np.diff(offsets) < 0) or \
                min(len(keys), len(values)) < offsets[-1]:
            raise ValueError("keyed history: offsets must start at 0, never decrease and fit the records")
        self.offsets, self.keys, self.values = offsets, keys, values
        self.view.nentries = len(offsets) - 1
        self._bind()

    def begin(self, i64 cap):
        """Empty the next buffer, with room for at least `cap` records, for a step over the current list."""
        cdef i64 n = self.view.nentries
        if len(self.next_offsets) < n + 1:
            self.next_offsets = np.zeros(n + 1, np.int64)
        if len(self.next_keys) < cap:
            self.next_keys = np.zeros(cap, np.int64)
            self.next_values = np.zeros((cap, self.view.width))
        self._bind()
        self.view.next_n = self.view.next_k = self.view.want = 0
        self.view.error = KEYED_OK

    def rollback(self, i64 k):
        """Drop what was appended for entries k and after (a kernel resumes at k)."""
        cdef KeyedView* h = &self.view
        if h.next_k > k:
            h.next_n = h.next_offsets[k]
            h.next_k = k

    def grow(self, i64 cap):
        """A next buffer of `cap` rows, keeping the records appended so far."""
        cdef i64 n = self.view.next_n
        if cap <= len(self.next_keys):
            return
        keys, values = np.zeros(cap, np.int64), np.zeros((cap, self.view.width))
        keys[:n], values[:n] = self.next_keys[:n], self.next_values[:n]
        self.next_keys, self.next_values = keys, values
        self._bind()

    def finish(self):
        """Close the offsets of the entries after the last one appended."""
        cdef KeyedView* h = &self.view
        while h.next_k <= h.nentries:
            h.next_offsets[h.next_k] = h.next_n
            h.next_k += 1

    def swap(self):
        """The next buffer becomes the old records; keys not appended this step are forgotten."""
        self.offsets, self.next_offsets = self.next_offsets, self.offsets
        self.keys, self.next_keys = self.next_keys, self.keys
        self.values, self.next_values = self.next_values, self.values
        self._bind()

    @property
    def width(self):
        return self.view.width

    @property
    def nentries(self):
        return self.view.nentries

    @property
    def nrec(self):
        return int(self.offsets[self.view.nentries])

    @property
    def next_n(self):
        return self.view.next_n

    @property
    def want(self):
        return self.view.want

    @property
    def error(self):
        return self.view.error


def pack_keyed(const i64[::1] offsets, const int[::1] neigh, const i64[::1] tag, KeyedBuffers buf,
               int nlocal, int[::1] npartner, i64[:, ::1] partner, i64[:, ::1] pkey, double[:, ::1] store):
    """Every nonzero record of the rows of owned particles into their store, by (partner tag, key); an
    all-zero record is not kept (a new key starts at zero). Returns 0, or the slots needed."""
    cdef const KeyedView* h = &buf.view
    cdef int i, m, c, nv = h.width, maxp = partner.shape[1], need = 0, nonzero
    cdef i64 k, r
    with nogil:
        for i in range(nlocal):
            m = 0
            for k in range(offsets[i], offsets[i + 1]):
                for r in range(h.offsets[k], h.offsets[k + 1]):
                    nonzero = 0
                    for c in range(nv):
                        if h.values[r * nv + c] != 0.0:
                            nonzero = 1
                            break
                    if not nonzero:
                        continue
                    if m < maxp:
                        partner[i, m] = tag[neigh[k]]
                        pkey[i, m] = h.keys[r]
                        for c in range(nv):
                            store[i, m * nv + c] = h.values[r * nv + c]
                    m += 1
            npartner[i] = m if m < maxp else maxp
            if m > need:
                need = m
    return need if need > maxp else 0


def unpack_keyed(const i64[::1] offsets, const int[::1] neigh, const i64[::1] tag, int nlocal,
                 const int[::1] npartner, const i64[:, ::1] partner, const i64[:, ::1] pkey,
                 const double[:, ::1] store, i64[::1] roff, i64[::1] keys, double[:, ::1] values):
    """The records of each entry of a fresh list from its owner's store, matched by partner tag, in store
    order: `roff` gets the record offsets; keys and values are filled when they have room for the total,
    which is returned."""
    cdef int i, m, c, nv = values.shape[1]
    cdef i64 k, r = 0, tj, total
    with nogil:
        roff[0] = 0
        for i in range(nlocal):
            for k in range(offsets[i], offsets[i + 1]):
                tj = tag[neigh[k]]
                for m in range(npartner[i]):
                    if partner[i, m] == tj:
                        r += 1
                roff[k + 1] = r
    total = r
    if total > keys.shape[0] or total > values.shape[0]:
        return total
    r = 0
    with nogil:
        for i in range(nlocal):
            for k in range(offsets[i], offsets[i + 1]):
                tj = tag[neigh[k]]
                for m in range(npartner[i]):
                    if partner[i, m] == tj:
                        keys[r] = pkey[i, m]
                        for c in range(nv):
                            values[r, c] = store[i, m * nv + c]
                        r += 1
    return r


cdef i64 _apply(KeyedView* h, const i64* offsets, i64 nlocal, const i64[::1] entry, const i64[::1] key,
                const double[:, ::1] add, i64[::1] visits, i64 start) noexcept nogil:
    cdef i64 n = entry.shape[0], i, k, p = 0, q, r
    cdef int c
    cdef double* row
    while p < n and entry[p] < start:
        p += 1
    for i in range(keyed_owner(offsets, nlocal, start), nlocal):
        for k in range(max(offsets[i], start), offsets[i + 1]):
            q = p
            while q < n and entry[q] == k:
                q += 1
            if not keyed_reserve(h, k, q - p):      # before anything of this pair is done
                return k
            visits[k] += 1
            for r in range(p, q):
                row = keyed_append(h, k, key[r])
                if row == NULL:
                    return -1
                for c in range(h.width):
                    row[c] += add[r, c]
            p = q
    return -1


def apply_records(KeyedBuffers buf, const i64[::1] offsets, int nlocal, const i64[::1] entry,
                  const i64[::1] key, const double[:, ::1] add, i64[::1] visits, i64 start):
    """The reference kernel of the keyed API (tests, tools): a pair loop from list entry `start` that
    appends the records (entry, key) given sorted by entry and adds `add` to each, counting in `visits`
    each entry it handles. Returns -1, or the entry to resume from when the next buffer is full."""
    cdef i64 resume
    if nlocal == 0 or start >= offsets[nlocal]:
        return -1
    with nogil:
        resume = _apply(&buf.view, &offsets[0], nlocal, entry, key, add, visits, start)
    return resume
