"""fix insert size distributions (lognormal, discrete) and mixtures of shapes (`mix`, mass or number
fractions): the drawn kinds and sizes against their distributions, the particles made from them, bad input.

Statistical bounds: a number fraction p of n draws has the binomial standard error sqrt(p (1 - p) / n); the
tests allow 4 of them (a failure by chance once in ~16000 runs)."""
import math

import numpy as np
import pytest

import dem
from dem.errors import DemError

N = 20_000
CUBE = 0.002                       # edge of the cube shape (volume 8e-9)
SPHERE_R = 0.001                   # sphere radius (volume 4.19e-9)


def _setup(fix, steps=None):
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary p p f
        region box block 0 0.2 0 0.2 0 0.2
        create_box 1 box
        shape c cube {CUBE}
        pair_style convex/gjk
        pair_coeff * * kn 1e4 en 0.5
        fix integ all nve/shape
        {fix}
        timestep 1e-6
        thermo 0
    """)
    if steps is not None:
        sim.run(steps)
    return sim


def _within(count, n, p):
    return abs(count / n - p) <= 4 * math.sqrt(p * (1 - p) / n)


def test_mix_number_fractions():
    """`mix c 0.3 sphere 0.7 fractions number`: kind 0 (the cube) with probability 0.3; cubes take the
    scale distribution (bounding radius sqrt(3) edge / 2 times the scale), spheres the radius one."""
    f = _setup(f"fix ins all insert 7 box count {N} mix c 0.3 sphere 0.7 fractions number "
               f"scale uniform 0.9 1.1 radius {SPHERE_R} density 2500").modify.find("ins")
    cubes = f.kinds == 0
    assert _within(cubes.sum(), N, 0.3)
    half_diag = math.sqrt(3) * CUBE / 2
    assert f.radii[cubes].min() >= 0.9 * half_diag and f.radii[cubes].max() <= 1.1 * half_diag
    assert np.array_equal(f.radii[~cubes], np.full((~cubes).sum(), SPHERE_R))


def test_mix_mass_fractions_by_default():
    """`mix c 0.5 sphere 0.5` (mass fractions, as LIGGGHTS): at one density, the number fraction of cubes is
    0.5 / V_c over (0.5 / V_c + 0.5 / V_s) = 0.3436 (V_c = 8e-9, V_s = 4.19e-9), and the mass of the drawn
    cubes is half the total within the binomial bound of that fraction."""
    f = _setup(f"fix ins all insert 11 box count {N} mix c 0.5 sphere 0.5 radius {SPHERE_R} "
               f"density 2500").modify.find("ins")
    vc, vs = CUBE ** 3, 4 / 3 * math.pi * SPHERE_R ** 3
    p = (0.5 / vc) / (0.5 / vc + 0.5 / vs)
    assert math.isclose(p, 0.3436, abs_tol=1e-4)
    assert _within((f.kinds == 0).sum(), N, p)


def test_mix_inserts_both_kinds_with_their_properties():
    """A run inserts the mixture: cubes carry the cube's shape index and mass density x scale^3 x V_c,
    spheres shape -1 and 4/3 pi r^3 density."""
    sim = _setup("fix ins all insert 3 box count 200 mix c 1 sphere 1 fractions number "
                 f"radius {SPHERE_R} density 2500", steps=1)
    assert sim.atom.natoms == 200
    shape = sim.gather("shape")
    m, r = sim.gather("rmass"), sim.gather("radius")
    cubes = shape >= 0
    assert 0 < cubes.sum() < 200
    scale = r[cubes] / (math.sqrt(3) * CUBE / 2)
    assert np.allclose(m[cubes], 2500 * CUBE ** 3 * scale ** 3, rtol=1e-6)    # the shape table's volume
    assert np.allclose(m[~cubes], 2500 * 4 / 3 * math.pi * SPHERE_R ** 3, rtol=1e-12)


def test_lognormal_and_discrete_radii():
    """lognormal MEDIAN SIGMA: the median of ln r is ln MEDIAN (its standard error 1.25 SIGMA / sqrt(N):
    bound 4 of them), the spread of ln r is SIGMA less the truncation at 3 SIGMA (1.3 % narrower: bound
    3 %), every draw within MEDIAN exp(+-3 SIGMA). discrete: each size in its number fraction."""
    f = _setup(f"fix ins all insert 5 box count {N} radius lognormal 0.001 0.25 density 2500").modify.find("ins")
    ln = np.log(f.radii)
    assert abs(np.median(ln) - math.log(0.001)) <= 4 * 1.25 * 0.25 / math.sqrt(N)
    assert ln.std() == pytest.approx(0.25, rel=0.03)
    assert f.radii.min() >= 0.001 * math.exp(-0.75) * (1 - 1e-12)
    assert f.radii.max() <= 0.001 * math.exp(0.75) * (1 + 1e-12)
    f = _setup(f"fix ins all insert 5 box count {N} radius discrete 0.001 1 0.002 3 density 2500").modify.find("ins")
    assert set(np.unique(f.radii)) == {0.001, 0.002}
    assert _within((f.radii == 0.001).sum(), N, 0.25)


def test_volfrac_with_a_mixture():
    """volfrac PHI draws kinds and sizes until their volume reaches PHI times the region's: the total
    passes the target only with the last particle."""
    f = _setup("fix ins all insert 9 box volfrac 0.01 mix c 0.5 sphere 0.5 radius lognormal 0.001 0.2 "
               "density 2500").modify.find("ins")
    vol = np.where(f.kinds == 0, CUBE ** 3 * (f.radii / (math.sqrt(3) * CUBE / 2)) ** 3,
                   4 / 3 * math.pi * f.radii ** 3)
    target = 0.01 * 0.2 ** 3
    assert vol.sum() >= target > vol[:-1].sum()
    assert (f.kinds == 0).any() and (f.kinds == 1).any()


@pytest.mark.parametrize("words, message", [
    ("mix c 0.5 sphere", "mix takes NAME WEIGHT pairs"),
    ("mix c -1 sphere 1", "mix weights must be >= 0"),
    ("mix c 0.5 q 0.5", "q"),
    ("shape c mix c 1", "give either 'shape NAME' or 'mix NAME W ...'"),
    ("fractions number", "'fractions' needs 'mix'"),
    ("mix c 1 fractions volume", "fractions must be mass or number"),
    ("mix c x", "mix weight"),
    ("radius discrete 0.001", "radius needs"),
    ("radius lognormal 0.001 -1", "radius lognormal needs MEDIAN > 0 and SIGMA >= 0"),
    ("mix density 1", "mix needs NAME WEIGHT pairs"),
])
def test_errors_name_the_line(words, message):
    with pytest.raises(DemError, match=message) as e:
        _setup(f"fix ins all insert 1 box count 10 {words}")
    assert "<string>:" in str(e.value)


def test_weights_are_normalised_with_a_warning():
    sim = dem.Simulation(screen=False)
    warnings = []
    sim.warning = warnings.append
    sim.commands(f"""
        region box block 0 0.2 0 0.2 0 0.2
        create_box 1 box
        shape c cube {CUBE}
        fix ins all insert 1 box count 10 mix c 2 sphere 2 fractions number
    """)
    assert any("mix weights sum to 4, normalised to 1" in w for w in warnings)
