"""fix wall/plane ... point multipoint law descantes: Descantes' eq. 3 at the wall's contact points (the
shared law of `pair_style polyhedron/multipoint law descantes`, dem.law.descantes): no attraction,
viscous tangential force capped by Coulomb, no spring.

Units: a cube of side 2 mm, density 1250 (m = 1e-5 kg), kn = 1e5 N/m, dt = 2e-6 s (contact time
pi sqrt(m / kn) = 3.1e-5 s, 16 steps); its weight m g = 9.8e-5 N gives a static overlap of 9.81e-10 m."""
import numpy as np
import pytest

import dem

BOX = """units si
boundary f f f
region box block -0.05 0.05 -0.01 0.01 -0.001 0.02
create_box 1 box
shape c cube 0.002
create_atoms 1 single 0 0 {z!r} shape c density 1250 v {vx!r} 0 {vz!r}
pair_style polyhedron/multipoint
pair_coeff * * kn 1e5 en 0.5
fix integrate all nve/shape
{gravity}
fix floor all wall/plane zplane 0 NULL kn 1e5 en {en} {friction} point multipoint law {law}
timestep 2e-6
thermo 0
"""
M = 1250 * 0.002 ** 3
G = 9.81
STATIC = M * G / 1e5          # static overlap of the cube's weight


def _sim(law, z, vx=0.0, vz=0.0, en=0.5, friction="mu 0.5 gamma_t 1e4", gravity=True, steps=0):
    sim = dem.Simulation(screen=False)
    sim.commands(BOX.format(z=z, vx=vx, vz=vz, en=en, friction=friction, law=law,
                            gravity="fix gravity all gravity 9.81 vector 0 0 -1" if gravity else ""))
    sim.run(steps)
    return sim


def test_cube_resting_on_floor_four_points_no_spin():
    """Dropped from 10 um face down, 1e5 steps (0.2 s, 6000 contact times; it bounces a few times: no
    attraction, en = 0.5): at rest on its 4 corners, omega and the orientation exactly unchanged (the 4
    points are symmetric: their torques cancel exactly, as with the Grains3D law,
    tests/test_walls_multipoint.py), the height at the static overlap m g / kn to round-off (measured
    2e-19 m, the last bit of z = 1e-3; bound 1e-6 of the overlap, 1e-15 m)."""
    sim = _sim("descantes", 0.00101, steps=100_000)
    assert sim.modify.find("floor").ncontacts == 4
    assert np.array_equal(sim.atom.local("omega")[0], np.zeros(3))
    assert np.array_equal(sim.atom.local("quat")[0], [1.0, 0, 0, 0])
    assert sim.atom.local("x")[0, 2] == pytest.approx(0.001 - STATIC, abs=1e-6 * STATIC)


def _wall_force(law, z, vz):
    """The force of the floor alone on the cube (no gravity, mu = 0, en = 0.1), evaluated once (no step)."""
    sim = _sim(law, z, vz=vz, en=0.1, friction="", gravity=False)
    sim.atom.local("f")[:] = 0.0
    sim.modify.find("floor").compute(False)
    return sim.atom.local("f")[0].copy()


def test_no_attraction_when_separating_fast():
    """1 nm into the floor, leaving it at 1 m/s, en = 0.1, no gravity: the dashpot 2 beta sqrt(kn m) U_n =
    0.83 N exceeds the spring kn delta = 1e-4 N. The Grains3D law pulls the cube back (F_z = -0.83 N);
    Descantes' law gives no force at all (exactly 0). Approaching at 1 cm/s on 1 um, both laws push
    alike (no tangential force: mu = 0), to the last bits."""
    f = {law: _wall_force(law, 0.001 - 1e-9, 1.0) for law in ("grains3d", "descantes")}
    assert f["grains3d"][2] < -0.5
    assert np.array_equal(f["descantes"], np.zeros(3))
    f = {law: _wall_force(law, 0.001 - 1e-6, -0.01) for law in ("grains3d", "descantes")}
    assert f["descantes"][2] > 0.1
    assert f["descantes"] == pytest.approx(f["grains3d"], rel=1e-14, abs=0)


def test_sliding_cube_friction_capped_by_coulomb():
    """A cube sliding on the floor at 5 cm/s (resting at its static overlap, mu = 0.5, gamma_t = 1e4: the
    viscous force 2 gamma_t m |U_t| = 1e-2 N exceeds the Coulomb cap mu m g / 4 per point down to
    |U_t| = 1.2e-4 m/s). While it slides, the tangential force of every point is mu times its normal
    force, so over any window T, Delta v_x = -mu (g T + Delta v_z): an identity of the integrator, to
    round-off (measured 1.2e-15 relative; bound 1e-12). The friction torque pitches the cube (the points
    share the deepest overlap, so only tilting can balance it: it rocks on 4 and 2 points, sometimes
    leaving the floor), whence a small Delta v_z: the mean deceleration is mu g to 0.4 % (measured 0.38 %
    over 7 ms, 35 mm/s lost; bound 1 %)."""
    sim = _sim("descantes", 0.001 - STATIC, vx=0.05, steps=500)
    v1 = sim.atom.local("v")[0].copy()
    sim.run(3500)
    v2 = sim.atom.local("v")[0].copy()
    T = 3500 * 2e-6
    assert v2[0] > 0.01                                  # still sliding
    dvx, dvz = v2[0] - v1[0], v2[2] - v1[2]
    assert dvx == pytest.approx(-0.5 * (G * T + dvz), rel=1e-12)
    assert -dvx / T == pytest.approx(0.5 * G, rel=0.01)
    assert v2[1] == pytest.approx(0.0, abs=1e-18)       # no sideways drift (round-off only)


def test_law_keyword():
    """`law` takes grains3d, descantes or volume on both wall fixes; Descantes' law keeps no history (no spring)."""
    with pytest.raises(dem.errors.DemError, match="law must be grains3d or descantes or volume, got 'hertz'"):
        _sim("hertz", 0.002)
    sim = _sim("descantes", 0.002, friction="mu 0.5 gamma_t 1e4 ks 2e4")
    assert not sim.modify.find("floor").use_history
    assert _sim("grains3d", 0.002, friction="mu 0.5 gamma_t 1e4 ks 2e4").modify.find("floor").use_history
    with pytest.raises(dem.errors.DemError, match="law must be grains3d or descantes"):
        dem.Simulation(screen=False).commands(BOX.split("fix floor")[0].format(
            z=0.002, vx=0.0, vz=0.0, gravity="") + "fix drum all wall/drum y 0 0 0.004 law rigid\n")
    sim = dem.Simulation(screen=False)
    sim.commands(BOX.split("fix floor")[0].format(z=0.0, vx=0.0, vz=0.0, gravity="") +
                 "fix drum all wall/drum y 0 0 0.004 rpm 10 point multipoint law descantes kn 1e5 en 0.5\n"
                 "timestep 2e-6\nrun 1\n")
    assert sim.modify.find("drum").contact_law == "descantes"


def test_beta_t_is_a_fraction_of_critical_damping():
    """`beta_t B` adds 2 B sqrt(kn m_ij) to nu_t (Descantes 2022 Table 2: gamma_t = gamma_n critical is
    beta_t 1 with en 0). A cube 1 um into the floor (4 points) sliding at 1 mm/s, mu 10 (far from the
    Coulomb cap), no gravity: the floor's tangential force is -2 sqrt(kn m) v_x in total (the points share
    it 1/4 each), the same as gamma_t = sqrt(kn / m) to round-off (different arithmetic: bound 1e-14)."""
    def fx(friction):
        sim = _sim("descantes", 0.001 - 1e-6, vx=1e-3, en=0.0, friction=friction, gravity=False)
        sim.atom.local("f")[:] = 0.0
        sim.modify.find("floor").compute(False)
        return sim.atom.local("f")[0, 0]
    critical = 2 * np.sqrt(1e5 * M) * 1e-3
    assert fx("mu 10 beta_t 1") == pytest.approx(-critical, rel=1e-14)
    assert fx(f"mu 10 gamma_t {float(np.sqrt(1e5 / M))!r}") == pytest.approx(-critical, rel=1e-14)
    assert fx("mu 10 beta_t 0.5 gamma_t 1e3") == pytest.approx(-0.5 * critical - 2e3 * M * 1e-3, rel=1e-14)
