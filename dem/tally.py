"""Per-particle contact tallies for analysis (LAMMPS's `vflag`/`eflag_atom` idea, on request only).

An analysis style (compute or fix) names the tallies it reads in its class attribute `tallies`; at the
setup of each run `update()` collects them and declares one per-particle field per tally in use. Kernels
see the field through `Particles` (dem/_particles.pxd) as a pointer that is NULL when nobody asked, so a
run without such a compute pays one pointer test per contact and nothing else.

* `stress` (9 values, row-major): sum over the particle's contact points of F (x) (P - G), F the force
  the particle receives at point P, G its centre of mass (Moreau's per-particle moment tensor, Descantes
  eq. 12), written by the shared law (dem/law/apply.pxd) for every pair style and wall;
* `types` (5 values): the particle's pair contacts by type: vertex/face, edge/edge, edge/face,
  face/face, with a sphere (only `pair_style polyhedron/multipoint` knows the types);
* `count` (2 values): the particle's pair contacts (touching neighbours; a pair of composites or
  polyhedra touching at several points counts once) and their contact points (a glued pair: one per
  touching pair of pieces; polyhedron/multipoint: the points of its contact types; spheres and convex
  particles: 1 per contact), written by every pair style.

Fields are zeroed with the forces before the pair style and the ghosts' parts are added to their owners
with the forces (`clear`, `reverse`, called by Update.force_pass), so they describe the last force
evaluation like `f`. Wall fixes act after the pair style (POST_FORCE) and add to owned rows only; they do
not act in the setup force pass of a run (so `run 0` tallies the pair contacts only)."""
from .errors import DemError

FIELDS = {"stress": ("tally_stress", 9), "types": ("tally_types", 5), "count": ("tally_count", 2)}
TYPE_NAMES = ("vertex_face", "edge_edge", "edge_face", "face_face", "sphere")


class Tally:
    def __init__(self, sim):
        self.sim = sim
        self.active = ()          # field names in use, in FIELDS order
        self.filled_at = None     # (ntimestep, first_step) of the last force evaluation that filled them

    def _users(self):
        return list(self.sim.computes.values()) + list(self.sim.modify.fixes)

    def wanted(self):
        want = set()
        for obj in self._users():
            want.update(obj.tallies)
        return [k for k in FIELDS if k in want]

    def update(self):
        """Declare the fields the current computes and fixes read, drop the others (setup of a run)."""
        sim = self.sim
        want = self.wanted()
        pair = sim.pair
        for k in want:
            if pair is None or k not in pair.tallies:
                users = [f"{o.kind} {o.id} ({o.style})" for o in self._users() if k in o.tallies]
                style = "no pair style" if pair is None else f"pair_style {pair.style}"
                has = f" (it provides: {', '.join(pair.tallies)})" if pair is not None and pair.tallies else ""
                raise DemError(f"{', '.join(users)} need(s) the per-particle contact {k} tally, which {style} does "
                               f"not provide{has}")
        for k, (name, width) in FIELDS.items():
            if k in want:
                sim.atom.add_field(name, (width,), float, 0.0, border=False)
            else:
                sim.atom.remove_field(name)
        self.active = tuple(FIELDS[k][0] for k in want)
        self.filled_at = None

    def clear(self):
        if self.active:
            atom = self.sim.atom
            for name in self.active:
                atom.data[name][:atom.nall] = 0.0

    def reverse(self):
        if self.active:
            self.sim.comm.reverse(self.active)
            up = self.sim.update
            self.filled_at = (up.ntimestep, up.first_step)

    def get(self, kind, who):
        """The owned rows of tally `kind`, after checking they hold the last force evaluation."""
        name = FIELDS[kind][0]
        up = self.sim.update
        if name not in self.active or self.filled_at is None or self.filled_at[1] != up.first_step:
            raise DemError(f"{who}: the contact {kind} tally is filled by the force evaluation of a run: evaluate "
                           f"it during a run, or after one started with the compute defined (e.g. `run 0`)")
        return self.sim.atom.data[name][:self.sim.atom.nlocal]
