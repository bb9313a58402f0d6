"""Plugin: pair style `glued/convex` (glued convex composites, Grains3D Part III, mixed with convex
particles and spheres)."""
from dem.hookspecs import hookimpl

from .pair_glued import PairGluedConvex


@hookimpl
def dem_styles():
    return [PairGluedConvex]
