"""fix print/series"""
import os

from dem.errors import DemError
from dem.files import open_output
from dem.fix import Fix, Stage
from dem.quantities import describe, header_line


class FixPrintSeries(Fix):
    """fix ID group print/series N FILE keyword ... [format FMT] [append yes|no]

    Writes a time series: every N steps one line `step time value ...` to FILE (a header line `# step
    time keyword ...` first, then `# quantity [unit]: ...` with what each column is, where known, for
    dem-plot's labels), the values being thermo keywords of any kind: `ke`, `cn`, `c_ID`,
    `c_ID[k]`, `v_NAME`, `f_ID[name]`... Lines are written at the end of the step (the values of the
    state after the step, as thermo would print them) and at the start of a run when its step is a
    multiple of N (not twice). `format` is a Python or C float format (default %.10g); `append yes`
    keeps an existing file (default: replaced when the fix is defined). Only rank 0 writes; the file is
    flushed after each line. The group is not used.

    Example: `fix series all print/series 500 drum.dat c_vm c_cn f_drum[revs]`; plot with
    `dem-plot drum.dat` (installed with dem; or `python -m dem.tools.plot_series`)."""

    style = "print/series"
    stages = Stage.END_OF_STEP

    def __init__(self, sim, fid, group, args):
        super().__init__(sim, fid, group, args)
        usage = "N FILE keyword ... [format FMT] [append yes|no]"
        self.need(3, usage)
        try:
            self.every = int(args[0])
        except ValueError:
            raise DemError(f"fix {fid} print/series: N must be an integer, got '{args[0]}'") from None
        if self.every < 1:
            raise DemError(f"fix {fid} print/series: N must be >= 1")
        self.path = args[1]
        words, fmt, append = [], "{:.10g}", False
        i = 2
        while i < len(args):
            if args[i] == "format" and i + 1 < len(args):
                f = args[i + 1]
                fmt = "{:" + f[1:] + "}" if f.startswith("%") else f
                try:
                    fmt.format(1.0)
                except (ValueError, IndexError):
                    raise DemError(f"fix {fid} print/series: bad format '{f}'") from None
                i += 2
            elif args[i] == "append" and i + 1 < len(args):
                if args[i + 1] not in ("yes", "on", "1", "no", "off", "0"):
                    raise DemError(f"fix {fid} print/series: append must be yes or no, got '{args[i + 1]}'")
                append = args[i + 1] in ("yes", "on", "1")
                i += 2
            else:
                words.append(args[i])
                i += 1
        if not words:
            raise DemError(f"fix {fid} print/series: no keyword to write; usage: fix ID group print/series "
                           f"{usage}")
        sim.output.thermo.check_style(words)
        self.keywords = words
        self.fmt = fmt
        self.last_step = None
        self.fh = None
        sim.output.names.claim(f"fix {fid}", [self.path], f"fix {fid} print/series")   # every rank refuses it
        if sim.comm.me == 0:
            exists = append and os.path.exists(self.path)
            self.fh = open_output(self.path, f"fix {fid} print/series", "a" if append else "w")
            if not exists:
                self.fh.write("# step time " + " ".join(words) + "\n")
                columns = ["step", "time"] + words                # what each is, for dem-plot's labels
                self.fh.write(header_line([describe(sim, w) for w in columns]) + "\n")
                self.fh.flush()

    def setup_output(self):          # after the run's first force evaluation: the values thermo prints
        step = self.sim.update.ntimestep
        if step % self.every == 0 and step != self.last_step:
            self.write(step)

    def end_of_step(self):
        up = self.sim.update
        step = up.ntimestep + 1      # END_OF_STEP runs before the step counter moves on
        if step % self.every:
            return
        with up.as_output_of_step(step):      # the values thermo will print for this step
            self.write(step)

    def write(self, step):
        thermo = self.sim.output.thermo
        values = [thermo.keyword(w) for w in self.keywords]     # every rank: reductions inside
        self.last_step = step
        if self.fh is not None:
            cols = [str(step), self.fmt.format(self.sim.update.time)]
            cols += [str(int(v)) if isinstance(v, (int,)) and not isinstance(v, bool) else self.fmt.format(v)
                     for v in values]
            try:
                self.fh.write(" ".join(cols) + "\n")
                self.fh.flush()
            except OSError as e:        # a full disk
                raise DemError(f"fix {self.id} print/series: cannot write '{self.path}': {e.strerror or e}") from None

    def unfix(self):
        if self.fh is not None:
            self.fh.close()
            self.fh = None
