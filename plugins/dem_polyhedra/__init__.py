"""Plugin: pair style `polyhedron/multipoint` (sharp polyhedra with multipoint face/edge contacts,
Descantes 2022, mixed with plain spheres) and its contact-type census `compute pair/contacts`."""
from dem.hookspecs import hookimpl

from .compute_pair_contacts import ComputePairContacts
from .pair_polyhedron import PairPolyhedronMultipoint


@hookimpl
def dem_styles():
    return [PairPolyhedronMultipoint, ComputePairContacts]
