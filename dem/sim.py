"""The root object (rule 1): one Sim owns comm, atom, domain, neighbor, pair, modify, update, output,
input, registry, the shape table and the computes; every style receives the sim and reaches what it
needs from it."""
import math
import sys

import numpy as np

from .atom import Atom
from .comm import make_comm
from .domain import Domain
from .errors import DemError
from .files import open_output
from .group import Groups
from .input import Input
from .job import Job
from .modify import Modify
from .neighbor import Neighbor
from .output import Output
from .registry import default_registry
from .shapes.command import SimShapes
from .tally import Tally
from .update import Update


class Sim:
    """A simulation driven by LAMMPS-style commands::

        sim = dem.Simulation()
        sim.command("units si")
        sim.file("in.pour")
        sim.run(1000)
        x = sim.gather("x")        # global array ordered by particle id
    """

    def __init__(self, screen=True, log=None, variables=(), registry=None, comm=None):
        self.registry = registry or default_registry()
        self.comm = comm or make_comm(self)
        self.screen = screen and self.comm.me == 0
        self.logfile = None
        if log:       # rank 0 opens it and tells the others: one error on every rank, never one rank waiting
            failure = None
            if self.comm.me == 0:
                try:
                    self.logfile = open_log(log)
                except DemError as e:
                    failure = e
            failure = self.comm.bcast(failure)
            if failure is not None:
                raise failure
        self._screen_lines = Lines(lambda text: print(text, flush=True))
        self._log_lines = Lines(self._log_write)
        self.atom = Atom()
        self.domain = Domain(self)
        self.groups = Groups(self)
        self.neighbor = Neighbor(self)
        self.pair = None
        self.modify = Modify(self)
        self.shapes = SimShapes()      # the shape table, empty until a `shape` command adds a row
        self.computes = {}             # compute ID -> compute, in definition order
        self.tally = Tally(self)       # per-particle contact tallies that analysis styles ask for
        self.callbacks = {}            # name -> Python function, for fix python/every
        self.update = Update(self)
        self.output = Output(self)
        if log:
            self.output.names.claim("log", [log], "the log file")
        self.job = Job(self)           # the script's runs, for jpct and jeta
        self.input = Input(self)
        self.units = "si"
        self.dimension = 3
        if variables:
            self.input.set_cli_vars(list(variables))

    # ----- driving ---------------------------------------------------------------------------------
    def command(self, line):
        self.input.one(line)
        return self

    def commands(self, text):
        self.input.lines(text)
        return self

    def file(self, path):
        self.input.file(path)
        return self

    def run(self, nsteps):
        if self.update.running:
            raise DemError("run: a run cannot be started from inside a run (e.g. from a python/every callback)")
        n = float(nsteps)
        if not (math.isfinite(n) and n == int(n)):
            raise DemError(f"run: the number of steps must be a whole number, got {nsteps!r}")
        self.update.run(int(n))
        return self

    def callback(self, name, func):
        """Register `func(sim)` as NAME for `fix ID group python/every N NAME`."""
        if not callable(func):
            raise DemError(f"callback {name}: {func!r} is not callable")
        self.callbacks[name] = func
        return self

    def every(self, n, func, fix_id=None):
        """Call `func(sim)` every n steps of the runs (fix python/every, ID `fix_id`, default
        `py_` + the function's name); returns the fix ID (`unfix ID` stops it)."""
        name = getattr(func, "__name__", "callback")
        if not name.isidentifier():
            name = "callback"
        fix_id = fix_id or f"py_{name}"
        self.callback(fix_id, func)
        self.command(f"fix {fix_id} all python/every {int(n)} {fix_id}")
        return fix_id

    # ----- output ----------------------------------------------------------------------------------
    def print(self, text, screen=True):
        """A line to the screen and the log (each counts a line repeated right after itself: Lines)."""
        if self.comm.me != 0:
            return
        if screen and self.screen:
            self._screen_lines.line(text)
        if self.logfile:
            self._log_lines.line(text)

    def warning(self, text):
        self.print(f"WARNING: {text}")

    def thermo_keyword(self, name):
        return self.output.thermo.keyword(name)

    def thermo_history(self):
        """Every thermo line printed so far, as {keyword: numpy array} (one entry per line; NaN where a
        line's thermo_style lacked the keyword)."""
        return self.output.thermo.columns()

    def thermo_dataframe(self):
        """thermo_history as a pandas DataFrame (pandas is not a dependency of dem: install it)."""
        try:
            import pandas
        except ImportError:
            raise DemError("thermo_dataframe needs pandas (pip install pandas); thermo_history gives "
                           "the same columns as numpy arrays") from None
        return pandas.DataFrame(self.thermo_history())

    def gather(self, name):
        """The global per-particle array `name`, ordered by particle id (tag)."""
        local = self.atom.local(name)
        tags = self.atom.local("tag")
        tags, values = self.comm.gather_rows(tags, local)
        order = np.argsort(tags, kind="stable")
        return values[order]

    def close(self):
        """Flush and close every output file (also after an error: nothing half-written stays open)."""
        self._screen_lines.flush()
        self._log_lines.flush()
        self.output.close()
        if self.logfile:
            self.logfile.close()
            self.logfile = None

    def _log_write(self, text):
        if self.logfile:
            try:
                self.logfile.write(text + "\n")
                self.logfile.flush()
            except OSError as e:        # a full disk: stop writing it, and say so (on the screen)
                name, self.logfile = self.logfile.name, None
                raise DemError(f"the log file (-log): cannot write '{name}': {e.strerror or e}") from None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


class Lines:
    """Lines of text to `write`, where the same line again right after itself is counted, not written
    (a loop of create_atoms prints `Created 1 particles` hundreds of times): the count follows when
    another line comes, or at flush."""

    def __init__(self, write):
        self.write, self.last, self.repeats = write, None, 0

    def line(self, text):
        if text == self.last:
            self.repeats += 1
            return
        self.flush()
        self.last = text
        self.write(text)

    def flush(self):
        if self.repeats:
            n, self.repeats = self.repeats, 0
            self.write(f"(the line above {n} more time{'s' if n > 1 else ''})")


def open_log(path):
    """The log file, its folder created as dumps do; a clear error when it cannot be written."""
    return open_output(path, "the log file (-log)")


def fatal(sim, error):
    """Report a DemError on stderr/log and return the exit status."""
    text = f"ERROR: {error}"
    if sim is not None:
        return sim.comm.fatal(sim, text)     # MPI: one report, and never a hang when one rank failed alone
    print(text, file=sys.stderr, flush=True)
    return 1


__all__ = ["Sim", "DemError", "fatal"]
