"""`damping tsuji` (dem/law/damping.pxd; Tsuji, Tanaka & Ishida, Powder Technol. 71 (1992) 239, as LAMMPS's
`pair granular ... damping tsuji`): gamma_n = alpha(en) sqrt(kn m*), kn the normal part's stiffness (4/3 Y* a
for Hertz, kn for Hooke), alpha Tsuji's polynomial of en, and the tangential dashpot nu_t = gamma_n.

Closed forms. With Hertz, m* x'' = -4/3 Y* sqrt(R*) x^(3/2) - alpha sqrt(m* 4/3 Y* sqrt(R*)) x^(1/4) x' scales
to s'' = -s^(3/2) - alpha s^(1/4) s': the restitution depends on alpha alone, not on the impact speed, and is
    e = exp(-pi alpha / sqrt(5 - alpha^2))
(damping hertz is this dashpot with alpha = sqrt(5) beta(en) and gives en, docs/hertz.md; scipy, rtol 1e-13,
agrees to 1e-12). With Hooke it is a linear oscillator of damping ratio alpha / 2:
e = exp(-pi alpha / sqrt(4 - alpha^2)). Neither is en: Tsuji's polynomial fits the restitution of the dashpot
alpha sqrt(2 m* kn) (m = 2 m*, the mass of one of two equal spheres), which it gives to 1.1e-3 for en in
[0.1, 1]; with the reduced mass, as LAMMPS defines the part and dem follows, en 0.3, 0.5, 0.9 rebound at
0.440, 0.616, 0.928 (LAMMPS measures the same, test_tsuji_restitution_is_lammps).

Tolerances. Leap-frog at 1000 steps per contact: dem's restitution differs from the closed form by 1.4e-5 to
4.8e-5 at 500, 1000 and 2000 steps (the end of the contact, where the dashpot ~ x^(1/4) outweighs the spring,
falls between steps), so 1e-4. At a fixed number of steps per contact, runs at different speeds are one
dimensionless run: measured spread 2e-7, tolerance 1e-5."""
import math

import numpy as np
import pytest

import dem
import dem.law
from dem.law import hertz
from lammps_runner import lammps_run, require_lammps, result

R, RHO, E, NU, KN = 0.005, 2500.0, 1e7, 0.3, 1e4
M = RHO * 4.0 / 3.0 * math.pi * R ** 3
YSTAR = E / (2.0 * (1.0 - NU * NU))
STEPS = 1000


def alpha(en):
    """Tsuji's polynomial, written here from the paper's fit (as LAMMPS's documentation gives it)."""
    return (1.2728 - 4.2783 * en + 11.087 * en ** 2 - 22.348 * en ** 3 + 27.467 * en ** 4 - 18.022 * en ** 5
            + 4.8218 * en ** 6)


def closed_form(a, normal="hertz"):
    return math.exp(-math.pi * a / math.sqrt((4.0 if normal == "hooke" else 5.0) - a * a))


def contact_time(normal, meff, v):
    """The contact's duration, to set about STEPS steps in it (Hooke: the damped half period)."""
    if normal == "hooke":
        return math.pi / math.sqrt(KN / meff)
    return hertz.contact_time(YSTAR, meff, 0.5 * R, v)


def impact(en, v, normal="hertz", wall=False, steps=STEPS):
    """A head-on impact at relative speed v of two equal spheres (or of one on a wall/plane): the restitution."""
    law = f"model hertz E {E} nu {NU}" if normal == "hertz" else f"kn {KN}"
    meff = M if wall else 0.5 * M
    dt = contact_time(normal, meff, v) / steps
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
boundary f f f
region box block -0.05 0.05 -0.05 0.05 -0.05 0.05
create_box 1 box
pair_style sphere
pair_coeff * * {law} en {en} mu 0 damping tsuji
""")
    if wall:
        sim.commands(f"create_atoms 1 single 0 0 {R + 1e-9!r} radius {R} density {RHO}\n"
                     f"fix wall all wall/plane zplane 0 NULL")
        sim.atom.local("v")[:] = [[0, 0, -v]]
    else:
        sim.commands(f"create_atoms 1 single {-R - 1e-9!r} 0 0 radius {R} density {RHO}\n"
                     f"create_atoms 1 single {R + 1e-9!r} 0 0 radius {R} density {RHO}")
        sim.atom.local("v")[:] = [[0.5 * v, 0, 0] if t == 1 else [-0.5 * v, 0, 0] for t in sim.atom.local("tag")]
    sim.commands(f"fix 1 all nve/sphere\ntimestep {dt!r}\nthermo 0")
    sim.run(int(2.5 * steps))
    vel = sim.atom.local("v")[np.argsort(sim.atom.local("tag"))]
    assert np.all(vel[:, 1:] == 0) if not wall else np.all(vel[:, :2] == 0)
    return vel[0, 2] / v if wall else (vel[1, 0] - vel[0, 0]) / v


def test_the_polynomial_is_tsujis_fit_with_the_mass_of_one_sphere():
    """dem.law.tsuji_alpha is the polynomial above; with the dashpot alpha sqrt(2 m* kn) its restitution is
    en to 1.1e-3 over [0.1, 1] (1.4e-2 at en 0: the fit's end), which a wrong coefficient would miss."""
    en = np.linspace(0.1, 1.0, 91)
    a = np.array([dem.law.tsuji_alpha(e) for e in en])
    assert np.allclose(a, alpha(en), rtol=0, atol=1e-14)      # summed in another order
    fit = np.array([closed_form(math.sqrt(2) * x) for x in a])
    assert np.max(np.abs(fit - en)) < 1.1e-3, np.max(np.abs(fit - en))


@pytest.mark.parametrize("en", [0.3, 0.5, 0.9])
def test_hertz_restitution_is_the_closed_form_at_every_speed(en):
    e = [impact(en, v) for v in (0.1, 1.0, 3.0)]
    assert max(e) - min(e) < 1e-5, e
    assert abs(e[1] - closed_form(alpha(en))) < 1e-4, (e, closed_form(alpha(en)))


def test_on_a_wall_and_with_hooke():
    """A wall contact (m* = m) and `normal hooke` (allowed, as LAMMPS allows it). Hooke's dashpot does not
    vanish at the end of the contact: the step that crosses it carries up to gamma_n v dt of impulse that
    belongs to no contact, alpha pi / STEPS of the speed (1.1e-3); measured 2e-5 to 2.7e-4 at 500 to 8000
    steps (it depends on where the last step falls), tolerance alpha pi / STEPS."""
    assert abs(impact(0.5, 1.0, wall=True) - closed_form(alpha(0.5))) < 1e-4
    e = impact(0.5, 1.0, normal="hooke")
    assert abs(e - closed_form(alpha(0.5), "hooke")) < alpha(0.5) * math.pi / STEPS, (
        e, closed_form(alpha(0.5), "hooke"))
    assert abs(closed_form(alpha(0.5), "hooke") - closed_form(alpha(0.5))) > 0.03    # the two laws differ


def test_dashpots_are_alpha_sqrt_kn_mstar_normal_and_tangential():
    """Two overlapping Hooke spheres moving apart and sliding, at rest otherwise: the force on sphere 1 is
    kn delta + gamma_n U_rn along n and -gamma_n U_rt across (nu_t = gamma_n, uncapped: mu 10), to round-off."""
    delta, un, ut = 1e-5, 0.02, 0.3
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
boundary f f f
region box block -0.05 0.05 -0.05 0.05 -0.05 0.05
create_box 1 box
create_atoms 1 single {-R + 0.5 * delta!r} 0 0 radius {R} density {RHO}
create_atoms 1 single {R - 0.5 * delta!r} 0 0 radius {R} density {RHO}
pair_style sphere
pair_coeff * * kn {KN} en 0.5 mu 10 damping tsuji
fix 1 all nve/sphere
timestep 1e-7
thermo 0
""")
    tags = sim.atom.local("tag")
    sim.atom.local("v")[:] = [[-0.5 * un, 0.5 * ut, 0] if t == 1 else [0.5 * un, -0.5 * ut, 0] for t in tags]
    sim.run(0)
    f = sim.atom.local("f")[np.argsort(tags)][0]
    g = alpha(0.5) * math.sqrt(KN * 0.5 * M)
    # n points from sphere 2 to sphere 1 (-x); sphere 1 moves away along n at un and across at ut
    assert math.isclose(f[0], -(KN * delta - g * un), rel_tol=1e-12), (f, KN * delta - g * un)
    assert math.isclose(f[1], -g * ut, rel_tol=1e-12), (f, -g * ut)


LAMMPS_PAIR = """units si
atom_style sphere
atom_modify map array
boundary f f f
region box block -0.05 0.05 -0.05 0.05 -0.05 0.05
create_box 1 box
create_atoms 1 single -${x} 0 0
create_atoms 1 single ${x} 0 0
set group all diameter ${d}
set group all density ${rho}
pair_style granular
pair_coeff * * hertz/material ${E} ${en} ${nu} damping tsuji tangential linear_nohistory 0 0
comm_modify vel yes
neighbor 0.001 bin
set atom 1 vx ${vh}
set atom 2 vx -${vh}
fix 1 all nve/sphere
timestep ${dt}
run ${n}
print "RESULT $(vx[1]:%.15g) $(vx[2]:%.15g)"
"""


@pytest.mark.parametrize("en", [0.3, 0.5, 0.9])
def test_tsuji_restitution_is_lammps(en, tmp_path):
    """The same impact in LAMMPS's pair granular (hertz/material, damping tsuji, no friction) at the same
    time step: both integrate with the same leap-frog, and they agree to round-off (measured 4e-15 at en 0.3,
    0.5, 0.9 and 0.1, 1, 3 m/s); tolerance 1e-10, far below the 0.03-0.14 between en and either."""
    require_lammps()
    v = 1.0
    dt = contact_time("hertz", 0.5 * M, v) / STEPS
    out = lammps_run(LAMMPS_PAIR, str(tmp_path), dict(x=R + 1e-9, d=2 * R, rho=RHO, E=E, en=en, nu=NU, vh=0.5 * v,
                                                      dt=dt, n=int(2.5 * STEPS)))
    v1, v2 = result(out)
    e_lammps = (v2 - v1) / v
    e_dem = impact(en, v)
    assert abs(e_lammps - e_dem) < 1e-10, (e_lammps, e_dem, closed_form(alpha(en)))
