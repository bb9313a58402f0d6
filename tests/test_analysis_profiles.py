"""fix ave/profile: binned profiles of per-particle quantities (Descantes 2022 Figs. 7, 13, 16), against
fields whose profile is known in closed form."""
import subprocess
import sys

import numpy as np
import pytest

import dem
from dem.errors import DemError
from dem_process.profile_bins import inertial_number

B = 0.01          # lattice spacing of the sphere tests (m)
GAMMA = 3.0       # shear rate of the imposed field (1/s)
U = 0.2           # velocity fluctuation (m/s)


def site(*x):
    return " ".join(repr(float(c)) for c in x)


def sphere_lattice(path, values, extra=""):
    """4 x 4 x 8 spheres of radius 0.3 B on a simple cubic lattice of spacing B (centres at (i + 1/2) B),
    vx = GAMMA z, vy = +U or -U alternately in each layer (8 of each), no contact; a run of one step
    without integrator samples them once."""
    lines = []
    for i in range(4):
        for j in range(4):
            for k in range(8):
                x, y, z = (np.array([i, j, k]) + 0.5) * B
                vy = U if (i + j) % 2 else -U
                lines.append(f"create_atoms 1 single {site(x, y, z)} radius {0.3 * B} density 2500 "
                             f"v {float(GAMMA * z)!r} {float(vy)!r} 0")
    sim = dem.Simulation(screen=False)
    sim.commands(f"""units si
boundary p p f
region box block 0 {4 * B} 0 {4 * B} 0 {8 * B}
create_box 1 box
""" + "\n".join(lines) + f"""
pair_style sphere
pair_coeff * * kn 1e3 en 0.5
timestep 1e-5
fix p all ave/profile 1 1 {path} z 8 {values}
""" + extra)
    sim.run(1)
    return sim, np.loadtxt(path)


def test_linear_velocity_and_temperature(tmp_path):
    """Each slab holds one lattice layer: count 16, vx = GAMMA z_layer, vy = 0 and Tyy = U^2 (eq. 13:
    <vy^2> - <vy>^2), Txx = Tzz = 0 to round-off (the variance of equal numbers: 1e-12 of vx^2), T = U^2;
    bin centres at the layer heights. Bound 1e-9 relative: the file's 10 significant digits."""
    sim, d = sphere_lattice(tmp_path / "p.dat", "count vx vy Txx Tyy Tzz T density")
    assert d.shape == (8, 12)
    assert np.array_equal(d[:, 0], np.ones(8)) and np.array_equal(d[:, 2], np.arange(1, 9))
    zc = (np.arange(8) + 0.5) * B
    assert d[:, 3] == pytest.approx(zc, rel=1e-9)       # the file has 10 significant digits
    count, vx, vy, txx, tyy, tzz, t, dens = d[:, 4:].T
    assert np.array_equal(count, np.full(8, 16.0))
    assert vx == pytest.approx(GAMMA * zc, rel=1e-9)
    assert np.all(np.abs(vy) < 1e-15)
    assert np.all(np.abs(txx) < 1e-12 * (GAMMA * 8 * B) ** 2) and np.all(np.abs(tzz) < 1e-15)
    assert tyy == pytest.approx(np.full(8, U * U), rel=1e-9)
    assert t == pytest.approx(np.full(8, U * U), rel=1e-9)
    assert dens == pytest.approx(np.full(8, 16 / (16 * B ** 3)), rel=1e-9)


def test_kinetic_stress(tmp_path):
    """Without contacts the stress is kinetic only: sigma_yy = sum m v'_y^2 / V = N m U^2 / V, v' about the
    mean (vx = GAMMA z is streaming within a slab: no xx part), per slab 16 m U^2 / (16 B^3); the global
    compute takes v' about the mean of the whole selection, so its xx part is the variance of GAMMA z over
    the layers: sum m (GAMMA (z - <z>))^2 / V. Both exact to round-off (bound 1e-12; the file's profile
    1e-9, its 10 significant digits)."""
    sim, d = sphere_lattice(tmp_path / "k.dat", "syy sxx kinetic yes", "compute s all stress kinetic yes\n")
    m = 2500 * 4 / 3 * np.pi * (0.3 * B) ** 3
    assert d[:, 4] == pytest.approx(np.full(8, m * U * U / B ** 3), rel=1e-9)      # 10 digits in the file
    assert np.all(np.abs(d[:, 5]) < 1e-12 * m * U * U / B ** 3)
    s = sim.computes["s"].vector()
    vol = 4 * 4 * 8 * B ** 3
    z = (np.arange(8) + 0.5) * B
    assert s[1] == pytest.approx(128 * m * U * U / vol, rel=1e-12)
    assert s[0] == pytest.approx(16 * m * float(np.sum((GAMMA * (z - z.mean())) ** 2)) / vol, rel=1e-12)


def test_solid_fraction_of_a_cube_lattice(tmp_path):
    """4^3 cubes of side 1 on a periodic simple cubic lattice of spacing 1.25 (centres at (k + 1/2) 1.25),
    20 slabs of 0.25 along z, grid spacing dx = 0.125 (10 points per period, no point on a cube face): a slab
    wholly inside a cube layer has phi = (1 / 1.25)^2 = 0.64, and the slabs that a layer's faces cut in
    half (each 0.125 of cube, 0.125 of gap) 0.32: the analytic fraction, exact on this grid (bound 1e-12);
    the mean over all slabs is (1 / 1.25)^3 = 0.512."""
    lines = [f"create_atoms 1 single {site(*((np.array([i, j, k]) + 0.5) * 1.25))} shape c density 1"
             for i in range(4) for j in range(4) for k in range(4)]
    path = tmp_path / "phi.dat"
    sim = dem.Simulation(screen=False)
    sim.commands("""units si
boundary p p p
region box block 0 5 0 5 0 5
create_box 1 box
shape c cube 1
""" + "\n".join(lines) + f"""
pair_style polyhedron/multipoint
pair_coeff * * kn 1e3 en 0.5
timestep 1e-3
fix p all ave/profile 1 1 {path} z 20 phi dx 0.125
""")
    sim.run(1)
    phi = np.loadtxt(path)[:, 4]
    lo = np.arange(20) * 0.25
    cover = sum(np.clip(np.minimum(lo + 0.25, 1.25 * k + 1.125) - np.maximum(lo, 1.25 * k + 0.125), 0, None)
                for k in range(4)) / 0.25
    assert phi == pytest.approx(0.64 * cover, abs=1e-12)
    assert sorted(set(np.round(phi, 12))) == [0.32, 0.64]
    assert phi.mean() == pytest.approx(0.512, abs=1e-12)


def test_inertial_number_of_a_simple_shear():
    """I = gamma_dot d / sqrt(P / rho): a linear profile vx = GAMMA z (central differences are exact for it),
    P = 100 Pa, d = 2 mm, rho = 2500: I = GAMMA d / sqrt(P / rho) in every bin; a bin without pressure: NaN."""
    z = (np.arange(6) + 0.5) * 0.01
    v = np.zeros((6, 3))
    v[:, 0] = GAMMA * z
    p = np.full(6, 100.0)
    p[5] = 0.0
    out = inertial_number(z, v, 2, p, np.full(6, 0.002), np.full(6, 2500.0))
    assert out[:5] == pytest.approx(np.full(5, GAMMA * 0.002 / np.sqrt(100.0 / 2500.0)), rel=1e-12)
    assert np.isnan(out[5])


def test_bad_input(tmp_path):
    sim = dem.Simulation(screen=False)
    sim.commands("""units si
region box block 0 1 0 1 0 1
create_box 1 box
""")
    with pytest.raises(DemError, match="axis must be x, y or z"):
        sim.command(f"fix p all ave/profile 1 1 {tmp_path / 'a'} w 8 count")
    with pytest.raises(DemError, match="unknown value or keyword 'speed'"):
        sim.command(f"fix p all ave/profile 1 1 {tmp_path / 'a'} z 8 speed")
    with pytest.raises(DemError, match="multiple of Nevery"):
        sim.command(f"fix p all ave/profile 2 3 {tmp_path / 'a'} z 8 count")
    with pytest.raises(DemError, match="no value"):
        sim.command(f"fix p all ave/profile 1 1 {tmp_path / 'a'} z 8 bounds 0 1")


def test_time_average_over_samples(tmp_path):
    """Free fall of the lattice under gravity (nve/sphere, no contact): ave/profile 1 2 averages samples at
    steps 1 and 2, so its vz is the mean of the two per-step profiles of ave/profile 1 1, and its Tzz, eq. 13
    with the means over the bin and time, is the variance of the two sample velocities, (g dt / 2)^2 (one
    step apart: vz differs by g dt). Bounds: 1e-9 relative for vz (the file's 10 digits), 1e-8 for the
    differences of file values (vz1 - vz2 is a third of vz: a digit lost)."""
    one, two = tmp_path / "one.dat", tmp_path / "two.dat"
    sim, _ = sphere_lattice(tmp_path / "p.dat", "count", f"""fix nve all nve/sphere
fix g all gravity 9.81 vector 0 0 -1
fix one all ave/profile 1 1 {one} z 8 vz
fix two all ave/profile 1 2 {two} z 8 vz Tzz count
""")
    sim.run(1)       # sphere_lattice ran step 1 with the fixes defined: samples at steps 1 and 2
    a, b = np.loadtxt(one), np.loadtxt(two)
    steps = sorted(set(a[:, 0]))
    assert steps == [1.0, 2.0] and sorted(set(b[:, 0])) == [2.0]
    v1, v2 = a[a[:, 0] == 1, 4], a[a[:, 0] == 2, 4]
    assert b[:, 4] == pytest.approx((v1 + v2) / 2, rel=1e-9)
    assert v1 - v2 == pytest.approx(np.full(8, 9.81 * 1e-5), rel=1e-8)
    assert b[:, 5] == pytest.approx(((v1 - v2) / 2) ** 2, rel=1e-8)
    assert np.array_equal(b[:, 6], np.full(8, 16.0))


def test_ave_vector_bad_input(tmp_path):
    sim = dem.Simulation(screen=False)
    sim.commands("""units si
region box block 0 1 0 1 0 1
create_box 1 box
compute g all rdf 10 0.2
compute q all nematic
""")
    with pytest.raises(DemError, match="differ in length"):
        sim.command(f"fix a all ave/vector 1 1 {tmp_path / 'a'} c_g c_q")
    with pytest.raises(DemError, match="not a compute vector"):
        sim.command(f"fix a all ave/vector 1 1 {tmp_path / 'a'} c_g[2]")
    with pytest.raises(DemError, match="unknown compute ID"):
        sim.command(f"fix a all ave/vector 1 1 {tmp_path / 'a'} c_nope")


@pytest.mark.parametrize("axis", ["y", "z"])
def test_radial_bins_of_a_rigid_rotation(tmp_path, axis):
    """Rings k = 0..4 of 4 (k + 1) spheres at radius (k + 1/2) B about a line along `axis` through (C1, C2),
    turning rigidly at OMEGA about +axis (v = OMEGA e_axis x r, the sense of wall/drum's positive rpm):
    each radial bin of width B holds one ring, vt = OMEGA r_k, vr = 0, count 4 (k + 1), density the count
    over the ring's volume pi ((k+1)^2 - k^2) B^2 L. Exact to the file's 10 digits (1e-9)."""
    omega, c1, c2, length = 2.0, 0.003, -0.002, 4 * B
    a = "xyz".index(axis)
    b, c = [d for d in range(3) if d != a]
    lines, rings = [], 5
    for k in range(rings):
        r = (k + 0.5) * B
        for j in range(4 * (k + 1)):
            t = 2 * np.pi * (j + 0.25) / (4 * (k + 1))
            x = np.zeros(3)
            x[a], x[b], x[c] = 2 * B, c1 + r * np.cos(t), c2 + r * np.sin(t)
            centre = np.zeros(3)
            centre[b], centre[c] = c1, c2
            v = omega * np.cross(np.eye(3)[a], x - centre)
            lines.append(f"create_atoms 1 single {site(*x)} radius {0.05 * B} density 2500 v {site(*v)}")
    lo, hi = np.full(3, -6 * B), np.full(3, 6 * B)
    lo[a], hi[a] = 0.0, length
    sim = dem.Simulation(screen=False)
    path = tmp_path / "r.dat"
    sim.commands(f"""units si
boundary {' '.join('p' if d == a else 'f' for d in range(3))}
region box block {lo[0]} {hi[0]} {lo[1]} {hi[1]} {lo[2]} {hi[2]}
create_box 1 box
""" + "\n".join(lines) + f"""
pair_style sphere
pair_coeff * * kn 1e3 en 0.5
timestep 1e-5
fix p all ave/profile 1 1 {path} radial {rings} count density vr vt cylinder {axis} {c1} {c2} bounds 0 {rings * B}
""")
    sim.run(1)
    d = np.loadtxt(path)
    k = np.arange(rings)
    assert d[:, 3] == pytest.approx((k + 0.5) * B, rel=1e-9)
    count, dens, vr, vt = d[:, 4:].T
    assert np.array_equal(count, 4.0 * (k + 1))
    assert dens == pytest.approx(4 * (k + 1) / (np.pi * (2 * k + 1) * B * B * length), rel=1e-9)
    assert np.all(np.abs(vr) < 1e-12) and vt == pytest.approx(omega * (k + 0.5) * B, rel=1e-9)


@pytest.mark.parametrize("args, message", [
    ("radial 4 count", "radial bins need 'cylinder A C1 C2'"),
    ("z 4 vt", "vt need radial bins"),
    ("radial 4 phi cylinder z 0 0", "phi are for slabs"),
    ("z 4 count cylinder z 0 0", "'cylinder' goes with radial bins"),
])
def test_radial_bins_bad_input(tmp_path, args, message):
    sim = dem.Simulation(screen=False)
    with pytest.raises(DemError, match=message):
        sim.commands(f"""units si
boundary f f f
region box block -1 1 -1 1 -1 1
create_box 1 box
fix p all ave/profile 1 1 {tmp_path / 'x.dat'} {args}
""")


BED = """units si
boundary p p f
region box block 0 0.01 0 0.01 0 0.01
create_box 1 box
create_atoms 1 random 20 5 box radius 0.0005 density 2500
pair_style sphere
pair_coeff * * kn 1000 en 0.5
timestep 1e-6
"""


@pytest.mark.parametrize("lines, wrong, message", [
    ("fix p all ave/profile 1 1 p.dat z 4 phi dx 1e-9\nrun 1\n", "fix p", "1e+21 grid points"),
    ("fix p all ave/profile 1 1 p.dat z 4 phi resolution 1e7\nrun 1\n", "run", "grid points per evaluation"),
    ("compute por all porosity box dx 1e-9\nthermo_style custom step c_por[1]\nrun 0\n", "run",
     "compute por porosity: a grid spacing of 1e-09 makes 1e+21 grid points"),
    ("fix p all ave/profile 1 1 p.dat z 1e9 count\nrun 1\n", "fix p", "NBIN must be in 1..1000000"),
    ("fix p all ave/profile 1 1 p.dat z 4 count bounds nan 0.01\nrun 1\n", "fix p",
     "bounds must be a finite number, got 'nan'"),
    ("fix p all ave/profile 1 1 p.dat z 4 count bounds 0 inf\nrun 1\n", "fix p",
     "bounds must be a finite number, got 'inf'"),
], ids=["dx", "resolution", "porosity dx", "nbin", "bounds nan", "bounds inf"])
def test_a_grid_or_bins_without_bound_are_refused(tmp_path, lines, wrong, message):
    """An absurd spacing or bin count used to make a sample that never ends (a run no signal stops) or a
    huge allocation; NaN bounds were taken. A subprocess, killed after 60 s: a regression never hangs."""
    script = BED + lines
    (tmp_path / "in.test").write_text(script)
    try:
        out = subprocess.run([sys.executable, "-m", "dem", "-in", "in.test", "-log", "none"], cwd=tmp_path,
                             capture_output=True, text=True, timeout=60)
    except subprocess.TimeoutExpired:
        pytest.fail("the run did not end")
    line = next(i for i, text in enumerate(script.splitlines(), 1) if text.startswith(wrong))
    assert out.returncode == 1 and "Traceback" not in out.stderr, out.stderr
    assert f"in.test:{line}: " in out.stderr and message in out.stderr, out.stderr
