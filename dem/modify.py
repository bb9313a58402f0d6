"""The list of fixes and, per stage, the fixes to call (built in init(), in input-script order)."""
import numpy as np

from .errors import DemError, unknown
from .fix import STAGE_METHODS, Stage


class Modify:
    def __init__(self, sim):
        self.sim = sim
        self.fixes = []
        self.by_stage = {s: [] for s in Stage}
        self.after_step = []
        self.rebuild_requests = []
        self.restart_states = {}     # fix id -> state read from a restart, given to the fix of that id

    def add_fix(self, args):
        if len(args) < 3:
            raise DemError("fix needs: fix ID group-ID style args ...")
        fid, group, style = args[0], args[1], args[2]
        if self.sim.update.running:
            raise DemError(f"fix {fid}: a fix cannot be defined during a run (e.g. from a python/every "
                           f"callback): define it before the run")
        cls = self.sim.registry.get("fix", style, args[3:])
        self.sim.groups.bit(group)
        fix = cls(self.sim, fid, group, args[3:])
        for i, old in enumerate(self.fixes):
            if old.id == fid:           # LAMMPS: redefining an ID replaces the fix in place
                old.unfix()
                self.fixes[i] = fix
                break
        else:
            self.fixes.append(fix)
        if fid in self.restart_states:
            fix.restore(self.restart_states.pop(fid))
        return fix

    def delete_fix(self, fid):
        for i, fix in enumerate(self.fixes):
            if fix.id == fid:
                fix.unfix()
                del self.fixes[i]
                self.sim.output.names.release(f"fix {fid}")     # its files may be written by others now
                if self.sim.update.running:     # from a callback: the rest of this run goes without it
                    self._lists()
                    up = self.sim.update
                    up.wall_fixes = [f for f in up.wall_fixes if f is not fix]
                return
        raise unknown("fix ID", fid, [f.id for f in self.fixes])

    def find(self, fid):
        for fix in self.fixes:
            if fix.id == fid:
                return fix
        return None

    def init(self):
        self._lists()
        for fix in self.fixes:
            fix.init()

    def _lists(self):
        for s in Stage:
            self.by_stage[s] = [f for f in self.fixes if f.stages & s]
        self.integrators = self.by_stage[Stage.INTEGRATE]
        # called after each complete step, before its output (fix python/every)
        self.after_step = [f for f in self.fixes if hasattr(f, "after_step")]
        # asked at the start of each step whether the neighbor list must rebuild (fix insert)
        self.rebuild_requests = [f for f in self.fixes if hasattr(f, "wants_rebuild")]

    def setup(self):
        for fix in self.fixes:
            fix.setup()

    def max_radius(self):
        atom = self.sim.atom
        r = float(atom.data["radius"][:atom.nlocal].max()) if atom.nlocal else 0.0
        r = max([r] + [f.max_radius() for f in self.fixes])
        return self.sim.comm.max(r)

    def acceleration(self):
        """The sum of the uniform body accelerations (gravity) the fixes apply, or None."""
        gs = [np.asarray(f.acceleration, float) for f in self.fixes if f.acceleration is not None]
        return np.sum(gs, axis=0) if gs and np.any(np.sum(gs, axis=0)) else None

    def particles_removed(self):
        for fix in self.fixes:
            fix.particles_removed()

    def _call(self, stage):
        for fix in self.by_stage[stage]:
            getattr(fix, STAGE_METHODS[stage])()

    def pre_exchange(self):
        self._call(Stage.PRE_EXCHANGE)

    def pre_neighbor(self):
        self._call(Stage.PRE_NEIGHBOR)

    def post_neighbor(self):
        self._call(Stage.POST_NEIGHBOR)

    def pre_force(self):
        self._call(Stage.PRE_FORCE)

    def post_force(self):
        self._call(Stage.POST_FORCE)

    def integrate(self):
        self._call(Stage.INTEGRATE)

    def post_integrate(self):
        self._call(Stage.POST_INTEGRATE)

    def end_of_step(self):
        self._call(Stage.END_OF_STEP)

    def thermo(self):
        out = {}
        for fix in self.fixes:
            for k, v in fix.thermo().items():
                out[f"f_{fix.id}[{k}]" if not k.startswith("f_") else k] = v
        return out
