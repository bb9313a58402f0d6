"""fix wall/drum and the drum analysis computes: a single sphere against the rolling solutions, and the
centrifuging transition of a bed (Part III sec 4.2)."""
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.special import ellipk

import dem
from dem.errors import DemError
from dem_process.compute_drum import surface_fit

R, G = 0.05, 9.81
LAW = "kn 1e5 en 0.73 mu 0.55 gamma_t 2000 ks 28571"



def _single(r, omega, v="0 0 0", w="0 0 0", rho=2500.0):
    """One sphere at the bottom of a drum of radius R (axis y, periodic along it), drum rotating at omega."""
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary f p f
        region box block -0.06 0.06 0 0.03 -0.06 0.06
        create_box 1 box
        create_atoms 1 single 0 0.015 {-(R - r)!r} radius {r} density {rho} v {v} omega {w}
        pair_style sphere
        pair_coeff * * {LAW}
        fix integ all nve/sphere
        fix g all gravity {G} vector 0 0 -1
        fix drum all wall/drum y 0 0 {R} omega {omega!r} {LAW}
        compute co all corotate drum
        timestep 1e-5
        thermo 0
    """)
    return sim


def _trajectory(sim, chunks, every=50):
    """Angle phi of the sphere's centre from the bottom, positive in the sense of the rotation."""
    t, phi, co = [], [], []
    for _ in range(chunks):
        sim.run(every)
        x = sim.atom.local("x")[0]
        t.append(sim.update.time)
        phi.append(math.atan2(-x[0], -x[2]))
        co.append(sim.thermo_keyword("c_co"))
    return np.array(t), np.array(phi), np.array(co)


def test_sphere_in_rigid_rotation_rolls_back_as_a_pendulum():
    """A sphere starting in rigid-body rotation with the drum (centre velocity Omega (R - r), spin Omega:
    no slip at the wall) is carried up, stops and rolls back. Rolling without slip on the moving wall,
    (R - r) phi' + r omega = R Omega, with I = 2/5 m r^2 gives (7/5)(R - r) phi'' = -g sin(phi) whatever
    Omega: a pendulum started at phi = 0 with phi' = Omega. Amplitude: cos(phi_max) = 1 - 0.7 (R - r)
    Omega^2 / g; it is back at the bottom after half a period, T/2 = 2 K(sin^2(phi_max/2)) / w with
    w^2 = 5 g / (7 (R - r)). Friction needed, (2/7) m g sin(phi), stays below mu N (no slip up to 62 deg).
    Chosen phi_max = 30 deg. Measured: amplitude within 1e-7, half period within 1e-5 (contact
    compliance, sampling every 50 steps). Tolerance 1e-3: a sliding sphere, or a sphere without its
    rotational inertia (factor 7/5), would be off by more than 10 %."""
    r = 0.005
    L = R - r
    phimax = math.radians(30.0)
    W = math.sqrt((1 - math.cos(phimax)) * G / (0.7 * L))
    sim = _single(r, W, v=f"{-W * L!r} 0 0", w=f"0 {W!r} 0")
    t, phi, co = _trajectory(sim, 800)       # 0.4 s: three quarters of a period
    assert co[0] == 1.0                                   # follows the drum as a rigid body at first
    assert phi.max() == pytest.approx(phimax, rel=1e-3)
    k = int(np.flatnonzero((phi[:-1] > 0) & (phi[1:] <= 0))[0])   # first return to the bottom
    t_back = t[k] + (t[k + 1] - t[k]) * phi[k] / (phi[k] - phi[k + 1])
    w = math.sqrt(5 * G / (7 * L))
    assert t_back == pytest.approx(2 * ellipk(math.sin(phimax / 2) ** 2) / w, rel=1e-3)
    assert phi.min() == pytest.approx(-phimax, rel=1e-3)  # and up the other side: no energy lost


def test_sphere_at_rest_slips_then_rolls():
    """A sphere at rest at the bottom of a drum suddenly rotating at Omega = 6 rad/s: the wall slips
    under it and kinetic friction mu N (N = m g cos(phi) + m (R - r) phi'^2) drags it up and spins it,
    until the contact point moves with the wall; it then rolls as the pendulum above. The DEM
    trajectory follows the solution of these equations of motion (slip, then roll) to 5e-4 degrees
    (sampled every 5e-4 s over 0.7 s); tolerance 0.01 degree, against an amplitude of 8.7 degrees."""
    r, mu, W = 0.005, 0.55, 6.0
    L = R - r
    sim = _single(r, W)
    t, phi, _ = _trajectory(sim, 700)
    inertia = 0.4 * r * r        # per unit mass

    def slip(_, y):
        p, pd, _w = y
        f = mu * (G * math.cos(p) + L * pd * pd)        # the wall is faster than the contact point
        return [pd, (-G * math.sin(p) + f) / L, r * f / inertia]

    def sticks(_, y):
        return L * y[1] + r * y[2] - R * W
    sticks.terminal, sticks.direction = True, 1
    s1 = solve_ivp(slip, (0, 1), [0.0, 0.0, 0.0], events=sticks, rtol=1e-10, atol=1e-12, max_step=1e-4)
    ts, y = s1.t_events[0][0], s1.y_events[0][0]
    s2 = solve_ivp(lambda _, q: [q[1], -G * math.sin(q[0]) / (1.4 * L)], (ts, 0.8), y[:2], rtol=1e-10,
                   atol=1e-12, dense_output=True, max_step=1e-3)
    ode = np.where(t < ts, np.interp(t, s1.t, s1.y[0]), s2.sol(np.maximum(t, ts))[0])
    assert 0.01 < ts < 0.03
    assert np.abs(np.degrees(phi - ode)).max() < 0.01
    assert math.degrees(phi.max()) == pytest.approx(8.74, abs=0.05)


# ----- a bed: centrifuging at Fr >= 2, not at 5 rpm ---------------------------------------------------
BED_LAW = "kn 1e4 en 0.73 mu 0.55 gamma_t 2000 ks 2857"


@pytest.fixture(scope="module")
def bed(tmp_path_factory):
    """350 spheres of radius 3 mm filling 60 % of a drum of radius 50 mm, 14 mm deep (periodic), settled.
    kn = 1e4 (softer than Table 6, overlaps < 0.1 %) allows dt = 1.5e-5 (25 steps per contact)."""
    path = tmp_path_factory.mktemp("drum") / "bed.restart"
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary f p f
        region box block -0.051 0.051 0 0.014 -0.051 0.051
        create_box 1 box
        region drum cylinder y 0 0 {R} EDGE EDGE
        pair_style sphere
        pair_coeff * * {BED_LAW}
        fix ins all insert 11 drum count 350 radius 0.003 density 2500
        fix integ all nve/sphere
        fix g all gravity {G} vector 0 0 -1
        fix drum all wall/drum y 0 0 {R} rpm 0 {BED_LAW}
        timestep 1.5e-5
        thermo 0
        run 15000
        write_restart {path}
    """)
    assert sim.atom.natoms == 350 and sim.thermo_keyword("ke") < 1e-4
    return path


def _rotate(path, rate):
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        read_restart {path}
        pair_style sphere
        pair_coeff * * {BED_LAW}
        fix integ all nve/sphere
        fix g all gravity {G} vector 0 0 -1
        fix drum all wall/drum y 0 0 {R} {rate} {BED_LAW}
        compute co all corotate drum
        compute rep all repose drum
        compute vm all vmean drum drum
        timestep 1.5e-5
        thermo 0
    """)
    return sim


def test_bed_centrifuges_at_froude_3(bed):
    """Fr = Omega^2 R / g = 3, reached with a linear ramp over 0.5 s: after the transient (cascading,
    cataracting), the bed is carried all around the drum as a rigid body from about 0.6 s on. A thin
    layer of spheres does not centrifuge (an isolated sphere rolls on the wall whatever Omega, see the
    pendulum test): the bed is 3 particles thick once centrifuged.
    Measured at 1.2 s, insertion seeds 11 (this bed) / 12 / 13:
    - co-rotating fraction 0.989 / 0.997 / 0.997 (346 to 349 of 350); asserted >= 0.97 (340 of 350: the
      lowest seed less 6 particles).
    - co-rotating at the top = at the top (within 45 degrees of the top, near the wall) 0.246 / 0.271 /
      0.243: a uniform ring has 0.25 there; asserted 0.25 +- 0.04 (the seeds lie within 0.025 of it; 0.015
      more is 5 particles); a bed not carried over the top has 0.
    - <|v|> / (Omega R): a rigid rotation moves each particle at Omega rho (rho its distance from the
      axis), so c_vm = <rho> / R for the co-rotating particles; measured 0.6 / 0.4 / -0.1 % off (the 0.3 to
      1 % of particles rolling on the layer's surface); asserted within 2 %."""
    W = math.sqrt(3.0 * G / R)
    sim = _rotate(bed, f"omega {W!r} ramp 0.5")
    sim.run(80000)
    co, co_top, top = (sim.thermo_keyword(f"c_co[{k}]") for k in (1, 2, 3))
    assert co >= 0.97
    assert co_top == pytest.approx(0.25, abs=0.04) and top == pytest.approx(0.25, abs=0.04)
    assert co_top <= top
    x = sim.gather("x")
    rho = np.hypot(x[:, 0], x[:, 2])          # the drum's axis: y through x = z = 0
    assert sim.thermo_keyword("c_vm") == pytest.approx(rho.mean() / R, rel=0.02)


def test_bed_does_not_centrifuge_at_5rpm(bed):
    """At 5 rpm (Fr = 0.0014) the bed's lower part turns with the drum, tilting the free surface up,
    but nothing is carried over the top. After 0.6 s (0.05 turn, 18 degrees) the surface has tilted by
    about 16 degrees with the drum: the bed has not reached its repose angle yet (25 degrees, from 1.2 s
    on, when avalanches start).
    Measured over 16 beds (insertion seeds 11-18, each with fix insert rebuilding the neighbor list at
    every insertion step (the old schedule) and only when a particle goes in (the new one): round-off
    makes them different beds): angle 13.1-18.4 degrees, mean 16.0, standard deviation 1.7; asserted
    16 +- 5 (3 standard deviations); a surface at the repose angle (25) or one that did not follow the
    drum (0) is outside. Co-rotating fraction 0.954-1.000 in 15 beds, 0.726 in one (old code, seed 16:
    part of the bed slid on the wall); asserted > 0.6, where a bed that does not follow the drum has
    next to none."""
    sim = _rotate(bed, "rpm 5")
    sim.run(40000)
    assert sim.thermo_keyword("c_co[3]") == 0.0        # nobody at the top of the drum
    assert sim.thermo_keyword("c_co") > 0.6            # the passive region turns with the drum
    angle = sim.thermo_keyword("c_rep")
    assert angle == pytest.approx(16.0, abs=5.0)


# ----- bookkeeping -----------------------------------------------------------------------------------
def test_angle_ramp_and_restart(tmp_path):
    """The drum angle integrates the rate exactly through the linear ramp: after t > T_ramp it is
    Omega (t - T_ramp / 2); it is saved in restarts and continues from there."""
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary f p f
        region box block -0.06 0.06 0 0.03 -0.06 0.06
        create_box 1 box
        pair_style sphere
        pair_coeff * * {LAW}
        fix integ all nve/sphere
        fix drum all wall/drum y 0 0 {R} rpm 60 ramp 0.01 {LAW}
        timestep 1e-4
        thermo 0
        run 300
        write_restart {tmp_path / 'd.restart'}
    """)
    W = 2 * math.pi
    assert sim.thermo_keyword("f_drum[angle]") == pytest.approx(W * (0.03 - 0.005), rel=1e-9)
    assert sim.thermo_keyword("f_drum[omega]") == pytest.approx(W)
    b = dem.Simulation(screen=False)
    b.commands(f"""
        read_restart {tmp_path / 'd.restart'}
        pair_style sphere
        pair_coeff * * {LAW}
        fix drum all wall/drum y 0 0 {R} rpm 60 ramp 0.01 {LAW}
        timestep 1e-4
        thermo 0
        run 100
    """)
    assert b.thermo_keyword("f_drum[angle]") == pytest.approx(W * (0.04 - 0.005), rel=1e-9)


def test_end_walls_contain_particles():
    """With `ends LO HI fixed` and no periodicity along the axis, a sphere thrown along the axis bounces
    back from an end wall and stays in the drum."""
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary f f f
        region box block -0.06 0.06 -0.001 0.031 -0.06 0.06
        create_box 1 box
        create_atoms 1 single 0 0.015 -0.04 radius 0.003 density 2500 v 0 1.0 0
        pair_style sphere
        pair_coeff * * {LAW}
        fix integ all nve/sphere
        fix g all gravity {G} vector 0 0 -1
        fix drum all wall/drum y 0 0 {R} rpm 10 ends 0 0.03 rotate {LAW}
        timestep 1e-5
        thermo 0
        run 1500
    """)
    assert sim.gather("v")[0, 1] < 0                   # came back from the far end (y = 0.03) at 0.012 s
    sim.run(20000)
    y = sim.gather("x")[0, 1]
    assert 0.003 - 1e-4 <= y <= 0.027 + 1e-4


def test_surface_fit_recovers_a_tilted_surface():
    """Particles filling a disc of radius 1 below a line of slope tan(25 deg): the fit of the highest
    particle per bin gives 25 degrees (within 1 degree: one bin's height step), and a roughness below the
    bins' height step (0.1 tan 25 = 0.047: the highest particle of a bin lies within it of the line). Ripples
    of amplitude 0.1 on the same surface give a roughness of 0.1 / sqrt(2) (the rms of a sine) within that
    step."""
    rng = np.random.default_rng(3)
    p = rng.uniform(-1, 1, (20000, 2))
    slope = math.tan(math.radians(25))
    keep = (np.hypot(p[:, 0], p[:, 1]) < 1) & (p[:, 1] < -0.2 + slope * p[:, 0])
    angle, b, a, used, rough = surface_fit(p[keep, 0], p[keep, 1], nbins=20, trim=0.15)
    assert angle == pytest.approx(25.0, abs=1.0)
    assert a == pytest.approx(-0.2, abs=0.03) and used >= 10
    assert rough < 0.1 * slope
    ripples = 0.1 * np.sin(2 * np.pi * p[:, 0] / 0.5)            # four ripples across the bed
    keep = (np.hypot(p[:, 0], p[:, 1]) < 1) & (p[:, 1] < -0.2 + slope * p[:, 0] + ripples)
    rough = surface_fit(p[keep, 0], p[keep, 1], nbins=40, trim=0.15)[4]
    assert rough * np.sqrt(1 + slope ** 2) == pytest.approx(0.1 / np.sqrt(2), abs=0.1 * slope / 2)


def test_surface_fit_skips_particles_above_a_gap():
    """Two particles carried on the drum wall high above the bed (as 3D crosses stuck in a rough wall at
    20 rpm): without the gap rule they are their bins' tops and tilt the line; with it (a gap larger than
    `gap` across the surface above the bed's column) the surface is the bed's again, as without them."""
    rng = np.random.default_rng(3)
    p = rng.uniform(-1, 1, (20000, 2))
    slope = math.tan(math.radians(25))
    bed = p[(np.hypot(p[:, 0], p[:, 1]) < 1) & (p[:, 1] < -0.2 + slope * p[:, 0])]
    carried = np.array([[-0.3, 0.95], [-0.25, 0.96]])
    both = np.vstack([bed, carried])
    alone = surface_fit(bed[:, 0], bed[:, 1], gap=0.2)
    assert alone[0] == pytest.approx(surface_fit(bed[:, 0], bed[:, 1])[0], abs=1e-12)   # no gap in a dense bed
    assert abs(surface_fit(both[:, 0], both[:, 1])[0] - alone[0]) > 3.0                 # no gap rule: fooled
    assert surface_fit(both[:, 0], both[:, 1], gap=0.2)[:4] == pytest.approx(alone[:4], abs=1e-12)


def test_errors():
    sim = dem.Simulation(screen=False)
    sim.commands("region box block -1 1 -1 1 -1 1\ncreate_box 1 box")
    with pytest.raises(DemError, match="wall/drum: AXIS must be x, y or z, got 'w'"):
        sim.command("fix d all wall/drum w 0 0 0.5 kn 1 en 0.5")
    with pytest.raises(DemError, match=r"wall/drum: unknown keyword 'rmp' \(did you mean 'ramp'\?\)"):
        sim.command("fix d all wall/drum y 0 0 0.5 rmp 5 kn 1 en 0.5")
    sim.command("fix d all wall/drum y 0 0 0.5 rpm 5 kn 1 en 0.5")
    sim.command("compute c all corotate d")
    with pytest.raises(DemError, match=r"fix g is a gravity, not a rotating drum \(fix wall/drum\)"):
        sim.command("fix g all gravity 9.81")
        sim.command("compute bad all corotate g")
        sim.thermo_keyword("c_bad")


def test_pictures_and_series(tmp_path):
    """dump png writes the cross-section during the run; dem-frames (dem.tools.drum_frames) draws the same
    from the HDF5 dump; fix print/series writes one line per N steps (plus the first) that dem-plot
    (dem.tools.plot_series) plots."""
    from dem.tools import drum_analysis, drum_frames, plot_series
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary f p f
        region box block -0.06 0.06 0 0.03 -0.06 0.06
        create_box 1 box
        region inside cylinder y 0 0 {R} EDGE EDGE
        pair_style sphere
        pair_coeff * * {LAW}
        fix ins all insert 5 inside count 40 radius 0.003 density 2500
        fix integ all nve/sphere
        fix g all gravity {G} vector 0 0 -1
        fix drum all wall/drum y 0 0 {R} rpm 30 {LAW}
        compute vm all vmean drum drum
        compute co all corotate drum
        compute cn all coord
        timestep 1e-5
        thermo 0
        fix series all print/series 50 {tmp_path / 'd.dat'} c_vm c_co[2] f_drum[revs] ke c_cn
        dump h all h5 100 {tmp_path / 'd.h5'}
        dump p all png 100 {tmp_path / 'p_*.png'} drum drum size 300
        run 200
    """)
    sim.close()
    assert (tmp_path / "p_0.png").exists() and (tmp_path / "p_200.png").exists()
    names, cols = plot_series.read_series(tmp_path / "d.dat")
    assert names == ["step", "time", "c_vm", "c_co[2]", "f_drum[revs]", "ke", "c_cn"]
    np.testing.assert_array_equal(cols["step"], [0, 50, 100, 150, 200])
    assert cols["f_drum[revs]"][-1] == pytest.approx(0.5 * 200 * 1e-5)   # 30 rpm = 0.5 turn/s
    drum_frames.main([str(tmp_path / "d.h5"), "--frames", "last", "--size", "300"])
    assert (tmp_path / "d_200.png").exists()
    plot_series.main([str(tmp_path / "d.dat"), "--x", "tstar", "--rpm", "30", "-o", str(tmp_path / "d_series.png")])
    assert (tmp_path / "d_series.png").exists()
    drum_analysis.main(["--rpm", "30", "--series", str(tmp_path / "d.dat"), "--h5", str(tmp_path / "d.h5"),
                        "-o", str(tmp_path / "a")])
    for name in ("a_vmean.png", "a_coordination.png", "a_pdf.png"):
        assert (tmp_path / name).exists()


# ----- shaped particles against the drum ----------------------------------------------------------------
KN = 1e5


def _drum_contact(shape_cmd, pos, quat, point="deepest", ends=""):
    """Forces of fix wall/drum (drum at rest, axis y through the origin) on one shaped particle at rest,
    and the posed body (world vertices or None, the table row for the support function)."""
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary f f f
        region box block -0.06 0.06 -0.03 0.03 -0.06 0.06
        create_box 1 box
        {shape_cmd}
        create_atoms 1 single {float(pos[0])!r} {float(pos[1])!r} {float(pos[2])!r} shape s density 2500 quat {' '.join(repr(float(c)) for c in quat)}
        pair_style convex/gjk
        pair_coeff * * kn {KN} en 0.5 mu 0.5
        fix drum all wall/drum y 0 0 {R} point {point} {ends} kn {KN} en 0.5 mu 0.5
        timestep 1e-6
        thermo 0
        run 0
    """)
    a = sim.atom.data
    a["f"][:] = 0.0
    a["torque"][:] = 0.0
    fix = sim.modify.find("drum")
    fix.compute(False)
    return sim, fix, a["f"][0].copy(), a["torque"][0].copy()


def _posed(sim):
    """World rotation, centre and the shape-table row of particle 0."""
    from dem.shapes import command as shape_command
    from dem.shapes._support import rotation_matrix
    a = sim.atom.data
    t = shape_command.kernel_arrays(sim)
    s = a["shape"][0]
    Rm = rotation_matrix(np.ascontiguousarray(a["quat"][0])) * (a["radius"][0] / t["radius"][s])
    verts = t["verts"][t["voff"][s]:t["voff"][s] + t["nv"][s]]
    return Rm, a["x"][0].copy(), t["kind"][s], t["params"][s], np.ascontiguousarray(verts)


def _farthest_independent(sim):
    """Largest distance from the drum axis over the posed body, the radial unit vector there and the point's
    axial coordinate: over the vertices of a polytope; for a curved body the maximum over the radial
    direction u (angle t) of its support value h(u) + u.x (the body's support function, refined by a
    bounded scalar search)."""
    from scipy.optimize import minimize_scalar
    from dem.shapes._support import support_points
    Rm, x, kind, params, verts = _posed(sim)
    if kind == 1:          # box: its 8 corners
        h = params[:3]
        verts = np.array([[sx * h[0], sy * h[1], sz * h[2]] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
    if len(verts):
        W = verts @ Rm.T + x
        rho = np.hypot(W[:, 0], W[:, 2])
        k = np.argmax(rho)
        return rho[k], np.array([W[k, 0], 0.0, W[k, 2]]) / rho[k], W[k, 1]

    def g(t):
        u = np.array([math.cos(t), 0.0, math.sin(t)])
        p = support_points(int(kind), np.ascontiguousarray(params), verts.reshape(-1, 3), (Rm.T @ u)[None, :])[0]
        return -(u @ (Rm @ p) + u @ x)
    ts = np.linspace(-math.pi, math.pi, 7201)
    t0 = ts[np.argmin([g(t) for t in ts])]
    r = minimize_scalar(g, bounds=(t0 - 1e-3, t0 + 1e-3), method="bounded", options={"xatol": 1e-13})
    u = np.array([math.cos(r.x), 0.0, math.sin(r.x)])
    p = Rm @ support_points(int(kind), np.ascontiguousarray(params), verts.reshape(-1, 3), (Rm.T @ u)[None, :])[0]
    return -r.fun, u, p[1] + x[1]


@pytest.mark.parametrize("shape_cmd, curved", [
    ("shape s cube 0.004", False),
    ("shape s box 0.002 0.005 0.003", False),
    ("shape s tetrahedron 0.005", False),
    ("shape s pinacoid 0.006 0.003 0.002 60", False),
    ("shape s cylinder 0.0015 0.006", True),
    ("shape s ellipsoid 0.003 0.002 0.0015", True),
])
def test_drum_wall_pushes_shaped_particles_from_their_farthest_point(shape_cmd, curved):
    """A shaped particle at rest, at random orientations, across the drum wall: the wall pushes with
    k_n delta (no velocity, no damping) towards the axis from the point of the body farthest from it,
    delta = rho_max - R, found independently (all vertices of a polytope; for a curved body, the radial
    direction maximising its support value). Polytopes: the same vertex, so exact to round-off (1e-12);
    curved bodies: the kernel iterates p = support(radial direction at p) to round-off; the reference
    maximum is flat to second order, so its value (delta, |F|) is exact to 1e-9 but its direction only to
    about sqrt(eps) (seen: 4e-9 rad), hence 1e-7 on the force components. The torque is the lever from
    the centre of mass to the contact point, midway in the overlap, times that force."""
    rng = np.random.default_rng(17)
    checked = 0
    for _ in range(12):
        q = rng.normal(size=4)
        q /= np.linalg.norm(q)
        phi = rng.uniform(-math.pi, math.pi)
        u0 = np.array([math.sin(phi), 0.0, -math.cos(phi)])
        sim, _, _, _ = _drum_contact(shape_cmd, (0.0, 0.0, 0.0), q)
        Rm, _, kind, params, verts = _posed(sim)
        from dem.shapes._support import support_points
        reach = u0 @ (Rm @ support_points(int(kind), np.ascontiguousarray(params), verts.reshape(-1, 3),
                                          (Rm.T @ u0)[None, :])[0])
        pos = (R - reach + rng.uniform(2e-6, 2e-5)) * u0      # the body pokes through by a few microns
        sim, fix, f, tq = _drum_contact(shape_cmd, pos, q)
        rho, u, y = _farthest_independent(sim)
        delta = rho - R
        assert delta > 0 and fix.ncontacts == 1
        expected = -KN * delta * u
        tol = 1e-7 if curved else 1e-12
        assert np.linalg.norm(f) == pytest.approx(KN * delta, rel=1e-9 if curved else 1e-12)
        np.testing.assert_allclose(f, expected, rtol=0, atol=tol * KN * delta)
        point = (R + 0.5 * delta) * u + [0.0, y, 0.0]
        np.testing.assert_allclose(tq, np.cross(point - pos, expected), rtol=0, atol=tol * KN * delta * 0.01)
        assert fix.energy == pytest.approx(0.5 * KN * delta ** 2, rel=1e-8 if curved else 1e-12)
        checked += 1
    assert checked == 12


def test_drum_wall_point_centroid_pushes_a_face_at_its_middle():
    """A cube with a face towards the drum wall touches it along its two outer edges (the wall is curved):
    `point deepest` (Grains3D) pushes at one corner, a lever of half the edge across the face, so a
    torque of about (a/2) |F|; `point centroid` pushes at the depth-weighted centroid of the four corners
    beyond the wall, which by symmetry lies on the line of centres: no torque (1e-12 |F| a), and the same
    force."""
    a = 0.004
    depth = 5e-6
    h = a / 2
    zc = -(math.sqrt(R * R - h * h) - h) - depth          # outer face `depth` beyond the wall at its edges
    delta = math.hypot(h, math.sqrt(R * R - h * h) + depth) - R
    pos = (0.0, 0.0, zc)
    q = (1.0, 0.0, 0.0, 0.0)
    _, _, fd, td = _drum_contact(f"shape s cube {a}", pos, q, "deepest")
    _, _, fc, tc = _drum_contact(f"shape s cube {a}", pos, q, "centroid")
    assert np.linalg.norm(fd) == pytest.approx(np.linalg.norm(fc), rel=1e-12)
    assert np.linalg.norm(fc) == pytest.approx(KN * delta, rel=1e-9)
    assert np.linalg.norm(td) > 0.4 * h * np.linalg.norm(fd)
    assert np.linalg.norm(tc) < 1e-12 * a * np.linalg.norm(fc)


def test_drum_end_walls_push_shaped_particles_from_their_deepest_point():
    """The flat ends of the drum: a tilted cube poking through the end at y = LO by d pushes back with k_n d
    along +y, d = LO - (lowest corner), exact."""
    a = 0.004
    rng = np.random.default_rng(3)
    q = rng.normal(size=4)
    q /= np.linalg.norm(q)
    sim, _, _, _ = _drum_contact(f"shape s cube {a}", (0.0, 0.0, -0.02), q, ends="ends -0.02 0.02 fixed")
    Rm = _posed(sim)[0]
    corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * a / 2 @ Rm.T
    reach = -corners[:, 1].min()
    d = 7e-6
    sim, fix, f, _ = _drum_contact(f"shape s cube {a}", (0.0, -0.02 + reach - d, -0.02), q,
                                   ends="ends -0.02 0.02 fixed")
    assert fix.ncontacts == 1
    np.testing.assert_allclose(f, [0.0, KN * d, 0.0], rtol=0, atol=1e-9 * KN * d)


def test_drum_cubes_input_runs(tmp_path):
    """inputs/in.drum_cubes, shortened (100 cubes, 0.15 s of fill, 0.03 s of damping): every phase runs,
    all cubes are inserted and stay in the drum, they rest on its wall (contacts) with overlaps far below
    the edge."""
    import os
    script = os.path.join(os.path.dirname(__file__), os.pardir, "inputs", "in.drum_cubes")
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        sim = dem.Simulation(screen=False, variables=[("N", ["100"]), ("fill", ["0.15"]),
                                                      ("settle", ["0.03"]), ("rotate", ["0.004"])])
        sim.file(script)
    finally:
        os.chdir(cwd)
    assert sim.atom.natoms == 100
    x = sim.gather("x")
    assert np.all(np.hypot(x[:, 0], x[:, 2]) < R)
    drum = sim.modify.find("drum")
    assert drum.ncontacts > 5 and drum.max_overlap < 0.01
    assert (tmp_path / "drum_cubes_final.png").exists()


@pytest.mark.parametrize("shape, n", [("cross3d", 40), ("sphere", 100), ("cube", 60)])
def test_main_drum_input_runs(tmp_path, monkeypatch, shape, n):
    """inputs/in.drum (the README's main job), shortened: crosses (its default), spheres and a convex shape
    are inserted, settle on the drum wall and turn; every output is written; the final picture (the
    mid-plane section) is not the last periodic one."""
    import os
    script = os.path.join(os.path.dirname(__file__), os.pardir, "inputs", "in.drum")
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False, variables=[("shape", [shape]), ("N", [str(n)]), ("W", ["0.012"]), ("fill", ["0.16"]),
                                                  ("settle", ["0.04"]), ("rotate", ["0.004"])])
    sim.file(script)
    types = sim.gather("type")
    bed, wall = types == 1, types == 2
    assert bed.sum() == n and wall.sum() > 200               # the bed and the rough wall's spheres
    assert (sim.gather("shape")[bed] >= 0).all() == (shape != "sphere")
    x, v = sim.gather("x"), sim.gather("v")
    assert np.all(np.hypot(x[bed, 0], x[bed, 2]) < R)
    # the wall's spheres turn with the drum, on the wall
    assert np.allclose(np.hypot(x[wall, 0], x[wall, 2]), R - 0.0015, rtol=1e-12)
    om = sim.modify.find("drum").omega
    assert np.allclose(np.linalg.norm(v[wall], axis=1), om * (R - 0.0015), rtol=1e-12)
    assert sim.pair.ncontacts > 5                             # the bed lies on the wall's spheres
    # per contact point a pair of crosses touching at several beams counts more than once; spheres and
    # convex shapes touch at one point
    cn, cp = sim.computes["cn"].scalar(), sim.computes["cp"].scalar()
    assert cn > 0 and (cp >= cn if shape == "cross3d" else cp == cn)
    for name in ("drum.dat", "drum.h5", "drum.xdmf", "drum_0.png", "drum_final.png"):
        assert (tmp_path / name).stat().st_size > 0, name
    assert (tmp_path / "drum_0.png").read_bytes() != (tmp_path / "drum_final.png").read_bytes()
    sim.close()
    # the sweep's analysis reads the series and the dump (with the crosses' surfaces in it)
    from dem.tools import drum_analysis
    drum_analysis.main(["--rpm", "40", "--series", "drum.dat", "--h5", "drum.h5", "-o", "a"])
    assert (tmp_path / "a_regimes.png").stat().st_size > 0
    # Fig. 27's PDF is the bed's: the wall's spheres (at 0.97 Omega R always) are not in it
    assert len(drum_analysis.time_averaged_speed("drum.h5", R, om)) == n
    pdf = _tool("drum_pdf")
    pdf.main(["drum.h5:40:bed", "-o", "p.png"])
    assert (tmp_path / "p.png").stat().st_size > 0
    # widths: a uniform spread over [0, 1] has std 1/sqrt(12) and a 5-95 % range of 0.9
    mean, std, spread = pdf.widths(np.linspace(0.0, 1.0, 100001))
    assert (mean, std, spread) == pytest.approx((0.5, 12 ** -0.5, 0.9), rel=1e-4)


def test_main_drum_input_stops_when_the_fill_is_too_short(tmp_path, monkeypatch):
    """1500 cubes (the default for 12 mm) cannot all go in within 1000 steps: the job stops after the fill
    (quit 2) and says how many are left (fix insert's pending count in the script's expression), rather than
    settling half a bed."""
    import os
    script = os.path.join(os.path.dirname(__file__), os.pardir, "inputs", "in.drum")
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False, log="log.dem", variables=[("shape", ["cube"]), ("W", ["0.012"]),
                                                                 ("fill", ["0.002"])])
    sim.file(script)
    left = sim.modify.find("ins").thermo()["pending"]
    sim.close()
    assert sim.input.quit_status == 2 and left > 0 and sim.update.ntimestep == 1000
    assert f"{left} of the 1500 particles are still to go in" in open("log.dem").read()


def test_main_drum_input_refuses_an_unknown_shape(tmp_path, monkeypatch):
    import os
    script = os.path.join(os.path.dirname(__file__), os.pardir, "inputs", "in.drum")
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False, variables=[("shape", ["cone"])])
    sim.file(script)
    assert sim.input.quit_status == 2 and sim.atom.natoms == 0


CARRY = """
boundary f p f
region box block -0.06 0.06 0 0.01 -0.06 0.06
create_box 2 box
shape c cube 0.002
create_atoms 2 single 0.03 0.005 -0.0385 radius 0.0015 density 2500
create_atoms 2 single -0.0485 0.002 0 shape c density 2500 quat 0.9238795 0 0.3826834 0
create_atoms 1 single 0 0.005 0 radius 0.001 density 2500
group bed type 1
group wall type 2
pair_style convex/gjk
pair_coeff * * {LAW}
fix integ {integ} nve/shape
fix drum {fixgroup} wall/drum y 0 0 {R} rpm 40 ramp 0.01 carry wall {LAW}
timestep 2e-5
thermo 0
"""


def test_carried_particles_turn_with_the_drum():
    """`carry GROUP`: after 2000 steps through a ramp, each carried particle sits at its start turned by the
    drum's angle f_drum[angle] (exact trapezoid of the linear ramp: to round-off, 1e-12 of R), moves at
    Omega e_y x r and spins at Omega e_y; a shaped one's orientation is turned by the same angle; the bed
    particle (no gravity, no contact) stays where it is."""
    sim = dem.Simulation(screen=False)
    sim.commands(CARRY.format(LAW=LAW, R=R, integ="bed", fixgroup="bed"))
    order = np.argsort(sim.atom.local("tag"))
    x0 = sim.atom.local("x")[order].copy()
    q0 = sim.atom.local("quat")[order].copy()
    sim.run(2000)
    order = np.argsort(sim.atom.local("tag"))
    x, v = sim.atom.local("x")[order], sim.atom.local("v")[order]
    w, q = sim.atom.local("omega")[order], sim.atom.local("quat")[order]
    drum = sim.modify.find("drum")
    th, om = drum.angle, drum.omega
    assert om == pytest.approx(40 * 2 * math.pi / 60, rel=1e-15)
    assert th == pytest.approx(om * (sim.update.time - 0.005), rel=1e-12)      # ramp over 0.01 s
    # a turn by th about +y: (z, x) -> (z cos - x sin, z sin + x cos)
    c, s = math.cos(th), math.sin(th)
    for k in (0, 1):
        expect = np.array([s * x0[k, 2] + c * x0[k, 0], x0[k, 1], c * x0[k, 2] - s * x0[k, 0]])
        assert np.abs(x[k] - expect).max() < 1e-12 * R
        assert np.abs(v[k] - om * np.cross([0.0, 1.0, 0.0], x[k])).max() < 1e-12 * om * R
        assert np.abs(w[k] - [0.0, om, 0.0]).max() < 1e-12 * om
    # the cube's orientation: the turn about y composed with its start (w x y z, scalar first)
    h = np.array([math.cos(th / 2), 0.0, math.sin(th / 2), 0.0])
    hw, hv, qw, qv = h[0], h[1:], q0[1, 0], q0[1, 1:]
    expect = np.r_[hw * qw - hv @ qv, hw * qv + qw * hv + np.cross(hv, qv)]
    assert np.abs(q[1] - expect).max() < 1e-12
    assert np.abs(x[2] - x0[2]).max() < 1e-15        # no gravity, no contact: the bed sphere stays put


@pytest.mark.parametrize("integ, fixgroup, message", [
    ("all", "bed", "fix integ nve/shape integrates particles of group wall"),
    ("bed", "all", "the carried particles are in the fix's group all"),
])
def test_carried_group_must_be_the_drums_alone(integ, fixgroup, message):
    sim = dem.Simulation(screen=False)
    sim.commands(CARRY.format(LAW=LAW, R=R, integ=integ, fixgroup=fixgroup))
    with pytest.raises(DemError, match=message):
        sim.run(1)


def _tool(name):
    """A script of tools/ as a module."""
    import importlib.util
    import os
    path = os.path.join(os.path.dirname(__file__), os.pardir, "tools", f"{name}.py")
    spec = importlib.util.spec_from_file_location(name, path)
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)
    return tool


def test_drum_coordination_plot(tmp_path):
    """tools/drum_coordination.py reads the regime tables kept in docs/data (Fig. 25 for several shapes)."""
    import os
    root = os.path.join(os.path.dirname(__file__), os.pardir)
    tool = _tool("drum_coordination")
    crosses = os.path.join(root, "docs", "data", "drum_sweep", "regimes.txt")
    t = tool.read_regimes(crosses)
    assert list(t["rpm"]) == [5, 20, 42, 80, 150, 200, 250] and t["coordination"][0] == 4.06
    # a table with the coordination per contact point too (crosses touching at several beams)
    points = os.path.join(root, "docs", "data", "drum_sweep", "cross3d_points", "regimes.txt")
    p = tool.read_regimes(points)
    assert list(p["rpm"]) == [42, 150, 200, 250] and (p["coord_points"] > p["coordination"]).all()
    out = tmp_path / "c.png"
    tool.main([f"{crosses}:3D crosses", os.path.join(root, "docs", "data", "drum_sweep", "spheres", "regimes.txt"),
               f"{points}:3D crosses, per point", "-o", str(out)])
    assert out.stat().st_size > 0


def test_drum_regime_map(tmp_path):
    """tools/drum_regime_map.py draws Fig. 30 from the regime tables kept in docs/data, the paper's rows first."""
    import os
    root = os.path.join(os.path.dirname(__file__), os.pardir)
    tool = _tool("drum_regime_map")
    data = os.path.join(root, "docs", "data", "drum_sweep")
    tables = [os.path.join(data, "regimes.txt") + ":3D crosses", os.path.join(data, "cubes", "regimes.txt") + ":cubes"]
    rows = tool.rows_of(tables)
    assert [label for label, _ in rows] == ["Part III (text), spheres [39]", "Part III (text), 3D crosses",
                                            "dem, 3D crosses", "dem, cubes"]
    assert rows[2][1][250.0] == "centrifuging" and rows[3][1][20.0] == "avalanching"
    out = tmp_path / "m.png"
    tool.main(tables + ["-o", str(out)])
    assert out.stat().st_size > 0
