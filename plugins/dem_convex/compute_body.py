"""compute body: state of a group as one rigid body (one particle: that particle)."""
import numpy as np

from dem.compute import Compute


class ComputeBody(Compute):
    """compute ID group body

    Vector of 9 values of the group: centre of mass `x y z` (1-3), mass-weighted mean velocity
    `vx vy vz` (4-6) and mean angular velocity (space frame) `wx wy wz` (7-9); for a group of one
    particle, the state of that particle (impact tests: `c_ID[3]` is its height, `c_ID[7]` its spin
    about x). Velocities are the stored half-step values (exact in free flight). No scalar."""

    style = "body"
    has_scalar = False
    size_vector = 9
    vector_names = ("x", "y", "z", "vx", "vy", "vz", "wx", "wy", "wz")

    def __init__(self, sim, cid, group, args):
        super().__init__(sim, cid, group, args)
        if args:
            raise self.parser().error("takes no arguments")

    def compute_vector(self):
        comm = self.sim.comm
        atom = self.sim.atom
        n = atom.nlocal
        sel = self.group_mask()
        m = atom.data["rmass"][:n][sel]
        sums = np.concatenate([(m[:, None] * atom.data["x"][:n][sel]).sum(0),
                               (m[:, None] * atom.data["v"][:n][sel]).sum(0),
                               atom.data["omega"][:n][sel].sum(0), [m.sum(), len(m)]])
        tot = np.array([comm.sum(float(s)) for s in sums])
        if tot[10] == 0:
            return np.zeros(9)
        return np.concatenate([tot[0:6] / tot[9], tot[6:9] / tot[10]])
