"""The overlap stop (thermo_modify overlap) covers wall contacts, and a particle whose centre lies behind
a wall (created there) stops the run at its first step, naming the particle and the wall; before, such a
particle was shot out at ~28 m/s with exit status 0 and no word."""
import pytest

import dem
from dem.errors import DemError

R = 0.0005


def sim_with(z, extra="", walls="fix floor all wall/plane zplane 0 NULL"):
    sim = dem.Simulation(screen=False)
    sim.commands(f"""units si
        boundary p p f
        region box block -0.005 0.005 -0.005 0.005 -0.005 0.01
        create_box 1 box
        create_atoms 1 single 0 0 0.004 radius {R} density 2500
        create_atoms 1 single 0.002 0 {z} radius {R} density 2500
        pair_style sphere
        pair_coeff * * kn 1000 en 0.5
        fix integ all nve/sphere
        {walls}
        {extra}
        timestep 1e-6
        thermo 0""")
    return sim


def test_particle_behind_a_wall_stops_the_first_step():
    sim = sim_with(-0.001)
    with pytest.raises(DemError) as info:
        sim.run(10)
    text = str(info.value)
    assert "particle 2 and wall 'zplane 0' (facing +z) of fix floor" in text, text
    assert "behind the wall" in text and "at step 0" in text
    assert "first step of the run" in info.value.hint
    assert "exceeds the limit 0.2" in text


def test_behind_a_wall_is_an_error_even_under_a_loose_limit():
    sim = sim_with(-0.001, extra="thermo_modify overlap 5")
    with pytest.raises(DemError) as info:
        sim.run(10)
    assert "particle 2" in str(info.value) and "centre behind a wall" in str(info.value)


def test_deep_wall_overlap_hits_the_limit():
    """Centre in front of the wall, overlap 0.4 diameter > 0.2: the same stop as for a pair overlap."""
    sim = sim_with(0.2 * R)
    with pytest.raises(DemError) as info:
        sim.run(10)
    text = str(info.value)
    assert "overlap of 0.4 x diameter between particle 2 and wall 'zplane 0'" in text, text
    assert "behind the wall" not in text           # its centre is in front


def test_drum_wall_names_the_drum():
    sim = sim_with(0.0, walls="fix drum all wall/drum y 0 0 0.003")
    with pytest.raises(DemError) as info:   # particle 1 at z = 0.004 lies outside the drum of radius 3 mm
        sim.run(10)
    assert "particle 1 and wall 'drum' of fix drum" in str(info.value), str(info.value)


def test_touching_a_wall_runs_on():
    sim = sim_with(0.9 * R)                  # overlap 0.05 diameter: under the limit
    sim.run(20)
    assert sim.update.ntimestep == 20
