"""read_data: LAMMPS data files of spheres (atom_style sphere), so LAMMPS/LIGGGHTS set-ups load as
they are."""
import numpy as np

from .command import Command
from .errors import DemError

HEADER_KEYS = {"atoms": "natoms", "atom types": "ntypes"}


class ReadData(Command):
    """read_data FILE

    Reads a LAMMPS data file with `atom_style sphere` lines (`id type diameter density x y z [ix iy iz]`)
    and an optional `Velocities` section (`id vx vy vz wx wy wz`). The box comes from the header
    (`xlo xhi` ...); set `boundary` before. Example: `read_data bed_8000.data`."""
    style = "read_data"
    usage = "file"

    def __call__(self, words):
        a = self.args(words)
        a.need(1)
        sim = self.sim
        if sim.domain.box_exist:
            raise a.error("the box already exists (read_data creates it)")
        path = a[0]
        try:
            with open(path) as fh:
                lines = fh.read().splitlines()
        except OSError as e:
            raise DemError(f"read_data: cannot open '{path}': {e.strerror}") from None
        header, sections = self.parse(path, lines)
        lo = [header.get(f"{d}lo", 0.0) for d in "xyz"]
        hi = [header.get(f"{d}hi", 1.0) for d in "xyz"]
        sim.domain.set_box(lo, hi)
        sim.atom.ntypes = int(header.get("ntypes", 1))
        if "Atoms" not in sections:
            raise DemError(f"read_data {path}: no Atoms section")
        rows = sections["Atoms"]
        natoms = int(header.get("natoms", len(rows)))
        if len(rows) != natoms:
            raise DemError(f"read_data {path}: header says {natoms} atoms, Atoms section has {len(rows)}")
        try:
            data = np.array([[float(w) for w in r[:10]] + [0.0] * (10 - len(r[:10])) for r in rows])
        except ValueError as e:
            raise DemError(f"read_data {path}: bad number in Atoms section ({e})") from None
        if data.shape[1] < 7 or any(len(r) < 7 for r in rows):
            raise DemError(f"read_data {path}: Atoms lines need 'id type diameter density x y z' (sphere)")
        tags = data[:, 0].astype(np.int64)
        radius = 0.5 * data[:, 2]
        if np.any(radius <= 0):
            raise DemError(f"read_data {path}: diameters must be > 0 (point particles are not supported)")
        rmass = data[:, 3] * 4.0 / 3.0 * np.pi * radius ** 3
        types = data[:, 1].astype(np.int64)
        if np.any(types < 1) or np.any(types > sim.atom.ntypes):
            raise DemError(f"read_data {path}: particle type out of range 1..{sim.atom.ntypes}")
        v, omega = np.zeros((len(tags), 3)), np.zeros((len(tags), 3))
        if "Velocities" in sections:
            vel = np.array([[float(w) for w in r[:7]] for r in sections["Velocities"]])
            index = {t: k for k, t in enumerate(tags)}
            for row in vel:
                k = index.get(int(row[0]))
                if k is None:
                    raise DemError(f"read_data {path}: velocity for unknown atom id {int(row[0])}")
                v[k] = row[1:4]
                omega[k] = row[4:7]
        mine = sim.comm.owned_mask(data[:, 4:7])     # every rank reads the file and keeps its sub-box
        sim.atom.add(data[mine, 4:7], radius[mine], rmass[mine], data[mine, 1].astype(np.int32),
                     tags=tags[mine], image=data[mine, 7:10].astype(np.int32), v=v[mine], omega=omega[mine])
        sim.atom.max_tag = max(sim.atom.max_tag, int(tags.max()) if len(tags) else 0)
        sim.atom.natoms += len(tags)
        sim.neighbor.invalidate()
        sim.print(f"Read {len(tags)} particles from {path}")

    def parse(self, path, lines):
        header, sections = {}, {}
        i = 1   # first line is a title
        current = None
        while i < len(lines):
            line = lines[i].split("#")[0].strip()
            i += 1
            if not line:
                continue
            words = line.split()
            if words[0][0].isalpha():
                current = words[0]
                sections[current] = []
                continue
            if current is None:
                self.header_line(path, i, words, header)
            else:
                sections[current].append(words)
        return header, sections

    def header_line(self, path, lineno, words, header):
        text = " ".join(words)
        for key, name in HEADER_KEYS.items():
            if text.endswith(key) and len(words) == len(key.split()) + 1:
                header[name] = int(words[0])
                return
        for d in "xyz":
            if text.endswith(f"{d}lo {d}hi"):
                header[f"{d}lo"], header[f"{d}hi"] = float(words[0]), float(words[1])
                return
        if text.endswith("xy xz yz"):
            raise DemError(f"read_data {path}:{lineno}: triclinic boxes are not supported")
        # other header lines (bonds, angles ...) are irrelevant to granular spheres
