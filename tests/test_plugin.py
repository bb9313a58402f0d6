"""A third-party package registered through the `dem` entry-point group adds a fix that a script uses.
The package (tests/plugin_example) is installed with pip into a temporary directory, exactly as a user
would install it, and a `dem` process with that directory on its path runs a script using `fix nudge`."""
import math
import os
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))

SCRIPT = """
boundary        p p p
region          box block 0 1 0 1 0 1
create_box      1 box
create_atoms    1 single 0.5 0.5 0.5 radius 0.1 density 1000
fix             move all nve/sphere
fix             push all nudge 0.0 0.0 {fz}
timestep        0.001
run             100
print           "KE $(ke:%.17g)"
"""


@pytest.fixture(scope="module")
def plugin_dir(tmp_path_factory):
    target = tmp_path_factory.mktemp("site")
    subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", "--no-deps", "--no-build-isolation",
                    "--target", str(target), os.path.join(HERE, "plugin_example")], check=True)
    return target


def run(tmp_path, plugin_dir, script):
    path = tmp_path / "in.nudge"
    path.write_text(script)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(plugin_dir), os.environ.get("PYTHONPATH", "")]))
    return subprocess.run([sys.executable, "-m", "dem", "-in", str(path), "-log", "none"], cwd=tmp_path,
                          env=env, capture_output=True, text=True)


def test_third_party_fix_is_found_and_used(tmp_path, plugin_dir):
    fz = 0.01
    out = run(tmp_path, plugin_dir, SCRIPT.format(fz=fz))
    assert out.returncode == 0, out.stderr
    ke = float(out.stdout.split("KE")[1].split()[0])
    # a constant force is integrated exactly by leap-frog: v = F t / m after t = 100 x 1 ms
    m = 1000.0 * 4.0 / 3.0 * math.pi * 0.1 ** 3
    assert ke == pytest.approx(0.5 * m * (fz * 0.1 / m) ** 2, rel=1e-12)


def test_without_the_plugin_the_style_is_unknown(tmp_path):
    path = tmp_path / "in.nudge"
    path.write_text(SCRIPT.format(fz=0.01))
    out = subprocess.run([sys.executable, "-m", "dem", "-in", str(path), "-log", "none"], cwd=tmp_path,
                         capture_output=True, text=True)
    assert out.returncode != 0
    assert "in.nudge:7: unknown fix style 'nudge'" in out.stderr
