"""compute porosity: structured-lattice voxelisation of the space occupied by particles (Part III sec 4.1)."""
import math

import numpy as np
import pytest

import dem
from dem.errors import DemError



def _lattice(n=4, a=0.002, extra=""):
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary p p p
        region box block 0 {n * a} 0 {n * a} 0 {n * a}
        create_box 1 box
        create_atoms 1 lattice box sc {a} radius {a / 2}
        {extra}
    """)
    return sim


def test_simple_cubic_default_resolution():
    """Touching spheres on a simple cubic lattice: porosity 1 - pi/6 = 47.64 %. At the default resolution
    (40 points per diameter) the grid is commensurate with the lattice, the worst case (aliasing): the
    error is 0.14 %; the brief's tolerance is 0.5 %."""
    sim = _lattice(extra="compute por all porosity box")
    eps = sim.thermo_keyword("c_por")
    assert eps == pytest.approx(1 - math.pi / 6, rel=5e-3)
    assert sim.thermo_keyword("c_por[2]") == pytest.approx(1 - eps)
    assert sim.thermo_keyword("c_por[3]") == 160 ** 3


def test_shifted_lattice_and_periodic_images():
    """The same lattice shifted by an arbitrary offset: spheres cut by the periodic boundaries count
    through their images; a sub-region (a block offset from the lattice, an integer number of cells
    wide) has the same porosity."""
    a = 0.002
    sim = _lattice(a=a, extra=f"region sub block {0.37 * a} {3.37 * a} {0.81 * a} {2.81 * a} {0.13 * a} {3.13 * a}\n"
                              "compute whole all porosity box\ncompute part all porosity sub")
    x = sim.atom.local("x")
    x += np.array([0.29, 0.61, 0.47]) * a
    sim.domain.pbc()
    for name in ("c_whole", "c_part"):
        assert sim.thermo_keyword(name) == pytest.approx(1 - math.pi / 6, rel=5e-3), name


def test_random_spheres_exact_volume():
    """Non-overlapping random spheres of several sizes in a periodic box: the solid fraction is exactly
    sum(4/3 pi r^3) / V. A random placement does not alias: at the default resolution the error is
    below 0.05 % (measured ~0.01 %); tolerance 0.2 %."""
    sim = dem.Simulation(screen=False)
    sim.commands("""
        boundary p p p
        region box block 0 0.02 0 0.02 0 0.02
        create_box 1 box
        create_atoms 1 random 150 3377 box radius uniform 0.001 0.002
        compute por all porosity box resolution 20
    """)
    r = sim.atom.local("radius")
    phi_exact = float(np.sum(4 / 3 * math.pi * r ** 3)) / 0.02 ** 3
    assert sim.thermo_keyword("c_por[2]") == pytest.approx(phi_exact, rel=2e-3)


def test_cylinder_region_and_errors():
    """One sphere inside a cylindrical region: the solid volume is that of the sphere (0.3 %: a single
    sphere, 40 points per diameter), the porosity 1 - V_sphere / V_cylinder."""
    sim = dem.Simulation(screen=False)
    sim.commands("""
        boundary f f f
        region box block -0.01 0.01 -0.01 0.01 -0.01 0.01
        create_box 1 box
        create_atoms 1 single 0 0 0 radius 0.002
        region cyl cylinder z 0 0 0.004 -0.005 0.005
        compute por all porosity cyl
    """)
    vs = 4 / 3 * math.pi * 0.002 ** 3
    vc = math.pi * 0.004 ** 2 * 0.01
    assert sim.thermo_keyword("c_por[4]") == pytest.approx(vs, rel=3e-3)
    assert sim.thermo_keyword("c_por") == pytest.approx(1 - vs / vc, rel=3e-3)
    with pytest.raises(DemError):
        sim.command("compute bad all porosity nowhere")
    with pytest.raises(DemError):
        sim.command("thermo_style custom step c_por[7]")
        sim.thermo_keyword("c_por[7]")


@pytest.mark.parametrize("shape", ["cube 0.002", "tetrahedron 0.003", "cylinder 0.001 0.0025", "cross3d 0.003",
                                   "cross2d 0.003", "spherecylinder 0.001 0.0012 9 resolution 200"])
def test_shaped_particles_true_volume(shape, tmp_path, monkeypatch):
    """Non-overlapping shaped particles (random orientations, periodic box: some cut by the boundaries)
    and glued composites: the solid volume is the sum of their true volumes, not of their bounding spheres.
    With 30 points per smallest bounding diameter the voxel error of randomly posed bodies averages out:
    measured 0.01-0.08 % (cross beams are 0.75 mm wide: ~10 points across); bound 1.5 % (bounding spheres
    would give 1.5x to 8.2x the volume)."""
    monkeypatch.setenv("DEM_SHAPE_DB", str(tmp_path / "db.h5"))
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        units si
        boundary p p p
        region box block 0 0.02 0 0.02 0 0.02
        create_box 1 box
        shape s {shape}
        create_atoms 1 random 40 2024 box shape s quat random density 1000
        compute por all porosity box resolution 30
    """)
    n = sim.atom.natoms
    exact = n * float(sim.shapes.volume[0])
    solid = sim.thermo_keyword("c_por[4]")
    assert solid == pytest.approx(exact, rel=1.5e-2)
    r = float(sim.atom.local("radius")[0])
    assert solid < 0.9 * n * 4 / 3 * math.pi * r ** 3
