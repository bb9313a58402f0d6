"""Polytope topology (faces as planar polygons, edges, adjacency) and its flat packing for the kernels.

Every polytope shape (``Box`` incl. ``cube``, ``Polyhedron`` incl. ``tetrahedron`` and ``pinacoid``) builds a
``Topology`` at construction, in its body frame, from its vertices and outward hull triangles:

* ``vertices`` (nv, 3): a polyhedron's ``shape.vertices`` (same order, so vertex ids are GJK's ids); a box's
  8 corners in ``box_corners`` order (corner k: bit j set means +h_j, dem/shapes/_support.pxd).
* ``faces``: list of int arrays, the vertex ids of each face polygon, counter-clockwise seen from outside.
  Coplanar hull triangles (normals within ``COPLANAR`` radians, sharing an edge) are merged, and vertices
  that are interior to a polygon side (collinear, 180 degree corners) are dropped from the polygon.
* ``face_normals`` (nf, 3) unit outward and ``face_offsets`` (nf,): the face plane is n.x = d, the body is
  n.x <= d; d is the maximum of n.v over the face's vertices (the plane supports the body).
* ``edges`` (ne, 2) vertex ids (v0, v1) and ``edge_faces`` (ne, 2) the two adjacent faces (f0, f1), f0 the
  face that runs v0 -> v1 in its counter-clockwise order, f1 the one that runs v1 -> v0.

Euler's V - E + F = 2 is checked on the vertices the faces use.

``pack_topology(rows)`` packs the topologies of a list of shapes (e.g. ``ShapeTable.rows``, so row indices
match the shape table) into flat arrays for a future ``TableView`` field, per row offsets and counts into
shared arrays like ``voff``/``nv`` of dem/shapes/table.py (see ``pack_topology``). Indices stored in the
shared arrays are local to the row (a vertex id is 0..nv-1 of that row, a face id 0..nf-1). The kernels
(dem/contact/_polytope.pyx) read them through ``TopologyView``.
"""
import numpy as np

COPLANAR = 1e-9          # radians: adjacent hull triangles closer than this are one face
COLLINEAR = 1e-12        # |sin| of a polygon corner below which the corner vertex is dropped


class Topology:
    """Faces, normals, offsets and edges of a convex polytope in its body frame (see the module doc)."""

    def __init__(self, vertices, faces, face_normals, face_offsets, edges, edge_faces):
        self.vertices = np.ascontiguousarray(vertices, float).reshape(-1, 3)
        self.faces = [np.asarray(f, np.int32) for f in faces]
        self.face_normals = np.ascontiguousarray(face_normals, float).reshape(-1, 3)
        self.face_offsets = np.ascontiguousarray(face_offsets, float).reshape(-1)
        self.edges = np.ascontiguousarray(edges, np.int32).reshape(-1, 2)
        self.edge_faces = np.ascontiguousarray(edge_faces, np.int32).reshape(-1, 2)

    @property
    def nv(self):
        return len(self.vertices)

    @property
    def nf(self):
        return len(self.faces)

    @property
    def ne(self):
        return len(self.edges)

    def __repr__(self):
        return "<Topology V=%d E=%d F=%d>" % (self.nv, self.ne, self.nf)


def _edges_of(faces):
    """Edges (v0, v1) and their faces (f0 running v0 -> v1, f1 running v1 -> v0), in first-seen order.
    Vectorised (a scanned grain has tens of thousands of faces): every directed side of every face
    polygon, grouped by its undirected key; a closed surface has each key exactly twice, reversed."""
    counts = np.array([len(f) for f in faces], np.int64)
    a = np.concatenate(faces).astype(np.int64)
    first = np.r_[0, np.cumsum(counts)[:-1]]
    nxt = np.arange(1, len(a) + 1)
    nxt[first + counts - 1] = first                 # the side from a face's last vertex to its first
    b = a[nxt]
    face = np.repeat(np.arange(len(faces)), counts)
    key = np.minimum(a, b) * (int(a.max()) + 1) + np.maximum(a, b)
    order = np.argsort(key, kind="stable")          # the sides of one edge, in the order they were seen
    _, at, many = np.unique(key[order], return_index=True, return_counts=True)
    one, two = order[at], order[np.minimum(at + 1, len(order) - 1)]
    bad = (many > 2) | ((many == 2) & ((a[two] != b[one]) | (b[two] != a[one])))
    if np.any(bad):
        k = one[np.argmax(bad)]
        raise ValueError("topology: edge %r is not shared by exactly two faces with opposite "
                         "orientations" % ((int(min(a[k], b[k])), int(max(a[k], b[k]))),))
    if np.any(many == 1):
        raise ValueError("topology: open surface (an edge with one face)")
    seen = np.argsort(one, kind="stable")           # first-seen order
    one, two = one[seen], two[seen]
    return (np.c_[a[one], b[one]].astype(np.int32).reshape(-1, 2),
            np.c_[face[one], face[two]].astype(np.int32).reshape(-1, 2))


def _check_euler(faces, edges):
    used = np.unique(np.concatenate(faces))
    if len(used) - len(edges) + len(faces) != 2:
        raise ValueError("topology: Euler characteristic %d != 2" % (len(used) - len(edges) + len(faces)))


def _rowdot(x, y):
    """Row-wise x . y computed as ndarray.dot of each row (batched matmul rounds alike), so that the
    vectorised faces equal those computed one by one, bit for bit."""
    return np.matmul(x[:, None, :], y[:, :, None])[:, 0, 0]


def from_triangles(V, F):
    """Topology of the convex polytope with vertices V and outward triangles F (a closed convex hull).

    Vectorised over the triangles: a scanned grain's hull has tens of thousands, and a Python loop per
    triangle cost seconds. Only groups of coplanar triangles (merged faces, few) go through a loop."""
    V = np.asarray(V, float).reshape(-1, 3)
    F = np.asarray(F, np.int64).reshape(-1, 3)
    T = len(F)
    c = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    n = c / np.linalg.norm(c, axis=1)[:, None]
    area = np.linalg.norm(c, axis=1)
    # triangles sharing an edge with (nearly) equal normals are one face: connected components of
    # those pairs; a face is named by its lowest triangle, and faces come in that order
    a, b = F.reshape(-1), F[:, [1, 2, 0]].reshape(-1)
    key = np.minimum(a, b) * (len(V) + 1) + np.maximum(a, b)
    order = np.argsort(key, kind="stable")
    _, at, many = np.unique(key[order], return_index=True, return_counts=True)
    at = at[many == 2]
    t0, t1 = order[at] // 3, order[at + 1] // 3
    d = n[t0] - n[t1]
    join = np.sqrt(_rowdot(d, d)) < COPLANAR
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    graph = coo_matrix((np.ones(int(join.sum())), (t0[join], t1[join])), shape=(T, T))
    _, label = connected_components(graph, directed=False)
    lowest = np.full(label.max() + 1, T)
    np.minimum.at(lowest, label, np.arange(T))
    root = lowest[label]
    roots, size = np.unique(root, return_counts=True)
    # single triangles: the polygon is the triangle from its lowest vertex id
    single = roots[size == 1]
    k0 = np.argmin(F[single], axis=1)
    tri = F[single[:, None], (k0[:, None] + np.arange(3)) % 3]
    w = n[single] * area[single, None]
    nrm1 = w / np.sqrt(_rowdot(w, w))[:, None]
    off1 = np.matmul(V[tri], nrm1[:, :, None])[:, :, 0].max(1)
    faces = [None] * len(roots)
    normals = np.empty((len(roots), 3))
    offsets = np.empty(len(roots))
    pos1 = np.flatnonzero(size == 1)
    normals[pos1], offsets[pos1] = nrm1, off1
    tri32 = tri.astype(np.int32)
    for p, f in zip(pos1.tolist(), tri32):
        faces[p] = f
    merged = np.flatnonzero(size > 1)
    if len(merged):
        members = np.argsort(root, kind="stable")    # triangles by face, increasing within each
        bounds = np.r_[0, np.cumsum(size)]
        for p in merged.tolist():
            ts = members[bounds[p]:bounds[p + 1]]
            faces[p], normals[p], offsets[p] = _merged_face(V, F, n, area, ts)
    edges, ef = _edges_of(faces)
    _check_euler(faces, edges)
    return Topology(V, faces, normals, offsets, edges, ef)


def _merged_face(V, F, n, area, ts):
    """(polygon, unit normal, offset) of the face made of the coplanar triangles ts."""
    nf = (n[ts] * area[ts, None]).sum(0)
    nf /= np.linalg.norm(nf)
    # the boundary of the group: directed triangle edges whose reverse is not in the group
    directed = set()
    for t in ts:
        for k in range(3):
            directed.add((int(F[t, k]), int(F[t, (k + 1) % 3])))
    nxt = {a: b for (a, b) in directed if (b, a) not in directed}
    start = min(nxt)
    loop = [start]
    while True:
        b = nxt[loop[-1]]
        if b == start:
            break
        loop.append(b)
        if len(loop) > len(nxt):
            raise ValueError("topology: face boundary is not a single loop")
    loop = _drop_collinear(V, loop, nf)
    return np.array(loop, np.int32), nf, float((V[loop] @ nf).max())


def _drop_collinear(V, loop, nf):
    """The loop without vertices at 180 degree corners (they would make zero-length-turn edges)."""
    changed = True
    loop = list(loop)
    while changed and len(loop) > 3:
        changed = False
        for k in range(len(loop)):
            a, b, c = V[loop[k - 1]], V[loop[k]], V[loop[(k + 1) % len(loop)]]
            u, w = b - a, c - b
            s = np.dot(np.cross(u, w), nf)
            if abs(s) <= COLLINEAR * np.linalg.norm(u) * np.linalg.norm(w) and np.dot(u, w) > 0:
                del loop[k]
                changed = True
                break
    k0 = int(np.argmin(loop))                     # start at the lowest vertex id: deterministic
    return loop[k0:] + loop[:k0]


def box_topology(half):
    """Topology of the box of half sides ``half``: corners in box_corners order (bit j set: +h_j), faces
    -x, +x, -y, +y, -z, +z (face 2j + s has normal (2s - 1) e_j)."""
    h = np.asarray(half, float)
    V = np.array([[(1 if k & 1 else -1) * h[0], (1 if k & 2 else -1) * h[1], (1 if k & 4 else -1) * h[2]]
                  for k in range(8)])
    faces, normals, offsets = [], [], []
    for j in range(3):
        a, b = (j + 1) % 3, (j + 2) % 3           # (j, a, b) right-handed
        for s in (0, 1):
            bit = (1 << j) if s else 0
            # corners of this face in counter-clockwise order seen from outside
            quad = [bit, bit | (1 << a), bit | (1 << a) | (1 << b), bit | (1 << b)]
            if not s:
                quad = quad[::-1]
            k0 = int(np.argmin(quad))
            quad = quad[k0:] + quad[:k0]
            nrm = np.zeros(3)
            nrm[j] = 1.0 if s else -1.0
            faces.append(np.array(quad, np.int32))
            normals.append(nrm)
            offsets.append(float(h[j]))
    edges, ef = _edges_of(faces)
    _check_euler(faces, edges)
    return Topology(V, faces, normals, offsets, edges, ef)


def check(topo, tol=1e-9):
    """Raise if the topology is not that of a convex polytope (tests): planar CCW faces, supporting planes."""
    V = topo.vertices
    R = max(np.linalg.norm(V, axis=1).max(), 1e-300)
    for f, nrm, d in zip(topo.faces, topo.face_normals, topo.face_offsets):
        P = V[f]
        if np.abs(P @ nrm - d).max() > tol * R:
            raise ValueError("non-planar face")
        if (V @ nrm).max() > d + tol * R:
            raise ValueError("face plane does not support the body")
        area = sum(np.cross(P[k] - P[0], P[k + 1] - P[0]) for k in range(1, len(P) - 1))
        if np.dot(area, nrm) <= 0:
            raise ValueError("face not counter-clockwise seen from outside")


# ---------------------------------------------------------------- flat packing
PACKED_COLUMNS = ("poly", "voff", "nv", "foff", "nf", "eoff", "ne", "fvoff", "radius",
                  "verts", "face_normal", "face_offset", "face_first", "face_count", "face_verts",
                  "edge_verts", "edge_faces", "box_half")


def box_half(topo):
    """The half sides of a topology laid out exactly as box_topology's (corner, face and edge order), else
    None: the kernels take the 15-axis box path for such rows (dem/contact/_polytope.pyx)."""
    if topo.nv != 8 or topo.nf != 6 or topo.ne != 12:
        return None
    h = np.abs(topo.vertices[7])
    ref = box_topology(h)
    if not (np.array_equal(topo.vertices, ref.vertices) and np.array_equal(topo.face_normals, ref.face_normals)
            and np.array_equal(topo.edges, ref.edges) and np.array_equal(topo.edge_faces, ref.edge_faces)):
        return None
    return h


def pack_topology(shapes):
    """Flat arrays of the topologies of ``shapes`` (one row each; rows without a topology have zero counts).

    Per row s (int64 offsets, int32 counts, like voff/nv of the shape table):
      ``poly[s]`` 1 if the row is a polytope; ``voff[s], nv[s]`` into ``verts`` (V, 3) (the topology's
      vertices, body frame); ``foff[s], nf[s]`` into the face arrays ``face_normal`` (F, 3), ``face_offset``
      (F,), ``face_first`` (F,) and ``face_count`` (F,); ``fvoff[s]`` into ``face_verts``: face f of row s has
      the vertex ids ``face_verts[fvoff[s] + face_first[foff[s] + f] + k]``, k < ``face_count[foff[s] + f]``;
      ``eoff[s], ne[s]`` into ``edge_verts`` (E, 2) and ``edge_faces`` (E, 2); ``radius[s]`` the largest vertex
      norm; ``box_half[s]`` (3,) the half sides of a row laid out as box_topology's, else zeros (``box_half``).
      All ids stored are local to the row. Empty shared arrays get one dummy entry (never read).
    """
    n = len(shapes)
    out = {k: np.zeros(n, np.int64) for k in ("voff", "foff", "eoff", "fvoff")}
    out.update({k: np.zeros(n, np.int32) for k in ("poly", "nv", "nf", "ne")})
    out["radius"] = np.zeros(n)
    out["box_half"] = np.zeros((n, 3))
    V, FN, FO, FF, FC, FV, EV, EF = [], [], [], [], [], [], [], []
    nv = nf = ne = nfv = 0
    for i, s in enumerate(shapes):
        t = getattr(s, "topology", None)
        if t is None:
            continue
        out["poly"][i] = 1
        out["voff"][i], out["nv"][i] = nv, t.nv
        out["foff"][i], out["nf"][i] = nf, t.nf
        out["eoff"][i], out["ne"][i] = ne, t.ne
        out["fvoff"][i] = nfv
        out["radius"][i] = float(np.linalg.norm(t.vertices, axis=1).max())
        h = box_half(t)
        if h is not None:
            out["box_half"][i] = h
        V.append(t.vertices)
        FN.append(t.face_normals)
        FO.append(t.face_offsets)
        counts = np.array([len(f) for f in t.faces], np.int32)
        FC.append(counts)
        FF.append(np.r_[0, np.cumsum(counts)[:-1]].astype(np.int32))
        FV.append(np.concatenate(t.faces).astype(np.int32))
        EV.append(t.edges)
        EF.append(t.edge_faces)
        nv, nf, ne, nfv = nv + t.nv, nf + t.nf, ne + t.ne, nfv + int(counts.sum())

    def cat(blocks, shape, dtype):
        if not blocks:
            return np.zeros(shape, dtype)
        return np.ascontiguousarray(np.concatenate(blocks).astype(dtype))
    out["verts"] = cat(V, (1, 3), float)
    out["face_normal"] = cat(FN, (1, 3), float)
    out["face_offset"] = cat(FO, (1,), float)
    out["face_first"] = cat(FF, (1,), np.int32)
    out["face_count"] = cat(FC, (1,), np.int32)
    out["face_verts"] = cat(FV, (1,), np.int32)
    out["edge_verts"] = cat(EV, (1, 2), np.int32)
    out["edge_faces"] = cat(EF, (1, 2), np.int32)
    return out
