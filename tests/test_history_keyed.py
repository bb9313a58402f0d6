"""Keyed contact history (several records per pair, each with a key) driven directly from Python: records
survive a neighbor rebuild with a spatial sort, a restart and a migration between two ranks, matched by
(partner tag, key); a key not appended in a step is forgotten, a new key starts at zero; a kernel stopped
by a full buffer resumes at the pair that did not fit, handling every pair once."""
import pickle
import subprocess
import sys

import numpy as np
import pytest

import dem
from dem import _history
from dem import history as history_module
from dem.errors import DemError
from dem.history import KeyedHistory

from conftest import MPIEXEC
from test_mpi import _env

WIDTH = 3
# a simple cubic lattice of spheres 0.1 apart: each one listed with its 6 nearest neighbors, no contact
SETUP = """
boundary {boundary}
region box block 0 6 0 3 0 3
create_box 1 box
create_atoms 1 lattice box sc 1.0 radius 0.45 density 1
neighbor 0.3 bin
thermo 0
"""
FORCES = """
pair_style sphere
pair_coeff * * kn 1e4 en 0.9
fix 1 all nve/sphere
timestep 1e-4
"""


def keys_of(ti, tj):
    """Several keys per pair, different for each pair: a single point (0), a component pair, a feature."""
    return [0, (ti % 3 + 1) << 32 | (tj % 2), 1000 + ti + tj]


def value_of(ti, tj, key):
    return (float(ti), float(tj), float(key % 9973) + 0.5)


def make(boundary="f f f", register=True):
    sim = dem.Simulation(screen=False)
    sim.commands(SETUP.format(boundary=boundary) + FORCES)
    h = None
    if register:
        h = KeyedHistory(sim, "keyed", WIDTH)
        sim.neighbor.histories.append(h)
    sim.run(0)
    return sim, h


def fill(sim, h):
    """Records of every pair by keys_of/value_of (a Python loop: tests only)."""
    i, j = sim.neighbor.pairs()
    tag = sim.atom.data["tag"]
    for k, (a, b) in enumerate(zip(i, j)):
        ti, tj = int(tag[a]), int(tag[b])
        keys = keys_of(ti, tj)
        h.set_records(k, keys, [value_of(ti, tj, key) for key in keys])


def expected(sim):
    tag = sim.atom.data["tag"]
    i, j = sim.neighbor.pairs()
    return {(int(tag[a]), int(tag[b]), key): value_of(int(tag[a]), int(tag[b]), key)
            for a, b in zip(i, j) for key in keys_of(int(tag[a]), int(tag[b]))}


def test_records_survive_a_rebuild_with_sort():
    sim, h = make("p p p")
    fill(sim, h)
    before = h.by_tags()
    assert before == expected(sim) and len(before) > 300
    order = sim.atom.local("tag").copy()
    sim.atom.local("x")[:, 0] += 2.0                   # a periodic shift: the same pairs, other owners
    sim.neighbor.last_sort = -10 ** 9                   # and a spatial sort that permutes the particles
    sim.neighbor.rebuild(sim.update.ntimestep)
    assert not np.array_equal(order, sim.atom.local("tag"))
    assert h.by_tags() == before


def step_with(sim, h, records):
    """One step of the reference kernel appending `records` {(entry, key): increment}."""
    items = sorted(records.items())
    entry = np.array([e for (e, _), _ in items], np.int64)
    key = np.array([k for (_, k), _ in items], np.int64)
    add = np.array([v for _, v in items], np.float64).reshape(-1, WIDTH)
    visits = np.zeros(sim.neighbor.nentries, np.int64)
    nb = sim.neighbor
    h.step(lambda start: _history.apply_records(h.buffers, nb.offsets, sim.atom.nlocal, entry, key, add,
                                                visits, start))
    return visits


def test_vanished_key_forgotten_new_key_from_zero():
    sim, h = make()
    fill(sim, h)
    sim.neighbor.rebuild(sim.update.ntimestep)         # the per-particle store now holds every key
    i, j = sim.neighbor.pairs()
    tag = sim.atom.data["tag"]
    k = 5
    ti, tj = int(tag[i[k]]), int(tag[j[k]])
    kept, gone = keys_of(ti, tj)[:2], keys_of(ti, tj)[2]
    new = 77
    inc = (0.25, -0.5, 1.0)
    step_with(sim, h, {(k, kept[0]): inc, (k, kept[1]): (0.0, 0.0, 0.0), (k, new): inc})
    keys, values = h.records(k)
    got = dict(zip(keys.tolist(), map(tuple, values)))
    assert set(got) == {kept[0], kept[1], new}
    assert got[kept[0]] == tuple(np.add(value_of(ti, tj, kept[0]), inc))      # from the old record
    assert got[kept[1]] == value_of(ti, tj, kept[1])
    assert got[new] == inc                                                     # from zero
    for other in range(sim.neighbor.nentries):        # pairs with nothing appended forget everything
        if other != k:
            assert len(h.records(other)[0]) == 0
    sim.neighbor.rebuild(sim.update.ntimestep)         # the vanished key does not come back from the store
    assert h.by_tags() == {(ti, tj, key): v for key, v in got.items()}


def test_full_buffer_resumes_at_the_pair_that_did_not_fit(monkeypatch):
    monkeypatch.setattr(history_module, "MIN_RECORDS", 1)
    sim, h = make()
    n = sim.neighbor.nentries
    records = {(e, key): (float(e), float(key), 1.0) for e in range(n) for key in (3, 1, 2)}
    visits = step_with(sim, h, records)
    assert h.nresumes > 1                              # the buffer filled up several times
    assert np.all(visits == 1)                         # each pair handled once, none twice
    visits = step_with(sim, h, records)
    assert np.all(visits == 1)
    for e in range(n):
        keys, values = h.records(e)
        assert keys.tolist() == [1, 2, 3]
        assert values.tolist() == [[2.0 * e, 2.0 * key, 2.0] for key in (1, 2, 3)]


def test_records_survive_a_restart(tmp_path):
    sim, h = make()
    fill(sim, h)
    before = h.by_tags()
    path = tmp_path / "keyed.restart"
    sim.command(f"write_restart {path}")
    new = dem.Simulation(screen=False)
    new.command(f"read_restart {path}")
    new.commands(FORCES)
    h2 = KeyedHistory(new, "keyed", WIDTH)
    new.neighbor.histories.append(h2)
    new.run(0)
    assert h2.by_tags() == before


def test_single_record_store_reads_as_key_0_records(tmp_path):
    """A restart holding a single-record history (one row per pair) read by a keyed history of that name:
    one key-0 record per row (how a style turned keyed reads its older restarts)."""
    sim = dem.Simulation(screen=False)
    sim.commands(SETUP.format(boundary="f f f") + FORCES.replace("en 0.9", "en 0.9 mu 0.5 ks 100"))
    sim.atom.local("v")[:] = np.random.default_rng(1).normal(scale=3.0, size=(sim.atom.nlocal, 3))
    sim.run(300)                                       # loaded tangential springs
    tag, (i, j) = sim.atom.data["tag"], sim.neighbor.pairs()
    rows = {(int(tag[a]), int(tag[b]), 0): tuple(v) for a, b, v in zip(i, j, sim.pair.history.values)
            if np.any(v)}
    assert len(rows) > 10
    path = tmp_path / "single.restart"
    sim.command(f"write_restart {path}")
    new = dem.Simulation(screen=False)
    new.command(f"read_restart {path}")
    new.commands(FORCES)
    h = KeyedHistory(new, "pair_xi", 3)
    new.neighbor.histories.append(h)
    new.run(0)
    assert h.by_tags() == rows


def test_restart_of_another_width_is_refused(tmp_path):
    sim, h = make()
    fill(sim, h)
    path = tmp_path / "keyed.restart"
    sim.command(f"write_restart {path}")
    new = dem.Simulation(screen=False)
    new.command(f"read_restart {path}")
    with pytest.raises(DemError, match=f"'keyed': the restart holds {WIDTH} values per record, this pair style 2"):
        KeyedHistory(new, "keyed", 2)


MIGRATE = f"""
import pickle
import numpy as np
import dem
from dem.history import KeyedHistory
from test_history_keyed import FORCES, SETUP, WIDTH, expected, fill

sim = dem.Simulation(screen=False)
sim.commands("processors 2 1 1\\n" + SETUP.format(boundary="p f f") + FORCES)
h = KeyedHistory(sim, "keyed", WIDTH)
sim.neighbor.histories.append(h)
sim.run(0)
fill(sim, h)
def everything():
    out = {{}}
    for part in sim.comm.allgather(h.by_tags()):
        out.update(part)
    return out
before = everything()
want = {{}}
for part in sim.comm.allgather(expected(sim)):
    want.update(part)
owned_before = set(sim.atom.local("tag").tolist())
sim.atom.local("x")[:, 0] += 3.0                  # half the periodic box: every particle changes rank
sim.neighbor.rebuild(sim.update.ntimestep)
owned_after = set(sim.atom.local("tag").tolist())
after = everything()
if sim.comm.me == 0:
    with open("out.pkl", "wb") as fh:
        pickle.dump((before, want, after, owned_before & owned_after, sim.comm.nprocs), fh)
"""


@pytest.mark.skipif(MPIEXEC is None, reason="mpiexec not found (pip install 'dem[mpi]')")
def test_records_migrate_between_two_ranks(tmp_path):
    (tmp_path / "drive.py").write_text(MIGRATE)
    env = _env()
    env["PYTHONPATH"] = str(__import__("pathlib").Path(__file__).parent) + ":" + env["PYTHONPATH"]
    res = subprocess.run([MPIEXEC, "-n", "2", sys.executable, "drive.py"], cwd=tmp_path, env=env,
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stdout[-3000:] + res.stderr[-3000:]
    before, want, after, stayed, nprocs = pickle.loads((tmp_path / "out.pkl").read_bytes())
    assert nprocs == 2 and not stayed                  # every particle moved to the other rank
    assert before == want and len(want) > 300
    assert after == before
