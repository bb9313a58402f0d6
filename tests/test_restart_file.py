"""The restart file (HDF5 with a whole-file checksum, version 4): values come back with their exact types, a
damaged file, a damaged dataset or a state that makes no physical sense is refused with a DemError naming
the file and what is wrong, and a pickle named as a restart is refused without being loaded.
(Many damaged copies, in subprocesses: test_damaged_files.py.)"""
import pickle

import h5py
import numpy as np
import pytest

import dem
from dem import restart_file, verified_file
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
    restart_file.write(path, state, 4)
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
    with pytest.raises(DemError, match=r"evil.restart.*version 1 or 2.*version 4 only.*not loaded"):
        dem.Simulation(screen=False).command(f"read_restart {path}")
    assert not marker.exists()


def test_not_a_restart(tmp_path):
    path = tmp_path / "text.restart"
    path.write_text("hello")
    with pytest.raises(DemError, match="text.restart' is not a dem restart file"):
        dem.Simulation(screen=False).command(f"read_restart {path}")


def edited(path):
    """h5py.File of the restart `path` to change, its whole-file checksum remade when closed (a file that
    is whole but wrong: for the checks that follow the checksum's)."""
    class Edit(h5py.File):
        def __exit__(self, *exc):
            super().__exit__(*exc)
            verified_file.seal(path, restart_file.KIND)
    return Edit(path, "a")


def test_the_file_opens_as_any_hdf5_file(restart):
    """The checksum header lives in the HDF5 user block: other programs read the file as it is."""
    with h5py.File(restart, "r") as f:
        assert f.userblock_size == verified_file.HEADER_SIZE and f.attrs["version"] == 4
        assert f["fields/x"].shape == (64, 3)
    assert restart.read_bytes().startswith(verified_file.MAGIC + b"kind restart\n")


@pytest.mark.parametrize("damage, what", [
    (lambda b: b[:-1], r"is truncated: \d+ bytes where its header says \d+"),
    (lambda b: b + b"\0", "is damaged: 1 bytes more than its header says"),
    (lambda b: b[:2000] + bytes([b[2000] ^ 1]) + b[2001:], "is damaged: checksum mismatch"),
    (lambda b: bytes(256) + b[256:], "is damaged: its checksum header is unreadable"),
    (lambda b: b"", r"is empty \(0 bytes\)"),
])
def test_a_damaged_file_is_refused_before_hdf5_opens_it(restart, damage, what, monkeypatch):
    restart.write_bytes(damage(restart.read_bytes()))
    monkeypatch.setattr(h5py, "File", None)          # HDF5 must not see it
    with pytest.raises(DemError, match=f"small.restart' {what}") as err:
        dem.Simulation(screen=False).command(f"read_restart {restart}")
    assert "continue from an earlier restart" in str(err.value) or "empty" in str(err.value)


class _Rank:
    def __init__(self, me, verdict=None):
        self.me, self.verdict = me, verdict

    def bcast(self, obj):
        return obj if self.me == 0 else self.verdict


def test_under_mpi_rank_zero_checks_the_file(restart, monkeypatch):
    """Rank 0 reads the whole file and broadcasts the verdict: the other ranks never read it for that."""
    verdict = restart_file.examine(restart)
    assert verdict == ("version", 4)
    monkeypatch.setattr(verified_file, "check", None)
    assert restart_file.file_version(restart, _Rank(1, verdict)) == 4
    with pytest.raises(DemError, match="rank 0 says so"):
        restart_file.file_version(restart, _Rank(1, ("error", "rank 0 says so", None)))


def _version_3(path, state):
    """A restart as dem wrote it before the whole-file checksum (version 3)."""
    from urllib.parse import quote
    with h5py.File(path, "w") as f:
        f.attrs["format"] = restart_file.MAGIC
        f.attrs["version"] = 3
        for key, value in state.items():
            restart_file._put(f, quote(key, safe=""), value)


def test_version_3_is_refused_and_converts(restart, tmp_path):
    import subprocess
    import sys
    from pathlib import Path
    tool = Path(__file__).resolve().parents[1] / "tools" / "convert_restart.py"
    old, new = tmp_path / "v3.restart", tmp_path / "v4.restart"
    state = restart_file.read(restart)
    _version_3(old, state)
    with pytest.raises(DemError, match=r"(?s)v3.restart' is an HDF5 file without dem's checksum header.*"
                                       r"version 3.*dem-convert-restart"):
        dem.Simulation(screen=False).command(f"read_restart {old}")
    subprocess.run([sys.executable, str(tool), str(old), str(new)], check=True, capture_output=True)
    back = restart_file.read(new)
    for name, values in state["fields"].items():
        assert np.array_equal(back["fields"][name], values), name
    again = subprocess.run([sys.executable, str(tool), str(new), str(tmp_path / "x")], capture_output=True,
                           text=True)
    assert again.returncode != 0 and "version 4: nothing to convert" in again.stderr


def test_other_version_is_refused(restart):
    with edited(restart) as f:
        f.attrs["version"] = 99
    with pytest.raises(DemError, match=r"small.restart.*version 99.*version 4 only"):
        dem.Simulation(screen=False).command(f"read_restart {restart}")


def test_damaged_dataset_is_refused(restart):
    with edited(restart) as f:
        f["fields/x"][0, 0] += 1e-9                    # the checksum no longer matches
    with pytest.raises(DemError, match=r"small.restart.*fields/x: checksum"):
        dem.Simulation(screen=False).command(f"read_restart {restart}")


def test_incomplete_state_is_refused(restart):
    with edited(restart) as f:
        del f["neighbor"]
    with pytest.raises(DemError, match=r"small.restart.*incomplete state \(no neighbor\)"):
        dem.Simulation(screen=False).command(f"read_restart {restart}")


def _edit(path, name, change):
    """Change a dataset and give it a matching checksum (a file that is whole but wrong)."""
    with edited(path) as f:
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
    """tools/convert_restart.py turns a trusted version-1 pickle into a version-4 file that reads back with
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
