"""Convex polyhedra: from vertices, OBJ/STL files, the regular tetrahedron and Descantes' pinacoid.

The convex hull (scipy.spatial.ConvexHull) of the given points is the shape. Mass properties come from
the divergence theorem on the outward triangulated hull (signed tetrahedra from the origin). The shape is
then recentred on its centre of mass and rotated onto its principal axes; ``centroid`` and ``rotation``
record that transform (input point = centroid + rotation @ body point). Among the equivalent principal
frames the one closest to the input axes is chosen, so a shape already given in principal axes (a box,
the pinacoid) keeps them, and degenerate moments (cube, tetrahedron) keep the input axes.
"""
import numpy as np

from .. import mesh_file
from .base import POLYHEDRON, Shape, check_lengths, mesh_volume, packed_params
from .topology import from_triangles

_DEGENERATE = 1e-9   # relative gap below which two principal moments are treated as equal
# Thinnest polyhedron, as a fraction of its largest extent. Below it the default crust (5 % of the
# inradius, < 2.5e-8 of the size) comes within 100 times the 1e-10 corner-merge tolerance of the core
# (_make_core) and near the 1e-9 coplanarity of the faces (topology.py): the core and the faces would be
# round-off, not geometry. (And a slab's smallest principal moment would be under 1e-12 of its largest.)
THINNEST = 1e-6
_FLAT = 1e-12        # width / extent at round-off level: the points are coplanar (collinear), not thin


def check_points(P):
    """ValueError unless the points span a solid: finite and bounded (check_lengths), at least 4 distinct,
    not collinear, not coplanar, and no thinner than THINNEST of their largest extent. Repeated points are
    allowed (the hull does not depend on them; an STL file repeats every corner in each of its facets)."""
    check_lengths(P, "polyhedron points")
    distinct = len(np.unique(P, axis=0))
    if distinct < 4:
        raise ValueError(f"a polyhedron needs at least 4 distinct points, got {distinct}")
    Pc = P - P.mean(0)
    _, _, Vt = np.linalg.svd(Pc, full_matrices=False)
    w = np.ptp(Pc @ Vt.T, axis=0)               # widths along the principal directions, largest first
    D = w[0]
    if w[1] <= _FLAT * D:
        raise ValueError("the points are collinear: a polyhedron needs volume")
    if w[2] <= _FLAT * D:
        raise ValueError("the points are coplanar: a polyhedron needs volume")
    if w[2] < THINNEST * D:
        raise ValueError(f"the polyhedron is {w[2]:.3g} thick for an extent of {D:.3g}: thinner than "
                         f"{THINNEST:g} of its size, its crust and faces would be round-off")


def _qhull(make, what):
    """make() with Qhull's errors (degenerate input Qhull could not resolve) as a one-line ValueError."""
    from scipy.spatial import QhullError
    try:
        return make()
    except QhullError as e:
        first = next((line for line in str(e).splitlines() if line.strip()), "")
        raise ValueError(f"{what}: Qhull failed ({first.strip()})") from None


def hull_mesh(points):
    """(vertices, outward triangles) of the convex hull of ``points``; vertices are the hull vertices only."""
    P = np.asarray(points, dtype=float).reshape(-1, 3)
    if len(P) < 4:
        raise ValueError("a polyhedron needs at least 4 points")
    from scipy.spatial import ConvexHull    # scipy is imported only when a hull is built
    h = _qhull(lambda: ConvexHull(P), "the convex hull of the points")
    idx = np.full(len(P), -1)
    idx[h.vertices] = np.arange(len(h.vertices))
    V = P[h.vertices]
    F = idx[h.simplices]
    n = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    flip = np.einsum("ij,ij->i", n, h.equations[:, :3]) < 0
    F[flip] = F[flip][:, [0, 2, 1]]
    return V, F, h.equations


def merge_close(P, tol):
    """P without the points closer than ``tol`` to an earlier kept point, in input order (the first of a
    cluster stands for it). A KD-tree finds the close pairs in O(N log N); only the points in such pairs
    (the few clusters of non-simple vertices) go through the greedy scan, so the result is that of
    comparing every point with every kept one before it, without its O(N^2) cost."""
    P = np.asarray(P, dtype=float).reshape(-1, 3)
    from scipy.spatial import cKDTree
    # a little wider than tol, then the distance of the scan itself decides (|p - q| <= tol merges), so
    # that the tree's own rounding never changes which pairs merge
    pairs = cKDTree(P).query_pairs(tol * (1.0 + 1e-6), output_type="ndarray")
    if len(pairs) == 0:
        return P
    d = np.linalg.norm(P[pairs[:, 0]] - P[pairs[:, 1]], axis=1)
    pairs = np.sort(pairs[d <= tol], axis=1)
    later = {}
    for i, j in pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))]:
        later.setdefault(int(i), []).append(int(j))
    dropped = set()
    for i in sorted(later):          # i is kept unless an earlier kept point dropped it
        if i not in dropped:
            dropped.update(later[i])
    keep = np.ones(len(P), dtype=bool)
    keep[list(dropped)] = False
    return P[keep]


def mesh_mass_properties(V, F):
    """Volume, centre of mass and second moment int x x^T dV of a closed outward triangle mesh."""
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    d6 = np.einsum("ij,ij->i", a, np.cross(b, c))           # 6 x signed volume of tet (0, a, b, c)
    vol = d6.sum() / 6.0
    s = a + b + c
    com = (d6[:, None] * s).sum(0) / 24.0 / vol
    # int over tet (0, a, b, c) of x x^T = d6/120 (a a^T + b b^T + c c^T + s s^T)
    M = np.einsum("i,ij,ik->jk", d6, a, a) + np.einsum("i,ij,ik->jk", d6, b, b) \
        + np.einsum("i,ij,ik->jk", d6, c, c) + np.einsum("i,ij,ik->jk", d6, s, s)
    return float(vol), com, M / 120.0


def inertia_from_second_moment(M):
    return np.trace(M) * np.eye(3) - M


def principal_frame(I):
    """Rotation R (det +1, columns = principal axes) closest to the identity, and moments diag(R^T I R)."""
    w, Q = np.linalg.eigh(I)
    scale = max(abs(w).max(), 1e-300)
    eq01, eq12 = w[1] - w[0] <= _DEGENERATE * scale, w[2] - w[1] <= _DEGENERATE * scale
    if eq01 and eq12:
        R = np.eye(3)
    elif eq01 or eq12:
        u = Q[:, 2] if eq01 else Q[:, 0]            # the distinct axis
        k = int(np.argmax(abs(u)))
        u = u * np.sign(u[k])
        i, j = (k + 1) % 3, (k + 2) % 3
        ei = np.eye(3)[i]
        a = ei - u * (u @ ei)
        if np.linalg.norm(a) < 1e-6:
            ei = np.eye(3)[j]
            a = ei - u * (u @ ei)
            a /= np.linalg.norm(a)
            R = np.empty((3, 3))
            R[:, k], R[:, j] = u, a
            R[:, i] = np.cross(a, u)
        else:
            a /= np.linalg.norm(a)
            R = np.empty((3, 3))
            R[:, k], R[:, i] = u, a
            R[:, j] = np.cross(u, a)
    else:
        from itertools import permutations
        best = max(permutations(range(3)), key=lambda p: sum(abs(Q[p[c], c]) for c in range(3)))
        R = np.empty((3, 3))
        for col, row in enumerate(best):
            R[:, row] = Q[:, col] * np.sign(Q[row, col] or 1.0)
        if np.linalg.det(R) < 0:
            k = int(np.argmin(abs(np.diag(R))))
            R[:, k] = -R[:, k]
    Qr, Rr = np.linalg.qr(R)
    R = Qr * np.sign(np.diag(Rr))      # re-orthonormalised, closest to R
    return R, np.diag(R.T @ I @ R).copy()


class Polyhedron(Shape):
    """Convex hull of a point set, recentred and aligned with its principal axes."""
    kind = POLYHEDRON
    name = "polyhedron"

    def __init__(self, points, crust=None, name=None):
        if name:
            self.name = name
        points = np.asarray(points, dtype=float).reshape(-1, 3)
        check_points(points)
        V, F, _ = hull_mesh(points)
        vol, com, M = mesh_mass_properties(V, F)
        if not vol > 0:
            raise ValueError("%s: degenerate (flat) point set" % self.name)
        Mc = M - vol * np.outer(com, com)
        R, _ = principal_frame(inertia_from_second_moment(Mc))
        self.centroid, self.rotation = com, R
        Vb = (V - com) @ R
        self.vertices = np.ascontiguousarray(Vb)
        self.faces = F                                  # hull triangles (mesh, mass properties)
        self.topology = from_triangles(Vb, F)           # merged planar faces, edges (topology.py)
        self.volume, c2, M2 = mesh_mass_properties(Vb, F)
        I = inertia_from_second_moment(M2 - self.volume * np.outer(c2, c2))
        self.principal_moments = np.diag(I).copy()
        self.params = packed_params()
        self.bounding_radius = float(np.linalg.norm(Vb, axis=1).max())
        eq = self._planes()
        self.inradius = float(-eq[:, 3].max())
        self._init_crust(crust)

    def _planes(self):
        """Unique face planes n.x + off <= 0 (unit outward n) in the body frame."""
        V, F = self.vertices, self.faces
        n = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
        n /= np.linalg.norm(n, axis=1)[:, None]
        off = -np.einsum("ij,ij->i", n, V[F[:, 0]])
        eq = np.c_[n, off]
        key = np.round(np.c_[n, off / max(self.bounding_radius, 1e-300)] * 1e9)
        _, keep = np.unique(key, axis=0, return_index=True)
        return eq[np.sort(keep)]

    def _make_core(self):
        if self.crust == 0.0:
            self.core_kind, self.core_params, self.core_vertices = POLYHEDRON, self.params.copy(), self.vertices
            return
        eq = self._planes().copy()
        eq[:, 3] += self.crust
        from scipy.spatial import HalfspaceIntersection
        hs = _qhull(lambda: HalfspaceIntersection(eq, np.zeros(3)), "the crust core")
        # non-simple vertices (4+ faces) give clusters of nearly equal points: merge them. Every
        # intersection is a vertex of the core (the dual of a facet of the planes' polar hull), so no
        # second hull is taken: it changed nothing on the shapes of the tests and cost 0.8 s of Qhull's
        # facet merging on the near-coplanar core of a 20,000-point grain (benchmarks/shape_build.py)
        Vc = merge_close(hs.intersections, 1e-10 * self.bounding_radius)
        if len(Vc) < 4:
            raise ValueError("%s: crust %g leaves no core (the shape is too thin for it)"
                             % (self.name, self.crust))
        self.core_kind, self.core_params = POLYHEDRON, self.params.copy()
        self.core_vertices = np.ascontiguousarray(Vc)

    def mesh(self, resolution=None):
        return self.vertices.copy(), self.faces.copy()

    def scaled(self, factor):
        s = Polyhedron(self.vertices * factor, crust=self._scaled_crust(factor), name=self.name)
        return s

    @classmethod
    def from_file(cls, path, crust=None, scale=1.0):
        """Convex hull of the vertices of an OBJ or STL (ASCII or binary) file."""
        return cls(np.asarray(read_mesh_vertices(path)) * scale, crust=crust,
                   name=str(path).rsplit("/", 1)[-1].rsplit(".", 1)[0])


def read_mesh_vertices(path):
    """Vertex coordinates of an OBJ or STL file (the shape is their hull)."""
    return read_mesh(path)[0]


def read_mesh(path):
    """(vertices, triangles) of an OBJ or STL (ASCII or binary) file, read as the mesh walls read it
    (dem.mesh_file.read_mesh: an STL's corners three per triangle, which nonconvex_note joins)."""
    path = str(path)
    if not path.lower().endswith((".obj", ".stl")):
        raise ValueError("unsupported mesh file (OBJ or STL): %s" % path)
    return mesh_file.read_mesh(path)


def nonconvex_note(V, T, shape):
    """The warning for a mesh (V, T of read_mesh) whose convex hull, `shape`, is larger than it, else None.
    A closed, consistently oriented mesh is compared by volume (divergence theorem); for another one only
    the vertices the hull leaves inside can tell (its own volume is unknown)."""
    if len(V):          # corners at equal coordinates are one vertex (an STL repeats them per facet)
        V, inverse = np.unique(V, axis=0, return_inverse=True)
        T = inverse.reshape(-1)[T]
    T = T[(T[:, 0] != T[:, 1]) & (T[:, 1] != T[:, 2]) & (T[:, 2] != T[:, 0])]
    glue = "for a non-convex grain, glue convex parts: shape NAME glued component ... (docs/composites.md)"
    if _closed(T):
        own = abs(mesh_volume(V, T))
        if own > 0 and shape.volume > own * (1.0 + 1e-6):       # round-off is ~1e-15 of the volume
            return (f"the mesh is not convex: the shape is its convex hull, volume {shape.volume:.6g}, "
                    f"{100.0 * (shape.volume / own - 1.0):.3g} % more than the mesh's own {own:.6g}; {glue}")
        return None
    from scipy.spatial import ConvexHull
    rest = np.setdiff1d(np.arange(len(V)), _qhull(lambda: ConvexHull(V), "the convex hull").vertices)
    eq = shape._planes()
    X = (V[rest] - shape.centroid) @ shape.rotation
    step = max(1, 2 ** 22 // len(eq))     # blocks of 4 M distances: all at once, 20,000 points took 6 GB
    depth = np.concatenate([-(X[k:k + step] @ eq[:, :3].T + eq[:, 3]).max(1) for k in range(0, len(X), step)]
                           or [np.zeros(0)])
    inside = depth > 1e-9 * shape.bounding_radius                # deeper than round-off
    if not np.any(inside):
        return None
    return (f"the mesh is not closed, so its own volume is unknown, and {int(inside.sum())} of its "
            f"{len(V)} vertices lie inside its convex hull (up to {depth.max():.3g} deep): the shape is the "
            f"hull, volume {shape.volume:.6g}; {glue}")


def _closed(T):
    """Every directed edge once and its reverse once: a closed, consistently oriented surface."""
    if not len(T):
        return False
    e = np.c_[T.reshape(-1), T[:, [1, 2, 0]].reshape(-1)]
    fwd = np.unique(e, axis=0)
    if len(fwd) != len(e):
        return False
    rev = np.unique(e[:, ::-1], axis=0)
    return np.array_equal(fwd, rev)


def tetrahedron(edge, crust=None):
    """Regular tetrahedron of edge length ``edge`` (vertices (+-1, +-1, +-1) with an even number of minus
    signs, scaled): volume edge^3/(6 sqrt 2), isotropic inertia edge^2/20 per unit mass."""
    s = edge / (2.0 * np.sqrt(2.0))
    V = s * np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], float)
    return Polyhedron(V, crust=crust, name="tetrahedron")


def pinacoid_vertices(L, G, E, alpha=60.0):
    """Vertices of Descantes' pinacoid (Fig. 4 / Table 1): 8 vertices, 14 edges, 8 faces.

    Reconstructed from the published volume V = L G E / 6 (3 - E / (L tan alpha)) and the counts: a
    rectangle L x G in the mid plane z = 0 and two ridges along x of length L - E / tan(alpha) at
    z = +-E/2 (a double hip roof). The end faces are triangles inclined at ``alpha`` (degrees) to the mid
    plane, the long faces trapezoids. For L = G = E the mid-plane corners lie on the sphere of diameter
    L sqrt(2), the circumscribed sphere d_sph = sqrt(2) L of Table 1, which the ridge ends stay inside.
    """
    t = np.tan(np.radians(alpha))
    if not (L > 0 and G > 0 and E > 0 and 0 < alpha < 90):
        raise ValueError("pinacoid: L, G, E > 0 and 0 < alpha < 90 degrees required")
    r = L / 2.0 - E / (2.0 * t)
    if r < 0:
        raise ValueError("pinacoid: E / tan(alpha) must not exceed L (alpha is in degrees)")
    V = [[sx * L / 2, sy * G / 2, 0.0] for sx in (-1, 1) for sy in (-1, 1)]
    V += [[sx * r, 0.0, sz * E / 2] for sx in (-1, 1) for sz in (-1, 1)]
    return np.array(V)


def pinacoid(L, G, E, alpha=60.0, crust=None):
    """Descantes' pinacoid (length L, width G, thickness E, end-face angle alpha in degrees)."""
    s = Polyhedron(pinacoid_vertices(L, G, E, alpha), crust=crust, name="pinacoid")
    s.pinacoid_parameters = (L, G, E, alpha)
    return s


def pinacoid_volume(L, G, E, alpha=60.0):
    """Table 1 of Descantes (2022): V = L G E / 6 (3 - E / (L tan alpha))."""
    return L * G * E / 6.0 * (3.0 - E / (L * np.tan(np.radians(alpha))))
