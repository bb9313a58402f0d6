"""Communication: ghost images of particles and global reductions.

Serial runs keep the same structure an MPI run needs: `borders()` makes ghost images near periodic
boundaries (each ghost remembers its owner and the shift of its image), `forward()` refreshes ghost
positions, velocities, spins and orientations from their owners every step, and `reverse()` adds the
forces accumulated on ghosts back to their owners (half neighbor lists, Newton's third law).
"""
import numpy as np

from . import _comm
from .errors import DemError


class Comm:
    me = 0
    nprocs = 1

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

    def gather_rows(self, tags, values):
        return np.asarray(tags).copy(), np.asarray(values).copy()

    def barrier(self):
        pass

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
