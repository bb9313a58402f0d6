"""inputs/in.hopper and inputs/in.mixer, shortened so that they cannot rot: the meshes are found beside the
script from any folder, particles leave the hopper through the orifice and are counted, the impeller is
resisted by the bed."""
import os

import numpy as np
import pytest

import dem

INPUTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "inputs")


def run(tmp_path, name, **variables):
    cwd = os.getcwd()
    os.chdir(tmp_path)                    # a scratch folder: the meshes are found beside the script
    try:
        sim = dem.Simulation(screen=False, variables=[(k, [str(v)]) for k, v in variables.items()])
        sim.file(os.path.join(INPUTS, name))
    finally:
        os.chdir(cwd)
    return sim


def test_hopper_discharges_through_the_orifice(tmp_path):
    """300 spheres fall into the hopper, settle on the plug for 0.15 s, then leave through the 30 mm orifice
    for 0.15 s: some are deleted below it and counted, f_out[mass] is their mass (equal spheres: count x m
    to round-off), the remaining ones are all inside the hopper or falling under it, and the series file,
    the restart and the pictures are written."""
    sim = run(tmp_path, "in.hopper", N=300, D=30, fill=0.15, discharge=0.15)
    removed = int(sim.thermo_keyword("f_out[removed]"))
    assert 0 < removed < 300 and sim.atom.natoms == 300 - removed
    m = float(sim.gather("rmass")[0])
    assert sim.thermo_keyword("f_out[mass]") == pytest.approx(removed * m, rel=1e-12)
    x = sim.gather("x")
    assert np.all(np.hypot(x[:, 0], x[:, 1]) < 0.05) and np.all(x[:, 2] > -0.05)
    for name in ("hopper.dat", "hopper_settled.restart", "hopper_0.png", "hopper_0_hopper.vtu",
                 "hopper_0_plate.vtu", "hopper.pvd"):
        assert (tmp_path / name).exists(), name


def test_mixer_blades_are_resisted(tmp_path):
    """400 spheres fallen into the vessel (0.1 s), then the impeller turns at 120 rpm for 0.05 s: it
    meets the bed, the torque on it about its axis opposes the turning (negative), the blades' angle is
    that of the ramped rate (0.05 s ramp: angle = omega t^2 / (2 ramp) at the end of the ramp)."""
    sim = run(tmp_path, "in.mixer", N=400, rpm=120, fill=0.1, rotate=0.05)
    assert sim.thermo_keyword("f_blades[contacts]") > 0
    data = np.loadtxt(tmp_path / "mixer.dat")
    assert np.mean(data[len(data) // 2:, 3]) < 0.0                 # torque column
    omega = 120 * 2 * np.pi / 60
    assert sim.thermo_keyword("f_blades[angle]") == pytest.approx(0.5 * omega * 0.05, rel=1e-6)
