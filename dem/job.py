"""The job: every run of the script given to `dem -in` (or sim.file / sim.commands), for the thermo
keywords jpct and jeta. pct and eta are of one run; a script of several runs (fill, settle, rotate) would
otherwise show the first run's ETA as the job's.

Its length is worked out again at the start of each run, from the script's text read before it began
(dem/job_scan.py): this run's steps, and each later run's length evaluated now, with the variables as they
stand, when that needs no value of the simulation's state (step, c_ID...) and no variable that a command
between here and there sets. Where a later run's length is not known yet, jpct and jeta are NaN (a number
still, for readers of the columns), and the thermo header says why.
"""
from .args import integer
from .errors import DemError
from .job_scan import STEP, scan

NAN = float("nan")
FROM_PYTHON = "a run started from Python (sim.run, sim.command), not by a script"


class Job:
    def __init__(self, sim):
        self.sim = sim
        self.plan = None
        self.reason = FROM_PYTHON
        self.done = 0            # steps of the job's runs that have ended (run ... every: its chunks)
        self.seconds = 0.0       # their loop time
        self.next_run = 0        # index in the plan's runs of the next run command
        self.total = None        # the job's steps, where known

    # ----- the script -----------------------------------------------------------------------------
    def begin(self, name, lines):
        self.plan = scan(name, lines)
        self.reason = self.plan.reason
        self.done, self.seconds, self.next_run, self.total = 0, 0.0, 0, None

    def end(self):
        self.plan, self.total = None, None
        self.reason = FROM_PYTHON

    # ----- its runs -------------------------------------------------------------------------------
    def start_run(self, lineno, nsteps):
        """A `run` command at line `lineno` of the script (None: not read from the script itself) is about
        to make `nsteps` steps: the job's length from here."""
        self.total = None
        if self.plan is None or self.plan.reason:
            return
        runs = self.plan.runs()
        if self.next_run >= len(runs) or runs[self.next_run].lineno != lineno:
            self.plan.reason = self.reason = f"a run the scan did not foresee (line {lineno})"
            return
        entry = runs[self.next_run]
        self.next_run += 1
        later, why = self._later(entry, self.sim.update.ntimestep + nsteps)
        self.reason = why
        if not why:
            self.total = self.done + nsteps + later

    def _later(self, current, step):
        """(steps of the runs after `current`, "") or (0, why not known)."""
        entries = self.plan.entries
        changed, steps = set(current.defines), 0
        if STEP in changed:                          # a reset_timestep among its `every` commands
            step = None
        for entry in entries[entries.index(current) + 1:]:
            if entry.kind == "run":
                n, why = self._length(entry, changed, step)
                if why:
                    return 0, why
                steps += n
                step = step + n if step is not None else None
            elif entry.kind == "reset":
                value, why = self._value(entry, changed)
                step = None if why else value
            if entry.kind == "restart" or STEP in entry.defines:
                step = None
            changed |= entry.defines
        return steps, ""

    def _length(self, entry, changed, step):
        words, why = self._words(entry, changed)
        if why:
            return 0, why
        upto = "upto" in words[2:words.index("every") if "every" in words else None]
        n = _count(words)
        if n is None:
            return 0, f"line {entry.lineno} '{entry.text}' has no plain number of steps"
        if not upto:
            return n, ""
        if step is None or n < step:
            return 0, f"line {entry.lineno} '{entry.text}' runs up to a step, from a step not known now"
        return n - step, ""

    def _value(self, entry, changed):
        words, why = self._words(entry, changed)
        n = None if why else _count(words)
        return (n, "") if n is not None else (0, why or "not a number")

    def _words(self, entry, changed):
        """The command's words substituted now, or why they may differ when it is read."""
        from .input import split_words
        inp = self.sim.input
        try:
            with inp.variables.static() as used:
                words = split_words(inp.substitute(entry.text))
        except DemError:
            return [], f"line {entry.lineno} '{entry.text}' has a length not known before the run"
        if used & changed or (used and "*" in changed):
            return [], (f"line {entry.lineno} '{entry.text}' reads variables that change before it "
                        f"({', '.join(sorted(used & changed)) or 'named by a variable'})")
        return words, ""

    def finished(self, steps, seconds):
        """A run (or a chunk of `run ... every`) ended after `steps` steps in `seconds` of loop time."""
        self.done += steps
        self.seconds += seconds

    # ----- the thermo keywords --------------------------------------------------------------------
    def progress(self):
        """(percent of the job's steps done, seconds left), NaN where the job's length is not known. The
        seconds left are the job's steps left at this run's speed (runs differ: a fill, a long rotation),
        or at the job's average speed before this run has one."""
        if self.total is None:
            return NAN, NAN
        up = self.sim.update
        done = self.done + (up.ntimestep - up.first_step if up.running else 0)
        left = max(self.total - done, 0)
        percent = 100.0 * done / self.total if self.total else 100.0
        rate = up.progress()[1] or (self.done / self.seconds if self.seconds > 0 else 0.0)
        if left == 0:
            return percent, 0.0
        return percent, left / rate if rate > 0 else NAN

    def note(self, style):
        """The thermo header's line on pct/eta and jpct/jeta, or None when the style has none of them."""
        words = set(style)
        if not words & {"pct", "eta", "jpct", "jeta"}:
            return None
        up = self.sim.update
        text = f"pct and eta: of this run, steps {up.first_step} to {up.last_step}"
        shown = bool(words & {"jpct", "jeta"})
        if self.total is not None:
            runs = len(self.plan.runs())
            job = f"run {self.next_run} of {runs}, {self.total} steps in all"
            text += (f"; jpct and jeta: of the job ({job}), jeta at this run's speed" if shown else
                     f"; the job: {job} (thermo keywords jpct and jeta)")
        else:
            text += ("; jpct and jeta: nan, the job's length is not known" if shown else
                     "; the script's later runs are not counted") + f" ({self.reason})"
        return f"({text})"


def _count(words):
    """The number of steps of `run N ...` or `reset_timestep N`, or None (the command itself will say)."""
    try:
        n = integer(words[1])
    except (IndexError, ValueError):
        return None
    return n if n >= 0 else None

