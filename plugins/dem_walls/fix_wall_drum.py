"""fix wall/drum"""
import math

import numpy as np

from dem.args import Args
from dem.errors import DemError, did_you_mean
from dem.fix import Fix, Stage

from .wall_fix import WALL_KEYWORDS, WallFix, cylinder, plane, turning, wall_keyword

RPM = 2.0 * math.pi / 60.0


class FixWallDrum(WallFix, Fix):
    """fix ID group wall/drum AXIS C1 C2 RADIUS [rpm W | omega W] [ramp T] [ends LO HI fixed|rotate]
        [carry GROUP] [point deepest|centroid|multipoint] [law grains3d|descantes]
        [kn KN en EN mu MU gamma_t GT beta_t BT ks KS mu_roll MR | model hertz E E nu NU en EN mu MU mu_roll MR]
        [normal|damping|tangential|rolling PART ...] [type T]

    A rotating cylindrical wall (a drum) with the particles inside. AXIS is x, y or z; the axis passes
    through (C1, C2) in the two other coordinates, in x, y, z order (as `region cylinder`); RADIUS is the
    inner radius of the drum.

    * `rpm W` or `omega W`: rotation rate in revolutions per minute or rad/s (default 0), positive
      counter-clockwise about +AXIS (right-hand rule).
    * `ramp T`: the rate grows linearly from 0 to W over the first T seconds after the fix is defined
      (default 0: full rate at once).
    * `ends LO HI fixed|rotate`: flat end walls at AXIS = LO (facing +AXIS) and HI (facing -AXIS), at rest
      or rotating with the drum. Without `ends`, make the box periodic along the axis.
    * `carry GROUP`: the particles of GROUP turn with the drum as one rigid body (positions, velocities
      Omega e_axis x r, spins Omega e_axis, orientations), whatever the forces on them: a layer of
      particles set along the wall makes it rough, as a real drum's (a smooth wall lets the bed slip).
      GROUP must be integrated by no other fix and lie outside the fix's own group (the bed).

    The wall surface moves with the velocity Omega e_axis x r of the drum at the contact point; it
    enters the contact's relative velocity, so the tangential (friction) force drags the bed along
    (with gamma_t = ks = 0 the law has no tangential force at all: give one of them).
    Contacts use the Grains3D law with m_ij = m_i and the coefficients given here (the same keywords as
    `pair_coeff`; without them those of each type with itself), a tangential history per particle and
    wall (when ks > 0) that survives rebuilds, restarts and migration, and the rolling resistance of
    `pair_style sphere` (mu_roll r_i |F_n| against the spin relative to the wall) for spheres.
    Particles with a shape (`shape` command) touch the walls at their deepest point (against the drum:
    the point of the body farthest from the axis), with the lever from their centre of mass to the
    contact point and no rolling resistance, as in `pair_style convex/gjk`. `point centroid` puts the
    contact point at the depth-weighted centroid of the body's vertices beyond the wall instead (as
    `fix wall/plane`): a flat face on the curved drum touches along two edges, and one arbitrary corner
    would rock the particle. `point multipoint`: a polytope touches at every vertex beyond the wall, the
    deepest overlap shared and the force divided by their number, as `fix wall/plane`. `law descantes`:
    Descantes' eq. 3 at every contact point instead of the Grains3D law (no attraction, viscous friction
    capped by Coulomb against the moving wall, no spring), as `fix wall/plane`. `model hertz`:
    Hertz-Mindlin as `fix wall/plane` (the drum and its ends of the particles' material,
    R* = r_i: the curvature of the drum, which makes R* larger by about r_i / RADIUS, is left out).
    The parts of the law (`normal jkr`, `rolling epsd`, ...) and `type T` as `fix wall/plane`.

    Redefining the fix (same ID, e.g. `rpm 0` to fill, then `rpm 40` to rotate) keeps the drum angle;
    the ramp starts again from the redefinition. Global state kept for restarts: the drum angle and the
    time since the fix was defined (ramp).
    Thermo values: `f_ID[contacts]`, `f_ID[omega]` (rad/s now), `f_ID[angle]` (rad), `f_ID[revs]`
    (revolutions), `f_ID[torque]` (torque of the walls on the particles about the axis, N m: the drive
    torque in steady rotation; power = torque x omega).

    Example (Part III sec 4.2: drum of radius 50 mm, periodic along y; inputs/in.drum)::

        fix drum all wall/drum y 0 0 0.05 rpm 40 ramp 0.02 kn 1e5 en 0.73 mu 0.55 gamma_t 2000 ks 28571
    """

    style = "wall/drum"
    thermo_quantities = {"contacts": ("wall contacts", "-"), "omega": ("drum rate", "rad/s"),
                         "angle": ("drum angle", "rad"), "revs": ("drum turns", "-"),
                         "torque": ("torque of the walls on the particles", "N m")}
    stages = Stage.POST_NEIGHBOR | Stage.POST_FORCE | Stage.INTEGRATE | Stage.END_OF_STEP
    usage = ("AXIS C1 C2 RADIUS [rpm W | omega W] [ramp T] [ends LO HI fixed|rotate] [carry GROUP] "
             "[point deepest|centroid|multipoint] "
             "[law grains3d|descantes] [kn KN en EN mu MU gamma_t GT beta_t BT ks KS mu_roll MR] "
             "[model hertz E E nu NU en EN mu MU mu_roll MR]")

    def __init__(self, sim, fid, group, args):
        super().__init__(sim, fid, group, args)
        a = Args(args, f"fix ID group wall/drum {self.usage}", f"fix {fid} wall/drum")
        a.need(4)
        if a[0] not in ("x", "y", "z"):
            raise a.error(f"AXIS must be x, y or z, got '{a[0]}'")
        self.axis = "xyz".index(a[0])
        others = [d for d in range(3) if d != self.axis]
        self.centre = np.zeros(3)
        self.centre[others] = a.floats(1, 2, "centre")
        self.radius = a.float(3, "radius", positive=True)
        self.omega_target = 0.0
        self.ramp = 0.0
        self.ends = None
        self.ends_rotate = False
        self.carry = None         # (group name, bit) of the particles turned with the drum
        self.point = 0
        i, law = 4, []
        while i < len(a):
            key = a[i]
            if key in ("rpm", "omega"):
                self.omega_target = a.float(i + 1, key) * (RPM if key == "rpm" else 1.0)
                i += 2
            elif key == "ramp":
                self.ramp = a.float(i + 1, "ramp", nonneg=True)
                i += 2
            elif key == "ends":
                lo, hi = a.float(i + 1, "LO"), a.float(i + 2, "HI")
                if hi <= lo:
                    raise a.error("ends: HI must exceed LO")
                if a[i + 3] not in ("fixed", "rotate"):
                    raise a.error(f"ends: expected fixed or rotate, got '{a[i + 3]}'")
                self.ends = (lo, hi)
                self.ends_rotate = a[i + 3] == "rotate"
                i += 4
            elif key == "carry":
                self.carry = (a[i + 1], sim.groups.bit(a[i + 1]))
                i += 2
            else:
                # law volume needs a half-space: the curved drum is not one (the planes of wall/plane are)
                i = wall_keyword(self, a, i, law, laws=("grains3d", "descantes"))
                if i is None:
                    known = ["rpm", "omega", "ramp", "ends", "carry"] + WALL_KEYWORDS
                    raise a.error(f"unknown keyword '{key}'{did_you_mean(key, known)}")
        self.parse_law(law)
        self.nwalls = 1 + (2 if self.ends else 0)
        self.angle = 0.0          # drum angle (rad), integrated exactly for the linear ramp
        self.elapsed = 0.0        # time since the fix was defined (s)
        old = sim.modify.find(fid)
        if old is not None and getattr(old, "style", None) == self.style:
            self.angle = old.angle   # redefined (e.g. to start rotating): the drum keeps its angle
        self.energy = 0.0          # elastic energy stored in the wall contacts (thermo pe, etotal)
        self.ncontacts = 0
        self.max_overlap = 0.0
        self.torque = 0.0

    # ----- rotation -------------------------------------------------------------------------------
    def omega_at(self, t):
        if self.ramp > 0.0 and t < self.ramp:
            return self.omega_target * t / self.ramp
        return self.omega_target

    @property
    def omega(self):
        """Rotation rate (rad/s) at the current time."""
        return self.omega_at(self.elapsed)

    def wall_velocity(self, x, omega=None):
        """Velocity (n, 3) of the drum, as a rigid body turning at omega (default: now), at points x (n, 3)."""
        e = np.zeros(3)
        e[self.axis] = 1.0
        r = np.asarray(x, dtype=float) - self.centre
        r[:, self.axis] = 0.0
        return (self.omega if omega is None else omega) * np.cross(e, r)

    # ----- stages ---------------------------------------------------------------------------------
    def init(self):
        sim = self.sim
        self.init_walls(self.nwalls)
        if self.ends is None and not sim.domain.periodic[self.axis]:
            sim.warning(f"fix {self.id} wall/drum: no end walls and the box is not periodic along "
                        f"{'xyz'[self.axis]}: particles can leave through the open ends")
        if self.carry is not None:
            self.check_carry()

    def check_carry(self):
        """The carried group is moved by this fix alone, and is not the wall's to push."""
        sim = self.sim
        name, bit = self.carry
        mask = sim.atom.data["mask"][:sim.atom.nlocal]
        carried = (mask & bit) != 0
        what = f"fix {self.id} wall/drum carry {name}"
        if sim.comm.any(bool(np.any(carried & ((mask & self.groupbit) != 0)))):
            raise DemError(f"{what}: the carried particles are in the fix's group {self.group}, so the wall "
                           f"would push them too: give the fix the bed's group")
        for fix in sim.modify.fixes:
            if fix is not self and fix.time_integrate and \
                    sim.comm.any(bool(np.any(carried & ((mask & fix.groupbit) != 0)))):
                raise DemError(f"{what}: fix {fix.id} {fix.style} integrates particles of group {name}, "
                               f"which the drum moves: give that fix the bed's group")

    def integrate(self):
        """Turn the carried particles with the drum over this step (the angle end_of_step adds); velocities
        and spins those of the drum at the end of the step, when the next forces are computed."""
        if self.carry is None:
            return
        atom = self.sim.atom
        n = atom.nlocal
        sel = np.flatnonzero((atom.data["mask"][:n] & self.carry[1]) != 0)
        if not len(sel):
            return
        dt = self.sim.update.dt
        t0 = self.elapsed
        dtheta = 0.5 * (self.omega_at(t0) + self.omega_at(t0 + dt)) * dt
        w = self.omega_at(t0 + dt)
        a = self.axis
        b, c = (a + 1) % 3, (a + 2) % 3          # e_a = e_b x e_c: a turn by dtheta in the (b, c) plane
        x = atom.data["x"]
        rb, rc = x[sel, b] - self.centre[b], x[sel, c] - self.centre[c]
        cs, sn = math.cos(dtheta), math.sin(dtheta)
        rb, rc = cs * rb - sn * rc, sn * rb + cs * rc
        x[sel, b], x[sel, c] = self.centre[b] + rb, self.centre[c] + rc
        # the drum's velocity w e_a x r, written by components (np.cross costs more than the rest here:
        # this runs every step for the rough wall's hundreds of spheres)
        v = atom.data["v"]
        v[sel, a] = 0.0
        v[sel, b] = -w * (x[sel, c] - self.centre[c])
        v[sel, c] = w * (x[sel, b] - self.centre[b])
        om = atom.data["omega"]
        om[sel] = 0.0
        om[sel, a] = w
        if "quat" in atom.data:                  # q <- h q, h = (cos, sin e_a) of the half angle
            q = atom.data["quat"][sel]
            h0, ha = math.cos(0.5 * dtheta), math.sin(0.5 * dtheta)
            out = np.empty_like(q)
            out[:, 0] = h0 * q[:, 0] - ha * q[:, 1 + a]
            out[:, 1 + a] = h0 * q[:, 1 + a] + q[:, 0] * ha
            out[:, 1 + b] = h0 * q[:, 1 + b] - ha * q[:, 1 + c]
            out[:, 1 + c] = h0 * q[:, 1 + c] + ha * q[:, 1 + b]
            atom.data["quat"][sel] = out

    def surfaces(self):
        """The drum (0) and its ends (1: LO facing +AXIS, 2: HI facing -AXIS), turning at the current rate
        (the ends only with `ends ... rotate`); all take part in the torque about the axis."""
        a, omega = self.axis, self.omega
        rows = [turning(cylinder(a, self.centre, self.radius), a, self.centre, omega)]
        if self.ends:
            spin = omega if self.ends_rotate else 0.0
            rows += [turning(plane(a, self.ends[0], 1.0), a, self.centre, spin),
                     turning(plane(a, self.ends[1], -1.0), a, self.centre, spin)]
        return np.array(rows)

    def surface_name(self, w):
        return ["'drum'", "'end LO'", "'end HI'"][w]

    def end_of_step(self):
        dt = self.sim.update.dt
        t0 = self.elapsed
        # trapezoid: exact for the piecewise-linear ramp except within the step that ends it
        self.angle += 0.5 * (self.omega_at(t0) + self.omega_at(t0 + dt)) * dt
        self.elapsed = t0 + dt

    def thermo(self):
        comm = self.sim.comm
        return {"contacts": comm.sum(self.ncontacts), "omega": self.omega, "angle": self.angle,
                "revs": self.angle / (2.0 * math.pi), "torque": comm.sum(self.torque)}

    def state(self):
        return {"angle": self.angle, "elapsed": self.elapsed}

    def restore(self, state):
        self.angle = float(state.get("angle", 0.0))
        self.elapsed = float(state.get("elapsed", 0.0))
