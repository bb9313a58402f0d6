"""`model hertz` on shaped bodies: R* from the spheres of equal volume, R_i = (3 V_i / 4 pi)^(1/3).

Head-on impacts that keep the bodies from turning (faces parallel, or tips on the line of centres), so
that the overlap is the relative displacement and the Hertz closed form of test_hertz.py holds with
R* = R_eq / 2, m* = m / 2 (two equal bodies) or R* = R_eq, m* = m (a wall):
    delta_max = (15 m* v^2 / (16 Y* sqrt(R*)))^(2/5),   t_c = 2 I delta_max / v,
    I = Gamma(7/5) sqrt(pi) / Gamma(9/10).
Several contact points (polyhedron face on face: 4; a cube on a wall with `point multipoint`: 4) each carry their weight of the one Hertz force at the shared overlap, so the
closed form is that of one equivalent sphere. Tolerances as in test_hertz.py: the contact time is counted
in whole steps (STEPS per contact: +-2 steps), the overlap is leap-frog's to O((dt/t_c)^2) (1e-4), the
rebound speed is en to 1e-3.
"""
import math

import numpy as np
import pytest

import dem

RHO, E, NU, V = 2500.0, 1e7, 0.3, 1.0
YSTAR = E / (2.0 * (1.0 - NU * NU))
STEPS = 1000
A = 0.008                                  # cube edge (m)
ELL = (0.006, 0.004, 0.003)                # ellipsoid semi-axes, the first along the line of impact
RG = 0.003                                 # two glued spheres of this radius touching on the x axis


def closed_form(meff, reff, v):
    dmax = (15.0 * meff * v * v / (16.0 * YSTAR * math.sqrt(reff))) ** 0.4
    return dmax, 2.0 * math.gamma(1.4) * math.sqrt(math.pi) / math.gamma(0.9) * dmax / v


def law(en):
    return f"model hertz E {E} nu {NU} en {en} mu 0.3"


# case -> (volume of one body, its half length along x, the commands that set it up)
CASES = {
    "polyhedron pair": (A ** 3, A / 2, """shape c cube {A}
pair_style polyhedron/multipoint
pair_coeff * * {law}
create_atoms 1 single {xa} 0 0 shape c density {RHO}
create_atoms 1 single {xb} 0 0 shape c density {RHO}
"""),
    "convex pair": (4 / 3 * math.pi * ELL[0] * ELL[1] * ELL[2], ELL[0], """shape e ellipsoid {ELL[0]} {ELL[1]} {ELL[2]}
pair_style convex/gjk
pair_coeff * * {law}
create_atoms 1 single {xa} 0 0 shape e density {RHO}
create_atoms 1 single {xb} 0 0 shape e density {RHO}
"""),
    "glued pair": (8 / 3 * math.pi * RG ** 3, 2 * RG, """shape g multisphere {RG} 0 0 {RG} -{RG} 0 0 {RG}
pair_style glued/convex
pair_coeff * * {law}
create_atoms 1 single {xa} 0 0 shape g density {RHO}
create_atoms 1 single {xb} 0 0 shape g density {RHO}
"""),
    "polyhedron wall": (A ** 3, A / 2, """shape c cube {A}
pair_style polyhedron/multipoint
pair_coeff * * kn 1 en 1
create_atoms 1 single {xb} 0 0 shape c density {RHO}
fix wall all wall/plane xplane 0 NULL point multipoint {law}
"""),
}


def impact(case, en=1.0):
    """Head-on impact at V along x; returns (contact time, largest overlap, relative speed after / V,
    |omega| max, m*, R*)."""
    volume, half, setup = CASES[case]
    wall = "wall" in case
    m = RHO * volume
    req = (0.75 * volume / math.pi) ** (1 / 3)
    meff, reff = (m, req) if wall else (0.5 * m, 0.5 * req)
    dt = closed_form(meff, reff, V)[1] / STEPS
    gap = 1e-7
    xa, xb = (-half - gap, half + gap) if not wall else (None, half + gap)
    sim = dem.Simulation(screen=False)
    sim.commands(f"""boundary f f f
region box block -0.05 0.05 -0.05 0.05 -0.05 0.05
create_box 1 box
""" + setup.format(A=A, ELL=ELL, RG=RG, RHO=RHO, law=law(en), xa=xa, xb=xb) +
                 f"fix 1 all nve/shape\ntimestep {dt!r}\nthermo 0\nrun 0\n")
    v = sim.atom.local("v")
    order = np.argsort(sim.atom.local("tag"))
    if wall:
        v[:] = [[-V, 0.0, 0.0]]
    else:
        v[order] = [[0.5 * V, 0.0, 0.0], [-0.5 * V, 0.0, 0.0]]
    counter = sim.modify.find("wall") if wall else sim.pair
    steps_in, dmax, wmax = 0, 0.0, 0.0
    for _ in range(int(1.6 * STEPS)):
        sim.run(1)
        x = sim.atom.local("x")[np.argsort(sim.atom.local("tag"))]
        d = half - x[0, 0] if wall else 2 * half - (x[1, 0] - x[0, 0])
        dmax = max(dmax, d)
        wmax = max(wmax, float(np.abs(sim.atom.local("omega")).max()))
        steps_in += bool(counter.ncontacts)
    assert steps_in < 1.5 * STEPS                  # the contact has ended
    v = sim.atom.local("v")[np.argsort(sim.atom.local("tag"))]
    after = v[0, 0] / V if wall else (v[1, 0] - v[0, 0]) / V
    sim.close()
    return steps_in * dt, dmax, after, wmax, meff, reff


@pytest.mark.parametrize("case", list(CASES))
def test_elastic_impact_of_shaped_bodies_is_the_hertz_impact_of_equal_volume_spheres(case):
    t, d, after, wmax, meff, reff = impact(case)
    dmax, tc = closed_form(meff, reff, V)
    assert wmax < 1e-9                              # nothing turned: the overlap is the displacement
    assert abs(t - tc) <= 2 * tc / STEPS, (t, tc)
    assert abs(d / dmax - 1) < 1e-4, (d, dmax)
    # R* of the bounding spheres (the other obvious choice) would be caught: delta_max ~ R*^(-1/5)
    assert abs(d / (dmax * 1.1 ** -0.2) - 1) > 1e-2
    assert abs(after - 1) < 1e-6


@pytest.mark.parametrize("case", ["polyhedron pair", "polyhedron wall", "glued pair"])
def test_restitution_of_shaped_bodies_is_the_requested_en(case):
    after = impact(case, en=0.5)[2]
    assert abs(after - 0.5) < 1e-3, after
