"""compute repose on beds of known angle: particles of a jittered grid below a straight (or S-shaped) free
surface in a drum's cross-section, from flat to near vertical, with particles in flight and on the wall.

The tolerance, 2.5 degrees, comes from the beds' grain: the top of a column is the outermost grid point
under the line, scattered across it by about a spacing d / sqrt(12) = 0.6 mm; a least-squares line through
14 such tops over the central 34 mm of the surface has a slope error of 0.6 / 36.7 = 0.016 rad (0.9
degree) standard deviation. Measured on the 156 beds of test_known_angle: largest error 2.3 degrees,
mean 0.57, standard deviation 0.73 (TOL is 3.4 of them). Columns standing vertically (the compute until
2026-12-04) read the same beds within 2.5 degrees up to 40 degrees, then miss 2 of 12 at 50, 3 at 55, 6 at
60, 11 at 65 and all 12 from 70 to 85 (70 read as 50.1-63.8, 75 as -16.1 to 65.8, 85 as -16.6 to 60.2)."""
import math

import numpy as np
import pytest

import dem
from dem_process.compute_drum import surface_fit

R, r = 0.025, 0.001          # drum radius, particle radius: a 50 mm drum
TOL = 2.5                    # degrees (module docstring)
GAP = 4 * r                  # compute repose's gap: SURFACE_GAP largest radii


def chord_offset(fill):
    """Signed distance from the axis of the chord below which the bed fills `fill` of the section."""
    lo, hi = -R, R
    for _ in range(60):
        c = 0.5 * (lo + hi)
        phi = 2 * math.acos(-c / R)                    # central angle of the segment below the chord
        lo, hi = (lo, c) if (phi - math.sin(phi)) / (2 * math.pi) > fill else (c, hi)
    return c


def bed(angle, seed, fill=0.35, s_shape=0.0, flying=0, wall=0, layers=4):
    """Cross-section (h, u) of a bed under a surface at `angle` degrees: `layers` grids of spacing 2.04 r
    along the axis, each shifted at random and jittered by a quarter spacing, seen together. `s_shape`
    bends the surface into an S by s_shape L ((s/L)^3 - 0.6 s/L) across it (s along it, L the central
    half-length): a cubic with no first moment over the central part, so that the least-squares line there
    stays the chord. `flying` particles 4 to 10 diameters above the surface; `wall` particles on the wall
    above the high end of the bed."""
    rng = np.random.default_rng(seed)
    a = math.radians(angle)
    t, n = np.array([math.cos(a), math.sin(a)]), np.array([-math.sin(a), math.cos(a)])
    c = chord_offset(fill)
    d = 2.04 * r
    g = np.arange(-R, R + d, d)
    grid = np.array([(x, z) for x in g for z in g])
    p = np.vstack([grid + rng.uniform(0, d, 2) + rng.uniform(-d / 4, d / 4, grid.shape) for _ in range(layers)])
    half = math.sqrt(R * R - c * c)
    s = p @ t / (0.7 * half)
    p = p[(np.hypot(p[:, 0], p[:, 1]) < R - r) & (p @ n < c + s_shape * 0.7 * half * (s ** 3 - 0.6 * s))]
    extra = [rng.uniform(-0.5, 0.5) * half * t + (c + rng.uniform(8, 20) * r) * n for _ in range(flying)]
    top = half * t + c * n                             # the high end of the chord
    for _ in range(wall):
        phi = math.atan2(top[1], top[0]) + rng.uniform(0.1, 0.6) * math.copysign(1, math.cos(a))
        extra.append((R - r) * np.array([math.cos(phi), math.sin(phi)]))
    return np.vstack([p] + [np.array(extra).reshape(-1, 2)])


KINDS = {"flat": {}, "S": {"s_shape": 0.15}, "reversed S": {"s_shape": -0.15},
         "in flight and on the wall": {"flying": 8, "wall": 8}}


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("angle", [0, 10, 20, 30, 40, 50, 55, 60, 65, 70, 75, 80, 85])
def test_known_angle(angle, kind):
    """Three beds per angle and kind, 35 % full as the papers' drums, within TOL."""
    for seed in range(3):
        h, u = bed(angle, seed, **KINDS[kind]).T
        got, slope, _, used, _ = surface_fit(h, u, gap=GAP)
        assert got == pytest.approx(angle, abs=TOL), (seed, got)
        assert used >= 10 and slope == pytest.approx(math.tan(math.radians(got)))


@pytest.mark.parametrize("fill", [0.2, 0.5, 0.65])
def test_other_fillings_and_mirror(fill):
    """Other fillings (the start frame is the bed's long axis at any filling, its normal towards the axis)
    and surfaces falling to the right (negative angles)."""
    for angle in (-75, -40, 40, 75):
        for seed in range(3):
            h, u = bed(angle, seed, fill=fill, flying=4, wall=4).T
            assert surface_fit(h, u, gap=GAP)[0] == pytest.approx(angle, abs=TOL), (angle, seed)


def test_intercept_and_roughness():
    """The line's height at the axis is the chord's, c / cos(angle) (within half a spacing across it,
    the tops lying under the line by up to a spacing), and a flat surface's roughness is under a
    spacing."""
    for angle in (20, 70):
        h, u = bed(angle, 0).T
        got, _, height, _, rough = surface_fit(h, u, gap=GAP)
        c = chord_offset(0.35)
        assert height * math.cos(math.radians(got)) == pytest.approx(c - 1.02 * r, abs=1.02 * r)
        assert rough < 2.04 * r


def test_compute_repose_on_a_read_bed(tmp_path):
    """The compute itself, `run 0` on beds read with read_data (axis y, gravity -z: h = up x axis = -x,
    so a surface rising to +x has a negative signed angle), at angles the vertical columns misread."""
    for angle in (40, 70, 80):
        rows = [(x, (k + 0.5) * 2.04 * r, z) for k in range(4)       # a layer of its own along the axis
                for x, z in bed(angle, 10 * k + 1, flying=1, wall=1, layers=1)]
        lines = [f"{i + 1} 1 {2 * r!r} 2500 {float(x)!r} {y!r} {float(z)!r} 0 0 0" for i, (x, y, z) in enumerate(rows)]
        path = tmp_path / f"bed{angle}.data"
        path.write_text(f"bed\n\n{len(lines)} atoms\n1 atom types\n\n{-R - r} {R + r} xlo xhi\n0 {4 * 2.04 * r} "
                        f"ylo yhi\n{-R - r} {R + r} zlo zhi\n\nAtoms # sphere\n\n" + "\n".join(lines) + "\n")
        sim = dem.Simulation(screen=False)
        sim.commands(f"""
            boundary f p f
            read_data {path}
            pair_style sphere
            pair_coeff * * kn 1e5 en 0.5 mu 0.5
            fix g all gravity 9.81 vector 0 0 -1
            fix drum all wall/drum y 0 0 {R} rpm 0 kn 1e5 en 0.5 mu 0.5
            compute rep all repose drum
            timestep 1e-5
            thermo 0
            run 0
        """)
        assert sim.thermo_keyword("c_rep") == pytest.approx(angle, abs=TOL)
        assert sim.thermo_keyword("c_rep[1]") == pytest.approx(-sim.thermo_keyword("c_rep"))


def test_columns_split_over_processes_have_the_same_tops():
    """What the ranks exchange: each finds the runs of its own particles (cut at gaps), and the columns
    joined from every rank's runs have the tops the whole bed has, however the particles are split (slabs
    across and along the surface, or at random: a column's particles then alternate between ranks)."""
    from dem_process.compute_drum import _column_tops, _runs
    rng = np.random.default_rng(5)
    for angle in (30, 75):
        h, u = bed(angle, 1, flying=8, wall=8).T
        a = math.radians(angle)
        s, n = h * math.cos(a) + u * math.sin(a), u * math.cos(a) - h * math.sin(a)
        k = np.minimum(((s - s.min()) / np.ptp(s) * 20).astype(np.int64), 19)
        whole = _column_tops(_runs(s, n, k, GAP, h, u), 20, GAP)
        for owner in (h > 0, u > -0.3 * R, rng.integers(0, 3, len(h)), rng.integers(0, 7, len(h))):
            owner = np.asarray(owner).astype(int)
            parts = [_runs(s[owner == p], n[owner == p], k[owner == p], GAP, h[owner == p], u[owner == p])
                     for p in np.unique(owner)]
            assert np.array_equal(_column_tops(np.concatenate(parts), 20, GAP), whole, equal_nan=True)


def test_compute_repose_on_one_and_two_ranks(tmp_path):
    """The compute on 2 ranks (the bed cut across the drum) reads the angle of 1 rank: no rank holds the
    whole bed, the ranks exchange a few numbers per bin."""
    from conftest import MPIEXEC
    from test_mpi import run_dem, thermo_rows
    if MPIEXEC is None:
        pytest.skip("mpiexec not found")
    rows = [(x, (k + 0.5) * 2.04 * r, z) for k in range(4) for x, z in bed(70, 10 * k + 1, flying=1, wall=1,
                                                                           layers=1)]
    lines = [f"{i + 1} 1 {2 * r!r} 2500 {float(x)!r} {y!r} {float(z)!r} 0 0 0" for i, (x, y, z) in enumerate(rows)]
    (tmp_path / "bed.data").write_text(
        f"bed\n\n{len(lines)} atoms\n1 atom types\n\n{-R - r} {R + r} xlo xhi\n0 {4 * 2.04 * r} ylo yhi\n"
        f"{-R - r} {R + r} zlo zhi\n\nAtoms # sphere\n\n" + "\n".join(lines) + "\n")
    script = f"""boundary f p f
processors 2 1 1
read_data bed.data
pair_style sphere
pair_coeff * * kn 1e5 en 0.5 mu 0.5
fix drum all wall/drum y 0 0 {R} rpm 0 kn 1e5 en 0.5 mu 0.5
compute rep all repose drum
thermo_style custom step c_rep c_rep[2] c_rep[3] c_rep[4] c_rep[5]
timestep 1e-5
run 0
"""
    got = []
    for nprocs in (1, 2):
        run_dem(tmp_path, script.replace("processors 2 1 1\n", "" if nprocs == 1 else "processors 2 1 1\n"),
                nprocs, f"log.{nprocs}")
        got.append([float(w) for w in thermo_rows(tmp_path / f"log.{nprocs}")[-1][1:]])
    assert got[0][0] == pytest.approx(70, abs=TOL)
    assert got[1] == pytest.approx(got[0], rel=1e-9, abs=1e-12)     # the same tops; sums in another order


@pytest.mark.parametrize("words, message", [
    ("repose", "expected"),
    ("repose nodrum", "no fix with ID 'nodrum'"),
    ("repose g", "fix g is a gravity, not a rotating drum"),
    ("repose drum bins 2", "bins must be within 3..100000"),
    ("repose drum bins 1000000000", "bins must be within 3..100000"),
    ("repose drum bins 2.5", "bins must be an integer, got '2.5'"),
    ("repose drum trim nan", "trim must be a finite number, got .nan."),
    ("repose drum trim 0.5", "0 <= trim < 0.5"),
    ("repose drum trim inf", "trim"),
    ("repose drum bins", "bins"),
    ("repose drum bind 20", "unknown keyword 'bind'"),
])
def test_bad_words(words, message):
    """Every bad word is an error naming the line: at the definition, or at the first evaluation for a
    fix that is not (yet) a drum."""
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary f p f
        region box block -0.03 0.03 0 0.01 -0.03 0.03
        create_box 1 box
        create_atoms 1 single 0 0.005 -0.02 radius 0.001 density 2500
        pair_style sphere
        pair_coeff * * kn 1e5 en 0.5 mu 0.5
        fix g all gravity 9.81 vector 0 0 -1
        fix drum all wall/drum y 0 0 {R} rpm 0 kn 1e5 en 0.5 mu 0.5
        timestep 1e-5
    """)
    with pytest.raises(dem.DemError, match=message):
        sim.commands(f"compute c all {words}\nthermo_style custom step c_c\nrun 0")
