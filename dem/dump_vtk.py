"""dump style vtk: one VTK XML UnstructuredGrid file (.vtu) per frame and a .pvd collection."""
import base64
import os
from .xml_text import quoteattr

import numpy as np

from .dump import Dump
from .files import atomic_write
from .errors import DemError

VTK_VERTEX = 1
VTK_TRIANGLE = 5
VTK_POLYGON = 7

_VTK_TYPES = {("f", 8): "Float64", ("f", 4): "Float32", ("i", 8): "Int64", ("i", 4): "Int32",
              ("i", 1): "Int8", ("u", 1): "UInt8", ("u", 4): "UInt32", ("u", 8): "UInt64"}


def _little(a):
    a = np.ascontiguousarray(a)
    return a.astype(a.dtype.newbyteorder("<"), copy=False)


class _Arrays:
    """Collects DataArray elements, inline ASCII or base64 (UInt64 byte-count header), appended at the end of
    the file or, with `inline`, in each element (OVITO's VTP reader takes no appended data)."""

    def __init__(self, binary, inline=False):
        self.binary = binary
        self.inline = inline
        self.blocks = []
        self.offset = 0

    def element(self, name, array, indent, ntuples=None):
        a = _little(np.asarray(array))
        ncomp = 1 if a.ndim == 1 else int(np.prod(a.shape[1:]))
        vtype = _VTK_TYPES[(a.dtype.kind, a.dtype.itemsize)]
        attrs = f'type="{vtype}"'
        if name is not None:
            attrs += f" Name={quoteattr(name)}"
        if ncomp != 1:
            attrs += f' NumberOfComponents="{ncomp}"'
        if ntuples is not None:
            attrs += f' NumberOfTuples="{ntuples}"'
        if self.binary:
            raw = np.array([a.nbytes], dtype="<u8").tobytes() + a.tobytes()
            block = base64.b64encode(raw)
            if self.inline:
                return f'{indent}<DataArray {attrs} format="binary">{block.decode("ascii")}</DataArray>\n'
            self.blocks.append(block)
            text = f'{indent}<DataArray {attrs} format="appended" offset="{self.offset}"/>\n'
            self.offset += len(block)
            return text
        flat = a.ravel()
        values = " ".join(repr(v) for v in flat.tolist()) if a.dtype.kind == "f" else \
            " ".join(str(v) for v in flat.tolist())
        return f'{indent}<DataArray {attrs} format="ascii">{values}</DataArray>\n'

    def appended(self):
        if not self.binary or self.inline:
            return ""
        return '  <AppendedData encoding="base64">\n   _' + b"".join(self.blocks).decode("ascii") + \
            "\n  </AppendedData>\n"


class DumpVTK(Dump):
    """dump ID group-ID vtk N file_*.vtu [fields name ...] [format binary|ascii] [pvd file.pvd|none]

    Writes one VTK XML UnstructuredGrid file per frame (ParaView, VisIt, meshio read them; OVITO 3.17 does
    not recognise them as particles: use ``dump vtp`` or ``dump custom`` for OVITO):
    ``*`` in the file name is replaced by the step number (``out/grains_*.vtu`` gives
    ``out/grains_1000.vtu``); a name without ``*`` gets ``_<step>`` before its extension. Each particle is
    a point (cell VTK_VERTEX) with point data ``id type velocity omega orientation radius mass shape``
    (those chosen by ``fields``); ``radius`` is the active scalar: in ParaView draw spheres with a Glyph
    filter (Sphere, Scale Array ``radius``, scale factor 2). Field data: ``TimeValue``, ``step``,
    ``box_lo``, ``box_hi``.

    Shaped particles (``shape`` command) are written as their true surface instead: the triangles of
    the posed, scaled mesh of their shape (cells VTK_TRIANGLE), every vertex carrying the particle's
    point data (color by ``id`` or ``velocity``); plain spheres stay points. ParaView then shows
    cubes as cubes with no glyph filter (for the spheres of a mixture, glyph the VTK_VERTEX cells).

    Mesh walls (``fix wall/mesh``) are written with every frame where they are then, one file each
    (``post/pour_1000_hopper.vtu`` for the fix ``hopper``: triangles), listed in the ``.pvd`` as further
    parts of the frame, so that ParaView shows the walls with the particles.

    A ``.pvd`` collection listing every frame with its time is rewritten after each frame; open it in
    ParaView to get the time series with the right times. Default name: the file name without ``*`` and
    the separator before it (``out/grains_*.vtu`` gives ``out/grains.pvd``; ``*.vtu`` gives ``ID.pvd``).

    Example::

        dump movie all vtk 2000 post/pour_*.vtu
        dump light all vtk 500 post/v_*.vtu fields id velocity radius format ascii pvd post/v.pvd

    Keywords (defaults first):

    * ``fields name ...``: the point data to write (default all; positions are always written).
    * ``format binary|ascii``: ``binary`` is base64 appended data (exact, compact), ``ascii`` writes
      exact decimal values (larger, human-readable).
    * ``pvd FILE|none``: name of the collection file, or none.

    Every file is written to a temporary file and renamed into place: a reader never sees a
    half-written frame. Frames written again at the same step replace the earlier entry of the .pvd.
    """

    style = "vtk"
    extension, file_kind = ".vtu", "VTK XML UnstructuredGrid"
    writes_walls = True       # mesh walls as further parts of each frame
    keywords = {"fields": None, "format": 1, "pvd": 1}

    def __init__(self, sim, did, group, every, path, args):
        self.binary = True
        self.pvd_path = ""        # "" = default, None = no collection
        super().__init__(sim, did, group, every, path, args)
        root, ext = os.path.splitext(self.path)
        if ext.lower() != self.extension:
            raise DemError(f"dump {did}: dump {self.style} writes {self.file_kind} files: the file name "
                           f"must end in {self.extension} ('{self.path}')")
        if self.path.count("*") > 1:
            raise DemError(f"dump {did}: at most one '*' in the file name ('{self.path}')")
        if "*" not in self.path:
            self.pattern = root + "_*" + ext
        else:
            self.pattern = self.path
        if self.pvd_path == "":
            folder, base = os.path.split(self.pattern)
            stem = os.path.splitext(base)[0].replace("*", "").rstrip("_-. ")
            self.pvd_path = os.path.join(folder, (stem or str(did)) + ".pvd")
        self._collection = {}     # step -> (time, [file path, wall mesh paths ...])

    def keyword(self, word, values):
        if word == "format":
            if values[0] not in ("binary", "ascii"):
                raise DemError(f"dump {self.id}: format must be binary or ascii, got '{values[0]}'")
            self.binary = values[0] == "binary"
        elif word == "pvd":
            self.pvd_path = None if values[0] == "none" else values[0]
        else:
            super().keyword(word, values)

    def output_files(self):
        return [self.pattern] + ([self.pvd_path] if self.pvd_path else [])

    def frame_path(self, step):
        return self.pattern.replace("*", str(int(step)))

    def gathered_fields(self):
        names = super().gathered_fields()
        if len(self.sim.shapes):      # to pose the meshes of shaped particles
            names += [n for n in ("shape", "orientation", "radius") if n not in names]
        return names

    # ----- geometry -------------------------------------------------------------------------------
    def geometry(self, frame):
        """(points (p, 3), connectivity, offsets, cell types, owner) of a frame. `owner` (p,) is the
        particle index of each point, or None when there is one point per particle (all spheres)."""
        x = frame.arrays["position"]
        n = len(x)
        meshes = self.particle_meshes(frame)
        if not meshes:
            idx = np.arange(n, dtype=np.int64)
            return x, idx, idx + 1, np.full(n, VTK_VERTEX, dtype=np.uint8), None
        points, owner, conn, sizes, types = [], [], [], [], []
        npts = 0
        for i in range(n):
            mesh = meshes.get(i)
            if mesh is None:
                points.append(x[i:i + 1])
                owner.append(np.array([i]))
                conn.append(np.array([npts]))
                sizes.append(np.array([1]))
                types.append(np.array([VTK_VERTEX]))
                npts += 1
                continue
            verts, faces = mesh
            faces = np.asarray(faces, dtype=np.int64)
            points.append(verts)
            owner.append(np.full(len(verts), i))
            conn.append(faces.ravel() + npts)
            sizes.append(np.full(len(faces), faces.shape[1]))
            types.append(np.full(len(faces), VTK_TRIANGLE if faces.shape[1] == 3 else VTK_POLYGON))
            npts += len(verts)
        return (np.concatenate(points).astype(np.float64), np.concatenate(conn).astype(np.int64),
                np.cumsum(np.concatenate(sizes)).astype(np.int64),
                np.concatenate(types).astype(np.uint8), np.concatenate(owner).astype(np.int64))

    # ----- writing --------------------------------------------------------------------------------
    def frame_text(self, frame):
        points, conn, offsets, types, owner = self.geometry(frame)
        arrays = _Arrays(self.binary)
        point_fields = [f for f in self.fields if f != "position"]
        active = []
        if "radius" in point_fields:
            active.append('Scalars="radius"')
        if "velocity" in point_fields:
            active.append('Vectors="velocity"')
        out = ['<?xml version="1.0"?>\n',
               '<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" '
               'header_type="UInt64">\n',
               '  <UnstructuredGrid>\n',
               '    <FieldData>\n',
               arrays.element("TimeValue", np.array([frame.time]), "      ", ntuples=1),
               arrays.element("step", np.array([frame.step], dtype=np.int64), "      ", ntuples=1),
               arrays.element("box_lo", frame.lo.reshape(1, 3), "      ", ntuples=1),
               arrays.element("box_hi", frame.hi.reshape(1, 3), "      ", ntuples=1),
               '    </FieldData>\n',
               f'    <Piece NumberOfPoints="{len(points)}" NumberOfCells="{len(types)}">\n',
               f'      <PointData{"".join(" " + a for a in active)}>\n']
        for field in point_fields:
            data = frame.arrays[field]
            out.append(arrays.element(field, data if owner is None else data[owner], "        "))
        out += ['      </PointData>\n',
                '      <Points>\n',
                arrays.element("Points", points, "        "),
                '      </Points>\n',
                '      <Cells>\n',
                arrays.element("connectivity", conn, "        "),
                arrays.element("offsets", offsets, "        "),
                arrays.element("types", types, "        "),
                '      </Cells>\n',
                '    </Piece>\n',
                '  </UnstructuredGrid>\n',
                arrays.appended(),
                '</VTKFile>\n']
        return "".join(out)

    def wall_text(self, frame, vertices, triangles):
        """A wall's triangle mesh as a VTK XML UnstructuredGrid (cells VTK_TRIANGLE)."""
        arrays = _Arrays(self.binary)
        tri = np.ascontiguousarray(triangles, dtype=np.int64)
        return "".join([
            '<?xml version="1.0"?>\n',
            '<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">\n',
            '  <UnstructuredGrid>\n',
            '    <FieldData>\n',
            arrays.element("TimeValue", np.array([frame.time]), "      ", ntuples=1),
            '    </FieldData>\n',
            f'    <Piece NumberOfPoints="{len(vertices)}" NumberOfCells="{len(tri)}">\n',
            '      <Points>\n',
            arrays.element("Points", np.ascontiguousarray(vertices, dtype=np.float64), "        "),
            '      </Points>\n',
            '      <Cells>\n',
            arrays.element("connectivity", tri.ravel(), "        "),
            arrays.element("offsets", 3 * np.arange(1, len(tri) + 1, dtype=np.int64), "        "),
            arrays.element("types", np.full(len(tri), VTK_TRIANGLE, dtype=np.uint8), "        "),
            '      </Cells>\n',
            '    </Piece>\n',
            '  </UnstructuredGrid>\n',
            arrays.appended(),
            '</VTKFile>\n'])

    def wall_path(self, step, fid):
        root, ext = os.path.splitext(self.frame_path(step))
        return f"{root}_{fid}{ext}"

    def pvd_text(self):
        folder = os.path.dirname(os.path.abspath(self.pvd_path))
        lines = ['<?xml version="1.0"?>\n',
                 '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">\n',
                 '  <Collection>\n']
        for step, (time, paths) in sorted(self._collection.items()):
            for part, path in enumerate(paths):
                rel = os.path.relpath(os.path.abspath(path), folder).replace(os.sep, "/")
                lines.append(f'    <DataSet timestep="{time!r}" group="" part="{part}" file={quoteattr(rel)}/>\n')
        lines += ['  </Collection>\n', '</VTKFile>\n']
        return "".join(lines)

    def write_frame(self, frame):
        paths = [self.frame_path(frame.step)]
        atomic_write(paths[0], self.frame_text(frame), f"dump {self.id}")
        for fix in self.sim.modify.fixes if self.writes_walls else ():   # mesh walls: parts 1, 2 ...
            wall = fix.surface_mesh()
            if wall is not None:
                paths.append(self.wall_path(frame.step, fix.id))
                atomic_write(paths[-1], self.wall_text(frame, *wall), f"dump {self.id}")
        if self.pvd_path is not None:
            self._collection[frame.step] = (frame.time, paths)
            atomic_write(self.pvd_path, self.pvd_text(), f"dump {self.id}")
