"""Structure of a packing: the pair correlation g(r) (compute rdf) and the nematic order Q00^2 (compute
nematic), Descantes 2022 Fig. 9a and sec. 3.1."""
import numpy as np
import pytest

import dem
from dem_process.compute_rdf import pair_distances, rdf

B = 0.01


def site(i, j, k, b):
    """The lattice site (i, j, k) + 1/2 at spacing b, as create_atoms words."""
    return " ".join(repr(float((c + 0.5) * b)) for c in (i, j, k))


def _box(text, bc="p p p", size=8):
    sim = dem.Simulation(screen=False)
    sim.commands(f"""units si
boundary {bc}
region box block 0 {size * B} 0 {size * B} 0 {size * B}
create_box 1 box
""" + text)
    return sim


def test_rdf_simple_cubic_lattice(tmp_path):
    """8^3 spheres on a periodic simple cubic lattice of spacing B: g(r) is zero but in the bins of the
    shells r = B sqrt(k) (6, 12, 8, 6 neighbours for k = 1, 2, 3, 4); the first peak is the bin of r = B,
    with exactly N 6 / 2 pairs. Bins of 0.0525 B put every shell radius at least 0.01 dr from a bin edge, so each
    bin's g is its exact pair count over the ideal-gas count (bound 1e-12). Written through fix ave/vector:
    rows of (r, g)."""
    lines = [f"create_atoms 1 single {site(i, j, k, B)} radius {0.3 * B} density 1000"
             for i in range(8) for j in range(8) for k in range(8)]
    path = tmp_path / "g.dat"
    sim = _box("\n".join(lines) + f"""
compute g all rdf 40 {2.1 * B}
fix gr all ave/vector 1 1 {path} c_g
timestep 1e-5
""")
    sim.run(1)
    g = sim.computes["g"].vector()
    dr = 2.1 * B / 40
    edges = np.arange(41) * dr
    shells = {1: 6, 2: 12, 3: 8, 4: 6}
    n = 512
    expect = np.zeros(40)
    for k, z in shells.items():
        b = int(np.floor(np.sqrt(k) * B / dr))
        expect[b] += 0.5 * n * z
    ideal = 0.5 * n * (n - 1) * 4 / 3 * np.pi * (edges[1:] ** 3 - edges[:-1] ** 3) / (8 * B) ** 3
    assert g == pytest.approx(expect / ideal, rel=1e-12)
    assert int(np.flatnonzero(g)[0]) == int(np.floor(B / dr)) and g[int(np.floor(B / dr))] > 1
    data = np.loadtxt(path)
    assert data.shape == (40, 5)
    # the file has 10 significant digits
    assert data[:, 3] == pytest.approx((edges[1:] + edges[:-1]) / 2, rel=1e-9)
    assert data[:, 4] == pytest.approx(g, rel=1e-9)


def test_rdf_uniform_random_gas():
    """N = 3000 uniform random points in a periodic unit box: g = 1 within the Poisson error of each bin,
    1/sqrt(expected pairs) (bins from r = 0.05 hold >= 1900 pairs: 2.3 %); every bin within 4 sigma and the
    mean of (g - 1) / sigma within 4 / sqrt(nbin) of 0. Distances checked against brute force."""
    rng = np.random.default_rng(7)
    x = rng.random((3000, 3))
    lo, prd, per = np.zeros(3), np.ones(3), np.ones(3, bool)
    d = pair_distances(x, lo, prd, per, 0.3)
    sub = x[:300]
    dd = sub[:, None] - sub[None]
    dd -= np.rint(dd)
    brute = np.sqrt((dd ** 2).sum(-1))[np.triu_indices(300, 1)]
    assert np.sort(pair_distances(sub, lo, prd, per, 0.3)) == pytest.approx(np.sort(brute[brute < 0.3]), abs=1e-14)
    r, g, counts = rdf(d, 3000, 1.0, 25, 0.3)
    keep = r > 0.05
    ideal = counts[keep] / g[keep]
    z = (g[keep] - 1.0) * np.sqrt(ideal)
    assert np.all(np.abs(z) < 4.0), z
    assert abs(z.mean()) < 4.0 / np.sqrt(len(z))


def test_nematic_aligned_and_random(tmp_path):
    """Aligned pinacoid-like boxes (2 x 1 x 0.5): Q00^2 = 1 for each principal axis, the director along the
    long axis (x, smallest moment). 1000 random orientations: the largest eigenvalue of Q is ~ the noise of
    a 3x3 traceless average of N terms of variance 1/5: each element's standard deviation sqrt(1/5N) =
    0.014; bound 0.08 (5.6 sigma for each axis), against 1 for order."""
    lines = [f"create_atoms 1 single {site(i, j, k, 0.04)} shape b density 1000"
             for i in range(10) for j in range(10) for k in range(10)]
    text = "shape b box 0.02 0.01 0.005\n" + "\n".join(lines) + "\ncompute q all nematic\n"
    sim = _box(text, size=40)
    v = sim.computes["q"].vector()
    assert v[:3] == pytest.approx([1.0, 1.0, 1.0], abs=1e-12)
    assert np.abs(v[3:]) == pytest.approx([1.0, 0.0, 0.0], abs=1e-12)
    rng = np.random.default_rng(3)
    q = rng.normal(size=(1000, 4))
    sim.atom.data["quat"][:1000] = q / np.linalg.norm(q, axis=1, keepdims=True)
    v = sim.computes["q"].vector()
    assert np.all(v[:3] < 0.08), v
    assert sim.computes["q"].scalar() == v[0]
