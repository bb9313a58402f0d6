"""fix remove"""

import numpy as np

from dem.args import Args
from dem.errors import did_you_mean
from dem.fix import Fix, Stage


class FixRemove(Fix):
    """fix ID group remove REGION-ID [every M]

    Deletes the particles of the group whose centre lies inside the region: an outlet below a hopper or
    a silo, a sink at the end of a chute. The test runs at the end of every step that is a multiple of M
    (default 1); if it finds particles inside, the fix forces a neighbor-list rebuild and deletes them at
    the start of the next step (PRE_EXCHANGE, before migration, with their contact history and every
    other per-particle field), so the output of the step that found them still shows them. A particle
    travelling faster than the region's depth every M steps may cross it unseen: keep M small or the
    region deep (a particle that reaches a fixed boundary is lost, see `thermo_modify lost`). Positions
    are wrapped into the box along periodic axes before the test. Deletions pending at the end of a run
    happen at the setup of the next run (or after `read_restart`, when the fix is defined again).

    Thermo: `f_ID[removed]` (number of particles deleted since the fix was defined, all ranks) and
    `f_ID[mass]` (their total mass); both continue across restarts.

    Example (a silo discharging through its outlet into a sink, the bottom centimetre of the box)::

        region sink block EDGE EDGE EDGE EDGE 0 0.01
        fix out all remove sink
        thermo_style custom step atoms f_out[removed] f_out[mass]
    """

    style = "remove"
    stages = Stage.PRE_EXCHANGE | Stage.END_OF_STEP
    usage = "fix ID group remove REGION-ID [every M]"

    def __init__(self, sim, fid, group, args):
        super().__init__(sim, fid, group, args)
        a = Args(args, self.usage, f"fix {fid} remove")
        a.need(1)
        regions = sim.domain.regions
        if a[0] not in regions:
            raise a.error(f"unknown region ID '{a[0]}'{did_you_mean(a[0], regions)}")
        self.region = regions[a[0]]
        kw = a.keywords(1, {"every": 1})
        self.every = a.to_int(kw["every"][0], "every") if "every" in kw else 1
        if self.every < 1:
            raise a.error(f"every must be >= 1, got {kw['every'][0]}")
        self.removed = 0          # totals over all ranks since the fix was defined
        self.mass = 0.0
        self.armed = False        # particles were found inside: delete them at the next PRE_EXCHANGE

    def _inside(self):
        """Mask of this rank's owned particles of the group whose centre is inside the region."""
        atom, dom = self.sim.atom, self.sim.domain
        n = atom.nlocal
        x = atom.data["x"][:n]
        if dom.periodic.any():        # between rebuilds a centre may have left the box along a periodic axis
            x = np.where(dom.periodic, dom.lo + np.mod(x - dom.lo, dom.prd), x)
        sel = (atom.data["mask"][:n] & self.groupbit) != 0
        if n:
            sel &= self.region.inside(x)
        return sel

    def init(self):
        # deletions found at the end of the last run: the setup's rebuild must be a full one (with
        # PRE_EXCHANGE), as the rebuild of the uninterrupted run would have been
        if self.armed:
            self.sim.neighbor.invalidate()

    def setup(self):
        if self.armed:
            self.sim.neighbor.force_rebuild = True

    def end_of_step(self):
        sim = self.sim
        if (sim.update.ntimestep + 1) % self.every:        # the step this END_OF_STEP completes
            return
        if sim.comm.sum(int(np.count_nonzero(self._inside()))):    # every rank takes part
            self.armed = True
            sim.neighbor.force_rebuild = True

    def pre_exchange(self):
        if not self.armed:
            return
        self.armed = False
        sim, atom = self.sim, self.sim.atom
        out = self._inside()
        totals = np.array([np.count_nonzero(out), atom.data["rmass"][:atom.nlocal][out].sum()], dtype=float)
        totals = sim.comm.sum_values(totals)          # one reduction, on every rank
        n = int(round(totals[0]))
        if not n:
            return
        atom.keep(~out)       # moves every per-particle field (contact and wall history included)
        atom.natoms -= n
        self.removed += n
        self.mass += float(totals[1])
        sim.modify.particles_removed()

    def thermo(self):
        return {"removed": self.removed, "mass": self.mass}

    def state(self):
        return {"removed": self.removed, "mass": self.mass, "armed": self.armed}

    def restore(self, state):
        self.removed = int(state["removed"])
        self.mass = float(state["mass"])
        self.armed = bool(state.get("armed", False))
