"""Commands about the particles themselves: atom_style, atom_modify (memory sort) and group."""
import numpy as np

from ..args import parse_types
from ..command import Command
from ..errors import did_you_mean
from .box import find_region


class AtomStyle(Command):
    """atom_style sphere | rigid

    Every particle is a rigid body (position, velocity, angular velocity and momentum, orientation, mass,
    principal inertia, shape); the style is accepted for LAMMPS compatibility."""
    style = "atom_style"
    usage = "sphere"

    def __call__(self, words):
        a = self.args(words)
        a.need(1)
        a.done(1)
        if a[0] not in ("sphere", "rigid", "shape", "granular"):
            raise a.error(f"atom style '{a[0]}' is not supported (use sphere)")


class AtomModify(Command):
    """atom_modify [sort N BINSIZE] [map array|hash|yes]

    `sort N BINSIZE`: every N steps (on a neighbor-list rebuild) order particles by spatial bin so that
    neighbors are close in memory (default N = 1000, BINSIZE 0 = half the largest pair cutoff; N = 0
    turns sorting off). `map` is accepted for LAMMPS compatibility (ids are always mapped)."""
    style = "atom_modify"
    usage = "[sort N binsize] [map array]"

    def __call__(self, words):
        a = self.args(words)
        kw = a.keywords(0, {"sort": 2, "map": 1, "id": 1, "first": 1})
        if "sort" in kw:
            nb = self.sim.neighbor
            nb.sort_every = max(0, a.to_int(kw["sort"][0], "sort N"))
            nb.sort_binsize = a.to_float(kw["sort"][1], "sort binsize")
            if nb.sort_binsize < 0:
                raise a.error("sort binsize must be >= 0")


class GroupCommand(Command):
    """group ID region REGION-ID | type T... | id A[:B]... | subtract G1 G2... | union G... | intersect G... |
    delete | clear

    Example: `group top region upper`, `group big type 2 3`, `group first id 1:100`."""
    style = "group"
    usage = "ID region|type|id|subtract|union|intersect|delete|clear ..."

    def __call__(self, words):
        a = self.args(words)
        a.need(2)
        sim = self.sim
        name, how = a[0], a[1]
        atom = sim.atom
        n = atom.nlocal
        if how in ("delete", "clear"):
            a.exactly(2)
        if how == "delete":
            bit = sim.groups.bit(name)
            atom.data["mask"][:atom.nmax] &= ~bit
            return
        if how == "clear":
            atom.data["mask"][:atom.nmax] &= ~sim.groups.bit(name)
            return
        if name == "all":
            raise a.error("group 'all' cannot be redefined")
        if how == "region":
            a.exactly(3)
            sel = find_region(sim, a[2]).inside(atom.data["x"][:n])
        elif how == "type":
            types = sorted({t for w in a.words[2:] for t in parse_types(w, atom.ntypes)})
            sel = np.isin(atom.data["type"][:n], types)
        elif how == "id":
            sel = np.zeros(n, dtype=bool)
            tags = atom.data["tag"][:n]
            for w in a.words[2:]:
                lo, _, hi = w.partition(":")
                lo = a.to_int(lo, "id")
                hi = a.to_int(hi, "id") if hi else lo
                sel |= (tags >= lo) & (tags <= hi)
        elif how in ("subtract", "union", "intersect"):
            a.need(3)
            masks = [sim.groups.members(g) for g in a.words[2:]]
            if how == "subtract":
                sel = masks[0].copy()
                for m in masks[1:]:
                    sel &= ~m
            elif how == "union":
                sel = np.logical_or.reduce(masks)
            else:
                sel = np.logical_and.reduce(masks)
        else:
            raise a.error(f"unknown group style '{how}'"
                          f"{did_you_mean(how, ['region', 'type', 'id', 'subtract', 'union', 'intersect', 'delete', 'clear'])}")
        bit = sim.groups.find_or_create(name)
        atom.data["mask"][:n][sel] |= bit
        sim.print(f"group {name}: {sim.groups.count(name)} particles")
