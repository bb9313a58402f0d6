"""compute porosity"""
import numpy as np

from dem.commands import find_region
from dem.compute import Compute
from dem.errors import DemError
from dem.shapes.base import POLYHEDRON
from dem.thermo import quat_to_matrix

from . import _compute_porosity

# One evaluation of a grid runs without a break (about 1e7 points/s on one core): a grid of more points
# than this (about 20 minutes) is a mistake in dx or the resolution, not a measurement.
MAX_POINTS = 1e10


def grid_counts(extent, dx, what, copies=1):
    """Points per axis (at least 1) of a grid of spacing dx across `extent`, evaluated `copies` times per
    evaluation; a DemError naming `what` when that makes more than MAX_POINTS points."""
    counts = np.maximum(np.rint(np.asarray(extent, float) / dx), 1.0)
    total = copies * float(np.prod(counts))
    if not total <= MAX_POINTS:
        raise DemError(f"{what}: a grid spacing of {dx:.6g} makes {total:.3g} grid points per evaluation, more "
                       f"than {MAX_POINTS:.0e}", hint="give a larger dx (or a smaller resolution)")
    return counts.astype(np.int64)


def polyhedron_planes(sim):
    """Face planes of the polyhedron rows of the shape table (the voxel kernel's point-in-body test):
    (planes (P, 4), start (rows + 1)), row k's at start[k]:start[k + 1]."""
    rows = sim.shapes.rows if len(sim.shapes) else []
    blocks = [np.asarray(s._planes(), float).reshape(-1, 4) if s.kind == POLYHEDRON else np.zeros((0, 4))
              for s in rows]
    start = np.zeros(len(rows) + 1, np.int64)
    start[1:] = np.cumsum([len(b) for b in blocks])
    planes = np.vstack(blocks + [np.zeros((1, 4))])
    return np.ascontiguousarray(planes), start


def gather_bodies(sim, sel):
    """The selected owned particles as the voxel kernel takes them (x, radius, shape, rotation rows), from
    every rank on every rank (each counts a share of the grid layers)."""
    atom, comm = sim.atom, sim.comm
    n = atom.nlocal
    fields = [atom.data[k][:n][sel] for k in ("x", "radius", "shape", "quat")]
    if comm.nprocs > 1:
        tags = atom.data["tag"][:n][sel]
        fields = [comm.allgather_rows(tags, f)[1] for f in fields]
    x, r, shape, quat = fields
    quat = np.asarray(quat, dtype=float).reshape(-1, 4)
    rot = np.ascontiguousarray(quat_to_matrix(quat).reshape(-1, 9)) if len(quat) else np.zeros((1, 9))
    return (np.ascontiguousarray(np.asarray(x, dtype=float).reshape(-1, 3)), np.ascontiguousarray(r, dtype=float),
            np.ascontiguousarray(shape, dtype=np.int32), rot)


def solid_points(sim, bodies, glo, h, npts, kind=0, params=None):
    """(grid points in the region, solid ones), summed over ranks, of the grid glo + (i + 1/2) h, i < npts,
    against `bodies` (gather_bodies)."""
    dom, comm = sim.domain, sim.comm
    x, r, shape, rot = bodies
    planes, start = polyhedron_planes(sim)
    inside, solid = _compute_porosity.voxel_count(
        x, r, np.asarray(glo, float), np.asarray(h, float), np.asarray(npts, np.int64), dom.lo, dom.prd,
        dom.periodic.astype(np.int32), kind, np.zeros(1) if params is None else params, shape, rot,
        sim.shapes.view(), planes, start, comm.me, comm.nprocs)
    return comm.sum(int(inside)), comm.sum(int(solid))


class ComputePorosity(Compute):
    """compute ID group porosity REGION-ID [resolution K | dx D]

    Porosity (void fraction) of a region by structured-lattice voxelisation, as Grains3D does for
    packings (Part III sec 4.1): the region's bounding box (clipped to the simulation box) is cut into a
    regular grid of cubic-ish cells; the centre of a cell is solid when it lies inside a particle of the
    group (inside a sphere, or inside the true body of a shaped particle: any convex piece of a glued
    composite; periodic images included); porosity = 1 - solid points / points
    inside the region. Grid spacing: D, or the smallest particle diameter of the group divided by K
    (default K = 40 points per diameter). Accuracy: on a lattice of spheres commensurate with the grid the
    error aliases (Gauss-circle counting): 0.14 % at K = 40 on a simple cubic lattice, erratic between
    0.1 and 0.7 % for K = 36..60, 1-3 % below K = 20; for random packings the errors of the spheres
    average out (< 0.05 % at K = 20; Part III uses about 27 and 54 points per diameter, Table 5).
    Regions: block, cylinder or sphere, side in. Vector: [porosity, solid fraction, points in the region,
    solid volume (points x cell volume)].

    The cost grows as the number of points (K^3 per cubic diameter; about 1e7 points/s on one core):
    evaluate it once at the end
    (e.g. `run 0` with it in thermo) rather than at every thermo line; a grid of more than 1e10 points
    is refused. In parallel runs every rank
    gathers the group's particles and counts a share of the grid layers.

    Example (Part III Table 5): `compute por all porosity bulk` then `thermo_style custom step c_por`."""

    style = "porosity"
    size_vector = 4
    vector_names = ("porosity", "solid_fraction", "points", "solid_volume")
    usage = "REGION-ID [resolution K | dx D]"

    def __init__(self, sim, cid, group, args):
        super().__init__(sim, cid, group, args)
        a = self.parser()
        a.need(1)
        self.region = find_region(sim, a[0])
        if self.region.style not in ("block", "cylinder", "sphere"):
            raise a.error(f"region style {self.region.style} is not supported (block, cylinder, sphere)")
        if not self.region.side_in:
            raise a.error("the region must be 'side in'")
        kw = a.keywords(1, {"resolution": 1, "dx": 1})
        if "resolution" in kw and "dx" in kw:
            raise a.error("give resolution or dx, not both")
        self.resolution = a.to_float(kw["resolution"][0], "resolution") if "resolution" in kw else 40.0
        self.dx = a.to_float(kw["dx"][0], "dx") if "dx" in kw else None
        if self.resolution <= 0 or (self.dx is not None and self.dx <= 0):
            raise a.error("resolution and dx must be > 0")

    def grid(self):
        """(lower corner, spacing per axis, points per axis) of the grid."""
        sim = self.sim
        dom = sim.domain
        lo, hi = self.region.bbox()
        lo, hi = np.maximum(lo, dom.lo), np.minimum(hi, dom.hi)
        if np.any(hi <= lo):
            raise DemError(f"compute {self.id} porosity: region {self.region.id} lies outside the box")
        dx = self.dx
        if dx is None:
            atom = sim.atom
            r = atom.data["radius"][:atom.nlocal][self.group_mask()]
            rmin = sim.comm.min(float(r.min()) if len(r) else np.inf)
            if not np.isfinite(rmin):
                raise DemError(f"compute {self.id} porosity: no particle in group {self.group} to set the "
                               f"grid spacing (give dx)")
            dx = 2.0 * rmin / self.resolution
        npts = grid_counts(hi - lo, dx, f"compute {self.id} porosity")
        return lo, (hi - lo) / npts, npts

    def _region_params(self):
        reg = self.region
        if reg.style == "cylinder":
            return 1, np.array([reg.axis, reg.c[0], reg.c[1], reg.radius, reg.lo, reg.hi], dtype=float)
        if reg.style == "sphere":
            return 2, np.array([*reg.center, reg.radius], dtype=float)
        return 0, np.zeros(1)

    def compute_vector(self):
        glo, h, npts = self.grid()
        kind, params = self._region_params()
        bodies = gather_bodies(self.sim, self.group_mask())
        inside, solid = solid_points(self.sim, bodies, glo, h, npts, kind, params)
        phi = solid / inside if inside else 0.0
        return np.array([1.0 - phi, phi, float(inside), solid * float(np.prod(h))])

    def compute_scalar(self):
        return self.vector()[0]
