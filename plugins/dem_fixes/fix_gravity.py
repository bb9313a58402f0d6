"""fix gravity"""
import numpy as np

from dem.args import Args
from dem.fix import Fix, Stage

from . import _fix_gravity


class FixGravity(Fix):
    """fix ID group gravity MAGNITUDE vector X Y Z

    Adds m g to each particle of the group, g of the given magnitude (m/s^2) along the direction
    (X, Y, Z) (normalised). `fix ID group gravity G` alone points down z.
    Example: `fix g all gravity 9.81 vector 0 0 -1`."""

    style = "gravity"
    stages = Stage.POST_FORCE

    def __init__(self, sim, fid, group, args):
        super().__init__(sim, fid, group, args)
        a = Args(args, "fix ID group gravity MAGNITUDE [vector X Y Z]", f"fix {fid} gravity")
        a.need(1)
        self.magnitude = a.float(0, "magnitude")
        direction = np.array([0.0, 0.0, -1.0])
        if len(a) > 1:
            if a[1] != "vector":
                raise a.error(f"expected 'vector X Y Z', got '{a[1]}'")
            a.exactly(5)
            direction = np.array(a.floats(2, 3, "direction"))
            if not np.linalg.norm(direction) > 0:
                raise a.error("the direction must not be zero")
        self.g = self.magnitude * direction / np.linalg.norm(direction)
        self.acceleration = self.g

    def post_force(self):
        atom = self.sim.atom
        a = atom.data
        _fix_gravity.gravity(a["f"], a["rmass"], a["mask"], int(self.groupbit), atom.nlocal, *self.g)
