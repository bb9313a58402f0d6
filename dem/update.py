"""The run: setup, the timestep loop and its timers.

One step computes forces on the current state, then integrates (leap-frog Verlet, Grains3D eq. 9):
    [rebuild: PRE_EXCHANGE, pbc, exchange, borders, PRE_NEIGHBOR, build, POST_NEIGHBOR] or forward comm
    clear forces; PRE_FORCE; pair; reverse comm; POST_FORCE (gravity, walls, damping)
    INTEGRATE (v(n+1/2) = v(n-1/2) + dt F(n)/m; x(n+1) = x(n) + dt v(n+1/2)); POST_INTEGRATE; END_OF_STEP
    output
Velocities are stored at half steps, so the state between steps is complete without forces: a new run (or a
run read from a restart) needs no setup force pass and continues the trajectory bitwise.
"""
import contextlib
import math
import time

import numpy as np

from .errors import DemError
from .interrupt import SIGNAL_STATE, Interrupted

TIMERS = ("pair", "neigh", "comm", "modify", "integrate", "output")


class Update:
    def __init__(self, sim):
        self.sim = sim
        self._dt = None
        self.ntimestep = 0
        self._time_anchor = (0, 0.0)   # (step, time) where dt last changed: see `time`
        self.first_step = 0
        self.last_step = 0
        self.beginstep = self.endstep = 0   # `run ... start S stop S`: the span of a run sequence
        self.ran = False                    # a run happened: `run ... pre no` may then skip setup output
        self.in_run = False                 # inside `run ... every`: its commands may not start a run
        self.running = False
        self.timers = dict.fromkeys(TIMERS, 0.0)
        self.setup_timers = dict.fromkeys(TIMERS, 0.0)
        self.wall_start = None
        self.max_overlap_fraction = 0.2
        self.vsync = 0.0   # v + vsync * f / m is the full-step velocity of the last force evaluation
        self.wall_fixes = []   # fixes with wall contacts (`worst_contact`), for the overlap stop
        self.stop_signal = 0   # SIGINT/SIGTERM agreed by every rank: the run stops at the end of this step
        self._checks = np.zeros(3)   # check_step's reduction buffer

    @property
    def time(self):
        """Simulated time, t0 + (step - step0) dt from the step where dt last changed: a sum of dt over
        the steps would gather round-off (0.020000000000000788 after 10,000 steps of 2e-6)."""
        step0, t0 = self._time_anchor
        return t0 + (self.ntimestep - step0) * self._dt if self._dt is not None else t0

    @time.setter
    def time(self, t):
        self._time_anchor = (self.ntimestep, float(t))

    @property
    def dt(self):
        return self._dt

    @dt.setter
    def dt(self, dt):
        if self._dt is not None:
            self.time = self.time      # the time so far, from here on with the new dt
        self._dt = dt

    @property
    def time_anchor(self):
        """(step, time) where dt last changed: restarts keep it, so that a continued run's time is the
        uninterrupted run's to the last digit."""
        return self._time_anchor

    @time_anchor.setter
    def time_anchor(self, anchor):
        step, t = anchor
        self._time_anchor = (int(step), float(t))

    @contextlib.contextmanager
    def as_output_of_step(self, step):
        """The state as the output of step `step` (END_OF_STEP, before the counter moves on) sees it: that
        step, its time (from the anchor: exact) and the velocities' synchronisation after it; restored."""
        saved = (self.ntimestep, self.vsync)
        self.ntimestep, self.vsync = step, -0.5 * self._dt
        try:
            yield
        finally:
            self.ntimestep, self.vsync = saved

    def reset_step(self, step):
        """`reset_timestep`: the step count changes, the time does not."""
        t = self.time
        self.ntimestep = step
        self.time = t

    # ----- setup ----------------------------------------------------------------------------------
    def setup(self, quiet=False):
        sim = self.sim
        sim.domain.require_box("run")
        if self.dt is None:
            raise DemError("no time step: use 'timestep DT' before run")
        if not sim.modify.integrators:
            sim.warning("no integrator fix (e.g. 'fix 1 all nve/sphere'): particles will not move")
        if sim.pair is not None:
            sim.pair.init()
        sim.tally.update()
        sim.neighbor.init()
        sim.comm.settle_grid()
        atom, nb = sim.atom, sim.neighbor
        continuing = not sim.comm.any(not (nb.hold_valid and len(nb.xhold) == atom.nlocal))
        nb.rebuild(self.ntimestep, wrap=not continuing)
        sim.modify.setup()
        self.check_timestep()
        self.force_pass(advance=False)
        self.vsync = 0.5 * self.dt
        sim.output.setup(thermo=not quiet)

    def check_timestep(self):
        pair = self.sim.pair
        tc = pair.min_contact_time() if pair is not None else None
        tcw = [f.min_contact_time() for f in self.sim.modify.fixes if hasattr(f, "min_contact_time")]
        tcs = [t for t in [tc] + tcw if t]
        if tcs:
            tmin = min(tcs)
            self.min_contact_time = tmin
            if self.dt > tmin / 10.0:
                self.sim.warning(f"time step {self.dt:g} exceeds T_c/10 = {tmin / 10:g} of the stiffest, "
                                 f"lightest contact (T_c = {tmin:g}); contacts will be under-resolved")
        else:
            self.min_contact_time = None

    # ----- the loop -------------------------------------------------------------------------------
    def run(self, nsteps, pre=True, post=True):
        """nsteps steps; `pre` False leaves out the setup's thermo header and line when this run continues
        the previous one, `post` False the end-of-run summary but its loop time line (`run` command)."""
        if nsteps < 0:
            raise DemError("run needs a number of steps >= 0")
        sim = self.sim
        quiet_setup = not pre and self.ran
        sim.modify.init()
        self.timers = dict.fromkeys(TIMERS, 0.0)
        self.first_step = self.ntimestep
        self.last_step = self.ntimestep + nsteps
        self.wall_fixes = [f for f in sim.modify.fixes if hasattr(f, "worst_contact")]
        self.stop_signal = 0
        t_setup = time.perf_counter()
        with SIGNAL_STATE.deferred():       # a signal stops the run at a step end (check_step)
            self.running = True
            try:
                self.setup(quiet=quiet_setup)
                self.ran = True
                self.setup_timers = dict(self.timers)   # the setup's force pass: not in the loop time
                self.wall_start = time.perf_counter()
                for _ in range(nsteps):
                    self.step()
                    if self.stop_signal:
                        break
                if not self.stop_signal:    # one that came after the last check: all ranks agree on it
                    self.stop_signal = int(sim.comm.max(SIGNAL_STATE.pending))
            finally:
                self.running = False
            done = self.ntimestep - self.first_step
            loop = time.perf_counter() - (self.wall_start or t_setup)
            sim.job.finished(done, loop)
            sim.output.finish(done, loop, time.perf_counter() - t_setup, full=post)
            if self.stop_signal:
                SIGNAL_STATE.take()
                raise Interrupted(self.stop_signal, sim.output.stop_report(self.stop_signal, done, nsteps),
                                  step=self.ntimestep)

    def step(self):
        sim = self.sim
        timers = self.timers
        clock = time.perf_counter
        t0 = clock()
        if sim.neighbor.decide(self.ntimestep):
            sim.neighbor.rebuild(self.ntimestep)
            t1 = clock()
            timers["neigh"] += t1 - t0
        else:
            sim.comm.forward()
            t1 = clock()
            timers["comm"] += t1 - t0
        t2 = self.force_pass(advance=True, t_start=t1)
        sim.modify.integrate()
        t3 = clock()
        timers["integrate"] += t3 - t2
        sim.modify.post_integrate()
        sim.modify.end_of_step()
        self.ntimestep += 1
        self.vsync = -0.5 * self.dt
        for fix in sim.modify.after_step:
            fix.after_step(self.ntimestep)
        t4 = clock()
        timers["modify"] += t4 - t3
        sim.output.step(self.ntimestep)
        timers["output"] += clock() - t4

    def force_pass(self, advance=True, t_start=None):
        sim = self.sim
        clock = time.perf_counter
        timers = self.timers
        t0 = t_start if t_start is not None else clock()
        atom = sim.atom
        atom.data["f"][:atom.nall] = 0.0
        atom.data["torque"][:atom.nall] = 0.0
        sim.tally.clear()
        if advance:
            sim.modify.pre_force()
        t1 = clock()
        timers["modify"] += t1 - t0
        pair = sim.pair
        if pair is not None:
            pair.compute(advance)
        t2 = clock()
        timers["pair"] += t2 - t1
        sim.comm.reverse()
        sim.tally.reverse()
        t3 = clock()
        timers["comm"] += t3 - t2
        if advance:
            sim.modify.post_force()
            self.check_step()
        t4 = clock()
        timers["modify"] += t4 - t3
        return t4

    def check_step(self):
        """Once per step, after the forces: the largest contact overlap (pair style and walls), a particle
        behind a wall, and a pending SIGINT/SIGTERM, in one reduction of three numbers (none in serial):
        every rank sees the same values, so all stop at the same step."""
        pair = self.sim.pair
        v = self._checks
        v[0] = pair.max_overlap if pair is not None else 0.0
        v[1] = 0.0
        for f in self.wall_fixes:
            v[0] = max(v[0], f.max_overlap)
            if f.behind:
                v[1] = 1.0
        v[2] = SIGNAL_STATE.pending
        self.sim.comm.max_values(v)
        if v[0] > self.max_overlap_fraction or v[1]:
            self.overlap_error(float(v[0]))
        if v[2]:
            self.stop_signal = int(v[2])

    def worst_contact(self):
        """(overlap / diameter, who) of this rank's largest overlap, pair style or wall."""
        pair = self.sim.pair
        found = [(0.0, "")]
        if pair is not None:
            tags = getattr(pair, "max_overlap_tags", None)
            found.append((pair.max_overlap, f"between particles {tags[0]} and {tags[1]}" if tags else ""))
        for f in self.wall_fixes:
            worst = f.worst_contact()
            if worst is not None:
                found.append((worst[0], "between " + worst[1]))
        return max(found, key=lambda p: p[0])

    def overlap_error(self, worst):
        self.sim.output.emergency()
        _, who = max(self.sim.comm.allgather(self.worst_contact()), key=lambda p: p[0])
        who = f" {who}" if who else ""
        limit = self.max_overlap_fraction
        what = (f"exceeds the limit {limit:g} (thermo_modify overlap)" if worst > limit else
                "with a particle's centre behind a wall")
        if self.ntimestep == self.first_step:
            hint = ("at the first step of the run: particles were created (create_atoms, read_data) "
                    "overlapping each other or inside or behind a wall; keep them a radius clear of the walls")
        else:
            tc = getattr(self, "min_contact_time", None)
            hint = (f"time step {self.dt:g} vs T_c = {tc:g} ({tc / self.dt:.1f} steps per contact)"
                    if tc else "check the stiffness and the time step")
            hint += "; a stiffer kn or a smaller time step reduces overlaps"
        raise DemError(f"overlap of {worst:.3g} x diameter{who} at step {self.ntimestep} {what}", hint=hint)

    def nan_error(self, detail):
        self.sim.output.emergency()
        tc = getattr(self, "min_contact_time", None)
        hint = f"time step {self.dt:g} vs T_c = {tc:g}" if tc else "check the time step"
        raise DemError(f"non-finite position or velocity at step {self.ntimestep}{detail}",
                       hint=hint + " (at least 10, better 50 steps per contact)")

    # ----- helpers --------------------------------------------------------------------------------
    def elapsed(self):
        return time.perf_counter() - self.wall_start if self.wall_start else 0.0

    def progress(self):
        """(fraction done, steps per second, seconds left) of the current run."""
        done = self.ntimestep - self.first_step
        total = max(self.last_step - self.first_step, 1)
        if not self.running or self.wall_start is None:
            return done / total, 0.0, math.inf
        elapsed = time.perf_counter() - self.wall_start
        tps = done / elapsed if elapsed > 0 else 0.0
        eta = (total - done) / tps if tps > 0 else math.inf
        return done / total, tps, eta


__all__ = ["Update", "TIMERS", "np"]
