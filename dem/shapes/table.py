"""ShapeTable: the packed, flat representation of many shapes for the Cython kernels.

One row per shape: ``kind`` (int32), ``params`` (float64[NPARAM]) and, for polyhedra, ``voff``/``nv``: an
offset and a count into one global float64 vertex array ``verts`` (N, 3). The core of each shape (the body
shrunk by its crust, see base.py) has its own ``core_kind``/``core_params``/``core_voff``/``core_nv`` into the
same ``verts``. A table built from the same shape list is bitwise identical on every rank.
"""
import numpy as np

from ._table import ShapeView
from .base import NPARAM, SPHERE


class ShapeTable:
    def __init__(self, shapes):
        self.shapes = list(shapes)
        n = len(self.shapes)
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
        blocks, total = [], 0
        for i, s in enumerate(self.shapes):
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
        self.verts = np.ascontiguousarray(np.vstack(blocks) if blocks else np.zeros((1, 3)))
        self.is_sphere = self.kind == SPHERE
        self._view = None

    def __len__(self):
        return len(self.shapes)

    def arrays(self):
        """The arrays the kernels take, by name."""
        return {k: getattr(self, k) for k in ("kind", "params", "voff", "nv", "core_kind", "core_params",
                                               "core_voff", "core_nv", "crust", "verts")}

    def kernel_arrays(self):
        """The arrays the contact kernels take (core for GJK, body for walls), contiguous; an empty table
        gives one dummy row (kernels never read it: every particle is a plain sphere)."""
        a = self.arrays()
        a["radius"] = self.radius
        a["crust_rel"] = a["crust"] / a["radius"]       # crust per unit bounding radius
        a["is_sphere"] = self.is_sphere.astype(np.int32)
        if not len(self):
            a.update(kind=np.zeros(1, np.int32), params=np.zeros((1, NPARAM)), voff=np.zeros(1, np.int64),
                     nv=np.zeros(1, np.int32), core_kind=np.zeros(1, np.int32), core_params=np.zeros((1, NPARAM)),
                     core_voff=np.zeros(1, np.int64), core_nv=np.zeros(1, np.int32), crust=np.zeros(1),
                     radius=np.ones(1), crust_rel=np.zeros(1), is_sphere=np.ones(1, np.int32))
        return {k: np.ascontiguousarray(v) for k, v in a.items()}

    def view(self):
        """The table as kernels take it (one TableView struct, dem/shapes/_table.pxd), built once."""
        if self._view is None:
            self._view = ShapeView(self.kernel_arrays())
        return self._view
