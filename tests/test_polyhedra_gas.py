"""Energy of a gas of polyhedra with en = 1, mu = 0 (issue 15: "keeps its energy to 1e-4 over 1e5 steps").

The gas: 27 bodies (9 cubes of edge 2 mm, 9 regular tetrahedra of edge 3 mm, 9 isometric pinacoids
L = G = E = 2.2 mm; density 1250) on a jittered 3 x 3 x 3 lattice of pitch 5 mm in a periodic box of
15 mm (solid fraction 4 %), random orientations, velocities of rms 1 m/s (no net momentum) and spins of
rms 170 rad/s; pair_style polyhedron/multipoint, kn = 1e5, en = 1, mu = 0, no gravity. Time step: the
shortest contact time, two tetrahedra (reduced mass 2.0e-6 kg), T_c = pi sqrt(m_ij / kn) = 1.4e-5 s,
over 100 (dt = 1.4e-7 s; the overlaps stay below 1e-5 m, 0.5 % of the size). The energy (translational
+ rotational) is read every 10 steps when no pair touches (no elastic energy, no half-step mixing).

Measured by hand over 1e5 steps at T_c/100 (0.014 s, 74 collisions between contact-free samples, 16 s
on one core): relative drift -7.1e-4, above the issue's 1e-4. The cause is one collision in which the
bodies met edge to face (12 of the 6815 contact-steps were edge/face): it changed the energy by -7.2e-4
alone. The 73 collisions
with vertex/face and edge/edge contacts only (one point, the exact depth and normal: a potential force)
sum to +1.0e-5 (largest single change 3.3e-5); their error is the integrator's: for edge/edge-only
collisions the rms change per collision is 1.7e-5, 3.9e-6, 9.9e-7 at T_c/50, /100, /200 (x4 per halving
of dt). A collision through a kink of the sharp depth (the deepest vertex passing from one end of an edge
to the other, or the depth from a face axis to an edge axis) errs to first order instead: up to 1.5e-4
at T_c/100 in this gas when the slab is dropped (docs/polyhedra.md, "Without the slab"). The edge/face collision does not converge: -7.2e-4 at T_c/100, -7.4e-4 at T_c/200 (the same
collision, 2e5 steps); at T_c/50 the trajectory differs and three edge/face collisions give +9.6e-4,
-5.5e-4, -0.9e-4. That is the shared-max-overlap rule (Descantes eq. 3): both ends of an edge that lies
within the overlap slab of a face push with the deepest overlap, which is not the gradient of any
potential (tests/test_polyhedron_pair.py: 1.8e-4 for a head-on edge/face collision, independent of dt;
a grazing one with spin can lose much more: 7.2e-4 of the gas's energy is about 1e-2 of one pair's
share of it).

The tests run the first 2e4 steps (6 s; they contain the edge/face collision, at step 17000):
* single-point collisions keep the energy: each interval between contact-free moments with only
  vertex/face and edge/edge contacts changes it by less than 5e-5 (measured: at most 1.1e-5 in these
  10 intervals, 3.3e-5 in the 73 of 1e5 steps: the gas is chaotic, another round-off takes it along
  another path, so the bound covers the worst seen), and all of them together by less than 1e-4 (the
  issue's bound; measured 2.1e-6); free flight between two samples keeps it to round-off (1e-12);
* the issue's bound on the whole gas, 1e-4, is NOT met: an expected failure (strict: it will report
  when a conservative multipoint rule makes it pass), measured -7.2e-4 after 2e4 steps; skipped when
  the trajectory meets no edge/face or face/face contact.
"""
import numpy as np
import pytest

import dem
import dem.law

STEPS = 20_000
EVERY = 10
TYPES = ("vertex_face", "edge_edge", "edge_face", "face_face")


def gas_input(per_contact=100, seed=3, n=3, pitch=0.005, speed=1.0):
    rng = np.random.default_rng(seed)
    L = n * pitch
    text = f"""units si
boundary p p p
region box block 0 {L!r} 0 {L!r} 0 {L!r}
create_box 1 box
shape c cube 0.002
shape t tetrahedron 0.003
shape p pinacoid 0.0022 0.0022 0.0022
"""
    v = rng.normal(size=(n ** 3, 3)) * speed / np.sqrt(3)
    v -= v.mean(axis=0)

    def words(a):
        return " ".join(repr(float(c)) for c in a)

    k = 0
    for ix in range(n):
        for iy in range(n):
            for iz in range(n):
                q = rng.normal(size=4)
                q /= np.linalg.norm(q)
                x = (np.array([ix, iy, iz]) + 0.5) * pitch + rng.uniform(-0.0005, 0.0005, 3)
                w = rng.normal(size=3) * 100
                text += (f"create_atoms 1 single {words(x)} shape {'ctp'[k % 3]} density 1250 quat {words(q)} "
                         f"v {words(v[k])} omega {words(w)}\n")
                k += 1
    m_tet = 1250 * 0.003 ** 3 / (6 * 2 ** 0.5)
    tc = dem.law.contact_time(1e5, 1.0, m_tet / 2)
    return text + f"""pair_style polyhedron/multipoint
pair_coeff * * kn 1e5 en 1.0 mu 0.0
fix integrate all nve/shape
timestep {tc / per_contact!r}
neighbor 0.0005 bin
thermo 0
"""


@pytest.fixture(scope="module")
def gas():
    """(relative energy at the contact-free samples, contact-steps per type up to each sample)."""
    sim = dem.Simulation(screen=False)
    sim.commands(gas_input())
    rows = []

    def sample(sim):
        p = sim.pair
        if p.ncontacts == 0:
            rows.append([sim.thermo_keyword("etotal")] + [p.stats[t] for t in TYPES])

    sim.every(EVERY, sample)
    sim.run(0)
    assert sim.pair.ncontacts == 0
    e0 = sim.thermo_keyword("etotal")
    sim.run(STEPS)
    r = np.array(rows)
    return r[:, 0] / e0 - 1.0, r[:, 1:]


def test_gas_single_point_collisions_keep_energy(gas):
    e, counts = gas
    de, dc = np.diff(e), np.diff(counts, axis=0)
    single = (dc[:, 2] + dc[:, 3] == 0) & (dc.sum(axis=1) > 0)
    assert single.sum() >= 8                                  # collisions happened (measured 10)
    assert np.abs(de[single]).max() < 5e-5
    assert abs(de[single].sum()) < 1e-4
    quiet = dc.sum(axis=1) == 0                               # no contact in between: free flight
    assert np.abs(de[quiet]).max() < 1e-12


@pytest.mark.xfail(strict=True, reason="the shared maximum overlap of an edge/face contact (Descantes eq. 3) "
                                       "is not a potential force: one edge/face collision changes the "
                                       "energy by -7.2e-4 (module docstring)")
def test_gas_keeps_energy_to_1e4(gas):
    e, counts = gas
    if counts[-1, 2] + counts[-1, 3] == 0:
        pytest.skip("this trajectory met no edge/face or face/face contact (another round-off, e.g. of a "
                    "faster geometry kernel, makes the gas take another path): nothing to show")
    assert abs(e[-1]) < 1e-4
