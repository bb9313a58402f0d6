"""fix wall/mesh"""
import math

import numpy as np

from dem.shapes import command as shape_command
from dem._particles import ParticleView
from dem.args import Args
from dem.errors import DemError, did_you_mean
from dem.fix import Fix, Stage

from . import _wall_mesh
from .mesh import load, read_motion, rotation_about
from dem.law.wall_coeffs import WallCoefficients

from .wall_fix import POINT_MODES, WALL_KEYWORDS, wall_keyword

RPM = 2.0 * math.pi / 60.0
STAT, POSE = _wall_mesh.STAT, _wall_mesh.POSE
MAX_CELLS = 4_000_000      # the grid of the triangles: cells of at least a particle diameter, at most this many


class FixWallMesh(WallCoefficients, Fix):
    """fix ID group wall/mesh file FILE [scale S] [rotate axis AX AY AZ angle DEG] [move DX DY DZ]
        [linear VX VY VZ] [turn origin OX OY OZ axis AX AY AZ rpm W | omega W] [ramp T]
        [table FILE [origin OX OY OZ axis AX AY AZ]]
        [point deepest|multipoint] [law grains3d|descantes]
        [kn KN en EN mu MU gamma_t GT beta_t BT ks KS mu_roll MR | model hertz E E nu NU en EN mu MU mu_roll MR]
        [normal hooke|hertz|dmt ...] [type T]

    A rigid wall made of a triangle mesh read from FILE: an STL file (ASCII or binary) or a Wavefront OBJ
    (`.obj`; polygons are split into triangles), the path relative to the folder dem runs in or, if not
    found there, to the folder of the input script (`meshes/hopper.stl` beside inputs/in.hopper). Vertices
    closer than 1e-9 of the mesh's size are merged, so that triangles share their edges and vertices
    (an STL file repeats them) and zero-area triangles are dropped. The mesh has two sides: a particle
    meets a triangle from either side, whatever the triangle's orientation.

    * Placement, applied in the order given: `scale S` (about the origin), `rotate axis AX AY AZ angle
      DEG` (about the origin, right-hand rule), `move DX DY DZ`.
    * Motion (a rigid body, from when the fix is defined): `linear VX VY VZ` translates it at that
      velocity; `turn origin OX OY OZ axis AX AY AZ rpm W` (or `omega W`, rad/s) turns it about the axis
      through the origin point (which moves with `linear`), `ramp T` bringing both rates from 0 up to
      their values over T seconds. `table FILE`: an imposed motion instead, lines `t dx dy dz angle` (s, m,
      degrees; `#` comments) giving the displacement and the angle turned about the axis through the
      origin (given after the file, default the z axis through 0 0 0) at times t since the fix was
      defined, increasing; linear in between, held at the first and last lines outside them (the
      velocity is then 0). The mesh's velocity at the contact point, V + Omega x (p - origin), enters the
      contact law, so a moving mesh drags the particles (a mixer blade, a conveyor, a shaking sieve).
      A run whose mesh would move more than the smallest particle's radius in one step (its fastest
      point: the translation plus the turn at the farthest vertex) is refused: particles could pass
      through it unseen.
    * Contacts: every particle of the group against every triangle it overlaps, one contact per touched
      feature: a sphere meets the triangles at their closest points, and a contact at a shared edge or
      vertex counts once, so a sphere rolling across two coplanar triangles, or over a convex edge, feels
      one continuous contact with the normal of the closest feature. Shaped particles (`shape`) meet each
      triangle with their true body (GJK, EPA depth), the contact point midway in the overlap, one
      contact per plane (a flat face over several coplanar triangles touches once); glued composites
      touch with each component (Model A or B as the pair style). `point multipoint`: a box or polyhedron
      whose contact with a triangle lies inside the triangle touches at each of its vertices beyond the
      triangle's plane, each with the deepest overlap and 1/alpha of the force (Descantes 2022 eq. 3, as
      `fix wall/plane`: a cube lying on a mesh floor on its 4 corners); at a triangle's edge or vertex it
      keeps one point.
    * Law and coefficients as `fix wall/plane` (m_ij = m_i, the wall of infinite mass; without them
      those of each type with itself from pair_coeff; `law descantes`, `model hertz` with R* = R_i;
      `type T`). The parts that keep more history than the tangential spring (`normal jkr`, `rolling
      epsd|epsd2`) are not available on meshes yet: an error at the run says so.
      The tangential spring is kept per particle and contact (6 at most at once), matched from step to
      step by the contact normal (within 60 degrees): it survives a move from one triangle to the next,
      rebuilds, restarts and migration between ranks.
    * Cost: the triangles are binned once, in the mesh's own frame, into cells of two triangle edges,
      but at least a particle radius and at most a diameter; a particle meets only the triangles of the
      cells its bounding sphere overlaps. The mesh
      is replicated on every rank (about 120 bytes a triangle, 4 bytes per triangle listed in a cell and
      8 per cell: 13 MB for the 10^5 triangles of benchmarks/mesh_wall.py).

    Thermo values: `f_ID[contacts]`, `f_ID[fx]`, `f_ID[fy]`, `f_ID[fz]` (force of the particles on the
    mesh, N), `f_ID[tx]`, `f_ID[ty]`, `f_ID[tz]` (their torque on it about the turning origin, which moves
    with the mesh, or the world origin without one, N m), `f_ID[torque]` (about the turning axis; z without
    one), `f_ID[angle]` (rad).
    Global state kept for restarts: the time since the fix was defined. Redefining the fix (same ID: e.g.
    the impeller of inputs/in.mixer, at rest while the vessel fills, then turning) starts its motion
    afresh from the placement given, and keeps the contacts' springs.

    Example (a hopper of inputs/meshes; inputs/in.hopper)::

        fix hopper all wall/mesh file meshes/hopper.stl kn 5000 en 0.5 mu 0.5 ks 1429
    """

    style = "wall/mesh"
    behind = 0                 # a mesh has two sides: no particle is behind it
    stages = Stage.POST_FORCE | Stage.END_OF_STEP
    usage = ("file FILE [scale S] [rotate axis AX AY AZ angle DEG] [move DX DY DZ] [linear VX VY VZ] "
             "[turn origin OX OY OZ axis AX AY AZ rpm W | omega W] [ramp T] [table FILE [origin OX OY OZ axis "
             "AX AY AZ]] [point deepest|multipoint] "
             "[law grains3d|descantes] [kn .. en .. mu .. | model hertz E .. nu .. en .. mu ..]")

    def __init__(self, sim, fid, group, args):
        super().__init__(sim, fid, group, args)
        a = Args(args, f"fix ID group wall/mesh {self.usage}", f"fix {fid} wall/mesh")
        a.need(2)
        if a[0] != "file":
            raise a.error(f"expected 'file FILE' first, got '{a[0]}'")
        self.path = sim.input.find_file(a[1])
        mesh = load(self.path)
        if mesh.dropped:
            sim.warning(f"fix {fid} wall/mesh: {mesh.dropped} degenerate triangle(s) of {self.path} dropped")
        self.velocity = np.zeros(3)
        self.origin = np.zeros(3)
        self.axis = np.array([0.0, 0.0, 1.0])
        self.omega_target = 0.0
        self.ramp = 0.0
        self.motion_table = None   # (t, displacement (n, 3), angle (rad)) of `table FILE`
        self.point = 0
        i, law = 2, []
        while i < len(a):
            key = a[i]
            if key == "scale":
                mesh = mesh.transformed(scale=a.float(i + 1, "scale", positive=True))
                i += 2
            elif key == "rotate":
                if a[i + 1] != "axis" or a[i + 5] != "angle":
                    raise a.error("rotate: expected 'rotate axis AX AY AZ angle DEG'")
                mesh = mesh.transformed(rotation=rotation_about(self._unit(a, i + 2, "rotate axis"),
                                                                math.radians(a.float(i + 6, "angle"))))
                i += 7
            elif key == "move":
                mesh = mesh.transformed(offset=a.floats(i + 1, 3, "move"))
                i += 4
            elif key == "linear":
                self.velocity = np.array(a.floats(i + 1, 3, "linear velocity"))
                i += 4
            elif key == "turn":
                if a[i + 1] != "origin" or a[i + 5] != "axis" or a[i + 9] not in ("rpm", "omega"):
                    raise a.error("turn: expected 'turn origin OX OY OZ axis AX AY AZ rpm W' (or omega W)")
                self.origin = np.array(a.floats(i + 2, 3, "turn origin"))
                self.axis = self._unit(a, i + 6, "turn axis")
                self.omega_target = a.float(i + 10, a[i + 9]) * (RPM if a[i + 9] == "rpm" else 1.0)
                i += 11
            elif key == "table":
                self.motion_table = read_motion(sim.input.find_file(a[i + 1]), f"fix {fid} wall/mesh")
                i += 2
                if i < len(a) and a[i] == "origin":
                    if a[i + 4] != "axis":
                        raise a.error("table: expected 'table FILE origin OX OY OZ axis AX AY AZ'")
                    self.origin = np.array(a.floats(i + 1, 3, "table origin"))
                    self.axis = self._unit(a, i + 5, "table axis")
                    i += 8
            elif key == "ramp":
                self.ramp = a.float(i + 1, "ramp", nonneg=True)
                i += 2
            else:
                # law volume clips a polytope by a half-space: a mesh face is not one (plane and drum walls)
                i = wall_keyword(self, a, i, law, modes=("deepest", "multipoint"), laws=("grains3d", "descantes"))
                if i is None:
                    known = ["scale", "rotate", "move", "linear", "turn", "ramp", "table"] + WALL_KEYWORDS
                    raise a.error(f"unknown keyword '{key}'{did_you_mean(key, known)}")
        if self.motion_table is not None and (np.any(self.velocity) or self.omega_target != 0.0 or self.ramp):
            raise a.error("table gives the motion: it cannot be combined with linear, turn or ramp")
        self.mesh = mesh
        v = mesh.vertices[mesh.triangles]
        self.edge_length = float(np.median(np.linalg.norm(v - np.roll(v, 1, axis=1), axis=2)))
        self.static = None         # the pose of a mesh that never moves, computed once
        if not np.any(self.velocity) and self.omega_target == 0.0 and self.motion_table is None:
            self.static = self.pose(0.0)
        self.parse_law(law)
        self.elapsed = 0.0         # time since the fix was defined (s)
        self.token = 0             # the kernel's triangle stamps (MeshIndex)
        self.index = None
        self.stats = np.zeros(STAT["NSTAT"])
        self.ncontacts = 0
        self.max_overlap = 0.0
        self.energy = 0.0          # elastic energy stored in the mesh contacts (thermo pe, etotal)

    @staticmethod
    def _unit(a, i, name):
        v = np.array(a.floats(i, 3, name))
        norm = float(np.linalg.norm(v))
        if norm == 0.0:
            raise a.error(f"{name} must not be zero")
        return v / norm

    # ----- motion ---------------------------------------------------------------------------------
    def _rate(self, t):
        """Fraction of the full rates at time t (the ramp) and the time integral of it from 0 to t."""
        if self.ramp > 0.0 and t < self.ramp:
            return t / self.ramp, 0.5 * t * t / self.ramp
        return 1.0, t - 0.5 * self.ramp

    def motion(self, t):
        """(displacement, angle, velocity, rate) of the mesh at time t since the definition."""
        if self.motion_table is None:
            f, integral = self._rate(t)
            return self.velocity * integral, self.omega_target * integral, self.velocity * f, self.omega_target * f
        times, disp, angle = self.motion_table
        k = min(max(int(np.searchsorted(times, t, side="right")) - 1, 0), len(times) - 2)
        inside = times[0] <= t <= times[-1] and len(times) > 1
        span = times[k + 1] - times[k] if len(times) > 1 else 1.0
        D = np.array([np.interp(t, times, disp[:, d]) for d in range(3)])
        rate = (angle[k + 1] - angle[k]) / span if inside else 0.0
        V = (disp[k + 1] - disp[k]) / span if inside else np.zeros(3)
        return D, float(np.interp(t, times, angle)), V, rate

    def pose(self, t=None):
        """The kernel's pose vector at time t since the definition (default: now): POSE."""
        t = self.elapsed if t is None else t
        if self.static is not None:
            return self.static
        D, angle, V, rate = self.motion(t)
        p = np.zeros(POSE["N"])
        p[POSE["M"]:POSE["M"] + 9] = rotation_about(self.axis, angle).ravel()
        p[POSE["C"]:POSE["C"] + 3] = self.origin
        p[POSE["D"]:POSE["D"] + 3] = D
        p[POSE["V"]:POSE["V"] + 3] = V
        p[POSE["W"]:POSE["W"] + 3] = self.axis * rate
        return p

    def surface_mesh(self):
        """The mesh's vertices (nv, 3) where it is now and its triangles (for the VTK dumps)."""
        p = self.pose()
        M = p[POSE["M"]:POSE["M"] + 9].reshape(3, 3)
        return (self.mesh.vertices - self.origin) @ M.T + self.origin + p[POSE["D"]:POSE["D"] + 3], \
            self.mesh.triangles

    # ----- stages ---------------------------------------------------------------------------------
    def history_width(self, nwalls):
        return _wall_mesh.HISTORY_WIDTH

    def init(self):
        sim = self.sim
        self.init_table(1)
        self.shape_view = shape_command.shape_view(sim)
        n = sim.atom.nlocal
        rmax = float(sim.atom.data["radius"][:n].max()) if n else 0.0
        rmax = sim.comm.max(max([rmax] + [fix.max_radius() for fix in sim.modify.fixes]))
        lo, hi = self.mesh.bounds()
        extent = np.maximum(hi - lo, 1e-12 * max(float(np.max(hi - lo)), 1.0))
        # cells between a particle radius and diameter, near two triangle edges: a fine mesh gets small
        # cells (fewer triangles listed with each particle), a coarse one cells of a particle diameter
        cell = float(np.clip(2.0 * self.edge_length, rmax, 2.0 * rmax)) if rmax > 0 else 2.0 * self.edge_length
        while np.prod(np.floor(extent / cell) + 1) > MAX_CELLS:
            cell *= 1.5
        if self.index is None or self.index.h != cell:
            self.index = _wall_mesh.MeshIndex(self.mesh, cell)
        self.check_speed()

    def fastest_speed(self):
        """The largest speed (m/s) of a point of the mesh over its motion: the translation plus the turn
        times the farthest vertex from the axis."""
        if self.static is not None:
            return 0.0
        if self.motion_table is None:
            speeds, rates = [np.linalg.norm(self.velocity)], [abs(self.omega_target)]
        else:
            times, disp, angle = self.motion_table
            span = np.diff(times)
            speeds = np.linalg.norm(np.diff(disp, axis=0), axis=1) / span if len(times) > 1 else [0.0]
            rates = np.abs(np.diff(angle)) / span if len(times) > 1 else [0.0]
        rel = self.mesh.vertices - self.origin
        arm = float(np.max(np.linalg.norm(rel - np.outer(rel @ self.axis, self.axis), axis=1)))
        return float(np.max(speeds)) + float(np.max(rates)) * arm

    def check_speed(self):
        """A mesh that moves more than the smallest particle's radius in one step can pass through
        particles without ever overlapping them enough to be seen (a plane wall also stops a particle
        behind it; a mesh has no behind)."""
        sim = self.sim
        n = sim.atom.nlocal
        rmin = sim.comm.min(float(sim.atom.data["radius"][:n].min()) if n else np.inf)
        step = self.fastest_speed() * sim.update.dt
        if np.isfinite(rmin) and step > rmin:
            raise DemError(f"fix {self.id} wall/mesh: its fastest point moves {step:.3g} m in one step, more "
                           f"than the smallest particle's radius {rmin:.3g} m: particles could pass through it",
                           hint="a smaller time step, or a slower motion")

    def compute(self, advance):
        sim = self.sim
        _wall_mesh.mesh_walls(ParticleView(sim.atom), int(self.groupbit), self.index, self.pose(), self.table[0],
                              self.shape_view, self.history(), self.use_history, sim.update.dt, advance,
                              self.point == POINT_MODES.index("multipoint"),
                              bool(getattr(sim.pair, "multipoint_average", True)), self.token, self.stats)
        self.token += max(sim.atom.nlocal, 1)
        self.ncontacts = int(self.stats[STAT["CONTACTS"]])
        self.max_overlap = float(self.stats[STAT["MAXOV"]])
        self.energy = float(self.stats[STAT["ENERGY"]])

    def post_force(self):
        self.compute(True)

    def end_of_step(self):
        self.elapsed += self.sim.update.dt

    def worst_contact(self):
        """(overlap / diameter, text naming the particle and the triangle) of this rank's largest overlap at
        the last compute, or None (the overlap stop of `Update.check_step`)."""
        i = int(self.stats[STAT["WORST_I"]])
        if i < 0:
            return None
        tag = int(self.sim.atom.data["tag"][i])
        return self.max_overlap, (f"particle {tag} and triangle {int(self.stats[STAT['WORST_T']])} of "
                                  f"{self.path} (fix {self.id} wall/mesh)")

    def thermo(self):
        comm = self.sim.comm
        force = [comm.sum(float(v)) for v in self.stats[STAT["FORCE"]:STAT["FORCE"] + 3]]
        torque = [comm.sum(float(v)) for v in self.stats[STAT["TORQUE"]:STAT["TORQUE"] + 3]]
        out = {"contacts": comm.sum(self.ncontacts), "angle": self.motion(self.elapsed)[1],
               "torque": float(np.dot(torque, self.axis))}
        out.update(zip(("fx", "fy", "fz"), force))
        out.update(zip(("tx", "ty", "tz"), torque))
        return out

    def state(self):
        return {"elapsed": self.elapsed}

    def restore(self, state):
        self.elapsed = float(state.get("elapsed", 0.0))

