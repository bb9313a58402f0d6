"""Walls (dem_walls: every wall style is a table of surfaces for one kernel) against closed forms.

Rolling resistance on a floor: a sphere rolling without slip feels the torque mu_roll R |F_n| against its
spin, and friction at the contact keeps it rolling, so (solid sphere, I = 2/5 m R^2)
    I dw/dt = -R F - mu_roll R m g,   m dv/dt = F,   v = R w   =>   dv/dt = -(5/7) mu_roll g,
while the friction force needed, (5/7) mu_roll m g, stays below mu m g. The tangential spring (ks = 2/7 kn,
with damping) carries the friction: it oscillates about the rolling solution with the period of the
sticking contact, 2 pi sqrt(m_t / ks) (m_t = 2/7 m for a rolling sphere), here about 2 ms, and its
damping takes out the start-up transient; the speed is compared after 100 periods, where the oscillation
amplitude is far below the deceleration's effect.
"""
import math

import numpy as np
import pytest

import dem

G = 9.81
R = 0.01
RHO = 2500.0
V0 = 0.5


def roll(mu_roll, wall, t_end=0.2):
    """A sphere set rolling along +y on a floor (wall/plane, or along the axis at the bottom of a still
    drum of radius 1 m, where the wall is straight in y). Returns (times, y-velocities) every 100 steps."""
    kn = 1e5
    law = f"kn {kn} en 0.5 mu 0.5 gamma_t 2000 ks {2.0 / 7.0 * kn} mu_roll {mu_roll}"
    sim = dem.Simulation(screen=False)
    if wall == "plane":
        walls = f"fix floor all wall/plane zplane 0 NULL {law}"
        box = "region box block -1 1 -1 1 0 1"
    else:     # the drum's axis along y through (x, z) = (0, 1): its bottom is the floor z = 0 near x = 0
        walls = f"fix drum all wall/drum y 0 1 1.0 {law}"
        box = "region box block -1 1 -1 1 0 2"
    m = RHO * 4.0 / 3.0 * math.pi * R ** 3
    overlap = m * G / kn                     # static overlap: start at rest in the normal direction
    sim.commands(f"""
        boundary p p f
        {box}
        create_box 1 box
        create_atoms 1 single 0 0 {R - overlap} radius {R} density {RHO} v 0 {V0} 0 omega {-V0 / R} 0 0
        pair_style sphere
        pair_coeff * * {law}
        fix integ all nve/sphere
        fix g all gravity {G} vector 0 0 -1
        {walls}
        timestep 1e-5
        thermo 0
    """)
    times, speeds = [], []
    for _ in range(int(round(t_end / 1e-3))):
        sim.run(100)
        times.append(sim.update.time)
        speeds.append(float(sim.gather("v")[0, 1]))
    return np.array(times), np.array(speeds)


@pytest.mark.parametrize("wall", ["plane", "drum"])
def test_rolling_resistance_decelerates_as_the_model(wall):
    """dv/dt = -(5/7) mu_roll g within 0.1 % (the fit over 0.1-0.2 s, 100 periods of the tangential
    oscillation; measured 2.2e-5 on both walls, the residual of that oscillation), and no deceleration
    without mu_roll (measured 1e-15 m/s^2: the contact point of a rolling sphere does not slide)."""
    mu_roll = 0.05
    t, v = roll(mu_roll, wall)
    late = t >= 0.1
    slope = np.polyfit(t[late], v[late], 1)[0]
    expected = -5.0 / 7.0 * mu_roll * G
    assert slope == pytest.approx(expected, rel=1e-3), (slope, expected)
    t, v = roll(0.0, wall)
    late = t >= 0.1
    assert abs(np.polyfit(t[late], v[late], 1)[0]) < 0.01 * abs(expected)
