"""Shape base class: mass properties, crust and core, packed representation.

Body frame: every shape is stored with its centre of mass at the origin and its axes along its principal
axes of inertia, so inertia tensors are diagonal (what the Omelyan integrator expects). A shape given in
another frame (a polyhedron from a file) remembers ``centroid`` and ``rotation``: a point ``p`` of the body
frame is ``centroid + rotation @ p`` in the frame it was given in.

All mass properties are per unit density: ``mass(rho) = rho * volume``, inertia = ``rho * inertia``.

Crust and core (Grains3D contact reconstruction, GJK on shrunk bodies)
---------------------------------------------------------------------
For contact detection a body is represented as ``core (+) ball(crust)``: GJK runs on the cores, and while
the core distance is below ``crust_a + crust_b`` the overlap, normal and point follow from the core closest
points without any penetration algorithm. The core is built so that this is *exact* for the rounded body
``core (+) ball(crust)``:

* sharp kinds (box, cylinder, cone, polyhedra): the core is the exact erosion of the body by the ball,
  ``{p : p + ball(crust) inside body}``, itself a box / cylinder / cone / polyhedron (faces moved inwards by
  ``crust``; for polyhedra the half-space intersection of the shifted face planes). The rounded body keeps
  every face of the true body and rounds its edges and vertices with radius ``crust`` (a cube corner moves
  inwards by ``crust*(sqrt(3)-1)``).
* smooth kinds (sphere, ellipsoid, superquadric with n1, n2 >= 2): the core support is the "margin" rule
  ``s(d) - crust*d/|d|``. This is the support of a convex body (the inner parallel body) exactly when every
  principal radius of curvature of the surface is >= crust, and then ``core (+) ball(crust)`` is the body
  itself. ``max_crust`` enforces it (ellipsoid: min a_i^2 / max a_j; superquadric: estimated numerically).
  The plain margin rule is *not* used for sharp kinds: at a vertex it yields points that are not the
  support of any convex set, and GJK on them would return a wrong distance.

Deep overlaps (cores intersecting) fall back to EPA on the cores plus both crusts, which is the exact
penetration depth of the two rounded bodies, so the overlap is continuous across the switch.
"""
import copy

import numpy as np

from ._support import LAYOUT, Kind, support_points

# kind codes and the parameter layout: defined once, in _support.pxd (the kernels' enums)
SPHERE, BOX, CYLINDER, CONE, ELLIPSOID, SUPERQUADRIC, POLYHEDRON, GLUED = (int(k) for k in Kind)
KIND_NAMES = {SPHERE: "sphere", BOX: "box", CYLINDER: "cylinder", CONE: "cone", ELLIPSOID: "ellipsoid",
              SUPERQUADRIC: "superquadric", POLYHEDRON: "polyhedron", GLUED: "glued"}
NPARAM = LAYOUT["NPARAM"]    # params per shape (float64)
MARGIN = LAYOUT["MARGIN"]    # params[MARGIN] erodes any kind by a ball
DEFAULT_CRUST_FRACTION = 0.05   # default crust = this * inradius: overlaps of a few % of the size stay on
#                                 the GJK fast path, rounding of edges stays well below 5 % of the size


MAX_LENGTH = 1e40   # m: the largest |number| in a shape definition (sizes, coordinates, offsets). The
#                     inertia per unit density grows as length^5 (1e200 here), which leaves 1e100 of room
#                     for density, scale^5 and the parallel-axis sums before float64 overflows (1.8e308);
#                     no grain comes near it (the Sun's radius is 7e8 m)


def check_lengths(values, what):
    """ValueError unless every number of `values` is finite and at most MAX_LENGTH in magnitude, so that
    the mass properties stay finite (an overflow would end in a failed eigen solve)."""
    v = np.asarray(values, dtype=float)
    bad = ~np.isfinite(v)
    if np.any(bad):
        raise ValueError(f"{what}: non-finite number {v[bad].flat[0]}")
    if v.size and np.abs(v).max() > MAX_LENGTH:
        raise ValueError(f"{what}: {np.abs(v).max():g} exceeds {MAX_LENGTH:g} in magnitude (the inertia, "
                         f"length^5, would overflow)")


def packed_params(*values, margin=0.0):
    p = np.zeros(NPARAM)
    p[:len(values)] = values
    p[MARGIN] = margin
    return p


def orient_outward(V, F):
    """Flip triangles of a convex mesh (origin inside) so that their normals point outwards."""
    F = np.array(F, dtype=np.int64).reshape(-1, 3)
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    flip = np.einsum("ij,ij->i", np.cross(b - a, c - a), (a + b + c) / 3.0) < 0
    F[flip] = F[flip][:, [0, 2, 1]]
    return F


def uv_mesh(point, nlat, nlon):
    """Closed triangle mesh of a star-shaped surface given by ``point(eta, omega)`` (arrays), with eta the
    latitude in [-pi/2, pi/2] and omega the longitude; poles at eta = -+pi/2."""
    eta = np.linspace(-np.pi / 2, np.pi / 2, nlat + 1)[1:-1]
    om = np.linspace(-np.pi, np.pi, nlon, endpoint=False)
    E, O = np.meshgrid(eta, om, indexing="ij")
    ring = point(E.ravel(), O.ravel())
    V = np.vstack([point(np.array([-np.pi / 2]), np.array([0.0])), ring,
                   point(np.array([np.pi / 2]), np.array([0.0]))])
    top = len(V) - 1
    F = []
    for j in range(nlon):
        jn = (j + 1) % nlon
        F.append((0, 1 + jn, 1 + j))
        for i in range(nlat - 2):
            a, b = 1 + i * nlon + j, 1 + i * nlon + jn
            F.append((a, b, b + nlon))
            F.append((a, b + nlon, a + nlon))
        r = 1 + (nlat - 2) * nlon
        F.append((r + j, r + jn, top))
    return V, orient_outward(V, F)


def mesh_volume(V, F):
    """Volume of a closed outward-oriented triangle mesh (divergence theorem)."""
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


class Shape:
    """A convex particle shape. Subclasses define ``kind``, ``params``, mass properties and the core."""
    kind = -1
    name = "shape"

    # filled by subclasses
    params = None             # float64[NPARAM], body frame
    vertices = np.zeros((0, 3))   # hull vertices in the body frame (polyhedra only)
    volume = 0.0
    principal_moments = None  # float64[3], per unit density
    bounding_radius = 0.0     # max distance from the centre of mass to the surface
    inradius = 0.0            # min distance from the centre of mass to the surface
    centroid = np.zeros(3)    # centre of mass in the frame the shape was given in
    rotation = np.eye(3)      # body axes in that frame (columns)
    topology = None           # polytopes (box, polyhedron): faces, edges, adjacency (dem/shapes/topology.py)

    def _init_crust(self, crust):
        limit = self.max_crust
        if crust is None:
            crust = min(DEFAULT_CRUST_FRACTION * self.inradius, 0.5 * limit)
        crust = float(crust)
        if not 0.0 <= crust < limit:
            raise ValueError("%s: crust %g must be in [0, %g)" % (self.name, crust, limit))
        self.crust = crust
        self._make_core()

    # ---- to be provided by subclasses ----
    @property
    def max_crust(self):
        """Crust thickness above which the core is empty or the margin rule stops being exact."""
        return self.inradius

    def _make_core(self):
        """Set core_kind, core_params, core_vertices for self.crust (default: margin rule)."""
        self.core_kind = self.kind
        self.core_params = self.params.copy()
        self.core_params[MARGIN] = self.crust
        self.core_vertices = self.vertices

    def mesh(self, resolution=24):
        """Triangle mesh (vertices, faces) of the surface in the body frame, faces outward."""
        raise NotImplementedError

    def scaled(self, factor):
        """The same shape scaled by ``factor`` (crust scaled alike): sizes distributions without redefining."""
        raise NotImplementedError

    # ---- common ----
    @property
    def inertia(self):
        """Inertia tensor per unit density in the body frame (diagonal)."""
        return np.diag(self.principal_moments)

    @property
    def principal_axes(self):
        """Principal axes (columns) in the frame the shape was given in."""
        return self.rotation

    # polytope topology (None on curved shapes); a polyhedron's ``faces`` stay its hull triangles
    @property
    def face_polygons(self):
        """Face polygons (vertex ids into ``topology.vertices``, counter-clockwise from outside)."""
        return None if self.topology is None else self.topology.faces

    @property
    def face_normals(self):
        """Unit outward face normals (nf, 3), body frame."""
        return None if self.topology is None else self.topology.face_normals

    @property
    def face_offsets(self):
        """Face plane offsets d (nf,): the body is n.x <= d."""
        return None if self.topology is None else self.topology.face_offsets

    @property
    def edges(self):
        """Edges (ne, 2) as vertex-id pairs into ``topology.vertices``."""
        return None if self.topology is None else self.topology.edges

    @property
    def edge_faces(self):
        """The two faces (ne, 2) adjacent to each edge."""
        return None if self.topology is None else self.topology.edge_faces

    def mass(self, density=1.0):
        return density * self.volume

    def with_crust(self, crust):
        """A copy with another crust thickness."""
        s = copy.copy(self)
        s._init_crust(crust)
        return s

    def support(self, d, core=False):
        """Body-frame support point(s) for direction(s) d (n, 3) or (3,)."""
        single = np.ndim(d) == 1
        d = np.ascontiguousarray(np.atleast_2d(d), dtype=float)
        kind, params, verts = (self.core_kind, self.core_params, self.core_vertices) if core else \
            (self.kind, self.params, self.vertices)
        out = support_points(kind, np.ascontiguousarray(params, float),
                             np.ascontiguousarray(verts, float).reshape(-1, 3), d)
        return out[0] if single else out

    def _scaled_crust(self, factor):
        return self.crust * factor

    def __repr__(self):
        return "<%s volume=%.6g R=%.6g crust=%.3g>" % (self.name, self.volume, self.bounding_radius, self.crust)
