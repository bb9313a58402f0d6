"""The free-surface tool of the tile-spacer drum (tools/tilespacer_surface.py) on surfaces of known shape,
and the drum's input through its first steps."""
import importlib.util
import os

import numpy as np

import dem

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir)
spec = importlib.util.spec_from_file_location("tilespacer_surface", os.path.join(ROOT, "tools", "tilespacer_surface.py"))
ts = importlib.util.module_from_spec(spec)
spec.loader.exec_module(ts)


def test_inclined_bed_gives_its_angle():
    """A bed filling a drum of radius 0.15 below the line z = tan(30 deg) x, sampled densely: each column's
    highest point lies within one column width (5 mm) of the line, so the fitted slope is the line's to
    well under a degree (measured: 30.0 to 0.1)."""
    rng = np.random.default_rng(1)
    x = rng.uniform(-0.15, 0.15, 200_000)
    z = rng.uniform(-0.15, 0.15, 200_000)
    keep = (x * x + z * z < 0.15 ** 2) & (z < np.tan(np.radians(30.0)) * x)
    c, top = ts.surface_profile(x[keep], z[keep], 0.005, 0.15)
    assert np.isfinite(top).sum() > 40
    assert abs(ts.surface_angle(c, top) - 30.0) < 0.5
    assert ts.surface_angle(c, top[::-1]) < -29.0          # mirrored: falls towards +x


def test_avalanches_are_falls_of_the_angle():
    """A sawtooth: the angle rises from 40 to 50 degrees over 1 s, then falls back within 0.05 s, three
    times: three avalanches, one per fall; a ripple of 1 degree counts none."""
    t = np.arange(0, 3.3, 0.025)
    phase = t % 1.1
    angle = np.where(phase < 1.0, 40 + 10 * phase, 50 - 200 * (phase - 1.0))
    found = ts.avalanches(t, angle)
    assert len(found) == 3
    assert np.allclose(found, [1.05, 2.15, 3.25], atol=0.05)
    assert ts.avalanches(t, 45 + np.sin(20 * t)) == []


def test_input_runs_its_first_steps(tmp_path):
    """inputs/in.tilespacer_drum with 20 spacers and the phases cut to a few steps: the two walls and the
    glued pair style take the input's words, and the settled print runs."""
    sim = dem.Simulation(screen=False)
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        sim.commands(f"""variable N index 20
variable fill index 0.0015
variable settle index 0.00075
variable rotate index 0.00075
include {os.path.join(ROOT, 'inputs', 'in.tilespacer_drum')}
""")
    finally:
        os.chdir(cwd)
    assert sim.atom.natoms == 20
    assert (tmp_path / "tiles.h5").exists() and (tmp_path / "tiles.dat").exists()
