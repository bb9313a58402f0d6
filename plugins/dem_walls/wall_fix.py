"""WallFix: what every wall fix shares: the law per surface and type (WallCoefficients), the shape view,
and the call of the wall kernel on the fix's surfaces table."""
import numpy as np

from dem._particles import ParticleView
from dem.errors import DemError
from dem.law import WORDS, max_reach
from dem.law.wall_coeffs import WallCoefficients
from dem.shapes import command as shape_command

from . import _walls
from ._walls import STAT, SURFACE as S


def plane(axis, position, side):
    """A surfaces-table row: the plane x[axis] = position facing side (+1 or -1), at rest."""
    row = np.zeros(S["NCOL"])
    row[S["A"]], row[S["POS"]], row[S["SIDE"]], row[S["SPIN"]] = axis, position, side, -1
    return row


def cylinder(axis, centre, radius):
    """A surfaces-table row: the inside of the cylinder of the given radius about axis through centre."""
    row = np.zeros(S["NCOL"])
    row[S["CYLINDER"]], row[S["A"]], row[S["R"]], row[S["SPIN"]] = 1.0, axis, radius, -1
    row[S["CENTRE"]:S["CENTRE"] + 3] = centre
    return row


def turning(row, axis, centre, omega):
    """The row turning at omega (rad/s) about the coordinate axis through centre."""
    row = row.copy()
    row[S["SPIN"]], row[S["OMEGA"]] = axis, omega
    row[S["CENTRE"]:S["CENTRE"] + 3] = centre
    return row


POINT_MODES = ("deepest", "centroid", "multipoint")   # `point` keyword of the wall fixes (kernel's `point`)
LAWS = ("grains3d", "descantes", "volume")             # `law` keyword of the wall fixes (dem.law, dem/law/volume.pxd)


def law_name(word, what):
    """The `law` keyword's value checked: one of LAWS (DemError naming the fix otherwise)."""
    if word not in LAWS:
        raise DemError(f"{what}: law must be {' or '.join(LAWS)}, got '{word}'")
    return word


def wall_keyword(fix, a, i, law, modes=POINT_MODES, laws=LAWS):
    """The keywords every wall fix takes, at a[i] (dem.args.Args): `point MODE` (one of modes) sets
    fix.point, `law NAME` (one of laws) fix.contact_law, a word of the law (or `type T`) is added to the
    list `law`. Returns the index after it, or None for another keyword."""
    key = a[i]
    if key == "point":
        if a[i + 1] not in modes:
            raise a.error(f"point must be {', '.join(modes)}, got '{a[i + 1]}'")
        fix.point = POINT_MODES.index(a[i + 1])
    elif key == "law":
        fix.contact_law = law_name(a[i + 1], f"fix {fix.id} {fix.style}")
        if fix.contact_law not in laws:
            raise a.error(f"law {fix.contact_law} is not available on this wall (it takes {', '.join(laws)})")
    elif key in LAW_WORDS:
        law += a.words[i:i + 2]
    else:
        return None
    return i + 2


LAW_WORDS = WORDS + ("type",)
WALL_KEYWORDS = ["point", "law"] + list(LAW_WORDS)   # for did_you_mean


class WallFix(WallCoefficients):
    """Mixin of a wall Fix: `surfaces()` returns the current table (one row per surface, the same count as
    the coefficient table's walls); `self.point` (an index of POINT_MODES) chooses the contact point(s) of
    shaped particles; `self.contact_law` (one of LAWS, default grains3d) the law at every contact point:
    `descantes` is Descantes' eq. 3 of the shared law (dem.law.descantes; no spring, no history)."""
    point = 0
    max_history = None           # the kernel keeps any history layout (dem.law.prepare)

    def init_walls(self, nwalls):
        self.init_table(nwalls)
        self.shape_view = shape_command.shape_view(self.sim)
        self.stats = np.zeros(STAT["NSTAT"])
        self.stats[STAT["WORST_I"]] = -1
        self.behind = 0
        self.reach = max_reach(self.table[:, 1:], self.sim.modify.max_radius())   # bonded spheres hold this far
        self.candidates_for = -1

    def post_neighbor(self):
        """The pairs of particles and surfaces to test until the next rebuild (_walls.candidates)."""
        sim = self.sim
        reach = (sim.neighbor.skin or 0.0) + self.reach
        self.candidates = _walls.candidates(ParticleView(sim.atom), int(self.groupbit), self.surfaces(), reach)
        self.candidates_for = sim.atom.nlocal

    def compute(self, advance):
        sim = self.sim
        if self.candidates_for != sim.atom.nlocal:   # particles removed since the rebuild: indices moved
            self.post_neighbor()
        _walls.walls(ParticleView(sim.atom), int(self.groupbit), self.surfaces(), self.table, self.shape_view,
                     self.history(), self.law_width, self.use_history, self.bonds, sim.update.dt, advance,
                     self.point, bool(getattr(sim.pair, "multipoint_average", True)), self.contact_law == "volume",
                     *self.candidates, self.stats)
        self.ncontacts = int(self.stats[STAT["CONTACTS"]])
        self.max_overlap = float(self.stats[STAT["MAXOV"]])
        self.energy = float(self.stats[STAT["ENERGY"]])
        self.torque = float(self.stats[STAT["TORQUE"]])
        self.behind = int(self.stats[STAT["BEHIND"]])

    def worst_contact(self):
        """(overlap / diameter, text naming the particle and the surface) of this rank's largest wall
        overlap at the last compute, or None (for the overlap stop, `Update.check_step`)."""
        i = int(self.stats[STAT["WORST_I"]])
        if i < 0:
            return None
        tag = int(self.sim.atom.data["tag"][i])
        gap = float(self.stats[STAT["WORST_GAP"]])
        text = f"particle {tag} and wall {self.surface_name(int(self.stats[STAT['WORST_W']]))} of fix {self.id}"
        if gap < 0.0:
            text += f" (its centre lies {-gap:.3g} behind the wall)"
        return self.max_overlap, text

    def surface_name(self, w):
        """How an error names surface w of the table (wall styles say more)."""
        return f"surface {w}"

    def post_force(self):
        self.compute(True)
