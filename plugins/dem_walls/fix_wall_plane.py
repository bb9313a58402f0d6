"""fix wall/plane"""
import numpy as np

from dem.args import number
from dem.errors import DemError
from dem.fix import Fix, Stage

from .wall_fix import POINT_MODES, S, WallFix, law_name, plane


class FixWallPlane(WallFix, Fix):
    """fix ID group wall/plane xplane|yplane|zplane LO HI [...] [kn KN en EN mu MU gamma_t GT beta_t BT ks KS mu_roll MR]
        [model hertz E E nu NU en EN mu MU mu_roll MR] [normal|damping|tangential|rolling PART ...] [type T]
        [point deepest|centroid|multipoint] [law grains3d|descantes|volume]

    Fixed planar walls. Each `xplane LO HI` adds a wall at x = LO facing +x and one at x = HI facing -x;
    NULL skips one (`zplane 0 NULL`: a floor only). Particles touching a wall feel the Grains3D law with
    the reduced mass m_ij = m_i (the wall is an obstacle of infinite mass) and their own tangential
    history per wall (kept per particle: it survives rebuilds, restarts and migration); spheres also feel
    the rolling resistance of `pair_style sphere` (mu_roll r_i |F_n| against their spin), as at the drum.
    Shaped particles (`shape` command) touch a wall at the deepest point of their body along the wall
    normal (support function): one contact point, lever from the centre of mass to it. `point deepest`
    (default, Grains3D) puts it at that deepest point; `point centroid` at the depth-weighted centroid of
    the body's vertices (rim points for cylinders and cones) below the wall, with the same overlap: a
    face or edge lying on the wall then pushes at its middle (no spurious torque from one arbitrary
    corner), a single corner below the wall is the deepest point again. `point multipoint`: a box or
    polyhedron touches at every vertex below the wall (a cube lying flat: its 4 corners, an edge: its 2
    ends), each point with the deepest overlap and the force divided by their number (Descantes 2022
    eq. 3); no tangential spring at those points (curved bodies keep their one point and spring).
    `law descantes` (default `law grains3d`): Descantes' eq. 3 at every contact point of this wall instead
    of the Grains3D law, as `pair_style polyhedron/multipoint law descantes` (the same function,
    dem.law.descantes): F_n = max(0, kn delta - nu_n U_n) / alpha (no attraction, nu_n from en with
    m_ij = m_i), F_t = -min(nu_t |U_t|, mu F_n) t / alpha (viscous, nu_t = 2 gamma_t m_i + 2 beta_t sqrt(kn m_i),
    capped by Coulomb: give gamma_t or beta_t for friction), no spring (ks unused, no history); alpha = the points of
    `point multipoint`, 1 otherwise. `law volume`: a sharp polytope meets the wall through the volume of
    its part beyond the plane, as `pair_style polyhedron/multipoint law volume` (A_ref = pi r_i^2; one
    point whatever `point` says; other shapes keep their point and the Hooke law). The wall's law is chosen
    here, not taken from the pair style.
    Glued composites (pair_style glued/convex) touch with each component, Model A/B as the pair style.
    Coefficients: given here for every type, or, when left out, those of each type with itself from
    pair_coeff. Example: `fix floor all wall/plane zplane 0.0 NULL kn 1000 en 0.5 mu 0.5 ks 285.7`.
    `model hertz E .. nu .. en .. mu ..` (as pair_style sphere's): Hertz-Mindlin against the wall, the wall
    of the particles' material E, nu, with R* = r_i (a shaped particle: the radius of its sphere of equal
    volume) and m* = m_i; not with `law descantes`. Taken from pair_coeff I I when that is model hertz.
    Any part of the law (docs/contact_law.md: `normal jkr|dmt`, `rolling epsd|epsd2`, ...) with the same
    words as pair_coeff; a JKR sphere stays bonded to the wall until its pull-off distance. `type T`: the
    wall is of particle type T (a type with no particles gives a wall of its own material), and a
    particle of type I meets it with the law of pair_coeff T I (materials mixed). A wall tests only the
    particles within the neighbor skin of it (listed at each neighbor rebuild, as the pair list): a
    particle moving more than half the skin between rebuilds (`neigh_modify check no` with a long
    `every`) may pass it, as it may pass another particle."""

    style = "wall/plane"
    stages = Stage.POST_NEIGHBOR | Stage.POST_FORCE

    def __init__(self, sim, fid, group, args):
        super().__init__(sim, fid, group, args)
        usage = ("fix ID group wall/plane xplane LO HI [yplane ..] [zplane ..] [kn .. en .. mu ..] "
                 "[model hertz E .. nu .. en .. mu ..]")
        axes, positions, sides = [], [], []
        i = 0
        while i < len(args) and args[i] in ("xplane", "yplane", "zplane"):
            if i + 2 >= len(args):
                raise DemError(f"fix {fid} wall/plane: {args[i]} needs LO and HI (or NULL); usage: {usage}")
            d = "xyz".index(args[i][0])
            for word, side in ((args[i + 1], 1.0), (args[i + 2], -1.0)):
                if word == "NULL":
                    continue
                try:
                    pos = number(word)
                except ValueError:
                    raise DemError(f"fix {fid} wall/plane: wall position must be a number or NULL, got "
                                   f"'{word}'") from None
                axes.append(d)
                positions.append(pos)
                sides.append(side)
            i += 3
        if not axes:
            raise DemError(f"fix {fid} wall/plane: no wall given; usage: {usage}")
        rest = list(args[i:])
        self.point = 0
        if "point" in rest:
            k = rest.index("point")
            if k + 1 >= len(rest) or rest[k + 1] not in POINT_MODES:
                raise DemError(f"fix {fid} wall/plane: point must be {', '.join(POINT_MODES)}")
            self.point = POINT_MODES.index(rest[k + 1])
            del rest[k:k + 2]
        if "law" in rest:
            k = rest.index("law")
            self.contact_law = law_name(rest[k + 1] if k + 1 < len(rest) else "", f"fix {fid} wall/plane")
            del rest[k:k + 2]
        args = args[:i] + rest
        self.table_rows = np.array([plane(*w) for w in zip(axes, positions, sides)])
        self.parse_law(args[i:])
        self.ncontacts = 0
        self.max_overlap = 0.0
        self.energy = 0.0          # elastic energy stored in wall contacts (thermo pe, etotal)

    def init(self):
        self.init_walls(len(self.table_rows))

    def surfaces(self):
        return self.table_rows

    def surface_name(self, w):
        axis, pos, side = int(self.table_rows[w][S["A"]]), self.table_rows[w][S["POS"]], self.table_rows[w][S["SIDE"]]
        return f"'{'xyz'[axis]}plane {pos:g}' (facing {'+' if side > 0 else '-'}{'xyz'[axis]})"

    def thermo(self):
        return {"contacts": self.sim.comm.sum(self.ncontacts)}
