"""Helpers shared by the analysis styles (contact/types, stress, rdf, nematic, ave/profile): the particles
of a group (optionally with their centre in a region), their true volumes, and stress from the tally."""
import numpy as np

from dem.commands import find_region
from dem.errors import DemError

AXES = {"x": 0, "y": 1, "z": 2}
STRESS_NAMES = ("sxx", "syy", "szz", "sxy", "sxz", "syz")
SYM6 = ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))     # the index pairs of STRESS_NAMES


def axis_index(word, what):
    if word not in AXES:
        raise DemError(f"{what}: axis must be x, y or z, got '{word}'")
    return AXES[word]


def region_of(sim, rid, what):
    """A region for selecting particle centres, with its volume inside the box."""
    reg = find_region(sim, rid)
    if not reg.side_in:
        raise DemError(f"{what}: region {rid} must be 'side in'")
    return reg


def region_volume(sim, reg, what):
    """Volume of a region inside the box: a block is clipped to the box, a cylinder or sphere must lie in
    it (its own volume)."""
    dom = sim.domain
    if reg.style == "block":
        lo, hi = reg.bbox()
        ext = np.minimum(hi, dom.hi) - np.maximum(lo, dom.lo)
        if np.any(ext <= 0):
            raise DemError(f"{what}: region {reg.id} lies outside the box")
        return float(np.prod(ext))
    if reg.style in ("cylinder", "sphere"):
        return float(reg.volume())
    raise DemError(f"{what}: cannot tell the volume of region style {reg.style} (block, cylinder, sphere; or "
                   f"give `volume V`)")


def selection(sim, groupbit, region=None):
    """Mask of the owned particles in the group (and with their centre in `region`)."""
    atom = sim.atom
    sel = (atom.data["mask"][:atom.nlocal] & groupbit) != 0
    if region is not None and sel.any():
        sel &= region.inside(atom.data["x"][:atom.nlocal])
    return sel


def volumes(sim, shape, radius):
    """True volume of each particle: a sphere's, or its shape row's volume scaled by (r / row radius)^3."""
    vol = 4.0 / 3.0 * np.pi * radius ** 3
    shaped = shape >= 0
    if shaped.any():
        tab = sim.shapes
        s = shape[shaped]
        vol[shaped] = tab.volume[s] * (radius[shaped] / tab.radius[s]) ** 3
    return vol


def contact_moment(sim, sel, who):
    """Sum over the selected particles of -sym(F (x) (P - G)) (compression positive), 3x3, this rank."""
    t = sim.tally.get("stress", who)[sel].reshape(-1, 3, 3).sum(axis=0)
    return -0.5 * (t + t.T)


def mass_moments(m, v):
    """[sum m v_i v_j (9), sum m v (3), sum m]: what the kinetic stress needs, summable over ranks."""
    return np.concatenate([np.einsum("n,ni,nj->ij", m, v, v).reshape(9), m @ v if len(m) else np.zeros(3),
                           [float(m.sum())]])


def kinetic_moment(mom):
    """sum m v' (x) v', v' about the mass-weighted mean velocity, from mass_moments (summed)."""
    mvv, mv, msum = mom[:9].reshape(3, 3), mom[9:12], mom[12]
    return mvv - np.outer(mv, mv) / msum if msum > 0 else np.zeros((3, 3))


def voigt(t):
    """The six components sxx syy szz sxy sxz syz of a symmetric tensor (or of a stack of them)."""
    t = np.asarray(t)
    return np.stack([t[..., a, b] for a, b in SYM6], axis=-1)
