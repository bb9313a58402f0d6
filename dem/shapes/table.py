"""ShapeTable: the packed, flat representation of many shapes for the Cython kernels.

One row per shape: ``kind`` (int32), ``params`` (float64[NPARAM]) and, for polyhedra, ``voff``/``nv``: an
offset and a count into one global float64 vertex array ``verts`` (N, 3). The core of each shape (the body
shrunk by its crust, see base.py) has its own ``core_kind``/``core_params``/``core_voff``/``core_nv`` into the
same ``verts``. A table built from the same shape list is bitwise identical on every rank.

Glued composites (dem/shapes/glued.py): the components of every composite are further rows, after the
rows of the shapes given (whose indices particles store, and which never move). A composite's row lists
them: ``comp_first``/``comp_count`` into the component arrays ``comp_row`` (the component's own row) and
``comp_pose`` (its rotation, row-major, then its offset: the pose in the composite's body frame at scale
1). Every other row has ``comp_count`` 0.

Polytope rows (box, cube, polyhedron, tetrahedron, pinacoid) carry their faces, edges and adjacency
(dem/shapes/topology.py ``pack_topology``, row for row) in ``kernel_arrays()["topology"]``: the kernels'
``TableView.topo``.
"""
import numpy as np

from ._table import COMPONENT_POSE as COMP_POSE, ShapeView
from .base import GLUED, NPARAM, SPHERE
from .topology import pack_topology


class ShapeTable:
    def __init__(self, shapes):
        self.shapes = list(shapes)
        rows = list(self.shapes)                     # then the components of the composites
        self.comp_first = np.full(len(rows), -1, np.int32)
        self.comp_count = np.zeros(len(rows), np.int32)
        comp_row, poses = [], []
        for i, s in enumerate(self.shapes):
            if s.kind == GLUED:
                self.comp_first[i], self.comp_count[i] = len(comp_row), len(s.components)
                for c, off, rot in s.components:
                    comp_row.append(len(rows))
                    rows.append(c)
                    poses.append(np.r_[np.asarray(rot, float).ravel(), off])
        self.comp_first = np.r_[self.comp_first, np.full(len(rows) - len(self.shapes), -1, np.int32)]
        self.comp_count = np.r_[self.comp_count, np.zeros(len(rows) - len(self.shapes), np.int32)]
        self.comp_row = np.array(comp_row or [0], np.int32)
        self.comp_pose = np.array(poses, float).reshape(-1, COMP_POSE) if poses else np.zeros((1, COMP_POSE))
        self.max_components = int(max(self.comp_count.max(initial=0), 1))
        self.rows = rows
        n = len(rows)
        self.kind = np.empty(n, np.int32)
        self.params = np.zeros((n, NPARAM))
        self.voff = np.zeros(n, np.int64)
        self.nv = np.zeros(n, np.int32)
        self.core_kind = np.empty(n, np.int32)
        self.core_params = np.zeros((n, NPARAM))
        self.core_voff = np.zeros(n, np.int64)
        self.core_nv = np.zeros(n, np.int32)
        self.crust = np.zeros(n)
        self.volume = np.zeros(n)
        self.inertia = np.zeros((n, 3))          # principal moments per unit density
        self.radius = np.zeros(n)                # bounding radius about the centre of mass
        self.half = np.zeros((n, 3))             # half sides of a bounding box on the body axes (centred)
        blocks, total = [], 0
        for i, s in enumerate(rows):
            self.kind[i], self.params[i] = s.kind, s.params
            self.core_kind[i], self.core_params[i] = s.core_kind, s.core_params
            for verts, off, cnt in ((s.vertices, self.voff, self.nv), (s.core_vertices, self.core_voff, self.core_nv)):
                verts = np.asarray(verts, float).reshape(-1, 3)
                off[i], cnt[i] = (total if len(verts) else 0), len(verts)   # 0: never points past the end
                if len(verts):
                    blocks.append(verts)
                    total += len(verts)
            self.crust[i], self.volume[i], self.radius[i] = s.crust, s.volume, s.bounding_radius
            self.inertia[i] = s.principal_moments
            if s.kind != GLUED:
                ext = s.support(np.vstack([np.eye(3), -np.eye(3)]))
                self.half[i] = np.maximum(np.diag(ext[:3]), -np.diag(ext[3:]))
        self.verts = np.ascontiguousarray(np.vstack(blocks) if blocks else np.zeros((1, 3)))
        self.is_sphere = self.kind == SPHERE
        self._view = None

    def __len__(self):
        return len(self.shapes)

    def arrays(self):
        """The arrays the kernels take, by name."""
        return {k: getattr(self, k) for k in ("kind", "params", "voff", "nv", "core_kind", "core_params",
                                               "core_voff", "core_nv", "crust", "verts")}

    def req_rel(self):
        """Per row: the radius of the sphere of its volume over its bounding radius (1 for sphere rows)."""
        return np.where(self.is_sphere, 1.0, np.cbrt(0.75 * self.volume / np.pi) / self.radius)

    def equivalent_radius(self, shape, radius):
        """Radii of the spheres of the particles' volumes (shape indices, -1 for spheres, and bounding radii);
        the kernels' `equivalent_radius` (_table.pxd) does the same."""
        shape, radius = np.asarray(shape), np.asarray(radius, dtype=float)
        if not len(self):
            return radius.copy()
        return np.where(shape >= 0, radius * self.req_rel()[np.maximum(shape, 0)], radius)

    def kernel_arrays(self):
        """The arrays the contact kernels take (core for GJK, body for walls), contiguous; an empty table
        gives one dummy row (kernels never read it: every particle is a plain sphere)."""
        a = self.arrays()
        a["radius"] = self.radius
        a["crust_rel"] = a["crust"] / a["radius"]       # crust per unit bounding radius
        a["req_rel"] = self.req_rel()
        a["is_sphere"] = self.is_sphere.astype(np.int32)
        a.update(comp_first=self.comp_first, comp_count=self.comp_count, comp_row=self.comp_row,
                 comp_pose=self.comp_pose, half=self.half)
        topology = pack_topology(self.rows if len(self) else [None])
        if not len(self):
            a.update(kind=np.zeros(1, np.int32), params=np.zeros((1, NPARAM)), voff=np.zeros(1, np.int64),
                     nv=np.zeros(1, np.int32), core_kind=np.zeros(1, np.int32), core_params=np.zeros((1, NPARAM)),
                     core_voff=np.zeros(1, np.int64), core_nv=np.zeros(1, np.int32), crust=np.zeros(1),
                     radius=np.ones(1), crust_rel=np.zeros(1), is_sphere=np.ones(1, np.int32),
                     comp_first=np.full(1, -1, np.int32), comp_count=np.zeros(1, np.int32),
                     half=np.zeros((1, 3)), req_rel=np.ones(1))
        a = {k: np.ascontiguousarray(v) for k, v in a.items()}
        a["topology"] = topology          # faces, edges (the polytope rows; _table.pxd TopoTable)
        return a

    def view(self):
        """The table as kernels take it (one TableView struct, dem/shapes/_table.pxd), built once."""
        if self._view is None:
            self._view = ShapeView(self.kernel_arrays())
        return self._view
