"""Commands that run the simulation and set how it steps: timestep, neighbor, neigh_modify, run,
reset_timestep."""
from ..command import Command


class Timestep(Command):
    """timestep DT

    The time step in seconds. A warning is printed when it exceeds T_c/10 of the stiffest, lightest
    contact."""
    style = "timestep"
    usage = "dt"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        self.sim.update.dt = a.float(0, "dt", positive=True)


class NeighborCommand(Command):
    """neighbor SKIN bin

    Skin distance added to the sum of bounding radii when listing pairs (default 0.1 x the largest
    diameter). Example: `neighbor 0.0001 bin`."""
    style = "neighbor"
    usage = "skin bin"

    def __call__(self, words):
        a = self.args(words)
        a.need(1)
        self.sim.neighbor.settings(a.float(0, "skin", nonneg=True))
        if len(a) > 1 and a[1] not in ("bin", "multi"):
            raise a.error(f"neighbor style '{a[1]}' is not supported (use bin)")


class NeighModify(Command):
    """neigh_modify [every N] [delay N] [check yes|no]

    Rebuild the list at most every N steps, not before `delay` steps since the last build, and (check
    yes, the default) only when a particle moved more than half the skin. Defaults: every 1 delay 0
    check yes."""
    style = "neigh_modify"
    usage = "[every N] [delay N] [check yes|no]"

    def __call__(self, words):
        a = self.args(words)
        kw = a.keywords(0, {"every": 1, "delay": 1, "check": 1, "once": 1, "page": 1, "one": 1})
        nb = self.sim.neighbor
        if "every" in kw:
            nb.every = max(1, a.to_int(kw["every"][0], "every"))
        if "delay" in kw:
            nb.delay = max(0, a.to_int(kw["delay"][0], "delay"))
        if "check" in kw:
            nb.check = a.yes_no(kw["check"][0], "check")


class Run(Command):
    """run N

    Runs N time steps.

    SIGINT (Ctrl-C) or SIGTERM during a run stops it at the end of the current step, on every MPI rank
    alike: the step's output is written, every dump and restart file is left complete (no half-written
    HDF5 frame, no temporary file), the log and stderr say at which step it stopped and which frames and
    restart were written, and `dem` exits with status 130 (SIGINT) or 143 (SIGTERM). A signal outside a
    run (while the script is read) ends `dem` at once with the same status; one during `write_restart`
    waits for the file. Called from Python, `sim.run` raises `dem.interrupt.Interrupted` (a
    KeyboardInterrupt) after such a stop."""
    style = "run"
    usage = "N"

    def __call__(self, words):
        a = self.args(words)
        a.need(1)
        self.sim.update.run(a.int(0, "N", nonneg=True))


class ResetTimestep(Command):
    """reset_timestep N"""
    style = "reset_timestep"
    usage = "N"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        self.sim.update.ntimestep = a.int(0, "N", nonneg=True)
        self.sim.neighbor.invalidate()
