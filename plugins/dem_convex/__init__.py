"""Plugin: pair style `convex/gjk` (convex particles of the shape table, mixed with spheres; Grains3D
crust contact by GJK, shared contact law), and compute `body` (state of a group as one rigid body)."""
from dem.hookspecs import hookimpl

from .compute_body import ComputeBody
from .pair_convex import PairConvexGJK


@hookimpl
def dem_styles():
    return [PairConvexGJK, ComputeBody]
