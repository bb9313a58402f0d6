"""fix damping/potyondy"""
from dem.args import Args
from dem.fix import Fix, Stage

import numpy as np

from . import _fix_damping_potyondy


class FixDampingPotyondy(Fix):
    """fix ID group damping/potyondy alpha A [start N] [stop M]

    Local non-viscous damping of Potyondy & Cundall (2004): every force and torque component is reduced
    against the motion,

        F_i <- F_i - A |F_i| sign(v_i),        T_i <- T_i - A |T_i| sign(omega_i)     (i = x, y, z)

    with 0 <= A < 1 (PFC's default 0.7). It removes kinetic energy in proportion to the unbalanced force,
    not to the velocity, so it speeds up settling to a static state (packings) without damping rigid-body
    motion at constant velocity; it is not physical in dynamic flows. v and omega are the stored
    half-step values (leap-frog), as in PFC's central-difference scheme.

    Active for steps start <= step < stop (defaults: always). It must see the total force: define it
    after every other force fix (gravity, walls, drums): it acts in POST_FORCE in input-script order,
    and a warning is printed at the start of a run if another POST_FORCE fix comes after it.
    Thermo: `f_ID[power]` (rate of work of the damping forces and torques, W, <= 0).

    Example: `fix calm all damping/potyondy alpha 0.7 stop 200000`."""

    style = "damping/potyondy"
    thermo_quantities = {"power": ("rate of work of the damping", "W")}
    stages = Stage.POST_FORCE

    def __init__(self, sim, fid, group, args):
        super().__init__(sim, fid, group, args)
        a = Args(args, "fix ID group damping/potyondy alpha A [start N] [stop M]",
                 f"fix {fid} damping/potyondy")
        a.need(2)
        if a[0] != "alpha":
            raise a.error(f"expected 'alpha A', got '{a[0]}'")
        self.alpha = a.float(1, "alpha", nonneg=True)
        if self.alpha >= 1.0:
            raise a.error("alpha must be < 1 (alpha = 1 cancels every force that drives a motion)")
        kw = a.keywords(2, {"start": 1, "stop": 1})
        self.start = a.to_int(kw["start"][0], "start") if "start" in kw else None
        self.stop = a.to_int(kw["stop"][0], "stop") if "stop" in kw else None
        self.stats = np.zeros(1)
        self.power = 0.0

    def init(self):
        post = self.sim.modify.by_stage[Stage.POST_FORCE]
        later = post[post.index(self) + 1:] if self in post else []
        if later:
            self.sim.warning(f"fix {self.id} damping/potyondy comes before POST_FORCE fix(es) "
                             f"{', '.join(f.id for f in later)}: their forces are not damped (define the "
                             f"damping last)")

    def active(self, step):
        return (self.start is None or step >= self.start) and (self.stop is None or step < self.stop)

    def post_force(self):
        sim = self.sim
        if not self.active(sim.update.ntimestep):
            self.power = 0.0
            return
        a = sim.atom.data
        _fix_damping_potyondy.damp(a["f"], a["torque"], a["v"], a["omega"], a["mask"], int(self.groupbit),
                                   sim.atom.nlocal, self.alpha, self.stats)
        self.power = float(self.stats[0])

    def thermo(self):
        return {"power": self.sim.comm.sum(self.power)}
