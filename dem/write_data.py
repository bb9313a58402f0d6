"""write_data: the particles as a LAMMPS data file (atom_style sphere), so a dem state goes back to
LAMMPS/LIGGGHTS, and comes back to dem through read_data with shaped particles intact."""
import math

import numpy as np

from .shapes import command as shape_command
from .command import Command
from .files import atomic_write
from .interrupt import SIGNAL_STATE


def _num(value):
    """The shortest text that reads back as the same float64 (repr), as LAMMPS reads it (C strtod)."""
    return repr(float(value))


def write_data(sim, path):
    """Write the data file `path` (rank 0 writes; every rank takes part in the gather)."""
    names = ("tag", "type", "radius", "rmass", "x", "image", "v", "omega", "quat", "shape")
    arrays = {name: sim.gather(name) for name in names}
    if sim.comm.me != 0:
        return
    d = arrays
    n = len(d["tag"])
    shaped = d["shape"] >= 0
    vol = shape_command.volume(sim, d["shape"], d["radius"])
    density = d["rmass"] / vol
    # spheres: the diameter; shaped particles: the diameter of the sphere of equal volume (and mass)
    diameter = np.where(shaped, 2.0 * np.cbrt(vol * 3.0 / (4.0 * math.pi)), 2.0 * d["radius"])
    t = sim.shapes
    dom, up = sim.domain, sim.update
    lines = [f"LAMMPS data file via write_data, dem, timestep = {up.ntimestep}, time = {_num(up.time)}, "
             f"units = si", "", f"{n} atoms", f"{sim.atom.ntypes} atom types", ""]
    for k, dim in enumerate("xyz"):
        lines.append(f"{_num(dom.lo[k])} {_num(dom.hi[k])} {dim}lo {dim}hi")
    if len(t):
        lines.append("")
        lines.append("# dem shapes (define them with these commands before read_data):")
        for name, words in zip(t.names, t.definitions):
            lines.append(f"# shape {' '.join(str(w) for w in words)}")
    lines += ["", "Atoms # sphere", ""]
    identity = np.all(d["quat"] == np.array([1.0, 0.0, 0.0, 0.0]), axis=1)
    for k in range(n):
        x = d["x"][k]
        img = d["image"][k]
        row = (f"{d['tag'][k]} {d['type'][k]} {_num(diameter[k])} {_num(density[k])} "
               f"{_num(x[0])} {_num(x[1])} {_num(x[2])} {img[0]} {img[1]} {img[2]}")
        extra = []
        if shaped[k]:
            s = d["shape"][k]
            extra.append(f"shape {t.names[s]} scale {_num(d['radius'][k] / t.radius[s])}")
        if shaped[k] or not identity[k]:
            extra.append("quat " + " ".join(_num(q) for q in d["quat"][k]))
        lines.append(row + (" # " + " ".join(extra) if extra else ""))
    lines += ["", "Velocities", ""]
    for k in range(n):
        v, w = d["v"][k], d["omega"][k]
        lines.append(f"{d['tag'][k]} " + " ".join(_num(c) for c in (*v, *w)))
    atomic_write(path, "\n".join(lines) + "\n", "write_data")


class WriteData(Command):
    """write_data FILE

    Writes the particles as a LAMMPS data file that LAMMPS and LIGGGHTS read with `atom_style sphere`
    (`read_data FILE`), and that dem's read_data reads back: a title line, the header (`N atoms`,
    `T atom types`, `xlo xhi`, `ylo yhi`, `zlo zhi`), an `Atoms # sphere` section
    (`id type diameter density x y z ix iy iz`, ordered by id) and a `Velocities` section
    (`id vx vy vz wx wy wz`; dem's half-step velocities). Values are written with 17 significant digits,
    so read_data gives the same particles back. Units are SI.

    Shaped particles (see `shape`) are written for LAMMPS as the sphere of equal volume and mass
    (diameter of that sphere, the particle's density); dem's extras follow on the Atoms line after a `#`,
    which LAMMPS and LIGGGHTS ignore as a comment: `# shape NAME scale S quat W X Y Z` (the orientation
    is written for spheres too when it is not the identity). The header lists the `shape` commands of
    the shape table as comments: dem's read_data needs the shapes defined by name before it.
    Not written: contact and wall histories, fix states, the angular momentum (nve/shape recomputes it
    from the angular velocity): use write_restart to continue a dem run bitwise. The log's or a dump's
    file is refused. Example: `write_data bed.data`."""
    style = "write_data"
    usage = "file"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        self.sim.domain.require_box("write_data")
        self.sim.output.check_restart_name(a[0], "write_data")
        with SIGNAL_STATE.deferred():
            write_data(self.sim, a[0])
        self.sim.print(f"Wrote {self.sim.atom.natoms} particles to {a[0]}")
