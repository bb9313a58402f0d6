"""Per-bin sums of one sample and the profiles made from time-averaged sums (fix ave/profile): the
arithmetic, apart from the fix's parsing and file."""
import numpy as np

from .analysis import STRESS_NAMES, SYM6, volumes
from .compute_contact_types import type_ends

# accumulator columns: name -> width
SUMS = {"n": 1, "v": 3, "v2": 3, "w": 3, "d": 1, "rho": 1, "stress": 6, "ends": 3, "phi": 1, "samples": 1,
        "vc": 2, "mvv": 6, "mv": 3, "m": 1}      # the last three: one sample's momenta for its kinetic stress
VALUES = ("count", "density", "vx", "vy", "vz", "wx", "wy", "wz", "vr", "vt", "Txx", "Tyy", "Tzz", "T", "phi",
          *STRESS_NAMES, "p", "I", "zs", "zd", "zt", "ztot", "ziso")
RADIAL_ONLY = {"vr", "vt"}          # the velocity in cylindrical components: radial bins only
AXIAL_ONLY = {"phi", "I"}           # slab geometry (grid passes per slab, the gradient along the axis)
NEEDS_STRESS = set(STRESS_NAMES) | {"p", "I"}
NEEDS_TYPES = {"zs", "zd", "zt", "ztot", "ziso"}


def layout():
    out, col = {}, 0
    for name, width in SUMS.items():
        out[name] = slice(col, col + width)
        col += width
    return out, col


LAYOUT, WIDTH = layout()


class Cylinder:
    """Radial bins: the distance of each centre from the line along `axis` through `centre` (3 values; the
    one along the axis is not used), and the velocity in cylindrical components."""

    def __init__(self, axis, centre):
        self.axis = axis
        self.centre = np.asarray(centre, float)
        self.b, self.c = [d for d in range(3) if d != axis]

    def offsets(self, x):
        return x[:, self.b] - self.centre[self.b], x[:, self.c] - self.centre[self.c]

    def coord(self, x):
        db, dc = self.offsets(x)
        return np.hypot(db, dc)

    def radial_tangential(self, x, v):
        """(v_r, v_t) per particle: v_t along e_axis x e_r (counter-clockwise about +axis); 0 on the axis."""
        db, dc = self.offsets(x)
        r = np.hypot(db, dc)
        safe = np.where(r > 0, r, 1.0)
        er = np.zeros((len(r), 3))
        er[:, self.b], er[:, self.c] = db / safe, dc / safe
        et = np.cross(np.eye(3)[self.axis], er)
        return np.einsum("ij,ij->i", er, v), np.einsum("ij,ij->i", et, v)


def bin_index(coord, lo, width, nbin):
    """Bin of each coordinate, -1 outside [lo, lo + nbin width)."""
    b = np.floor((coord - lo) / width).astype(np.int64)
    b[(b < 0) | (b >= nbin)] = -1
    return b


def _add(acc, key, b, values, nbin):
    sl = LAYOUT[key]
    values = np.asarray(values, float).reshape(len(b), -1)
    for c in range(values.shape[1]):
        acc[:, sl.start + c] += np.bincount(b, weights=values[:, c], minlength=nbin)


def sample_sums(sim, sel, axis, lo, width, nbin, bin_volume, tally_stress=None, tally_types=None,
                kinetic=False, cylinder=None):
    """This rank's (nbin, WIDTH) sums of one sample over the selected owned particles (phi and samples
    are left to the caller): counts, velocity moments, spins, d_eq and density sums, the bin's contact
    stress (compression positive, per bin volume: a number, or one per bin), with `kinetic` the momenta
    for add_kinetic, and the contact ends by kind. Bins along `axis`, or with `cylinder` (a Cylinder) by
    the distance from its axis, adding the radial and tangential velocity sums."""
    atom = sim.atom
    n = atom.nlocal
    acc = np.zeros((nbin, WIDTH))
    x = atom.data["x"][:n][sel]
    b = bin_index(x[:, axis] if cylinder is None else cylinder.coord(x), lo, width, nbin)
    keep = b >= 0
    b = b[keep]
    if not len(b):
        return acc
    pick = np.flatnonzero(sel)[keep]
    volume_of = np.broadcast_to(np.asarray(bin_volume, float), (nbin,))[b][:, None]    # each particle's bin
    v = atom.data["v"][pick]
    if cylinder is not None:
        _add(acc, "vc", b, np.column_stack(cylinder.radial_tangential(x[keep], v)), nbin)
    m = atom.data["rmass"][pick]
    vol = volumes(sim, atom.data["shape"][pick], atom.data["radius"][pick])
    _add(acc, "n", b, np.ones(len(b)), nbin)
    _add(acc, "v", b, v, nbin)
    _add(acc, "v2", b, v * v, nbin)
    _add(acc, "w", b, atom.data["omega"][pick], nbin)
    _add(acc, "d", b, np.cbrt(6.0 * vol / np.pi), nbin)
    _add(acc, "rho", b, m / vol, nbin)
    if tally_stress is not None:
        t = tally_stress[pick].reshape(-1, 3, 3)
        t = -0.5 * (t + np.transpose(t, (0, 2, 1)))
        s = np.stack([t[:, a, c] for a, c in SYM6], axis=1)
        _add(acc, "stress", b, s / volume_of, nbin)
    if kinetic:
        _add(acc, "mvv", b, m[:, None] * np.stack([v[:, a] * v[:, c] for a, c in SYM6], axis=1), nbin)
        _add(acc, "mv", b, m[:, None] * v, nbin)
        _add(acc, "m", b, m, nbin)
    if tally_types is not None:
        _add(acc, "ends", b, type_ends(tally_types[pick]), nbin)
    return acc


def add_kinetic(acc, bin_volume):
    """Adds one sample's kinetic stress sum m v' v' / V_bin (v' about the bin's mean velocity in the sample,
    from the momenta summed over ranks) to its stress columns, and clears the momenta."""
    mvv, mv, m = acc[:, LAYOUT["mvv"]], acc[:, LAYOUT["mv"]], acc[:, LAYOUT["m"]][:, 0]
    safe = np.where(m > 0, m, 1.0)
    kin = mvv - np.stack([mv[:, a] * mv[:, c] for a, c in SYM6], axis=1) / safe[:, None]
    acc[:, LAYOUT["stress"]] += np.where(m[:, None] > 0, kin, 0.0) / np.reshape(bin_volume, (-1, 1))
    for key in ("mvv", "mv", "m"):
        acc[:, LAYOUT[key]] = 0.0


def inertial_number(centres, vmean, axis, pressure, d, rho):
    """I = gamma_dot d / sqrt(P / rho) per bin: gamma_dot the norm of the derivative along `axis` of the mean
    velocity's two other components (central differences), P the normal stress along the axis, d and rho
    the mean equivalent diameter and particle density of the bin; NaN where P <= 0 or a bin is empty."""
    other = [c for c in range(3) if c != axis]
    if len(centres) < 2:
        return np.full(len(centres), np.nan)
    grad = np.stack([np.gradient(vmean[:, c], centres) for c in other], axis=1)
    gdot = np.sqrt((grad * grad).sum(axis=1))
    with np.errstate(invalid="ignore", divide="ignore"):
        out = gdot * d / np.sqrt(pressure / rho)
    out[~(pressure > 0)] = np.nan
    return out


def profiles(acc, centres, axis, bin_volume):
    """Value name -> profile (nbin,) from the time-summed accumulators (bin_volume: a number or one per
    bin; axis None for radial bins, which have no inertial number)."""
    ns = max(acc[0, LAYOUT["samples"]][0], 1.0)
    n = acc[:, LAYOUT["n"]][:, 0]
    with np.errstate(invalid="ignore", divide="ignore"):
        per = 1.0 / n
        v = acc[:, LAYOUT["v"]] * per[:, None]
        v2 = acc[:, LAYOUT["v2"]] * per[:, None]
        temp = v2 - v * v                    # Descantes eq. 13: <v_j^2> - <v_j>^2 over the bin and the time
        stress = acc[:, LAYOUT["stress"]] / ns
        ends = acc[:, LAYOUT["ends"]] * per[:, None]
        d = acc[:, LAYOUT["d"]][:, 0] * per
        rho = acc[:, LAYOUT["rho"]][:, 0] * per
        w = acc[:, LAYOUT["w"]] * per[:, None]
        vc = acc[:, LAYOUT["vc"]] * per[:, None]
    out = {"count": n / ns, "density": n / ns / np.asarray(bin_volume, float), "vr": vc[:, 0], "vt": vc[:, 1]}
    for c, name in enumerate("xyz"):
        out["v" + name] = v[:, c]
        out["w" + name] = w[:, c]
        out["T" + name * 2] = temp[:, c]
    out["T"] = temp.sum(axis=1)
    out["phi"] = acc[:, LAYOUT["phi"]][:, 0] / ns
    for c, name in enumerate(STRESS_NAMES):
        out[name] = stress[:, c]
    out["p"] = stress[:, :3].mean(axis=1)
    if axis is not None:
        out["I"] = inertial_number(centres, v, axis, stress[:, axis], d, rho)
    zs, zd, zt = ends[:, 0], ends[:, 1], ends[:, 2]
    out.update(zs=zs, zd=zd, zt=zt, ztot=zs + zd + zt, ziso=zs + 2 * zd + 3 * zt)
    return out
