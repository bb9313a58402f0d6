"""compute rdf"""
import numpy as np

from dem.compute import Compute
from dem.errors import DemError


def pair_distances(x, lo, prd, periodic, rmax):
    """Distances below rmax of all pairs of points x, minimum image along periodic axes (a k-d tree on a
    torus; non-periodic axes get a period longer than the spread plus rmax, so no image comes near)."""
    x = np.asarray(x, float)
    if len(x) < 2:
        return np.zeros(0)
    span = np.where(periodic, prd, x.max(axis=0) - x.min(axis=0) + 2.0 * rmax + 1.0)
    origin = np.where(periodic, lo, x.min(axis=0))
    y = np.mod(x - origin, span)
    y = np.where(y >= span, 0.0, y)            # mod can round up to the period itself
    from scipy.spatial import cKDTree      # here: scipy.spatial is 0.19 s of every start-up
    pairs = cKDTree(y, boxsize=span).query_pairs(rmax, output_type="ndarray")
    d = y[pairs[:, 0]] - y[pairs[:, 1]]
    d -= span * np.rint(d / span)
    return np.sqrt(np.einsum("ij,ij->i", d, d))


def rdf(dist, n, volume, nbin, rmax):
    """g(r) at the bin centres: pairs per shell / (the ideal-gas count n (n - 1) / 2 * shell / V)."""
    edges = np.linspace(0.0, rmax, nbin + 1)
    counts, _ = np.histogram(dist, bins=edges)
    shell = 4.0 / 3.0 * np.pi * (edges[1:] ** 3 - edges[:-1] ** 3)
    ideal = 0.5 * n * (n - 1) * shell / volume
    return 0.5 * (edges[1:] + edges[:-1]), counts / ideal if n > 1 else np.zeros(nbin), counts


class ComputeRDF(Compute):
    """compute ID group rdf NBIN RMAX

    Pair correlation function g(r) of the particle centres of the group (Descantes 2022 Fig. 9a): the
    number of pairs at distance r in [r, r + dr), over its value for an ideal gas of the same number density
    N / V, V the box volume: g -> 1 where positions are uncorrelated. NBIN bins of width RMAX / NBIN from 0;
    distances are minimum-image along periodic axes. Along a non-periodic axis shells cut by the box walls
    are not corrected: g falls below 1 at r ~ the distance to the walls (use a periodic box or read g where
    r << the box). RMAX must be under half the shortest periodic length.

    Vector: g at the NBIN bin centres r_k = (k - 1/2) RMAX / NBIN (`c_ID[k]`); the bin centres are the
    fix ave/vector `coords`. Cost: a k-d tree over every particle of the group (gathered on every rank),
    O(N) for fixed RMAX: evaluate it at output only. Example: `compute g all rdf 100 0.01` then
    `fix gr all ave/vector 1000 10000 rdf.dat c_g`."""

    style = "rdf"
    usage = "NBIN RMAX"
    has_scalar = False

    def __init__(self, sim, cid, group, args):
        super().__init__(sim, cid, group, args)
        a = self.parser()
        a.exactly(2)
        self.nbin = a.to_int(a[0], "NBIN")
        self.rmax = a.to_float(a[1], "RMAX")
        if self.nbin < 1 or self.rmax <= 0:
            raise a.error("NBIN must be >= 1 and RMAX > 0")
        self.size_vector = self.nbin
        self.coords = 0.5 * (np.arange(self.nbin) + 0.5) * 2.0 * self.rmax / self.nbin
        self.vector_names = tuple(f"g{k + 1}" for k in range(self.nbin))

    def init(self):
        dom = self.sim.domain
        dom.require_box(f"compute {self.id} rdf")
        per = np.asarray(dom.periodic, bool)
        if per.any() and self.rmax >= 0.5 * float(np.min(np.asarray(dom.prd)[per])):
            raise DemError(f"compute {self.id} rdf: RMAX {self.rmax:g} must be under half the shortest periodic "
                           f"box length {float(np.min(np.asarray(dom.prd)[per])):g}")

    def compute_vector(self):
        sim = self.sim
        atom, dom, comm = sim.atom, sim.domain, sim.comm
        sel = self.group_mask()
        tags = atom.data["tag"][:atom.nlocal][sel]
        x = comm.allgather_rows(tags, atom.data["x"][:atom.nlocal][sel])[1]
        dist = pair_distances(x, np.asarray(dom.lo), np.asarray(dom.prd), np.asarray(dom.periodic, bool),
                              self.rmax)
        return rdf(dist, len(x), float(np.prod(dom.prd)), self.nbin, self.rmax)[1]
