"""Thermodynamic output: one line every N steps with global quantities, and the keyword values used by
equal-style variables. Kinetic energies use the stored (half-step) velocities, as Grains3D does; `etotal`
is time-centred instead (full-step velocities and the elastic energy of the same force evaluation) so
that energy conservation can be checked to round-off of the scheme."""
import array
import math

import numpy as np

from .errors import DemError, did_you_mean
from .quantities import THERMO

DEFAULT_STYLE = ["step", "time", "atoms", "ke", "erot", "contacts", "cn", "maxov", "pct", "tps", "eta"]
INT_KEYWORDS = {"step", "atoms", "contacts", "lost", "nbuild"}


def quat_to_matrix(q):
    """Rotation matrices (n, 3, 3) from unit quaternions (n, 4) (w, x, y, z): body -> space."""
    w, x, y, z = q[:, 0], q[:, 1], q[:, 2], q[:, 3]
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], axis=-1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], axis=-1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=-1)], axis=1)


class Thermo:
    def __init__(self, sim):
        self.sim = sim
        self.every = 0
        self.style = list(DEFAULT_STYLE)
        self.float_format = "{:.6g}"
        self.header_printed_for = None
        self.history = []          # [style, array of its lines' values] per stretch of one thermo_style

    # ----- values ---------------------------------------------------------------------------------
    def _ke(self, synchronised=False):
        atom = self.sim.atom
        n = atom.nlocal
        v = atom.data["v"][:n]
        m = atom.data["rmass"][:n]
        if synchronised:
            v = v + self.sim.update.vsync * atom.data["f"][:n] / m[:, None]
        return self.sim.comm.sum(0.5 * float(np.dot(m, np.einsum("ij,ij->i", v, v))))

    def _erot(self, synchronised=False):
        atom = self.sim.atom
        n = atom.nlocal
        w = atom.data["omega"][:n]
        inertia = atom.data["inertia"][:n]
        if synchronised:
            w = w + self.sim.update.vsync * atom.data["torque"][:n] / np.where(inertia > 0, inertia, 1.0)
        shaped = atom.data["shape"][:n] >= 0
        e = 0.5 * float(np.sum(inertia[~shaped, 0] * np.einsum("ij,ij->i", w[~shaped], w[~shaped])))
        if shaped.any():
            rot = quat_to_matrix(atom.data["quat"][:n][shaped])
            wb = np.einsum("nji,nj->ni", rot, w[shaped])
            e += 0.5 * float(np.sum(inertia[shaped] * wb * wb))
        return self.sim.comm.sum(e)

    def _pe(self):
        """Elastic energy stored in every contact: particle pairs and walls."""
        sim = self.sim
        e = sim.pair.energy if sim.pair is not None else 0.0
        e += sum(getattr(f, "energy", 0.0) for f in sim.modify.fixes)
        return sim.comm.sum(e)

    def keyword(self, name):
        sim = self.sim
        up, dom, atom, pair = sim.update, sim.domain, sim.atom, sim.pair
        if name.startswith("v_"):
            return sim.input.evaluate(f"v_{name[2:]}")
        if name.startswith("c_"):
            from .compute import thermo_value
            return thermo_value(sim, name)
        if name.startswith("f_"):
            values = sim.modify.thermo()
            if name in values:
                return values[name]
            raise DemError(f"unknown fix thermo value '{name}'{did_you_mean(name, values)}")
        simple = {
            "step": lambda: up.ntimestep,
            "time": lambda: up.time,
            "dt": lambda: up.dt or 0.0,
            "atoms": lambda: atom.natoms,
            "ke": lambda: self._ke(),
            "erot": lambda: self._erot(),
            "pe": lambda: self._pe(),
            "etotal": lambda: self._ke(True) + self._erot(True) + self._pe(),
            "contacts": lambda: sim.comm.sum(pair.ncontacts) if pair else 0,
            "cn": lambda: (2.0 * sim.comm.sum(pair.ncontacts) / atom.natoms) if (pair and atom.natoms) else 0.0,
            "maxov": lambda: sim.comm.max(pair.max_overlap) if pair else 0.0,
            "lost": lambda: dom.nlost,
            "nbuild": lambda: sim.neighbor.nbuilds,
            "xlo": lambda: dom.lo[0], "xhi": lambda: dom.hi[0],
            "ylo": lambda: dom.lo[1], "yhi": lambda: dom.hi[1],
            "zlo": lambda: dom.lo[2], "zhi": lambda: dom.hi[2],
            "lx": lambda: dom.prd[0], "ly": lambda: dom.prd[1], "lz": lambda: dom.prd[2],
            "vol": lambda: dom.volume,
            "pct": lambda: 100.0 * up.progress()[0],
            "tps": lambda: up.progress()[1],
            "eta": lambda: up.progress()[2],
            "jpct": lambda: sim.job.progress()[0],
            "jeta": lambda: sim.job.progress()[1],
            "cpu": lambda: up.elapsed(),
            "spcpu": lambda: up.progress()[1],                     # the LAMMPS names
            "tpcpu": lambda: up.progress()[1] * (up.dt or 0.0),
            "cpuremain": lambda: up.progress()[2],
        }
        if name in THERMO:                 # the table of keywords and their units (dem/quantities.py)
            return simple[name]()
        raise DemError(f"unknown thermo keyword '{name}'{did_you_mean(name, list(THERMO))}")

    def check_style(self, words):
        for w in words:
            if w.startswith(("v_", "f_", "c_")):
                continue
            if w not in THERMO:
                self.keyword(w)   # raises with a suggestion

    # ----- lines ----------------------------------------------------------------------------------
    def _format(self, name, value):
        if name in INT_KEYWORDS:
            return f"{int(value):>10d}"
        if name in ("pct", "jpct"):
            return f"{value:>6.1f}"
        if name == "eta":
            return f"{'-' if not math.isfinite(value) else f'{value:.0f}s':>7}"
        if name == "jeta":             # seconds, no unit: a number (or nan) for the readers of the columns
            return f"{value:>7.0f}"
        return f"{self.float_format.format(value):>13}"

    def header(self):
        cols = []
        for name in self.style:
            width = 10 if name in INT_KEYWORDS else 6 if name in ("pct", "jpct") else \
                7 if name in ("eta", "jeta") else 13
            cols.append(f"{name:>{width}}")
        note = self.sim.job.note(self.style)      # of this run or of the whole job
        if note:
            self.sim.print(note)
        self.sim.print(" ".join(cols))

    def line(self):
        values = [float(self.keyword(n)) for n in self.style]
        style = tuple(self.style)
        if not self.history or self.history[-1][0] != style:
            self.history.append([style, array.array("d")])       # 8 bytes a value: thermo 1 runs long
        self.history[-1][1].extend(values)
        self.sim.print(" ".join(self._format(n, v) for n, v in zip(self.style, values)))

    def columns(self):
        """The thermo lines printed so far as {keyword: array}, one entry per line (NaN in the lines
        whose thermo_style lacked the keyword), keywords in the order they first appeared."""
        names = list(dict.fromkeys(n for style, _ in self.history for n in style))
        blocks = [np.array(values, dtype=np.float64).reshape(-1, len(style)) for style, values in self.history]
        nlines = sum(len(b) for b in blocks)
        table = {n: np.full(nlines, np.nan) for n in names}
        row = 0
        for (style, _), block in zip(self.history, blocks):
            for k, n in enumerate(style):
                table[n][row:row + len(block)] = block[:, k]
            row += len(block)
        return table
