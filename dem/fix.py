"""Base class of fixes. A fix declares the stages it acts in (rule 4) with `stages`; `modify` calls it
once per stage per step, in input-script order. Kernels do the per-particle work (rule 5)."""
import enum

from .errors import DemError


class Stage(enum.IntFlag):
    PRE_EXCHANGE = 1
    PRE_NEIGHBOR = 2
    POST_NEIGHBOR = 4
    PRE_FORCE = 8
    POST_FORCE = 16
    INTEGRATE = 32
    POST_INTEGRATE = 64
    END_OF_STEP = 128


STAGE_METHODS = {s: s.name.lower() for s in Stage}


class Fix:
    """fix ID group-ID style args ...

    Subclasses set `style`, `stages`, and implement the stage methods named after the stages
    (`post_force(self)`, `integrate(self)`...). `init()` runs before every run, `setup()` after the first
    neighbor build of a run. Global state to restart goes through `state()`/`restore(state)`; per-particle
    state goes in fields declared with `sim.atom.add_field` (named after the fix ID)."""

    kind = "fix"
    style = None
    stages = Stage(0)
    time_integrate = False
    tallies = ()          # per-particle contact tallies read (dem/tally.py: "stress", "types", "count")
    acceleration = None   # a uniform body acceleration (gravity) it applies: the MPI grid leaves its axis whole

    def __init__(self, sim, fid, group, args):
        self.sim = sim
        self.id = fid
        self.group = group
        self.groupbit = sim.groups.bit(group)
        self.args = list(args)

    def init(self):
        pass

    def setup(self):
        pass

    def setup_output(self):
        """At the start of a run, with its output: after the first force evaluation (a fix writing values
        of the state writes them here, as thermo does)."""
        pass

    def max_radius(self):
        """Bounding radius of particles this fix will create (ghost cutoff covers them from the start)."""
        return 0.0

    def thermo(self):
        """Extra thermo keywords: {name: value}."""
        return {}

    # name of a thermo value: (quantity, unit), for plot labels (dem/quantities.py)
    thermo_quantities = {}

    def state(self):
        return {}

    def restore(self, state):
        pass

    def unfix(self):
        pass

    def particles_removed(self):
        pass

    def surface_mesh(self):
        """(vertices (nv, 3), triangles (nt, 3)) of the wall this fix is, where it is now, for the VTK dumps;
        None for a fix without one."""
        return None

    def no_args(self):
        """For a style without arguments: any word after the style is an error, never ignored."""
        if self.args:
            raise DemError(f"fix {self.id} {self.style}: takes no arguments, got '{' '.join(self.args)}'")

    def need(self, n, usage):
        if len(self.args) < n:
            raise DemError(f"fix {self.style}: too few arguments; usage: fix ID group {self.style} {usage}")
