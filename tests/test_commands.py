"""Set-up commands: particle creation, groups, set, read_data of LAMMPS files, thermo keywords."""
import math

import numpy as np
import pytest

import dem

BOX = """
units si
boundary p p f
region box block 0 0.01 0 0.01 0 0.02
create_box 2 box
"""


def make(script):
    sim = dem.Simulation(screen=False)
    sim.commands(script)
    return sim


def test_random_fill_is_reproducible_and_never_overlaps():
    script = BOX + "create_atoms 1 random 300 77 box radius uniform 0.0003 0.0005 density 2500\n"
    a, b = make(script), make(script)
    assert np.array_equal(a.gather("x"), b.gather("x"))
    x, r = a.gather("x"), a.gather("radius")
    d = x[:, None, :] - x[None, :, :]
    d[..., :2] -= 0.01 * np.round(d[..., :2] / 0.01)        # periodic x and y: minimum image
    dist = np.sqrt((d ** 2).sum(-1)) + np.eye(len(x))
    assert np.all(dist >= (r[:, None] + r[None, :]) * (1 - 1e-12))
    assert np.all(x[:, 2] - r >= 0) and np.all(x[:, 2] + r <= 0.02)   # inside the region
    assert np.all((r >= 0.0003) & (r <= 0.0005))
    c = make(script.replace(" 77 ", " 78 "))
    assert not np.array_equal(a.gather("x"), c.gather("x"))


def test_lattice_and_single():
    sim = make(BOX + "create_atoms 1 lattice box sc 0.001 radius 0.0004 density 1000\n"
                     "create_atoms 2 single 0.005 0.005 0.0195 radius 0.0002 v 1 2 3\n")
    assert sim.atom.natoms == 10 * 10 * 20 + 1
    m = sim.gather("rmass")
    assert m[0] == pytest.approx(1000 * 4 / 3 * math.pi * 0.0004 ** 3, rel=1e-14)
    assert sim.gather("v")[-1].tolist() == [1, 2, 3]
    assert sim.gather("type")[-1] == 2


def test_groups_and_set():
    sim = make(BOX + "create_atoms 1 lattice box sc 0.001 radius 0.0004 density 1000\n"
                     "region top block INF INF INF INF 0.01 INF\n"
                     "group top region top\n"
                     "set group top type 2 v 0 0 -1 density 2000\n"
                     "group heavy type 2\n"
                     "group rest subtract all heavy\n")
    assert sim.groups.count("top") == sim.groups.count("heavy") == 1000
    assert sim.groups.count("rest") == 1000
    top = sim.groups.members("top")
    m = sim.atom.local("rmass")
    assert m[top][0] == pytest.approx(2 * m[~top][0], rel=1e-14)
    assert np.all(sim.atom.local("v")[top] == [0, 0, -1])


DATA = """LAMMPS data file via write_data, version 22 Jul 2025, timestep = 30000, units = si

3 atoms
2 atom types

0 0.02 xlo xhi
0 0.02 ylo yhi
0 0.044 zlo zhi

Atoms # sphere

7 1 0.001 2500 0.0005 0.0005 0.0005 0 0 0
2 2 0.002 1000 0.003 0.002 0.001 1 -2 0
5 1 0.001 2500 0.0015 0.0005 0.0005 0 3 0

Velocities

2 0.1 0.2 0.3 1 2 3
7 0 0 -1 0 0 0
5 0 0 0 0 0 0
"""


def test_read_data_of_a_lammps_sphere_file(tmp_path):
    """The format of LAMMPS write_data for atom_style sphere (the benchmark beds are written so):
    `id type diameter density x y z ix iy iz`. Every column is checked against the file, by id (the
    values are copied, not computed: exact), with distinct x, y and z so that a swap of columns shows,
    types not all equal, and non-zero image flags (periodic x and y: a particle that crossed them)."""
    path = tmp_path / "bed.data"
    path.write_text(DATA)
    sim = make(f"units si\nboundary p p fm\nread_data {path}\n")
    assert sim.atom.natoms == 3 and sim.atom.ntypes == 2
    assert sim.domain.lo.tolist() == [0, 0, 0] and sim.domain.hi.tolist() == [0.02, 0.02, 0.044]
    assert sim.gather("tag").tolist() == [2, 5, 7]
    assert sim.gather("type").tolist() == [2, 1, 1]
    assert sim.gather("x").tolist() == [[0.003, 0.002, 0.001], [0.0015, 0.0005, 0.0005],
                                        [0.0005, 0.0005, 0.0005]]
    assert sim.gather("image").tolist() == [[1, -2, 0], [0, 3, 0], [0, 0, 0]]
    assert sim.gather("radius").tolist() == [0.001, 0.0005, 0.0005]
    # mass = density * 4/3 pi r^3: one product of floats, to round-off
    assert sim.gather("rmass")[0] == pytest.approx(1000 * 4 / 3 * math.pi * 0.001 ** 3, rel=1e-14)
    assert sim.gather("rmass")[1] == pytest.approx(2500 * 4 / 3 * math.pi * 0.0005 ** 3, rel=1e-14)
    assert sim.gather("v")[0].tolist() == [0.1, 0.2, 0.3] and sim.gather("omega")[0].tolist() == [1, 2, 3]
    assert sim.gather("v")[2].tolist() == [0, 0, -1]


def test_thermo_keywords_and_run_zero():
    """`contacts` and `cn` counted exactly on a lattice. Spheres on a simple cubic lattice (spacing
    1 mm, 10 x 10 x 20 sites, periodic in x and y, not in z), radius set to 0.51 mm after creation so that
    every lattice neighbour overlaps by 0.02 mm (2 % of a diameter, well above round-off and well below
    the 0.2 overlap limit; touching spheres would have zero overlap, counted or not by round-off).
    Contacts: 10*10*20 along x + 10*10*20 along y (periodic: every site has its +x and +y neighbour) +
    10*10*19 along z = 5900; cn = 2 * contacts / atoms = 2 * 5900 / 2000 = 5.9 (each contact touches
    two particles). Both are integer counts over a ratio of integers: exact."""
    sim = make(BOX + "create_atoms 1 lattice box sc 0.001 radius 0.0005 density 1000\n"
                     "set group all radius 0.00051\n"
                     "pair_style sphere\npair_coeff * * kn 100 en 0.5\n"
                     "fix nve all nve/sphere\ntimestep 1e-6\nthermo_style custom step atoms contacts cn\n"
                     "run 0\n")
    assert sim.thermo_keyword("atoms") == 2000
    assert sim.thermo_keyword("contacts") == 10 * 10 * 20 * 2 + 10 * 10 * 19
    assert sim.thermo_keyword("cn") == 2.0 * 5900 / 2000          # 5.9: one division, exact
    assert sim.thermo_keyword("step") == 0
    assert sim.thermo_keyword("xhi") == 0.01 and sim.thermo_keyword("vol") == pytest.approx(2e-6)
    with pytest.raises(dem.DemError, match="unknown thermo keyword 'nope'"):
        sim.thermo_keyword("nope")


def test_nan_stops_the_run_with_the_particle_id():
    sim = make(BOX + "create_atoms 1 single 0.005 0.005 0.01 radius 0.0005\n"
                     "create_atoms 1 single 0.002 0.002 0.01 radius 0.0005\n"
                     "fix nve all nve/sphere\ntimestep 1e-6\n")
    # `set ... vx nan` is refused at parse time: the NaN comes from outside the script
    atom = sim.atom
    atom.data["v"][:atom.nlocal][atom.data["tag"][:atom.nlocal] == 2, 0] = math.nan
    with pytest.raises(dem.DemError, match=r"non-finite position or velocity at step \d+ \(particle ids 2\)"):
        sim.run(10)
