"""The post-processing tools are installed with the package: console scripts (dem-frames, dem-plot, ...),
`python -m dem.tools.NAME`, and the source tree's tools/NAME.py wrappers, all run from outside the source
tree (where `dem` would be the unbuilt sources) and using the installed plugins, not plugins/."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

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


def test_plot_series_script(outputs):
    res = run([console_script("dem-plot"), str(outputs / "d.dat"), "-o", str(outputs / "s.png")], cwd=outputs)
    assert res.returncode == 0, res.stderr[-2000:]
    assert (outputs / "s.png").exists()
