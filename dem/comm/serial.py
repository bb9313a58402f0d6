"""The communicator of a single process, and the base class of every communicator: each method the rest
of the code calls is declared here, so callers never ask how many ranks there are to know whether a
method exists (`CommMPI` in mpi.py overrides what a decomposition changes).

Serial runs keep the same structure an MPI run needs: `borders()` makes ghost images near periodic
boundaries (each ghost remembers its owner and the shift of its image), `forward()` refreshes ghost
positions, velocities, spins and orientations from their owners every step, and `reverse()` adds the
forces accumulated on ghosts back to their owners (half neighbor lists, Newton's third law).
"""
import sys

import numpy as np

from ..errors import DemError
from . import _serial


class Comm:
    me = 0
    nprocs = 1
    procgrid = (1, 1, 1)
    grid_settled = False   # the decomposition is final (settle_grid ran, a restart or `balance` set it)

    def __init__(self, sim):
        self.sim = sim
        self.ghost_owner = np.zeros(0, dtype=np.int64)
        self.ghost_shift = np.zeros((0, 3))
        self.cutghost = 0.0

    # ----- reductions (serial: identity) ------------------------------------------------------------
    def sum(self, value):
        return value

    def max(self, value):
        return value

    def min(self, value):
        return value

    def max_values(self, values):
        """Elementwise max over ranks of a small float64 array (in place; serial: as it is)."""
        return values

    def sum_values(self, values):
        """Elementwise sum over ranks of a float64 array (in place; serial: as it is): analysis profiles."""
        return values

    def min_avg_max(self, values):
        """(min, average, max) over ranks of a small float array, elementwise (serial: the values thrice)."""
        v = np.asarray(values, dtype=np.float64)
        return v.copy(), v.copy(), v.copy()

    def any(self, flag):
        return bool(flag)

    def bcast(self, obj):
        return obj

    def allgather(self, obj):
        """[obj of rank 0, obj of rank 1, ...] on every rank (small Python objects, error paths)."""
        return [obj]

    def gather_rows(self, tags, values):
        """Rows of every rank on rank 0 (other ranks: empty), in rank order."""
        return np.asarray(tags).copy(), np.asarray(values).copy()

    def allgather_rows(self, tags, values):
        """Rows of every rank on every rank, in rank order."""
        return np.asarray(tags).copy(), np.asarray(values).copy()

    def barrier(self):
        pass

    # ----- decomposition (serial: one sub-box, the whole box) --------------------------------------
    def set_processors(self, grid):
        """`processors Px Py Pz` (0 for '*'): checked against the number of ranks."""
        if all(p > 0 for p in grid) and int(np.prod(grid)) != self.nprocs:
            raise DemError(f"processors {' '.join(map(str, grid))} needs {int(np.prod(grid))} ranks, "
                           f"the job has {self.nprocs}")
        if any(p > 0 and self.nprocs % p for p in grid):
            raise DemError(f"processors {' '.join(str(p) if p else '*' for p in grid)}: {self.nprocs} "
                           f"ranks cannot be arranged so")

    def owned_mask(self, x):
        """Which of the (globally identical) positions x this rank owns: commands making particles build
        them identically on every rank and keep these."""
        return np.ones(len(x), dtype=bool)

    def settle_grid(self):
        """At the first run: revise a decomposition chosen by default (one rank: nothing to do)."""

    def balance(self, dims="xyz", weight="count", thresh=1.0):
        """Shift sub-box boundaries to even out the load; returns the imbalance before."""
        return 1.0

    def imbalance(self, weight="count"):
        return 1.0

    def report(self, nsteps=0):
        """Lines for the end-of-run summary (communication statistics)."""
        return []

    # ----- particles ------------------------------------------------------------------------------
    def exchange(self):
        """Move particles to the rank owning their sub-box (serial: nothing to move)."""

    def borders(self):
        """Make ghost images of the particles within `cutghost` of a periodic boundary."""
        atom, domain = self.sim.atom, self.sim.domain
        atom.nghost = 0
        nlocal = atom.nlocal
        cut = self.cutghost
        owner = [np.arange(nlocal)]
        shift = [np.zeros((nlocal, 3))]
        for d in range(3):
            if not domain.periodic[d]:
                continue
            length = domain.prd[d]
            if length < 2.0 * cut:
                raise DemError(f"periodic box length {length:g} along {'xyz'[d]} is less than twice the "
                               f"ghost cutoff {cut:g} (largest particle diameter + skin)")
            own = np.concatenate(owner)
            sh = np.concatenate(shift)
            pos = atom.data["x"][own, d] + sh[:, d]
            lo = np.flatnonzero(pos < domain.lo[d] + cut)
            hi = np.flatnonzero(pos >= domain.hi[d] - cut)
            for sel, sign in ((lo, 1.0), (hi, -1.0)):
                s = sh[sel].copy()
                s[:, d] += sign * length
                owner.append(own[sel])
                shift.append(s)
        self.ghost_owner = np.ascontiguousarray(np.concatenate(owner[1:]) if len(owner) > 1 else np.zeros(0), dtype=np.int64)
        self.ghost_shift = np.ascontiguousarray(np.concatenate(shift[1:]) if len(shift) > 1 else np.zeros((0, 3)))
        n = len(self.ghost_owner)
        atom.grow(nlocal + n)
        g = slice(nlocal, nlocal + n)
        for name in atom.border_fields():
            atom.data[name][g] = atom.data[name][self.ghost_owner]
        atom.data["x"][g] += self.ghost_shift
        atom.nghost = n

    def forward(self):
        """Refresh ghost copies of x, v, omega and quat from their owners."""
        atom = self.sim.atom
        if atom.nghost == 0:
            return
        d = atom.data
        _serial.forward(d["x"], d["v"], d["omega"], d["quat"], self.ghost_owner, self.ghost_shift, atom.nlocal)

    def reverse(self, fields=None):
        """Add the forces and torques accumulated on ghosts to their owners, in ghost order (or the float
        per-particle `fields` named, e.g. the contact tallies of dem/tally.py)."""
        atom = self.sim.atom
        if atom.nghost == 0:
            return
        if fields is None:
            _serial.reverse(atom.data["f"], atom.data["torque"], self.ghost_owner, atom.nlocal)
            return
        for name in fields:
            arr = atom.data[name]
            _serial.reverse_rows(arr.reshape(arr.shape[0], -1), self.ghost_owner, atom.nlocal)

    # ----- restarts (serial: the file holds this process's particles as they are) -------------------
    def gather_restart(self, state):
        """The restart state to write on rank 0, completed with every rank's particles."""
        return state

    def scatter_restart(self, state):
        """(fields, reference positions of the last neighbor build) of this rank's share of a restart."""
        return state["fields"], state["neighbor"]["xhold"]

    # ----- errors -------------------------------------------------------------------------------------
    def fatal(self, sim, text, status=1):
        """Report a DemError or an interrupt (log, then stderr) and return the exit status."""
        if sim is not None:
            sim.print(text, screen=False)
        print(text, file=sys.stderr, flush=True)
        return status
