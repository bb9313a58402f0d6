"""create_atoms and set: making particles and changing their properties."""
import math

import numpy as np

from .shapes import command as shape_command
from .command import Command
from .commands import find_region
from .errors import DemError


# more particles than this in one create_atoms is a typo (1e13 would exhaust any memory before failing)
MAX_CREATE = 10 ** 9


def sphere_mass(radius, density):
    return density * 4.0 / 3.0 * math.pi * np.asarray(radius, dtype=float) ** 3


def radius_spec(a, kw, n, rng):
    """Radii from `radius R`, `radius uniform RMIN RMAX` or `radius gaussian MEAN SD` (truncated > 0)."""
    words = kw.get("radius")
    if words is None:
        return np.full(n, 0.5)
    if words[0] == "uniform":
        lo, hi = a.to_float(words[1], "rmin"), a.to_float(words[2], "rmax")
        if not 0 < lo <= hi:
            raise a.error("radius uniform needs 0 < rmin <= rmax")
        return lo + (hi - lo) * rng.random(n)
    if words[0] == "gaussian":
        mean, sd = a.to_float(words[1], "mean"), a.to_float(words[2], "sd")
        if mean <= 0 or sd < 0:
            raise a.error("radius gaussian needs mean > 0 and sd >= 0")
        r = mean + sd * rng.standard_normal(n)
        return np.clip(r, 0.1 * mean, None)
    r = a.to_float(words[0], "radius")
    if r <= 0:
        raise a.error("radius must be > 0")
    return np.full(n, r)


def _radius_words(a, start):
    """Split the keyword tail, allowing `radius uniform A B` / `radius gaussian A B` (3 values)."""
    words = a.words[start:]
    kw, i = {}, 0
    counts = {"radius": 1, "density": 1, "v": 3, "omega": 3, "attempts": 1, "seed": 1, "shape": 1,
              "scale": 1, "quat": 4}
    while i < len(words):
        key = words[i]
        if key not in counts:
            from .errors import did_you_mean
            raise a.error(f"unknown keyword '{key}'{did_you_mean(key, counts)}")
        n = counts[key]
        if key in ("radius", "scale") and i + 1 < len(words) and words[i + 1] in ("uniform", "gaussian"):
            n = 3
        if key == "quat" and i + 1 < len(words) and words[i + 1] == "random":
            n = 1
        if i + n >= len(words) + 1 or len(words[i + 1:i + 1 + n]) < n:
            raise a.error(f"keyword '{key}' needs {n} value(s)")
        kw[key] = words[i + 1:i + 1 + n]
        i += 1 + n
    return kw


def _seed(a, kw):
    seed = a.to_int(kw["seed"][0], "seed") if "seed" in kw else 1
    if seed < 0:
        raise a.error("seed must be >= 0")
    return seed


def _min_image(d, domain):
    per = domain.periodic
    if per.any():
        prd = domain.prd
        d[:, per] -= prd[per] * np.round(d[:, per] / prd[per])
    return d


class CreateAtoms(Command):
    """create_atoms TYPE single X Y Z [keywords]
    create_atoms TYPE random N SEED REGION-ID [keywords]
    create_atoms TYPE lattice REGION-ID sc|bcc|fcc SPACING [keywords]

    Keywords: `radius R` | `radius uniform RMIN RMAX` | `radius gaussian MEAN SD` (default 0.5 m: give
    the size here, particles are placed at it; `set ... diameter` afterwards cannot make them fit),
    `density RHO` (default 1), `v VX VY VZ`, `omega WX WY WZ`, `attempts N` (random: tries per particle,
    default 1000).
    Shaped particles (see the `shape` command): `shape NAME`, `scale S` | `scale uniform SMIN SMAX` |
    `scale gaussian MEAN SD` (default 1; or give the bounding `radius` instead), `quat W X Y Z` |
    `quat random` (orientation body -> space, default identity; random: uniform, from the seed of
    `random`, or `seed N`). Mass = density x volume, principal inertia of the (scaled) shape, radius =
    bounding radius; `random` keeps the bounding spheres apart.
    `random` places N non-overlapping spheres uniformly inside the region (fully inside it, not
    overlapping existing particles, also across periodic boundaries), reproducibly for a given SEED.
    Example: `create_atoms 1 random 2000 4821 fill radius 0.0005 density 2500`."""
    style = "create_atoms"
    usage = "type single|random|lattice ..."

    def __call__(self, words):
        sim = self.sim
        a = self.args(words)
        a.need(2)
        sim.domain.require_box("create_atoms")
        type_ = a.int(0, "type", positive=True)
        if type_ > sim.atom.ntypes:
            raise a.error(f"type {type_} exceeds the number of types {sim.atom.ntypes}")
        how = a[1]
        if how == "single":
            a.need(5)
            kw = _radius_words(a, 5)
            rng = np.random.default_rng(_seed(a, kw))
            x = np.array([a.floats(2, 3, "position")])
            radius = self.sizes(a, kw, 1, rng)
        elif how == "random":
            a.need(5)
            n = a.int(2, "N", nonneg=True)
            if n > MAX_CREATE:
                raise a.error(f"N = {a[2]} particles is more than dem can create at once ({MAX_CREATE:.0e})")
            seed = a.int(3, "seed", positive=True)
            region = find_region(sim, a[4])
            kw = _radius_words(a, 5)
            if "seed" in kw:        # it would be ignored: SEED above drives positions and orientations
                raise a.error("random takes its seed as SEED (create_atoms T random N SEED REGION), "
                              "not as a 'seed' keyword")
            rng = np.random.default_rng(seed)
            radius = self.sizes(a, kw, n, rng)
            attempts = a.to_int(kw["attempts"][0], "attempts") if "attempts" in kw else 1000
            if attempts < 1:
                raise a.error("attempts must be >= 1")
            self.check_fits(a, kw, region, radius)
            x = self.random_fill(region, radius, rng, attempts)
        elif how == "lattice":
            a.need(4)
            region = find_region(sim, a[2])
            kind = a[3]
            spacing = a.float(4, "spacing", positive=True)
            kw = _radius_words(a, 5)
            x = self.lattice(region, kind, spacing)
            rng = np.random.default_rng(_seed(a, kw))
            radius = self.sizes(a, kw, len(x), rng)
            if np.any(2 * radius > spacing * (1.0 if kind == "sc" else 0.866 if kind == "bcc" else 0.7071) + 1e-12):
                raise a.error("particles of this radius overlap on this lattice")
        else:
            raise a.error(f"unknown create_atoms style '{how}' (single, random or lattice)")
        density = a.to_float(kw["density"][0], "density") if "density" in kw else 1.0
        if density <= 0:
            raise a.error("density must be > 0")
        outside = ~sim.domain.inside(x)
        if outside.any():
            raise a.error(f"{int(outside.sum())} particle(s) would lie outside the box")
        v = np.array([a.to_float(w, "v") for w in kw["v"]]) if "v" in kw else None
        omega = np.array([a.to_float(w, "omega") for w in kw["omega"]]) if "omega" in kw else None
        # every rank made the same particles (ids in creation order); each keeps those in its sub-box
        atom = sim.atom
        tags = np.arange(atom.max_tag + 1, atom.max_tag + 1 + len(x), dtype=np.int64)
        radius = np.broadcast_to(radius, (len(x),))
        quat = self.orientations(a, kw, len(x), rng)
        mine = sim.comm.owned_mask(x)
        s = atom.add(x[mine], radius[mine], sphere_mass(radius[mine], density), type_, v=v, omega=omega,
                     tags=tags[mine])
        if "shape" in kw:
            p = shape_command.properties(sim, kw["shape"][0], radius=radius[mine], density=density)
            for name in ("rmass", "inertia", "shape"):
                atom.data[name][s] = p[name]
        if quat is not None:
            atom.data["quat"][s] = quat[mine]
        atom.max_tag = max(atom.max_tag, int(tags[-1]) if len(tags) else 0)
        atom.natoms += len(x)
        sim.neighbor.invalidate()
        sim.print(f"Created {len(x)} particles")

    def sizes(self, a, kw, n, rng):
        """Bounding radii: `radius ...` for spheres; for a shape `scale ...` (default 1) times its bounding
        radius, or `radius ...` directly."""
        if "shape" not in kw:
            if "scale" in kw:
                raise a.error("'scale' needs 'shape NAME' (spheres: radius)")
            return radius_spec(a, kw, n, rng)
        idx = shape_command.shape_index(self.sim, kw["shape"][0])
        if "radius" in kw:
            if "scale" in kw:
                raise a.error("give either 'scale' or 'radius' for shaped particles")
            return radius_spec(a, kw, n, rng)
        if "scale" not in kw:
            return np.full(n, float(self.sim.shapes.radius[idx]))
        return radius_spec(a, {"radius": kw["scale"]}, n, rng) * self.sim.shapes.radius[idx]

    def orientations(self, a, kw, n, rng):
        q = kw.get("quat")
        if q is None:
            return None
        if q == ["random"]:
            return shape_command.random_quaternions(rng, n)
        q = np.array([a.to_float(w, "quat") for w in q])
        if not np.linalg.norm(q) > 0:
            raise a.error("quat must not be zero")
        return np.broadcast_to(q / np.linalg.norm(q), (n, 4))

    def existing(self):
        """Positions and radii of every particle already present (all ranks), ordered by id."""
        atom = self.sim.atom
        n = atom.nlocal
        comm = self.sim.comm
        tags, x = comm.allgather_rows(atom.data["tag"][:n], atom.data["x"][:n])
        _, r = comm.allgather_rows(atom.data["tag"][:n], atom.data["radius"][:n])
        order = np.argsort(tags, kind="stable")
        return x[order], r[order]

    @staticmethod
    def check_fits(a, kw, region, radius):
        """A sphere of the largest radius fits inside the region, or an error that gives the radius (the
        default 0.5 m when none was given: `set ... diameter` afterwards comes too late)."""
        if not len(radius):
            return
        rmax = float(np.max(radius))
        lo, hi = region.extent(rmax)
        if np.all(hi > lo):
            return
        if "radius" not in kw and "shape" not in kw:
            raise DemError(f"create_atoms: region {region.id} is too small for particles of the default radius "
                           f"{rmax:g} m (no 'radius' keyword given)",
                           hint="give the size on create_atoms, e.g. 'create_atoms 1 random 2000 12345 fill "
                                "radius 0.001': particles are placed at their size, so 'set type 1 diameter "
                                "...' afterwards is too late")
        raise DemError(f"create_atoms: region {region.id} is too small for particles of radius {rmax:g} m",
                       hint="a smaller radius (or scale), or a larger region")

    def random_fill(self, region, radius, rng, attempts):
        """Random sequential addition: each sphere (largest first) is tried at fresh random points until
        it overlaps nothing, periodic images included; the result depends only on the seed."""
        domain = self.sim.domain
        old_x, old_r = self.existing()
        n = len(radius)
        order = np.argsort(-radius, kind="stable")
        rmax = max(float(radius.max()) if n else 0.0, float(old_r.max()) if len(old_r) else 0.0)
        per, lo, prd = domain.periodic, domain.lo, domain.prd
        ncell = np.maximum(np.floor(prd / (2.0 * rmax)).astype(np.int64), 1) if rmax > 0 else np.ones(3, int)
        size = np.where(per, prd / ncell, 2.0 * rmax)     # periodic cells tile the box exactly
        grid = {}
        xs, rs = list(old_x), list(old_r)

        def cell(p):
            c = np.floor((p - lo) / size).astype(np.int64)
            return np.where(per, np.mod(c, ncell), c)

        for k, p in enumerate(old_x):
            grid.setdefault(tuple(cell(p)), []).append(k)
        offsets = [np.array(o) for o in np.ndindex(3, 3, 3)]

        def clashes(p, r):
            c = cell(p)
            for o in offsets:
                cc = c + o - 1
                cc = np.where(per, np.mod(cc, ncell), cc)
                for q in grid.get(tuple(cc), ()):
                    d = _min_image((p - xs[q])[None, :], domain)[0]
                    if d @ d < (r + rs[q]) ** 2:
                        return True
            return False

        out = np.zeros((n, 3))
        for count, idx in enumerate(order):
            r = radius[idx]
            for trial in range(attempts):
                if trial % 32 == 0:
                    cands = region.random_points(rng, 32, margin=r)
                p = cands[trial % 32]
                if not clashes(p, r):
                    break
            else:
                raise DemError(f"create_atoms random: placed only {count} of {n} particles without overlap "
                               f"in region {region.id} after {attempts} tries for the next one (too full: "
                               f"use a larger region or fewer particles)")
            out[idx] = p
            grid.setdefault(tuple(cell(p)), []).append(len(xs))
            xs.append(p)
            rs.append(r)
        return out

    def lattice(self, region, kind, a):
        basis = {"sc": [[0, 0, 0]], "bcc": [[0, 0, 0], [0.5, 0.5, 0.5]],
                 "fcc": [[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]]}
        if kind not in basis:
            raise DemError(f"unknown lattice '{kind}' (sc, bcc or fcc)")
        lo, hi = region.bbox()
        lo = np.maximum(lo, self.sim.domain.lo)
        hi = np.minimum(hi, self.sim.domain.hi)
        i0 = np.floor((lo - self.sim.domain.lo) / a).astype(int)
        i1 = np.ceil((hi - self.sim.domain.lo) / a).astype(int)
        count = int(np.prod(np.maximum(i1 - i0 + 1, 0))) * len(basis[kind])
        if count > MAX_CREATE:
            raise DemError(f"create_atoms lattice: spacing {a:g} gives {count:.3g} lattice sites in region "
                           f"{region.id}, more than dem can create at once ({MAX_CREATE:.0e})")
        grid = np.stack(np.meshgrid(*[np.arange(i0[d], i1[d] + 1) for d in range(3)], indexing="ij"), -1)
        grid = grid.reshape(-1, 3)
        pts = [(grid + np.array(b) + 0.5) * a + self.sim.domain.lo for b in basis[kind]]
        x = np.vstack(pts)
        keep = region.inside(x) & self.sim.domain.inside(x)
        x = x[keep]
        order = np.lexsort((x[:, 0], x[:, 1], x[:, 2]))
        return x[order]


class SetCommand(Command):
    """set atom ID|type T|group G|region R keyword values ...

    Keywords (applied in order): `v VX VY VZ`, `vx V`, `vy V`, `vz V`, `omega WX WY WZ`, `x X`, `y Y`,
    `z Z`, `radius R` and `diameter D` (mass follows at constant density), `density RHO`, `mass M`,
    `type T`, `quat W X Y Z` | `quat random` (orientation; random: uniform, reproducible for a given
    `seed N`, default 1), `shape NAME` (the shape of the `shape` command at `scale S`, default 1; the
    density is kept), `scale S` (rescale shaped particles). For a shaped particle `radius`/`diameter`
    is its bounding radius/diameter (the body is scaled to it). Example: `set group top v 0 0 -1`."""
    style = "set"
    usage = "atom|type|group|region ID keyword values ..."

    COUNTS = {"v": 3, "vx": 1, "vy": 1, "vz": 1, "omega": 3, "x": 1, "y": 1, "z": 1, "radius": 1,
              "diameter": 1, "density": 1, "mass": 1, "type": 1, "quat": 4, "shape": 1, "scale": 1, "seed": 1}

    def __call__(self, words):
        from .args import parse_types
        sim = self.sim
        a = self.args(words)
        a.need(4)
        atom = sim.atom
        n = atom.nlocal
        what, ident = a[0], a[1]
        if what == "atom":
            sel = np.zeros(n, bool)
            for w in ident.split(","):
                lo, _, hi = w.partition(":")
                lo = a.to_int(lo, "id")
                hi = a.to_int(hi, "id") if hi else lo
                sel |= (atom.data["tag"][:n] >= lo) & (atom.data["tag"][:n] <= hi)
        elif what == "type":
            sel = np.isin(atom.data["type"][:n], parse_types(ident, atom.ntypes))
        elif what == "group":
            sel = sim.groups.members(ident)
        elif what == "region":
            sel = find_region(sim, ident).inside(atom.data["x"][:n])
        else:
            raise a.error(f"unknown set target '{what}' (atom, type, group or region)")
        words = list(a.words)
        for k in range(2, len(words) - 1):      # `quat random` takes one value
            if words[k] == "quat" and words[k + 1] == "random":
                words[k + 1:k + 2] = ["random"] * 4
        a.words = words
        kw = a.keywords(2, self.COUNTS)
        d = atom.data
        rows = np.flatnonzero(sel)
        for key, vals in kw.items():
            if key == "shape":
                scale = a.to_float(kw["scale"][0], "scale") if "scale" in kw else 1.0
                if scale <= 0:
                    raise a.error("scale must be > 0")
                shape_command.shape_index(sim, vals[0])     # the same error on every rank
                shape_command.assign(sim, rows, vals[0], scale)
                continue
            if key == "scale":
                if "shape" not in kw:
                    scale = a.to_float(vals[0], "scale")
                    if scale <= 0:
                        raise a.error("scale must be > 0")
                    shape_command.assign(sim, rows, None, scale)
                continue
            if key == "seed":
                continue
            if key == "quat" and vals[0] == "random":
                # the same stream on every rank: draw for all particles by id, keep the selected
                rng = np.random.default_rng(a.to_int(kw["seed"][0], "seed") if "seed" in kw else 1)
                tags = d["tag"][:n]
                q = shape_command.random_quaternions(rng, int(sim.atom.max_tag) + 1)
                d["quat"][:n][sel] = q[tags[sel]]
                d["angmom"][:n][sel] = 0.0
                continue
            f = [a.to_float(v, key) for v in vals]
            if key == "v":
                d["v"][:n][sel] = f
            elif key in ("vx", "vy", "vz"):
                d["v"][:n][sel, "xyz".index(key[1])] = f[0]
            elif key == "omega":
                d["omega"][:n][sel] = f
                d["angmom"][:n][sel] = 0.0   # recomputed by the integrator from omega
            elif key in ("x", "y", "z"):
                d["x"][:n][sel, "xyz".index(key)] = f[0]
                sim.neighbor.invalidate()
            elif key in ("radius", "diameter"):
                r = f[0] if key == "radius" else 0.5 * f[0]
                if r <= 0:
                    raise a.error(f"{key} must be > 0")
                shaped = rows[d["shape"][rows] >= 0]
                if len(shaped):
                    shape_command.assign(sim, shaped, None, r / sim.shapes.radius[d["shape"][shaped]])
                spheres = rows[d["shape"][rows] < 0]
                rho = d["rmass"][spheres] / sphere_mass(d["radius"][spheres], 1.0)
                d["radius"][spheres] = r
                d["rmass"][spheres] = sphere_mass(r, 1.0) * rho
                d["inertia"][spheres] = (0.4 * d["rmass"][spheres] * r * r)[:, None]
                sim.neighbor.invalidate()
            elif key == "density":
                if f[0] <= 0:
                    raise a.error("density must be > 0")
                scale = f[0] / shape_command.particle_density(sim, rows)
                d["rmass"][:n][sel] *= scale
                d["inertia"][:n][sel] *= scale[:, None]
            elif key == "mass":
                if f[0] <= 0:
                    raise a.error("mass must be > 0")
                scale = f[0] / d["rmass"][:n][sel]
                d["rmass"][:n][sel] = f[0]
                d["inertia"][:n][sel] *= scale[:, None]
            elif key == "type":
                t = a.to_int(vals[0], "type")
                if not 1 <= t <= atom.ntypes:
                    raise a.error(f"type {t} out of range 1..{atom.ntypes}")
                d["type"][:n][sel] = t
            elif key == "quat":
                q = np.array(f)
                if not np.linalg.norm(q) > 0:
                    raise a.error("quat must not be zero")
                d["quat"][:n][sel] = q / np.linalg.norm(q)
                d["angmom"][:n][sel] = 0.0   # recomputed by the integrator from omega
        sim.print(f"Setting properties of {int(sim.comm.sum(int(sel.sum())))} particles")
