"""The restart file (HDF5, version 3): values come back with their exact types, a damaged dataset or a state
that makes no physical sense is refused with a DemError naming the file and what is wrong, and a pickle
named as a restart is refused without being loaded."""
import pickle

import h5py
import numpy as np
import pytest

import dem
from dem import restart_file
from dem.errors import DemError

SCRIPT = """
boundary f f f
region box block 0 4 0 4 0 4
create_box 1 box
create_atoms 1 lattice box sc 1.0 radius 0.45 density 1
pair_style sphere
pair_coeff * * kn 1e4 en 0.9
fix 1 all nve/sphere
timestep 1e-4
thermo 0
run 0
"""


@pytest.fixture
def restart(tmp_path):
    sim = dem.Simulation(screen=False)
    sim.commands(SCRIPT)
    path = tmp_path / "small.restart"
    sim.command(f"write_restart {path}")
    return path


def test_values_keep_their_types(tmp_path):
    state = {"none": None, "flag": True, "big": 2 ** 100 + 7, "x": 0.1, "name": "walls/1", "np": np.float64(0.3),
             "i32": np.int32(-4), "arr": np.arange(6, dtype=np.int32).reshape(2, 3), "empty": np.zeros((0, 3)),
             "words": np.array(["a", "bc"]), "tup": ((3,), "<f8", 0.0, False), "list": [["cube", "0.002"]],
             "nested": {"a/b": {"c": [1, 2.5]}}}
    path = tmp_path / "t.h5"
    restart_file.write(path, state, 3)
    back = restart_file.read(path)
    assert back.keys() == state.keys()
    for key in state:
        a, b = state[key], back[key]
        assert type(a) is type(b), key
        if isinstance(a, np.ndarray):
            assert a.dtype == b.dtype and np.array_equal(a, b), key
        else:
            assert a == b, key


def test_restart_reads_back(restart):
    sim = dem.Simulation(screen=False)
    sim.command(f"read_restart {restart}")
    assert sim.atom.natoms == 64


def test_crafted_pickle_is_refused_unloaded(tmp_path):
    marker = tmp_path / "ran"

    class Payload:
        def __reduce__(self):
            return (open, (str(marker), "w"))

    path = tmp_path / "evil.restart"
    path.write_bytes(pickle.dumps({"format": "dem-restart-2", "version": 2, "x": Payload()}))
    with pytest.raises(DemError, match=r"evil.restart.*version 1 or 2.*version 3 only.*not loaded"):
        dem.Simulation(screen=False).command(f"read_restart {path}")
    assert not marker.exists()


def test_not_a_restart(tmp_path):
    path = tmp_path / "text.restart"
    path.write_text("hello")
    with pytest.raises(DemError, match="text.restart' is not a dem restart file"):
        dem.Simulation(screen=False).command(f"read_restart {path}")


def test_other_version_is_refused(restart):
    with h5py.File(restart, "a") as f:
        f.attrs["version"] = 99
    with pytest.raises(DemError, match=r"small.restart.*version 99.*version 3 only"):
        dem.Simulation(screen=False).command(f"read_restart {restart}")


def test_damaged_dataset_is_refused(restart):
    with h5py.File(restart, "a") as f:
        f["fields/x"][0, 0] += 1e-9                    # the checksum no longer matches
    with pytest.raises(DemError, match=r"small.restart.*fields/x: checksum"):
        dem.Simulation(screen=False).command(f"read_restart {restart}")


def test_incomplete_state_is_refused(restart):
    with h5py.File(restart, "a") as f:
        del f["neighbor"]
    with pytest.raises(DemError, match=r"small.restart.*incomplete state \(no neighbor\)"):
        dem.Simulation(screen=False).command(f"read_restart {restart}")


def _edit(path, name, change):
    """Change a dataset and give it a matching checksum (a file that is whole but wrong)."""
    with h5py.File(path, "a") as f:
        data = np.asarray(f[name][()])
        change(data)
        f[name][...] = data
        f[name].attrs["crc32"] = restart_file._crc(data)


@pytest.mark.parametrize("name, change, what", [
    ("fields/x", lambda a: a.__setitem__((3, 1), np.nan), "'x' has non-finite"),
    ("fields/quat", lambda a: a.__setitem__((2, 0), 0.9), "unit quaternions"),
    ("fields/rmass", lambda a: a.__setitem__(5, -1.0), "masses and radii must be positive"),
    ("fields/tag", lambda a: a.__setitem__(7, a[8]), "ids are not unique"),
    ("lo", lambda a: a.__setitem__(0, 10.0), "invalid box"),
])
def test_invalid_state_is_refused(restart, name, change, what):
    _edit(restart, name, change)
    with pytest.raises(DemError, match=f"small.restart.*{what}"):
        dem.Simulation(screen=False).command(f"read_restart {restart}")


def test_old_pickle_restart_converts_with_the_tool(restart, tmp_path):
    """tools/convert_restart.py turns a trusted version-1 pickle into a version-3 file that reads back with
    the same state (every field bit for bit), and refuses without --trust."""
    import subprocess
    import sys
    from pathlib import Path
    tool = Path(__file__).resolve().parents[1] / "tools" / "convert_restart.py"
    state = restart_file.read(restart)
    old, new = tmp_path / "old.restart", tmp_path / "new.restart"
    with open(old, "wb") as fh:
        pickle.dump({**state, "format": "dem-restart-1"}, fh)
    refused = subprocess.run([sys.executable, str(tool), str(old), str(new)], capture_output=True, text=True)
    assert refused.returncode != 0 and "--trust" in refused.stderr and not new.exists()
    subprocess.run([sys.executable, str(tool), str(old), str(new), "--trust"], check=True, capture_output=True)
    back = restart_file.read(new)
    assert back["step"] == state["step"] and back["time"] == state["time"]
    for name, values in state["fields"].items():
        assert np.array_equal(back["fields"][name], values), name
    sim = dem.Simulation(screen=False)
    sim.command(f"read_restart {new}")
    assert sim.atom.natoms == 64
