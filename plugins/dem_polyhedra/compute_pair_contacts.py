"""compute pair/contacts: the contact-type census of pair_style polyhedron/multipoint, for thermo."""
import numpy as np

from dem.compute import Compute
from dem.errors import DemError

from .pair_polyhedron import TYPES


class ComputePairContacts(Compute):
    """compute ID all pair/contacts

    The contacts of `pair_style polyhedron/multipoint` at the last force evaluation, summed over the
    ranks. Scalar: the contacting pairs. Vector (`c_ID[1]` ... `c_ID[6]`): the pairs of each contact type,
    vertex_face, edge_edge (1 point each), edge_face (2 points), face_face (3 or more: the corners of the
    overlap polygon), sphere (a pair with a plain sphere), then the contact points (sum over the pairs of
    their points). Wall contacts are not counted (`f_WALL[contacts]`). Reads `sim.pair.contact_types`
    and `npoints`; the pair style counts over all particles, so the group must be `all`.
    Example: `compute ct all pair/contacts` then `thermo_style custom step c_ct c_ct[3] c_ct[4]`."""

    style = "pair/contacts"
    size_vector = len(TYPES) + 1
    vector_names = TYPES + ("points",)

    def __init__(self, sim, cid, group, args):
        super().__init__(sim, cid, group, args)
        self.parser().exactly(0)
        if group != "all":
            raise DemError(f"compute {cid} pair/contacts: the pair style counts contacts over all particles: "
                           "use group all")

    def init(self):
        pair = self.sim.pair
        if pair is None or not hasattr(pair, "contact_types"):
            raise DemError(f"compute {self.id} pair/contacts needs pair_style polyhedron/multipoint (the pair "
                           f"style is {getattr(pair, 'style', 'not set')})")

    def compute_scalar(self):
        return self.sim.comm.sum(self.sim.pair.ncontacts)

    def compute_vector(self):
        pair, comm = self.sim.pair, self.sim.comm
        return np.array([comm.sum(pair.contact_types[k]) for k in TYPES] + [comm.sum(pair.npoints)], dtype=float)
