"""MPI runs: the same scripts on 1 and 2 ranks (launched with `mpiexec -n 2` in a subprocess; the test
command itself stays plain `pytest`).

Bounds: the two runs sum forces in different orders (ghost forces come back through reverse
communication), so states agree to round-off, not bitwise: after 200 steps of a dense frictional bed
(tangential history, walls) positions agree within 1e-9 of a diameter and velocities within 1e-9 of the
largest velocity (measured: ~1e-15 and ~1e-12). Integer observables (particles, contacts) agree exactly at
every step. A run continued on the same number of ranks from its restart is bitwise identical.
"""
import os
import subprocess
import sys
import time
from pathlib import Path

import h5py
import numpy as np
import pytest

from conftest import MPIEXEC

pytestmark = pytest.mark.skipif(MPIEXEC is None, reason="mpiexec not found (pip install 'dem[mpi]')")

D = 1e-3          # particle diameter of the scripts (m)
TIMEOUT = 120


def _env():
    """Subprocesses run the tree under test: the folders holding `dem` and the built-in plugins first."""
    import dem
    import dem_sphere
    paths = [str(Path(dem.__file__).resolve().parents[1]), str(Path(dem_sphere.__file__).resolve().parents[1])]
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(paths + [p for p in [env.get("PYTHONPATH")] if p])
    env.setdefault("OMP_NUM_THREADS", "1")
    return env


def run_dem(tmp, script, nprocs, log, timeout=TIMEOUT, check=True):
    path = Path(tmp) / f"in.{log}"
    path.write_text(script)
    cmd = [sys.executable, "-m", "dem", "-in", path.name, "-log", log, "-screen", "none"]
    if nprocs > 1:
        cmd = [MPIEXEC, "-n", str(nprocs)] + cmd
    res = subprocess.run(cmd, cwd=tmp, env=_env(), capture_output=True, text=True, timeout=timeout)
    if check:
        assert res.returncode == 0, f"{' '.join(cmd)} failed:\n{res.stdout[-3000:]}\n{res.stderr[-3000:]}"
    return res


def thermo_rows(path):
    """Rows of the thermo table(s) of a log: lists of words."""
    rows, on = [], False
    for line in Path(path).read_text().splitlines():
        words = line.split()
        if words and words[0] == "step":
            on = True
            continue
        if words and words[0] == "Loop":
            on = False
        if on and words and words[0].isdigit():
            rows.append(words)
    return rows


def frame(path, step):
    with h5py.File(path, "r") as f:
        g = f[f"frames/{step:010d}"]
        return {k: np.asarray(g[k]) for k in g}


SETTINGS = """                 # pair, fixes and output of the bed and of its continuation from a restart
pair_style      sphere
pair_coeff      * * kn 2000 en 0.5 mu 0.5 gamma_t 0 ks 571.4
fix             integrate all nve/sphere
fix             gravity all gravity 9.81 vector 0.3 0.2 -1
fix             walls all wall/plane xplane 0 0.012 yplane 0 0.008 zplane 0 NULL
timestep        2e-6
neighbor        0.0001 bin
thermo          1
thermo_style    custom step atoms contacts f_walls[contacts] ke
thermo_modify   format float %.17g
dump            d all h5 200 {dump}
"""

BED = """
units           si
boundary        f f fm
{processors}
region          box block 0 0.012 0 0.008 0 0.02
create_box      1 box
region          fill block 0 0.012 0 0.008 0 0.012
create_atoms    1 lattice fill bcc 0.00116 radius uniform 0.00045 0.0005 density 2500
{balance}
""" + SETTINGS + "{run}\n"

SETTINGS_AFTER_RESTART = "read_restart    bed.restart\n" + SETTINGS + "run             100\n"


def bed(dump, run="run 200", processors="", balance=""):
    return BED.format(dump=dump, run=run, processors=processors, balance=balance)


@pytest.fixture(scope="module")
def serial_bed(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("bed1")
    run_dem(tmp, bed("bed.h5"), 1, "log.1")
    return thermo_rows(tmp / "log.1"), frame(tmp / "bed.h5", 200)


def assert_same_state(a, b):
    assert np.array_equal(a["id"], b["id"])
    assert np.abs(a["position"] - b["position"]).max() <= 1e-9 * D
    vmax = np.abs(a["velocity"]).max()
    assert np.abs(a["velocity"] - b["velocity"]).max() <= 1e-9 * vmax
    assert np.abs(a["omega"] - b["omega"]).max() <= 1e-9 * np.abs(a["omega"]).max()


@pytest.mark.parametrize("variant", ["grid", "balanced"])
def test_dense_bed_two_ranks_matches_serial(tmp_path, serial_bed, variant):
    """Particles and contacts (pair and wall) equal at every step, state equal to round-off after 200
    steps; 'balanced' also moves the sub-box boundary (balance + fix balance) during the run."""
    if variant == "grid":
        script = bed("bed.h5")      # default grid: cut across gravity, balanced at the first run
    else:
        script = bed("bed.h5", processors="processors 2 1 1",
                     balance="balance 1.0 shift x\nfix lb all balance 50 1.0 shift x weight time")
    run_dem(tmp_path, script, 2, "log.2")
    rows1, frame1 = serial_bed
    rows2 = thermo_rows(tmp_path / "log.2")
    assert len(rows1) == len(rows2) == 201
    assert [r[:4] for r in rows1] == [r[:4] for r in rows2]
    assert int(rows1[-1][2]) > 100        # a dense bed: many frictional contacts
    ke1, ke2 = (np.array([float(r[4]) for r in rows]) for rows in (rows1, rows2))
    assert np.allclose(ke1, ke2, rtol=1e-9, atol=0)
    assert_same_state(frame1, frame(tmp_path / "bed.h5", 200))
    log = (tmp_path / "log.2").read_text()
    assert "on 2 procs" in log
    if variant == "balanced":
        assert "Balance: imbalance" in log


def test_restart_written_on_two_ranks_continues_on_one(tmp_path, serial_bed):
    run_dem(tmp_path, bed("bedA.h5", run="run 100\nwrite_restart bed.restart\nrun 100"), 2, "log.A")
    run_dem(tmp_path, SETTINGS_AFTER_RESTART.format(dump="bedB1.h5"), 1, "log.B1")
    run_dem(tmp_path, SETTINGS_AFTER_RESTART.format(dump="bedB2.h5"), 2, "log.B2")
    rows1, frame1 = serial_bed
    a, b1, b2 = (frame(tmp_path / f, 200) for f in ("bedA.h5", "bedB1.h5", "bedB2.h5"))
    assert_same_state(frame1, a)
    assert_same_state(frame1, b1)          # 2 ranks -> 1 rank: round-off of the uninterrupted run
    for key in a:                          # 2 ranks -> 2 ranks: bitwise
        assert np.array_equal(a[key], b2[key]), key
    # the first line after read_restart is the setup pass (contacts of the state at step 100); the
    # uninterrupted run printed those of the force pass of step 99 there: compare from step 101 on
    rows_b1 = thermo_rows(tmp_path / "log.B1")
    assert [r[:4] for r in rows_b1[1:]] == [r[:4] for r in rows1[101:]]


FLOW = """
units           si
boundary        p p f
processors      * 1 1
region          box block 0 0.008 0 0.004 0 0.008
create_box      2 box
region          lower block 0 0.008 0 0.004 0 0.004
region          upper block 0 0.008 0 0.004 0.004 0.008
create_atoms    1 random 40 4821 lower radius uniform 0.0004 0.0005 density 2500 v 1.0 0.1 0
create_atoms    2 random 40 1234 upper radius 0.0005 density 2500 v -1.0 0 0.2
pair_style      sphere
pair_coeff      * * kn 2000 en 0.8 mu 0.3 gamma_t 0 ks 571.4
fix             integrate all nve/sphere
fix             gravity all gravity 9.81 vector 0.5 0 -1
fix             walls all wall/plane zplane 0 0.008
timestep        2e-6
neighbor        0.0001 bin
thermo          500
thermo_style    custom step atoms contacts ke
thermo_modify   format float %.17g
dump            d all h5 10000 flow.h5
run             10000
"""


def test_periodic_flow_loses_nothing(tmp_path):
    """10^4 steps of two counter-flowing layers, periodic along x (cut between the ranks) and y (one
    rank: periodic images of a rank's own particles): every particle crosses the ranks several times."""
    run_dem(tmp_path, FLOW, 2, "log.2")
    rows = thermo_rows(tmp_path / "log.2")
    assert len(rows) == 21 and all(r[1] == "80" for r in rows)
    f = frame(tmp_path / "flow.h5", 10000)
    assert np.array_equal(f["id"], np.arange(1, 81))
    log = (tmp_path / "log.2").read_text()
    migrations = int(log.split(" migrations")[0].split()[-1])
    assert migrations > 200
    # the same particles as a serial run, also after 10^4 steps (round-off, not yet amplified)
    serial = tmp_path / "serial"
    serial.mkdir()
    run_dem(serial, FLOW, 1, "log.1")
    g = frame(serial / "flow.h5", 10000)
    assert np.abs(f["position"] - g["position"]).max() < 1e-6 * D
    assert [r[:3] for r in rows] == [r[:3] for r in thermo_rows(serial / "log.1")]


def test_input_error_stops_every_rank(tmp_path):
    res = run_dem(tmp_path, "units si\nboundary p p p\nnot_a_command 1\n", 2, "log.e", timeout=60,
                  check=False)
    assert res.returncode != 0
    assert res.stderr.count("unknown command 'not_a_command'") >= 1


def test_error_on_one_rank_aborts_the_job(tmp_path):
    """An exception on one rank while the others wait in a collective: abort, never a hang."""
    script = ("from dem.sim import Sim\n"
              "sim = Sim(screen=False)\n"
              "if sim.comm.me == 1:\n"
              "    raise RuntimeError('boom on rank 1')\n"
              "sim.comm.barrier()\n")
    (tmp_path / "drive.py").write_text(script)
    res = subprocess.run([MPIEXEC, "-n", "2", sys.executable, "drive.py"], cwd=tmp_path, env=_env(),
                         capture_output=True, text=True, timeout=60)
    assert res.returncode != 0
    assert "boom on rank 1" in res.stderr


ONE_RANK_ERROR = """
units           si
boundary        f f f
region          box block 0 0.008 0 0.004 0 0.004
create_box      1 box
create_atoms    1 lattice box sc 0.001 radius 0.0004 density 2500
pair_style      sphere
pair_coeff      * * kn 2000 en 0.5
fix             integrate all nve/sphere
timestep        1e-6
thermo          0
run             10
write_restart   no_such_folder/bed.restart
run             100000
"""


def test_error_on_one_rank_only_aborts_the_job(tmp_path):
    """A DemError that only one rank sees, on a user path: write_restart into a folder that does not
    exist fails on rank 0 (rank 0 alone writes the file), while rank 1 goes on to the next `run` and waits
    in its first collective. comm.fatal on rank 0 reports the error and, the other rank not joining it
    within ERROR_WAIT (5 s), aborts the job: a non-zero exit status and the message, never a hang.
    Timeout 90 s: the job takes ~5 s plus start-up (2 x Python + mpi4py, a few s, more on a loaded
    machine); a job that does not abort runs until killed (100000 steps on rank 1 never start)."""
    try:
        res = run_dem(tmp_path, ONE_RANK_ERROR, 2, "log.e", timeout=90, check=False)
    except subprocess.TimeoutExpired:
        pytest.fail("an error on one rank hung the job (no abort within 90 s)")
    assert res.returncode != 0
    assert "in.log.e:13: write_restart: cannot write 'no_such_folder/bed.restart'" in res.stderr, res.stderr
    assert "the other ranks did not stop with this error: aborting the MPI job" in res.stderr, res.stderr


def test_a_log_that_cannot_be_written_ends_every_rank(tmp_path):
    """Rank 0 alone opens the log: its failure (here a file where the log's folder should be) used to leave
    rank 1 waiting in its first collective (create_box) for ever. Now every rank stops with the error."""
    (tmp_path / "blocker").write_text("")
    (tmp_path / "in.x").write_text(ONE_RANK_ERROR)
    start = time.monotonic()
    try:
        res = subprocess.run([MPIEXEC, "-n", "2", sys.executable, "-m", "dem", "-in", "in.x", "-log", "blocker/log"],
                             cwd=tmp_path, env=_env(), capture_output=True, text=True, timeout=30)
    except subprocess.TimeoutExpired:
        pytest.fail("a log that cannot be written hung the job")
    assert time.monotonic() - start < 10
    assert res.returncode == 1 and "Traceback" not in res.stderr, res.stderr
    assert "the log file (-log): cannot write 'blocker/log': 'blocker' is not a folder" in res.stderr, res.stderr


def test_serial_run_does_not_import_mpi4py(tmp_path):
    code = "import sys\nfrom dem.sim import Sim\nSim(screen=False)\nprint('mpi4py' in sys.modules)\n"
    env = {k: v for k, v in _env().items() if k not in ("PMI_SIZE", "OMPI_COMM_WORLD_SIZE", "PMIX_SIZE",
                                                          "MPI_LOCALNRANKS")}
    res = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env, capture_output=True, text=True,
                         timeout=60)
    assert res.returncode == 0, res.stderr
    assert res.stdout.strip() == "False"


def timing_table(log):
    """{section: (min, avg, max, %varavg, %total)} of the last timing table of a log."""
    lines = Path(log).read_text().splitlines()
    start = max(i for i, line in enumerate(lines) if line.startswith("Section   |"))
    table = {}
    for line in lines[start + 2:]:
        if "|" not in line:
            break
        cells = [c.strip() for c in line.split("|")]
        table[cells[0]] = tuple(float(c) for c in cells[1:])
    return table


def test_timing_table_min_avg_max_over_ranks(tmp_path):
    """LAMMPS's table: min <= avg <= max over the ranks, and %total (avg over the average loop time, with
    Other the rest of each rank's loop) sums to 100, not beyond."""
    run_dem(tmp_path, bed("bed.h5", run="run 100"), 2, "log.2")
    text = (tmp_path / "log.2").read_text()
    assert "Section timing over 2 rank(s)" in text
    table = timing_table(tmp_path / "log.2")
    assert list(table) == ["Pair", "Neigh", "Comm", "Modify", "Integrate", "Output", "Other"]
    for name, (lo, avg, hi, varavg, share) in table.items():
        assert 0 <= lo <= avg * (1 + 1e-4) and avg <= hi * (1 + 1e-4), name
        assert 0 <= varavg <= 100 and 0 <= share <= 100
    assert sum(row[4] for row in table.values()) == pytest.approx(100, abs=0.05)
    assert table["Pair"][2] > table["Pair"][0]      # two ranks, two amounts of work: not one number


def test_write_data_on_two_ranks_reads_back_as_on_one(tmp_path):
    """write_data gathers every rank's particles in id order: the file of a 2-rank run reads back (on one
    rank) as the file of the serial run, to the round-off of the force sums."""
    import dem
    files = {}
    for n in (1, 2):
        folder = tmp_path / f"r{n}"
        folder.mkdir()
        run_dem(folder, bed("bed.h5", run="run 50\nwrite_data bed.data"), n, f"log.{n}")
        sim = dem.Simulation(screen=False).command("boundary f f fm").command(f"read_data {folder / 'bed.data'}")
        files[n] = {k: sim.gather(k) for k in ("tag", "x", "v", "radius")}
    assert np.array_equal(files[1]["tag"], files[2]["tag"]) and len(files[1]["tag"]) > 1000
    assert np.array_equal(files[1]["radius"], files[2]["radius"])
    assert np.abs(files[1]["x"] - files[2]["x"]).max() <= 1e-9 * D


POUR = """
units           si
boundary        f f fm
{processors}
region          box block 0 0.01 0 0.008 0 0.04
create_box      1 box
region          fill block 0 0.01 0 0.008 0.02 0.036
create_atoms    1 random 300 4821 fill radius 0.0005 density 2500
pair_style      sphere
pair_coeff      * * kn 2000 en 0.5 mu 0.5 ks 571.4
fix             integrate all nve/sphere
fix             gravity all gravity 9.81 vector 0 0 -1
fix             walls all wall/plane xplane 0 0.01 yplane 0 0.008 zplane 0 NULL
timestep        2e-6
neighbor        0.0001 bin
run             10
"""


def _pour_ranks(tmp_path, processors):
    """(log text, per rank (nlocal, grid)) after POUR on 2 ranks."""
    (tmp_path / "in.pour").write_text(POUR.format(processors=processors))
    (tmp_path / "drive.py").write_text(
        "import dem\n"
        "sim = dem.Simulation(log='log.pour', screen=False)\n"
        "sim.file('in.pour')\n"
        "with open(f'rank{sim.comm.me}', 'w') as f:\n"
        "    print(sim.comm.me, sim.atom.nlocal, *sim.comm.procgrid, file=f)\n")
    res = subprocess.run([MPIEXEC, "-n", "2", sys.executable, "drive.py"], cwd=tmp_path, env=_env(),
                         capture_output=True, text=True, timeout=TIMEOUT)
    assert res.returncode == 0, res.stderr[-3000:]
    ranks = [tuple(int(w) for w in (tmp_path / f"rank{r}").read_text().split()) for r in range(2)]
    return (tmp_path / "log.pour").read_text(), ranks


def test_default_grid_leaves_the_gravity_axis_whole_and_starts_balanced(tmp_path):
    """Particles placed in a tall fill region would be cut along z (least surface) and all fall onto the
    lower rank; at the first run dem cuts across gravity instead (along x, the longer side) and balances
    the cut by count: 150 particles per rank. A grid the user gave is kept."""
    log, ranks = _pour_ranks(tmp_path, "")
    assert "Processor grid: 1 x 1 x 2 (2 MPI ranks)" in log
    assert "Processor grid: 2 x 1 x 1 (2 MPI ranks), instead, as gravity points along z" in log
    assert ranks == [(0, 150, 2, 1, 1), (1, 150, 2, 1, 1)]
    log, ranks = _pour_ranks(tmp_path, "processors * * 2")
    assert "instead" not in log and [r[2:] for r in ranks] == [(1, 1, 2)] * 2


ROUGH_DRUM = """
units           si
boundary        f p f
region          box block -0.011 0.011 0 0.005 -0.011 0.011
create_box      2 box
variable        i loop 24
label           ring
create_atoms    2 single $(0.009*cos(2*PI*v_i/24)) 0.002 $(0.009*sin(2*PI*v_i/24)) radius 0.001 density 2500
next            i
jump            SELF ring
group           wall type 2
region          low block -0.005 0.005 EDGE EDGE -0.0075 -0.003
create_atoms    1 random 12 4821 low radius 0.0008 density 2500
group           bed type 1
pair_style      sphere
pair_coeff      * * kn 2000 en 0.5 mu 0.5 ks 571.4
fix             integrate bed nve/sphere
fix             gravity bed gravity 9.81 vector 0 0 -1
fix             drum bed wall/drum y 0 0 0.01 rpm 300 carry wall kn 2000 en 0.5 mu 0.5 ks 571.4
timestep        2e-6
thermo          1000
thermo_style    custom step atoms contacts ke
thermo_modify   format float %.17g
dump            d all h5 10000 rough.h5
run             10000
"""


def test_rough_drum_wall_carried_across_ranks(tmp_path):
    """wall/drum carry on 2 ranks: the wall's 24 spheres turn half a turn (3.14 rad), crossing the cut
    between the ranks, and land where the drum angle puts them (1e-12 m: a formula of the angle); the 12
    spheres of the bed fall onto them and are stirred: particles and contacts equal at every thermo step,
    positions within 1e-6 D of the serial run after 10^4 steps (round-off, not yet amplified, as in
    test_periodic_flow_loses_nothing)."""
    run_dem(tmp_path, ROUGH_DRUM, 2, "log.2")
    serial = tmp_path / "serial"
    serial.mkdir()
    run_dem(serial, ROUGH_DRUM, 1, "log.1")
    a, b = frame(tmp_path / "rough.h5", 10000), frame(serial / "rough.h5", 10000)
    assert np.array_equal(a["id"], b["id"])
    assert np.abs(a["position"] - b["position"]).max() < 1e-6 * D
    wall = a["id"] <= 24
    angle = 300 * 2 * np.pi / 60 * 10000 * 2e-6
    t = 2 * np.pi * a["id"][wall] / 24
    # turning about +y by the angle takes (x, z) = r (cos t, sin t) to r (cos(t - angle), sin(t - angle))
    assert np.abs(a["position"][wall, 0] - 0.009 * np.cos(t - angle)).max() < 1e-12
    assert np.abs(a["position"][wall, 2] - 0.009 * np.sin(t - angle)).max() < 1e-12
    assert "Processor grid: 2 x 1 x 1" in (tmp_path / "log.2").read_text()
    rows = thermo_rows(tmp_path / "log.2")
    assert [r[:3] for r in rows] == [r[:3] for r in thermo_rows(serial / "log.1")]
    assert int(rows[-1][2]) > 0                               # the bed touches the turning wall


def test_mesh_walls_two_ranks_match_serial(tmp_path, serial_bed):
    """The dense bed of test_dense_bed_two_ranks_matches_serial in a box of triangles (fix wall/mesh, 160
    triangles, the mesh on every rank) instead of planes: particles, pair and wall contacts equal at every
    step on 1 and 2 ranks, the state equal to round-off after 200 steps; and the same as the planes' serial
    run (the spheres meet the same faces: test_wall_mesh)."""
    from test_wall_mesh import open_box
    open_box(tmp_path / "box.stl", (0, 0, 0), (0.012, 0.008, 0.03))
    script = bed("bed.h5").replace("fix             walls all wall/plane xplane 0 0.012 yplane 0 0.008 zplane 0 NULL",
                                   "fix             walls all wall/mesh file box.stl")
    assert "wall/mesh" in script
    run_dem(tmp_path, script, 2, "log.2")
    serial = tmp_path / "serial"
    serial.mkdir()
    (serial / "box.stl").write_bytes((tmp_path / "box.stl").read_bytes())
    run_dem(serial, script, 1, "log.1")
    rows1, rows2 = thermo_rows(serial / "log.1"), thermo_rows(tmp_path / "log.2")
    assert len(rows1) == len(rows2) == 201
    assert [r[:4] for r in rows1] == [r[:4] for r in rows2]
    assert int(rows1[-1][3]) > 10                             # spheres on the mesh
    assert_same_state(frame(serial / "bed.h5", 200), frame(tmp_path / "bed.h5", 200))
    assert_same_state(serial_bed[1], frame(tmp_path / "bed.h5", 200))
    assert "on 2 procs" in (tmp_path / "log.2").read_text()
