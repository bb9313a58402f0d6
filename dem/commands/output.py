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
    lx ly lz vol cpu pct tps eta spcpu tpcpu cpuremain, v_NAME (equal-style variable), f_ID[name] (fix
    value), c_ID and c_ID[k] (compute value).
    `ke`/`erot` use the stored half-step velocities; `etotal` is time-centred (full-step kinetic energy
    plus the elastic energy of the same force evaluation). `contacts` counts particle-particle contacts,
    `cn` = 2 contacts / particles, `maxov` the largest overlap over the smaller diameter, and pct/tps/eta
    the progress of the run (percent, steps per second, seconds left); `cpu` the seconds since the run
    started. LAMMPS names work too: `spcpu` (= tps), `tpcpu` (simulated seconds per second), `cpuremain`
    (= eta, in seconds).
    Default (`one`): step time atoms ke erot contacts cn maxov pct tps eta."""
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
