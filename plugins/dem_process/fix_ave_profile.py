"""fix ave/profile"""
import numpy as np

from dem.args import float_error, integer, number
from dem.errors import DemError
from dem.fix import Fix, Stage

from . import profile_bins as pb
from .analysis import axis_index, selection
from .compute_porosity import gather_bodies, grid_counts, solid_points
from .series_file import SeriesFile, sample_step


MAX_BINS = 10**6      # more than any profile can fill; the per-bin sums are held in memory


class FixAveProfile(Fix):
    """fix ID group ave/profile Nevery Nfreq FILE AXIS NBIN value ... [bounds LO HI] [kinetic yes|no] [dx D | resolution K]
    fix ID group ave/profile Nevery Nfreq FILE radial NBIN value ... cylinder A C1 C2 [bounds LO HI] [kinetic yes|no]

    Profiles along an axis, time-averaged and written to a file (LAMMPS's `compute chunk/atom bin/1d` with
    `fix ave/chunk`, in one fix): the group's particles are binned by their centre in NBIN (at most 1e6)
    slabs of equal width across [LO, HI) (finite numbers) along AXIS (x, y or z; default the box bounds when the fix is defined); every
    Nevery steps a sample is taken, and every Nfreq steps (a multiple of Nevery) the average of the samples
    since the last write is written, one line per bin. A bin's volume is its width times the box's cross-
    section (Descantes' L_x L_y dz).

    `radial` (LAMMPS's `bin/cylinder`): bins by the distance of the centre from the line along A (x, y or
    z) through C1 C2 (the two other coordinates, in x, y, z order), NBIN rings of equal width across
    [LO, HI) (default 0 to the farthest box face from the line, across it); a bin's volume is its ring's
    area times the box length along A. E.g. a drum: `radial 10 vt count ... cylinder y 0 0`. `vr vt`
    (radial bins only): the mean radial velocity and the tangential one, counter-clockwise about +A (the
    sense of `wall/drum`'s positive rpm). `phi` and `I` are for slabs only.

    Values (any of, in the order given):
    * `count` particles per bin (mean over the samples), `density` the same per unit volume;
    * `vx vy vz`, `wx wy wz`: mean velocity and spin of the bin's particles (sums over bin and samples
      divided by the count: LAMMPS's `norm all`); `vr vt` the same in cylindrical components (radial);
    * `Txx Tyy Tzz T`: granular temperature, Descantes eq. 13: T_jj = <v_j^2> - <v_j>^2 with both means over
      the bin and the samples (so slow changes of the mean flow between samples count as agitation), T the
      trace; per unit mass (m^2/s^2);
    * `phi`: solid fraction of the slab occupied by the true particle shapes (sphere, polytope, convex body,
      glued piece: the voxel test of `compute porosity`), grid spacing D (`dx`) or the smallest particle
      diameter of the group / K (`resolution`, default 20); Descantes uses Monte Carlo shots (Fig. 7), a
      regular grid gives the same mean without noise. It costs a grid pass per sample (~1e7 points/s);
      a grid of more than 1e10 points per sample (all slabs) is refused (at the fix line for `dx`, at
      the first sample for `resolution`);
    * `sxx syy szz sxy sxz syz p`: stress of the slab (Descantes eq. 12, as `compute stress`): -sym(sum of
      F (x) (P - G)) over the contacts of the bin's particles, divided by the bin volume, compression
      positive, p the mean normal stress; `kinetic yes` adds sum m v' v' per bin volume, v' about the bin's
      mean velocity in the sample;
    * `I`: inertial number gamma_dot d / sqrt(P / rho) (GDR MiDi; Descantes Fig. 16a), gamma_dot the norm of
      the gradient along AXIS of the two other mean velocity components (central differences of the
      averaged profile), P the averaged normal stress s_AXIS,AXIS, d the mean volume-equivalent diameter and
      rho the mean particle density of the bin; NaN where P <= 0 or a bin is empty;
    * `zs zd zt ztot ziso`: coordination by contact type as `compute contact/types` per bin (Fig. 9b; pair
      style polyhedron/multipoint only).

    File: a header `# step time bin coord value ...` then per write NBIN lines `step time bin coord v ...`
    (coord: the bin centre), a plain table that `numpy.loadtxt` reads whole (select the rows of one step).
    Empty bins give NaN for means. Stress and contact-type values need the per-particle contact tallies
    (dem/tally.py), turned on for the runs where this fix exists; the stress counts every pair style and
    wall. Samples are taken at the end of a step (the forces of that step's evaluation, the positions after
    it). Only rank 0 writes; every rank takes part in the sums.

    Example (Descantes Figs. 7-9, 0.1 d_eq slabs): `fix prof all ave/profile 1000 10000 prof.dat z 120
    phi szz sxx syy syz zs zd zt ziso count`."""

    style = "ave/profile"
    stages = Stage.END_OF_STEP

    def __init__(self, sim, fid, group, args):
        super().__init__(sim, fid, group, args)
        usage = ("fix ID group ave/profile Nevery Nfreq FILE x|y|z|radial NBIN value ... [cylinder A C1 C2] "
                 "[bounds LO HI] [kinetic yes|no] [dx D | resolution K]")
        what = f"fix {fid} ave/profile"
        if len(args) < 6:
            raise DemError(f"{what}: expected at least 6 arguments; usage: {usage}")
        self.every = _int(args[0], "Nevery", what)
        self.nfreq = _int(args[1], "Nfreq", what)
        if self.every < 1 or self.nfreq < 1 or self.nfreq % self.every:
            raise DemError(f"{what}: Nevery and Nfreq must be >= 1 and Nfreq a multiple of Nevery")
        path = args[2]
        self.radial = args[3] == "radial"
        self.axis = None if self.radial else axis_index(args[3], what)
        self.nbin = _int(args[4], "NBIN", what)
        if not 1 <= self.nbin <= MAX_BINS:
            raise DemError(f"{what}: NBIN must be in 1..{MAX_BINS}, got {self.nbin}")
        self.values, kw, i = [], {}, 5
        opts = {"bounds": 2, "kinetic": 1, "dx": 1, "resolution": 1, "cylinder": 3}
        while i < len(args):
            w = args[i]
            if w in opts:
                if i + opts[w] >= len(args):
                    raise DemError(f"{what}: '{w}' needs {opts[w]} value(s); usage: {usage}")
                kw[w] = args[i + 1:i + 1 + opts[w]]
                i += 1 + opts[w]
            elif w in pb.VALUES:
                self.values.append(w)
                i += 1
            else:
                raise DemError(f"{what}: unknown value or keyword '{w}' (values: {' '.join(pb.VALUES)}; keywords: "
                               f"{' '.join(opts)})")
        if not self.values:
            raise DemError(f"{what}: no value to profile; usage: {usage}")
        dom = sim.domain
        dom.require_box(what)
        self.cylinder = None
        if self.radial:
            if "cylinder" not in kw:
                raise DemError(f"{what}: radial bins need 'cylinder A C1 C2' (the axis and its position)")
            axis = axis_index(kw["cylinder"][0], what)
            centre = np.zeros(3)
            centre[[d for d in range(3) if d != axis]] = [_float(v, "cylinder", what) for v in kw["cylinder"][1:]]
            self.cylinder = pb.Cylinder(axis, centre)
        elif "cylinder" in kw:
            raise DemError(f"{what}: 'cylinder' goes with radial bins (AXIS radial), not with AXIS {args[3]}")
        wrong = set(self.values) & (pb.AXIAL_ONLY if self.radial else pb.RADIAL_ONLY)
        if wrong:
            raise DemError(f"{what}: {' '.join(sorted(wrong))} "
                           f"{'are for slabs along x, y or z' if self.radial else 'need radial bins (AXIS radial)'}")
        if "bounds" in kw:
            self.lo, self.hi = (_float(v, "bounds", what) for v in kw["bounds"])
        elif self.radial:
            c = self.cylinder
            self.lo = 0.0
            self.hi = float(max(max(c.centre[d] - dom.lo[d], dom.hi[d] - c.centre[d]) for d in (c.b, c.c)))
        else:
            self.lo, self.hi = float(dom.lo[self.axis]), float(dom.hi[self.axis])
        if self.radial and self.lo < 0:
            raise DemError(f"{what}: radial bounds start at 0 or more")
        if self.hi <= self.lo:
            raise DemError(f"{what}: bounds must have HI > LO")
        if "dx" in kw and "resolution" in kw:
            raise DemError(f"{what}: give dx or resolution, not both")
        self.dx = _float(kw["dx"][0], "dx", what) if "dx" in kw else None
        self.resolution = _float(kw["resolution"][0], "resolution", what) if "resolution" in kw else 20.0
        if (self.dx is not None and self.dx <= 0) or self.resolution <= 0:
            raise DemError(f"{what}: dx and resolution must be > 0")
        word = kw.get("kinetic", ["no"])[0]
        if word not in ("yes", "no"):
            raise DemError(f"{what}: kinetic must be yes or no, got '{word}'")
        self.kinetic = word == "yes"
        wanted = set(self.values)
        self.tallies = tuple(k for k, names in (("stress", pb.NEEDS_STRESS), ("types", pb.NEEDS_TYPES))
                             if wanted & names)
        self.width = (self.hi - self.lo) / self.nbin
        self.centres = self.lo + (np.arange(self.nbin) + 0.5) * self.width
        self.acc = np.zeros((self.nbin, pb.WIDTH))
        self.last = None
        if "phi" in self.values and self.dx is not None:
            self._grid(self.dx)           # an absurd dx is refused here, not when the first sample never ends
        self.file = SeriesFile(sim, path, what, "# step time bin coord " + " ".join(self.values),
                               f"fix {self.id}")
        where = (f"radial about {'xyz'[self.cylinder.axis]} through ({', '.join(f'{c:.10g}' for c in self.cylinder.centre)})"
                 if self.radial else f"axis {'xyz'[self.axis]}")
        self.file.comment(f"# fix {fid} ave/profile: {where}, {self.nbin} bins of width "
                          f"{self.width:.10g} from {self.lo:.10g}; averages of the samples every {self.every} "
                          f"steps, written every {self.nfreq}")

    def bin_volume(self):
        """A slab's volume, or each ring's (radial)."""
        prd = np.asarray(self.sim.domain.prd, float)
        if self.radial:
            edges = self.lo + np.arange(self.nbin + 1) * self.width
            return np.pi * np.diff(edges * edges) * prd[self.cylinder.axis]
        return self.width * float(np.prod([prd[d] for d in range(3) if d != self.axis]))

    def _grid(self, dx):
        """(points per axis, spacing) of the phi grid of one slab, spacing about dx."""
        prd = np.asarray(self.sim.domain.prd, float).copy()
        prd[self.axis] = self.width
        npts = grid_counts(prd, dx, f"fix {self.id} ave/profile: phi", copies=self.nbin)
        return npts, prd / npts

    def _solid_fraction(self, sel):
        """phi per bin: one grid pass per slab, the grid across the box's cross-section."""
        sim = self.sim
        dom = sim.domain
        dx = self.dx
        if dx is None:
            r = sim.atom.data["radius"][:sim.atom.nlocal][sel]
            rmin = sim.comm.min(float(r.min()) if len(r) else np.inf)
            if not np.isfinite(rmin):
                return np.zeros(self.nbin)
            dx = 2.0 * rmin / self.resolution
        lo = np.asarray(dom.lo, float).copy()
        lo[self.axis] = self.lo
        npts, h = self._grid(dx)
        phi = np.zeros(self.nbin)
        bodies = gather_bodies(sim, sel)
        for k in range(self.nbin):
            lo[self.axis] = self.lo + k * self.width
            inside, solid = solid_points(sim, bodies, lo, h, npts)
            phi[k] = solid / inside if inside else 0.0
        return phi

    def sample(self):
        sim = self.sim
        sel = selection(sim, self.groupbit)
        who = f"fix {self.id} ave/profile"
        stress = sim.tally.get("stress", who) if "stress" in self.tallies else None
        types = sim.tally.get("types", who) if "types" in self.tallies else None
        acc = pb.sample_sums(sim, sel, self.axis, self.lo, self.width, self.nbin, self.bin_volume(), stress,
                             types, self.kinetic, self.cylinder)
        acc = sim.comm.sum_values(acc.reshape(-1)).reshape(acc.shape)
        if self.kinetic:
            pb.add_kinetic(acc, self.bin_volume())
        if "phi" in self.values:
            acc[:, pb.LAYOUT["phi"]] = self._solid_fraction(sel)[:, None]
        acc[:, pb.LAYOUT["samples"]] = 1.0
        self.acc += acc

    def write(self, step, time):
        prof = pb.profiles(self.acc, self.centres, self.axis, self.bin_volume())
        cols = np.column_stack([prof[v] for v in self.values])
        lines = [f"{step} {time:.10g} {k + 1} {self.centres[k]:.10g} " + " ".join(f"{c:.10g}" for c in cols[k])
                 for k in range(self.nbin)]
        self.file.write(lines)
        self.acc[:] = 0.0

    def end_of_step(self):
        up = self.sim.update
        step = sample_step(self)
        if step is None:
            return
        self.sample()
        if step % self.nfreq == 0:
            self.write(step, up.time + up.dt)

    def unfix(self):
        self.file.close()


def _int(word, name, what):
    try:
        return integer(word)
    except ValueError:
        raise DemError(f"{what}: {name} must be an integer, got '{word}'") from None


def _float(word, name, what):
    try:
        return number(word)
    except ValueError:
        raise DemError(f"{what}: {float_error(word, name)}") from None
