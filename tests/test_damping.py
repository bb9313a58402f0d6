"""fix damping/potyondy (local non-viscous damping, Potyondy & Cundall 2004) against closed forms."""
import math

import numpy as np
import pytest

import dem
from dem.errors import DemError



def _one_particle(extra, box="-1 1 -1 1 -1 1", boundary="f f f"):
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary {boundary}
        region box block {box}
        create_box 1 box
        create_atoms 1 single 0 0 0 radius 0.01 density 1000
        pair_style sphere
        pair_coeff * * kn 1e4 en 1.0
        fix integ all nve/sphere
        {extra}
        timestep 1e-4
        thermo 0
    """)
    return sim


def test_constant_force_exact():
    """Under a constant force F from rest, the damped force is F (1 - alpha) once the particle moves:
    v after N steps of the leap-frog is exactly dt F / m (1 + (N - 1)(1 - alpha)) (the first kick sees
    v = 0, sign 0), so the kinetic energy is (1 - alpha)^2 that of the free motion at large N."""
    alpha, g, n, dt = 0.3, 9.81, 500, 1e-4
    sim = _one_particle(f"fix g all gravity {g} vector 0 0 -1\nfix damp all damping/potyondy alpha {alpha}")
    sim.run(n)
    vz = sim.gather("v")[0, 2]
    expected = -dt * g * (1 + (n - 1) * (1 - alpha))
    assert vz == pytest.approx(expected, rel=1e-12)          # exact up to round-off
    ke = sim.thermo_keyword("ke")
    m = float(sim.gather("rmass")[0])
    assert ke == pytest.approx(0.5 * m * expected ** 2, rel=1e-12)
    # the rate of work of the damping force, -alpha m g |v|, with v the half-step velocity it acted on
    v_last = dt * g * (1 + (n - 2) * (1 - alpha))
    assert sim.thermo_keyword("f_damp[power]") == pytest.approx(-alpha * m * g * v_last, rel=1e-12)


def test_start_stop_window():
    """Active only for start <= step < stop: in the window the particle accelerates at (1 - alpha) g."""
    alpha, g, dt = 0.5, 9.81, 1e-4
    sim = _one_particle(f"fix g all gravity {g} vector 0 0 -1\n"
                        f"fix damp all damping/potyondy alpha {alpha} start 100 stop 200")
    sim.run(300)
    vz = sim.gather("v")[0, 2]
    assert vz == pytest.approx(-dt * g * (200 + 100 * (1 - alpha)), rel=1e-12)


def test_oscillator_amplitude_decay():
    """A sphere resting on a floor with an elastic contact (en = 1) and gravity oscillates about
    delta0 = m g / kn with the contact stiffness. Local damping makes the restoring force (1 + alpha) k x
    while moving away from equilibrium and (1 - alpha) k x when coming back, so from one turning point to
    the next (half a period) the amplitude ratio is exactly sqrt((1 - alpha)/(1 + alpha)), the energy ratio
    (1 - alpha)/(1 + alpha), whatever the amplitude (piecewise-linear). The leap-frog switches the sign
    of v half a step late and the turning points are sampled once per step: with 1000 steps per period
    the measured ratios are within 1e-4 of the formula. Tolerance 2e-3: 20x that, and five times smaller
    than the gap (1 %) to the small-alpha estimate exp(-alpha) at alpha = 0.3, so the test tells the
    exact law from its approximation."""
    alpha, kn, r, rho, g = 0.3, 1e4, 0.01, 1000.0, 9.81
    m = rho * 4 / 3 * math.pi * r ** 3
    w = math.sqrt(kn / m)
    period = 2 * math.pi / w
    dt = period / 1000
    delta0 = m * g / kn
    a0 = 0.5 * delta0                  # stays in contact
    z0 = r - delta0 - a0               # start below equilibrium (compressed), at rest
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary f f f
        region box block -0.1 0.1 -0.1 0.1 -0.1 0.1
        create_box 1 box
        create_atoms 1 single 0 0 {z0!r} radius {r} density {rho}
        pair_style sphere
        pair_coeff * * kn {kn} en 1.0
        fix integ all nve/sphere
        fix g all gravity {g} vector 0 0 -1
        fix floor all wall/plane zplane 0 NULL kn {kn} en 1.0
        fix damp all damping/potyondy alpha {alpha}
        timestep {dt!r}
        thermo 0
    """)
    zeq = r - delta0
    zs = []
    for _ in range(3000):              # three periods: six turning points
        sim.run(1)
        zs.append(float(sim.atom.local("x")[0, 2]) - zeq)
    zs = np.array(zs)
    # turning points: local extrema of the displacement
    k = np.flatnonzero((np.abs(zs[1:-1]) >= np.abs(zs[:-2])) & (np.abs(zs[1:-1]) >= np.abs(zs[2:]))) + 1
    amps = [abs(zs[0])] + [abs(zs[i]) for i in k]
    amps = np.array(amps[:6])
    ratios = amps[1:] / amps[:-1]
    expected = math.sqrt((1 - alpha) / (1 + alpha))
    assert len(ratios) >= 4
    np.testing.assert_allclose(ratios, expected, rtol=2e-3)


def test_order_warning_and_bad_alpha():
    sim = _one_particle("fix damp all damping/potyondy alpha 0.7\nfix g all gravity 9.81")
    msgs = []
    sim.warning = msgs.append
    sim.run(1)
    assert any("damping/potyondy comes before" in m for m in msgs)
    with pytest.raises(DemError):
        _one_particle("fix damp all damping/potyondy alpha 1.0")
    with pytest.raises(DemError):
        _one_particle("fix damp all damping/potyondy 0.7")
