"""Binary impacts against the closed forms of the Grains3D contact law (Part III eq. 10-16; see
../shared/science/README.md): normal restitution and contact duration,
    omega0^2 = kn / m_ij,  gamma_n = beta omega0,  T_c = pi / sqrt(omega0^2 - gamma_n^2),  e = exp(-gamma_n T_c),
for a sphere against a wall (m_ij = m) and two unequal spheres (m_ij = m1 m2 / (m1 + m2)), and the Coulomb
impulse solution of an oblique frictional impact (sliding throughout, and the rolling limit).

How the figures are measured: away from the contact the motion is free flight, so the stored (half-step)
velocities before and after the contact are exactly the incoming and outgoing velocities, and the positions
lie exactly on two straight lines. The contact duration is the time between the crossings of these two lines
with the contact distance (for the continuous solution the overlap starts and ends there): this interpolates
the crossing, so the figure is not quantised to whole steps.

Accuracy of the scheme (measured, and the reason for the steps per contact used below): with en = 1 the
leap-frog is second order (T_c error -1.6e-4 at 50 steps per contact, /4 per halving of dt; e error 1e-5).
With en < 1 the error is first order in dt, for two reasons: the dissipative force is evaluated with the
half-step velocity v(n-1/2) (it lags by dt/2: T_c comes out short by about gamma_n dt / 2), and the dashpot
force jumps from 0 to 2 gamma_n m_ij v at the first and last step of overlap, so e depends on where the
contact starts between two steps (by up to about gamma_n dt (1 + 1/e)). Measured worst case over the
sub-step phase of the first contact (10 phases), sphere-wall:
    en    steps/T_c   e error                 T_c error
    0.3      50       [-4.3e-2, +6.9e-3]      -1.07e-2
    0.3     200       [-1.0e-2, +1.7e-3]      -2.6e-3
    0.3     800       [-2.6e-3, +4.3e-4]      -6.4e-4
    0.73     50       [-3.3e-3, +1.0e-2]      -3.3e-3
    0.73    200       [-7.6e-4, +2.4e-3]      -7.9e-4
    0.95     50       [-1.4e-4, -2.3e-5]      -6.8e-4
So 50 steps per contact meet 0.5 % only for weak dissipation (en >~ 0.9); the tests below use, per en, the
resolution at which the worst phase is inside 0.5 % (>= 50 steps per contact in every case), check several
phases, and check separately that the error falls at least linearly with dt.
"""
import math

import numpy as np
import pytest

import dem
import dem.law

TOL = 5e-3            # the acceptance tolerance of issue 2 (0.5 %)
# steps per contact at which the worst sub-step phase is inside TOL with margin (table in the docstring)
STEPS_PER_CONTACT = {0.3: 800, 0.5: 400, 0.73: 200, 0.9: 100, 0.95: 50, 1.0: 50}
PHASES = (0.0, 0.25, 0.5, 0.75)     # where, between two steps, the first overlap occurs


def sphere_mass(r, rho):
    return rho * 4.0 / 3.0 * math.pi * r ** 3


def closed_form(kn, en, meff):
    w0 = math.sqrt(kn / meff)
    g = dem.law.beta(en) * w0
    tc = math.pi / math.sqrt(w0 * w0 - g * g)
    return w0, g, tc


# ----- sphere against a wall ----------------------------------------------------------------------------
def wall_impact(en, spt, phase, vn=0.5, vt=0.0, kn=1e4, R=0.5, rho=1.0, mu=0.0, gamma_t=0.0, ks=0.0,
                record=False):
    """A sphere (no spin) hits the floor z = 0 with velocity (vt, 0, -vn). Returns a dict of measurements."""
    m = sphere_mass(R, rho)
    tc = closed_form(kn, en, m)[2]
    dt = tc / spt
    gap = (10.0 + phase) * vn * dt          # first overlap `phase` of a step after step 10
    z0 = R + gap
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
boundary f f f
region box block -50 50 -2 2 -1 3
create_box 1 box
create_atoms 1 single 0 0 {z0!r} radius {R} density {rho} v {vt} 0 {-vn}
pair_style sphere
pair_coeff * * kn {kn} en {en}
fix 1 all nve/sphere
fix floor all wall/plane zplane 0 NULL kn {kn} en {en} mu {mu} gamma_t {gamma_t} ks {ks}
timestep {dt!r}
thermo 0
""")
    z_start = float(sim.atom.local("x")[0, 2])
    nsteps = int(gap / (vn * dt) + 1.5 * spt) + 5
    fs = []
    if record:      # per-step forces (for the Coulomb cap check)
        for _ in range(nsteps):
            sim.run(1)
            fs.append(sim.atom.local("f")[0].copy())
    else:
        sim.run(nsteps)
    wall = sim.modify.fixes[-1]
    assert wall.ncontacts == 0, "still in contact at the end: run longer"
    x, v, w = sim.atom.local("x")[0], sim.atom.local("v")[0], sim.atom.local("omega")[0]
    vz = float(v[2])
    assert vz > 0
    t_in = (z_start - R) / vn                          # free-flight line in crosses z = R
    t_out = nsteps * dt - (float(x[2]) - R) / vz       # free-flight line out crosses z = R
    return dict(e=vz / vn, tc=t_out - t_in, tc_theory=tc, dt=dt, m=m, v=v.copy(), omega=w.copy(),
                forces=np.array(fs))


@pytest.mark.parametrize("en", [0.3, 0.73, 0.95])
def test_wall_normal_impact_restitution_and_duration(en):
    spt = STEPS_PER_CONTACT[en]
    for phase in PHASES:
        r = wall_impact(en, spt, phase)
        de, dtc = r["e"] / en - 1.0, r["tc"] / r["tc_theory"] - 1.0
        # TOL: the acceptance figure; measured worst phase (docstring table) is at most half of it
        assert abs(de) < TOL, f"en={en}, {spt} steps/T_c, phase {phase}: restitution error {de:.2e}"
        assert abs(dtc) < TOL, f"en={en}, {spt} steps/T_c, phase {phase}: T_c error {dtc:.2e}"


def test_wall_elastic_impact_is_second_order():
    """en = 1 (no dashpot): the leap-frog keeps energy through a contact to O(dt^2)."""
    for phase in PHASES:
        r = wall_impact(1.0, 50, phase)
        # measured at 50 steps/T_c: |e - 1| <= 1.6e-5, T_c error -1.6e-4 (1/4 of it at 100 steps): 3x margin
        assert abs(r["e"] - 1.0) < 5e-5
        assert abs(r["tc"] / r["tc_theory"] - 1.0) < 5e-4


@pytest.mark.parametrize("en", [0.3, 0.73])
def test_wall_impact_converges_at_least_linearly(en):
    """The T_c error (phase independent with the interpolated crossings) falls at least linearly with dt, and
    is about gamma_n dt / 2 at 50 steps per contact (1.2 % for en = 0.3; measured 1.07 %, 0.33 % for 0.73)."""
    errs = []
    for spt in (50, 100, 200):
        r = wall_impact(en, spt, 0.5)
        errs.append(abs(r["tc"] / r["tc_theory"] - 1.0))
    assert errs[0] < 1.5e-2
    # at least first order: halving dt divides the error by >= ~2 (measured 2.03 and 2.02); 0.6 allows for
    # the phase-dependent part, and passes as well for a better (second-order) treatment of the dashpot
    assert errs[1] < 0.6 * errs[0] and errs[2] < 0.6 * errs[1], errs


# ----- two unequal spheres, head on ---------------------------------------------------------------------
def head_on(en, spt, phase, R1=0.5, rho1=1.0, R2=0.3, rho2=3.0, v1=0.3, v2=-0.5, kn=1e4):
    m1, m2 = sphere_mass(R1, rho1), sphere_mass(R2, rho2)
    meff = m1 * m2 / (m1 + m2)
    tc = closed_form(kn, en, meff)[2]
    dt = tc / spt
    vrel = v1 - v2
    gap = (10.0 + phase) * vrel * dt
    x1, x2 = -R1 - 0.5 * gap, R2 + 0.5 * gap
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
boundary f f f
region box block -5 5 -5 5 -5 5
create_box 2 box
create_atoms 1 single {x1!r} 0 0 radius {R1} density {rho1} v {v1} 0 0
create_atoms 2 single {x2!r} 0 0 radius {R2} density {rho2} v {v2} 0 0
pair_style sphere
pair_coeff * * kn {kn} en {en}
fix 1 all nve/sphere
timestep {dt!r}
thermo 0
""")
    m = sim.gather("rmass")
    assert np.allclose(m, [m1, m2], rtol=1e-14)
    p0 = (m[:, None] * sim.gather("v")).sum(axis=0)
    x = sim.gather("x")
    d0 = float(x[1, 0] - x[0, 0])
    nsteps = int(gap / (vrel * dt) + 1.5 * spt) + 5
    sim.run(nsteps)
    assert sim.pair.ncontacts == 0
    x, v = sim.gather("x"), sim.gather("v")
    p1 = (m[:, None] * v).sum(axis=0)
    vrel_out = float(v[1, 0] - v[0, 0])          # separation speed
    t_in = (d0 - (R1 + R2)) / vrel
    t_out = nsteps * dt - (float(x[1, 0] - x[0, 0]) - (R1 + R2)) / vrel_out
    return dict(e=vrel_out / vrel, tc=t_out - t_in, tc_theory=tc, p0=p0, p1=p1,
                pscale=m1 * abs(v1) + m2 * abs(v2))


@pytest.mark.parametrize("en", [0.5, 0.9, 1.0])
def test_sphere_sphere_head_on_unequal_masses(en):
    spt = STEPS_PER_CONTACT[en]
    for phase in PHASES:
        r = head_on(en, spt, phase)
        de, dtc = r["e"] / en - 1.0, r["tc"] / r["tc_theory"] - 1.0
        # TOL (0.5 %): T_c with the reduced mass; a wrong mass (m1, m2 or their mean) is off by > 20 %
        assert abs(de) < TOL, f"en={en} phase {phase}: restitution error {de:.2e}"
        assert abs(dtc) < TOL, f"en={en} phase {phase}: T_c error {dtc:.2e}"
        # equal and opposite forces: momentum changes only by the rounding of v += dt f / m (~1e-16 of the
        # momenta per step, a few hundred steps): 1e-13 leaves a wide margin and catches any real imbalance
        assert np.all(np.abs(r["p1"] - r["p0"]) <= 1e-13 * r["pscale"]), (r["p1"] - r["p0"])


# ----- oblique frictional impact on a wall ----------------------------------------------------------------
def sliding_integrals(en, vn, kn, m, R):
    """Continuous linear spring-dashpot contact, overlap d(t) = vn/wd exp(-g t) sin(wd t) on [0, T_c]:
    returns (int |F_n| dt / m, int d |F_n| dt / m). The dashpot makes F_n tensile after the inflection point
    t* of d(t) (F_n / m = -d''); the law caps |F_t| by mu |F_n|, so the tangential impulse is
    mu int |F_n| dt = mu m [vn (1 - e) + 2 |d'(t*)|], which is mu (1 + e) m vn only when en = 1."""
    w0, g, tc = closed_form(kn, en, m)
    wd = math.pi / tc
    e = math.exp(-g * tc)
    if g == 0.0:
        t_star = tc
    else:
        t_star = (math.pi - math.atan(2.0 * g * wd / (wd * wd - g * g))) / wd

    def ddot(t):
        return vn * np.exp(-g * t) * (np.cos(wd * t) - g / wd * np.sin(wd * t))

    abs_fn = vn * (1.0 - e) + 2.0 * abs(float(ddot(t_star)))
    t = np.linspace(0.0, tc, 200001)
    d = vn / wd * np.exp(-g * t) * np.sin(wd * t)
    fn = w0 * w0 * d + 2.0 * g * ddot(t)
    y = d * np.abs(fn)
    lever = float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(t)))
    return abs_fn, lever, e


@pytest.mark.parametrize("en", [1.0, 0.5])
def test_oblique_impact_sliding_coulomb_impulse(en):
    """Sphere (no spin) hits the floor with (vt, 0, -vn), mu = 0.3, ks = 0 and a large gamma_t, so that the
    viscous trial force always exceeds the Coulomb cap: sliding throughout (checked: the slip velocity at the
    contact point stays > 0, and |F_t| = mu |F_n| at every step of the contact).
    Impulse solution: J_t = mu int |F_n| dt (= mu (1 + e) m vn for en = 1, larger for en < 1, see
    sliding_integrals); dv_t = -J_t / m; the friction acts at the contact point below the centre, with the lever
    c = R - delta/2 of the law, so the spin (+y for motion along +x) changes by
    dw_y = mu int c |F_n| dt / I = (5/2) J_t / (m R) - (5/4) mu int delta |F_n| dt / (m R^2)."""
    vn, vt, mu, kn, R = 0.5, 2.0, 0.3, 1e4, 0.5
    spt = STEPS_PER_CONTACT[en]
    r = wall_impact(en, spt, 0.5, vn=vn, vt=vt, kn=kn, R=R, mu=mu, gamma_t=1e4, record=True)
    m = r["m"]
    abs_fn, lever, e = sliding_integrals(en, vn, kn, m, R)
    # the cap, step by step: f = (F_t, 0, F_n) for a sphere on the floor (no gravity)
    f = r["forces"]
    touching = np.abs(f[:, 2]) > 0
    assert touching.sum() >= spt - 2
    assert np.allclose(np.abs(f[touching, 0]), mu * np.abs(f[touching, 2]), rtol=1e-12, atol=0)
    assert np.all(f[touching, 0] <= 0) and np.all(f[:, 1] == 0)
    v, w = r["v"], r["omega"]
    dv_t = v[0] - vt
    dw_y = w[1]
    assert v[0] - R * w[1] > 0.5, "slip stopped: not the sliding regime"
    dv_expected = -mu * abs_fn
    dw_expected = 2.5 * mu * abs_fn / R - 1.25 * mu * lever / R ** 2
    # discrete impulse = dt sum |F_n|, within the restitution error of this resolution (< 2.5e-3 for en = 0.5
    # at 400 steps per contact, 1e-5 for en = 1; the impulse ratio itself is exact, checked above): 0.5 %
    tol = 1e-4 if en == 1.0 else TOL
    assert dv_t / dv_expected - 1.0 == pytest.approx(0.0, abs=tol), (dv_t, dv_expected)
    assert dw_y / dw_expected - 1.0 == pytest.approx(0.0, abs=tol), (dw_y, dw_expected)
    if en == 1.0:
        # the textbook form, J_n = (1 + e) m vn with e = 1; the lever correction is 0.3 % here
        assert dv_t == pytest.approx(-mu * 2.0 * vn, rel=1e-4)
        assert dw_y == pytest.approx(2.5 * mu * 2.0 * vn / R, rel=5e-3)
    else:
        # with a dashpot the tensile tail of F_n adds friction: the naive -mu (1 + e) vn is 6.7 % short here
        # (measured dv_t / naive = 1.067, as sliding_integrals predicts)
        assert dv_t / (-mu * (1.0 + e) * vn) > 1.03


def test_oblique_impact_rolling_limit():
    """Sliding stops during the contact (large mu, small vt): the viscous tangential force (ks = 0) then damps
    the slip u = v_t - R w at the rate 7 gamma_t (1/m + R^2/I = 7/(2m)), here 7 gamma_t T_c = 40, so the
    sphere leaves rolling. With the friction impulse J_t alone acting tangentially, v_t = v0 - J_t/m and
    R w = (5/2) J_t/m, so u = 0 gives v_t = 5/7 v0 (and R w = 5/7 v0), independent of mu and en."""
    en, spt, vn, vt = 0.9, 200, 0.5, 0.3
    kn, R, rho = 1e6, 0.5, 1.0     # stiff: the lever R - delta/2 differs from R by delta_max/2R = 3.6e-4
    m = sphere_mass(R, rho)
    tc = closed_form(kn, en, m)[2]
    gamma_t = 0.2 / (7.0 * tc / spt)     # 7 gamma_t dt = 0.2: the explicit slip damping is monotone
    r = wall_impact(en, spt, 0.5, vn=vn, vt=vt, kn=kn, R=R, rho=rho, mu=0.5, gamma_t=gamma_t)
    v, w = r["v"], r["omega"]
    # tolerance: O(delta_max / R) = 7e-4 from the lever and the slip that the changing lever re-creates while
    # the overlap shrinks; measured error -5e-5
    assert v[0] == pytest.approx(5.0 / 7.0 * vt, rel=1e-3)
    assert R * w[1] == pytest.approx(5.0 / 7.0 * vt, rel=1e-3)


def test_wall_critical_damping_en_zero():
    """en = 0 is critical damping (beta = 1, Descantes 2022 Table 1: gamma_n = 2 sqrt(m_ij kn)): the
    overlap of a sphere hitting the floor at v0 is delta(t) = v0 t exp(-omega0 t) (no gravity), so it peaks
    at v0 / (omega0 e) at t = 1 / omega0 and the sphere never leaves the floor. The leap-frog with the
    half-step dashpot is first order: at 400 steps per 1/omega0 the peak is within 0.5 % (measured 0.04 %);
    after 30 / omega0 the sphere still touches and moves at < 1e-9 v0 (closed form 30 e^-30 v0 = 2.8e-12 v0,
    measured 3.5e-12 v0)."""
    kn, R, rho, v0 = 1e4, 0.5, 1.0, 0.5
    m = sphere_mass(R, rho)
    w0 = math.sqrt(kn / m)
    assert dem.law.beta(0.0) == 1.0
    dt = 1.0 / (400 * w0)
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
boundary f f f
region box block -2 2 -2 2 -1 3
create_box 1 box
create_atoms 1 single 0 0 {R + 2 * v0 * dt!r} radius {R} density {rho} v 0 0 {-v0}
pair_style sphere
pair_coeff * * kn {kn} en 0
fix 1 all nve/sphere
fix floor all wall/plane zplane 0 NULL kn {kn} en 0
timestep {dt!r}
thermo 0
""")
    peak = 0.0
    for _ in range(1200):                  # 3 / omega0
        sim.run(1)
        peak = max(peak, R - float(sim.atom.local("x")[0, 2]))
    assert peak == pytest.approx(v0 / (w0 * math.e), rel=5e-3)
    sim.run(400 * 27)
    assert sim.modify.fixes[-1].ncontacts == 1
    assert abs(float(sim.atom.local("v")[0, 2])) < 1e-9 * v0
