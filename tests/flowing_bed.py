"""The test bed of test_neighbor.py and test_restart.py: a frictional bed (240 polydisperse spheres of two
types, ks > 0: tangential springs with history) flowing down a tilted gravity against walls that keep their
own history; `periodic` along x or `walled`."""
import numpy as np

import dem

BOX = """
boundary {boundary}
region box block 0 0.01 0 0.006 0 0.02
create_box 2 box
region fill block 0 0.01 0 0.006 0 0.004
create_atoms 1 lattice fill sc 0.001 radius uniform 0.0003 0.00048 density 2500
region upper block INF INF INF INF 0.002 INF
set region upper type 2 density 2000
timestep 1.5e-6
neighbor 0.0001 bin
thermo 0
"""
# what a restarted script repeats (as in LAMMPS: the restart holds no pair style or fix)
FORCES = """
pair_style sphere
pair_coeff * * kn 2000 en 0.5 mu 0.5 gamma_t 0 ks 571.4
pair_coeff 1 2 kn 3000 en 0.6 mu 0.4 gamma_t 10 ks 800
fix integrate all nve/sphere
fix gravity all gravity 60 vector 0.3 0 -1
fix walls all wall/plane {walls} zplane 0 NULL kn 2000 en 0.5 mu 0.3 ks 571.4
"""
CASES = {"periodic": ("p f fm", "yplane 0 0.006"), "walled": ("f f fm", "xplane 0 0.01 yplane 0 0.006")}


def bed(case, extra=""):
    """The bed (`case` of CASES) with random initial velocities; `extra` commands come last."""
    boundary, walls = CASES[case]
    sim = dem.Simulation(screen=False)
    sim.commands(BOX.format(boundary=boundary) + FORCES.format(walls=walls) + extra)
    rng = np.random.default_rng(5)
    sim.atom.local("v")[:] = 0.05 * rng.normal(size=(sim.atom.nlocal, 3))
    return sim
