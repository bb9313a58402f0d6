"""Output during a run: thermo lines, dumps and periodic restarts, and the end-of-run summary with the
time per stage."""
import resource

import numpy as np

from .errors import DemError
from .output_names import OutputNames
from .thermo import Thermo
from .update import TIMERS


class Output:
    def __init__(self, sim):
        self.sim = sim
        self.thermo = Thermo(sim)
        self.dumps = {}
        self.restart_every = 0
        self.restart_files = []
        self.last_thermo = None
        self.last_restart = None   # (file, step) of the last periodic restart written
        self.names = OutputNames()  # the files of the log, dumps and restarts (no two on one file)

    # ----- dumps ----------------------------------------------------------------------------------
    def add_dump(self, args):
        if len(args) < 5:
            raise DemError("dump needs: dump ID group style N file [args]")
        did, group, style, every, path = args[:5]
        cls = self.sim.registry.get("dump", style, args[5:])
        try:
            every = int(every)
        except ValueError:
            raise DemError(f"dump {did}: N must be an integer, got '{every}'") from None
        if every <= 0:
            raise DemError(f"dump {did}: N must be > 0")
        if did in self.dumps:
            raise DemError(f"dump ID '{did}' already exists (undump it first)")
        dump = cls(self.sim, did, group, every, path, args[5:])
        self.names.claim(f"dump {did}", dump.output_files(), f"dump {did} ({style})")
        self.dumps[did] = dump

    def modify_dump(self, args):
        """dump_modify ID keyword value ..."""
        if len(args) < 2:
            raise DemError("dump_modify needs: dump_modify ID keyword value ...")
        if args[0] not in self.dumps:
            from .errors import unknown
            raise unknown("dump ID", args[0], self.dumps)
        self.dumps[args[0]].modify(list(args[1:]))

    def undump(self, did):
        if did not in self.dumps:
            from .errors import unknown
            raise unknown("dump ID", did, self.dumps)
        self.dumps.pop(did).close()
        self.names.release(f"dump {did}")

    # ----- restarts -------------------------------------------------------------------------------
    def set_restart(self, every, files):
        """`restart N file [file2]`: files checked against the other outputs' (0 turns it off)."""
        if every:
            self.names.claim("restart", files, "restart")
        else:
            self.names.release("restart")
        self.restart_every, self.restart_files = every, list(files) if every else []

    def check_restart_name(self, path, use):
        """A restart written once (write_restart) must not replace the log or a dump."""
        self.names.check([path], use, owner="restart")

    # ----- during a run ---------------------------------------------------------------------------
    def setup(self, thermo=True):
        step = self.sim.update.ntimestep
        if thermo:
            self.thermo.header()
            self.thermo.line()
            self.last_thermo = step
        for fix in self.sim.modify.fixes:
            fix.setup_output()
        for dump in self.dumps.values():
            # a run continuing the last one (run every, run after run) writes no frame twice
            if step % dump.every == 0 and dump.last_step != step:
                dump.write(step)

    def step(self, step):
        every = self.thermo.every
        last = step == self.sim.update.last_step
        if (every and step % every == 0) or last:
            self.thermo.line()
            self.last_thermo = step
        for dump in self.dumps.values():
            if step % dump.every == 0:
                dump.write(step)
        if self.restart_every and step % self.restart_every == 0:
            from .restart import write_restart
            path = self.restart_files[(step // self.restart_every) % len(self.restart_files)]
            path = path.replace("*", str(step))
            write_restart(self.sim, path, "restart")
            self.last_restart = (path, step)

    def emergency(self):
        """Before an error stops a run: write the current frame and flush every file."""
        step = self.sim.update.ntimestep
        for dump in self.dumps.values():
            try:
                if getattr(dump, "last_step", None) != step:
                    dump.write(step)
                dump.flush()
            except Exception:      # never mask the original error
                pass

    def stop_report(self, signum, done, nsteps):
        """What a run stopped by a signal says: where it stopped and the files it leaves (all complete)."""
        from .interrupt import signal_name
        step = self.sim.update.ntimestep
        lines = [f"{signal_name(signum)}: the run stopped at the end of step {step} ({done} of {nsteps} "
                 f"steps); every output file is complete"]
        for dump in self.dumps.values():
            last = f", the last at step {dump.last_step}" if dump.last_step is not None else ""
            lines.append(f"  dump {dump.id} ({dump.style}): {dump.nframes} frame(s) in '{dump.path}'{last}")
        if self.last_restart:
            lines.append(f"  restart: '{self.last_restart[0]}' at step {self.last_restart[1]}")
        elif self.restart_every:
            lines.append("  restart: none written yet")
        return "\n".join(lines)

    def finish(self, nsteps, loop, total, full=True):
        sim = self.sim
        natoms = sim.atom.natoms
        if nsteps == 0:      # run 0: the state was evaluated and output, nothing to time
            sim.print(f"Setup only (run 0) with {natoms} particles: {total:.4g} s")
            for dump in self.dumps.values():
                dump.flush()
            return
        sim.print(f"Loop time of {loop:.4g} on {sim.comm.nprocs} procs for {nsteps} steps with {natoms} "
                  f"particles")
        if not full:        # run ... post no
            for dump in self.dumps.values():
                dump.flush()
            return
        if loop > 0 and nsteps:
            sim.print(f"Performance: {nsteps / loop:.4g} steps/s, {nsteps * natoms / loop:.4g} particle-steps/s")
        sim.print("")
        for line in timing_table(sim, loop):
            sim.print(line)
        sim.print("")
        nb = sim.neighbor
        sim.print(f"Neighbor list builds = {nb.nbuilds}, pairs listed = {sim.comm.sum(nb.nentries)}, "
                  f"skin = {nb.skin:g}")
        for line in sim.comm.report(nsteps):
            sim.print(line)
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
        sim.print(f"Peak memory: {peak:.1f} MiB per process")
        sim.print(f"Total wall time (setup + loop): {total:.4g} s")
        for dump in self.dumps.values():
            dump.flush()

    def close(self):
        for dump in list(self.dumps.values()):
            try:
                dump.close()
            except Exception:
                pass
        self.dumps.clear()


def timing_table(sim, loop):
    """The time of each section of the loop over the ranks, as LAMMPS prints it: min, average and max over
    ranks (seconds), %varavg (standard deviation over ranks in percent of the average: load imbalance)
    and %total (the average's share of the average loop time). `Other` is each rank's loop time not in a
    section, so the %total column sums to 100. Collective: every rank calls it."""
    up = sim.update
    t = np.array([up.timers[name] - up.setup_timers[name] for name in TIMERS] + [0.0])
    t[-1] = max(loop - t[:-1].sum(), 0.0)
    lo, avg, hi = sim.comm.min_avg_max(np.concatenate([t, t * t, [loop]]))
    n = len(t)
    lo, avg2, hi, avg, loop_avg = lo[:n], avg[n:2 * n], hi[:n], avg[:n], avg[-1]
    var = np.sqrt(np.maximum(avg2 - avg * avg, 0.0))
    lines = [f"Section timing over {sim.comm.nprocs} rank(s) (seconds):",
             "Section   |  min time  |  avg time  |  max time  |%varavg| %total",
             "----------+------------+------------+------------+-------+-------"]
    for k, name in enumerate(TIMERS + ("other",)):
        varavg = 100.0 * var[k] / avg[k] if avg[k] > 0 else 0.0
        share = 100.0 * avg[k] / loop_avg if loop_avg > 0 else 0.0
        lines.append(f"{name.capitalize():<10}| {lo[k]:<10.5g} | {avg[k]:<10.5g} | {hi[k]:<10.5g} |"
                     f"{varavg:6.1f} |{share:6.2f}")
    return lines
