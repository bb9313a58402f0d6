"""Commands that set up the box: units, dimension, boundary, region, create_box."""
import numpy as np

from ..command import Command
from ..errors import DemError, unknown

# coefficient tables are ntypes x ntypes rows: beyond this they no longer fit in memory comfortably
MAX_TYPES = 1000


class Units(Command):
    """units si

    dem works in SI units (m, kg, s). `units si` is the default; other LAMMPS unit systems are refused
    rather than silently misread."""
    style = "units"
    usage = "si"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        if a[0] != "si":
            raise a.error(f"unit style '{a[0]}' is not supported; dem uses SI units (units si)")
        self.sim.units = "si"


class Dimension(Command):
    """dimension 3

    dem is three-dimensional (a 2D problem is a thin periodic slab)."""
    style = "dimension"
    usage = "3"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        if a[0] != "3":
            raise a.error("only 'dimension 3' is supported (model 2D as a thin periodic slab)")


class Boundary(Command):
    """boundary x y z

    Per axis: p (periodic), f (fixed: a particle leaving is lost), s (open, shrink-wrapped to the
    particles), m (open, shrink-wrapped but never smaller than the initial box); two letters give the
    lower and upper face separately, e.g. `boundary p p fm`. Default: p p p. Must come before the box."""
    style = "boundary"
    usage = "x y z (each p, f, s, m or a pair like fm)"

    def __call__(self, words):
        if self.sim.domain.box_exist:
            raise DemError("boundary must be set before the box is created")
        self.sim.domain.set_boundary(words)


class RegionCommand(Command):
    """region ID style args [side in|out]

    Styles: block, cylinder, sphere (see each region's documentation).
    Example: `region box block 0 0.02 0 0.02 0 0.04`."""
    style = "region"
    usage = "ID style args"

    def __call__(self, words):
        a = self.args(words)
        a.need(2)
        rid, style = a[0], a[1]
        if rid in self.sim.domain.regions:
            raise a.error(f"region ID '{rid}' already exists")
        cls = self.sim.registry.get("region", style, a.words[2:])
        self.sim.domain.regions[rid] = cls(self.sim, rid, a.words[2:])


def find_region(sim, rid):
    if rid not in sim.domain.regions:
        raise unknown("region ID", rid, sim.domain.regions)
    return sim.domain.regions[rid]


class CreateBox(Command):
    """create_box NTYPES REGION-ID

    Creates the simulation box as the bounding box of a block region, with NTYPES particle types.
    Example: `create_box 1 box`."""
    style = "create_box"
    usage = "ntypes region-ID"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(2)
        if self.sim.domain.box_exist:
            raise a.error("the box already exists")
        ntypes = a.int(0, "ntypes", positive=True)
        if ntypes > MAX_TYPES:
            raise a.error(f"{ntypes} particle types is more than dem supports ({MAX_TYPES}): coefficient "
                          f"tables hold one row per pair of types")
        region = find_region(self.sim, a[1])
        lo, hi = region.bbox()
        if np.any(np.abs(lo) >= 1e29) or np.any(np.abs(hi) >= 1e29):
            raise a.error("the region of the box must be bounded (no INF)")
        self.sim.domain.set_box(lo, hi)
        self.sim.atom.ntypes = ntypes
