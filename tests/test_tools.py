"""The post-processing tools are installed with the package: console scripts (dem-frames, dem-plot, ...),
`python -m dem.tools.NAME`, and the source tree's tools/NAME.py wrappers, all run from outside the source
tree (where `dem` would be the unbuilt sources) and using the installed plugins, not plugins/."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import dem

TOOLS = Path(__file__).resolve().parents[1] / "tools"
SCRIPT = """
boundary f f f
region box block 0 0.02 0 0.02 0 0.02
create_box 1 box
create_atoms 1 random 20 7 box radius 0.001 density 2500 v 0.1 0 0
fix 1 all nve/sphere
timestep 1e-5
thermo 0
fix s all print/series 5 {dat} ke
dump h all h5 10 {h5}
run 20
"""


@pytest.fixture(scope="module")
def outputs(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("tools")
    with dem.Simulation(screen=False) as sim:
        sim.commands(SCRIPT.format(dat=tmp / "d.dat", h5=tmp / "d.h5"))
    return tmp


def run(args, cwd):
    return subprocess.run(args, cwd=cwd, capture_output=True, text=True, timeout=120)


def console_script(name):
    found = shutil.which(name, path=os.path.dirname(sys.executable)) or shutil.which(name)
    if found is None:
        pytest.skip(f"{name} not on PATH (pip install the package)")
    return found


def test_frames_last_from_every_entry_point(outputs):
    ways = {"script": [console_script("dem-frames")],
            "module": [sys.executable, "-m", "dem.tools.drum_frames"],
            "wrapper": [sys.executable, str(TOOLS / "drum_frames.py")]}
    for way, cmd in ways.items():
        out_dir = outputs / way
        res = run(cmd + [str(outputs / "d.h5"), "--frames", "last", "--size", "200", "--out", str(out_dir)],
                  cwd=outputs)
        assert res.returncode == 0, f"{way}: {res.stderr[-2000:]}"
        assert (out_dir / "d_20.png").exists() and res.stdout.strip() == str(out_dir / "d_20.png"), way


def test_tools_leave_sys_path_alone_and_use_the_installed_plugins(outputs):
    """The old script put the source tree's plugins/ first on sys.path: after a non-editable install those
    sources lack their compiled kernels and the import failed."""
    code = ("import sys; before = list(sys.path)\n"
            "from dem.tools import drum_frames\n"
            f"drum_frames.main([{str(outputs / 'd.h5')!r}, '--frames', 'last', '--size', '100'])\n"
            "assert sys.path == before, 'sys.path changed'\n"
            "import dem_process; print(dem_process.__file__)\n")
    res = run([sys.executable, "-c", code], cwd=outputs)
    assert res.returncode == 0, res.stderr[-2000:]
    import dem_process
    assert res.stdout.splitlines()[-1] == dem_process.__file__


def test_plot_series_script(outputs, tmp_path):
    res = run([console_script("dem-plot"), str(outputs / "d.dat"), "-o", str(outputs / "s.png")], cwd=outputs)
    assert res.returncode == 0, res.stderr[-2000:]
    assert (outputs / "s.png").exists()
    res = run([console_script("dem-plot"), str(outputs / "d.dat")], cwd=tmp_path)    # into the current folder
    assert res.returncode == 0 and (tmp_path / "d_series.png").exists(), res.stderr[-2000:]


def test_frames_draw_the_dumps_shapes_as_dump_png_does(tmp_path, monkeypatch):
    """dem-frames takes the shape table the HDF5 dump holds: the outlines it draws are those dump png
    draws from the simulation's own table (the same renderer; each composite's convex pieces are the
    connected parts of its stored mesh), to round-off."""
    from dem.tools import drum_frames
    from dem_process.render import shaped_polygons, view_basis
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False)
    sim.commands("""boundary p p f
        region box block 0 0.03 0 0.03 0 0.03
        create_box 1 box
        shape x cross3d 0.004 aspect 4
        shape t tetrahedron 0.004
        create_atoms 1 single 0.008 0.015 0.015 shape x quat 0.9 0.3 0.2 0.1 density 2500
        create_atoms 1 single 0.022 0.015 0.015 shape t scale 1.5 quat 0.8 0.1 0.5 0.3 density 2500
        timestep 1e-6
        dump h all h5 1 d.h5
        run 0""")
    sim.close()
    step, _, arrays = drum_frames.read_frames("d.h5")[-1]
    stored = drum_frames.read_shapes("d.h5")
    args = (arrays["shape"], arrays["position"] - 0.015, arrays["orientation"], arrays["radius"], view_basis(1))
    owners, polygons = shaped_polygons(stored, *args)
    owners_sim, polygons_sim = shaped_polygons(sim.shapes, *args)
    assert owners.tolist() == owners_sim.tolist() == [0, 0, 0, 1]        # three beams, one tetrahedron
    for a, b in zip(polygons, polygons_sim):
        np.testing.assert_allclose(a, b, atol=1e-15)
    drum_frames.main(["d.h5", "--radius", "0", "--size", "200"])
    assert (tmp_path / f"d_{step}.png").exists()
