# cython: language_level=3
"""ShapeView: the shape table's arrays behind one TableView struct (see _table.pxd)."""
import numpy as np

COLUMNS = ("kind", "params", "voff", "nv", "core_kind", "core_params", "core_voff", "core_nv", "crust", "crust_rel",
           "radius", "is_sphere", "verts", "comp_first", "comp_count", "comp_row", "comp_pose",
           "half")
COMPONENT_POSE = COMP_POSE            # (for Python: table.py)


cdef class ShapeView:
    """Built from the arrays of ShapeTable.kernel_arrays() (or the one-row dummy of an empty table); the
    composite columns may be left out (a table without composites)."""

    def __cinit__(self, dict arrays):
        n = len(arrays["kind"])
        defaults = {"comp_first": np.full(n, -1, np.int32), "comp_count": np.zeros(n, np.int32),   # no composite
                    "comp_row": np.zeros(1, np.int32), "comp_pose": np.zeros((1, COMP_POSE)), "half": np.zeros((n, 3))}
        a = {k: np.ascontiguousarray(arrays[k] if k in arrays else defaults[k]) for k in COLUMNS}
        cdef const int[::1] kind = a["kind"], nv = a["nv"], core_kind = a["core_kind"]
        cdef const int[::1] core_nv = a["core_nv"], is_sphere = a["is_sphere"]
        cdef const int[::1] comp_first = a["comp_first"], comp_count = a["comp_count"], comp_row = a["comp_row"]
        cdef const double[:, ::1] comp_pose = a["comp_pose"], half = a["half"]
        cdef const i64[::1] voff = a["voff"], core_voff = a["core_voff"]
        cdef const double[:, ::1] params = a["params"], core_params = a["core_params"], verts = a["verts"]
        cdef const double[::1] crust = a["crust"], crust_rel = a["crust_rel"], radius = a["radius"]
        self.arrays = a
        self.t.nrows = <int>kind.shape[0]
        self.t.kind = &kind[0]
        self.t.params = &params[0, 0]
        self.t.voff = &voff[0]
        self.t.nv = &nv[0]
        self.t.core_kind = &core_kind[0]
        self.t.core_params = &core_params[0, 0]
        self.t.core_voff = &core_voff[0]
        self.t.core_nv = &core_nv[0]
        self.t.crust = &crust[0]
        self.t.crust_rel = &crust_rel[0]
        self.t.radius = &radius[0]
        self.t.is_sphere = &is_sphere[0]
        self.t.verts = &verts[0, 0]
        self.t.comp_first = &comp_first[0]
        self.t.comp_count = &comp_count[0]
        self.t.comp_row = &comp_row[0]
        self.t.comp_pose = &comp_pose[0, 0]
        self.t.half = &half[0, 0]

    def __len__(self):
        return self.t.nrows
