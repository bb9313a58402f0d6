"""Script errors: every mistake gives `file:line: message` on stderr and a non-zero exit status, and
leaves no half-written output behind."""
import os
import subprocess
import sys

import pytest

BOX = """units si
boundary p p f
region box block 0 0.01 0 0.01 0 0.01
create_box 1 box
"""
ATOMS = BOX + "create_atoms 1 random 20 5 box radius 0.0005 density 2500\n"
READY = ATOMS + """pair_style sphere
pair_coeff * * kn 1000 en 0.5
fix nve all nve/sphere
timestep 1e-6
"""


def run_script(tmp_path, text, name="in.test", extra=()):
    path = tmp_path / name
    path.write_text(text)
    return subprocess.run([sys.executable, "-m", "dem", "-in", name, "-log", "none", *extra],
                          cwd=tmp_path, capture_output=True, text=True)


def line_of(text, needle):
    return next(i for i, line in enumerate(text.splitlines(), 1) if needle in line)


CASES = [
    # (script, the line that is wrong, expected message fragment)
    (READY + "fix g all gravty 9.81\n", "gravty", "unknown fix style 'gravty' (did you mean 'gravity'?)"),
    (READY + "rn 100\n", "rn 100", "unknown command 'rn' (did you mean 'run'?)"),
    (BOX + "timestep abc\n", "timestep abc", "timestep: dt must be a number, got 'abc'"),
    ("units si\ncreate_atoms 1 single 0 0 0\n", "create_atoms", "create_atoms needs a box: use create_box, read_data or read_restart first"),
    (ATOMS + "pair_coeff * * kn 1 en 0.5\n", "pair_coeff", "pair_coeff before pair_style"),
    (ATOMS + "pair_style sphere\npair_coeff * * kn 1000 en 1.5\n", "en 1.5", "pair_coeff: en must be in [0, 1] (0: critical damping)"),
    (ATOMS + "pair_style sphere\npair_coeff * * kn 1000 en 0.5 mu_rol 1\n", "mu_rol",
     "unknown coefficient 'mu_rol' (did you mean 'mu_roll'?)"),
    (BOX + "print ${undefined}\n", "undefined", "undefined variable 'undefined'"),
    ("boundary p q p\n", "boundary", "bad boundary 'q'"),
    (BOX + "region r1 block 0 1 0 1\n", "region r1", "region r1: expected at least 6 argument(s), got 4"),
    (READY + "thermo_style custom step kee\n", "kee", "unknown thermo keyword 'kee' (did you mean 'ke'?)"),
    ("units si\nread_data nowhere.data\n", "read_data", "cannot open 'nowhere.data'"),
    (BOX + "include missing.in\n", "include", "cannot open include file 'missing.in'"),
    (READY + "fix w all wall/plane zplane 0 NULL kn 1000\n", "wall/plane", "fix w wall/plane: give both kn and en (or neither, to use pair_coeff I I)"),
    (READY + "dump d all h5 0 out.h5\n", "dump d", "dump d: N must be > 0"),
    (READY + "run -5\n", "run -5", "run: N must be >= 0, got -5"),
    (BOX + "create_atoms 1 random 100000 5 box radius 0.001\n", "create_atoms", "of 100000 particles without overlap in region box"),
    ("units lj\n", "units", "unit style 'lj' is not supported"),
    (READY + "set group all density -1\n", "set group", "set: density must be > 0"),
    (READY + "group g1 region nowhere\n", "group g1", "unknown region ID 'nowhere'"),
]


@pytest.mark.parametrize("script, needle, message", CASES, ids=[c[2][:40] for c in CASES])
def test_error_names_file_and_line(tmp_path, script, needle, message):
    out = run_script(tmp_path, script)
    assert out.returncode != 0
    lineno = line_of(script, needle)
    assert f"in.test:{lineno}:" in out.stderr, out.stderr
    assert message in out.stderr, out.stderr
    assert "Traceback" not in out.stderr


def test_error_in_included_file_names_that_file(tmp_path):
    (tmp_path / "inc.in").write_text("# settings\ntimestep 1e-6\nneighbor -1 bin\n")
    out = run_script(tmp_path, BOX + "include inc.in\n")
    assert out.returncode != 0
    assert "inc.in:3: neighbor" in out.stderr


def test_error_before_run_leaves_no_output_file(tmp_path):
    out = run_script(tmp_path, READY + "dump d all h5 10 out.h5\ndump v all vtk 10 out_*.vtu\n"
                                       "fix g all gravty 9.81\nrun 10\n")
    assert out.returncode != 0
    assert not [p for p in os.listdir(tmp_path) if p.startswith("out")]


def test_lost_particle_stops_with_ids(tmp_path):
    script = BOX.replace("p p f", "p p f") + """create_atoms 1 single 0.005 0.005 0.0095 v 0 0 5 radius 0.0004
fix nve all nve/sphere
timestep 1e-5
run 100
"""
    out = run_script(tmp_path, script)
    assert out.returncode != 0
    assert "left the box through a fixed boundary" in out.stderr and "ids 1" in out.stderr
    assert "in.test:8:" in out.stderr


def test_excessive_overlap_stops_with_hint_after_writing_the_frame(tmp_path):
    script = BOX + """create_atoms 1 single 0.005 0.005 0.003 v 0 0 20 radius 0.001 density 2500
create_atoms 1 single 0.005 0.005 0.006 v 0 0 -20 radius 0.001 density 2500
pair_style sphere
pair_coeff * * kn 10 en 0.5
fix nve all nve/sphere
dump d all h5 1000 out.h5
timestep 1e-5
run 2000
"""
    out = run_script(tmp_path, script)
    assert out.returncode != 0
    assert "exceeds the limit 0.2" in out.stderr and "between particles 1 and 2" in out.stderr
    assert "steps per contact" in out.stderr
    import h5py
    with h5py.File(tmp_path / "out.h5", "r") as h5:
        steps = sorted(int(k) for k in h5["frames"])
    assert steps[0] == 0 and len(steps) == 2       # step 0 and the failing step


def test_bad_command_line(tmp_path):
    out = subprocess.run([sys.executable, "-m", "dem", "-in"], capture_output=True, text=True, cwd=tmp_path)
    assert out.returncode != 0 and "ERROR: missing value after an option" in out.stderr
    assert "usage: dem -in FILE" in out.stderr
    out = subprocess.run([sys.executable, "-m", "dem", "-in", "nothere.in", "-log", "none"],
                         capture_output=True, text=True, cwd=tmp_path)
    assert out.returncode != 0 and "Traceback" not in out.stderr
    assert "ERROR: cannot open input file 'nothere.in'" in out.stderr


@pytest.mark.parametrize("radius, needle", [("", "the default radius 0.5 m (no 'radius' keyword given)"),
                                            ("radius 0.02", "too small for particles of radius 0.02 m")])
def test_create_atoms_random_region_too_small_names_the_radius(radius, needle):
    """The LAMMPS idiom `create_atoms ... random ...` then `set type 1 diameter D` meets the default
    radius first: the message says which radius did not fit and how to give it."""
    import dem
    sim = dem.Simulation(screen=False)
    with pytest.raises(dem.DemError) as err:
        sim.commands("region box block 0 0.05 0 0.05 0 0.05\ncreate_box 1 box\n"
                     "region fill block 0.005 0.045 0.005 0.045 0.005 0.045\n"
                     f"create_atoms 1 random 2000 12345 fill {radius}\nset type 1 diameter 0.002\n")
    text = str(err.value)
    assert "region fill is too small" in text and needle in text and err.value.where == "<string>:4"
    if not radius:
        assert "radius 0.001" in text and "set type 1 diameter" in text       # the hint: give it here
    assert sim.atom.natoms == 0
