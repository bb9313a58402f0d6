"""dump style vtp: particles as the points of VTK XML PolyData files (.vtp), one per frame, named as OVITO's
VTP particle reader expects (the names Aspherix writes), and a .pvd collection for ParaView."""
import numpy as np

from .dump import Dump
from .dump_vtk import DumpVTK, _Arrays

# dump field -> VTP point-data name that OVITO maps to its standard particle property
VTP_NAMES = {"id": "id", "type": "type", "velocity": "v", "omega": "omega", "orientation": "Orientation",
             "radius": "radius", "mass": "mass", "shape": "shape"}
BOX_BLOCKINESS = 200.0     # a box drawn as a superquadric: OVITO's roundness 2/200 = 0.01 (sharp-looking)


class DumpVTP(DumpVTK):
    """dump ID group-ID vtp N file_*.vtp [fields name ...] [format binary|ascii] [pvd file.pvd|none]

    Writes one VTK XML PolyData file per frame, every particle a point (cell VTK_VERTEX) with its point
    data, for OVITO (its VTP particle reader, as for Aspherix/LIGGGHTS output) and ParaView. File names,
    ``fields``, ``format`` and ``pvd`` work as in ``dump vtk``. The point data are named as OVITO maps them
    to its particle properties: ``id`` (Particle Identifier), ``type`` (Material Type), ``v`` (Velocity),
    ``omega`` (Angular Velocity), ``Orientation`` (the quaternion in OVITO's order x y z w), ``radius``
    (Radius: the bounding radius), ``mass`` (Mass); ``shape`` is dem's shape index.

    With shapes defined, each particle also gets ``shapex shapey shapez`` (half sizes along its body axes:
    OVITO's Aspherical Shape) and ``blockiness1 blockiness2`` (Superquadric Roundness) for the shapes OVITO
    can draw: boxes (blockiness 200, i.e. almost sharp), ellipsoids and superquadrics (their exponents
    n1, n2); other shapes (polyhedra, cylinders, cones, composites) and spheres have zero half sizes, so
    OVITO draws them as spheres of their radius: ``dump gsd`` gives OVITO every shape as it is (and
    ``dump vtk`` ParaView).

    Example::

        dump ov all vtp 2000 post/pour_*.vtp

    Open ``post/pour_*.vtp`` in OVITO (File > Load File: the frames form a trajectory), or
    ``post/pour.pvd`` in ParaView (Point Gaussian representation, or a Glyph filter scaled by ``radius``).
    """

    style = "vtp"
    extension, file_kind = ".vtp", "VTK XML PolyData"
    writes_walls = False      # OVITO reads one particle file per frame: mesh walls go to dump vtk

    def gathered_fields(self):
        names = Dump.gathered_fields(self)
        if len(self.sim.shapes):      # the half sizes follow the shape and its scale
            names += [n for n in ("shape", "radius") if n not in names]
        return names

    def shape_columns(self, frame):
        """(half sizes (n, 3), blockiness (n, 2)) of each particle, zeros where OVITO draws a sphere."""
        from .shapes import BOX, ELLIPSOID, SUPERQUADRIC
        n = frame.count
        half, block = np.zeros((n, 3)), np.full((n, 2), 2.0)
        table = self.sim.shapes
        row = np.asarray(frame.arrays["shape"])
        for s in np.unique(row[row >= 0]):
            kind = int(table.kind[s])
            if kind not in (BOX, ELLIPSOID, SUPERQUADRIC):
                continue
            mine = row == s
            scale = np.asarray(frame.arrays["radius"])[mine] / table.radius[s]
            half[mine] = scale[:, None] * table.half[s]
            if kind == BOX:
                block[mine] = BOX_BLOCKINESS
            elif kind == SUPERQUADRIC:
                block[mine] = table.rows[s].n1, table.rows[s].n2
        return half, block

    def point_data(self, frame):
        """The frame's point data: ([(name, array)], the PointData element's attributes)."""
        items = []
        for field in self.fields:
            if field == "position":
                continue
            data = frame.arrays[field]
            if field == "orientation":
                data = np.asarray(data)[:, [1, 2, 3, 0]]        # w x y z -> OVITO's x y z w
            items.append((VTP_NAMES[field], data))
        if len(self.sim.shapes):
            half, block = self.shape_columns(frame)
            for k, name in enumerate(("shapex", "shapey", "shapez")):
                items.append((name, np.ascontiguousarray(half[:, k])))
            for k, name in enumerate(("blockiness1", "blockiness2")):
                items.append((name, np.ascontiguousarray(block[:, k])))
        return items, ' Scalars="radius"' if "radius" in self.fields else ""

    def frame_text(self, frame):
        # OVITO recognises the file by a Piece right after PolyData (so the frame's time is in the .pvd,
        # not in field data) and reads only inline data arrays
        arrays = _Arrays(self.binary, inline=True)
        n = frame.count
        idx = np.arange(n, dtype=np.int64)
        items, attrs = self.point_data(frame)
        out = ['<?xml version="1.0"?>\n',
               '<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">\n',
               '  <PolyData>\n',
               f'    <Piece NumberOfPoints="{n}" NumberOfVerts="{n}" NumberOfLines="0" NumberOfStrips="0" '
               f'NumberOfPolys="0">\n',
               f'      <PointData{attrs}>\n']
        out += [arrays.element(name, data, "        ") for name, data in items]
        out += ['      </PointData>\n',
                '      <Points>\n',
                arrays.element("Points", np.asarray(frame.arrays["position"], np.float64), "        "),
                '      </Points>\n',
                '      <Verts>\n',
                arrays.element("connectivity", idx, "        "),
                arrays.element("offsets", idx + 1, "        "),
                '      </Verts>\n',
                '    </Piece>\n',
                '  </PolyData>\n',
                '</VTKFile>\n']
        return "".join(out)
