"""dump custom: LAMMPS-style text snapshots. The format is checked against LAMMPS's documented layout
with a parser of our own (always), and read back by OVITO's own reader when the `ovito` package is
installed (pip install ovito)."""
import gzip
import zlib

import numpy as np
import pytest

import dem
from dem.dump_custom import DumpCustom
from dem.errors import DemError
from test_dump import FakeSim, expected

ALL = ("id type x y z vx vy vz omegax omegay omegaz radius mass quatw quati quatj quatk shape").split()


def parse(text):
    """Snapshots of a LAMMPS dump custom text (the documented layout: ITEM: TIMESTEP, NUMBER OF ATOMS,
    BOX BOUNDS with 3 lines 'lo hi', ATOMS with the column names; ITEM: TIME optional before TIMESTEP)."""
    lines = text.splitlines()
    snaps, i = [], 0
    while i < len(lines):
        snap = {}
        if lines[i] == "ITEM: TIME":
            snap["time"] = float(lines[i + 1])
            i += 2
        assert lines[i] == "ITEM: TIMESTEP", lines[i]
        snap["step"] = int(lines[i + 1])
        assert lines[i + 2] == "ITEM: NUMBER OF ATOMS"
        n = int(lines[i + 3])
        head = lines[i + 4].split()
        assert head[:3] == ["ITEM:", "BOX", "BOUNDS"] and len(head) == 6, head
        snap["boundary"] = head[3:]
        snap["box"] = np.array([[float(v) for v in lines[i + 5 + d].split()] for d in range(3)])
        cols = lines[i + 8].split()
        assert cols[:2] == ["ITEM:", "ATOMS"]
        snap["columns"] = cols[2:]
        rows = [line.split() for line in lines[i + 9:i + 9 + n]]
        assert all(len(r) == len(cols) - 2 for r in rows)
        snap["data"] = {c: np.array([float(r[k]) for r in rows]) for k, c in enumerate(cols[2:])}
        snap["raw"] = {c: [r[k] for r in rows] for k, c in enumerate(cols[2:])}
        snaps.append(snap)
        i += 9 + n
    return snaps


def check_values(snap, exp, exact=True):
    d = snap["data"]
    compare = np.testing.assert_array_equal if exact else \
        (lambda a, b: np.testing.assert_allclose(a, b, rtol=1e-9, atol=0))
    compare(d["id"], exp["id"])
    compare(d["type"], exp["type"])
    compare(np.stack([d["x"], d["y"], d["z"]], 1), exp["position"])
    compare(np.stack([d["vx"], d["vy"], d["vz"]], 1), exp["velocity"])
    compare(np.stack([d["omegax"], d["omegay"], d["omegaz"]], 1), exp["omega"])
    compare(np.stack([d["quatw"], d["quati"], d["quatj"], d["quatk"]], 1), exp["orientation"])
    compare(d["radius"], exp["radius"])
    compare(d["mass"], exp["mass"])
    compare(d["shape"], exp["shape"])


def test_format_single_file_matches_lammps_layout(tmp_path):
    sim = FakeSim()
    d = DumpCustom(sim, "t", "all", 10, str(tmp_path / "all.dump"), ALL)
    d.modify(["format", "float", "%.17g"])
    snaps = []
    for k in range(3):
        if k:
            sim.advance(10)
        d.write(sim.update.ntimestep)
        snaps.append((sim.update.ntimestep, expected(sim)))
    text = (tmp_path / "all.dump").read_text()
    read = parse(text)
    assert [s["step"] for s in read] == [0, 10, 20]
    for s, (step, exp) in zip(read, snaps):
        assert s["columns"] == ALL and s["boundary"] == ["pp", "pp", "pp"]
        np.testing.assert_array_equal(s["box"], np.stack([sim.domain.lo, sim.domain.hi], 1))
        check_values(s, exp)
        assert all("." not in v and "e" not in v for v in s["raw"]["id"] + s["raw"]["type"])   # integers
    # default float format: 10 significant digits
    d2 = DumpCustom(sim, "u", "all", 10, str(tmp_path / "short.dump"), ALL)
    d2.write(30)
    check_values(parse((tmp_path / "short.dump").read_text())[0], expected(sim), exact=False)


def test_star_gzip_pad_time_and_group(tmp_path):
    sim = FakeSim()
    d = DumpCustom(sim, "t", "big", 10, str(tmp_path / "snap.*.dump.gz"), ALL)
    d.modify(["pad", "6", "time", "yes", "format", "float", "%.17g"])
    d.write(0)
    sim.advance(10)
    d.write(10)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["snap.000000.dump.gz", "snap.000010.dump.gz"]
    s = parse(gzip.decompress((tmp_path / "snap.000010.dump.gz").read_bytes()).decode())
    assert len(s) == 1 and s[0]["step"] == 10 and s[0]["time"] == sim.update.time
    check_values(s[0], expected(sim, "big"))
    # one gzip file: one member (OVITO reads the first only), complete after every snapshot
    g = DumpCustom(sim, "g", "all", 10, str(tmp_path / "one.dump.gz"), ["id", "x", "y", "z"])
    g.write(10)
    assert [s["step"] for s in parse(first_member(tmp_path / "one.dump.gz"))] == [10]
    g.write(20)
    g.close()
    g.write(30)          # reopened by a later run: appended
    assert [s["step"] for s in parse(first_member(tmp_path / "one.dump.gz"))] == [10, 20, 30]
    assert [s["step"] for s in parse(gzip.open(tmp_path / "one.dump.gz", "rt").read())] == [10, 20, 30]


def first_member(path):
    """The text of the file's first gzip member, checking it is the whole file (as a reader that stops
    at the end of the first member sees it)."""
    d = zlib.decompressobj(31)
    text = d.decompress(path.read_bytes())
    assert d.eof and d.unused_data == b""
    return text.decode()


def test_sort_append_and_derived_columns(tmp_path):
    sim = FakeSim()
    sim.local["image"] = np.arange(21, dtype=np.int32).reshape(7, 3) - 10
    sim.local["f"] = np.ones((7, 3))
    path = tmp_path / "d.txt"
    path.write_text("old contents\n")
    d = DumpCustom(sim, "t", "all", 10, str(path),
                   ["id", "xs", "yu", "ix", "iy", "iz", "diameter", "fx", "shapex", "shapez"])
    d.modify(["sort", "-id", "format", "float", "%.17g"])
    d.write(0)
    s = parse(path.read_text())[0]                # replaced, not appended
    exp = expected(sim)
    order = np.argsort(-exp["id"])
    img = sim.gather("image")[order]
    box = sim.domain.hi - sim.domain.lo
    np.testing.assert_array_equal(s["data"]["id"], exp["id"][order])
    np.testing.assert_allclose(s["data"]["xs"], (exp["position"][order, 0] - sim.domain.lo[0]) / box[0])
    np.testing.assert_allclose(s["data"]["yu"], exp["position"][order, 1] + img[:, 1] * box[1])
    np.testing.assert_array_equal(np.stack([s["data"]["ix"], s["data"]["iy"], s["data"]["iz"]], 1), img)
    np.testing.assert_array_equal(s["data"]["diameter"], 2 * exp["radius"][order])
    np.testing.assert_array_equal(s["data"]["shapex"], 2 * exp["radius"][order])    # spheres: diameter
    np.testing.assert_array_equal(s["data"]["fx"], 1.0)
    d.modify(["sort", "2"])                       # by column 2 (xs) ascending
    d.write(10)
    s = parse(path.read_text())[1]
    assert np.all(np.diff(s["data"]["xs"]) >= 0)
    d2 = DumpCustom(sim, "a", "all", 10, str(path), ["id"])
    d2.modify(["append", "yes"])
    d2.write(20)
    assert [s["step"] for s in parse(path.read_text())] == [0, 10, 20]


def test_bad_columns_and_modify(tmp_path):
    sim = FakeSim()
    with pytest.raises(DemError, match="unknown dump custom column 'wx' .did you mean 'omegax'"):
        DumpCustom(sim, "t", "all", 10, str(tmp_path / "a.dump"), ["id", "wx"])
    with pytest.raises(DemError, match="unknown dump custom column 'radus' .did you mean 'radius'"):
        DumpCustom(sim, "t", "all", 10, str(tmp_path / "a.dump"), ["radus"])
    with pytest.raises(DemError, match="needs the columns"):
        DumpCustom(sim, "t", "all", 10, str(tmp_path / "a.dump"), [])
    d = DumpCustom(sim, "t", "all", 10, str(tmp_path / "a.dump"), ["id", "x"])
    for args, msg in [(["sort", "3"], "sort must be off, id, -id or a column number 1..2"),
                      (["sortt", "id"], "unknown keyword 'sortt'.*did you mean 'sort'"),
                      (["format", "float", "%q"], "bad format '%q'"),
                      (["format", "line", "%d"], "format line needs 2 formats"),
                      (["pad", "x"], "pad must be an integer"), (["every", "0"], "every must be > 0")]:
        with pytest.raises(DemError, match=msg):
            d.modify(args)
    assert list(tmp_path.iterdir()) == []


SCRIPT = """units si
boundary p p f
region box block 0 0.02 0 0.02 0 0.02
create_box 2 box
create_atoms 1 random 12 5 box radius 0.001 density 2500
pair_style sphere
pair_coeff * * kn 1000 en 0.5
fix nve all nve/sphere
fix g all gravity 9.81 vector 0 0 -1
timestep 1e-5
"""


def test_script_errors_name_the_line(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False)
    with pytest.raises(DemError) as err:
        sim.commands(SCRIPT + "dump t all custom 10 a.dump id x y z omgeax\n")
    assert err.value.where == f"<string>:{SCRIPT.count(chr(10)) + 1}"
    assert "unknown dump custom column 'omgeax' (did you mean 'omegax'?)" in str(err.value)
    with pytest.raises(DemError) as err:
        sim.commands("dump_modify nope sort id\n")
    assert "unknown dump ID 'nope'" in str(err.value)
    sim.commands("dump h all h5 10 a.h5\ndump_modify h sort id every 5\n")
    assert sim.output.dumps["h"].every == 5
    with pytest.raises(DemError, match="sort must be id or off"):
        sim.commands("dump_modify h sort -id\n")


def run_script(tmp_path, monkeypatch, extra, steps=40):
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False)
    sim.commands(SCRIPT + extra + f"run {steps}\n")
    return sim


def test_simulation_dump_round_trip(tmp_path, monkeypatch):
    sim = run_script(tmp_path, monkeypatch, "dump t all custom 20 snap.*.txt " + " ".join(ALL) + "\n"
                     "dump_modify t format float %.17g\n")
    s = parse((tmp_path / "snap.40.txt").read_text())[0]
    assert s["boundary"] == ["pp", "pp", "ff"] and s["step"] == 40
    exp = {f: sim.gather(a) for f, a in [("id", "tag"), ("type", "type"), ("position", "x"), ("velocity", "v"),
                                         ("omega", "omega"), ("orientation", "quat"), ("radius", "radius"),
                                         ("mass", "rmass"), ("shape", "shape")]}
    check_values(s, exp)


CUBES = """units si
boundary p p f
region box block 0 0.02 0 0.02 0 0.02
create_box 1 box
shape c cube 0.002
pair_style convex/gjk
pair_coeff * * kn 1000 en 0.5
fix nve all nve/shape
fix g all gravity 9.81 vector 0 0 -1
fix ins all insert 3 box count 8 shape c density 2500
timestep 1e-5
"""


def test_read_by_ovito(tmp_path, monkeypatch):
    """OVITO's own LAMMPS dump reader: positions, radii, orientations, velocities and the cubes' shapes."""
    ovito_io = pytest.importorskip("ovito.io")
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False)
    sim.commands(CUBES + "dump t all custom 20 cubes.*.dump.gz " + " ".join(ALL) + " shapex shapey shapez\n"
                 "dump_modify t time yes\n" "dump one all custom 20 one.dump id type x y z radius\n"
                 "dump gz all custom 20 one.dump.gz id type x y z radius\n" "run 40\n")
    pipeline = ovito_io.import_file(str(tmp_path / "cubes.*.dump.gz"))
    assert pipeline.num_frames == 3
    data = pipeline.compute(2)
    assert data.attributes["Timestep"] == 40
    assert data.attributes["Time"] == pytest.approx(sim.update.time)
    p = data.particles
    assert p.count == 8
    tag = sim.gather("tag")
    np.testing.assert_array_equal(np.asarray(p["Particle Identifier"]), tag)
    np.testing.assert_allclose(np.asarray(p["Position"]), sim.gather("x"), rtol=1e-7)
    np.testing.assert_allclose(np.asarray(p["Radius"]), sim.gather("radius"), rtol=1e-7)
    np.testing.assert_allclose(np.asarray(p["Velocity"]), sim.gather("v"), rtol=1e-7, atol=1e-12)
    np.testing.assert_allclose(np.asarray(p["Angular Velocity"]), sim.gather("omega"), rtol=1e-7, atol=1e-12)
    q = sim.gather("quat")                       # w x y z; OVITO stores x y z w
    np.testing.assert_allclose(np.asarray(p["Orientation"]), q[:, [1, 2, 3, 0]], rtol=1e-7, atol=1e-12)
    # OVITO halves LAMMPS's shapex (diameters) into half-axes: a cube of edge 2 mm
    np.testing.assert_allclose(np.asarray(p["Aspherical Shape"]), 0.001, rtol=1e-7)
    np.testing.assert_array_equal(np.asarray(p["shape"]), 0)
    np.testing.assert_allclose(data.cell[:, :3].diagonal(), sim.domain.hi - sim.domain.lo)
    for name in ("one.dump", "one.dump.gz"):        # every frame of one file, compressed or not
        single = ovito_io.import_file(str(tmp_path / name))
        assert single.num_frames == 3
        assert [single.compute(k).attributes["Timestep"] for k in range(3)] == [0, 20, 40]
