"""One ghost message of the MPI decomposition (`Swap`, made by `CommMPI.borders`) and the two ways the
per-step communication runs through it: `Forward` (owners -> ghosts) and `Reverse` (ghosts -> owners).
The packing itself is in _mpi.pyx, one kernel call per field and swap."""
import numpy as np

from . import _mpi


class Swap:
    """One ghost message: `sendlist` (local indices) goes to `sendproc`; `nrecv` ghosts come from
    `recvproc` and are stored at `first`.."""

    __slots__ = ("sendlist", "sendproc", "recvproc", "first", "nrecv", "shift", "local", "buffers")

    def buffer(self, key, rows, width):
        buf = self.buffers.get(key)
        if buf is None or buf.shape != (rows, width):
            buf = self.buffers[key] = np.empty((rows, width))
        return buf


class Forward:
    """Owners -> ghosts: the rows of a swap's send list go to `sendproc` (positions shifted across a
    periodic edge), and what comes from `recvproc` overwrites the swap's ghost rows."""
    name, tag = "forward", 3

    @staticmethod
    def sizes(s):
        return len(s.sendlist), s.nrecv

    @staticmethod
    def ends(s):
        return s.sendproc, s.recvproc

    @staticmethod
    def pack(s, name, rows, buf, col):
        if name == "x" and s.shift is not None:
            _mpi.pack_shift(rows, s.sendlist, buf, col, *s.shift)
        else:
            _mpi.pack(rows, s.sendlist, buf, col)

    @staticmethod
    def store(s, buf, col, rows):
        _mpi.unpack(buf, col, rows, s.first, s.nrecv)


class Reverse:
    """Ghosts -> owners, the same swap run backwards: the ghost rows go to `recvproc`, and what comes from
    `sendproc` is added to the owners in the send list."""
    name, tag = "reverse", 4

    @staticmethod
    def sizes(s):
        return s.nrecv, len(s.sendlist)

    @staticmethod
    def ends(s):
        return s.recvproc, s.sendproc

    @staticmethod
    def pack(s, name, rows, buf, col):
        _mpi.pack_range(rows, s.first, s.nrecv, buf, col)

    @staticmethod
    def store(s, buf, col, rows):
        _mpi.add(buf, col, rows, s.sendlist)
