"""Groups of particles as bits of the per-particle `mask` (bit 0 is `all`)."""
import numpy as np

from .errors import DemError

MAX_GROUPS = 32


class Groups:
    def __init__(self, sim):
        self.sim = sim
        self.names = ["all"]

    def bit(self, name):
        if name not in self.names:
            from .errors import did_you_mean
            raise DemError(f"unknown group '{name}'{did_you_mean(name, self.names)}")
        return np.int32(1 << self.names.index(name))

    def find_or_create(self, name):
        if name not in self.names:
            if len(self.names) == MAX_GROUPS:
                raise DemError(f"too many groups (at most {MAX_GROUPS})")
            self.names.append(name)
        return self.bit(name)

    def members(self, name, nlocal=None):
        """Boolean mask of owned particles in group `name`."""
        atom = self.sim.atom
        n = atom.nlocal if nlocal is None else nlocal
        return (atom.data["mask"][:n] & self.bit(name)) != 0

    def count(self, name):
        return int(self.sim.comm.sum(int(self.members(name).sum())))
