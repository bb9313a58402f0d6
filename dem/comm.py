"""Communication: ghost images of particles and global reductions.

`make_comm` picks the implementation: this serial `Comm`, or `dem.comm_mpi.CommMPI` (spatial domain
decomposition over MPI, see docs/parallel.md) when the process was launched by mpiexec with more than
one rank. Serial runs never import mpi4py.

Serial runs keep the same structure an MPI run needs: `borders()` makes ghost images near periodic
boundaries (each ghost remembers its owner and the shift of its image), `forward()` refreshes ghost
positions, velocities, spins and orientations from their owners every step, and `reverse()` adds the
forces accumulated on ghosts back to their owners (half neighbor lists, Newton's third law).
"""
import os

import numpy as np

from . import _comm
from .errors import DemError


# environment variables by which MPI launchers announce the world size (MPICH/Hydra, Open MPI, PMIx)
WORLD_SIZE_VARIABLES = ("PMI_SIZE", "OMPI_COMM_WORLD_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS")


def launched_world_size():
    """World size announced by an MPI launcher, without initialising MPI (1 when not launched)."""
    for name in WORLD_SIZE_VARIABLES:
        try:
            n = int(os.environ.get(name, "1"))
        except ValueError:
            continue
        if n > 1:
            return n
    return 1


def make_comm(sim):
    """Serial `Comm`, or `CommMPI` under mpiexec with more than one rank."""
    if launched_world_size() > 1:
        try:
            from .comm_mpi import CommMPI
        except ImportError as e:
            raise DemError(f"launched on several MPI ranks but mpi4py cannot be imported ({e})",
                           hint="pip install 'dem[mpi]' (mpi4py and the mpich wheel)") from None
        comm = CommMPI(sim)
        if comm.nprocs > 1:
            return comm
    return Comm(sim)


class Comm:
    me = 0
    nprocs = 1
    procgrid = (1, 1, 1)

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

    def balance(self, dims="xyz", weight="count", thresh=1.0):
        """Shift sub-box boundaries to even out the load; returns (imbalance before, after)."""
        return 1.0, 1.0

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
        _comm.forward(d["x"], d["v"], d["omega"], d["quat"], self.ghost_owner, self.ghost_shift, atom.nlocal)

    def reverse(self):
        """Add the forces and torques accumulated on ghosts to their owners, in ghost order."""
        atom = self.sim.atom
        if atom.nghost == 0:
            return
        _comm.reverse(atom.data["f"], atom.data["torque"], self.ghost_owner, atom.nlocal)
