"""Base class of dumps: snapshots of the particles written every N steps.

    dump ID group-ID style N file [keyword value ...]

* ID: a name for the dump (``undump ID`` removes it).
* group-ID: only particles of this group are written.
* style: ``h5`` (one HDF5 file + XDMF sidecar, see :class:`dem.dump_h5.DumpH5`), ``vtk`` (one VTK
  XML ``.vtu`` file per frame + ``.pvd`` collection, see :class:`dem.dump_vtk.DumpVTK`), ``vtp`` (particles
  as VTK PolyData points named for OVITO, see :class:`dem.dump_vtp.DumpVTP`) or ``custom`` (LAMMPS text
  snapshots for OVITO, see :class:`dem.dump_custom.DumpCustom`).
* N: write a frame every N steps (and at the start of a run when its step is a multiple of N).
* file: where to write (style specific).

Keyword of the h5, vtk and vtp styles (``custom`` takes LAMMPS column names instead):

* ``fields name name ...``: the per-particle arrays to write, among ``id type position velocity omega
  orientation radius mass shape`` (default: all of them). ``position`` is always written (the points
  need coordinates). The LAMMPS-like aliases ``tag x v quat rmass`` are accepted.

Per-particle arrays (global, ordered by particle id):

=============  =============  ==========  ===================================================
name           atom field     shape       meaning
=============  =============  ==========  ===================================================
id             tag            (n,)        particle id (int64)
type           type           (n,)        particle type (int32)
position       x              (n, 3)      centre of mass
velocity       v              (n, 3)      velocity of the centre of mass
omega          omega          (n, 3)      angular velocity (world frame)
orientation    quat           (n, 4)      unit quaternion, w x y z
radius         radius         (n,)        (bounding) radius
mass           rmass          (n,)        mass
shape          shape          (n,)        shape index (-1: sphere of the particle's radius)
=============  =============  ==========  ===================================================

``dump_modify ID every N`` changes N of any dump; ``dump_modify ID sort id|off`` is accepted by every
style (frames are ordered by id); styles may take more keywords (``custom``: sort, format, pad, time,
append).

Only rank 0 writes files; every rank takes part in gathering the data (``write`` is collective).
Writing a style: subclass :class:`Dump`, set ``style`` and ``keywords``, implement ``write_frame(frame)``
and, when it keeps a file open, ``flush()``/``close_files()``; announce the class from a plugin.
"""
import numpy as np

from .errors import DemError, did_you_mean

# user-visible name -> per-particle atom field
FIELDS = {
    "id": "tag",
    "type": "type",
    "position": "x",
    "velocity": "v",
    "omega": "omega",
    "orientation": "quat",
    "radius": "radius",
    "mass": "rmass",
    "shape": "shape",
}
ALIASES = {"tag": "id", "x": "position", "v": "velocity", "quat": "orientation", "rmass": "mass"}


class Frame:
    """One gathered snapshot (rank 0 only): step, time, box bounds and the per-particle arrays of the
    group members ordered by id (``arrays[name]`` for the names of FIELDS that were gathered)."""

    def __init__(self, step, time, lo, hi, arrays):
        self.step = int(step)
        self.time = float(time)
        self.lo = np.array(lo, dtype=np.float64).reshape(3)
        self.hi = np.array(hi, dtype=np.float64).reshape(3)
        self.arrays = arrays

    @property
    def count(self):
        return len(self.arrays["position"])


class Dump:
    """dump ID group-ID style N file [fields name ...] -- see the module documentation.

    Attributes used by ``Output``: ``every`` (N), ``last_step`` (the step of the last frame written, or
    None); methods ``write(step)``, ``flush()``, ``close()`` (idempotent; a later ``write`` reopens)."""

    kind = "dump"
    style = None
    # keyword -> number of values (None: a list running to the next keyword)
    keywords = {"fields": None}

    def __init__(self, sim, did, group, every, path, args):
        self.sim = sim
        self.id = did
        self.group = group
        self.groupbit = sim.groups.bit(group)      # DemError for an unknown group
        self.every = int(every)
        self.path = str(path)
        self.args = list(args)
        self.fields = list(FIELDS)
        self.last_step = None
        self.nframes = 0          # frames written (counted on every rank)
        self.closed = False
        self.parse_args(self.args)

    # ----- keywords -------------------------------------------------------------------------------
    def parse_args(self, args):
        i = 0
        while i < len(args):
            word = args[i]
            if word not in self.keywords:
                raise DemError(f"dump {self.id}: unknown {self.style} dump keyword "
                               f"'{word}'{did_you_mean(word, self.keywords)}",
                               hint=f"keywords of dump {self.style}: {', '.join(self.keywords)}")
            nvalues = self.keywords[word]
            if nvalues is None:
                j = i + 1
                while j < len(args) and args[j] not in self.keywords:
                    j += 1
                values = args[i + 1:j]
            else:
                values = args[i + 1:i + 1 + nvalues]
                if len(values) < nvalues:
                    raise DemError(f"dump {self.id}: keyword '{word}' needs {nvalues} value(s)")
                j = i + 1 + nvalues
            self.keyword(word, list(values))
            i = j

    def keyword(self, word, values):
        """Apply one keyword (subclasses handle theirs and call this for the common ones)."""
        if word == "fields":
            self.set_fields(values)

    def set_fields(self, names):
        if not names:
            raise DemError(f"dump {self.id}: 'fields' needs at least one name among {', '.join(FIELDS)}")
        chosen = set()
        for name in names:
            if name == "all":
                chosen.update(FIELDS)
                continue
            name = ALIASES.get(name, name)
            if name not in FIELDS:
                raise DemError(f"dump {self.id}: unknown field '{name}'"
                               f"{did_you_mean(name, list(FIELDS) + list(ALIASES))}",
                               hint=f"fields: {' '.join(FIELDS)}")
            chosen.add(name)
        chosen.add("position")
        self.fields = [name for name in FIELDS if name in chosen]   # canonical order

    # ----- dump_modify ----------------------------------------------------------------------------
    def modify(self, args):
        """``dump_modify ID keyword value ...``: ``every N``; ``sort id|off`` (accepted: frames are always
        ordered by id). Styles with more keywords override this."""
        i = 0
        while i < len(args):
            word = args[i]
            if word not in ("every", "sort"):
                raise DemError(f"dump_modify {self.id}: unknown keyword '{word}' for dump {self.style}"
                               f"{did_you_mean(word, ['every', 'sort'])}",
                               hint=f"dump {self.style} takes 'every N' and 'sort id|off' (its frames are "
                                    "ordered by id)")
            if i + 1 >= len(args):
                raise DemError(f"dump_modify {self.id}: {word} needs a value")
            value = args[i + 1]
            if word == "every":
                self.set_every(value)
            elif value not in ("id", "off"):
                raise DemError(f"dump_modify {self.id}: dump {self.style} writes its particles ordered by "
                               f"id: sort must be id or off, got '{value}'")
            i += 2

    def set_every(self, value):
        try:
            every = int(value)
        except ValueError:
            raise DemError(f"dump_modify {self.id}: every must be an integer, got '{value}'") from None
        if every <= 0:
            raise DemError(f"dump_modify {self.id}: every must be > 0")
        self.every = every

    # ----- gathering ------------------------------------------------------------------------------
    def atom_field(self, name):
        """The atom field gathered for the frame array `name`."""
        return FIELDS[name]

    def gathered_fields(self):
        """Names (keys of FIELDS) to gather for a frame: the written fields, plus what the geometry
        needs (subclasses may add: e.g. shape and orientation to pose meshes)."""
        return list(self.fields)

    def gather(self, step):
        """Collective: gather the group's particles ordered by id. Returns a Frame on rank 0, else None."""
        sim = self.sim
        names = self.gathered_fields()
        raw = {name: sim.gather(self.atom_field(name)) for name in names}
        mask = sim.gather("mask")
        if sim.comm.me != 0:
            return None
        member = (np.asarray(mask) & self.groupbit) != 0
        if not member.all():
            raw = {name: np.asarray(a)[member] for name, a in raw.items()}
        arrays = {name: np.ascontiguousarray(a) for name, a in raw.items()}
        return Frame(step, sim.update.time, sim.domain.lo, sim.domain.hi, arrays)

    # ----- shaped particles (hook) ----------------------------------------------------------------
    def posed_mesh(self, shape, position, quat, scale=1.0):
        """World-frame surface of one shaped particle: ``(vertices (m, 3) float, faces (k, 3) int)`` or
        None to draw the particle as a point with its radius.

        The body-frame mesh of row ``shape`` (>= 0) of ``sim.shapes`` (cached per shape), scaled by
        ``scale`` (the particle's radius over the shape's bounding radius), rotated by the unit
        quaternion ``quat`` (w, x, y, z) and translated to ``position`` (the centre of mass)."""
        table = self.sim.shapes
        if len(table) == 0:
            return None
        from .thermo import quat_to_matrix
        verts, faces = table.mesh(int(shape))
        rot = quat_to_matrix(np.asarray(quat, dtype=np.float64).reshape(1, 4))[0]
        return (scale * verts) @ rot.T + np.asarray(position, dtype=np.float64), faces

    def particle_meshes(self, frame):
        """{particle index in frame: (vertices, faces)} for the shaped particles that have a mesh. Empty
        while no shape is defined (``sim.shapes``), or when shape/orientation were not gathered."""
        table = self.sim.shapes
        if len(table) == 0:
            return {}
        arrays = frame.arrays
        if "shape" not in arrays or "orientation" not in arrays:
            return {}
        radius = arrays.get("radius")
        meshes = {}
        for i in np.flatnonzero(arrays["shape"] >= 0):
            s = int(arrays["shape"][i])
            args = (s, arrays["position"][i], arrays["orientation"][i])
            if radius is not None:
                args += (float(radius[i]) / float(table.radius[s]),)
            mesh = self.posed_mesh(*args)
            if mesh is not None:
                verts = np.asarray(mesh[0], dtype=np.float64).reshape(-1, 3)
                faces = np.asarray(mesh[1], dtype=np.int64)
                meshes[int(i)] = (verts, faces)
        return meshes

    def surface(self, frame):
        """All posed meshes of a frame joined: (points (p, 3), triangles (t, 3) int64, owner (p,) particle
        index in the frame), or None when no particle has a mesh."""
        meshes = self.particle_meshes(frame)
        if not meshes:
            return None
        points, tris, owner, n = [], [], [], 0
        for i in sorted(meshes):
            verts, faces = meshes[i]
            points.append(verts)
            tris.append(faces + n)
            owner.append(np.full(len(verts), i, dtype=np.int64))
            n += len(verts)
        return np.concatenate(points), np.concatenate(tris).astype(np.int64), np.concatenate(owner)

    # ----- writing --------------------------------------------------------------------------------
    def write(self, step):
        """Write one frame (collective: every rank calls it; rank 0 writes the files)."""
        frame = self.gather(step)
        if self.sim.comm.me == 0:
            try:
                self.write_frame(frame)
            except OSError as e:
                raise DemError(f"dump {self.id}: cannot write '{e.filename or self.path}': "
                               f"{e.strerror or e}") from None
        self.closed = False
        self.nframes += 1
        self.last_step = step

    def write_frame(self, frame):
        raise NotImplementedError

    def output_files(self):
        """The files this dump writes (`*`: the step), that no other output may write."""
        return [self.path]

    def flush(self):
        """Push what was written to disk (styles that keep a file open)."""

    def close(self):
        """Close open files (idempotent). A dump that never wrote a frame leaves no file behind."""
        if self.closed:
            return
        self.closed = True
        if self.sim.comm.me == 0:
            self.close_files()

    def close_files(self):
        pass

    def __repr__(self):
        return f"<dump {self.id} {self.style} group {self.group} every {self.every} '{self.path}'>"
