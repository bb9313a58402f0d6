"""Computes of global bulk quantities: ke, erotate, coord, vmean (small styles kept together)."""
import numpy as np

from dem.compute import Compute
from dem.errors import DemError
from dem.thermo import quat_to_matrix

from ._common import find_drum


class ComputeKE(Compute):
    """compute ID group ke

    Translational kinetic energy sum 0.5 m v^2 of the group (J), from the stored half-step velocities as
    thermo `ke`. Example: `compute k all ke` then `thermo_style custom step c_k`."""

    style = "ke"
    scalar_quantity = ("translational kinetic energy", "J")

    def __init__(self, sim, cid, group, args):
        super().__init__(sim, cid, group, args)
        self.parser().exactly(0)

    def compute_scalar(self):
        atom = self.sim.atom
        n = atom.nlocal
        sel = self.group_mask()
        v = atom.data["v"][:n][sel]
        m = atom.data["rmass"][:n][sel]
        return self.sim.comm.sum(0.5 * float(np.dot(m, np.einsum("ij,ij->i", v, v))))


class ComputeERotate(Compute):
    """compute ID group erotate

    Rotational kinetic energy of the group (J): 0.5 I omega^2 for spheres, 0.5 sum_k I_k w_k^2 in the body
    frame for shaped particles."""

    style = "erotate"
    scalar_quantity = ("rotational kinetic energy", "J")

    def __init__(self, sim, cid, group, args):
        super().__init__(sim, cid, group, args)
        self.parser().exactly(0)

    def compute_scalar(self):
        atom = self.sim.atom
        n = atom.nlocal
        sel = self.group_mask()
        w = atom.data["omega"][:n][sel]
        inertia = atom.data["inertia"][:n][sel]
        shaped = atom.data["shape"][:n][sel] >= 0
        e = 0.5 * float(np.sum(inertia[~shaped, 0] * np.einsum("ij,ij->i", w[~shaped], w[~shaped])))
        if shaped.any():
            rot = quat_to_matrix(atom.data["quat"][:n][sel][shaped])
            wb = np.einsum("nji,nj->ni", rot, w[shaped])
            e += 0.5 * float(np.sum(inertia[shaped] * wb * wb))
        return self.sim.comm.sum(e)


class ComputeCoord(Compute):
    """compute ID group coord [points]

    Coordination number: the mean number of contacts per particle of the group, Z = sum_i c_i / N, c_i
    the particle-particle contacts of particle i at the last force evaluation (pair style; a pair touching
    at several points counts once) and N the group's particles; for group `all`, 2 C / N with C the
    contacts. `points`: c_i counts contact points instead, as Grains3D counts the contacts of glued
    composites (one per touching pair of pieces: two crosses touching at two beams count 2;
    polyhedron/multipoint: the points of each contact type; spheres and convex particles: 1 per contact).
    Vector: [Z, Z counting wall contacts too (sum_i c_i + W) / N, sum_i c_i / 2 (C for `all`), W], W the
    contacts of the wall fixes (every fix with a contact count: wall/plane, wall/drum, wall/mesh; all of
    them, whatever their group; one per wall contact also with `points`). A group other than `all`, and
    `points`, read the per-particle contact count (dem/tally.py), which every pair style fills."""

    style = "coord"
    size_vector = 4
    vector_names = ("Z", "Z_walls", "contacts", "wall_contacts")
    scalar_quantity = ("coordination number", "-")
    vector_quantities = (scalar_quantity, ("coordination number with walls", "-"), ("contacts", "-"),
                         ("wall contacts", "-"))

    def __init__(self, sim, cid, group, args):
        super().__init__(sim, cid, group, args)
        self.points = "points" in self.parser().keywords(0, {"points": 0})
        self.whole = group == "all" and not self.points
        self.tallies = () if self.whole else ("count",)

    def _counts(self):
        sim = self.sim
        w = sum(sim.comm.sum(getattr(f, "ncontacts", 0)) for f in sim.modify.fixes
                if isinstance(getattr(f, "ncontacts", None), int))
        if self.whole:
            c = sim.comm.sum(sim.pair.ncontacts) if sim.pair is not None else 0
            return 2.0 * c, w, sim.atom.natoms
        ends = sim.tally.get("count", f"compute {self.id} coord")[:, 1 if self.points else 0]
        sel = self.group_mask()
        return sim.comm.sum(float(ends[sel].sum())), w, sim.comm.sum(int(sel.sum()))

    def compute_scalar(self):
        ends, _, n = self._counts()
        return ends / n if n else 0.0

    def compute_vector(self):
        ends, w, n = self._counts()
        return np.array([ends / n if n else 0.0, (ends + w) / n if n else 0.0, 0.5 * ends, w], dtype=float)


class ComputeVMean(Compute):
    """compute ID group vmean [scale V | drum FIX-ID]

    Mean translational velocity magnitude <|v|> of the group, divided by V (default 1), or by Omega R of
    a drum (`drum FIX-ID`: the target rate of fix wall/drum times its radius: the dimensionless velocity
    of Part III Fig. 26). Vector: [<|v|>, <vx>, <vy>, <vz>, max |v|, rms |v|], all divided alike.
    Velocities are the stored half-step values."""

    style = "vmean"
    size_vector = 6
    vector_names = ("mean", "vx", "vy", "vz", "max", "rms")

    def __init__(self, sim, cid, group, args):
        super().__init__(sim, cid, group, args)
        a = self.parser()
        kw = a.keywords(0, {"scale": 1, "drum": 1})
        if "scale" in kw and "drum" in kw:
            raise a.error("give scale or drum, not both")
        self.scale = a.to_float(kw["scale"][0], "scale") if "scale" in kw else 1.0
        if self.scale <= 0:
            raise a.error("scale must be > 0")
        self.drum_id = kw["drum"][0] if "drum" in kw else None

    def quantity(self, index=None):
        what = ("mean speed", "mean vx", "mean vy", "mean vz", "largest speed", "rms speed")[(index or 1) - 1] \
            if (index or 1) <= self.size_vector else None
        if what is None:
            return None
        if self.drum_id is not None:
            return (f"{what} / (Omega R)", "-")
        return (what, "m/s") if self.scale == 1.0 else (f"{what} / {self.scale:g} m/s", "-")

    def _scale(self):
        if self.drum_id is None:
            return self.scale
        drum = find_drum(self.sim, self.drum_id, f"compute {self.id} vmean")
        s = abs(drum.omega_target) * drum.radius
        return s if s > 0 else 1.0

    def compute_vector(self):
        comm = self.sim.comm
        atom = self.sim.atom
        v = atom.data["v"][:atom.nlocal][self.group_mask()]
        speed = np.sqrt(np.einsum("ij,ij->i", v, v))
        n = comm.sum(len(v))
        if not n:
            return np.zeros(6)
        s = self._scale()
        sums = [comm.sum(float(speed.sum()))] + [comm.sum(float(v[:, d].sum())) for d in range(3)]
        vmax = comm.max(float(speed.max()) if len(speed) else 0.0)
        rms = np.sqrt(comm.sum(float(np.dot(speed, speed))) / n)
        return np.array([x / n for x in sums] + [vmax, rms]) / s

    def compute_scalar(self):
        return self.vector()[0]
