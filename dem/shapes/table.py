"""ShapeTable: the packed, flat representation of many shapes for the Cython kernels.

One row per shape: ``kind`` (int32), ``params`` (float64[NPARAM]) and, for polyhedra, ``voff``/``nv``: an
offset and a count into one global float64 vertex array ``verts`` (N, 3). The core of each shape (the body
shrunk by its crust, see base.py) has its own ``core_kind``/``core_params``/``core_voff``/``core_nv`` into the
same ``verts``. A table built from the same shape list is bitwise identical on every rank.
"""
import numpy as np

from .base import NPARAM


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

    def __len__(self):
        return len(self.shapes)

    def arrays(self):
        """The arrays the kernels take, by name."""
        return {k: getattr(self, k) for k in ("kind", "params", "voff", "nv", "core_kind", "core_params",
                                               "core_voff", "core_nv", "crust", "verts")}
