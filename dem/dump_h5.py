"""dump style h5: every frame of a dump in one HDF5 file, plus an XDMF sidecar for ParaView."""
import os
from .xml_text import escape, quoteattr

import numpy as np

from .dump import Dump
from .files import atomic_write, check_target, ensure_dir
from .errors import DemError

FORMAT = "dem-dump-h5"
VERSION = 1
PARTIAL = "frame_being_written"     # a frame is written here, then moved under /frames in one step

# XDMF attribute name and type of each field (position is the geometry)
XDMF_NAMES = {
    "id": "id",
    "type": "type",
    "velocity": "velocity",
    "omega": "omega",
    "orientation": "orientation",
    "radius": "radius",
    "mass": "mass",
    "shape": "shape",
}


def frame_name(step):
    """Name of the HDF5 group of a frame under /frames (zero-padded: sorts by step)."""
    return f"{int(step):010d}"


def _number_type(dtype):
    dtype = np.dtype(dtype)
    if dtype.kind == "f":
        return "Float", dtype.itemsize
    if dtype.kind == "i":
        return "Int", dtype.itemsize
    if dtype.kind == "u":
        return ("UChar", 1) if dtype.itemsize == 1 else ("UInt", dtype.itemsize)
    raise TypeError(f"no XDMF number type for {dtype}")


COMPONENTS = {"orientation": "wxyz"}   # names of the scalar attributes a field of other than 1 or 3 columns becomes


def _attributes(name, center, h5name, path, shape, dtype, indent):
    """XDMF attributes of one dataset: a Scalar (n,) or a Vector (n, 3); any other width is one Scalar per
    column, each a hyperslab of the dataset (ParaView 5.11's XDMF reader reads a Vector as 3 columns
    whatever its width, 80 tuples of 3 for 60 quaternions; VTK 9's reads a Matrix as one tuple)."""
    if len(shape) == 1 or shape[1] == 3:
        return [f'{indent}<Attribute Name={quoteattr(name)} '
                f'AttributeType="{"Scalar" if len(shape) == 1 else "Vector"}" Center="{center}">',
                f"{indent}  " + _data_item(h5name, path, shape, dtype),
                f"{indent}</Attribute>"]
    n, width = (int(d) for d in shape)
    labels = COMPONENTS.get(name) or [str(k) for k in range(width)]
    ntype, precision = _number_type(dtype)      # on the slab too: the Xdmf3 readers skip it without
    lines = []
    for k, label in enumerate(labels):
        lines += [f'{indent}<Attribute Name={quoteattr(f"{name}_{label}")} AttributeType="Scalar" '
                  f'Center="{center}">',
                  f'{indent}  <DataItem ItemType="HyperSlab" Dimensions="{n} 1" Type="HyperSlab" '
                  f'NumberType="{ntype}" Precision="{precision}">',
                  f'{indent}    <DataItem Dimensions="3 2" Format="XML">0 {k} 1 1 {n} 1</DataItem>',
                  f"{indent}    " + _data_item(h5name, path, shape, dtype),
                  f"{indent}  </DataItem>",
                  f"{indent}</Attribute>"]
    return lines


def _data_item(h5name, path, shape, dtype):
    ntype, precision = _number_type(dtype)
    dims = " ".join(str(int(d)) for d in shape)
    return (f'<DataItem Dimensions="{dims}" NumberType="{ntype}" Precision="{precision}" '
            f'Format="HDF">{escape(h5name)}:{path}</DataItem>')


def xdmf_grid(h5name, step, time, datasets):
    """XDMF text of one frame. `datasets`: {field: (shape, dtype)} of the frame's datasets. Radius comes
    first (the active scalar); a frame without particles gets an empty inline geometry (the readers
    fail on empty HDF5 data items)."""
    base = f"/frames/{frame_name(step)}"
    n = int(datasets["position"][0][0])
    lines = [f'      <Grid Name="step_{int(step)}" GridType="Uniform">',
             f'        <Time Value="{float(time)!r}"/>',
             f'        <Topology TopologyType="Polyvertex" NumberOfElements="{n}" NodesPerElement="1"/>',
             '        <Geometry GeometryType="XYZ">']
    if n == 0:      # a blank, not nothing: the Xdmf3 readers abort ParaView on an item without content
        lines.append('          <DataItem Dimensions="0 3" NumberType="Float" Precision="8" Format="XML">'
                     ' </DataItem>')
    else:
        lines.append("          " + _data_item(h5name, f"{base}/position", *datasets["position"]))
    lines.append("        </Geometry>")
    order = sorted((f for f in datasets if f != "position"), key=lambda f: f != "radius")
    for field in order if n else ():
        lines += _attributes(XDMF_NAMES[field], "Node", h5name, f"{base}/{field}", *datasets[field], "        ")
    lines.append("      </Grid>")
    return "\n".join(lines) + "\n"


# per-triangle arrays of the surfaces (cell data): the values of the particle each triangle belongs to
SURFACE_CELL_FIELDS = ("id", "type", "velocity", "omega", "shape")


def xdmf_surface(h5name, step, time, particle_grid, npoints, ntris, cell_fields=None):
    """XDMF of a frame with posed particle surfaces: a spatial collection of the particle grid (points)
    and a triangle grid of the surfaces (point attribute ``id``: the particle of each vertex; cell
    attributes ``cell_fields`` {name: (shape, dtype)}: the particle's values on each triangle). With
    npoints 0 the collection holds the particle grid only, or nothing in a frame without particles (every
    frame then reads as the same kind of data set)."""
    base = f"/frames/{frame_name(step)}/surface"
    inner = "\n".join("  " + line for line in particle_grid.rstrip("\n").split("\n"))
    inner = inner.replace(f'<Grid Name="step_{int(step)}"', '<Grid Name="particles"', 1)
    inner = "\n".join(line for line in inner.split("\n") if "<Time " not in line)
    lines = [f'      <Grid Name="step_{int(step)}" GridType="Collection" CollectionType="Spatial">',
             f'        <Time Value="{float(time)!r}"/>']
    if 'NumberOfElements="0"' not in particle_grid:      # the readers fail on an empty grid here
        lines.append(inner)
    if npoints:
        lines += ['        <Grid Name="surfaces" GridType="Uniform">',
                  f'          <Topology TopologyType="Triangle" NumberOfElements="{ntris}">',
                  "            " + _data_item(h5name, f"{base}/triangles", (ntris, 3), np.int64),
                  "          </Topology>",
                  '          <Geometry GeometryType="XYZ">',
                  "            " + _data_item(h5name, f"{base}/points", (npoints, 3), np.float64),
                  "          </Geometry>",
                  '          <Attribute Name="id" AttributeType="Scalar" Center="Node">',
                  "            " + _data_item(h5name, f"{base}/id", (npoints,), np.int64),
                  "          </Attribute>"]
        for name, (shape, dtype) in (cell_fields or {}).items():
            lines += _attributes("cell_" + name if name == "id" else name, "Cell", h5name, f"{base}/cell_{name}",
                                 shape, dtype, "          ")
        lines.append("        </Grid>")
    lines.append("      </Grid>")
    return "\n".join(lines) + "\n"


def xdmf_walls(h5name, step, time, frame_grid, walls):
    """XDMF of a frame with mesh walls: a spatial collection of the frame's grid (particles, or particles and
    their surfaces) and one triangle grid per wall, `walls` [(fix ID, npoints, ntris)], its posed points and
    triangles at /frames/<frame>/walls/<fix ID>/."""
    base = f"/frames/{frame_name(step)}/walls"
    inner = "\n".join("  " + line for line in frame_grid.rstrip("\n").split("\n") if "<Time " not in line)
    inner = inner.replace(f'<Grid Name="step_{int(step)}"', '<Grid Name="particles"', 1)
    lines = [f'      <Grid Name="step_{int(step)}" GridType="Collection" CollectionType="Spatial">',
             f'        <Time Value="{float(time)!r}"/>']
    if "<Topology" in inner and 'NumberOfElements="0"' not in inner:   # the readers fail on an empty grid
        lines.append(inner)
    for fid, npoints, ntris in walls:
        lines += [f'        <Grid Name={quoteattr("wall_" + fid)} GridType="Uniform">',
                  f'          <Topology TopologyType="Triangle" NumberOfElements="{ntris}">',
                  "            " + _data_item(h5name, f"{base}/{fid}/triangles", (ntris, 3), np.int64),
                  "          </Topology>",
                  '          <Geometry GeometryType="XYZ">',
                  "            " + _data_item(h5name, f"{base}/{fid}/points", (npoints, 3), np.float64),
                  "          </Geometry>",
                  "        </Grid>"]
    lines.append("      </Grid>")
    return "\n".join(lines) + "\n"


def xdmf_document(grids, name="particles"):
    """The whole XDMF file: a temporal collection of the given frame grids (texts of xdmf_grid)."""
    head = ('<?xml version="1.0" encoding="utf-8"?>\n'
            '<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>\n'
            '<Xdmf Version="3.0" xmlns:xi="http://www.w3.org/2001/XInclude">\n'
            '  <Domain>\n'
            f'    <Grid Name={quoteattr(name)} GridType="Collection" CollectionType="Temporal">\n')
    tail = "    </Grid>\n  </Domain>\n</Xdmf>\n"
    return head + "".join(grids) + tail


class DumpH5(Dump):
    """dump ID group-ID h5 N file.h5 [fields name ...] [surface yes|no] [xdmf_paths relative|absolute]

    Writes every frame of the dump into ONE HDF5 file (h5py), and an XDMF sidecar ``file.xdmf`` (same
    folder, same name with the extension replaced) that ParaView opens as a time series of point sets
    ("Xdmf Reader" or "Xdmf3 Reader"); draw spheres with a Glyph filter: Sphere glyph, Scale Array
    ``radius``, scale factor 2 (glyph radius 0.5), no orientation.

    Example::

        dump snap all h5 1000 out/pour.h5
        dump grains big h5 500 big.h5 fields id position velocity radius

    Layout of the file (version 1)::

        /                      attributes: format="dem-dump-h5", version=1, dump_id, group, units
        /frames/0000001000     one group per frame (zero-padded step), attributes:
                                 step (int), time (float), natoms (int), box_lo, box_hi (3 floats)
            id           (n,)   int64    particle id          (ordered by id)
            type         (n,)   int32
            position     (n,3)  float64
            velocity     (n,3)  float64
            omega        (n,3)  float64  angular velocity
            orientation  (n,4)  float64  unit quaternion w x y z
            radius       (n,)   float64
            mass         (n,)   float64
            shape        (n,)   int32    shape index (-1: sphere)

    In the XDMF the quaternion is four scalars ``orientation_w``, ``_x``, ``_y``, ``_z``, each a column of
    the one dataset: declared as one 4-column attribute, ParaView 5.11's "Xdmf Reader" reads a Vector as
    3 columns (80 tuples for 60 particles) and VTK 9's reads a Matrix as one tuple. ParaView's "Xdmf3
    Reader" skips these columns ("Skipping unrecognized array type"); its other arrays are right.

    Keyword ``fields`` limits the per-particle datasets (``position`` is always written); default: all.

    Mesh walls (``fix wall/mesh``), where they are at each frame::

        /frames/<step>/walls/<fix ID>/points     (v,3) float64   the posed vertices
                                     /triangles  (t,3) int64

    and in the XDMF each frame is then a spatial collection of the particles and one triangle grid per
    wall (``wall_<fix ID>``): ParaView shows the hopper or the mixer's blades with the particles.

    The XDMF names the HDF5 file relative to the XDMF file's own folder (both lie in one folder: the
    data items read ``file.h5:/frames/...``), so the two files can be moved together; ParaView's "Xdmf
    Reader" and VTK's vtkXdmfReader open it from any folder, by a relative or absolute name. ParaView's
    "Xdmf3 Reader" (5.11) given a bare relative name (``pvpython``: ``OpenDataFile('drum.xdmf')``) looks
    for ``drum.xdmfdrum.h5`` and aborts: it prefixes relative data items with the name it was given when
    that name has no folder part. Open ``./drum.xdmf`` or an absolute name with it (ParaView's file dialog
    does), or write ``xdmf_paths absolute`` (the XDMF then names the HDF5 file by its absolute path, and
    the files can no longer be moved).

    meshio's XDMF time-series reader (``meshio.xdmf.TimeSeriesReader``) cannot read this file: it reads
    one fixed mesh and per-step attributes only, while particles move and their number changes from frame
    to frame (each frame is its own grid). Read the frames with h5py (layout below), or the VTU files of
    ``dump vtk`` with ``meshio.read``.

    Shaped particles (``shape`` command): the file also holds the shape table, rewritten when it
    grows::

        /shapes                attributes: count; one row per shape index (the ``shape`` dataset)
            name         (s,)   str      names given by the ``shape`` command
            kind         (s,)   int32    0 sphere 1 box 2 cylinder 3 cone 4 ellipsoid 5 superquadric
                                         6 polyhedron;  kind_name (s,) str
            params       (s,8)  float64  sizes of the kind (dem/shapes/_support.pyx), scale 1
            crust, volume, bounding_radius (s,) float64;  inertia (s,3) principal moments / density
            definition   (s,)   str      the shape command that made it
            mesh_<k>/vertices (m,3), mesh_<k>/faces (t,3)   body-frame surface of shape k, scale 1

    A particle's body is: mesh of ``shape`` x (``radius`` / bounding_radius[shape]) rotated by
    ``orientation`` (body -> space) and moved to ``position``. With ``surface yes`` (the default when
    shapes exist) each frame also stores that posed surface, ``surface/points`` (p,3),
    ``surface/triangles`` (t,3) and ``surface/id`` (p,) (particle id of each vertex), and per triangle
    the values of its particle ``surface/cell_id``, ``cell_type``, ``cell_velocity``, ``cell_omega``,
    ``cell_shape``; the XDMF frame becomes a spatial collection of the points and a triangle grid with
    point data ``id`` and cell data ``cell_id type velocity omega shape``: ParaView shows cubes as cubes,
    coloured by ``velocity`` (Magnitude) or ``omega``. A frame without particles is then an empty
    collection (every frame reads as a multiblock data set).

    The file is created at the first frame (a script that stops before its first run leaves no file;
    an existing file of that name is then replaced). It is opened for each frame and closed (flushed)
    right after: between frames it is complete, so it can be read while the run goes on (ParaView,
    h5py, in this process or another) and after a crash. The writer does not lock the file; a reader in
    this same process must have closed it before the next frame is written. The XDMF sidecar is
    rewritten atomically after every frame. A frame is built in the group ``/frame_being_written`` and
    then moved under ``/frames`` in one step, so ``/frames`` only ever holds whole frames (SIGINT and
    SIGTERM also wait for the end of the step, see ``run``). A frame written again at the same step (two runs meeting at
    a step) replaces the earlier one.
    """

    style = "h5"
    keywords = {"fields": None, "surface": 1, "xdmf_paths": 1}

    def __init__(self, sim, did, group, every, path, args):
        self.surfaces = True
        self.absolute_paths = False
        self._nshapes = 0          # shape table rows written to the file
        super().__init__(sim, did, group, every, path, args)
        if "*" in self.path:
            raise DemError(f"dump {did}: dump h5 writes all frames into one file: no '*' in its name "
                           f"('{self.path}')", hint="use dump vtk for one file per frame")
        if not self.path or self.path.endswith(os.sep):
            raise DemError(f"dump {did}: bad file name '{self.path}'")
        root, ext = os.path.splitext(self.path)
        self.xdmf_path = (root if ext else self.path) + ".xdmf"
        self._grids = {}          # step -> XDMF text of the frame (insertion order)
        self._created = False     # the file was created by this dump (later opens append)

    def output_files(self):
        return [self.path, self.xdmf_path]

    def keyword(self, word, values):
        if word == "surface":
            if values[0] not in ("yes", "no"):
                raise DemError(f"dump {self.id}: surface must be yes or no, got '{values[0]}'")
            self.surfaces = values[0] == "yes"
        elif word == "xdmf_paths":
            if values[0] not in ("relative", "absolute"):
                raise DemError(f"dump {self.id}: xdmf_paths must be relative or absolute, got '{values[0]}'")
            self.absolute_paths = values[0] == "absolute"
        else:
            super().keyword(word, values)

    def gathered_fields(self):
        names = super().gathered_fields()
        if self.surfaces and len(self.sim.shapes):
            names += [n for n in ("id", "shape", "orientation", "radius") + SURFACE_CELL_FIELDS
                      if n not in names]
        return names

    def write_shapes(self, f):
        """The shape table (see the class documentation), when it has rows not yet written."""
        table = self.sim.shapes
        if len(table) == self._nshapes:
            return
        from .shapes.base import KIND_NAMES
        if "shapes" in f:
            del f["shapes"]
        g = f.create_group("shapes")
        g.attrs["count"] = len(table)
        strings = lambda xs: np.array([str(x).encode() for x in xs], dtype=object)
        import h5py
        text = h5py.string_dtype()
        g.create_dataset("name", data=strings(table.names), dtype=text)
        g.create_dataset("kind", data=table.kind)
        g.create_dataset("kind_name", data=strings(KIND_NAMES.get(int(k), "?") for k in table.kind), dtype=text)
        g.create_dataset("params", data=table.params)
        g.create_dataset("crust", data=table.crust)
        g.create_dataset("volume", data=table.volume)
        g.create_dataset("bounding_radius", data=table.radius)
        g.create_dataset("inertia", data=table.inertia)
        g.create_dataset("definition", data=strings(" ".join(w) for w in table.definitions), dtype=text)
        for k in range(len(table)):
            verts, faces = table.mesh(k)
            m = g.create_group(f"mesh_{k}")
            m.create_dataset("vertices", data=verts)
            m.create_dataset("faces", data=faces)
        self._nshapes = len(table)

    # ----- files ----------------------------------------------------------------------------------
    def _open(self):
        """Open the file for one frame: created (replacing an old one) at the first frame, appended to
        afterwards. Not locked, so that other programs may read it meanwhile."""
        try:
            import h5py
        except ImportError:
            raise DemError("dump h5 needs the h5py package (pip install h5py)") from None
        check_target(self.path, f"dump {self.id}")
        ensure_dir(self.path)
        mode = "a" if self._created else "w"
        try:
            try:
                f = h5py.File(self.path, mode, locking=False)
            except TypeError:      # h5py without the locking option
                f = h5py.File(self.path, mode)
        except OSError as e:
            raise DemError(f"dump {self.id}: cannot open '{self.path}' to write step "
                           f"{self.sim.update.ntimestep}: {e}",
                           hint="is the file open in this process (h5py)? close it before the run, or "
                                "open it with h5py.File(path, 'r', locking=False)") from None
        if not self._created:
            f.attrs["format"] = FORMAT
            f.attrs["version"] = VERSION
            f.attrs["dump_id"] = str(self.id)
            f.attrs["group"] = str(self.group)
            f.attrs["units"] = str(self.sim.units)
            f.require_group("frames")
            self._created = True
            self._nshapes = 0
        return f

    def write_frame(self, frame):
        with self._open() as f:
            frames = f.require_group("frames")
            name = frame_name(frame.step)
            if PARTIAL in f:          # left by a process killed while writing a frame
                del f[PARTIAL]
            g = f.create_group(PARTIAL)
            try:
                datasets, surf = self._fill_frame(f, g, frame)
                walls = self._fill_walls(g)
            except BaseException:
                del f[PARTIAL]
                raise
            if name in frames:
                del frames[name]
            f.move(PARTIAL, f"frames/{name}")    # the frame appears whole or not at all
        self._grids.pop(frame.step, None)
        h5name = self.data_item_path()
        grid = xdmf_grid(h5name, frame.step, frame.time, datasets)
        if surf is not None:
            grid = xdmf_surface(h5name, frame.step, frame.time, grid, len(surf[0]), len(surf[1]), surf[3])
        elif self.surfaces and len(self.sim.shapes):
            grid = xdmf_surface(h5name, frame.step, frame.time, grid, 0, 0)
        if walls:
            grid = xdmf_walls(h5name, frame.step, frame.time, grid, walls)
        self._grids[frame.step] = grid
        atomic_write(self.xdmf_path, xdmf_document(self._grids.values(), name=str(self.id)), f"dump {self.id}")

    def _fill_frame(self, f, g, frame):
        """The attributes and datasets of a frame into group g; (datasets {field: (shape, dtype)}, surface)."""
        g.attrs["step"] = np.int64(frame.step)
        g.attrs["time"] = np.float64(frame.time)
        g.attrs["natoms"] = np.int64(frame.count)
        g.attrs["box_lo"] = frame.lo
        g.attrs["box_hi"] = frame.hi
        datasets = {}
        for field in self.fields:
            data = frame.arrays[field]
            g.create_dataset(field, data=data)
            datasets[field] = (data.shape, data.dtype)
        self.write_shapes(f)
        surf = self.surface(frame) if self.surfaces else None
        if surf is not None:
            points, tris, owner = surf
            ids = frame.arrays["id"][owner] if "id" in frame.arrays else owner
            s = g.create_group("surface")
            s.create_dataset("points", data=points)
            s.create_dataset("triangles", data=tris)
            s.create_dataset("id", data=np.asarray(ids, dtype=np.int64))
            tri_owner = owner[tris[:, 0]]
            cells = {}
            for name in SURFACE_CELL_FIELDS:
                if name in frame.arrays:
                    data = np.ascontiguousarray(frame.arrays[name][tri_owner])
                    s.create_dataset(f"cell_{name}", data=data)
                    cells[name] = (data.shape, data.dtype)
            surf = (points, tris, owner, cells)
        return datasets, surf

    def _fill_walls(self, g):
        """The mesh walls (fix wall/mesh), posed now, into group g/walls/<fix ID>: [(ID, points, triangles)]."""
        walls = []
        for fix in self.sim.modify.fixes:
            mesh = fix.surface_mesh()
            if mesh is None:
                continue
            w = g.require_group("walls").create_group(fix.id)
            w.create_dataset("points", data=np.asarray(mesh[0], dtype=np.float64))
            w.create_dataset("triangles", data=np.asarray(mesh[1], dtype=np.int64))
            walls.append((fix.id, len(mesh[0]), len(mesh[1])))
        return walls

    def data_item_path(self):
        """The HDF5 file as the XDMF names it: relative to the XDMF file's folder (the same folder: its
        base name), or absolute with ``xdmf_paths absolute``."""
        if self.absolute_paths:
            return os.path.abspath(self.path)
        return os.path.relpath(os.path.abspath(self.path),
                               os.path.dirname(os.path.abspath(self.xdmf_path))).replace(os.sep, "/")
