"""compute contact/types"""
import numpy as np

from dem.compute import Compute

from .analysis import region_of, selection

NAMES = ("z_s", "z_d", "z_t", "z_iso", "z_tot", "share_s", "share_d", "share_t", "particles", "contacts")


def type_ends(counts):
    """Per particle (n, 3): single-point, edge/face and face/face contacts from the tally rows (n, 5):
    vertex/face, edge/edge and contacts with a sphere are single points."""
    return np.stack([counts[:, 0] + counts[:, 1] + counts[:, 4], counts[:, 2], counts[:, 3]], axis=1)


def coordination(ends, n):
    """[z_s, z_d, z_t, z_iso, z_tot, shares s d t] from the contact ends by kind and the particle count."""
    zs, zd, zt = ends / n if n else np.zeros(3)
    tot = zs + zd + zt
    shares = np.array([zs, zd, zt]) / tot if tot else np.zeros(3)
    return np.array([zs, zd, zt, zs + 2 * zd + 3 * zt, tot, *shares])


class ComputeContactTypes(Compute):
    """compute ID group contact/types [region REGION-ID]

    Coordination number split by contact type (Descantes 2022 Fig. 9b), from the pair contacts of the last
    force evaluation of `pair_style polyhedron/multipoint`: z_s single-point contacts (vertex/face,
    edge/edge, and a sphere touching anything), z_d edge/face, z_t face/face, each the mean number per
    particle of the group; z_iso = z_s + 2 z_d + 3 z_t (the constraints the contacts impose, 1, 2 and 3 per
    contact: Descantes' isostaticity count), z_tot = z_s + z_d + z_t, and the share of each type among the
    contacts. With `region`, only particles whose centre is inside the region count, with all their contacts
    (partners outside included): the bulk value away from walls and free surface (the paper: between 3 and
    6 d_eq above the floor). Wall contacts are not counted.

    Vector: [z_s, z_d, z_t, z_iso, z_tot, share_s, share_d, share_t, particles, contacts], `contacts` the
    contact ends of the selected particles (a contact between two selected particles counts twice, so
    z_tot = contacts / particles); scalar: z_tot. The pair kernel counts contacts per particle by type only
    while a compute like this one exists (dem/tally.py); evaluate it in a run (or after `run 0`).

    Example: `region bulk block INF INF INF INF 0.03 0.06` then `compute zt all contact/types region bulk`
    and `thermo_style custom step c_zt[1] c_zt[2] c_zt[3] c_zt[4]`."""

    style = "contact/types"
    usage = "[region REGION-ID]"
    size_vector = len(NAMES)
    vector_names = NAMES
    tallies = ("types",)

    def __init__(self, sim, cid, group, args):
        super().__init__(sim, cid, group, args)
        a = self.parser()
        kw = a.keywords(0, {"region": 1})
        self.region = region_of(sim, kw["region"][0], f"compute {cid} contact/types") if "region" in kw else None

    def compute_vector(self):
        sim = self.sim
        sel = selection(sim, self.groupbit, self.region)
        counts = sim.tally.get("types", f"compute {self.id} contact/types")[sel]
        ends = sim.comm.sum_values(type_ends(counts).sum(axis=0).astype(float))
        n = sim.comm.sum(int(sel.sum()))
        return np.concatenate([coordination(ends, n), [float(n), float(ends.sum())]])

    def compute_scalar(self):
        return self.vector()[4]
