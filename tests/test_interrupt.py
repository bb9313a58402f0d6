"""SIGINT and SIGTERM stop a run cleanly (dem/interrupt.py): at the end of a step on every rank, exit status
130 / 143, a message naming the step and the files, no temporary file left, every HDF5 frame whole and
every restart readable. Each case starts `dem` (serial, and on 2 ranks under mpiexec) in a subprocess
writing an HDF5 dump and alternating restarts every few steps, waits until both exist, then signals it."""
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

import dem

h5py = pytest.importorskip("h5py")
from conftest import MPIEXEC  # noqa: E402
from test_mpi import _env   # noqa: E402  (the same launch as the MPI tests)

FIELDS = {"id", "type", "position", "velocity", "omega", "orientation", "radius", "mass", "shape"}

SCRIPT = """units si
boundary p p f
region box block 0 0.008 0 0.008 0 0.016
create_box 1 box
create_atoms 1 random 300 7 box radius 0.0004 density 2500
pair_style sphere
pair_coeff * * kn 1000 en 0.5 mu 0.5
fix integ all nve/sphere
fix g all gravity 9.81 vector 0 0 -1
fix floor all wall/plane zplane 0 0.016
timestep 2e-6
thermo 50
dump snap all h5 {dump_every} out.h5
restart {restart_every} r.a r.b
run 100000000
"""

PARSING = """units si
print started
label again
variable i loop 1000000000
next i
jump SELF again
"""


def start(tmp, text, nprocs):
    (tmp / "in.sig").write_text(text)
    cmd = [sys.executable, "-m", "dem", "-in", "in.sig", "-log", "log.dem", "-screen", "none"]
    if nprocs > 1:
        cmd = [MPIEXEC, "-n", str(nprocs)] + cmd
    return subprocess.Popen(cmd, cwd=tmp, env=_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)


def wait_for(proc, ready, timeout=90):
    deadline = time.monotonic() + timeout
    while not ready():
        if proc.poll() is not None:
            pytest.fail(f"the run ended before it was signalled:\n{proc.communicate()[1][-3000:]}")
        if time.monotonic() > deadline:
            proc.kill()
            pytest.fail("the run did not start writing in time")
        time.sleep(0.05)


def stop(proc, signum, timeout=60):
    proc.send_signal(signum)
    try:
        out, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, err = proc.communicate()
        pytest.fail(f"still running {timeout} s after the signal (hang):\n{err[-3000:]}")
    return proc.returncode, out, err


def check_files(tmp):
    left = [p.name for p in tmp.iterdir() if ".tmp" in p.name]
    assert not left, f"temporary files left: {left}"
    with h5py.File(tmp / "out.h5", "r") as f:
        assert "frame_being_written" not in f
        frames = f["frames"]
        assert len(frames) >= 1
        for name, g in frames.items():
            assert set(g) == FIELDS, f"frame {name} holds {sorted(g)}"
            n = int(g.attrs["natoms"])
            assert all(len(g[k]) == n for k in g) and n == 300
    restarts = [p for p in (tmp / "r.a", tmp / "r.b") if p.exists()]
    assert restarts
    for path in restarts:
        sim = dem.Simulation(screen=False)
        sim.command(f"read_restart {path}")
        assert sim.atom.natoms == 300
        sim.close()


@pytest.mark.parametrize("nprocs", [1, 2])
@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_signal_stops_a_run_with_whole_files(tmp_path, signum, nprocs):
    if nprocs > 1 and MPIEXEC is None:
        pytest.skip("mpiexec not found")
    proc = start(tmp_path, SCRIPT.format(dump_every=5, restart_every=7), nprocs)
    wait_for(proc, lambda: (tmp_path / "out.h5").exists() and (tmp_path / "r.b").exists())
    time.sleep(0.3)
    rc, out, err = stop(proc, signum)
    assert rc == 128 + signum, f"exit status {rc}:\n{err[-3000:]}"
    name = signal.Signals(signum).name
    assert f"INTERRUPTED: {name}: the run stopped at the end of step" in err, err[-3000:]
    assert "dump snap (h5):" in err and "restart: 'r." in err, err
    assert "Traceback" not in err and "Abort" not in err, err[-3000:]
    check_files(tmp_path)
    assert "stopped at the end of step" in (tmp_path / "log.dem").read_text()


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_signal_while_parsing_exits_cleanly(tmp_path, signum):
    proc = start(tmp_path, PARSING, 1)
    wait_for(proc, lambda: "started" in (tmp_path / "log.dem").read_text()
             if (tmp_path / "log.dem").exists() else False)
    rc, out, err = stop(proc, signum)
    assert rc == 128 + signum, err
    assert f"INTERRUPTED: interrupted by {signal.Signals(signum).name}" in err
    assert "Traceback" not in err


def test_library_run_stops_at_a_step_end_and_restores_handlers():
    """sim.run from Python: a SIGINT during the run ends it after the step, as Interrupted (a
    KeyboardInterrupt); the caller's handlers are back afterwards."""
    from dem.interrupt import Interrupted
    sim = dem.Simulation(screen=False)
    sim.commands("""units si
        region box block 0 0.01 0 0.01 0 0.01
        create_box 1 box
        create_atoms 1 single 0.005 0.005 0.005 radius 0.001 density 2500
        fix integ all nve/sphere
        timestep 1e-5
        thermo 0""")
    before = signal.getsignal(signal.SIGINT)
    plain_step = sim.update.step

    def step():                  # signals this process at the end of step 7
        plain_step()
        if sim.update.ntimestep == 7:
            os.kill(os.getpid(), signal.SIGINT)
    sim.update.step = step
    with pytest.raises(Interrupted) as info:
        sim.run(100)
    assert info.value.exit_code == 130
    assert sim.update.ntimestep == 8          # signalled after step 7: seen at step 8's check, stops after it
    assert "the run stopped at the end of step 8 (8 of 100 steps)" in str(info.value)
    assert signal.getsignal(signal.SIGINT) is before
    sim.close()


STUCK = """
import ctypes
import dem
from dem.interrupt import SIGNAL_STATE
SIGNAL_STATE.install()                    # as the dem command does
sim = dem.Simulation(screen=False, log="log.dem")
sim.callback("stuck", lambda sim: (print("stuck", flush=True), ctypes.CDLL(None).sleep(600)))
sim.commands('''units si
region box block 0 0.01 0 0.01 0 0.01
create_box 1 box
create_atoms 1 single 0.005 0.005 0.005 radius 0.001 density 2500
fix integ all nve/sphere
timestep 1e-5
thermo 1
fix s all python/every 3 stuck
run 100''')
"""


@pytest.mark.skipif(sys.version_info < (3, 10), reason="the signal thread needs interrupt_main(signum): 3.10")
@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_a_second_signal_stops_a_stuck_step_at_once(tmp_path, signum):
    """A step that does not end (here a C call of 600 s inside it, the GIL released as dem's kernels
    release it): the first signal waits for the end of the step and says so; the second ends the
    process within a second, exit status 128 + signal, the log's lines so far on disk."""
    (tmp_path / "stuck.py").write_text(STUCK)
    proc = subprocess.Popen([sys.executable, "stuck.py"], cwd=tmp_path, env=_env(), stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "stuck"
    proc.send_signal(signum)
    time.sleep(1.0)
    assert proc.poll() is None                       # the first signal waits for the step
    sent = time.monotonic()
    rc, out, err = stop(proc, signum, timeout=30)
    assert time.monotonic() - sent < 1.0, "the second signal did not stop the process at once"
    name = signal.Signals(signum).name
    assert rc == 128 + signum, err
    assert f"{name}: stopping at the end of this step ({name} again: at once)" in err
    assert f"INTERRUPTED: a second {name}: stopped at once" in err and "Traceback" not in err
    assert "\n         2 " in (tmp_path / "log.dem").read_text()    # the thermo line before the stuck step
