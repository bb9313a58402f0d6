"""Load balancing of MPI runs: the `balance` command (once) and `fix balance` (every N steps, on
neighbor-rebuild steps). Both shift the cuts of the processor grid along the chosen axes so that each slab
holds the same number of particles, or the same measured compute time (LAMMPS' shift style, with the cuts
found by a global bisection). Serial runs accept both and do nothing."""
from .command import Command
from .errors import DemError
from .fix import Fix, Stage


def parse_balance(a, start, what):
    """THRESH [shift DIMS [NITER STOPTHRESH]] [weight count|time] -> (thresh, dims, weight)."""
    thresh = a.float(start, "thresh", positive=True)
    if thresh < 1.0:
        raise a.error("the imbalance threshold must be >= 1 (max over average load)")
    dims, weight = "xyz", "count"
    i = start + 1
    while i < len(a):
        key = a[i]
        if key == "shift":
            if i + 1 >= len(a) or not a[i + 1] or any(c not in "xyz" for c in a[i + 1]):
                raise a.error("shift needs the axes to balance, e.g. 'shift x' or 'shift xyz'")
            dims = a[i + 1]
            i += 2
            # LAMMPS' NITER STOPTHRESH: accepted (the bisection here always converges)
            while i < len(a) and a[i] not in ("shift", "weight"):
                a.to_float(a[i], "shift parameter")
                i += 1
        elif key == "weight":
            if i + 1 >= len(a) or a[i + 1] not in ("count", "time"):
                raise a.error("weight must be 'count' (particles) or 'time' (measured compute time)")
            weight = a[i + 1]
            i += 2
        else:
            from .errors import did_you_mean
            raise a.error(f"unknown {what} keyword '{key}'{did_you_mean(key, ['shift', 'weight'])}")
    return thresh, dims, weight


class Balance(Command):
    """balance THRESH [shift DIMS [NITER STOPTHRESH]] [weight count|time]

    Moves the sub-box boundaries of an MPI run, once, when the imbalance (largest over average number of
    particles per rank, or compute time with `weight time`) exceeds THRESH: the cuts along DIMS (default
    xyz) are shifted so that every slab of the processor grid holds the same load, keeping sub-boxes at
    least one ghost cutoff wide. Example: `balance 1.1 shift x`. Does nothing in serial runs."""
    style = "balance"
    usage = "thresh [shift dims] [weight count|time]"

    def __call__(self, words):
        sim = self.sim
        a = self.args(words)
        a.need(1)
        thresh, dims, weight = parse_balance(a, 0, "balance")
        sim.domain.require_box("balance")
        if sim.comm.nprocs == 1:
            return
        before = sim.comm.balance(dims, weight, thresh)
        sim.comm.grid_settled = True        # the user placed the cuts: the first run keeps them
        if before > thresh:
            sim.comm.exchange()
        after = sim.comm.imbalance("count")
        sim.print(f"Balance: imbalance {before:.3f} -> {after:.3f} (particles per rank, max / average)")


class FixBalance(Fix):
    """fix ID group balance N THRESH [shift DIMS [NITER STOPTHRESH]] [weight count|time]

    Re-balances an MPI run (see the `balance` command) at the first neighbor rebuild at least N steps
    after the last check (and when a run starts), when the imbalance exceeds THRESH. `f_ID[imbalance]`
    is the imbalance found at the last check. Example: `fix lb all balance 1000 1.1 shift x weight time`.
    Does nothing in serial runs."""
    style = "balance"
    stages = Stage.PRE_EXCHANGE

    def __init__(self, sim, fid, group, args):
        super().__init__(sim, fid, group, args)
        from .args import Args
        a = Args(args, "fix ID group balance N THRESH [shift DIMS] [weight count|time]", f"fix {fid} balance")
        a.need(2)
        self.every = a.int(0, "N", positive=True)
        self.thresh, self.dims, self.weight = parse_balance(a, 1, "fix balance")
        self.last = None
        self.value = 1.0
        self.nbalance = 0

    def pre_exchange(self):
        sim = self.sim
        if sim.comm.nprocs == 1:
            return
        step = sim.update.ntimestep
        if self.last is not None and step - self.last < self.every:
            return
        self.last = step
        self.value = sim.comm.balance(self.dims, self.weight, self.thresh)
        if self.value > self.thresh:
            self.nbalance += 1

    def thermo(self):
        return {"imbalance": self.value, "nbalance": self.nbalance}


BALANCE_STYLES = [Balance, FixBalance]
__all__ = ["Balance", "FixBalance", "BALANCE_STYLES", "DemError"]
