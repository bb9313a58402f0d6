"""Particle shapes in a simulation: the `shape` command, the shape table `sim.shapes`, and the helpers that
give particles a shape (used by create_atoms, set, and insertion fixes).

    shape NAME KIND params... [file F] [crust C]

Every kind is a style of kind ``shape`` (rule 2: a plugin may add more): the class builds a
:class:`dem.shapes.Shape` from the parameters (the convex kinds: convex_kinds.py; the composites:
glued_kinds.py). ``sim.shapes`` is a :class:`SimShapes`, a
:class:`dem.shapes.ShapeTable` that also knows the names; every rank runs the same commands, so the table
is identical on every rank (ghosts carry only the shape index).

A shaped particle is a rigid body made of: its shape index (row of ``sim.shapes``; -1 is a plain sphere of
the particle's own radius), its orientation ``quat`` (body -> space), and its size: ``radius`` is the
bounding radius of the scaled body, so the scale factor is ``radius / sim.shapes.radius[shape]``. Scaled
shapes thus make size distributions without new table rows: kernels scale the body on the fly (the
rotation matrix handed to the support functions is multiplied by the scale, the crust by the scale).
Mass = density x volume x scale^3, inertia = density x principal moments x scale^5.

For insertion fixes: :class:`ShapeTemplate` (the interface of dem_process's SphereTemplate),
:func:`properties` gives the per-particle fields of shaped particles of given radii (``rmass``,
``inertia``, ``shape``), :func:`assign` shapes existing particles in place.
"""
import math

import numpy as np

from ..command import Command
from ..errors import DemError, did_you_mean
from .base import KIND_NAMES
from .convex_kinds import SHAPE_KINDS
from .glued_kinds import GLUED_KINDS
from .table import ShapeTable


# ----- the table ------------------------------------------------------------------------------------
class SimShapes(ShapeTable):
    """The shape table of a simulation: a ShapeTable plus ``names`` (one per row) and ``definitions``
    (the command words that made each row, to rebuild the table from a restart)."""

    def __init__(self, entries=()):
        entries = list(entries)
        super().__init__([s for _, s, _ in entries])
        self.entries = entries
        self.names = [n for n, _, _ in entries]
        self.definitions = [list(w) for _, _, w in entries]
        self._meshes = {}

    def added(self, name, shape, words):
        return SimShapes(self.entries + [(name, shape, list(words))])

    def index(self, name):
        if isinstance(name, (int, np.integer)):
            if not 0 <= int(name) < len(self):
                raise DemError(f"shape index {name} out of range 0..{len(self) - 1}")
            return int(name)
        try:
            return self.names.index(name)
        except ValueError:
            raise DemError(f"unknown shape '{name}'{did_you_mean(name, self.names)}",
                           hint="define it first: shape NAME KIND params ...") from None

    def convex_pieces(self, idx, resolution=24):
        """The body-frame convex pieces of row idx at scale 1: a list of (vertices, faces) meshes whose union
        is the body (a composite's posed components; one piece, the row's mesh, for the convex shapes)."""
        shape = self.shapes[idx]
        if hasattr(shape, "pieces"):
            return shape.pieces(resolution)
        return [self.mesh(idx, resolution)]

    def mesh(self, idx, resolution=24):
        """Body-frame surface (vertices, faces) of row idx at scale 1, cached."""
        m = self._meshes.get(idx)
        if m is None:
            V, F = self.shapes[idx].mesh(resolution)
            m = self._meshes[idx] = (np.asarray(V, float), np.asarray(F, np.int64))
        return m


def table(sim):
    """sim.shapes (empty until a shape is defined)."""
    return sim.shapes


def _check_rows(sim):
    """Every particle's shape index has a row (checked collectively): kernels do not check bounds."""
    atom = sim.atom
    n = atom.nlocal
    top = int(atom.data["shape"][:n].max()) if n else -1
    top = int(sim.comm.max(top))
    nrows = len(sim.shapes)
    if top >= nrows:
        raise DemError(f"particles have shape index {top} but only {nrows} shape(s) are defined",
                       hint="define the shapes (shape NAME KIND ...) in the same order before read_restart "
                            "or read_data")


def kernel_arrays(sim):
    """The shape table arrays (ShapeTable.kernel_arrays), after checking the particles' shape indices."""
    _check_rows(sim)
    return sim.shapes.kernel_arrays()


def shape_view(sim):
    """The shape table as the kernels take it (dem.shapes._table.ShapeView), checked as kernel_arrays."""
    _check_rows(sim)
    return sim.shapes.view()


def pair_shape_view(sim):
    """shape_view for a pair style's init, with the warning every shaped pair style gives (collective) when
    shaped particles are not integrated by fix nve/shape."""
    atom = sim.atom
    shaped = sim.comm.any(bool(np.any(atom.data["shape"][:atom.nlocal] >= 0)))
    if shaped and not any(f.style == "nve/shape" for f in sim.modify.integrators):
        sim.warning("shaped particles are integrated without fix nve/shape: their rotation is that of "
                    "a sphere (wrong for non-spherical bodies)")
    return shape_view(sim)


def shape_index(sim, name):
    t = table(sim)
    if len(t) == 0:
        raise DemError(f"unknown shape '{name}': no shape defined yet", hint="shape NAME KIND params ...")
    return t.index(name)


# ----- per-particle properties ----------------------------------------------------------------------
def volume(sim, shape, radius):
    """Volume of particles of shape indices `shape` (-1: sphere) and bounding radii `radius`."""
    shape = np.asarray(shape)
    radius = np.asarray(radius, dtype=float)
    out = 4.0 / 3.0 * math.pi * radius ** 3
    shaped = shape >= 0
    if np.any(shaped):
        t = table(sim)
        s = shape[shaped]
        out = np.array(out, dtype=float)
        out[shaped] = t.volume[s] * (radius[shaped] / t.radius[s]) ** 3
    return out


def unit_inertia(sim, shape, radius):
    """Principal moments per unit density (n, 3)."""
    shape = np.asarray(shape)
    radius = np.asarray(radius, dtype=float)
    out = (0.4 * 4.0 / 3.0 * math.pi * radius ** 5)[:, None] * np.ones(3)
    shaped = shape >= 0
    if np.any(shaped):
        t = table(sim)
        s = shape[shaped]
        out[shaped] = t.inertia[s] * ((radius[shaped] / t.radius[s]) ** 5)[:, None]
    return out


def properties(sim, shape, radius=None, scale=None, density=1.0):
    """Per-particle fields of particles of one shape (name or index): `radius` (bounding radii, array) or
    `scale` (array or number; default 1). Returns {radius, rmass, inertia (n, 3), shape} for atom.add.
    Density may be a number or an array."""
    idx = shape_index(sim, shape)
    t = sim.shapes
    if radius is None:
        scale = np.atleast_1d(np.asarray(1.0 if scale is None else scale, dtype=float))
        radius = scale * t.radius[idx]
    radius = np.atleast_1d(np.asarray(radius, dtype=float))
    if np.any(radius <= 0):
        raise DemError("shaped particles need a scale > 0")
    n = len(radius)
    s = radius / t.radius[idx]
    rho = np.broadcast_to(np.asarray(density, dtype=float), (n,))
    return {"radius": radius, "rmass": rho * t.volume[idx] * s ** 3,
            "inertia": (rho * s ** 5)[:, None] * t.inertia[idx][None, :],
            "shape": np.full(n, idx, dtype=np.int32)}


def particle_density(sim, rows):
    """Current density of owned particles `rows` (mass / volume of their present body)."""
    d = sim.atom.data
    return d["rmass"][rows] / volume(sim, d["shape"][rows], d["radius"][rows])


def assign(sim, rows, shape, scale=1.0, density=None, quat=None):
    """Give owned particles `rows` (slice, index array or boolean mask over 0..nlocal) the shape `shape`
    (name or index; None: keep their shape and only rescale them) at `scale` (number or array), keeping
    their density unless `density` is given; `quat` (4,) or (n, 4) sets their orientation (normalised).
    Mass, principal inertia and bounding radius follow. For fix insert: call it right after atom.add on
    the new slice. Not collective (the table is not changed)."""
    atom = sim.atom
    d = atom.data
    idx = np.arange(atom.nlocal)[rows]
    if len(idx) == 0:
        return
    rho = particle_density(sim, idx) if density is None else density
    scale = np.broadcast_to(np.asarray(scale, dtype=float), (len(idx),))
    if shape is None:       # rescale: shaped particles only (spheres are left alone)
        keep = d["shape"][idx] >= 0
        idx, scale = idx[keep], scale[keep]
        rho = np.broadcast_to(np.asarray(rho, dtype=float), keep.shape)[keep]
        cur = d["shape"][idx]
        t = sim.shapes
        d["radius"][idx] = scale * t.radius[cur]
        d["rmass"][idx] = rho * t.volume[cur] * scale ** 3
        d["inertia"][idx] = (rho * scale ** 5)[:, None] * t.inertia[cur]
    else:
        p = properties(sim, shape, scale=scale, density=rho)
        for name in ("radius", "rmass", "inertia", "shape"):
            d[name][idx] = p[name]
    if quat is not None:
        q = np.asarray(quat, dtype=float)
        d["quat"][idx] = q / np.linalg.norm(q, axis=-1, keepdims=True)
    d["angmom"][idx] = 0.0      # recomputed from omega by nve/shape with the new inertia
    sim.neighbor.invalidate()


class ShapeTemplate:
    """A particle template for insertion fixes (the interface of dem_process.templates.SphereTemplate):
    particles of one shape at scales drawn from `distribution` (an object with draw(rng, n) and bounds()
    giving scales, e.g. dem_process.templates.RadiusDistribution read as scales), of one density."""

    def __init__(self, sim, shape, distribution, density):
        self.sim = sim
        self.index = shape_index(sim, shape)
        self.distribution = distribution
        self.density = density

    @property
    def bounding(self):
        return float(self.sim.shapes.radius[self.index])

    def draw_radius(self, rng, n):
        return self.distribution.draw(rng, n) * self.bounding

    def max_radius(self):
        return self.distribution.bounds()[1] * self.bounding

    def volume(self, radius):
        return float(self.sim.shapes.volume[self.index]) * (np.asarray(radius, dtype=float) / self.bounding) ** 3

    def mean_volume(self):
        return float(self.sim.shapes.volume[self.index]) * self.distribution.mean_cube()

    def properties(self, radius):
        """Per-particle fields for atom.add: rmass, inertia (n, 3), shape."""
        p = properties(self.sim, self.index, radius=radius, density=self.density)
        return {k: p[k] for k in ("rmass", "inertia", "shape")}


def random_quaternions(rng, n):
    """Uniformly distributed unit quaternions (w, x, y, z) (Shoemake 1992)."""
    u = rng.random((n, 3))
    a, b = np.sqrt(1.0 - u[:, 0]), np.sqrt(u[:, 0])
    t1, t2 = 2.0 * math.pi * u[:, 1], 2.0 * math.pi * u[:, 2]
    return np.stack([b * np.cos(t2), a * np.sin(t1), a * np.cos(t1), b * np.sin(t2)], axis=1)


class ShapeCommand(Command):
    """shape NAME KIND params... [file F] [crust C]

    Defines a particle shape named NAME and adds it to the shape table (`sim.shapes`, the same on every
    rank). Kinds: `sphere R`, `box A B C`, `cube A`, `cylinder R L` (axis z), `cone R H`,
    `ellipsoid A B C`, `superquadric A B C N1 N2`, `tetrahedron EDGE`, `pinacoid L G E [ALPHA]`,
    `polyhedron X Y Z ...` or `polyhedron file F.obj|F.stl` (convex hull). Sizes are full sizes except
    radii and ellipsoid/superquadric half axes. The body frame is the principal frame through the centre
    of mass. Every number of a shape (sizes, points, component offsets) is finite and at most 1e40 in
    magnitude: the inertia grows as size^5 and must not overflow.

    `crust C`: thickness of the Grains3D crust (contact detection on bodies shrunk by C; overlaps up to
    twice the crust are found by GJK, deeper ones by EPA; edges and corners are rounded by C in
    particle-particle contacts). Default: 5 % of the inradius.

    Particles get a shape with `create_atoms ... shape NAME [scale S] [quat ...]` or
    `set ... shape NAME [scale S]`; `scale` makes size distributions of one shape. Use
    `fix ID all nve/shape` to integrate them and `pair_style convex/gjk` for their contacts. Particles
    store the index of their shape: `read_restart` restores the shapes of the restart, so a script
    continuing from it defines none before it (shapes defined before it must be the restart's, the same
    in the same order, else read_restart is an error naming both; new shapes may follow it).

    Example (Part III sec 3.3)::

        shape cube2mm cube 0.002
        create_atoms 1 single 0 0 0.08 shape cube2mm density 2500 quat 0.9 0.1 0.1 0
    """
    style = "shape"
    usage = "NAME KIND params... [file F] [crust C]"

    def __call__(self, words):
        sim = self.sim
        a = self.args(words)
        a.need(2)
        name, kind = a[0], a[1]
        t = table(sim)
        if name in t.names:
            raise a.error(f"shape '{name}' already exists (shape indices must not change)")
        cls = sim.registry.get("shape", kind)
        if getattr(cls, "raw", False):       # composites read their own words (glued_kinds.py)
            shape = cls(sim).parse(a, 2)
            sim.shapes = t.added(name, shape, words)
            sim.print(f"Shape {name} ({kind}, {len(shape.components)} components): volume {shape.volume:.6g} "
                      f"({shape.mass_method}" + (f", estimated error {shape.mass_error:.2g}" if shape.mass_error
                                                 else "") + (", from the shape database" if shape.mass_cached
                                                             else "") + f"), bounding radius {shape.bounding_radius:.6g}, "
                      f"principal moments / density {' '.join(f'{m:.6g}' for m in shape.principal_moments)}")
            return
        values, crust, file = [], None, None
        i = 2
        while i < len(a):
            w = a[i]
            if w in ("crust", "file"):
                if i + 1 >= len(a):
                    raise a.error(f"keyword '{w}' needs a value")
                if w == "crust":
                    crust = a.float(i + 1, "crust", nonneg=True)
                else:
                    file = a[i + 1]
                i += 2
                continue
            values.append(a.float(i, f"{kind} parameter"))
            i += 1
        if cls.nparams is not None and len(values) != cls.nparams:
            raise a.error(f"shape kind {kind} needs {cls.nparams} number(s): {cls.usage}")
        if file is not None and kind != "polyhedron":
            raise a.error("'file' applies to polyhedron shapes")
        try:
            shape = cls(sim).build(values, crust, file)
        except (ValueError, OSError) as e:
            raise a.error(str(e)) from None
        sim.shapes = t.added(name, shape, words)
        sim.print(f"Shape {name} ({KIND_NAMES.get(shape.kind, kind)}): volume {shape.volume:.6g}, bounding "
                  f"radius {shape.bounding_radius:.6g}, crust {shape.crust:.3g}, principal moments / density "
                  f"{' '.join(f'{m:.6g}' for m in shape.principal_moments)}")


def check_restart(sim, definitions):
    """DemError when the script defined shapes before read_restart that are not the restart's, the same in
    the same order: saved particles hold row indices, and another row there would give them another
    shape. Rows the script defined beyond the restart's are kept."""
    here = table(sim).definitions
    if not here:
        return
    for k, saved in enumerate(definitions):
        mine = here[k] if k < len(here) else None
        if mine is None or not _same_words(mine, saved):
            defined = f"'shape {' '.join(mine)}'" if mine else "no shape"
            raise DemError(f"read_restart: shape {k + 1} of the restart is 'shape {' '.join(saved)}', but the "
                           f"script defined {defined} in its place before read_restart",
                           hint="define no shape before read_restart (it restores the restart's shapes), or the "
                                "same ones in the same order")


def _same_words(a, b):
    """The same definition: the same words, numbers compared by value (0.002 is 2e-3)."""
    def value(word):
        try:
            return float(word)
        except ValueError:
            return word
    return len(a) == len(b) and all(x == y or value(x) == value(y) for x, y in zip(a, b))


def rebuild(sim, definitions):
    """Re-run shape definitions (from a restart) when the script has not defined them (check_restart has
    made sure that those it defined are the restart's)."""
    if len(table(sim)):
        return
    cmd = ShapeCommand(sim)
    for words in definitions:
        cmd(words)


SHAPE_STYLES = [ShapeCommand] + SHAPE_KINDS + GLUED_KINDS
