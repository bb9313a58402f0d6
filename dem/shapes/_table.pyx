# cython: language_level=3
"""ShapeView: the shape table's arrays behind one TableView struct (see _table.pxd)."""
import numpy as np

COLUMNS = ("kind", "params", "voff", "nv", "core_kind", "core_params", "core_voff", "core_nv", "crust", "crust_rel",
           "radius", "is_sphere", "verts", "comp_first", "comp_count", "comp_row", "comp_pose",
           "half", "req_rel")
COMPONENT_POSE = COMP_POSE            # (for Python: table.py)
TOPOLOGY_COLUMNS = ("poly", "voff", "nv", "foff", "nf", "eoff", "ne", "fvoff", "radius", "verts", "face_normal",
                    "face_offset", "face_first", "face_count", "face_verts", "edge_verts", "edge_faces", "box_half")


cdef dict topology_pointers(dict packed, TopoTable* t):
    """Points t at the arrays of pack_topology (made contiguous and typed); returns them (keep them alive)."""
    a = {k: np.ascontiguousarray(packed[k]) for k in TOPOLOGY_COLUMNS}
    for k in ("voff", "foff", "eoff", "fvoff"):
        a[k] = a[k].astype(np.int64)
    for k in ("poly", "nv", "nf", "ne", "face_first", "face_count", "face_verts", "edge_verts", "edge_faces"):
        a[k] = np.ascontiguousarray(a[k], np.int32).reshape(-1)
    for k in ("radius", "verts", "face_normal", "face_offset", "box_half"):
        a[k] = np.ascontiguousarray(a[k], float).reshape(-1)
    cdef const int[::1] poly = a["poly"], nv = a["nv"], nf = a["nf"], ne = a["ne"]
    cdef const int[::1] ff = a["face_first"], fc = a["face_count"], fv = a["face_verts"]
    cdef const int[::1] ev = a["edge_verts"], ef = a["edge_faces"]
    cdef const i64[::1] voff = a["voff"], foff = a["foff"], eoff = a["eoff"], fvoff = a["fvoff"]
    cdef const double[::1] radius = a["radius"], verts = a["verts"], fn = a["face_normal"]
    cdef const double[::1] fo = a["face_offset"], bh = a["box_half"]
    t.nrows = <int>poly.shape[0]
    t.poly = &poly[0]
    t.voff = &voff[0]
    t.nv = &nv[0]
    t.foff = &foff[0]
    t.nf = &nf[0]
    t.eoff = &eoff[0]
    t.ne = &ne[0]
    t.fvoff = &fvoff[0]
    t.radius = &radius[0]
    t.verts = &verts[0]
    t.face_normal = &fn[0]
    t.face_offset = &fo[0]
    t.face_first = &ff[0]
    t.face_count = &fc[0]
    t.face_verts = &fv[0]
    t.edge_verts = &ev[0]
    t.edge_faces = &ef[0]
    t.box_half = &bh[0]
    return a


cdef class ShapeView:
    """Built from the arrays of ShapeTable.kernel_arrays() (or the one-row dummy of an empty table); the
    composite columns and the topology (`topology`: pack_topology's dict) may be left out (a table without
    composites, without polytopes)."""

    def __cinit__(self, dict arrays):
        n = len(arrays["kind"])
        defaults = {"comp_first": np.full(n, -1, np.int32), "comp_count": np.zeros(n, np.int32),   # no composite
                    "comp_row": np.zeros(1, np.int32), "comp_pose": np.zeros((1, COMP_POSE)), "half": np.zeros((n, 3)),
                    "req_rel": np.ones(n)}
        a = {k: np.ascontiguousarray(arrays[k] if k in arrays else defaults[k]) for k in COLUMNS}
        cdef const int[::1] kind = a["kind"], nv = a["nv"], core_kind = a["core_kind"]
        cdef const int[::1] core_nv = a["core_nv"], is_sphere = a["is_sphere"]
        cdef const int[::1] comp_first = a["comp_first"], comp_count = a["comp_count"], comp_row = a["comp_row"]
        cdef const double[:, ::1] comp_pose = a["comp_pose"], half = a["half"]
        cdef const i64[::1] voff = a["voff"], core_voff = a["core_voff"]
        cdef const double[:, ::1] params = a["params"], core_params = a["core_params"], verts = a["verts"]
        cdef const double[::1] crust = a["crust"], crust_rel = a["crust_rel"], radius = a["radius"]
        cdef const double[::1] req_rel = a["req_rel"]
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
        self.t.req_rel = &req_rel[0]
        if "topology" in arrays:
            a["topology"] = topology_pointers(arrays["topology"], &self.t.topo)
        else:
            from .topology import pack_topology
            a["topology"] = topology_pointers(pack_topology([None] * n), &self.t.topo)

    def __len__(self):
        return self.t.nrows
