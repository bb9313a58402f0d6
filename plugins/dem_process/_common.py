"""Helpers shared by the drum computes: the drum fix a compute refers to, and the vertical."""
import numpy as np

from dem.errors import DemError


def find_drum(sim, fid, what):
    fix = sim.modify.find(fid)
    if fix is None:
        raise DemError(f"{what}: no fix with ID '{fid}' (a fix wall/drum)")
    if not all(hasattr(fix, k) for k in ("axis", "centre", "radius", "omega", "omega_target")):
        raise DemError(f"{what}: fix {fid} is a {fix.style}, not a rotating drum (fix wall/drum)")
    return fix


def up_direction(sim):
    """Unit vector opposite to gravity (the fixes' body acceleration, Modify.acceleration), +z without one."""
    g = sim.modify.acceleration()
    return -g / np.linalg.norm(g) if g is not None else np.array([0.0, 0.0, 1.0])


def cross_section_basis(sim, drum):
    """(e_axis, e_h, e_up): e_up is the vertical projected on the drum's cross-section, e_h = e_up x e_axis
    horizontal in it (seen along +axis, e_h points to the right when e_up points up)."""
    e = np.zeros(3)
    e[drum.axis] = 1.0
    up = up_direction(sim)
    up = up - np.dot(up, e) * e
    if np.linalg.norm(up) < 1e-12:
        raise DemError("drum analysis: gravity is parallel to the drum axis")
    up /= np.linalg.norm(up)
    return e, np.cross(up, e), up
