"""Plugin: pair style `polyhedron/multipoint` (sharp polyhedra with multipoint face/edge contacts,
Descantes 2022, mixed with plain spheres), its contact-type census `compute pair/contacts` and the dump
of its contact points `dump ... contacts`."""
from dem.hookspecs import hookimpl

from .compute_pair_contacts import ComputePairContacts
from .dump_contacts import DumpContacts
from .pair_polyhedron import PairPolyhedronMultipoint


@hookimpl
def dem_styles():
    return [PairPolyhedronMultipoint, ComputePairContacts, DumpContacts]
