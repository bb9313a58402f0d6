"""Glued convex composites (Grains3D Part III): a non-convex particle as a rigid union of convex components.

A component is ``(shape, offset, rotation)``: a convex dem.shapes Shape in its own body frame, placed in
the composite's frame at ``offset`` (its centre of mass) and turned by ``rotation`` (its body axes as
columns). Components may overlap.

Mass properties of the union (Part III sec 2.3): exact sums and parallel axes when no two components
overlap (slices of a cylinder, the 8 cubes of a cube), exact cells of the face-plane grid for boxes turned
alike (crosses, tile spacers); otherwise the structured-lattice integration of eq. 7-8 (`glued_mass`),
cached in the shape database (`shape_db`). The composite is then moved to its
centre of mass and principal axes like every shape: ``centroid`` and ``rotation`` record the move, and
``components`` hold the body-frame poses that the shape table and the kernels use.

The composite itself has no support function (it is not convex): kernels meet its components, rows of
the shape table listed by the composite's row (dem/shapes/_table.pxd).
"""
import numpy as np

from .base import BOX, GLUED, POLYHEDRON, Shape, check_lengths, packed_params
from .polyhedron import principal_frame

DEFAULT_RESOLUTION = 500      # lattice points along the longest side: < 0.2 % error (Part III Fig. 3)
_MESH_RESOLUTION = 96         # far-point search on curved components (see _far_point)
_LATTICE_NOISE = 1e-6         # relative round-off of lattice sums: a symmetric union's moments agree to it


def _rotation(rot):
    R = np.asarray(rot, dtype=float).reshape(3, 3)
    if not (np.allclose(R.T @ R, np.eye(3), atol=1e-9) and np.linalg.det(R) > 0):
        raise ValueError("a component rotation must be a proper rotation matrix")
    return R


def _far_point(shape, offset, rot):
    """Distance from the composite origin to the farthest point of a posed component (an upper bound).
    Polytopes: their vertices (exact). Curved kinds: the vertices of a fine mesh, plus the most a mesh of
    that resolution can cut off a rim (r (1 - cos(pi/n)) for a circle of radius r, r <= R_c), never more
    than |offset| + R_c."""
    V, _ = shape.mesh(_MESH_RESOLUTION)
    far = float(np.linalg.norm(V @ rot.T + offset, axis=1).max())
    loose = float(np.linalg.norm(offset)) + shape.bounding_radius
    if shape.kind not in (BOX, POLYHEDRON):
        far += 2.0 * shape.bounding_radius * (1.0 - np.cos(np.pi / _MESH_RESOLUTION))
    return min(far, loose)


def _clean_tensor(I, tol):
    """I with lattice noise below tol (relative) removed: off-diagonal terms zeroed, nearly equal diagonal
    terms set equal, so that a symmetric composite keeps the axes it was given in (principal_frame then
    sees degenerate moments, not noise)."""
    scale = abs(np.diag(I)).max()
    J = I.copy()
    off = ~np.eye(3, dtype=bool)
    J[off & (abs(J) <= tol * scale)] = 0.0
    d = np.diag(J).copy()
    for a in range(3):
        for b in range(a + 1, 3):
            if abs(d[a] - d[b]) <= tol * scale:
                d[a] = d[b] = 0.5 * (d[a] + d[b])
    J[np.diag_indices(3)] = d
    return J


class Glued(Shape):
    """A composite of convex components. ``resolution``: lattice points along the longest side of the
    union's bounding box, used when components overlap; ``db``: the shape database (a `shape_db.ShapeDB`,
    a path, ``None`` for the default, ``"none"`` for no cache); ``comm`` splits the lattice over ranks."""
    kind = GLUED
    name = "glued"
    mass_cached = False       # the lattice result came from the shape database

    def __init__(self, components, resolution=DEFAULT_RESOLUTION, db=None, comm=None, name=None, _props=None):
        from . import glued_mass, shape_db
        if name:
            self.name = name
        comps = []
        for c in components:
            shape, off, rot = c
            if not isinstance(shape, Shape) or shape.kind == GLUED:
                raise ValueError("components of a glued shape are convex shapes")
            off = np.asarray(off, dtype=float).reshape(3)
            check_lengths(off, "a component offset")
            comps.append((shape, off, _rotation(rot)))
        if not comps:
            raise ValueError("a glued shape needs at least one component")
        self.resolution = int(resolution)
        if _props is not None:
            volume, com, I, self.mass_method, self.mass_error = _props
        elif len(comps) == 1 or not glued_mass.components_overlap(comps):
            volume, com, I = glued_mass.exact_mass_properties(comps)
            self.mass_method, self.mass_error = "exact", 0.0
        elif glued_mass.aligned_boxes(comps):         # overlapping boxes turned alike: exact grid cells
            volume, com, I = glued_mass.aligned_boxes_mass_properties(comps)
            self.mass_method, self.mass_error = "exact", 0.0
        else:
            p = shape_db.cached_union_mass_properties(comps, self.resolution, db=db, comm=comm)
            volume, com, I = p["volume"], p["centre"], p["inertia"]
            self.mass_method, self.mass_error = "lattice", float(p["error"])
            self.mass_cached = bool(p.get("cached", False))
        com = np.asarray(com, dtype=float)
        I = np.asarray(I, dtype=float)
        if self.mass_method == "lattice":
            I = _clean_tensor(I, _LATTICE_NOISE)
        R, moments = principal_frame(I)
        self.centroid, self.rotation = com, R
        self.volume = float(volume)
        self.principal_moments = moments
        self.components = [(s, R.T @ (off - com), R.T @ rot) for s, off, rot in comps]
        self.params = packed_params()
        self.bounding_radius = max(_far_point(s, off, rot) for s, off, rot in self.components)
        self.inradius = min(s.inradius for s, _, _ in self.components)
        self.crust = max(s.crust for s, _, _ in self.components)     # (each component keeps its own)
        self.core_kind, self.core_params, self.core_vertices = GLUED, self.params.copy(), self.vertices

    def _init_crust(self, crust):
        raise ValueError("a glued shape has no crust of its own: give each component its crust")

    def with_crust(self, crust):
        return self._init_crust(crust)

    @property
    def max_crust(self):
        return min(s.max_crust for s, _, _ in self.components)

    def support(self, d, core=False):
        raise ValueError("a glued shape is not convex: query its components")

    def pieces(self, resolution=24):
        """Body-frame surface meshes (vertices, faces) of the posed components."""
        out = []
        for s, off, rot in self.components:
            V, F = s.mesh(resolution)
            out.append((np.asarray(V, float) @ rot.T + off, np.asarray(F, np.int64)))
        return out

    def mesh(self, resolution=24):
        """The union's surface as the posed component meshes together (overlapping where they overlap)."""
        Vs, Fs, n = [], [], 0
        for V, F in self.pieces(resolution):
            Vs.append(V)
            Fs.append(F + n)
            n += len(V)
        return np.vstack(Vs), np.vstack(Fs)

    def scaled(self, factor):
        f = float(factor)
        comps = [(s.scaled(f), off * f, rot) for s, off, rot in self.components]
        props = (self.volume * f ** 3, np.zeros(3), np.diag(self.principal_moments) * f ** 5, self.mass_method,
                 self.mass_error)
        return Glued(comps, resolution=self.resolution, name=self.name, _props=props)

    def __repr__(self):
        return "<%s of %d components volume=%.6g R=%.6g (%s)>" % (self.name, len(self.components), self.volume,
                                                              self.bounding_radius, self.mass_method)
