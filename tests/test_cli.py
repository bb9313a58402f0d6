"""The `dem` command line as LAMMPS users know it: the script from standard input, --version, and -h
listing every installed style by kind with its plugin."""
import subprocess
import sys

import dem

SCRIPT = """region box block 0 1 0 1 0 1
create_box 1 box
create_atoms 1 single 0.5 0.5 0.5 radius 0.1 density 1000
fix move all nve/sphere
timestep 0.001
run 10
print "STEP $(step)"
"""


def dem_run(args, cwd, stdin=None):
    """`python -m dem ARGS` run outside the source tree (there `dem` would be the unbuilt sources)."""
    return subprocess.run([sys.executable, "-m", "dem", *args], input=stdin, capture_output=True, text=True,
                          cwd=cwd, timeout=120)


def test_script_from_standard_input(tmp_path):
    out = dem_run(["-log", "none"], stdin=SCRIPT, cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert "STEP 10" in out.stdout and "input standard input" in out.stdout
    lines = out.stdout.splitlines()
    header = next(k for k, line in enumerate(lines) if line.split()[:1] == ["step"])
    assert lines[header - 1].startswith("(pct and eta: of this run, steps 0 to ")     # not of the whole job


def test_an_error_in_standard_input_names_its_line(tmp_path):
    out = dem_run(["-log", "none"], stdin=SCRIPT.replace("timestep 0.001", "timestep abc"), cwd=tmp_path)
    assert out.returncode == 1 and "<stdin>:5:" in out.stderr and "Traceback" not in out.stderr


def test_quit_sets_the_exit_status(tmp_path):
    """`quit N` ends the script with exit status N, as the inputs' checks of their -var words need."""
    out = dem_run(["-log", "none"], stdin='print "checked"\nquit 2\nprint never\n', cwd=tmp_path)
    assert out.returncode == 2 and "checked" in out.stdout and "never" not in out.stdout
    assert dem_run(["-log", "none"], stdin="quit\n", cwd=tmp_path).returncode == 0


def test_version(tmp_path):
    out = dem_run(["--version"], cwd=tmp_path)
    assert out.returncode == 0 and out.stdout.strip() == f"dem {dem.__version__}"


def test_help_lists_every_installed_style_by_kind(tmp_path):
    out = dem_run(["-h"], cwd=tmp_path)
    assert out.returncode == 0 and out.stdout.startswith("usage: dem")
    registry = dem.registry.default_registry()
    for kind, styles in registry.styles.items():
        line = next(ln for ln in out.stdout.splitlines() if ln.strip().startswith(f"{kind} ("))
        assert line.strip().startswith(f"{kind} ({len(styles)}):")
        for name in styles:
            assert f"{name} ({registry.provider(kind, name)})" in line
    assert "wall/drum (walls)" in out.stdout and "convex/gjk (convex)" in out.stdout


def test_help_on_one_style(tmp_path):
    """`dem -h NAME` prints the documentation of that command or style (as `lmp -h` does), the same text
    as docs/commands.md; an unknown name is an error with the closest names, a LIGGGHTS name with dem's
    equivalent."""
    import inspect
    from dem_walls.fix_wall_mesh import FixWallMesh
    out = dem_run(["-h", "wall/mesh"], cwd=tmp_path)
    assert out.returncode == 0 and out.stdout.startswith("fix wall/mesh (provided by walls):")
    assert inspect.cleandoc(FixWallMesh.__doc__) in out.stdout
    assert dem_run(["-h", "run"], cwd=tmp_path).stdout.startswith("command run (provided by core):")
    for name, message in (("wal/mesh", "no command or style 'wal/mesh' (did you mean 'wall/mesh'?)"),
                          ("mesh/surface", "dem has no 'mesh/surface' (LIGGGHTS fix): LIGGGHTS's fix mesh/surface"),
                          ("nothing-like-it", "no command or style 'nothing-like-it'")):
        out = dem_run(["-h", name], cwd=tmp_path)
        assert out.returncode != 0 and message in out.stderr and "Traceback" not in out.stderr


def test_lammps_thermo_names(tmp_path):
    """spcpu, tpcpu and cpuremain (LAMMPS) are dem's tps, tps * dt and eta: evaluated one after the other
    in one thermo line, they agree to the clock's advance between them (5 %)."""
    log = tmp_path / "log.test"
    sim = dem.Simulation(screen=False, log=str(log))
    sim.commands(SCRIPT.replace("run 10", "thermo_style custom step tps spcpu tpcpu cpuremain eta\n"
                                          "thermo 500\nrun 2000"))
    sim.close()
    lines = log.read_text().splitlines()
    start = next(i for i, ln in enumerate(lines) if ln.split()[:2] == ["step", "tps"])
    row = next(ln.split() for ln in lines[start + 1:] if ln.split()[:1] == ["1000"])
    tps, spcpu, tpcpu = float(row[1]), float(row[2]), float(row[3])
    assert tps > 0 and abs(spcpu / tps - 1) < 0.05 and abs(tpcpu / (spcpu * 0.001) - 1) < 0.05
    assert float(row[4]) > 0
