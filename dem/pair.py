"""Base class of pair styles (contact geometry + contact law between particles)."""
from .errors import DemError


class Pair:
    """pair_style style args ...

    A pair style finds contacts among the neighbor list's pairs and applies the contact law.
    `compute(advance)` adds forces and torques (on owned particles and ghosts; the core adds ghost
    contributions to their owners) and, when `advance` is False (a setup or `run 0` pass), must leave
    every contact history unchanged. After each compute: `ncontacts` (owned contacts), `max_overlap`
    (largest overlap divided by the smaller diameter), `energy` (elastic energy stored in contacts).
    `reach`, set by `init`, is how far beyond touch a contact may still act (a cohesive law's pull-off
    distance): the neighbor list adds it to every pair's cutoff."""

    kind = "pair"
    style = None
    tallies = ()          # per-particle contact tallies its kernel can fill (dem/tally.py)
    reach = 0.0

    def __init__(self, sim, args):
        self.sim = sim
        self.args = list(args)
        self.ncontacts = 0
        self.max_overlap = 0.0
        self.energy = 0.0

    def coeff(self, args):
        raise DemError(f"pair style {self.style} takes no pair_coeff")

    def init(self):
        pass

    def compute(self, advance=True):
        raise NotImplementedError

    def state(self):
        return {}

    def restore(self, state):
        pass

    def min_contact_time(self):
        """Shortest contact duration of any type pair (for the time-step warning), or None."""
        return None
