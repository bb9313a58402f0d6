"""Outputs never replace what is not a regular file: every output (write_data, restarts, dumps of every
style, the log, print and series files, the shape database) named after a device, a FIFO or a symbolic
link to a device is refused with `file:line: message` naming the path, and the device or FIFO is still
there afterwards (dem.files). The devices are made in tmp_path (mknod, as /dev/null and /dev/full are),
so that a regression run as root replaces a copy, never the machine's /dev/null; each run has a timeout
(a FIFO opened for writing blocks until a reader comes)."""
import os
import stat
import subprocess
import sys

import pytest

READY = """units si
boundary p p f
region box block 0 0.01 0 0.01 0 0.01
create_box 1 box
create_atoms 1 random 20 5 box radius 0.0005 density 2500
pair_style sphere
pair_coeff * * kn 1000 en 0.5
fix nve all nve/sphere
timestep 1e-6
thermo 0
"""

# (name, the lines after READY with T for the target's name, the target's name, the line refused)
CASES = [
    ("write_data", "write_data T\n", "t.10", "write_data"),
    ("write_restart", "write_restart T\n", "t.10", "write_restart"),
    ("restart", "restart 5 T\nrun 10\n", "t.10", "restart"),
    ("restart *", "restart 10 t.*\nrun 10\n", "t.10", "run"),
    ("dump custom", "dump d all custom 5 T id x y z\nrun 10\n", "t.10", "dump d"),
    ("dump custom *", "dump d all custom 10 t.* id x y z\nrun 10\n", "t.10", "run"),
    ("dump vtk *", "dump d all vtk 10 t_*.vtu\nrun 10\n", "t_10.vtu", "run"),
    ("dump vtp pvd", "dump d all vtp 10 p_*.vtp pvd T\nrun 10\n", "t.pvd", "dump d"),
    ("dump vtp *", "dump d all vtp 10 t_*.vtp\nrun 10\n", "t_10.vtp", "run"),
    ("dump h5", "dump d all h5 10 T\nrun 10\n", "t.h5", "dump d"),
    ("dump gsd", "dump d all gsd 10 T\nrun 10\n", "t.gsd", "dump d"),
    ("dump h5 xdmf", "dump d all h5 10 t.h5\nrun 10\n", "t.xdmf", "dump d"),
    ("dump png *", "dump d all png 10 t_*.png\nrun 10\n", "t_10.png", "run"),
    ("print file", "print hello file T\n", "t.10", "print"),
    ("print append", "print hello append T\n", "t.10", "print"),
    ("fix print/series", "fix s all print/series 5 T ke\nrun 10\n", "t.10", "fix s"),
    ("fix ave/profile", "fix p all ave/profile 1 5 T z 4 count\nrun 10\n", "t.10", "fix p"),
    ("shape db", "shape g cross3d 0.002 resolution 8 db T\n", "t.10", "shape g"),
]

NODES = {"null": (1, 3), "full": (1, 7)}


def make_target(folder, name, kind):
    """At folder/name: a character device like /dev/null or /dev/full, a FIFO, or a symbolic link to a
    null device. Returns the stat test the target must still pass afterwards."""
    path = os.path.join(folder, name)
    if kind == "fifo":
        os.mkfifo(path)
        return stat.S_ISFIFO
    node = "full" if kind == "full" else "null"
    device = os.path.join(folder, "null.node") if kind == "link" else path
    try:
        os.mknod(device, stat.S_IFCHR | 0o666, os.makedev(*NODES[node]))
    except OSError:         # not root: a link to the machine's device, which this user cannot replace
        device = f"/dev/{node}"
    if device != path:
        os.symlink(device, path)
    return stat.S_ISCHR


def run_dem(folder, script, log="none", env=None):
    with open(os.path.join(folder, "in.test"), "w") as fh:
        fh.write(script)
    try:
        return subprocess.run([sys.executable, "-m", "dem", "-in", "in.test", "-log", log], cwd=folder,
                              capture_output=True, text=True, timeout=60, env=env)
    except subprocess.TimeoutExpired:
        pytest.fail("dem blocked on its output (a FIFO opened for writing?)")


def line_of(script, start):
    return next(i for i, line in enumerate(script.splitlines(), 1) if line.startswith(start))


@pytest.mark.parametrize("kind", ["null", "full", "fifo", "link"])
@pytest.mark.parametrize("case", CASES, ids=[c[0] for c in CASES])
def test_output_to_a_device_or_fifo_is_refused_and_left_alone(tmp_path, case, kind):
    _, lines, name, refused = case
    if name.endswith(".png"):
        pytest.importorskip("matplotlib")
    if name.endswith((".h5", ".xdmf")):
        pytest.importorskip("h5py")
    still = make_target(str(tmp_path), name, kind)
    script = READY + lines.replace("T", name)
    out = run_dem(str(tmp_path), script)
    target = tmp_path / name
    assert still(os.stat(target).st_mode), f"{name} was replaced: {oct(os.stat(target).st_mode)}"
    assert kind != "link" or os.path.islink(target)
    assert out.returncode == 1, out.stdout + out.stderr
    assert "Traceback" not in out.stderr, out.stderr
    assert f"in.test:{line_of(script, refused)}: " in out.stderr, out.stderr
    assert f"'{name}' is a " in out.stderr and "dem writes its outputs to regular files only" in out.stderr, \
        out.stderr


@pytest.mark.parametrize("kind", ["null", "fifo", "link"])
def test_log_on_a_device_or_fifo_is_refused_and_left_alone(tmp_path, kind):
    still = make_target(str(tmp_path), "t.log", kind)
    out = run_dem(str(tmp_path), "units si\n", log="t.log")
    assert still(os.stat(tmp_path / "t.log").st_mode)
    assert out.returncode == 1 and "Traceback" not in out.stderr, out.stderr
    assert "the log file (-log): 't.log' is a " in out.stderr, out.stderr


def test_shape_database_of_the_environment_on_a_fifo_is_not_used(tmp_path):
    """$DEM_SHAPE_DB is no script line: a FIFO there gives a warning and no cache, never a blocked run."""
    os.mkfifo(tmp_path / "db.h5")
    env = dict(os.environ, DEM_SHAPE_DB=str(tmp_path / "db.h5"))
    lattice = "shape g multisphere 0 0 0 0.001 0.001 0 0 0.001 resolution 8\n"      # overlapping: the cache
    out = run_dem(str(tmp_path), READY + lattice, env=env)
    assert out.returncode == 0, out.stderr
    assert "is a FIFO" in out.stderr, out.stderr
    assert stat.S_ISFIFO(os.stat(tmp_path / "db.h5").st_mode)
    assert not os.path.exists(tmp_path / "db.h5.lock")


def test_a_link_to_a_regular_file_is_kept_and_its_file_written(tmp_path):
    (tmp_path / "real.data").write_text("old\n")
    os.symlink("real.data", tmp_path / "bed.data")
    out = run_dem(str(tmp_path), READY + "write_data bed.data\nwrite_restart bed.data\n")
    assert out.returncode == 0, out.stderr
    assert os.path.islink(tmp_path / "bed.data")
    assert (tmp_path / "real.data").read_bytes().startswith(b"dem checked file")   # the restart, through the link
