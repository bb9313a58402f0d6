"""Computes: global quantities evaluated on demand, by thermo (`c_ID`, `c_ID[k]`), equal-style variables
and output fixes (e.g. `fix print/series`). A compute never changes the simulation.

    compute ID group-ID style args ...
    uncompute ID

A compute class sets `style`, and implements `compute_scalar()` (when `has_scalar`) and/or
`compute_vector()` returning `size_vector` values (`vector_names` name them, 1-based `c_ID[k]` picks
one). `init()` runs before each evaluation that follows a change of run (resolve fix references there).
Values are cached per time step while a run is going on, so that several thermo columns of one vector
cost one evaluation. Every rank calls a compute (reductions go through `sim.comm`).

Computes live in `sim.computes` (a dict id -> compute, in definition order).
"""
import re

from .args import Args
from .command import Command
from .errors import DemError, did_you_mean, unknown

_INDEXED = re.compile(r"^c_([^\[\]]+)(?:\[(\d+)\])?$")


class Compute:
    """compute ID group-ID style args ..."""

    kind = "compute"
    style = None
    usage = ""
    has_scalar = True
    size_vector = 0
    vector_names = ()
    tallies = ()          # per-particle contact tallies read (dem/tally.py: "stress", "types", "count")
    coords = None         # the coordinate of each vector element where it has one (rdf: r), else None
    scalar_quantity = None    # (quantity, unit) of c_ID, for plot labels (dem/quantities.py)
    vector_quantities = ()    # the same of c_ID[k], k = 1.. (fewer or none: not declared)

    def __init__(self, sim, cid, group, args):
        self.sim = sim
        self.id = cid
        self.group = group
        self.groupbit = sim.groups.bit(group)
        self.args = list(args)
        self._cache = {}

    def parser(self):
        return Args(self.args, f"compute ID group {self.style} {self.usage}".strip(),
                    f"compute {self.id} {self.style}")

    def init(self):
        pass

    def compute_scalar(self):
        raise DemError(f"compute {self.id} ({self.style}) has no scalar value")

    def compute_vector(self):
        raise DemError(f"compute {self.id} ({self.style}) has no vector")

    # ----- cached access --------------------------------------------------------------------------
    def _key(self):
        up = self.sim.update
        return (up.ntimestep, up.time) if up.running else None

    def _cached(self, what, func):
        key = self._key()
        hit = self._cache.get(what)
        if key is not None and hit is not None and hit[0] == key:
            return hit[1]
        if self._cache.get("run") != self.sim.update.first_step or key is None:
            self.init()
            self._cache["run"] = self.sim.update.first_step
        value = func()
        self._cache[what] = (key, value)
        return value

    def scalar(self):
        if not self.has_scalar:
            raise DemError(f"compute {self.id} ({self.style}) has no scalar value: use c_{self.id}[k], "
                           f"k = 1..{self.size_vector}")
        return float(self._cached("scalar", self.compute_scalar))

    def vector(self):
        if not self.size_vector:
            raise DemError(f"compute {self.id} ({self.style}) has no vector: use c_{self.id}")
        return self._cached("vector", self.compute_vector)

    def value(self, index=None):
        """Scalar (index None) or vector element `index` (1-based)."""
        if index is None:
            return self.scalar()
        if not 1 <= index <= self.size_vector:
            raise DemError(f"c_{self.id}[{index}]: index out of range 1..{self.size_vector}"
                           + (f" ({', '.join(self.vector_names)})" if self.vector_names else ""))
        return float(self.vector()[index - 1])

    def quantity(self, index=None):
        """(quantity, unit) of c_ID (index None) or c_ID[index], or None where not declared."""
        if index is None:
            return self.scalar_quantity if self.has_scalar else None
        return self.vector_quantities[index - 1] if 0 < index <= len(self.vector_quantities) else None

    def group_mask(self, n=None):
        atom = self.sim.atom
        n = atom.nlocal if n is None else n
        return (atom.data["mask"][:n] & self.groupbit) != 0


def find_compute(sim, cid):
    table = sim.computes
    if cid not in table:
        raise unknown("compute ID", cid, table)
    return table[cid]


def thermo_value(sim, name):
    """Value of the thermo keyword `c_ID` or `c_ID[k]`."""
    m = _INDEXED.match(name)
    if not m:
        raise DemError(f"bad compute reference '{name}': use c_ID or c_ID[k]")
    return find_compute(sim, m.group(1)).value(int(m.group(2)) if m.group(2) else None)


class ComputeCommand(Command):
    """compute ID group-ID style args ...

    Defines a compute: a global value (scalar and/or vector) evaluated when thermo, a variable or an
    output fix asks for it: `thermo_style custom step c_ID c_ID[2]`. Redefining an ID is an error
    (uncompute it first)."""
    style = "compute"
    usage = "ID group style args"

    def __call__(self, words):
        a = self.args(words)
        a.need(3)
        cid, group, style = a[0], a[1], a[2]
        table = self.sim.computes
        if cid in table:
            raise a.error(f"compute ID '{cid}' already exists (uncompute it first)")
        if not re.match(r"^[A-Za-z0-9_]+$", cid):
            raise a.error(f"compute ID '{cid}' may contain only letters, digits and underscores")
        cls = self.sim.registry.get("compute", style, a.words[3:])
        table[cid] = cls(self.sim, cid, group, a.words[3:])


class Uncompute(Command):
    """uncompute ID

    Deletes a compute."""
    style = "uncompute"
    usage = "ID"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        table = self.sim.computes
        if a[0] not in table:
            raise a.error(f"unknown compute ID '{a[0]}'{did_you_mean(a[0], table)}")
        del table[a[0]]


COMMANDS = [ComputeCommand, Uncompute]
