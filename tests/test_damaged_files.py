"""Damaged files dem reads back: restarts, shape databases and data files. Each small file is written once,
then damaged from fixed seeds (bytes flipped at random offsets, 256-byte blocks zeroed, truncations at
random lengths, plus an empty file and random garbage). Every copy is read in a subprocess
(damaged_reader.py) with a time limit per file, so that a crash or a hang inside the HDF5 library fails
the case it came from instead of the test run: a damaged restart must be refused with a DemError naming
the file, a damaged shape database with a warning naming it (the database is then rewritten), and a data
file either read or refused with a DemError; never a traceback, a crash or a hang."""
import json
import os
import re
import select
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pytest

import dem
from damaged_reader import RESOLUTION, components
from test_restart_file import SCRIPT     # the small restart's bed

HERE = Path(__file__).resolve().parent
READER = HERE / "damaged_reader.py"
# damaged copies per file kind, by seed (a third each: flips, zeroed blocks, truncations); the zeroed
# blocks of seeds 94, 157 and 340 (and 49) made HDF5 loop for ever in read_restart of a restart of version 3
SEEDS = (*range(60), 94, 157, 340)
PER_FILE_S = 30        # a file still being read after this long hangs
BLOCK = 256

SAID_DAMAGED = re.compile(r"damaged|truncated|not a dem|empty")


def _env():
    import dem_sphere
    paths = [str(Path(dem.__file__).resolve().parents[1]), str(Path(dem_sphere.__file__).resolve().parents[1]),
             str(HERE)]
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(paths + [p for p in [env.get("PYTHONPATH")] if p])
    env.setdefault("OMP_NUM_THREADS", "1")
    return env


def damaged(data, seed):
    """A damaged copy of the bytes `data`: by seed, 1-3 bytes flipped, a 256-byte block zeroed or the
    file cut short."""
    rng = np.random.default_rng(seed)
    out = bytearray(data)
    how = seed % 3
    if how == 0:
        for _ in range(int(rng.integers(1, 4))):
            out[int(rng.integers(len(out)))] ^= int(rng.integers(1, 256))
    elif how == 1:
        start = BLOCK * int(rng.integers(len(out) // BLOCK + 1))
        out[start:start + BLOCK] = bytes(len(out[start:start + BLOCK]))
    else:
        del out[int(rng.integers(len(out))):]
    return bytes(out)


def copies(original, folder, suffix):
    """{path: damaged bytes differ from the original} of every damaged copy, written in `folder`."""
    data = original.read_bytes()
    made = {f"seed{seed}": damaged(data, seed) for seed in SEEDS}
    made["empty"] = b""
    made["garbage"] = np.random.default_rng(99).integers(0, 256, 4096, dtype=np.uint8).tobytes()
    made["head"] = data[:600]        # the start of the file only
    out = {}
    for name, content in made.items():
        path = folder / f"{name}{suffix}"
        path.write_bytes(content)
        out[str(path)] = content != data
    return out


def read_all(kind, paths):
    """{path: (outcome, text)}: outcomes of damaged_reader.py, or "crash" (the process died while reading
    the file) or "hang" (killed after PER_FILE_S). After a crash or a hang the next files are read by a
    new process."""
    results, todo = {}, list(paths)
    while todo:
        with tempfile.TemporaryFile() as err:
            proc = subprocess.Popen([sys.executable, str(READER), kind, *todo], stdout=subprocess.PIPE,
                                    stderr=err, env=_env())
            current, deadline = todo[0], time.monotonic() + PER_FILE_S
            while True:
                ready, _, _ = select.select([proc.stdout], [], [], max(0.0, deadline - time.monotonic()))
                if not ready:
                    proc.kill()                 # SIGKILL: a hang inside HDF5 ignores SIGTERM
                    proc.wait()
                    results[current] = ("hang", f"still reading after {PER_FILE_S} s")
                    break
                line = proc.stdout.readline()
                if not line:
                    rc = proc.wait()
                    if current is not None:
                        err.seek(0)
                        tail = err.read().decode(errors="replace")[-2000:]
                        results[current] = ("crash", f"exit status {rc}: {tail}")
                    break
                event = json.loads(line)
                if event["event"] == "start":
                    current, deadline = event["path"], time.monotonic() + PER_FILE_S
                else:
                    results[event["path"]] = (event["event"], event["text"])
                    current = None
            proc.stdout.close()
        todo = [p for p in todo if p not in results]
    return results


def failures(kind, made, check):
    results = read_all(kind, list(made))
    bad = []
    for path, changed in made.items():
        outcome, text = results[path]
        problem = check(path, changed, outcome, text)
        if problem:
            bad.append(f"{Path(path).name}: {problem} ({outcome}: {text.strip()[-600:]})")
    return bad


def refused_naming_the_file(path, changed, outcome, text):
    if not changed:
        return None if outcome == "read" else "an undamaged copy is not read"
    if outcome != "refused":
        return "not refused"
    if path not in text or not SAID_DAMAGED.search(text):
        return "the message does not name the file and say it is damaged"
    return None


def test_damaged_restarts_are_refused(tmp_path):
    sim = dem.Simulation(screen=False)
    sim.commands(SCRIPT)
    original = tmp_path / "small.restart"
    sim.command(f"write_restart {original}")
    made = copies(original, tmp_path, ".restart")
    bad = failures("restart", made, refused_naming_the_file)
    assert not bad, f"{len(bad)} of {len(made)} damaged restarts:\n" + "\n".join(bad)


def test_damaged_shape_databases_are_set_aside(tmp_path):
    from dem.shapes import glued_mass, shape_db
    original = tmp_path / "shapes.h5"
    text = shape_db.definition_text(components())
    assert shape_db.ShapeDB(original).put(text, RESOLUTION, glued_mass.union_mass_properties(components(),
                                                                                            RESOLUTION))
    made = copies(original, tmp_path, ".h5")
    bad = failures("shapedb", made, refused_naming_the_file)
    assert not bad, f"{len(bad)} of {len(made)} damaged shape databases:\n" + "\n".join(bad)


def test_damaged_data_files_are_read_or_refused(tmp_path):
    sim = dem.Simulation(screen=False)
    sim.commands(SCRIPT)
    original = tmp_path / "small.data"
    sim.command(f"write_data {original}")
    made = copies(original, tmp_path, ".data")

    def check(path, changed, outcome, text):
        if outcome == "read":
            return None
        if outcome != "refused":
            return "neither read nor refused"
        if f"read_data {path}" not in text and f"read_data: '{path}'" not in text:
            return "the message does not name the file"
        return None
    bad = failures("data", made, check)
    assert not bad, f"{len(bad)} of {len(made)} damaged data files:\n" + "\n".join(bad)


@pytest.mark.parametrize("what", ["truncated", "zeroed"])
def test_the_command_line_reports_a_damaged_restart(tmp_path, what):
    """Through `dem -in`: exit status 1, one ERROR line naming the script line and the file."""
    sim = dem.Simulation(screen=False)
    sim.commands(SCRIPT)
    path = tmp_path / "small.restart"
    sim.command(f"write_restart {path}")
    data = path.read_bytes()
    path.write_bytes(data[:len(data) // 2] if what == "truncated" else data[:1024] + bytes(BLOCK) + data[1280:])
    (tmp_path / "in.read").write_text(f"read_restart {path}\n")
    res = subprocess.run([sys.executable, "-m", "dem", "-in", "in.read", "-log", "none"], cwd=tmp_path,
                         capture_output=True, text=True, env=_env(), timeout=60)
    assert res.returncode == 1, res.stderr
    assert "Traceback" not in res.stderr and "in.read:1: read_restart" in res.stderr, res.stderr
    assert str(path) in res.stderr and SAID_DAMAGED.search(res.stderr), res.stderr
