"""Commands that choose the physics: pair_style and pair_coeff (contact model), fix and unfix
(integration, gravity, walls... applied every step)."""
from ..command import Command
from ..errors import DemError


class PairStyle(Command):
    """pair_style STYLE args

    Selects the contact model between particles (e.g. `pair_style sphere`); coefficients follow with
    pair_coeff."""
    style = "pair_style"
    usage = "style args"

    def __call__(self, words):
        a = self.args(words)
        a.need(1)
        cls = self.sim.registry.get("pair", a[0], a.words[1:])
        nb = self.sim.neighbor
        if self.sim.pair is not None:        # a replaced style takes its contact history with it
            for h in nb.histories:
                h.discard()
        nb.histories = []                    # the new style declares its own
        self.sim.pair = cls(self.sim, a.words[1:])


class PairCoeff(Command):
    """pair_coeff I J args

    Coefficients of the pair style for particle types I and J (ranges like * or 1*3 allowed)."""
    style = "pair_coeff"
    usage = "I J args"

    def __call__(self, words):
        if self.sim.pair is None:
            raise DemError("pair_coeff before pair_style")
        self.sim.domain.require_box("pair_coeff")
        self.sim.pair.coeff(words)


class FixCommand(Command):
    """fix ID GROUP STYLE args

    Adds an operation applied every step (integration, gravity, walls...). Redefining an ID replaces it."""
    style = "fix"
    usage = "ID group style args"

    def __call__(self, words):
        self.sim.domain.require_box("fix")
        self.sim.modify.add_fix(words)


class Unfix(Command):
    """unfix ID"""
    style = "unfix"
    usage = "ID"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        self.sim.modify.delete_fix(a[0])
