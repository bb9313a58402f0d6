"""Twisting friction (`twisting sds|marshall`, dem/law/twisting.pxd; Marshall, J. Comput. Phys. 228 (2009)
1541, as LAMMPS's pair granular) against its closed forms.

A sphere resting on a floor at its static Hertz overlap delta0 = (3 m g / (4 Y* sqrt(R)))^(2/3) and spun
about the normal (z) feels no force from the spin (the contact point is on the axis): the twisting torque
is its only torque. Below the cap that is a torsional oscillator,
    I theta'' = -k_tw theta - gamma_tw theta',   I = 2/5 m r^2,
whose spin follows omega0 e^(-z w0 t) (cos(wd t) - z / sqrt(1 - z^2) sin(wd t)), w0^2 = k_tw / I,
z = gamma_tw / (2 sqrt(k_tw I)); the incremental spring (xi += omega dt, the stored spin half a step ahead of
the angle, as rolling epsd's) is leap-frog: undamped error O((w0 dt)^2), measured 4e-6 omega0 at w0 dt =
3e-3 (sds), 4e-8 at 4e-4 (marshall); the dashpot reads the same stored spin, a first-order error of about
z w0 dt (measured 5.6e-4 omega0 at z 0.3). Tolerance 1e-3 omega0, as tests/test_rolling_epsd.py.
Above the cap the spring holds mu_tw m g: the spin falls linearly at mu_tw m g / I (measured to 1.6e-12,
sds, and 1.1e-11, marshall; tolerance 1e-6).
Marshall's coefficients are the tangential part's over the contact disc: with Mindlin kt = 8 G* a,
k_tw = kt a^2 / 2 = 4 G* a^3, mu_tw = 2/3 mu a, a = sqrt(R delta0); with Hooke and ks, k_tw = ks a^2 / 2 with
the geometric a = sqrt(R m g / kn)."""
import math

import numpy as np
import pytest

import dem
import dem.law
from lammps_runner import lammps_run, require_lammps
from test_rolling_epsd import bonded_jkr_pair, oscillator

R, RHO, E, NU, G = 0.002, 2500.0, 1e7, 0.3, 9.81
M = RHO * 4.0 / 3.0 * math.pi * R ** 3
I = 0.4 * M * R * R
YSTAR = E / (2 * (1 - NU * NU))
GSTAR = E / (2 * (1 + NU)) / (2 * (2 - NU))
DELTA0 = (3 * M * G / (4 * YSTAR * math.sqrt(R))) ** (2.0 / 3.0)
A0 = math.sqrt(R * DELTA0)


def spinning_on_floor(law, omega0, dt, delta0=DELTA0, g=G):
    """A sphere resting on a floor of its own material at overlap delta0, spun about z at omega0."""
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
boundary f f f
region box block -0.01 0.01 -0.01 0.01 0 0.01
create_box 1 box
create_atoms 1 single 0 0 {R - delta0!r} radius {R} density {RHO}
pair_style sphere
pair_coeff * * {law}
fix floor all wall/plane zplane 0 NULL
fix g all gravity {g} vector 0 0 -1
fix 1 all nve/sphere
timestep {dt!r}
thermo 0
""")
    sim.atom.local("omega")[0] = [0, 0, omega0]
    return sim


def follow(sim, k, c, omega0, dt, quarters=8):
    """The largest distance of the spin from the oscillator over `quarters` quarter periods."""
    period = 2 * math.pi / math.sqrt(k / I)
    sim.run(0)
    t, worst = 0.0, 0.0
    for _ in range(quarters):
        n = int(0.25 * period / dt)
        sim.run(n)
        t += n * dt
        worst = max(worst, abs(sim.atom.local("omega")[0, 2] - oscillator(omega0, k, c, I, t + 0.5 * dt)))
    assert np.allclose(sim.atom.local("omega")[0, :2], 0.0) and np.allclose(sim.atom.local("v")[0, :2], 0.0)
    return worst


def slope(sim, dt, first=1000, steps=200):
    """The spin's rate of change once the spring has reached its cap (after `first` steps)."""
    sim.run(first)
    w1 = sim.atom.local("omega")[0, 2]
    sim.run(steps)
    return (sim.atom.local("omega")[0, 2] - w1) / (steps * dt)


HERTZ = f"model hertz E {E} nu {NU}"


@pytest.mark.parametrize("z", [0.0, 0.3])
def test_sds_spring_and_dashpot(z):
    omega0, dt = 0.1, 1e-6
    k = I * 3000.0 ** 2                        # w0 = 3000 rad/s
    c = z * 2 * math.sqrt(k * I)
    mu = 1e-3
    assert math.sqrt(k * I) * omega0 < 0.5 * mu * M * G          # below the cap all along
    sim = spinning_on_floor(f"{HERTZ} en 1 mu 0.5 twisting sds k_twist {k!r} gamma_twist {c!r} mu_twist {mu}",
                            omega0, dt)
    worst = follow(sim, k, c, omega0, dt)
    assert worst < 1e-3 * omega0, worst


def test_sds_slides_at_the_cap_with_a_constant_torque():
    """A Coulomb twisting torque: the spin falls linearly at mu_twist m g / I."""
    k, mu, omega0, dt = I * 3000.0 ** 2, 1e-4, 50.0, 1e-6
    sim = spinning_on_floor(f"{HERTZ} en 0.5 mu 0.5 twisting sds k_twist {k!r} gamma_twist 0 mu_twist {mu}",
                            omega0, dt)
    rate = slope(sim, dt)
    assert abs(rate / (-mu * M * G / I) - 1) < 1e-6, (rate, -mu * M * G / I)


def test_marshall_with_mindlin_is_a_spring_of_4_gstar_a3():
    omega0, dt = 0.1, 5e-6                     # w0 dt = 4e-4: a soft spring (period 0.07 s)
    k = 4 * GSTAR * A0 ** 3
    assert math.sqrt(k * I) * omega0 < 0.5 * 2 / 3 * 0.5 * A0 * M * G
    sim = spinning_on_floor(f"{HERTZ} en 1 mu 0.5 twisting marshall", omega0, dt)
    worst = follow(sim, k, 0.0, omega0, dt, quarters=4)
    assert worst < 1e-3 * omega0, worst
    # the tangential spring alone (kt a^2, twice k) would be caught: its period is sqrt(2) shorter
    assert abs(oscillator(omega0, 2 * k, 0.0, I, 0.25 * 2 * math.pi / math.sqrt(k / I))) > 0.1 * omega0


def test_marshall_slides_at_two_thirds_mu_a_load():
    mu, omega0, dt = 0.5, 50.0, 1e-6
    sim = spinning_on_floor(f"{HERTZ} en 0.5 mu {mu} twisting marshall", omega0, dt)
    rate = slope(sim, dt)
    expected = -2.0 / 3.0 * mu * A0 * M * G / I
    assert abs(rate / expected - 1) < 1e-6, (rate, expected)


@pytest.mark.parametrize("z", [0.0, 0.3])
def test_marshall_with_hooke_takes_the_geometric_contact_radius(z):
    """Hooke has no contact radius of its own: a = sqrt(R* delta), as LAMMPS; k_tw = ks a^2 / 2 and, from the
    tangential dashpot of damping restitution nu_t = 2 gamma_t m, gamma_tw = nu_t a^2 / 2 = gamma_t m a^2."""
    kn, ks, omega0, dt = 1e4, 3e4, 0.1, 2e-6
    delta0 = M * G / kn
    a = math.sqrt(R * delta0)
    k = 0.5 * ks * a * a
    c = z * 2 * math.sqrt(k * I)
    sim = spinning_on_floor(f"kn {kn} en 0.5 mu 0.5 ks {ks} gamma_t {c / (M * a * a)!r} twisting marshall", omega0,
                            dt, delta0=delta0)
    worst = follow(sim, k, c, omega0, dt, quarters=4)
    assert worst < 1e-3 * omega0, worst


def test_between_two_spheres_both_turn():
    """Two JKR spheres bonded at zero net load (the cap mu_twist |F_n + 2 F_c| = mu_twist 3 pi w R*) spun in
    opposite senses about their line of centres: the relative spin is an oscillator of inertia I / 2, and the
    torques are equal and opposite (the total spin stays zero)."""
    r, rho, w, omega0, dt = 1e-4, 2500.0, 0.05, 20.0, 2e-7
    m = rho * 4.0 / 3.0 * math.pi * r ** 3
    inertia = 0.4 * m * r * r
    rs = 0.5 * r
    k = inertia * 2000.0 ** 2
    mu = 1e-4
    assert math.sqrt(2 * k * inertia) * omega0 < 0.5 * mu * 3 * math.pi * w * rs
    sim, _ = bonded_jkr_pair(r, rho, E, NU, w, dt, f"twisting sds k_twist {k!r} gamma_twist 0 mu_twist {mu}")
    sim.atom.local("omega")[:] = [[omega0, 0, 0] if t == 1 else [-omega0, 0, 0] for t in sim.atom.local("tag")]
    sim.run(0)
    period = 2 * math.pi / math.sqrt(2 * k / inertia)
    t, worst = 0.0, 0.0
    for _ in range(8):
        n = int(0.25 * period / dt)
        sim.run(n)
        t += n * dt
        om = sim.atom.local("omega")[np.argsort(sim.atom.local("tag"))]
        worst = max(worst, abs(om[0, 0] - om[1, 0] - oscillator(2 * omega0, k, 0.0, 0.5 * inertia, t + 0.5 * dt)))
        assert abs(om[0, 0] + om[1, 0]) < 1e-12 * omega0
    assert worst < 1e-3 * 2 * omega0, worst
    assert sim.pair.ncontacts == 1


def test_history_layout_puts_the_twist_after_the_rolling_spring():
    law = dem.law
    rows = np.array([law.row(law.parse(line.split(), "pc")) for line in (
        "kn 1e5 en 0.5 mu 0.3 ks 1e4 rolling epsd2 mu_roll 0.1",
        "kn 1e5 en 0.5 mu 0.3 twisting sds k_twist 1e-3 gamma_twist 0 mu_twist 1e-4",
        f"normal jkr E {E} nu {NU} w 0.05 en 0.5 mu 0.3 twisting marshall",
        "kn 1e5 en 0.5 mu 0.3")])
    assert law.prepare(rows) == law.XI_WIDTH + law.ROLL_WIDTH + law.TWIST_WIDTH + law.BOND_WIDTH
    assert list(rows[:, law.H_TWIST]) == [-1, 6, 6, -1] and list(rows[:, law.H_BOND]) == [-1, -1, 7, -1]
    assert list(rows[:, law.TWISTING]) == [0, law.PARTS["twisting"]["sds"], law.PARTS["twisting"]["marshall"], 0]
    assert law.prepare(rows[[0, 3]]) == law.XI_WIDTH + law.ROLL_WIDTH    # no twist row: no twist angle


LAMMPS_FLOOR = """units si
atom_style sphere
atom_modify map array
boundary f f f
region box block -0.01 0.01 -0.01 0.01 0 0.01
create_box 1 box
create_atoms 1 single 0 0 ${z}
set group all diameter ${d}
set group all density ${rho}
pair_style granular
pair_coeff * * hertz/material ${E} 0 ${nu} damping velocity tangential linear_history ${kt} 0 ${mu} twisting TWIST
fix floor all wall/gran granular hertz/material ${E} 0 ${nu} damping velocity &
    tangential linear_history ${kt} 0 ${mu} twisting TWIST zplane 0 NULL
comm_modify vel yes
fix g all gravity ${g} vector 0 0 -1
set atom 1 omega 0 0 ${omega0}
fix 1 all nve/sphere
timestep ${dt}
run ${n}
write_dump all custom final.txt omegaz tqz z modify format float %.17g
"""


@pytest.mark.parametrize("twist", ["marshall", "sds"])
@pytest.mark.parametrize("omega0", [0.1, 50.0])
def test_twisting_is_lammps(twist, omega0, tmp_path):
    """The sphere on the floor in LAMMPS (fix wall/gran granular: hertz/material, no damping, a linear
    tangential spring kt, twisting marshall or sds) and in dem (model hertz en 1, tangential spring ks kt):
    the spin after 3000 steps, below the cap (omega0 0.1: a tenth of marshall's period, 1.4 of sds's) and
    sliding at it (omega0 50). LAMMPS's velocity Verlet keeps the spin at whole steps, dem's leap-frog half
    a step on: LAMMPS's is moved on by its torque dt / 2I. Measured to agree to 4e-13 omega0 (the same
    integration); tolerance 1e-10 omega0."""
    require_lammps()
    kt, mu, dt, n = 3e3, 0.5, 1e-6, 3000
    sds = f"sds {I * 3000.0 ** 2!r} 0 1e-4"
    lammps_run(LAMMPS_FLOOR.replace("TWIST", sds if twist == "sds" else "marshall"), str(tmp_path), dict(
        z=R - DELTA0, d=2 * R, rho=RHO, E=E, nu=NU, kt=kt, mu=mu, g=G, omega0=omega0, dt=dt, n=n))
    w, tq, z_lammps = np.loadtxt(tmp_path / "final.txt", skiprows=9)
    w_lammps = w + tq * dt / (2 * I)            # LAMMPS's spin half a step on, where dem's stands
    words = "marshall" if twist == "marshall" else sds.replace("sds", "sds k_twist", 1).replace(
        " 0 ", " gamma_twist 0 mu_twist ")
    sim = spinning_on_floor(f"{HERTZ} en 1 mu {mu} tangential spring ks {kt} twisting {words}", omega0, dt)
    sim.run(n)
    w_dem = sim.atom.local("omega")[0, 2]
    assert abs(w_dem - w_lammps) < 1e-10 * omega0, (w_dem, w_lammps)
    assert abs(w_dem - omega0) > 1e-3 * omega0          # the twist acted (0.7 % at least)
    assert sim.atom.local("x")[0, 2] == z_lammps        # and nothing else moved the sphere differently
