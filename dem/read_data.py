"""read_data: LAMMPS data files of spheres (atom_style sphere), so LAMMPS/LIGGGHTS set-ups load as
they are. The whole file is read and checked before anything changes: a bad file leaves no box and no
particles behind."""
import math

import numpy as np

from .shapes import command as shape_command
from .args import integer, number
from .command import Command
from .commands.box import MAX_TYPES
from .errors import DemError

HEADER_KEYS = {"atoms": "natoms", "atom types": "ntypes"}
# sections dem reads; any other (Bonds, Angles, Pair Coeffs ...) is refused rather than skipped
SECTIONS = ("Atoms", "Velocities", "Masses")
ATOM_COLUMNS = (7, 10)      # id type diameter density x y z [ix iy iz]
MAX_TAG = 2 ** 63 - 1       # ids are int64
MAX_IMAGE = 2 ** 31 - 1     # image flags are int32


class ReadData(Command):
    """read_data FILE

    Reads a LAMMPS data file with `atom_style sphere` lines (`id type diameter density x y z [ix iy iz]`)
    and an optional `Velocities` section (`id vx vy vz wx wy wz`). The box comes from the header
    (`xlo xhi` ...); set `boundary` before. Example: `read_data bed_8000.data`.
    Every value is checked: ids unique positive integers, types integers in 1..ntypes, diameters and
    densities finite and > 0, one Velocities line per listed id at most. An `Atoms # STYLE` comment
    other than sphere, a section other than Atoms, Velocities and Masses (ignored: masses come from
    diameter and density) or a text that is not UTF-8 is an error.
    Shaped particles (dem's extras, as write_data writes them): an Atoms line ending in
    `# shape NAME scale S quat W X Y Z` is a particle of shape NAME at scale S (its bounding radius S
    times the shape's; the diameter column is then not used, the mass is density x volume), with that
    orientation (`quat` alone orients a sphere). The shapes must be defined (`shape NAME KIND ...`)
    before read_data; when none is, the `# shape ...` comment lines of the header define them. Other
    comments are ignored, as LAMMPS does."""
    style = "read_data"
    usage = "file"

    def __call__(self, words):
        a = self.args(words)
        a.exactly(1)
        sim = self.sim
        if sim.domain.box_exist:
            raise a.error("the box already exists (read_data creates it)")
        path = a[0]
        try:
            with open(path, encoding="utf-8") as fh:
                lines = fh.read().splitlines()
        except OSError as e:
            raise DemError(f"read_data: cannot open '{path}': {e.strerror}") from None
        except UnicodeDecodeError:
            raise DemError(f"read_data: '{path}' is not a text (UTF-8) data file") from None
        d = DataFile(path, lines)
        atoms = d.atoms()
        d.check_inside(atoms, sim.domain.boundary)
        v, omega = d.velocities(atoms["tags"])
        if "Masses" in d.sections:
            sim.warning(f"read_data {path}: Masses section ignored (masses come from diameter and density)")
        shapes_before = sim.shapes
        try:
            shaped = d.shapes(sim, atoms)
        except DemError:
            sim.shapes = shapes_before      # nothing half-made: not even the shape table
            raise
        # everything checked: now the box and the particles
        sim.domain.set_box(d.lo, d.hi)
        sim.atom.ntypes = d.ntypes
        tags, x = atoms["tags"], atoms["x"]
        mine = sim.comm.owned_mask(x)     # every rank reads the file and keeps its sub-box
        s = sim.atom.add(x[mine], atoms["radius"][mine], atoms["rmass"][mine], atoms["types"][mine],
                         tags=tags[mine], image=atoms["image"][mine], v=v[mine], omega=omega[mine])
        rows = np.arange(s.start, s.stop)
        for k_all, k in zip(np.flatnonzero(mine), rows):
            if atoms["quat"][k_all] is not None:
                q = atoms["quat"][k_all]
                sim.atom.data["quat"][k] = q / np.linalg.norm(q)
        for index in sorted(set(shaped[mine]) - {-1}):
            sel = shaped[mine] == index
            shape_command.assign(sim, rows[sel], int(index), atoms["scale"][mine][sel],
                                 density=atoms["density"][mine][sel])
        sim.atom.max_tag = max(sim.atom.max_tag, int(tags.max()) if len(tags) else 0)
        sim.atom.natoms += len(tags)
        sim.neighbor.invalidate()
        sim.print(f"Read {len(tags)} particles from {path}")


class DataFile:
    """The header and sections of a data file; every error names `file:line`."""

    def __init__(self, path, lines):
        self.path = path
        self.header = {}
        self.sections = {}      # name -> [(line number, words)]
        self.comments = {}      # line number -> the comment of a section line (dem's extras)
        self.shape_commands = []    # `# shape NAME KIND ...` header comments (written by write_data)
        current = None
        for lineno, raw in enumerate(lines[1:], 2):     # the first line is a title
            text, _, comment = raw.partition("#")
            words = text.split()
            if not words:
                if current is None and comment.split()[:1] == ["shape"]:
                    self.shape_commands.append((lineno, comment.split()[1:]))
                continue
            if words[0][0].isalpha():
                current = " ".join(words)
                if current not in SECTIONS:
                    raise self.error(lineno, f"section '{current}' is not supported (atom_style sphere reads "
                                             f"{', '.join(SECTIONS)})")
                if current in self.sections:
                    raise self.error(lineno, f"a second {current} section")
                style = comment.split()[0] if comment.split() else "sphere"
                if current == "Atoms" and style != "sphere":
                    raise self.error(lineno, f"Atoms section of atom_style '{style}': dem reads atom_style "
                                             f"sphere (id type diameter density x y z)")
                self.sections[current] = []
            elif current is None:
                self.header_line(lineno, words)
            else:
                self.sections[current].append((lineno, words))
                if comment.strip():
                    self.comments[lineno] = comment.split()
        self.lo = [self.header.get(f"{dim}lo", 0.0) for dim in "xyz"]
        self.hi = [self.header.get(f"{dim}hi", 1.0) for dim in "xyz"]
        for dim, lo, hi in zip("xyz", self.lo, self.hi):
            if not lo < hi:
                raise self.error(None, f"{dim}lo {lo:g} must be below {dim}hi {hi:g}")
        self.ntypes = self.header.get("ntypes", 1)

    def error(self, lineno, message):
        where = f"{self.path}:{lineno}" if lineno else self.path
        return DemError(f"read_data {where}: {message}")

    def header_line(self, lineno, words):
        text = " ".join(words)
        for key, name in HEADER_KEYS.items():
            if text.endswith(key) and len(words) == len(key.split()) + 1:
                value = self.integer(lineno, words[0], key)
                limit = MAX_TYPES if name == "ntypes" else 10 ** 9
                if not (1 if name == "ntypes" else 0) <= value <= limit:
                    raise self.error(lineno, f"'{text}': the number of {key} must be in "
                                             f"{1 if name == 'ntypes' else 0}..{limit}")
                self.header[name] = value
                return
        for d in "xyz":
            if text.endswith(f"{d}lo {d}hi") and len(words) == 4:
                self.header[f"{d}lo"] = self.number(lineno, words[0], f"{d}lo")
                self.header[f"{d}hi"] = self.number(lineno, words[1], f"{d}hi")
                return
        if text.endswith("xy xz yz"):
            raise self.error(lineno, "triclinic boxes are not supported")
        if len(words) >= 2 and not words[-1][0].isalpha():
            raise self.error(lineno, f"unreadable header line '{text}'")
        # other counts (bonds, angles, extra ...) do not concern granular spheres

    def number(self, lineno, word, name):
        try:
            return number(word)
        except ValueError:
            raise self.error(lineno, f"{name} must be a finite number, got '{word}'") from None

    def integer(self, lineno, word, name):
        try:
            return integer(word)
        except ValueError:
            raise self.error(lineno, f"{name} must be an integer, got '{word}'") from None

    def atoms(self):
        if "Atoms" not in self.sections and self.header.get("natoms", 1) != 0:
            raise self.error(None, "no Atoms section")
        rows = self.sections.get("Atoms", [])
        if "Atoms" in self.sections and not rows:
            raise self.error(None, "the Atoms section is empty")
        natoms = self.header.get("natoms", len(rows))
        if len(rows) != natoms:
            raise self.error(None, f"header says {natoms} atoms, the Atoms section has {len(rows)} lines "
                                   f"(a truncated file?)")
        n = len(rows)
        tags, types = np.zeros(n, np.int64), np.zeros(n, np.int32)
        diameter, density = np.zeros(n), np.zeros(n)
        x, image = np.zeros((n, 3)), np.zeros((n, 3), np.int32)
        shape, scale, quat = [None] * n, np.ones(n), [None] * n
        seen = {}
        for k, (lineno, words) in enumerate(rows):
            if len(words) not in ATOM_COLUMNS:
                raise self.error(lineno, f"an Atoms line of atom_style sphere has 7 or 10 values "
                                         f"(id type diameter density x y z [ix iy iz]), got {len(words)}")
            tag = self.integer(lineno, words[0], "atom id")     # range first: no overflow in the arrays
            if not 1 <= tag <= MAX_TAG:
                raise self.error(lineno, f"atom id must be in 1..{MAX_TAG}, got {words[0]}")
            if tag in seen:
                raise self.error(lineno, f"atom id {tag} already given on line {seen[tag]}")
            tags[k], seen[tag] = tag, lineno
            atype = self.integer(lineno, words[1], "atom type")
            if not 1 <= atype <= self.ntypes:
                raise self.error(lineno, f"atom type {words[1]} out of range 1..{self.ntypes}")
            types[k] = atype
            diameter[k] = self.number(lineno, words[2], "diameter")
            density[k] = self.number(lineno, words[3], "density")
            if not diameter[k] > 0:
                raise self.error(lineno, f"diameter must be > 0 (point particles are not supported), "
                                         f"got {words[2]}")
            if not density[k] > 0:
                raise self.error(lineno, f"density must be > 0, got {words[3]}")
            x[k] = [self.number(lineno, w, "position") for w in words[4:7]]
            if len(words) == 10:
                flags = [self.integer(lineno, w, "image flag") for w in words[7:10]]
                if any(abs(f) > MAX_IMAGE for f in flags):
                    raise self.error(lineno, f"image flags must be in -{MAX_IMAGE}..{MAX_IMAGE}, got "
                                             f"{' '.join(words[7:10])}")
                image[k] = flags
            if lineno in self.comments:
                shape[k], scale[k], quat[k] = self.extras(lineno, self.comments[lineno])
        radius = 0.5 * diameter
        with np.errstate(over="ignore"):
            rmass = density * 4.0 / 3.0 * math.pi * radius ** 3
        if not np.all(np.isfinite(rmass)):
            k = int(np.flatnonzero(~np.isfinite(rmass))[0])
            raise self.error(rows[k][0], f"diameter {rows[k][1][2]} and density {rows[k][1][3]} give an "
                                         f"infinite mass")
        return {"tags": tags, "types": types, "radius": radius, "x": x, "image": image, "density": density,
                "rmass": rmass, "lines": [ln for ln, _ in rows],
                "shape": shape, "scale": scale, "quat": quat}

    def extras(self, lineno, words):
        """dem's extras in an Atoms line's comment (write_data): `shape NAME scale S` and `quat W X Y Z`,
        in any order. Any other comment is left alone (LAMMPS comments)."""
        if not words or words[0] not in ("shape", "quat"):
            return None, 1.0, None
        shape, scale, quat = None, 1.0, None
        i = 0
        while i < len(words):
            key = words[i]
            if key == "shape" and i + 1 < len(words):
                shape = words[i + 1]
                i += 2
            elif key == "scale" and i + 1 < len(words):
                scale = self.number(lineno, words[i + 1], "scale")
                if not scale > 0:
                    raise self.error(lineno, f"scale must be > 0, got {words[i + 1]}")
                i += 2
            elif key == "quat" and i + 5 <= len(words):
                quat = np.array([self.number(lineno, w, "quat") for w in words[i + 1:i + 5]])
                if not np.any(quat):
                    raise self.error(lineno, "quat must not be zero")
                quat /= np.max(np.abs(quat))        # normalised later: 1e308 components must not overflow
                i += 5
            else:
                raise self.error(lineno, f"unreadable dem extras '# {' '.join(words)}' (expected "
                                         f"'# shape NAME scale S quat W X Y Z')")
        return shape, scale, quat

    def check_inside(self, atoms, boundary):
        """Atom centres lie inside the box along fixed ('f') boundaries (elsewhere the box follows the
        atoms, or periodic images wrap them); the first one outside is an error naming its line."""
        x = atoms["x"]
        for d in range(3):
            for side, style in enumerate(boundary[d]):
                if style != "f":
                    continue
                out = np.flatnonzero(x[:, d] < self.lo[d] if side == 0 else x[:, d] > self.hi[d])
                if len(out):
                    k, axis = out[0], "xyz"[d]
                    bound = f"{axis}lo {self.lo[d]:g}" if side == 0 else f"{axis}hi {self.hi[d]:g}"
                    raise self.error(atoms["lines"][k], f"atom {atoms['tags'][k]} lies outside the box "
                                                        f"({axis} = {x[k, d]:g} beyond {bound}, a fixed "
                                                        f"boundary); {len(out)} atom(s) in all")

    def shapes(self, sim, atoms):
        """Shape indices (-1: sphere) of the Atoms lines with dem's `# shape NAME` extras. With no shape
        defined yet, the `# shape ...` commands of the header (write_data's) define them first."""
        names = atoms["shape"]
        index = np.full(len(names), -1, dtype=np.int64)
        if not any(n is not None for n in names):
            return index
        if len(sim.shapes) == 0 and self.shape_commands:
            cmd = shape_command.ShapeCommand(sim)
            for lineno, words in self.shape_commands:
                try:
                    cmd(words)
                except DemError as e:
                    raise self.error(lineno, f"shape {' '.join(words)}: {e}") from None
        known = {}
        for k, name in enumerate(names):
            if name is None:
                continue
            if name not in known:
                try:
                    known[name] = shape_command.shape_index(sim, name)
                except DemError as e:
                    raise self.error(atoms["lines"][k], f"{e} (define the shapes with `shape NAME KIND ...` "
                                                        f"before read_data)") from None
            index[k] = known[name]
        return index

    def velocities(self, tags):
        n = len(tags)
        v, omega = np.zeros((n, 3)), np.zeros((n, 3))
        index = {int(t): k for k, t in enumerate(tags)}
        done = {}
        for lineno, words in self.sections.get("Velocities", []):
            if len(words) != 7:
                raise self.error(lineno, f"a Velocities line has 7 values (id vx vy vz wx wy wz), got "
                                         f"{len(words)}")
            tag = self.integer(lineno, words[0], "atom id")
            if tag not in index:
                raise self.error(lineno, f"velocity for unknown atom id {tag}")
            if tag in done:
                raise self.error(lineno, f"a second velocity for atom id {tag} (first on line {done[tag]})")
            done[tag] = lineno
            values = [self.number(lineno, w, "velocity") for w in words[1:7]]
            v[index[tag]], omega[index[tag]] = values[:3], values[3:]
        return v, omega
