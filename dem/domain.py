"""The simulation box: bounds, boundary conditions (p periodic, f fixed, s/m shrink-wrapped open), periodic
wrapping with image counters, and the lost-particle policy for non-periodic boundaries."""
import numpy as np

from .errors import DemError


class Domain:
    def __init__(self, sim):
        self.sim = sim
        self.box_exist = False
        self.lo = np.zeros(3)
        self.hi = np.ones(3)
        self.boundary = [["p", "p"], ["p", "p"], ["p", "p"]]
        self.periodic = np.ones(3, dtype=bool)
        self.regions = {}
        self.lost_policy = "error"   # error | warn | ignore
        self.nlost = 0

    @property
    def prd(self):
        return self.hi - self.lo

    @property
    def volume(self):
        return float(np.prod(self.prd))

    def set_boundary(self, words):
        if len(words) != 3:
            raise DemError("boundary needs three words, one per axis (e.g. 'boundary p p f')")
        styles = []
        for w in words:
            pair = [w[0], w[-1]] if len(w) in (1, 2) else None
            if pair is None or any(c not in "pfsm" for c in pair) or (("p" in pair) and pair != ["p", "p"]):
                raise DemError(f"bad boundary '{w}': use p, f, s or m (two letters for lo/hi, p on both)")
            styles.append(pair)
        self.boundary = styles
        self.periodic = np.array([s[0] == "p" for s in styles])

    def set_box(self, lo, hi):
        lo, hi = np.asarray(lo, float), np.asarray(hi, float)
        if np.any(hi <= lo):
            raise DemError(f"box has no volume: lo {lo.tolist()} hi {hi.tolist()}")
        self.lo, self.hi = lo.copy(), hi.copy()
        self.box_exist = True

    def require_box(self, what):
        if not self.box_exist:
            raise DemError(f"{what} needs a box: use create_box, read_data or read_restart first")

    def inside(self, x):
        return np.all((x >= self.lo) & (x < self.hi), axis=1)

    def pbc(self):
        """Wrap owned particles into periodic dims, grow shrink-wrapped bounds, apply the lost policy.
        Runs on rebuild steps only, so a wrapped position changes at the same steps in every run."""
        atom = self.sim.atom
        n = atom.nlocal
        x = atom.data["x"][:n]
        image = atom.data["image"][:n]
        for d in range(3):
            if self.periodic[d]:
                length = self.hi[d] - self.lo[d]
                below = x[:, d] < self.lo[d]
                above = x[:, d] >= self.hi[d]
                x[below, d] += length
                image[below, d] -= 1
                x[above, d] -= length
                image[above, d] += 1
        self.shrink_wrap()
        out = np.zeros(n, dtype=bool)
        for d in range(3):
            if not self.periodic[d]:
                out |= (x[:, d] < self.lo[d]) | (x[:, d] > self.hi[d])
        nout = int(self.sim.comm.sum(int(out.sum())))
        if nout:
            tags = np.concatenate(self.sim.comm.allgather(atom.data["tag"][:n][out]))
            if self.lost_policy == "error":
                bad = ", ".join(str(t) for t in tags[:5])
                raise DemError(f"{nout} particle(s) left the box through a fixed boundary at step "
                               f"{self.sim.update.ntimestep} (ids {bad}{' ...' if len(tags) > 5 else ''})",
                               hint="use 'thermo_modify lost ignore' to delete them, or enclose the "
                                    "particles with walls / open boundaries (s or m)")
            if self.lost_policy == "warn":
                self.sim.warning(f"{nout} particle(s) lost at step {self.sim.update.ntimestep}")
            atom.keep(~out)
            self.nlost += nout
            atom.natoms -= nout
            self.sim.modify.particles_removed()

    def shrink_wrap(self):
        """Open (s, m) boundaries follow the particles; m never shrinks below the initial bound."""
        atom = self.sim.atom
        n = atom.nlocal
        x = atom.data["x"][:n]
        r = atom.data["radius"][:n]
        for d in range(3):
            for side, style in enumerate(self.boundary[d]):
                if style not in "sm":
                    continue
                # every rank takes part in the reduction, with or without particles
                if side == 0:
                    lo = self.sim.comm.min(float(np.min(x[:, d] - r)) if n else np.inf)
                    if np.isfinite(lo):
                        self.lo[d] = lo if style == "s" else min(lo, self.lo[d])
                else:
                    hi = self.sim.comm.max(float(np.max(x[:, d] + r)) if n else -np.inf)
                    if np.isfinite(hi):
                        self.hi[d] = hi if style == "s" else max(hi, self.hi[d])

    def unwrap(self, x, image):
        return x + image * self.prd
