"""fix python/every: a Python function called every N steps during runs, for coupling and control from a
Python driver (docs/python.md). The function is registered with the Simulation (`sim.every(N, func)`, or
`sim.callback(NAME, func)` and `fix ID all python/every N NAME` in a script)."""
from .errors import DemError, did_you_mean
from .fix import Fix


class FixPythonEvery(Fix):
    """fix ID group python/every N NAME

    Calls the Python function registered as NAME (`sim.callback(NAME, func)`, or `sim.every(N, func)`,
    which registers it and defines this fix) as `func(sim)` every N steps of a run, after the step is
    complete and before that step's thermo line and dumps: `sim.update.ntimestep` is the step just done and
    the function sees the state the outputs of that step show. It may read anything (particle arrays,
    thermo values with `sim.thermo_keyword`, `sim.gather`), and change settings and values for the next
    steps (variables, fix parameters, velocities of the owned particles); it may not start a run. Under MPI
    it runs on every rank (each has its own particles), so collective calls (`gather`, thermo values) are
    made by all ranks alike. A whole Python call every N steps: for coupling and control, not for
    per-particle work inside a step (write a fix with a kernel for that). The group is not used."""

    style = "python/every"

    def __init__(self, sim, fid, group, args):
        super().__init__(sim, fid, group, args)
        if len(self.args) != 2:
            raise DemError(f"fix {fid} python/every: expected N NAME, got '{' '.join(self.args)}'; usage: "
                           f"fix ID group python/every N NAME")
        try:
            self.every = int(self.args[0])
        except ValueError:
            self.every = 0
        if self.every < 1:
            raise DemError(f"fix {fid} python/every: N must be an integer >= 1, got '{self.args[0]}'")
        name = self.args[1]
        callbacks = sim.callbacks
        if name not in callbacks:
            raise DemError(f"fix {fid} python/every: no Python function registered as '{name}'"
                           f"{did_you_mean(name, list(callbacks))}",
                           hint="register it from Python first: sim.callback(NAME, func), or use "
                                "sim.every(N, func)")
        self.func = callbacks[name]
        self.name = name

    def after_step(self, step):
        if step % self.every:
            return
        update = self.sim.update
        was = update.in_run
        update.in_run = True        # a run started from the callback is refused (run ... every's rule)
        try:
            self.func(self.sim)
        finally:
            update.in_run = was


PYTHON_FIXES = [FixPythonEvery]
