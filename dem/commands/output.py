"""Output commands: thermo, thermo_style, thermo_modify (the thermo line), dump and undump (files of
particle frames)."""
from ..command import Command
from ..errors import did_you_mean
from ..thermo import DEFAULT_STYLE


class ThermoCommand(Command):
    """thermo N

    Print a thermo line every N steps (0: only at the start and end of a run)."""
    style = "thermo"
    usage = "N"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        self.sim.output.thermo.every = a.int(0, "N", nonneg=True)


class ThermoStyle(Command):
    """thermo_style custom keyword ... | thermo_style one

    Keywords: step time dt atoms ke erot pe etotal contacts cn maxov lost nbuild xlo xhi ylo yhi zlo zhi
    lx ly lz vol cpu pct tps eta jpct jeta spcpu tpcpu cpuremain, v_NAME (equal-style variable), f_ID[name]
    (fix value), c_ID and c_ID[k] (compute value).
    `ke`/`erot` use the stored half-step velocities; `etotal` is time-centred (full-step kinetic energy
    plus the elastic energy of the same force evaluation). `contacts` counts particle-particle contacts,
    `cn` = 2 contacts / particles, `maxov` the largest overlap over the smaller diameter, and pct/tps/eta
    the progress of the run (percent, steps per second, seconds left); `cpu` the seconds since the run
    started. LAMMPS names work too: `spcpu` (= tps), `tpcpu` (simulated seconds per second), `cpuremain`
    (= eta, in seconds).
    `jpct`/`jeta`: the progress of the whole job, every run of the script given to `dem -in` (or
    sim.file, sim.commands): percent of its steps done, and seconds left (a plain number, no `s`). jeta
    is the job's steps left at the speed of the current run (a fill, a settling and a long rotation step
    at different speeds: the current run is the best guess of the next ones), at the job's average speed
    before the run has a speed of its own. The job's length is known where, at the start of each run,
    every later `run N` has an N that is a number, or a `${name}`/`$(expression)` of variables defined
    by then (-var included) that no command before that run changes, and that reads no value of the
    simulation (step, c_ID...); `run N upto` counts from the step it will start at. It is not known with
    a run inside an `if` or `run ... every`, a loop (`jump SELF` back) over a run, a jump forward or to
    another file, an `include`, or runs started from Python (sim.run, sim.command): jpct and jeta are
    then `nan` (a number still, for dem-plot and pandas). The thermo header says which: e.g.
    `(pct and eta: of this run, steps 0 to 60000; jpct and jeta: of the job (run 1 of 4, 235000 steps
    in all), jeta at this run's speed)`, or `...; jpct and jeta: nan, the job's length is not known
    (line 12 'run ${n}' reads variables that change before it (n))`.
    Default (`one`): step time atoms ke erot contacts cn maxov pct tps eta.
    Each keyword's quantity and SI unit (ke: J, time: s, ...) are in dem/quantities.py; computes and
    fixes declare those of their values (compute repose: degrees); fix print/series writes them into
    its file's header and dem-plot labels its panels with them."""
    style = "thermo_style"
    usage = "custom keywords... | one"

    def __call__(self, words):
        a = self.args(words)
        a.need(1)
        thermo = self.sim.output.thermo
        if a[0] == "one":
            thermo.style = list(DEFAULT_STYLE)
            return
        if a[0] != "custom":
            raise a.error(f"thermo style '{a[0]}' is not supported (use custom or one)")
        if len(a) < 2:
            raise a.error("thermo_style custom needs at least one keyword")
        thermo.check_style(a.words[1:])
        thermo.style = a.words[1:]


class ThermoModify(Command):
    """thermo_modify [lost error|warn|ignore] [overlap FRACTION] [format float FMT] [norm no] [flush yes]

    `lost`: what to do with a particle leaving through a fixed boundary (default error). `overlap`: stop
    the run when an overlap exceeds this fraction of the smaller diameter (default 0.2), between two
    particles or between a particle and a wall (its diameter); the error names both. A particle whose
    centre lies behind a wall (created there) stops the run whatever the limit. `format float`:
    a Python or C format for float columns, e.g. %.8g."""
    style = "thermo_modify"
    usage = "[lost error|warn|ignore] [overlap F] [format float FMT] [norm no]"

    def __call__(self, words):
        a = self.args(words)
        i = 0
        while i < len(a):
            key = a[i]
            if key == "lost":
                if a[i + 1] not in ("error", "warn", "ignore"):
                    raise a.error("lost must be error, warn or ignore")
                self.sim.domain.lost_policy = a[i + 1]
                i += 2
            elif key == "overlap":
                self.sim.update.max_overlap_fraction = a.float(i + 1, "overlap", positive=True)
                i += 2
            elif key == "format":
                if a[i + 1] not in ("float", "line"):
                    raise a.error("use 'format float FORMAT'")
                fmt = a[i + 2]
                fmt = "{:" + fmt[1:] + "}" if fmt.startswith("%") else fmt
                try:
                    fmt.format(1.0)
                except (ValueError, IndexError):
                    raise a.error(f"bad format '{a[i + 2]}'") from None
                self.sim.output.thermo.float_format = fmt
                i += 3
            elif key in ("norm", "flush"):
                if key == "norm" and a.yes_no(a[i + 1], "norm"):
                    raise a.error("only 'norm no' is supported (extensive values)")
                i += 2
            else:
                raise a.error(f"unknown keyword '{key}'{did_you_mean(key, ['lost', 'overlap', 'format', 'norm', 'flush'])}")


class DumpCommand(Command):
    """dump ID GROUP STYLE N FILE [args]

    Styles: h5 (one HDF5 file + XDMF for ParaView), vtk (VTU frames + PVD), custom (LAMMPS text
    snapshots, for OVITO: `dump d2 all custom 1000 snap.*.gz id type x y z radius`). Example:
    `dump d1 all h5 1000 pour.h5`. A file (or `*` pattern) already written by another output (the log,
    another dump, the periodic restarts) is refused: two outputs on one file destroy each other."""
    style = "dump"
    usage = "ID group style N file [args]"

    def __call__(self, words):
        self.sim.output.add_dump(words)


class DumpModify(Command):
    """dump_modify ID keyword value ...

    Change a dump after the dump command: `every N` (any style), `sort id|off` (any style); dump custom
    also takes `sort -id|N|-N`, `format float|int|line FMT`, `pad N`, `time yes|no`, `append yes|no`
    (see dump custom)."""
    style = "dump_modify"
    usage = "ID keyword value ..."

    def __call__(self, words):
        self.sim.output.modify_dump(list(words))


class Undump(Command):
    """undump ID"""
    style = "undump"
    usage = "ID"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        self.sim.output.undump(a[0])
