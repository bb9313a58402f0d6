"""fix insert"""

import numpy as np

from dem.args import float_error, number
from dem.commands import find_region
from dem.errors import DemError, did_you_mean
from dem.fix import Fix, Stage
from dem.shapes.command import ShapeTemplate, random_quaternions

from . import _fix_insert
from .templates import RadiusDistribution, SphereTemplate


def random_points(region, domain, rng, n, margin):
    """n uniform random points of the region at least `margin` from its boundary, except across periodic
    boundaries that the region spans (there a particle may straddle the boundary: its image continues
    it). Spanned axes are tested at the middle of the region, the others as they are."""
    lo, hi = region.extent(0.0)
    lo, hi = np.maximum(lo, domain.lo), np.minimum(hi, domain.hi)
    if np.any(hi <= lo):
        raise DemError(f"region {region.id} lies outside the box")
    span = domain.periodic & (lo <= domain.lo) & (hi >= domain.hi)
    mid = 0.5 * (lo + hi)
    out, tries = [], 0
    count = 0
    while count < n:
        trial = lo + (hi - lo) * rng.random((max(2 * (n - count), 64), 3))
        if region.side_in:
            probe = np.where(span, mid, trial)
            keep = region._inside_margin(probe, margin)
        else:
            keep = region.inside(trial)
        out.append(trial[keep])
        count += int(keep.sum())
        tries += 1
        if tries > 1000 and count == 0:
            raise DemError(f"region {region.id} has no room for a particle of radius {margin:g}")
    return np.vstack(out)[:n]


class FixInsert(Fix):
    """fix ID group insert SEED REGION-ID count N | volfrac PHI [every M] [per K | massrate Q] [start STEP]
        [radius R | radius uniform|gaussian|lognormal A B | radius discrete R1 F1 ...] [density RHO]
        [shape NAME [scale ...] | mix NAME1 W1 NAME2 W2 ... [fractions mass|number]] [type T]
        [v VX VY VZ] [omega WX WY WZ] [orient random|fixed]

    Inserts particles at random positions and orientations inside a region, without overlap (Part III
    sec 4.1): at each insertion step, K pending particles (default: all that are pending) get a fresh
    random position, at least the largest of their radii inside the region's boundary (except across
    the periodic boundaries that the region spans), and a random orientation; one that would overlap
    anything (existing particles, periodic images included, or a particle placed earlier in the same
    step) is not inserted now: it stays pending and is tried again at the next insertion step with a new
    random pose. Insertion steps come every M steps (default 1) from the first step of the next run (or
    from step START). The candidates are drawn and tested when the step starts, as the neighbor list
    decides whether to rebuild; only a step at which one of them fits forces a rebuild, and they are
    added at its PRE_EXCHANGE (the same positions: nothing moves in between). A step at which none fits
    leaves the list alone (a packing fed into a full layer retries every step without rebuilding).

    * `massrate Q`: a continuous feed of Q kg/s instead of all pending particles at each insertion step
      (not with `per`). At an insertion step at time t, the pending particles are taken in the order
      they were drawn while the mass inserted before each (earlier steps and the ones taken before it
      at this step) is at most Q (t - t0), t0 the time of the first insertion step: the inserted mass
      stays at or below Q (t - t0) plus one particle's mass (so the first particle goes in at t0, and
      a slow rate starts at once). For particles of equal mass m, floor(Q (t - t0) / m) + 1 have been
      taken by time t (until the count is reached). A particle refused for overlap stays first in line
      and is retried at the next insertion step; the target is cumulative, so a feed held back by a
      full region catches up once there is room. Insertion steps at which the feed has nothing to take
      draw nothing (a slow feed with `every 1` rebuilds only when a particle is due and fits).
    * `count N`: insert N particles; `volfrac PHI`: insert particles until their volume reaches PHI times
      the region volume (the sizes are drawn up front, so the number is known at once).
    * Sizes: `radius` (default 0.5, see `create_atoms`): one size, `uniform RMIN RMAX`, `gaussian MEAN SD`
      (truncated at +-3 SD), `lognormal MEDIAN SIGMA` (ln R normal, truncated at +-3 SIGMA) or `discrete
      R1 F1 R2 F2 ...` (sizes in number fractions); `density` (default 1, mass = density x volume). All
      sizes are drawn once, from SEED, before insertion starts: a particle keeps its size across retries
      (no bias towards small particles).
    * `type` (default 1), initial `v` and `omega` (default 0), `orient random` (default) or `fixed`
      (identity quaternion).
    * New particles join `all` and the fix group, get ids above the largest existing id.
    * Walls are not tested: keep the region clear of them (the margin keeps particles inside it).
    * Shapes: `shape NAME [scale S | scale uniform A B | scale gaussian M SD]` inserts particles of a
      shape defined by the `shape` command (scale 1: the shape as defined), with random orientations;
      the overlap test uses bounding spheres (conservative for non-spherical shapes).
    * Mixtures: `mix NAME1 W1 NAME2 W2 ...` draws each particle's kind from the shapes NAME (or `sphere`)
      with weights W, mass fractions by default as LIGGGHTS's particledistribution/discrete (`fractions
      number` for number fractions); weights are normalised to sum 1. Spheres take the `radius`
      distribution, shapes the `scale` one; all share `density` and `type`. The kinds are drawn with the
      sizes, up front (module `templates`).

    The random stream depends only on SEED (every rank draws the same candidates; each rank tests its own
    particles and the verdicts are combined), so the packing is the same whatever the number of ranks.
    The ghost cutoff covers the largest particle to come from the start of the run. A line is logged when
    every particle has been inserted. Thermo: `f_ID[inserted]`, `f_ID[pending]`, `f_ID[mass]` (the
    inserted mass).

    Example (Part III sec 4.1: a shower from a thin layer at the top of the box)::

        region top block EDGE EDGE EDGE EDGE 0.09 0.1
        fix ins all insert 4821 top count 1000 every 200 per 40 radius 0.0015 density 2500 v 0 0 -0.5
    """

    style = "insert"
    thermo_quantities = {"inserted": ("particles inserted", "-"), "pending": ("particles to insert", "-"),
                         "mass": ("mass inserted", "kg")}
    stages = Stage.PRE_EXCHANGE
    usage = ("SEED REGION-ID count N | volfrac PHI [every M] [per K | massrate Q] [start STEP] [radius ...] "
             "[shape NAME [scale ...] | mix NAME1 W1 ... [fractions mass|number]] [density RHO] [type T] "
             "[v VX VY VZ] [omega WX WY WZ] [orient random|fixed]")
    COUNTS = {"count": 1, "volfrac": 1, "every": 1, "per": 1, "start": 1, "radius": 1, "density": 1,
              "type": 1, "v": 3, "omega": 3, "orient": 1, "shape": 1, "scale": 1, "mix": 2, "fractions": 1,
              "massrate": 1}

    def __init__(self, sim, fid, group, args):
        super().__init__(sim, fid, group, args)
        what = f"fix {fid} insert"
        self.need(2, self.usage)
        try:
            self.seed = int(args[0])
        except ValueError:
            raise DemError(f"{what}: SEED must be an integer, got '{args[0]}'") from None
        if self.seed <= 0:
            raise DemError(f"{what}: SEED must be > 0")
        self.region = find_region(sim, args[1])
        kw = self._keywords(args[2:], what)
        if ("count" in kw) == ("volfrac" in kw):
            raise DemError(f"{what}: give exactly one of 'count N' or 'volfrac PHI'; usage: fix ID group "
                           f"insert {self.usage}")
        num = lambda k, i=0: self._number(kw[k][i], k, what)   # noqa: E731
        self.every = int(num("every")) if "every" in kw else 1
        self.per = int(num("per")) if "per" in kw else None
        self.start = int(num("start")) if "start" in kw else None
        if self.every < 1 or (self.per is not None and self.per < 1):
            raise DemError(f"{what}: every and per must be >= 1")
        self.massrate = num("massrate") if "massrate" in kw else None
        if self.massrate is not None:
            if "per" in kw:
                raise DemError(f"{what}: give either 'per K' or 'massrate Q', not both")
            if self.massrate <= 0:
                raise DemError(f"{what}: massrate must be > 0 (kg/s), got {kw['massrate'][0]}")
        density = num("density") if "density" in kw else 1.0
        if density <= 0:
            raise DemError(f"{what}: density must be > 0")
        self.type = int(num("type")) if "type" in kw else 1
        if not 1 <= self.type <= sim.atom.ntypes:
            raise DemError(f"{what}: type {self.type} out of range 1..{sim.atom.ntypes}")
        self.v = np.array([num("v", k) for k in range(3)]) if "v" in kw else np.zeros(3)
        self.omega0 = np.array([num("omega", k) for k in range(3)]) if "omega" in kw else np.zeros(3)
        orient = kw.get("orient", ["random"])[0]
        if orient not in ("random", "fixed"):
            raise DemError(f"{what}: orient must be random or fixed")
        self.random_orient = orient == "random"
        self.templates, weights = self._templates(sim, kw, density, what)
        self.rng = np.random.default_rng(self.seed)
        if "count" in kw:
            n = int(num("count"))
            if n < 0:
                raise DemError(f"{what}: count must be >= 0")
            self.kinds, self.radii = self._draw(n, weights)
        else:
            phi = num("volfrac")
            if not 0 < phi < 1:
                raise DemError(f"{what}: volfrac must be in (0, 1)")
            if not self.region.side_in:
                raise DemError(f"{what}: volfrac needs a region with side in")
            self.kinds, self.radii = self._draw_volume(phi * self.region.volume(), weights)
        self.pending = np.arange(len(self.radii))     # particles still to insert, in order
        self.next_step = None
        self.inserted = 0
        self.attempts = 0
        self.done_logged = False
        self.t0 = None               # time of the first insertion step (massrate)
        self._masses = None
        self._mass_in = None         # cached inserted_mass()
        self._ready = None           # the candidates that fit, from wants_rebuild to this step's PRE_EXCHANGE

    # ----- parsing --------------------------------------------------------------------------------
    def _keywords(self, words, what):
        kw, i = {}, 0
        while i < len(words):
            key = words[i]
            if key not in self.COUNTS:
                raise DemError(f"{what}: unknown keyword '{key}'{did_you_mean(key, self.COUNTS)}; usage: "
                               f"fix ID group insert {self.usage}")
            if key in ("radius", "scale"):
                n = RadiusDistribution.nwords(words, i)
            elif key == "mix":              # NAME W pairs, up to the next keyword
                n = 0
                while i + 1 + n < len(words) and words[i + 1 + n] not in self.COUNTS:
                    n += 1
                if not n:
                    raise DemError(f"{what}: mix needs NAME WEIGHT pairs")
            else:
                n = self.COUNTS[key]
            if len(words[i + 1:i + 1 + n]) < n:
                raise DemError(f"{what}: keyword '{key}' needs {n} value(s)")
            kw[key] = words[i + 1:i + 1 + n]
            i += 1 + n
        return kw

    def _templates(self, sim, kw, density, what):
        """The templates and their number fractions (None: a single template)."""
        if "mix" in kw and "shape" in kw:
            raise DemError(f"{what}: give either 'shape NAME' or 'mix NAME W ...', not both")
        if "fractions" in kw and "mix" not in kw:
            raise DemError(f"{what}: 'fractions' needs 'mix'")
        if "shape" in kw and "radius" in kw:
            raise DemError(f"{what}: give the size of shaped particles with 'scale', not 'radius'")
        if "scale" in kw and "shape" not in kw and "mix" not in kw:
            raise DemError(f"{what}: 'scale' needs 'shape NAME' or 'mix' (spheres: radius)")
        radii = RadiusDistribution(kw.get("radius", ["0.5"]), what)
        scales = RadiusDistribution(kw.get("scale", ["1"]), f"{what} scale")
        if "shape" in kw:
            return [ShapeTemplate(sim, kw["shape"][0], scales, density)], None
        if "mix" not in kw:
            return [SphereTemplate(radii, density)], None
        words = kw["mix"]
        if len(words) % 2:
            raise DemError(f"{what}: mix takes NAME WEIGHT pairs, got '{' '.join(words)}'")
        names, w = words[::2], np.array([self._number(x, "mix weight", what) for x in words[1::2]])
        if (w < 0).any() or w.sum() <= 0:
            raise DemError(f"{what}: mix weights must be >= 0, not all 0")
        mode = kw.get("fractions", ["mass"])[0]
        if mode not in ("mass", "number"):
            raise DemError(f"{what}: fractions must be mass or number, got '{mode}'")
        if not np.isclose(w.sum(), 1.0):
            sim.warning(f"{sim.input.location + ': ' if sim.input.location else ''}{what}: mix weights sum "
                        f"to {w.sum():g}, normalised to 1")
        templates = [SphereTemplate(radii, density) if name == "sphere" else
                     ShapeTemplate(sim, name, scales, density) for name in names]
        if mode == "mass":       # number fraction of kind k ~ its mass fraction / its mean mass
            w = w / np.array([t.mean_volume() for t in templates])
        return templates, w / w.sum()

    def _draw(self, n, weights):
        """Kinds and sizes of n particles (one template: the sizes only, as the stream always was)."""
        if weights is None:
            return np.zeros(n, dtype=np.int32), self.templates[0].draw_radius(self.rng, n)
        kinds = self.rng.choice(len(weights), size=n, p=weights).astype(np.int32)
        radii = np.zeros(n)
        for t, tpl in enumerate(self.templates):
            sel = kinds == t
            radii[sel] = tpl.draw_radius(self.rng, int(sel.sum()))
        return kinds, radii

    @staticmethod
    def _number(word, key, what):
        try:
            return number(word)
        except ValueError:
            raise DemError(f"{what}: {float_error(word, key)}") from None

    def _draw_volume(self, target, weights):
        """Kinds and sizes drawn in chunks until their volume reaches the target (the particle that
        reaches it included)."""
        smallest = min(t.mean_volume() for t in self.templates)
        chunk = max(16, int(target / smallest) + 16)
        kinds, radii, total = [], [], 0.0
        while total < target:
            k, r = self._draw(chunk, weights)
            vol = np.zeros(chunk)
            for t, tpl in enumerate(self.templates):
                sel = k == t
                vol[sel] = tpl.volume(r[sel])
            vol = np.cumsum(vol) + total
            m = int(np.searchsorted(vol, target)) + 1
            if m <= chunk:
                kinds.append(k[:m])
                radii.append(r[:m])
                break
            kinds.append(k)
            radii.append(r)
            total = float(vol[-1])
        if not radii:
            return np.zeros(0, dtype=np.int32), np.zeros(0)
        return np.concatenate(kinds), np.concatenate(radii)

    # ----- fix interface --------------------------------------------------------------------------
    def max_radius(self):
        return float(self.radii[self.pending].max()) if len(self.pending) else 0.0

    def init(self):
        dom = self.sim.domain
        lo, hi = self.region.extent()
        fixed = [d for d in range(3) if not dom.periodic[d] and "f" in dom.boundary[d]]
        for d in fixed:
            if lo[d] < dom.lo[d] or hi[d] > dom.hi[d]:
                raise DemError(f"fix {self.id} insert: region {self.region.id} extends beyond the box along "
                               f"{'xyz'[d]} (a fixed boundary): particles inserted there would be lost")

    def setup(self):
        step = self.sim.update.ntimestep
        if self.next_step is None:
            self.next_step = step if self.start is None else max(step, self.start)
        if len(self.pending) and self.next_step <= step:
            self.next_step = step
        self._ready = None

    def wants_rebuild(self, step):
        """Asked by the neighbor list at the start of every step (Neighbor.decide): on an insertion step,
        draws and tests the candidates; a rebuild only when one of them fits (inserted at PRE_EXCHANGE)."""
        if not len(self.pending) or self.next_step is None or step < self.next_step:
            return False
        self.next_step = step + self.every
        self._ready = self._test(step)
        return self._ready is not None

    def pre_exchange(self):
        ready, self._ready = self._ready, None
        if ready is not None:
            self._insert(*ready)

    def masses(self):
        """Masses of all the drawn particles (pending or not), in draw order."""
        if self._masses is None:
            self._masses = self._properties(np.arange(len(self.radii)))["rmass"]
        return self._masses

    def inserted_mass(self):
        """Mass of the particles inserted so far, all ranks (the drawn particles no longer pending)."""
        if self._mass_in is None:
            done = np.ones(len(self.radii), dtype=bool)
            done[self.pending] = False
            self._mass_in = float(self.masses()[done].sum())
        return self._mass_in

    def _take(self):
        """The pending particles to try at this insertion step, a prefix of the pending list."""
        if self.per is not None:
            return self.pending[:self.per]
        if self.massrate is None:
            return self.pending
        time = self.sim.update.time
        if self.t0 is None:
            self.t0 = time
        m = self.masses()[self.pending]
        before = self.inserted_mass() + (np.cumsum(m) - m)     # mass inserted before each pending particle
        k = int(np.searchsorted(before, self.massrate * (time - self.t0), side="right"))
        return self.pending[:k]

    def _test(self, step):
        """Draws this insertion step's candidates and tests them (all ranks agree); returns what
        _insert needs when at least one fits, else None (they stay pending)."""
        sim, atom, dom = self.sim, self.sim.atom, self.sim.domain
        take = self._take()
        if not len(take):
            return None
        k = len(take)
        radius = self.radii[take]
        # every rank draws the same candidates from the same stream
        x = random_points(self.region, dom, self.rng, k, float(radius.max()))
        quat = random_quaternions(self.rng, k)
        if not self.random_orient:
            quat[:] = (1.0, 0.0, 0.0, 0.0)
        self.attempts += k
        reject = np.zeros(k, dtype=np.int8)
        periodic = dom.periodic.astype(np.int32)
        n = atom.nlocal
        # against this rank's particles (minimum image across periodic boundaries), then the verdicts of
        # all ranks combined, then among the candidates in order (the same on every rank)
        _fix_insert.clash(atom.data["x"][:n], atom.data["radius"][:n], n, x, radius, k, dom.lo, dom.prd,
                          periodic, False, reject)
        if sim.comm.nprocs > 1:
            reject = np.maximum.reduce(sim.comm.allgather(reject)).astype(np.int8)
        _fix_insert.clash(np.zeros((0, 3)), np.zeros(0), 0, x, radius, k, dom.lo, dom.prd, periodic, True,
                          reject)
        ok = reject == 0
        if not ok.any():
            return None
        return step, take, ok, x, quat

    def _insert(self, step, take, ok, x, quat):
        sim, atom = self.sim, self.sim.atom
        k = len(take)
        chosen = take[ok]
        nnew = len(chosen)
        first = atom.max_tag + 1
        tags = first + np.arange(nnew, dtype=np.int64)
        mine = sim.comm.owned_mask(x[ok])
        self._add(chosen[mine], x[ok][mine], quat[ok][mine], tags[mine])
        atom.max_tag = first + nnew - 1      # the same on every rank
        atom.natoms += nnew
        self.inserted += nnew
        self.pending = np.concatenate([take[~ok], self.pending[k:]])
        self._mass_in = None
        if not len(self.pending) and not self.done_logged:
            self.done_logged = True
            sim.print(f"fix {self.id} insert: all {self.inserted} particles inserted at step {step} "
                      f"(t = {sim.update.time:.6g} s, {self.attempts} attempts)")

    def _properties(self, idx):
        """rmass, inertia and shape of the drawn particles idx."""
        n = len(idx)
        kinds = self.kinds[idx]
        radius = self.radii[idx]
        props = {"rmass": np.zeros(n), "inertia": np.zeros((n, 3)), "shape": np.zeros(n, dtype=np.int32)}
        for t, tpl in enumerate(self.templates):
            sel = kinds == t
            if sel.any():
                for name, values in tpl.properties(radius[sel]).items():
                    props[name][sel] = values
        return props

    def _add(self, idx, x, quat, tags):
        atom = self.sim.atom
        n = len(idx)
        if not n:
            return
        radius = self.radii[idx]
        props = self._properties(idx)
        s = atom.add(x, radius, props["rmass"], self.type, v=np.tile(self.v, (n, 1)),
                     omega=np.tile(self.omega0, (n, 1)), tags=tags, quat=quat, inertia=props["inertia"],
                     shape=props["shape"])
        atom.data["mask"][s] |= self.groupbit

    def thermo(self):
        return {"inserted": self.inserted, "pending": len(self.pending), "mass": self.inserted_mass()}

    def state(self):
        return {"rng": self.rng.bit_generator.state, "radii": self.radii, "kinds": self.kinds,
                "pending": self.pending, "next_step": self.next_step, "inserted": self.inserted,
                "attempts": self.attempts, "done_logged": self.done_logged, "t0": self.t0}

    def restore(self, state):
        self.rng.bit_generator.state = state["rng"]
        for key in ("radii", "kinds", "pending", "next_step", "inserted", "attempts", "done_logged"):
            setattr(self, key, state[key])
        self.t0 = state.get("t0")          # absent from restarts written before massrate existed
        self._masses = self._mass_in = None
