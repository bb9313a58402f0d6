"""A third-party plugin: `fix ID group nudge FX FY FZ` adds a constant force to each particle."""
import numpy as np

from dem.fix import Fix, Stage
from dem.hookspecs import hookimpl


class FixNudge(Fix):
    """fix ID group nudge FX FY FZ: a constant force (N) on every particle of the group."""

    style = "nudge"
    stages = Stage.POST_FORCE

    def __init__(self, sim, fid, group, args):
        super().__init__(sim, fid, group, args)
        self.need(3, "FX FY FZ")
        self.force = np.array([float(a) for a in args[:3]])

    def post_force(self):
        atom = self.sim.atom
        sel = (atom.data["mask"][:atom.nlocal] & self.groupbit) != 0
        atom.data["f"][:atom.nlocal][sel] += self.force


@hookimpl
def dem_styles():
    return [FixNudge]
