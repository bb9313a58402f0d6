"""Commands that run the simulation and set how it steps: timestep, neighbor, neigh_modify, run,
reset_timestep."""
from ..command import Command
from ..errors import did_you_mean


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
        a.done(2)
        if len(a) > 1 and a[1] not in ("bin", "multi"):
            raise a.error(f"neighbor style '{a[1]}' is not supported (use bin)")
        self.sim.neighbor.settings(a.float(0, "skin", nonneg=True))


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
    """run N [upto] [start S] [stop S] [pre yes|no] [post yes|no] [every M "command" ...]

    Runs N time steps (`run 0`: set up, evaluate and output the state without stepping).
    `upto`: N is the last step, not a count (run from the current step up to step N; a script restarted
    from its last restart file then finishes the same run). `start S` / `stop S`: the first and last step
    of a run made of several run commands, recorded as `update.beginstep` / `update.endstep` (S <= the
    current step, S >= the last step of this run); no dem style reads them yet (LAMMPS uses them to
    ramp fix and variable values over the whole sequence). `pre no`: when the run continues the
    previous one, the thermo header and the repeated thermo line of the setup are left out (the setup
    itself is always done: it is cheap and keeps trajectories bitwise identical). `post no`: only the
    loop time line of the end-of-run summary is printed. `every M c1 c2 ...`: the run is split into
    chunks of M steps (the last may be shorter) and the quoted commands are executed after each chunk,
    substituted anew each time (`NULL`: no command); with `pre no` / `post no` the chunks after the
    first / before the last skip that output. Example: `run 10000 every 1000 "print 'step $(step)'"`.

    SIGINT (Ctrl-C) or SIGTERM during a run stops it at the end of the current step, on every MPI rank
    alike: the step's output is written, every dump and restart file is left complete (no half-written
    HDF5 frame, no temporary file), the log and stderr say at which step it stopped and which frames and
    restart were written, and `dem` exits with status 130 (SIGINT) or 143 (SIGTERM). A signal outside a
    run (while the script is read) ends `dem` at once with the same status; one during `write_restart`
    waits for the file. Called from Python, `sim.run` raises `dem.interrupt.Interrupted` (a
    KeyboardInterrupt) after such a stop. A second signal before the first was acted on (a step that
    does not end) stops `dem` at once (Python 3.10 and later), with the same status: the files written before are whole, the
    step in progress is lost."""
    style = "run"
    usage = "N [upto] [start S] [stop S] [pre yes|no] [post yes|no] [every M c1 c2 ...]"

    def __call__(self, words):
        a = self.args(words)
        a.need(1)
        sim = self.sim
        update = sim.update
        if update.running or update.in_run:
            raise a.error("a run cannot be started from inside a run (e.g. from its 'every' commands)")
        n = a.int(0, "N", nonneg=True)
        upto, start, stop, pre, post, every, commands = False, None, None, True, True, 0, []
        i = 1
        while i < len(a):
            key = a[i]
            if key == "upto":
                upto, i = True, i + 1
            elif key in ("start", "stop"):
                value = a.int(i + 1, key, nonneg=True)
                start, stop = (value, stop) if key == "start" else (start, value)
                i += 2
            elif key in ("pre", "post"):
                flag = a.yes_no(a[i + 1], key)
                pre, post = (flag, post) if key == "pre" else (pre, flag)
                i += 2
            elif key == "every":
                every = a.int(i + 1, "every M", positive=True)
                commands = [w for w in a.words[i + 2:] if w != "NULL"]
                if len(a) == i + 2:
                    raise a.error("every M needs at least one command (NULL for none)")
                break       # every takes the rest of the line
            else:
                raise a.error(f"unknown keyword '{key}'"
                              f"{did_you_mean(key, ['upto', 'start', 'stop', 'pre', 'post', 'every'])}")
        nsteps = n - update.ntimestep if upto else n
        if nsteps < 0:
            raise a.error(f"run {n} upto: the current step {update.ntimestep} is already past step {n}")
        last = update.ntimestep + nsteps
        if start is not None and start > update.ntimestep:
            raise a.error(f"start {start} must be <= the current step {update.ntimestep}")
        if stop is not None and stop < last:
            raise a.error(f"stop {stop} must be >= the last step of this run ({last})")
        update.beginstep = update.ntimestep if start is None else start
        update.endstep = last if stop is None else stop
        sim.job.start_run(sim.input.script_line, nsteps)
        if not every:
            update.run(nsteps, pre=pre, post=post)
            return
        self.chunks(nsteps, every, commands, pre, post)

    def chunks(self, nsteps, every, commands, pre, post):
        """LAMMPS `run N every M`: chunks of M steps, the commands after each one."""
        sim, update = self.sim, self.sim.update
        left, first = nsteps, True
        update.in_run = True
        try:
            while left > 0 or first:
                size = min(every, left)
                update.run(size, pre=pre or first, post=post or left <= size)
                for command in commands:
                    sim.input.one(command)
                left -= size
                first = False
        finally:
            update.in_run = False


class ResetTimestep(Command):
    """reset_timestep N

    Sets the step count to N. The simulated time goes on from its value at this point."""
    style = "reset_timestep"
    usage = "N"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        self.sim.update.reset_step(a.int(0, "N", nonneg=True))
        self.sim.neighbor.invalidate()
