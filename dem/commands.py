"""Set-up commands: units, dimension, boundary, regions, the box, groups, settings of neighbor lists,
time step, thermo output, pair and fix definitions, dumps and run."""
import numpy as np

from .command import Command
from .errors import DemError


class Units(Command):
    """units si

    dem works in SI units (m, kg, s). `units si` is the default; other LAMMPS unit systems are refused
    rather than silently misread."""
    style = "units"
    usage = "si"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        if a[0] != "si":
            raise a.error(f"unit style '{a[0]}' is not supported; dem uses SI units (units si)")
        self.sim.units = "si"


class Dimension(Command):
    """dimension 3

    dem is three-dimensional (a 2D problem is a thin periodic slab)."""
    style = "dimension"
    usage = "3"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        if a[0] != "3":
            raise a.error("only 'dimension 3' is supported (model 2D as a thin periodic slab)")


class Boundary(Command):
    """boundary x y z

    Per axis: p (periodic), f (fixed: a particle leaving is lost), s (open, shrink-wrapped to the
    particles), m (open, shrink-wrapped but never smaller than the initial box); two letters give the
    lower and upper face separately, e.g. `boundary p p fm`. Default: p p p. Must come before the box."""
    style = "boundary"
    usage = "x y z (each p, f, s, m or a pair like fm)"

    def __call__(self, words):
        if self.sim.domain.box_exist:
            raise DemError("boundary must be set before the box is created")
        self.sim.domain.set_boundary(words)


class RegionCommand(Command):
    """region ID style args [side in|out]

    Styles: block, cylinder, sphere (see each region's documentation).
    Example: `region box block 0 0.02 0 0.02 0 0.04`."""
    style = "region"
    usage = "ID style args"

    def __call__(self, words):
        a = self.args(words)
        a.need(2)
        rid, style = a[0], a[1]
        if rid in self.sim.domain.regions:
            raise a.error(f"region ID '{rid}' already exists")
        cls = self.sim.registry.get("region", style)
        self.sim.domain.regions[rid] = cls(self.sim, rid, a.words[2:])


def find_region(sim, rid):
    if rid not in sim.domain.regions:
        from .errors import unknown
        raise unknown("region ID", rid, sim.domain.regions)
    return sim.domain.regions[rid]


class CreateBox(Command):
    """create_box NTYPES REGION-ID

    Creates the simulation box as the bounding box of a block region, with NTYPES particle types.
    Example: `create_box 1 box`."""
    style = "create_box"
    usage = "ntypes region-ID"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(2)
        if self.sim.domain.box_exist:
            raise a.error("the box already exists")
        ntypes = a.int(0, "ntypes", positive=True)
        region = find_region(self.sim, a[1])
        lo, hi = region.bbox()
        if np.any(np.abs(lo) >= 1e29) or np.any(np.abs(hi) >= 1e29):
            raise a.error("the region of the box must be bounded (no INF)")
        self.sim.domain.set_box(lo, hi)
        self.sim.atom.ntypes = ntypes


class AtomStyle(Command):
    """atom_style sphere | rigid

    Every particle is a rigid body (position, velocity, angular velocity and momentum, orientation, mass,
    principal inertia, shape); the style is accepted for LAMMPS compatibility."""
    style = "atom_style"
    usage = "sphere"

    def __call__(self, words):
        a = self.args(words)
        a.need(1)
        if a[0] not in ("sphere", "rigid", "shape", "granular"):
            raise a.error(f"atom style '{a[0]}' is not supported (use sphere)")


class Ignored(Command):
    """Accepted for LAMMPS compatibility and ignored (the behaviour is always what dem does)."""
    usage = "..."

    def __call__(self, words):
        pass


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


class CommModify(Ignored):
    """comm_modify vel yes: accepted for LAMMPS compatibility (ghosts always carry velocities)."""
    style = "comm_modify"


class Newton(Ignored):
    """newton on|off: accepted for LAMMPS compatibility (dem applies Newton's third law in half lists)."""
    style = "newton"


class Processors(Command):
    """processors Px Py Pz

    The grid of sub-boxes of an MPI run (Px x Py x Pz = number of ranks); `*` lets dem choose that
    factor (the grid with the least sub-box surface for the box shape). Example: `processors * * 1` for
    a bed under gravity along z. Must come before particles are created; serial runs only check it."""
    style = "processors"
    usage = "Px Py Pz"

    def __call__(self, words):
        a = self.args(words)
        a.need(3)
        grid = tuple(0 if w == "*" else a.int(k, f"P{'xyz'[k]}", positive=True) for k, w in
                     enumerate(a.words[:3]))
        if len(a) > 3:
            raise a.error(f"processors takes three values (Px Py Pz), got extra '{a[3]}'")
        self.sim.comm.set_processors(grid)


class Timestep(Command):
    """timestep DT

    The time step in seconds. A warning is printed when it exceeds T_c/10 of the stiffest, lightest
    contact."""
    style = "timestep"
    usage = "dt"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        self.sim.update.dt = a.float(0, "dt", positive=True)


class NeighborCommand(Command):
    """neighbor SKIN bin

    Skin distance added to the sum of bounding radii when listing pairs (default 0.1 x the largest
    diameter). Example: `neighbor 0.0001 bin`."""
    style = "neighbor"
    usage = "skin bin"

    def __call__(self, words):
        a = self.args(words)
        a.need(1)
        self.sim.neighbor.settings(a.float(0, "skin", nonneg=True))
        if len(a) > 1 and a[1] not in ("bin", "multi"):
            raise a.error(f"neighbor style '{a[1]}' is not supported (use bin)")


class NeighModify(Command):
    """neigh_modify [every N] [delay N] [check yes|no]

    Rebuild the list at most every N steps, not before `delay` steps since the last build, and (check
    yes, the default) only when a particle moved more than half the skin. Defaults: every 1 delay 0
    check yes."""
    style = "neigh_modify"
    usage = "[every N] [delay N] [check yes|no]"

    def __call__(self, words):
        a = self.args(words)
        kw = a.keywords(0, {"every": 1, "delay": 1, "check": 1, "once": 1, "page": 1, "one": 1})
        nb = self.sim.neighbor
        if "every" in kw:
            nb.every = max(1, a.to_int(kw["every"][0], "every"))
        if "delay" in kw:
            nb.delay = max(0, a.to_int(kw["delay"][0], "delay"))
        if "check" in kw:
            nb.check = a.yes_no(kw["check"][0], "check")


class ThermoCommand(Command):
    """thermo N

    Print a thermo line every N steps (0: only at the start and end of a run)."""
    style = "thermo"
    usage = "N"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        self.sim.output.thermo.every = a.int(0, "N", nonneg=True)


class ThermoStyle(Command):
    """thermo_style custom keyword ... | thermo_style one

    Keywords: step time dt atoms ke erot pe etotal contacts cn maxov lost nbuild xlo xhi ylo yhi zlo zhi
    lx ly lz vol cpu pct tps eta, v_NAME (equal-style variable), f_ID[name] (fix value), c_ID and c_ID[k]
    (compute value).
    `ke`/`erot` use the stored half-step velocities; `etotal` is time-centred (full-step kinetic energy
    plus the elastic energy of the same force evaluation). `contacts` counts particle-particle contacts,
    `cn` = 2 contacts / particles, `maxov` the largest overlap over the smaller diameter, and pct/tps/eta
    the progress of the run (percent, steps per second, seconds left).
    Default (`one`): step time atoms ke erot contacts cn maxov pct tps eta."""
    style = "thermo_style"
    usage = "custom keywords... | one"

    def __call__(self, words):
        from .thermo import DEFAULT_STYLE
        a = self.args(words)
        a.need(1)
        thermo = self.sim.output.thermo
        if a[0] == "one":
            thermo.style = list(DEFAULT_STYLE)
            return
        if a[0] != "custom":
            raise a.error(f"thermo style '{a[0]}' is not supported (use custom or one)")
        if len(a) < 2:
            raise a.error("thermo_style custom needs at least one keyword")
        thermo.check_style(a.words[1:])
        thermo.style = a.words[1:]


class ThermoModify(Command):
    """thermo_modify [lost error|warn|ignore] [overlap FRACTION] [format float FMT] [norm no] [flush yes]

    `lost`: what to do with a particle leaving through a fixed boundary (default error). `overlap`: stop
    the run when an overlap exceeds this fraction of the smaller diameter (default 0.2). `format float`:
    a Python or C format for float columns, e.g. %.8g."""
    style = "thermo_modify"
    usage = "[lost error|warn|ignore] [overlap F] [format float FMT] [norm no]"

    def __call__(self, words):
        a = self.args(words)
        i = 0
        while i < len(a):
            key = a[i]
            if key == "lost":
                if a[i + 1] not in ("error", "warn", "ignore"):
                    raise a.error("lost must be error, warn or ignore")
                self.sim.domain.lost_policy = a[i + 1]
                i += 2
            elif key == "overlap":
                self.sim.update.max_overlap_fraction = a.float(i + 1, "overlap", positive=True)
                i += 2
            elif key == "format":
                if a[i + 1] not in ("float", "line"):
                    raise a.error("use 'format float FORMAT'")
                fmt = a[i + 2]
                fmt = "{:" + fmt[1:] + "}" if fmt.startswith("%") else fmt
                try:
                    fmt.format(1.0)
                except (ValueError, IndexError):
                    raise a.error(f"bad format '{a[i + 2]}'") from None
                self.sim.output.thermo.float_format = fmt
                i += 3
            elif key in ("norm", "flush"):
                if key == "norm" and a.yes_no(a[i + 1], "norm"):
                    raise a.error("only 'norm no' is supported (extensive values)")
                i += 2
            else:
                from .errors import did_you_mean
                raise a.error(f"unknown keyword '{key}'{did_you_mean(key, ['lost', 'overlap', 'format', 'norm', 'flush'])}")


class PairStyle(Command):
    """pair_style STYLE args

    Selects the contact model between particles (e.g. `pair_style sphere`); coefficients follow with
    pair_coeff."""
    style = "pair_style"
    usage = "style args"

    def __call__(self, words):
        a = self.args(words)
        a.need(1)
        cls = self.sim.registry.get("pair", a[0])
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


class DumpCommand(Command):
    """dump ID GROUP STYLE N FILE [args]

    Styles: h5 (one HDF5 file + XDMF for ParaView), vtk (VTU frames + PVD). Example:
    `dump d1 all h5 1000 pour.h5`."""
    style = "dump"
    usage = "ID group style N file [args]"

    def __call__(self, words):
        self.sim.output.add_dump(words)


class Undump(Command):
    """undump ID"""
    style = "undump"
    usage = "ID"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        self.sim.output.undump(a[0])


class Run(Command):
    """run N

    Runs N time steps."""
    style = "run"
    usage = "N"

    def __call__(self, words):
        a = self.args(words)
        a.need(1)
        self.sim.update.run(a.int(0, "N", nonneg=True))


class ResetTimestep(Command):
    """reset_timestep N"""
    style = "reset_timestep"
    usage = "N"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        self.sim.update.ntimestep = a.int(0, "N", nonneg=True)
        self.sim.neighbor.invalidate()


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
            from .args import parse_types
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
            from .errors import did_you_mean
            raise a.error(f"unknown group style '{how}'"
                          f"{did_you_mean(how, ['region', 'type', 'id', 'subtract', 'union', 'intersect', 'delete', 'clear'])}")
        bit = sim.groups.find_or_create(name)
        atom.data["mask"][:n][sel] |= bit
        sim.print(f"group {name}: {sim.groups.count(name)} particles")


COMMANDS = [Units, Dimension, Boundary, RegionCommand, CreateBox, AtomStyle, AtomModify, CommModify, Newton,
            Processors, Timestep, NeighborCommand, NeighModify, ThermoCommand, ThermoStyle, ThermoModify,
            PairStyle, PairCoeff, FixCommand, Unfix, DumpCommand, Undump, Run, ResetTimestep, GroupCommand]
