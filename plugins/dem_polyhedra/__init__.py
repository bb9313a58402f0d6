"""Plugin: pair style `polyhedron/multipoint` (sharp polyhedra with multipoint face/edge contacts,
Descantes 2022, mixed with plain spheres)."""
from dem.hookspecs import hookimpl

from .pair_polyhedron import PairPolyhedronMultipoint


@hookimpl
def dem_styles():
    return [PairPolyhedronMultipoint]
