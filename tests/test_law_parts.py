"""The law in parts (dem/law): materials per type mixed per pair, a wall of its own type, the history a
table lays out, and every bad line a clear error naming it.

Mixed materials against the Hertz closed form (written here from the textbook, as tests/test_hertz.py):
1 / Y* = (1 - nu_1^2) / E_1 + (1 - nu_2^2) / E_2, delta_max = (15 m* v^2 / (16 Y* sqrt(R*)))^(2/5),
t_c = 2.8682 (m*^2 / (R* Y*^2 v))^(1/5); elastic impacts resolved with 1000 steps: overlap to ~1e-6
(tolerance 1e-4), contact time counted in whole steps (tolerance 2 steps)."""
import math

import numpy as np
import pytest

import dem
import dem.law

R, RHO, V, STEPS = 0.005, 2500.0, 1.0, 1000
M = RHO * 4.0 / 3.0 * math.pi * R ** 3
MATERIALS = {1: (1e7, 0.3), 2: (5e7, 0.2), 3: (2e8, 0.45)}     # type: (E, nu)


def ystar(*types):
    return 1.0 / sum((1 - MATERIALS[t][1] ** 2) / MATERIALS[t][0] for t in types)


def closed_form(ys, meff, reff, v):
    dmax = (15.0 * meff * v * v / (16.0 * ys * math.sqrt(reff))) ** 0.4
    return dmax, 2.0 * math.gamma(1.4) * math.sqrt(math.pi) / math.gamma(0.9) * dmax / v


MATERIAL_LINES = "\n".join(f"pair_coeff {t} {t} model hertz E {e} nu {nu} en 1 mu 0"
                           for t, (e, nu) in MATERIALS.items()) + """
pair_coeff 1 2 model hertz en 1 mu 0
pair_coeff 1 3 normal hertz en 1 mu 0
pair_coeff 2 3 model hertz en 1 mu 0
"""


def impact(case):
    """Type 1 hitting type 2 (pair) or a wall of type 3: (contact time, largest overlap, closed forms)."""
    ys = ystar(1, 2) if case == "pair" else ystar(1, 3)
    meff, reff = (0.5 * M, 0.5 * R) if case == "pair" else (M, R)
    dmax, tc = closed_form(ys, meff, reff, V)
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
boundary f f f
region box block -0.05 0.05 -0.05 0.05 0 0.05
create_box 3 box
pair_style sphere
{MATERIAL_LINES}
""")
    if case == "pair":
        sim.commands(f"""
create_atoms 1 single {-R - 1e-6!r} 0 0.02 radius {R} density {RHO}
create_atoms 2 single {R + 1e-6!r} 0 0.02 radius {R} density {RHO}
""")
        sim.atom.local("v")[:] = [[0.5 * V, 0, 0] if t == 1 else [-0.5 * V, 0, 0] for t in sim.atom.local("type")]
    else:
        sim.commands(f"""
create_atoms 1 single 0 0 {R + 1e-6!r} radius {R} density {RHO}
fix wall all wall/plane zplane 0 NULL type 3
""")
        sim.atom.local("v")[:] = [[0, 0, -V]]
    sim.commands(f"fix 1 all nve/sphere\ntimestep {tc / STEPS!r}\nthermo 0")
    sim.run(0)
    counter = sim.modify.find("wall") if case == "wall" else sim.pair
    steps_in, dmin = 0, np.inf
    for _ in range(int(1.6 * STEPS)):
        sim.run(1)
        x = sim.atom.local("x")
        gap = abs(x[1, 0] - x[0, 0]) - 2 * R if case == "pair" else x[0, 2] - R
        dmin = min(dmin, gap)
        steps_in += bool(counter.ncontacts)
    return steps_in * tc / STEPS, -dmin, tc, dmax


@pytest.mark.parametrize("case", ["pair", "wall"])
def test_impact_of_two_materials_has_the_mixed_hertz_contact(case):
    t, d, tc, dmax = impact(case)
    assert abs(t - tc) <= 2 * tc / STEPS, (t, tc)
    assert abs(d / dmax - 1) < 1e-4, (d, dmax)
    # one material for both would be caught: type 1's alone moves the overlap by > 10 %
    ys1 = ystar(1, 1)
    assert abs(closed_form(ys1, 0.5 * M, 0.5 * R, V)[0] / dmax - 1) > 0.1


def test_mixed_rows_history_layout_and_plans():
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
boundary f f f
region box block 0 1 0 1 0 1
create_box 3 box
pair_style sphere
{MATERIAL_LINES}
pair_coeff 3 3 normal jkr E 2e8 nu 0.45 w 0.1 en 0.5 mu 0.4 rolling epsd mu_roll 0.1 eta_roll 0.3
pair_coeff 1 1 normal jkr E 1e7 nu 0.3 w 0.4 en 0.5 mu 0.4
pair_coeff 1 3 normal jkr en 0.5 mu 0.4
create_atoms 1 single 0.5 0.5 0.5 radius 0.01 density 2500
""")
    sim.pair.init()
    table, law = sim.pair.table, dem.law
    e1, nu1 = MATERIALS[1]
    e2, nu2 = MATERIALS[2]
    g1, g2 = e1 / (2 * (1 + nu1)), e2 / (2 * (1 + nu2))
    assert math.isclose(table[1, 2, law.YSTAR], ystar(1, 2), rel_tol=1e-14)
    assert math.isclose(table[2, 1, law.GSTAR], 1 / ((2 - nu1) / g1 + (2 - nu2) / g2), rel_tol=1e-14)
    assert math.isclose(table[1, 3, law.W], math.sqrt(0.4 * 0.1), rel_tol=1e-14)   # Berthelot
    assert table[1, 3, law.NORMAL] == law.PARTS["normal"]["jkr"]
    # plans: the common combinations skip the checks of what they lack
    assert table[1, 2, law.PLAN] == law.PLANS["hertz_mindlin"] and table[1, 3, law.PLAN] == law.PLANS["general"]
    # history: xi (3), the rolling spring (3) of the epsd row, the bond of the jkr rows
    assert sim.pair.history_width == 7
    assert table[3, 3, law.H_ROLL] == 3 and table[1, 1, law.H_ROLL] == -1
    assert table[1, 3, law.H_BOND] == 6 and table[2, 2, law.H_BOND] == -1
    # the largest pull-off distance is added to the neighbor cutoff (R* up to the largest radius)
    ys = table[1, 3, law.YSTAR]
    assert math.isclose(sim.pair.reach, 0.75 * (math.pi ** 2 * 0.4 ** 2 * 0.01 / table[1, 1, law.YSTAR] ** 2) ** (
        1 / 3), rel_tol=1e-12) and ys > table[1, 1, law.YSTAR]
    sim.neighbor.init()
    assert sim.neighbor.cutmax() == 2 * 0.01 + sim.pair.reach + sim.neighbor.skin


BOX = """boundary f f f
region box block 0 1 0 1 0 1
create_box 2 box
pair_style sphere
"""
ATOM = "create_atoms 1 single 0.5 0.5 0.5 radius 0.01 density 2500\ntimestep 1e-6\n"
JKR = "normal jkr E 1e7 nu 0.3 w 0.05 en 0.5 mu 0.3"
HERTZ = "model hertz E 1e7 nu 0.3"
TWIST = "model hertz E 1e7 nu 0.3 en 0.5 mu 0.3 twisting sds"
BRIDGE = "cohesion capillary liquid_volume 1e-11 surface_tension 0.07 contact_angle 20"
BAD = [
    # parse time
    ("pair_coeff * * normal jkr E 1e7 nu 0.3 en 0.5 mu 0.3\n", "normal jkr needs w"),
    ("pair_coeff * * normal jkr E 1e7 nu 0.3 w 0 en 0.5 mu 0.3\n", "w (work of adhesion) must be > 0"),
    ("pair_coeff * * normal jkr E 1e7 nu 0.3 w nan en 0.5 mu 0.3\n", "w must be a finite number, got 'nan'"),
    ("pair_coeff * * normal jkr E 1e7 nu 0.3 w -inf en 0.5 mu 0.3\n", "w must be a finite number"),
    ("pair_coeff * * normal jkrr E 1e7 nu 0.3 w 1 en 0.5 mu 0.3\n", "normal must be one of hooke, hertz, jkr, dmt"),
    ("pair_coeff * * model hertz normal jkr E 1e7 nu 0.3 w 1 en 0.5 mu 0.3\n", "'normal' is given twice"),
    ("pair_coeff * * kn 1e5 en 0.5 w 0.1\n", "'w' is a coefficient of normal jkr or normal dmt"),
    (f"pair_coeff * * {JKR} rolling epsd mu_roll 0.1\n", "needs eta_roll"),
    (f"pair_coeff * * {JKR} rolling epsd mu_roll 0 eta_roll 0.3\n", "rolling epsd needs mu_roll > 0"),
    (f"pair_coeff * * {JKR} eta_roll 0.3\n", "'eta_roll' is a coefficient of rolling epsd"),
    (f"pair_coeff * * {JKR} rolling spring\n", "rolling must be one of constant, epsd, epsd2"),
    ("pair_coeff * * kn 1e5 en 0.5 tangential mindlin mu 0.3\n", "tangential mindlin needs the Hertz family"),
    ("pair_coeff * * model hertz E 1e7 nu 0.3 en 0.5 mu 0.3 tangential viscous\n",
     "tangential viscous takes its dashpot from damping restitution"),
    ("pair_coeff * * model hertz en 0.5 mu 0.3\n", "model hertz needs E, nu"),
    ("pair_coeff 1 2 model hertz E 1e7 en 0.5 mu 0.3\n", "model hertz needs nu"),
    (f"pair_coeff * * {JKR}\nfix w all wall/plane zplane 0 NULL type 3\n", "wall type"),
    (f"pair_coeff * * {JKR}\nfix w all wall/plane zplane 0 NULL type 1 kn 5 en 0.5\n", "takes no coefficients"),
    (f"pair_coeff * * {JKR}\nfix w all wall/plane zplane 0 NULL type\n", "type"),
    (f"pair_coeff * * {JKR}\nfix w all wall/drum z 0.5 0.5 0.4 normal dmt E 1e7 nu 0.3 w -1 en 0.5 mu 0\n",
     "w (work of adhesion) must be > 0"),
    (f"pair_coeff * * kn 1e5 en 0.5 {BRIDGE.replace('angle 20', 'angle 95')}\n",
     "contact_angle must be in [0, 90) degrees"),
    (f"pair_coeff * * kn 1e5 en 0.5 {BRIDGE.replace('volume 1e-11', 'volume 0')}\n",
     "liquid_volume must be > 0"),
    (f"pair_coeff * * kn 1e5 en 0.5 {BRIDGE.replace('tension 0.07', 'tension nan')}\n",
     "surface_tension must be a finite number, got 'nan'"),
    ("pair_coeff * * kn 1e5 en 0.5 cohesion capillary liquid_volume 1e-11 contact_angle 20\n",
     "cohesion capillary needs surface_tension"),
    ("pair_coeff * * kn 1e5 en 0.5 cohesion capilary liquid_volume 1e-11\n",
     "cohesion must be one of none, capillary, sjkr, got 'capilary' (did you mean 'capillary'"),
    ("pair_coeff * * kn 1e5 en 0.5 liquid_volume 1e-11\n", "'liquid_volume' is a coefficient of cohesion capillary"),
    ("pair_coeff * * kn 1e5 en 0.5 cohesion sjkr\n", "cohesion sjkr needs cohesion_energy_density"),
    ("pair_coeff * * kn 1e5 en 0.5 cohesion sjkr cohesion_energy_density -1\n",
     "cohesion_energy_density must be > 0"),
    ("pair_coeff * * kn 1e5 en 0.5 cohesion sjkr cohesion_energy_density inf\n",
     "cohesion_energy_density must be a finite number"),
    ("pair_coeff * * kn 1e5 en 0.5 limit_damping 2\n", "limit_damping must be 0 or 1, got 2"),
    ("pair_coeff * * kn 1e5 en 0.5 limit_damping -1\n", "limit_damping must be 0 or 1"),
    ("pair_coeff * * kn 1e5 en 0.5 limit_damping nan\n", "limit_damping must be a finite number"),
    ("pair_coeff * * kn 1e5 en 0.5 limit_damping yes\n", "limit_damping must be a number, got 'yes'"),
    ("pair_coeff * * kn 1e5 en 0.5 limit_damping\n", "'keyword value' pairs"),
    ("pair_coeff * * kn 1e5 en 0.5 tangential viscous mu 0.3 limit_damping 1 limit_damping 0\n",
     "'limit_damping' is given twice"),
    # damping tsuji: en in [0, 1] and given; no coefficient of another damping part
    (f"pair_coeff * * {HERTZ} en 1.5 mu 0.3 damping tsuji\n", "en must be in [0, 1]"),
    (f"pair_coeff * * {HERTZ} en -0.1 mu 0.3 damping tsuji\n", "en must be in [0, 1]"),
    (f"pair_coeff * * {HERTZ} en nan mu 0.3 damping tsuji\n", "en must be a finite number, got 'nan'"),
    (f"pair_coeff * * {HERTZ} en inf mu 0.3 damping tsuji\n", "en must be a finite number"),
    (f"pair_coeff * * {HERTZ} mu 0.3 damping tsuji\n", "model hertz needs en"),
    ("pair_coeff * * kn 1e5 mu 0.3 damping tsuji\n", "the Hooke law needs en"),
    ("pair_coeff * * kn 1e5 en 0.5 damping tsuji gamma_t 10\n", "'gamma_t' is a coefficient of damping restitution"),
    ("pair_coeff * * kn 1e5 en 0.5 damping tsuji beta_t 0.5\n", "'beta_t' is a coefficient of damping restitution"),
    (f"pair_coeff * * {HERTZ} en 0.5 mu 0.3 damping tsuji damping hertz\n", "'damping' is given twice"),
    (f"pair_coeff * * {HERTZ} en 0.5 mu 0.3 damping tsujii\n",
     "damping must be one of restitution, hertz, tsuji, got 'tsujii' (did you mean 'tsuji'"),
    ("pair_coeff * * kn 1e5 en 0.5 mu 0.3 damping tsuji tangential viscous\n",
     "tangential viscous takes its dashpot from damping restitution"),
    (f"pair_coeff * * kn 1e5 en 0.5\nfix w all wall/plane zplane 0 NULL {HERTZ} mu 0.3 damping tsuji\n",
     "model hertz needs en"),
    # twisting: sds needs its three numbers, finite, k and gamma >= 0, mu_twist > 0; marshall needs mu > 0
    (f"pair_coeff * * {TWIST} k_twist 1e-3 gamma_twist 0\n", "twisting sds needs mu_twist"),
    (f"pair_coeff * * {TWIST} mu_twist 1e-4\n", "twisting sds needs k_twist, gamma_twist"),
    (f"pair_coeff * * {TWIST} k_twist 1e-3 gamma_twist 0 mu_twist 0\n",
     "mu_twist must be > 0 (the twisting torque is capped at mu_twist |F_n|), got 0"),
    (f"pair_coeff * * {TWIST} k_twist 1e-3 gamma_twist 0 mu_twist -1e-4\n", "mu_twist must be > 0"),
    (f"pair_coeff * * {TWIST} k_twist 1e-3 gamma_twist 0 mu_twist nan\n", "mu_twist must be a finite number"),
    (f"pair_coeff * * {TWIST} k_twist -1 gamma_twist 0 mu_twist 1e-4\n", "k_twist must be >= 0"),
    (f"pair_coeff * * {TWIST} k_twist inf gamma_twist 0 mu_twist 1e-4\n", "k_twist must be a finite number"),
    (f"pair_coeff * * {TWIST} k_twist 1e-3 gamma_twist -0.1 mu_twist 1e-4\n", "gamma_twist must be >= 0"),
    (f"pair_coeff * * {TWIST} k_twist 1e-3 gamma_twist -nan mu_twist 1e-4\n", "gamma_twist must be a finite number"),
    (f"pair_coeff * * {TWIST} k_twist 1e-3 gamma_twist none mu_twist 1e-4\n", "gamma_twist must be a number"),
    ("pair_coeff * * kn 1e5 en 0.5 mu 0.3 k_twist 1e-3\n", "'k_twist' is a coefficient of twisting sds"),
    ("pair_coeff * * kn 1e5 en 0.5 mu 0.3 twisting marshall mu_twist 1e-4\n",
     "'mu_twist' is a coefficient of twisting sds"),
    ("pair_coeff * * kn 1e5 en 0.5 mu 0.3 twisting marshal\n",
     "twisting must be one of none, marshall, sds, got 'marshal' (did you mean 'marshall'"),
    ("pair_coeff * * kn 1e5 en 0.5 mu 0.3 twisting marshall twisting sds\n", "'twisting' is given twice"),
    ("pair_coeff * * kn 1e5 en 0.5 twisting marshall\n", "twisting marshall takes its friction from the tangential"),
    (f"pair_coeff * * {HERTZ} en 0.5 mu 0 twisting marshall\n", "twisting marshall takes its friction"),
    ("pair_coeff * * kn 1e5 en 0.5 mu 0.3 twisting\n", "'keyword value' pairs"),
]
BAD_AT_RUN = [
    # the line that leaves its material to types that have none
    ("pair_coeff 1 1 kn 1e5 en 0.5\npair_coeff 2 2 model hertz E 1e7 nu 0.3 en 0.5 mu 0.3\n"
     "pair_coeff 1 2 model hertz en 0.5 mu 0.3\n", 3, "type 1 has none of its own"),
    ("pair_coeff * * model hertz E 1e7 nu 0.3 en 0.5 mu 0.3\npair_coeff 1 2 normal jkr en 0.5 mu 0.3\n", 2,
     "this line gives no material (E, nu, w)"),
]


@pytest.mark.parametrize("line, message", BAD, ids=[f"{i}-{m[:28]}" for i, (_, m) in enumerate(BAD)])
def test_bad_law_line_is_a_clear_error_naming_the_line(line, message):
    sim = dem.Simulation(screen=False)
    script = BOX + line
    with pytest.raises(dem.DemError) as err:
        sim.commands(script)
    assert err.value.where == f"<string>:{len(script.splitlines())}", str(err.value)
    assert message in str(err.value), str(err.value)


@pytest.mark.parametrize("lines, bad, message", BAD_AT_RUN, ids=[m[:28] for _, _, m in BAD_AT_RUN])
def test_material_missing_at_the_run_names_the_pair_coeff_line(lines, bad, message):
    sim = dem.Simulation(screen=False)
    sim.commands(BOX + lines + ATOM)
    with pytest.raises(dem.DemError) as err:
        sim.commands("run 1")
    assert f"<string>:{len(BOX.splitlines()) + bad}" in str(err.value), str(err.value)
    assert message in str(err.value), str(err.value)


@pytest.mark.parametrize("style, shape", [("convex/gjk", "cube 0.01"), ("glued/convex", "cross3d 0.01"),
                                          ("polyhedron/multipoint", "cube 0.01")])
@pytest.mark.parametrize("law", [JKR, f"kn 1e5 en 0.5 {BRIDGE}", "kn 1e5 en 0.5 rolling epsd2 mu_roll 0.1",
                                 "kn 1e5 en 0.5 mu 0.3 twisting marshall"])
def test_parts_a_pair_style_cannot_keep_are_refused_at_the_run(style, shape, law):
    sim = dem.Simulation(screen=False)
    sim.commands(BOX.replace("pair_style sphere", f"shape s {shape}\npair_style {style}") +
                 f"pair_coeff * * {law}\ncreate_atoms 1 single 0.5 0.5 0.5 shape s density 2500\n"
                 "timestep 1e-6\n")
    with pytest.raises(dem.DemError, match="pair_style sphere has them"):
        sim.commands("run 1")


def test_jkr_on_a_mesh_wall_is_refused_at_the_run(tmp_path):
    stl = tmp_path / "floor.stl"
    stl.write_text("solid f\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                   "endloop\nendfacet\nendsolid f\n")
    sim = dem.Simulation(screen=False)
    sim.commands(BOX + f"pair_coeff * * kn 1e5 en 0.5\nfix m all wall/mesh file {stl} {JKR}\n" + ATOM)
    with pytest.raises(dem.DemError, match="fix wall/plane and wall/drum have them"):
        sim.commands("run 1")
    sim = dem.Simulation(screen=False)
    sim.commands(BOX + f"pair_coeff * * kn 1e5 en 0.5\nfix m all wall/mesh file {stl} kn 1e5 en 0.5 mu 0.3 "
                       f"twisting marshall\n" + ATOM)
    with pytest.raises(dem.DemError, match="twisting marshall/sds keep history this wall has no room for yet"):
        sim.commands("run 1")


@pytest.mark.parametrize("law", ["model hertz E 1e7 nu 0.3 en 0.3 mu 0", "kn 1e4 en 0.3"])
def test_limit_damping_keeps_the_normal_force_repulsive(law):
    """A damped impact on a wall: the dashpot pulls as the sphere leaves (the normal force turns
    attractive before the overlap ends) unless the line says limit_damping 1 (LAMMPS's limit_damping),
    which clamps it at zero; the rebound is then faster (less of the impact is dissipated)."""
    def impact(extra):
        sim = dem.Simulation(screen=False)
        sim.commands(f"""
            boundary f f f
            region box block -0.05 0.05 -0.05 0.05 0 0.05
            create_box 1 box
            create_atoms 1 single 0 0 {R + 1e-6!r} radius {R} density {RHO} v 0 0 -1
            pair_style sphere
            pair_coeff * * {law} {extra}
            fix wall all wall/plane zplane 0 NULL
            fix 1 all nve/sphere
            timestep 1e-7
            thermo 0
        """)
        forces = []
        sim.every(1, lambda s: forces.append(float(s.atom.local("f")[0, 2])))
        sim.run(40000)
        return min(forces), float(sim.atom.local("v")[0, 2])
    pull, rebound = impact("")
    held, rebound_held = impact("limit_damping 1")
    assert pull < 0 and held == 0.0
    assert 0 < rebound < rebound_held


def test_every_old_line_makes_the_row_it_always_made():
    """Today's lines keep their parts' codes 0 (Hooke, restitution, spring, constant) and their numbers."""
    law = dem.law
    r = law.row(law.parse("kn 1e5 en 0.5 mu 0.3 ks 2e4 gamma_t 10 beta_t 0.5 mu_roll 0.1".split(), "pc"))
    assert r[law.NORMAL] == r[law.DAMPING] == r[law.TANGENTIAL] == r[law.ROLLING] == r[law.LIMIT] == 0
    assert (r[law.KN], r[law.KS], r[law.GAMMA_T], r[law.BETA_T], r[law.MU], r[law.MU_ROLL]) == (
        1e5, 2e4, 10, 0.5, 0.3, 0.1)
    rows = np.array([r, law.descantes(r)])
    assert law.prepare(rows) == law.XI_WIDTH and list(rows[:, law.PLAN]) == [law.PLANS["grains3d"],
                                                                            law.PLANS["general"]]
    h = law.row(law.parse("model hertz E 1e7 nu 0.3 en 0.5 mu 0.3".split(), "pc"))
    assert (h[law.NORMAL], h[law.DAMPING], h[law.TANGENTIAL]) == (
        law.PARTS["normal"]["hertz"], law.PARTS["damping"]["hertz"], law.PARTS["tangential"]["mindlin"])
    d = law.descantes(r)
    assert d[law.LIMIT] == 1 and d[law.TANGENTIAL] == law.PARTS["tangential"]["viscous"]
    assert r[law.ALPHA] == h[law.ALPHA] == 0     # Tsuji's alpha only on damping tsuji rows
    t = law.row(law.parse("kn 1e5 en 0.5 damping tsuji".split(), "pc"))
    assert t[law.DAMPING] == law.PARTS["damping"]["tsuji"] and t[law.ALPHA] == law.tsuji_alpha(0.5) > 0
    assert law.prepare(np.array([d])) == 0 and law.prepare(np.array([r])) == law.XI_WIDTH
