"""dump style custom: LAMMPS-style text snapshots (``ITEM: TIMESTEP`` ...), read natively by OVITO,
LAMMPS tools (pizza.py, LIGGGHTS post-processing), ASE and MDAnalysis."""
import gzip
import os

import numpy as np

from .dump import Dump
from .files import atomic_write, open_output
from .errors import DemError, did_you_mean
from .gzip_member import GzipMember

# column -> (frame array, component or None, kind); kind "i" integer, "f" float
COLUMNS = {"id": ("id", None, "i"), "type": ("type", None, "i"), "mass": ("mass", None, "f"),
           "radius": ("radius", None, "f"), "diameter": ("radius", None, "f"), "shape": ("shape", None, "i")}
for _k, _c in enumerate("xyz"):
    COLUMNS[_c] = ("position", _k, "f")
    COLUMNS[_c + "s"] = ("position", _k, "f")            # scaled by the box
    COLUMNS[_c + "u"] = ("position", _k, "f")            # unwrapped with the image counters
    COLUMNS["i" + _c] = ("image", _k, "i")
    COLUMNS["v" + _c] = ("velocity", _k, "f")
    COLUMNS["f" + _c] = ("force", _k, "f")
    COLUMNS["omega" + _c] = ("omega", _k, "f")
    COLUMNS["angmom" + _c] = ("angmom", _k, "f")
    COLUMNS["tq" + _c] = ("torque", _k, "f")
    COLUMNS["shape" + _c] = ("shape", _k, "f")           # extents of the body along its axes
for _k, _c in enumerate(("quatw", "quati", "quatj", "quatk")):
    COLUMNS[_c] = ("orientation", _k, "f")
del _k, _c

# frame arrays beyond those of dem.dump.FIELDS -> atom field
EXTRA = {"image": "image", "force": "f", "angmom": "angmom", "torque": "torque"}
# names users try, from other codes -> the LAMMPS column
HINTS = {"wx": "omegax", "wy": "omegay", "wz": "omegaz", "qw": "quatw", "qx": "quati", "qy": "quatj",
         "qz": "quatk", "q0": "quatw", "tag": "id", "rmass": "mass", "r": "radius", "vel": "vx",
         "position": "x", "velocity": "vx", "omega": "omegax", "orientation": "quatw"}


class DumpCustom(Dump):
    """dump ID group-ID custom N file column column ...

    LAMMPS's ``dump custom`` text format, one snapshot after the other::

        ITEM: TIMESTEP
        1000
        ITEM: NUMBER OF ATOMS
        2
        ITEM: BOX BOUNDS pp pp ff
        0.0 0.1
        0.0 0.1
        0.0 0.2
        ITEM: ATOMS id type x y z radius
        1 1 0.05 0.04 0.01 0.002
        2 1 0.05 0.06 0.01 0.002

    OVITO opens it natively (File > Load File, or ``ovito.io.import_file``), with the standard
    properties taken from the column names: ``id`` Particle Identifier, ``type`` Particle Type, ``x y z``
    Position, ``vx vy vz`` Velocity, ``omegax omegay omegaz`` Angular Velocity, ``radius`` Radius (spheres
    drawn at their size), ``mass`` Mass, ``quatw quati quatj quatk`` Orientation, ``shapex shapey shapez``
    Aspherical Shape; other columns (``shape``) become user properties. To see cubes as cubes in OVITO,
    dump ``quatw quati quatj quatk shapex shapey shapez`` and set the particle type's shape to Box
    (Particle types > Shape, or ``ParticlesVis.shape``); ellipsoids: Ellipsoid.

    Example::

        dump snap all custom 1000 post/drum.*.dump.gz id type x y z vx vy vz radius quatw quati quatj quatk
        dump_modify snap sort id

    Columns (LAMMPS names):

    =================================  ======================================================
    id type                            particle id, type
    x y z                              position of the centre of mass (in the box)
    xu yu zu                           unwrapped position (periodic images added)
    xs ys zs                           position scaled by the box (0..1)
    ix iy iz                           periodic image counters
    vx vy vz                           velocity
    fx fy fz                           force
    omegax omegay omegaz               angular velocity (world frame)
    angmomx angmomy angmomz            angular momentum
    tqx tqy tqz                        torque
    radius diameter                    (bounding) radius, twice it
    mass                               mass
    quatw quati quatj quatk            orientation, unit quaternion body -> world
    shape                              dem shape index (-1: sphere of the particle's radius)
    shapex shapey shapez               extents of the particle along its body axes (the size of the
                                       box of its mesh; a sphere: its diameter, as LAMMPS's shapex)
    =================================  ======================================================

    An unknown column stops the script at this line, naming the closest column.

    File: ``*`` in the name is replaced by the step (one file per snapshot, each written through a
    temporary file: a reader never sees half a snapshot); without ``*`` every snapshot is appended to
    the one file (created at the first snapshot, replacing an old file unless ``dump_modify append
    yes``). A name ending in ``.gz`` is gzip-compressed (one file is one gzip stream, which OVITO reads
    whole, complete after every snapshot: it can be read while the run goes on). The file is closed between snapshots.

    ``dump_modify ID keyword value ...`` (any number of them, after the dump command):

    * ``sort id | -id | N | -N | off``: order of the lines: by id (ascending, the default), descending,
      by column N (1-based) ascending or descending; ``off`` is accepted (the lines stay ordered by id).
    * ``format float FMT`` (C or Python format of the float columns, default ``%.10g``; ``%.17g`` writes
      exact values), ``format int FMT``, ``format line "FMT FMT ..."`` (one per column),
      ``format none`` (back to the defaults).
    * ``pad N``: zero-pad the step in ``*`` file names to N digits.
    * ``time yes|no``: write ``ITEM: TIME`` (the simulated time) before each snapshot, as LAMMPS does with
      ``time yes`` (OVITO reads it as the attribute Time; default no).
    * ``append yes|no``: append to an existing single file instead of replacing it (default no).
    * ``every N``: write every N steps.

    Under MPI every rank takes part in gathering the particles; rank 0 writes.
    """

    style = "custom"
    keywords = {}

    def __init__(self, sim, did, group, every, path, args):
        self.columns = []
        self.sort = "id"
        self.float_format = "%.10g"
        self.int_format = "%d"
        self.line_format = None
        self.pad = 0
        self.write_time = False
        self.append = False
        self._opened = False         # the single file was created (later snapshots append)
        self._member = GzipMember()  # the single .gz file's one gzip member
        super().__init__(sim, did, group, every, path, [])
        if not args:
            raise DemError(f"dump {did}: dump custom needs the columns to write after the file name "
                           f"(e.g. 'dump {did} {group} custom {every} {path} id type x y z radius')")
        for name in args:
            if name not in COLUMNS:
                hint = HINTS.get(name)
                close = f" (did you mean '{hint}'?)" if hint else did_you_mean(name, COLUMNS)
                raise DemError(f"dump {did}: unknown dump custom column '{name}'{close}",
                               hint="columns: " + " ".join(COLUMNS))
            self.columns.append(name)
        if self.path.count("*") > 1:
            raise DemError(f"dump {did}: at most one '*' in the file name ('{self.path}')")
        if not os.path.basename(self.path):
            raise DemError(f"dump {did}: bad file name '{self.path}'")
        self.gzip = self.path.endswith(".gz")
        self.fields = self.gathered_fields()

    # ----- dump_modify ----------------------------------------------------------------------------
    def modify(self, args):
        """dump_modify keywords (see the class documentation)."""
        i = 0
        while i < len(args):
            word = args[i]
            need = {"sort": 1, "pad": 1, "time": 1, "append": 1, "every": 1}.get(word)
            if word == "format":
                if i + 1 >= len(args):
                    raise DemError(f"dump_modify {self.id}: format needs 'float FMT', 'int FMT', "
                                   f"'line \"FMT ...\"' or 'none'")
                what = args[i + 1]
                if what == "none":
                    self.float_format, self.int_format, self.line_format = "%.10g", "%d", None
                    i += 2
                    continue
                if what not in ("float", "int", "line") or i + 2 >= len(args):
                    raise DemError(f"dump_modify {self.id}: format needs 'float FMT', 'int FMT', "
                                   f"'line \"FMT ...\"' or 'none', got '{' '.join(args[i + 1:i + 3])}'")
                self.set_format(what, args[i + 2])
                i += 3
                continue
            if need is None:
                words = ["sort", "format", "pad", "time", "append", "every"]
                raise DemError(f"dump_modify {self.id}: unknown keyword '{word}'{did_you_mean(word, words)}",
                               hint="keywords of dump custom: " + ", ".join(words))
            if i + 1 >= len(args):
                raise DemError(f"dump_modify {self.id}: {word} needs a value")
            value = args[i + 1]
            if word == "sort":
                self.set_sort(value)
            elif word == "pad":
                try:
                    self.pad = int(value)
                except ValueError:
                    raise DemError(f"dump_modify {self.id}: pad must be an integer, got '{value}'") from None
            elif word in ("time", "append"):
                if value not in ("yes", "no"):
                    raise DemError(f"dump_modify {self.id}: {word} must be yes or no, got '{value}'")
                setattr(self, "write_time" if word == "time" else "append", value == "yes")
            elif word == "every":
                self.set_every(value)
            i += 2

    def set_sort(self, value):
        if value in ("off", "id", "-id"):
            self.sort = value
            return
        try:
            col = int(value)
        except ValueError:
            col = 0
        if col == 0 or abs(col) > len(self.columns):
            raise DemError(f"dump_modify {self.id}: sort must be off, id, -id or a column number 1.."
                           f"{len(self.columns)} (negative: descending), got '{value}'")
        self.sort = col

    def set_format(self, what, fmt):
        fmts = fmt.split() if what == "line" else [fmt]
        if what == "line" and len(fmts) != len(self.columns):
            raise DemError(f"dump_modify {self.id}: format line needs {len(self.columns)} formats (one per "
                           f"column), got {len(fmts)}")
        for f in fmts:
            try:
                f % (1 if what == "int" else 1.0)
            except (TypeError, ValueError):
                raise DemError(f"dump_modify {self.id}: bad format '{f}' (a C format such as %.8g or %d)") \
                    from None
        if what == "float":
            self.float_format = fmt
        elif what == "int":
            self.int_format = fmt
        else:
            self.line_format = " ".join(fmts)

    # ----- gathering ------------------------------------------------------------------------------
    def atom_field(self, name):
        return EXTRA.get(name) or super().atom_field(name)

    def gathered_fields(self):
        names = {COLUMNS[c][0] for c in self.columns} | {"position", "id"}
        if any(c in ("xu", "yu", "zu") for c in self.columns):
            names.add("image")
        if any(c.startswith("shape") and c != "shape" for c in self.columns):
            names |= {"radius", "shape"}
        return sorted(names)

    # ----- writing --------------------------------------------------------------------------------
    def frame_path(self, step):
        if "*" not in self.path:
            return self.path
        return self.path.replace("*", str(int(step)).zfill(self.pad))

    def output_files(self):
        return [self.path]

    def extents(self, frame):
        """(n, 3) size of each particle along its body axes: a sphere's diameter, else the box of the
        posed shape's mesh in the body frame, scaled by radius / bounding radius."""
        a = frame.arrays
        size = np.repeat(2.0 * a["radius"][:, None], 3, axis=1)
        table = self.sim.shapes
        if len(table) and "shape" in a:
            cache = {}
            for i in np.flatnonzero(a["shape"] >= 0):
                s = int(a["shape"][i])
                if s not in cache:
                    verts = np.asarray(table.mesh(s)[0], dtype=np.float64).reshape(-1, 3)
                    cache[s] = (verts.max(axis=0) - verts.min(axis=0)) / float(table.radius[s])
                size[i] = cache[s] * a["radius"][i]
        return size

    def column_values(self, frame):
        """The columns of a frame: list of 1-D arrays, in the order of the dump command."""
        a = frame.arrays
        box = frame.hi - frame.lo
        out, size = [], None
        for c in self.columns:
            field, k, _ = COLUMNS[c]
            if c == "diameter":
                v = 2.0 * a["radius"]
            elif c in ("xs", "ys", "zs"):
                v = (a["position"][:, k] - frame.lo[k]) / box[k]
            elif c in ("xu", "yu", "zu"):
                v = a["position"][:, k] + a["image"][:, k] * box[k]
            elif c in ("shapex", "shapey", "shapez"):
                size = self.extents(frame) if size is None else size
                v = size[:, k]
            else:
                v = a[field] if k is None else a[field][:, k]
            out.append(np.asarray(v))
        return out

    def order(self, frame, values):
        if self.sort in ("off", "id"):
            return None                      # gathered by id already
        if self.sort == "-id":
            return np.argsort(-frame.arrays["id"], kind="stable")
        col = values[abs(self.sort) - 1]
        idx = np.argsort(col, kind="stable")
        return idx[::-1] if self.sort < 0 else idx

    def boundary(self):
        b = getattr(self.sim.domain, "boundary", None) or [["p", "p"]] * 3
        return " ".join("".join(side) for side in b)

    def snapshot_text(self, frame):
        values = self.column_values(frame)
        idx = self.order(frame, values)
        if idx is not None:
            values = [v[idx] for v in values]
        lines = []
        if self.write_time:
            lines += ["ITEM: TIME", repr(float(frame.time))]
        lines += ["ITEM: TIMESTEP", str(frame.step), "ITEM: NUMBER OF ATOMS", str(frame.count),
                  f"ITEM: BOX BOUNDS {self.boundary()}"]
        lines += [f"{float(frame.lo[d])!r} {float(frame.hi[d])!r}" for d in range(3)]
        lines.append("ITEM: ATOMS " + " ".join(self.columns))
        text = "\n".join(lines) + "\n"
        if frame.count:
            fmt = self.line_format or " ".join(self.int_format if COLUMNS[c][2] == "i" else self.float_format
                                               for c in self.columns)
            fmt += "\n"
            cols = [v.tolist() for v in values]
            text += "".join(fmt % row for row in zip(*cols))
        return text

    def write_frame(self, frame):
        data = self.snapshot_text(frame).encode("ascii")
        path = self.frame_path(frame.step)
        if "*" in self.path:
            atomic_write(path, gzip.compress(data, compresslevel=6) if self.gzip else data, f"dump {self.id}")
            return
        mode = "r+b" if (self._opened or self.append) and os.path.exists(path) else "wb"
        with open_output(path, f"dump {self.id}", mode) as f:
            if self.gzip:
                self._member.append(f, data)
            else:
                f.seek(0, 2)
                f.write(data)
        self._opened = True
