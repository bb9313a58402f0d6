"""inputs/in.packing_box in its cylindrical container (Part III Fig. 19: D = 6.25 d, wall/drum at rest with
end walls), shortened: the particles are inserted inside the cylinder, settle on its floor and stay
within its wall; these few particles all lie in the lowest 3 d, so the script's voxelised porosity there
is 1 minus their volume over that of the region (within 0.05: the voxels' resolution and the wall's
overlaps are far smaller, a particle reaching above 3 d is not); a wrong container is named."""
import os

import numpy as np
import pytest

import dem

SCRIPT = os.path.join(os.path.dirname(__file__), os.pardir, "inputs", "in.packing_box")
D = 6.25 * 0.003


@pytest.mark.parametrize("shape, n, inner", [("sphere", 60, 0.0015), ("cube", 30, 0.5 * 0.003 * (3.14159265 / 6) ** (1 / 3))])
def test_cylinder_container(tmp_path, monkeypatch, shape, n, inner):
    """inner: the least distance from the centre to the surface (the sphere's radius, the cube's half edge)."""
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False, variables=[("shape", [shape]), ("container", ["cylinder"]), ("N", [str(n)]),
                                                  ("settle", ["0.25"])])
    sim.file(SCRIPT)
    x = sim.gather("x")
    assert len(x) == n
    assert np.all(np.hypot(x[:, 0], x[:, 1]) + inner < D / 2 + 1e-5)   # overlaps of at most ~1e-5 m
    assert np.all(x[:, 2] > 0) and x[:, 2].max() < 0.02                  # on the floor, not falling
    solid = n * 3.14159265 / 6 * 0.003 ** 3 / (3.14159265 / 4 * D * D * 3 * 0.003)    # their volume in 0-3 d
    assert sim.computes["porw"].scalar() == pytest.approx(1 - solid, abs=0.05)          # all of it down there
    sim.close()


def test_unknown_container(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False, variables=[("container", ["can"])])
    sim.file(SCRIPT)
    assert sim.input.quit_status == 2 and sim.atom.natoms == 0


def test_sharp_cubes_take_the_multipoint_law(tmp_path, monkeypatch):
    """`-var sharp 1`: cubes without the crust, through pair_style polyhedron/multipoint, the floor touched
    at every corner beyond it; a few steps with a few cubes in a small box (a quick final porosity)."""
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False, variables=[("shape", ["cube"]), ("sharp", ["1"]), ("N", ["5"]),
                                                  ("settle", ["0.0002"]), ("L", ["0.01"])])
    sim.file(SCRIPT)
    assert sim.pair.style == "polyhedron/multipoint"
    floor = next(f for f in sim.modify.fixes if f.id == "floor")
    assert "multipoint" in " ".join(floor.args)
    sim.close()


def test_sharp_needs_a_polytope(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False, variables=[("shape", ["sphere"]), ("sharp", ["1"])])
    sim.file(SCRIPT)
    assert sim.input.quit_status == 2 and sim.atom.natoms == 0


def test_insertion_layer_thickness(tmp_path, monkeypatch):
    """`-var layer T`: the insertion layer is T equivalent diameters thick, its top 1.2 d under the box top
    (3D crosses of aspect 8 have a bounding diameter of 2.34 d: the default 2.3 d leaves them no room)."""
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False, variables=[("layer", ["3.3"]), ("N", ["2"]), ("settle", ["0.00001"]),
                                                  ("L", ["0.01"])])
    sim.file(SCRIPT)
    lo, hi = sim.domain.regions["layer"].extent()
    assert hi[2] - lo[2] == pytest.approx(3.3 * 0.003, rel=1e-12)
    assert sim.domain.hi[2] - hi[2] == pytest.approx(1.2 * 0.003, rel=1e-12)
    sim.close()
