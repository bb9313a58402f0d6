# cython: language_level=3
"""Packing kernels of the per-step ghost communication: rows of a (n, k) float array to and from columns
of a message buffer, so that forward and reverse communication cost one call per field and swap."""
cimport numpy as cnp

ctypedef cnp.int64_t i64


def pack(const double[:, ::1] src, const i64[::1] idx, double[:, ::1] buf, int col):
    """buf[m, col:col+k] = src[idx[m]]"""
    cdef Py_ssize_t m, c, k = src.shape[1]
    with nogil:
        for m in range(idx.shape[0]):
            for c in range(k):
                buf[m, col + c] = src[idx[m], c]


def pack_shift(const double[:, ::1] src, const i64[::1] idx, double[:, ::1] buf, int col,
               double sx, double sy, double sz):
    """buf[m, col:col+3] = src[idx[m]] + shift (positions of periodic images)"""
    cdef Py_ssize_t m
    with nogil:
        for m in range(idx.shape[0]):
            buf[m, col] = src[idx[m], 0] + sx
            buf[m, col + 1] = src[idx[m], 1] + sy
            buf[m, col + 2] = src[idx[m], 2] + sz


def unpack(const double[:, ::1] buf, int col, double[:, ::1] dst, Py_ssize_t first, Py_ssize_t n):
    """dst[first + m] = buf[m, col:col+k]"""
    cdef Py_ssize_t m, c, k = dst.shape[1]
    with nogil:
        for m in range(n):
            for c in range(k):
                dst[first + m, c] = buf[m, col + c]


def pack_range(const double[:, ::1] src, Py_ssize_t first, Py_ssize_t n, double[:, ::1] buf, int col):
    """buf[m, col:col+k] = src[first + m]"""
    cdef Py_ssize_t m, c, k = src.shape[1]
    with nogil:
        for m in range(n):
            for c in range(k):
                buf[m, col + c] = src[first + m, c]


def add(const double[:, ::1] buf, int col, double[:, ::1] dst, const i64[::1] idx):
    """dst[idx[m]] += buf[m, col:col+k], in message order (deterministic)"""
    cdef Py_ssize_t m, c, k = dst.shape[1]
    with nogil:
        for m in range(idx.shape[0]):
            for c in range(k):
                dst[idx[m], c] += buf[m, col + c]
