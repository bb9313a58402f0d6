"""Triangle meshes for mesh walls: reading STL (ASCII or binary) and Wavefront OBJ files, welding the
triangle soup into an indexed mesh with shared vertices and edges, and writing STL (for tools and tests).

    tris = read_triangles("inputs/meshes/hopper.stl")     # (nt, 3, 3) float64, one row per corner
    mesh = weld(tris)                                     # Mesh: vertices, triangles, edges, normals
    mesh = load("hopper.stl").transformed(scale=1e-3)     # the same in one call; mm -> m

File formats: dem/mesh_file.py (read_triangles, shared with `shape polyhedron file`).

Welding (`weld`): corners closer than tol x the bounding-box diagonal become one vertex (pairs found with
a k-d tree, so two corners either side of a rounding-grid boundary still merge; chains of close corners
merge transitively; the vertex keeps the coordinates of its first corner in file order). Triangles left
with two equal vertex ids, or with a height over their longest edge at most tol x the diagonal (zero
area at that tolerance), are dropped and counted in `Mesh.dropped`. Vertices no triangle uses are removed.
"""
import math
import os
import struct

import numpy as np

from dem.errors import DemError
from dem.mesh_file import STL_RECORD, read_triangles

__all__ = ["Mesh", "load", "read_motion", "read_triangles", "rotation_about", "weld"]

_BINARY_HEADER = b"binary STL written by dem (dem_walls.mesh)"


# ---------------------------------------------------------------------------------------------- meshes

class Mesh:
    """An indexed triangle mesh (build it with `weld` or `load`). All arrays are C-contiguous:

    * vertices (nv, 3) float64
    * triangles (nt, 3) int32: vertex ids of each triangle's corners v0 v1 v2
    * edges (nt, 3) int32: edges[t, k] is the id (0 .. nedges-1) of the edge joining corners k and
      (k+1) % 3 of triangle t; a shared edge has one id
    * edge_vertices (nedges, 2) int32: the two vertex ids of each edge, lower id first
    * normals (nt, 3) float64: unit normals, right-hand rule over v0 v1 v2
    * nedges: the number of distinct edges
    * dropped: the number of degenerate triangles dropped while welding

    Meshes made by `transformed` share the topology arrays (triangles, edges, edge_vertices): treat them
    as read-only."""

    def __init__(self, vertices, triangles, dropped=0, _topology=None):
        self.vertices = np.ascontiguousarray(vertices, dtype=np.float64).reshape(-1, 3)
        self.dropped = int(dropped)
        if _topology is not None:
            self.triangles, self.edges, self.edge_vertices = _topology
        else:
            self.triangles = np.ascontiguousarray(triangles, dtype=np.int32).reshape(-1, 3)
            if len(self.triangles) and (self.triangles.min() < 0 or self.triangles.max() >= len(self.vertices)):
                raise ValueError("Mesh: vertex id out of range")
            self.edges, self.edge_vertices = _edges(self.triangles)
        self.nedges = len(self.edge_vertices)
        self.normals = _normals(self.vertices, self.triangles)

    def __repr__(self):
        return (f"Mesh({len(self.vertices)} vertices, {len(self.triangles)} triangles, {self.nedges} edges, "
                f"{self.boundary_edges()} boundary edges, {self.dropped} dropped)")

    def transformed(self, scale=1.0, offset=(0.0, 0.0, 0.0), rotation=None):
        """A new Mesh with vertices scale * R v + offset (R = rotation, a proper 3x3 rotation matrix, or the
        identity) and normals R n; the topology arrays are shared with this mesh."""
        scale = float(scale)
        if not scale > 0.0:
            raise DemError(f"mesh scale must be positive, got {scale:g}")
        offset = np.asarray(offset, dtype=np.float64)
        if offset.shape != (3,) or not np.isfinite(offset).all():
            raise DemError(f"mesh offset must be 3 finite numbers, got {offset.tolist()}")
        if rotation is None:
            rot = np.eye(3)
        else:
            rot = np.asarray(rotation, dtype=np.float64)
            if rot.shape != (3, 3) or not np.allclose(rot.T @ rot, np.eye(3), atol=1e-9) \
                    or np.linalg.det(rot) <= 0.0:
                raise DemError("mesh rotation must be a 3x3 rotation matrix (orthonormal, determinant +1)")
        vertices = scale * (self.vertices @ rot.T) + offset
        out = Mesh(vertices, None, self.dropped, _topology=(self.triangles, self.edges, self.edge_vertices))
        out.normals = np.ascontiguousarray(self.normals @ rot.T)
        return out

    def area(self):
        """Total area of the triangles."""
        v = self.vertices[self.triangles]
        return float(0.5 * np.linalg.norm(np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), axis=1).sum())

    def bounds(self):
        """(lo, hi): the corners of the bounding box, two (3,) arrays."""
        return self.vertices.min(axis=0), self.vertices.max(axis=0)

    def boundary_edges(self):
        """The number of edges used by one triangle only (0 for a closed surface)."""
        uses = np.bincount(self.edges.ravel(), minlength=self.nedges)
        return int(np.count_nonzero(uses == 1))

    def write_stl(self, path, binary=True, name="dem_mesh"):
        """Write the mesh as a binary STL (float32 coordinates) or an ASCII STL (coordinates written with
        repr: they read back exactly)."""
        path = os.fspath(path)
        corners = self.vertices[self.triangles]
        try:
            if binary:
                records = np.zeros(len(self.triangles), dtype=STL_RECORD)
                records["normal"] = self.normals
                records["v"] = corners
                with open(path, "wb") as f:
                    f.write(_BINARY_HEADER.ljust(80, b" "))
                    f.write(struct.pack("<I", len(records)))
                    f.write(records.tobytes())
            else:
                lines = [f"solid {name}"]
                for n, tri in zip(self.normals.tolist(), corners.tolist()):
                    lines.append(f"  facet normal {n[0]!r} {n[1]!r} {n[2]!r}")
                    lines.append("    outer loop")
                    for x, y, z in tri:
                        lines.append(f"      vertex {x!r} {y!r} {z!r}")
                    lines.append("    endloop")
                    lines.append("  endfacet")
                lines.append(f"endsolid {name}\n")
                with open(path, "w") as f:
                    f.write("\n".join(lines))
        except OSError as e:
            raise DemError(f"cannot write mesh file '{path}' ({e.strerror or e})") from None


def _edges(triangles):
    """(edges (nt, 3), edge_vertices (ne, 2)) of an (nt, 3) vertex-id array."""
    a = triangles.astype(np.int64)
    b = np.roll(a, -1, axis=1)                  # corner (k+1) % 3
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    nv = int(hi.max()) + 1 if len(hi) else 1
    unique, inverse = np.unique((lo * nv + hi).ravel(), return_inverse=True)
    edges = np.ascontiguousarray(inverse.reshape(-1, 3), dtype=np.int32)
    edge_vertices = np.stack([unique // nv, unique % nv], axis=1)
    return edges, np.ascontiguousarray(edge_vertices, dtype=np.int32)


def _normals(vertices, triangles):
    v = vertices[triangles]
    n = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
    length = np.linalg.norm(n, axis=1, keepdims=True)
    return np.ascontiguousarray(n / np.where(length > 0.0, length, 1.0))


def weld(triangles, tol=1e-9):
    """An indexed Mesh from an (nt, 3, 3) triangle soup: corners closer than tol x the bounding-box
    diagonal merge; degenerate triangles (two equal vertex ids, or height over the longest edge at most
    tol x the diagonal) are dropped and counted in Mesh.dropped. Raises DemError when none is left."""
    tris = np.asarray(triangles, dtype=np.float64)
    if tris.ndim != 3 or tris.shape[1:] != (3, 3):
        raise ValueError(f"weld: triangles must have shape (nt, 3, 3), got {tris.shape}")
    if len(tris) == 0:
        raise DemError("mesh has no triangles")
    if not np.isfinite(tris).all():
        raise DemError("mesh has a non-finite coordinate")
    tol = float(tol)
    if not tol >= 0.0:
        raise ValueError(f"weld: tol must be >= 0, got {tol}")
    corners = tris.reshape(-1, 3)
    diagonal = float(np.linalg.norm(corners.max(axis=0) - corners.min(axis=0)))
    eps = tol * diagonal
    # exact duplicates first (the usual case: shared corners written out again), then near ones
    sort = np.lexsort(corners.T[::-1])
    ordered = corners[sort]
    new = np.ones(len(corners), dtype=bool)
    new[1:] = (ordered[1:] != ordered[:-1]).any(axis=1)
    inverse = np.empty(len(corners), dtype=np.int64)
    inverse[sort] = np.cumsum(new) - 1
    unique = ordered[new]
    n = len(unique)
    if eps > 0.0 and n > 1:
        # (compact_nodes=False: compacting slows query_pairs ~20x on coordinates with few distinct values,
        # as on a ring of points at one height)
        from scipy.sparse import coo_matrix        # here: scipy is a fifth of every start-up
        from scipy.sparse.csgraph import connected_components
        from scipy.spatial import cKDTree
        tree = cKDTree(unique, balanced_tree=False, compact_nodes=False)
        pairs = tree.query_pairs(eps, output_type="ndarray")
        graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
        nclusters, label = connected_components(graph, directed=False)
    else:
        nclusters, label = n, np.arange(n)
    cluster = label[inverse]                      # the cluster of each corner
    # each vertex at the coordinates of its cluster's first corner in file order
    _, first = np.unique(cluster, return_index=True)
    tri_ids = cluster.reshape(-1, 3)
    # degenerate: repeated id, or height (2 area / longest edge) <= eps
    v = corners[first][tri_ids]
    doubled_area = np.linalg.norm(np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), axis=1)
    longest = np.linalg.norm(v - np.roll(v, -1, axis=1), axis=2).max(axis=1)
    repeated = (tri_ids[:, 0] == tri_ids[:, 1]) | (tri_ids[:, 1] == tri_ids[:, 2]) | \
        (tri_ids[:, 2] == tri_ids[:, 0])
    flat = doubled_area <= eps * longest
    keep = ~(repeated | flat)
    dropped = int(len(tris) - np.count_nonzero(keep))
    if not keep.any():
        raise DemError(f"mesh has no triangles left: all {len(tris)} are degenerate (zero area at welding "
                       f"tolerance {tol:g} x the bounding-box diagonal {diagonal:g})")
    tri_ids = tri_ids[keep]
    # number the used vertices by first appearance among the kept triangles
    used, first_use = np.unique(tri_ids.ravel(), return_index=True)
    used = used[np.argsort(first_use)]
    renumber = np.empty(nclusters, dtype=np.int64)
    renumber[used] = np.arange(len(used))
    vertices = corners[first[used]]
    return Mesh(vertices, renumber[tri_ids], dropped)


def load(path, tol=1e-9):
    """weld(read_triangles(path), tol), with the file named in a DemError."""
    tris = read_triangles(path)
    try:
        return weld(tris, tol)
    except DemError as e:
        raise DemError(f"mesh file '{os.fspath(path)}': {e.message}") from None


def rotation_about(axis, angle):
    """The 3x3 matrix of the rotation by angle (radians, right-hand rule) about axis (any length > 0)
    (Rodrigues' formula)."""
    axis = np.asarray(axis, dtype=np.float64)
    length = np.linalg.norm(axis)
    if axis.shape != (3,) or not length > 0.0 or not np.isfinite(length):
        raise DemError(f"rotation axis must be a non-zero vector of 3 numbers, got {axis.tolist()}")
    x, y, z = axis / length
    k = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    return np.eye(3) + np.sin(angle) * k + (1.0 - np.cos(angle)) * (k @ k)


def read_motion(path, what):
    """A motion table for a mesh wall: lines `t dx dy dz angle` (s, m, degrees), `#` comments and blank
    lines ignored, times increasing. Returns (t (n,), displacement (n, 3), angle (n,) in radians); DemError
    naming `what`, the file and the line otherwise."""
    rows = []
    try:
        with open(path, encoding="utf-8") as fh:
            lines = fh.readlines()
    except OSError as e:
        raise DemError(f"{what}: cannot read the motion table '{path}': {e.strerror or e}") from None
    except UnicodeDecodeError:
        raise DemError(f"{what}: the motion table '{path}' is not a text file") from None
    for lineno, line in enumerate(lines, 1):
        words = line.split("#", 1)[0].split()
        if not words:
            continue
        if len(words) != 5:
            raise DemError(f"{what}: {path}:{lineno}: expected 't dx dy dz angle', got {len(words)} value(s)")
        try:
            row = [float(w) for w in words]
        except ValueError:
            raise DemError(f"{what}: {path}:{lineno}: not a number in '{line.strip()}'") from None
        if not all(math.isfinite(v) for v in row):
            raise DemError(f"{what}: {path}:{lineno}: not a finite number in '{line.strip()}'")
        if rows and not row[0] > rows[-1][0]:
            raise DemError(f"{what}: {path}:{lineno}: times must increase ({row[0]:g} after {rows[-1][0]:g})")
        rows.append(row)
    if not rows:
        raise DemError(f"{what}: the motion table '{path}' has no line")
    table = np.array(rows)
    return table[:, 0].copy(), np.ascontiguousarray(table[:, 1:4]), np.radians(table[:, 4])
