"""inputs/in.polyhedra_box (cubes, tetrahedra and pinacoids poured into a walled box, polyhedron/multipoint)
shortened so that it cannot rot, and `compute pair/contacts`, the contact census it prints."""
import os

import numpy as np
import pytest

import dem

SCRIPT = os.path.join(os.path.dirname(__file__), os.pardir, "inputs", "in.polyhedra_box")


@pytest.mark.parametrize("law", ["grains3d", "descantes"])
def test_polyhedra_box_input_runs(tmp_path, law):
    """2 particles of each shape, 0.04 s (2e4 steps: they fall the 2.5 cm of the box by 0.024 s and land):
    all 6 are inserted and stay in the box, they bounce off the floor, every output is written."""
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        sim = dem.Simulation(screen=False, variables=[("N", ["2"]), ("settle", ["0.04"]), ("law", [law]),
                                                      ("out", ["out"])])
        sim.file(SCRIPT)
    finally:
        os.chdir(cwd)
    assert sim.atom.natoms == 6
    assert sorted(np.bincount(sim.gather("shape"))) == [2, 2, 2]
    x = sim.gather("x")
    assert np.all((x > 0) & (x < [0.015, 0.015, 0.035]))
    # launched at 1 m/s downwards and inserted within 2 ms of each other (every 60 steps), particles that
    # touched only each other would all still fall at more than 1 m/s: rising ones bounced off the floor
    assert np.any(sim.gather("v")[:, 2] > 0)
    assert sim.pair.law == law and sim.modify.find("walls").contact_law == law
    out = tmp_path / "out"
    for name in ("polyhedra.pvd", "polyhedra_20000.vtu", "polyhedra.h5", "polyhedra.xdmf", "side_20000.png",
                 "slice_20000.png"):
        assert (out / name).exists(), name


CUBES = """units si
boundary f f f
region box block -0.02 0.02 -0.02 0.02 -0.02 0.03
create_box 1 box
shape c cube 0.002
create_atoms 1 single 0 0 0.001 shape c density 1250
create_atoms 1 single 0 0 0.0029999 shape c density 1250
create_atoms 1 single {x3!r} -0.0004 0.0009 shape c density 1250 quat {q}
pair_style polyhedron/multipoint
pair_coeff * * kn 1e5 en 0.5
fix integrate all nve/shape
timestep 2e-6
compute ct all pair/contacts
"""


def test_compute_pair_contacts_census():
    """Three cubes: the second face to face on the first (face/face, 4 points), the third beside the
    first, turned 0.1 rad about z so that a vertical edge meets its side face (edge/face, 2 points), 0.1 mm
lower than it (it misses the second). The
    compute returns the pair style's census: 2 pairs, [vf, ee, ef, ff, sphere, points] = [0, 0, 1, 1, 0, 6]."""
    th = 0.1
    sim = dem.Simulation(screen=False)
    x3 = 0.001 + 0.001 * (np.cos(th) + np.sin(th)) - 1e-7          # 0.1 um into the first one's side
    sim.commands(CUBES.format(q=f"{float(np.cos(th / 2))!r} 0 0 {float(np.sin(th / 2))!r}", x3=float(x3)))
    sim.run(0)
    assert sim.thermo_keyword("c_ct") == 2
    assert [sim.thermo_keyword(f"c_ct[{k}]") for k in range(1, 7)] == [0, 0, 1, 1, 0, 6]


def test_compute_pair_contacts_errors():
    sim = dem.Simulation(screen=False)
    with pytest.raises(dem.errors.DemError, match="use group all"):
        sim.commands(CUBES.format(q="1 0 0 0", x3=0.004).replace("compute ct all", "group one id 1\ncompute ct one"))
    sim = dem.Simulation(screen=False)
    sim.commands(CUBES.format(q="1 0 0 0", x3=0.004).replace("polyhedron/multipoint", "convex/gjk") + "run 0\n")
    with pytest.raises(dem.errors.DemError, match="needs pair_style polyhedron/multipoint"):
        sim.thermo_keyword("c_ct")
