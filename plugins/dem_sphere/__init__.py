"""Plugin: pair style `sphere` (spheres, Grains3D contact law)."""
from dem.hookspecs import hookimpl

from .pair_sphere import PairSphere


@hookimpl
def dem_styles():
    return [PairSphere]
