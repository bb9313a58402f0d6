"""Restart files: the complete state between two steps (particles with every per-particle field, contact
and wall histories, neighbor-list reference positions, fix states, step and time), so that
`read_restart` + the same commands continue a run bitwise on one rank.

Particle order is kept as it is in memory (not sorted by id): the order in which forces are summed is
then the same as in the uninterrupted run. Layout and versions: docs/restart.md."""
import numpy as np

from . import restart_file
from .command import Command
from .errors import DemError
from .files import replace_file
from .interrupt import SIGNAL_STATE
from .shapes import command as shape_command

# 1: pickle, single-record history stores ({name}_n, _tag, _val); 2: pickle, keyed stores too
# ({name}_key); 3: HDF5 (restart_file); 4: the same with a whole-file checksum in a header (verified_file),
# checked before HDF5 opens the file. Pickles are refused: loading one can run any code. Version 3 files
# are refused too (HDF5 cannot read a damaged one safely): dem-convert-restart converts both.
VERSION = 4
PICKLE_VERSIONS = "1 or 2"


def write_restart(sim, path, use="write_restart"):
    atom = sim.atom
    for h in sim.neighbor.histories:
        h.pack()
    n = atom.nlocal
    keep = [name for name in atom.fields if name not in sim.tally.active]    # tallies: remade each step
    fields = {name: atom.data[name][:n].copy() for name in keep}
    nb = sim.neighbor
    state = {
        "step": sim.update.ntimestep, "time": sim.update.time, "dt": sim.update.dt,
        "time_anchor": list(sim.update.time_anchor),
        "lo": sim.domain.lo.copy(), "hi": sim.domain.hi.copy(), "boundary": sim.domain.boundary,
        "ntypes": atom.ntypes, "natoms": atom.natoms, "max_tag": atom.max_tag, "groups": sim.groups.names,
        "nlost": sim.domain.nlost,
        "fields": fields,
        "field_specs": {k: (v[0], v[1].str, v[2], v[3]) for k, v in atom.fields.items() if k in keep},
        "neighbor": {"xhold": nb.xhold.copy() if nb.hold_valid else None, "last_build": nb.last_build,
                     "last_sort": nb.last_sort, "sort_every": nb.sort_every,
                     "skin": nb.skin, "every": nb.every, "delay": nb.delay, "check": nb.check},
        "fixes": {f.id: f.state() for f in sim.modify.fixes},
        "pair": sim.pair.state() if sim.pair is not None else {},
        "shapes": [list(w) for w in sim.shapes.definitions],
    }
    state = sim.comm.gather_restart(state)
    if sim.comm.me == 0:
        replace_file(path, lambda tmp: restart_file.write(tmp, state, VERSION), use)


def load(path, comm=None):
    """The state of a restart file of the current version, checked; a DemError naming the file for any
    other file (an old pickle restart is recognised by its first byte and never loaded). Under MPI
    (`comm`) rank 0 checks the whole file, then every rank reads it."""
    version = restart_file.file_version(path, comm)
    if version != VERSION:
        found = PICKLE_VERSIONS if version is None else version
        raise DemError(f"read_restart: '{path}' is a dem restart file of version {found}; this dem reads "
                       f"version {VERSION} only" + (" (old pickle restarts are not loaded: they could run "
                                                    "code)" if version is None else ""),
                       hint=restart_file.CONVERT_HINT if version is None or version < VERSION else None)
    state = restart_file.read(path, checked=True)
    restart_file.validate(state, path)
    return state


def read_restart(sim, path):
    state = load(path, sim.comm)
    if sim.domain.box_exist:
        raise DemError("read_restart: the box already exists (read_restart creates it)")
    shape_command.check_restart(sim, state.get("shapes") or [])
    dom, atom, up, nb = sim.domain, sim.atom, sim.update, sim.neighbor
    dom.set_boundary(["".join(b) if b[0] != b[1] else b[0] for b in state["boundary"]])
    dom.set_box(state["lo"], state["hi"])
    dom.nlost = state["nlost"]
    atom.ntypes = state["ntypes"]
    for name in state["groups"]:
        sim.groups.find_or_create(name)
    up.ntimestep = state["step"]
    if up.dt is None or up.dt == state["dt"]:      # the restart's dt: its time goes on as it would have
        up.dt = state["dt"]
        up.time_anchor = state["time_anchor"]
    else:                                          # the script's own dt, from the restart's time on
        up.time = state["time"]
    fields, xhold = sim.comm.scatter_restart(state)
    for name, values in fields.items():
        if name not in atom.fields:
            atom.pending[name] = values
    for name, (tail, dtype, fill, border) in state["field_specs"].items():
        if name in atom.pending:
            continue
        if name not in atom.fields:
            atom.add_field(name, tuple(tail), np.dtype(dtype), fill, border)
    atom.unpack({k: v for k, v in fields.items() if k in atom.fields})
    atom.natoms, atom.max_tag = state["natoms"], state["max_tag"]
    ninfo = state["neighbor"]
    nb.skin, nb.every, nb.delay, nb.check = ninfo["skin"], ninfo["every"], ninfo["delay"], ninfo["check"]
    if xhold is not None and len(xhold) == atom.nlocal:
        nb.xhold = xhold
        nb.hold_valid = True
        nb.last_build = ninfo["last_build"]
        nb.last_sort, nb.sort_every = ninfo["last_sort"], ninfo["sort_every"]
    else:
        nb.invalidate()
    if state.get("shapes"):           # the shape table, unless the script defined the same already
        shape_command.rebuild(sim, state["shapes"])
    sim.modify.restart_states = dict(state["fixes"])
    sim.restart_pair_state = state["pair"]
    sim.print(f"Read restart {path}: {atom.natoms} particles at step {up.ntimestep}")


class WriteRestart(Command):
    """write_restart FILE

    Writes the complete state (see read_restart). The file is written to a temporary name and renamed, so
    an interrupted write never leaves a broken restart (nor the temporary file); SIGINT/SIGTERM wait
    for the end of the write. The log's or a dump's file is refused."""
    style = "write_restart"
    usage = "file"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        self.sim.domain.require_box("write_restart")
        self.sim.output.check_restart_name(a[0], "write_restart")
        with SIGNAL_STATE.deferred():      # a signal waits for the whole file (and every rank)
            write_restart(self.sim, a[0])


class ReadRestart(Command):
    """read_restart FILE

    Restores box, particles (all fields, contact and wall histories), shapes, step, time, time step and
    neighbor state; fixes defined afterwards with the same IDs take their saved state back. Pair style,
    coefficients and fixes are re-specified by the script, as in LAMMPS; shapes are not (shapes defined
    before read_restart must be the restart's, the same in the same order, else an error names both).
    With the same commands, the continued run is bitwise identical to the uninterrupted one on one rank."""
    style = "read_restart"
    usage = "file"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        read_restart(self.sim, a[0])


class Restart(Command):
    """restart N FILE [FILE2]

    Writes a restart every N steps (0 turns it off); `*` in the name is replaced by the step, two files
    alternate. The log's or a dump's file is refused (as by write_restart)."""
    style = "restart"
    usage = "N file [file2]"

    def __call__(self, words):
        a = self.args(words)
        a.need(1)
        every = a.int(0, "N", nonneg=True)
        a.done(3)
        if every:
            a.need(2)
        self.sim.output.set_restart(every, a.words[1:3])


RESTART_COMMANDS = [WriteRestart, ReadRestart, Restart]
