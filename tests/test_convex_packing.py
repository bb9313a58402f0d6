"""A packing of 1024 cubes settles under gravity (pair_style convex/gjk, fix nve/shape, a floor through
fix wall/plane, bi-periodic box as Part III sec 4.1): no particle lost, the bed at rest, overlaps far
below 1 % of the edge (measured by the kernel and, independently, pair by pair from Python), no deep
(EPA) contact ever. Contacts see the cubes with edges and corners rounded by the crust (2.5 % of the
edge by default): sharp edges and corners may interpenetrate by their roundings more (<= 2 crust
(sqrt 3 - 1)).

The cubes are those of Part III sec 4.1 (the volume of a sphere of radius 1.5 mm, density 2500) on a
16 x 16 x 4 simple-cubic lattice of spacing 1.75 edges (bounding spheres apart), randomly oriented. To
settle within the test budget the contact is softer than Table 5 (kn = 1e4 N/m, en = 0.5, mu = 0.55,
gamma_t = 2000 1/s, ks = 2/7 kn; T_c = 1.4e-4 s, dt = 7e-6 s: 20 steps per contact): the static
overlap under the bed is m g / kn ~ 1e-4 of the edge, the impact overlaps a few 1e-3. 40000 steps
(0.28 s) take about 45 s on one core."""
import numpy as np
import pytest

import dem
from dem.contact import geometry

A = 0.002418
SP = 1.75 * A
NX, NZ = 16, 4
LAW = "kn 1e4 en 0.5 mu 0.55 gamma_t 2000 ks 2857"




def test_cube_packing_settles():
    L = NX * SP
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary p p f
        region box block 0 {L} 0 {L} 0 {(NZ + 1) * SP + A}
        create_box 1 box
        shape c cube {A}
        region lat block 0 {L} 0 {L} {A} {NZ * SP + A}
        create_atoms 1 lattice lat sc {SP} shape c density 2500 quat random seed 5
        pair_style convex/gjk
        pair_coeff * * {LAW}
        fix integ all nve/shape
        fix g all gravity 9.81 vector 0 0 -1
        fix floor all wall/plane zplane 0 NULL {LAW}
        timestep 7e-6
        thermo 0
    """)
    n = sim.atom.natoms
    assert n == NX * NX * NZ == 1024
    m = float(sim.atom.local("rmass")[0])
    assert m == pytest.approx(2500 * A ** 3, rel=1e-12)
    worst = 0.0
    for _ in range(16):
        sim.run(2500)
        worst = max(worst, sim.pair.max_overlap, sim.modify.find("floor").max_overlap)
    # nothing lost, everything above the floor and below the top of the initial lattice
    assert sim.atom.natoms == n and sim.domain.nlost == 0
    x = sim.atom.local("x")
    assert np.all(x[:, 2] > 0.45 * A) and np.all(x[:, 2] < NZ * SP + A)
    # at rest: kinetic energy (translation + rotation) tiny against the weight, the bulk still
    ke = sim.thermo_keyword("ke") + sim.thermo_keyword("erot")
    assert ke < 5e-3 * n * m * 9.81 * A
    speed = np.linalg.norm(sim.atom.local("v"), axis=1)
    assert np.median(speed) < 2e-3
    # overlaps (kernel: per bounding diameter) far below 1 % of the edge, and never an EPA contact
    bounding_diameter = np.sqrt(3.0) * A
    assert worst * bounding_diameter < 0.01 * A
    assert sim.pair.nepa == 0
    assert sim.pair.ncontacts > n          # a connected bed
    # independent check over every listed pair (Python, not the kernel): the overlap of the rounded
    # bodies that the contact law sees (crust contact), and the interpenetration of the sharp bodies
    # (GJK/EPA), which may exceed it by the roundings of the two features in contact (at most two
    # corners, 2 crust (sqrt 3 - 1); two edges 2 crust (sqrt 2 - 1))
    shape = sim.shapes.shapes[0]
    q = sim.atom.data["quat"]
    xa = sim.atom.data["x"]
    i_idx, j_idx = sim.neighbor.pairs()
    rounded, sharp = 0.0, 0.0
    for i, j in zip(i_idx, j_idx):
        c = geometry.contact(shape, xa[i], q[i], shape, xa[j], q[j])
        if c is not None:
            rounded = max(rounded, c[0])
        d, _, _ = geometry.distance(shape, xa[i], q[i], shape, xa[j], q[j])
        sharp = max(sharp, -d)
    assert rounded < 0.01 * A
    assert sharp < rounded + 2.0 * shape.crust * (np.sqrt(3.0) - 1.0) + 1e-9 * A
    # the bed: bounding-sphere lattice 4 layers of 1.75 edges collapsed to ~2.5-4 edges of cubes
    assert x[:, 2].max() < 4.5 * A
