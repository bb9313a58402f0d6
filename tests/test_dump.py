"""Dumps (h5 + XDMF, vtk + pvd) against a tiny fake sim: only what the dumps use."""
import base64
import importlib
import subprocess
import sys
import types
import xml.etree.ElementTree as ET
from pathlib import Path

import h5py
import numpy as np
import pytest


def _load(name):
    try:
        return importlib.import_module(name)
    except ImportError:
        # the compiled core may not be built yet: load the pure-Python dump modules without dem/__init__
        if "dem" not in sys.modules:
            pkg = types.ModuleType("dem")
            pkg.__path__ = [str(Path(__file__).resolve().parents[1] / "dem")]
            sys.modules["dem"] = pkg
        return importlib.import_module(name)


dump = _load("dem.dump")
dump_h5 = _load("dem.dump_h5")
dump_vtk = _load("dem.dump_vtk")
DemError = _load("dem.errors").DemError
DumpH5, DumpVTK = dump_h5.DumpH5, dump_vtk.DumpVTK

ATOM = {"id": "tag", "type": "type", "position": "x", "velocity": "v", "omega": "omega",
        "orientation": "quat", "radius": "radius", "mass": "rmass", "shape": "shape"}


class FakeGroups:
    names = ["all", "big"]

    def bit(self, name):
        if name not in self.names:
            raise DemError(f"unknown group '{name}'")
        return np.int32(1 << self.names.index(name))


class OneShape:
    """A shape table of one row, for a dump whose posed_mesh is given: only its size and bounding radius
    are read."""
    radius = np.ones(1)

    def __len__(self):
        return 1


class FakeSim:
    """Particles stored in shuffled local order; gather() returns them ordered by tag."""

    def __init__(self, n=7, me=0, seed=1):
        rng = np.random.default_rng(seed)
        self.comm = types.SimpleNamespace(me=me, nprocs=1)
        self.update = types.SimpleNamespace(ntimestep=0, time=0.0)
        self.domain = types.SimpleNamespace(lo=np.array([-1.0, -2.0, 0.0]), hi=np.array([1.0, 2.0, 3.5]))
        self.groups = FakeGroups()
        self.units = "si"
        self.shapes = ()                       # no shape defined: every particle is a sphere
        self.modify = types.SimpleNamespace(fixes=[])   # no fix: no mesh wall to write
        tags = rng.permutation(np.arange(10, 10 + n)).astype(np.int64)
        radius = rng.uniform(0.1, 0.5, n)
        q = rng.normal(size=(n, 4))
        self.local = {
            "tag": tags,
            "type": rng.integers(1, 4, n).astype(np.int32),
            "x": rng.normal(size=(n, 3)),
            "v": rng.normal(size=(n, 3)),
            "omega": rng.normal(size=(n, 3)),
            "quat": q / np.linalg.norm(q, axis=1)[:, None],
            "radius": radius,
            "rmass": 2500.0 * 4.0 / 3.0 * np.pi * radius ** 3,
            "shape": np.full(n, -1, dtype=np.int32),
            "mask": np.where(radius > 0.3, 3, 1).astype(np.int32),   # bit 1: group big
        }

    def gather(self, name):
        order = np.argsort(self.local["tag"], kind="stable")
        return self.local[name][order].copy()

    def advance(self, steps, dt=1e-3):
        self.update.ntimestep += steps
        self.update.time += steps * dt
        self.local["x"] += steps * dt * self.local["v"]
        self.local["v"] *= 0.9


def expected(sim, group="all"):
    keep = (sim.gather("mask") & sim.groups.bit(group)) != 0
    return {f: sim.gather(a)[keep] for f, a in ATOM.items()}


def run(sim, d, nframes, every=10):
    snaps = []
    for k in range(nframes):
        if k:
            sim.advance(every)
        d.write(sim.update.ntimestep)
        snaps.append((sim.update.ntimestep, sim.update.time, expected(sim, d.group)))
    return snaps


# ----- h5 ----------------------------------------------------------------------------------------------
def test_h5_frames_round_trip(tmp_path):
    sim = FakeSim()
    path = tmp_path / "out" / "snap.h5"          # folder created on demand
    d = DumpH5(sim, "d1", "all", 10, str(path), [])
    snaps = run(sim, d, 3)
    assert d.last_step == 20
    d.close()
    d.close()                                     # idempotent
    with h5py.File(path, "r") as f:
        assert f.attrs["format"] == "dem-dump-h5"
        assert f.attrs["dump_id"] == "d1"
        frames = f["frames"]
        assert list(frames) == [dump_h5.frame_name(s) for s, _, _ in snaps]
        for step, time, exp in snaps:
            g = frames[dump_h5.frame_name(step)]
            assert g.attrs["step"] == step and g.attrs["time"] == time
            assert g.attrs["natoms"] == len(exp["id"])
            np.testing.assert_array_equal(g.attrs["box_lo"], sim.domain.lo)
            np.testing.assert_array_equal(g.attrs["box_hi"], sim.domain.hi)
            assert set(g) == set(ATOM)
            for field, values in exp.items():
                assert g[field].dtype == values.dtype, field
                np.testing.assert_array_equal(g[field][()], values)   # exact
            assert np.all(np.diff(g["id"][()]) > 0)


def test_h5_xdmf_references_datasets(tmp_path):
    sim = FakeSim()
    path = tmp_path / "snap.h5"
    d = DumpH5(sim, "d1", "big", 5, str(path), [])
    snaps = run(sim, d, 3, every=5)
    xdmf = tmp_path / "snap.xdmf"
    assert xdmf.exists()
    root = ET.parse(xdmf).getroot()
    assert root.tag == "Xdmf"
    coll = root.find("Domain/Grid")
    assert coll.get("GridType") == "Collection" and coll.get("CollectionType") == "Temporal"
    grids = coll.findall("Grid")
    assert len(grids) == len(snaps)
    with h5py.File(path, "r") as f:          # readable between frames, in this process too
        for grid, (step, time, exp) in zip(grids, snaps):
            n = len(exp["id"])
            assert float(grid.find("Time").get("Value")) == time
            topo = grid.find("Topology")
            assert topo.get("TopologyType") == "Polyvertex" and int(topo.get("NumberOfElements")) == n
            assert grid.find("Geometry").get("GeometryType") == "XYZ"
            items = grid.findall(".//DataItem[@Format='HDF']")
            assert {item.text.split(":", 1)[1].rsplit("/", 1)[1] for item in items} == set(ATOM)
            for item in items:
                fname, dset = item.text.strip().split(":", 1)
                assert fname == "snap.h5"
                data = f[dset]
                assert tuple(int(v) for v in item.get("Dimensions").split()) == data.shape
                assert int(item.get("Precision")) == data.dtype.itemsize
                assert item.get("NumberType") == ("Float" if data.dtype.kind == "f" else "Int")
                assert data.shape[0] == n
            attrs = {a.get("Name"): a for a in grid.findall("Attribute")}
            quaternion = [f"orientation_{c}" for c in "wxyz"]
            assert set(attrs) == set(ATOM) - {"position", "orientation"} | set(quaternion)
            assert attrs["radius"].get("AttributeType") == "Scalar"
            assert attrs["velocity"].get("AttributeType") == "Vector"
            for k, name in enumerate(quaternion):       # one column of the (n, 4) dataset each
                slab = attrs[name].find("DataItem")
                assert slab.get("ItemType") == "HyperSlab" and slab.get("Dimensions") == f"{n} 1"
                assert slab.find("DataItem").text.split() == ["0", str(k), "1", "1", str(n), "1"]
            assert attrs["radius"].get("Center") == "Node"
    d.close()
    assert not list(tmp_path.glob(".*tmp"))      # no temp file left behind


def test_h5_readable_by_another_process_while_open(tmp_path):
    sim = FakeSim()
    path = tmp_path / "live.h5"
    d = DumpH5(sim, "d1", "all", 10, str(path), [])
    run(sim, d, 2)
    code = ("import h5py, sys; f = h5py.File(sys.argv[1], 'r'); "
            "print(len(f['frames']), f['frames'][sorted(f['frames'])[-1]]['position'].shape[0])")
    out = subprocess.run([sys.executable, "-c", code, str(path)], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["2", str(len(sim.local["tag"]))]
    d.close()


def test_h5_reader_in_this_process_between_frames(tmp_path):
    sim = FakeSim()
    path = tmp_path / "r.h5"
    d = DumpH5(sim, "d1", "all", 10, str(path), [])
    d.write(0)
    with h5py.File(path, "r") as f:
        assert list(f["frames"]) == [dump_h5.frame_name(0)]
    sim.advance(10)
    d.write(10)
    f = h5py.File(path, "r")                   # still open at the next frame: a clear error
    sim.advance(10)
    with pytest.raises(DemError, match="cannot open .* to write step"):
        d.write(20)
    f.close()
    d.write(20)
    with h5py.File(path, "r") as f:
        assert len(f["frames"]) == 3


def test_h5_lazy_no_file_without_frame(tmp_path):
    sim = FakeSim()
    path = tmp_path / "never.h5"
    d = DumpH5(sim, "d1", "all", 10, str(path), [])
    assert not path.exists()
    d.flush()
    d.close()
    assert list(tmp_path.iterdir()) == []


def test_h5_fields_keyword_and_reopen_after_close(tmp_path):
    sim = FakeSim()
    path = tmp_path / "f.h5"
    d = DumpH5(sim, "d1", "all", 10, str(path), ["fields", "id", "v", "radius"])
    assert d.fields == ["id", "position", "velocity", "radius"]
    d.write(0)
    d.close()
    sim.advance(10)
    d.write(10)                                   # reopens and appends
    d.write(10)                                   # same step again: replaces the frame
    d.close()
    with h5py.File(path, "r") as f:
        assert list(f["frames"]) == [dump_h5.frame_name(0), dump_h5.frame_name(10)]
        for g in f["frames"].values():
            assert set(g) == {"id", "position", "velocity", "radius"}
    grids = ET.parse(tmp_path / "f.xdmf").getroot().findall("Domain/Grid/Grid")
    assert [g.get("Name") for g in grids] == ["step_0", "step_10"]
    assert {a.get("Name") for a in grids[0].findall("Attribute")} == {"id", "velocity", "radius"}


def test_h5_bad_names(tmp_path):
    sim = FakeSim()
    with pytest.raises(DemError, match=r"writes all frames into one file: no '\*' in its name"):
        DumpH5(sim, "d1", "all", 10, str(tmp_path / "a_*.h5"), [])
    with pytest.raises(DemError, match="unknown group 'nogroup'"):
        DumpH5(sim, "d1", "nogroup", 10, str(tmp_path / "a.h5"), [])


def test_non_root_rank_writes_nothing(tmp_path):
    sim = FakeSim(me=1)
    d = DumpH5(sim, "d1", "all", 10, str(tmp_path / "a.h5"), [])
    v = DumpVTK(sim, "d2", "all", 10, str(tmp_path / "a_*.vtu"), [])
    d.write(0)
    v.write(0)
    assert d.last_step == 0 and v.last_step == 0
    d.close()
    v.close()
    assert list(tmp_path.iterdir()) == []


# ----- keywords ----------------------------------------------------------------------------------------
@pytest.mark.parametrize("cls,name", [(DumpH5, "a.h5"), (DumpVTK, "a_*.vtu")])
def test_unknown_keyword_and_field(tmp_path, cls, name):
    sim = FakeSim()
    with pytest.raises(DemError, match="unknown .*keyword 'feilds'.*did you mean 'fields'"):
        cls(sim, "d1", "all", 10, str(tmp_path / name), ["feilds", "id"])
    with pytest.raises(DemError, match="unknown field 'radus'.*did you mean 'radius'"):
        cls(sim, "d1", "all", 10, str(tmp_path / name), ["fields", "radus"])
    with pytest.raises(DemError, match="'fields' needs at least one name among id, type, position"):
        cls(sim, "d1", "all", 10, str(tmp_path / name), ["fields"])
    assert list(tmp_path.iterdir()) == []


def test_vtk_keywords(tmp_path):
    sim = FakeSim()
    with pytest.raises(DemError, match="format must be binary or ascii, got 'hex'"):
        DumpVTK(sim, "d1", "all", 10, str(tmp_path / "a_*.vtu"), ["format", "hex"])
    with pytest.raises(DemError, match=r"keyword 'format' needs 1 value\(s\)"):
        DumpVTK(sim, "d1", "all", 10, str(tmp_path / "a_*.vtu"), ["format"])
    with pytest.raises(DemError, match=r"the file name must end in \.vtu \('.*a_\*\.vtk'\)"):
        DumpVTK(sim, "d1", "all", 10, str(tmp_path / "a_*.vtk"), [])
    d = DumpVTK(sim, "d1", "all", 10, str(tmp_path / "a_*.vtu"),
                ["fields", "radius", "format", "ascii", "pvd", str(tmp_path / "c.pvd")])
    assert d.fields == ["position", "radius"] and not d.binary and d.pvd_path == str(tmp_path / "c.pvd")


# ----- vtk ---------------------------------------------------------------------------------------------
def read_vtu(path):
    """{name: array} of every DataArray of a .vtu (ascii or appended base64 with UInt64 headers)."""
    root = ET.parse(path).getroot()
    assert root.get("type") == "UnstructuredGrid" and root.get("header_type") == "UInt64"
    app = root.find("AppendedData")
    blob = app.text.strip()[1:] if app is not None else ""
    dtypes = {"Float64": "<f8", "Int64": "<i8", "Int32": "<i4", "UInt8": "u1"}
    out = {}
    for da in root.iter("DataArray"):
        dt = np.dtype(dtypes[da.get("type")])
        if da.get("format") == "appended":
            assert app.get("encoding") == "base64"
            start = int(da.get("offset"))
            head = base64.b64decode(blob[start:start + 12])
            nbytes = int(np.frombuffer(head[:8], "<u8")[0])
            nchars = 4 * ((8 + nbytes + 2) // 3)
            raw = base64.b64decode(blob[start:start + nchars])
            assert len(raw) == 8 + nbytes
            values = np.frombuffer(raw[8:], dt)
        else:
            assert da.get("format") == "ascii"
            values = np.array((da.text or "").split(), dtype=float).astype(dt)
        ncomp = int(da.get("NumberOfComponents", 1))
        out[da.get("Name")] = values.reshape(-1, ncomp) if ncomp > 1 else values
    piece = root.find("UnstructuredGrid/Piece")
    return root, piece, out


@pytest.mark.parametrize("fmt", ["binary", "ascii"])
def test_vtu_frames_and_pvd(tmp_path, fmt):
    sim = FakeSim()
    d = DumpVTK(sim, "mov", "big", 10, str(tmp_path / "post" / "grains_*.vtu"), ["format", fmt])
    snaps = run(sim, d, 3)
    d.close()
    for step, time, exp in snaps:
        path = tmp_path / "post" / f"grains_{step}.vtu"
        root, piece, arrays = read_vtu(path)
        n = len(exp["id"])
        assert int(piece.get("NumberOfPoints")) == n and int(piece.get("NumberOfCells")) == n
        assert piece.find("PointData").get("Scalars") == "radius"
        np.testing.assert_array_equal(arrays["Points"], exp["position"])
        for field in ("id", "type", "velocity", "omega", "orientation", "radius", "mass", "shape"):
            np.testing.assert_array_equal(arrays[field], exp[field])   # exact, ascii too
        np.testing.assert_array_equal(arrays["connectivity"], np.arange(n))
        np.testing.assert_array_equal(arrays["offsets"], np.arange(1, n + 1))
        np.testing.assert_array_equal(arrays["types"], np.full(n, 1))
        assert arrays["TimeValue"][0] == time and arrays["step"][0] == step
        np.testing.assert_array_equal(arrays["box_lo"].ravel(), sim.domain.lo)
    pvd = ET.parse(tmp_path / "post" / "grains.pvd").getroot()
    assert pvd.get("type") == "Collection"
    sets = pvd.findall("Collection/DataSet")
    assert [(float(s.get("timestep")), s.get("file")) for s in sets] == \
        [(time, f"grains_{step}.vtu") for step, time, _ in snaps]
    assert all((tmp_path / "post" / s.get("file")).exists() for s in sets)
    assert sorted(p.name for p in (tmp_path / "post").iterdir()) == \
        sorted(["grains.pvd"] + [f"grains_{s}.vtu" for s, _, _ in snaps])   # no temp files


def test_vtk_names_fields_and_lazy(tmp_path):
    sim = FakeSim()
    d = DumpVTK(sim, "d1", "all", 10, str(tmp_path / "plain.vtu"), ["fields", "id", "radius"])
    assert not list(tmp_path.iterdir())           # nothing before the first frame
    d.write(0)
    sim.advance(10)
    d.write(10)
    d.close()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["plain.pvd", "plain_0.vtu", "plain_10.vtu"]
    _, piece, arrays = read_vtu(tmp_path / "plain_10.vtu")
    assert {da.get("Name") for da in piece.find("PointData")} == {"id", "radius"}
    assert piece.find("PointData").get("Vectors") is None
    np.testing.assert_array_equal(arrays["id"], sim.gather("tag"))

    e = DumpVTK(sim, "solo", "all", 10, str(tmp_path / "x" / "*.vtu"), ["pvd", "none"])
    e.write(10)
    assert [p.name for p in (tmp_path / "x").iterdir()] == ["10.vtu"]
    assert DumpVTK(sim, "solo", "all", 10, str(tmp_path / "*.vtu"), []).pvd_path == str(tmp_path / "solo.pvd")
    f = DumpVTK(sim, "never", "all", 10, str(tmp_path / "y" / "n_*.vtu"), [])
    f.close()
    assert not (tmp_path / "y").exists()


def test_vtk_empty_group_frame(tmp_path):
    sim = FakeSim()
    sim.local["mask"][:] = 1                      # nobody in 'big'
    d = DumpVTK(sim, "d1", "big", 10, str(tmp_path / "e_*.vtu"), [])
    d.write(0)
    _, piece, arrays = read_vtu(tmp_path / "e_0.vtu")
    assert piece.get("NumberOfPoints") == "0" and arrays["Points"].size == 0


def test_vtk_mesh_hook(tmp_path):
    """The shaped-particle hook: a posed mesh replaces the point of a particle with shape >= 0."""
    sim = FakeSim(n=4)
    sim.shapes = OneShape()
    sim.local["shape"][:] = [-1, 0, -1, 0]
    tri = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    faces = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])

    class Meshed(DumpVTK):
        def posed_mesh(self, shape, position, quat, scale=1.0):
            return tri + position, faces

    d = Meshed(sim, "d1", "all", 10, str(tmp_path / "m_*.vtu"), ["fields", "id", "radius"])
    d.write(0)
    _, piece, arrays = read_vtu(tmp_path / "m_0.vtu")
    shapes = sim.gather("shape")
    nmesh = int((shapes >= 0).sum())
    assert int(piece.get("NumberOfPoints")) == 2 + 4 * nmesh
    assert int(piece.get("NumberOfCells")) == 2 + 4 * nmesh
    types_ = arrays["types"]
    assert sorted(types_.tolist()) == [1, 1] + [5] * (4 * nmesh)
    ids = sim.gather("tag")
    # each point carries its particle's id; mesh points sit around their particle
    x = sim.gather("x")
    for i, tag in enumerate(ids):
        pts = arrays["Points"][arrays["id"] == tag]
        if shapes[i] >= 0:
            np.testing.assert_array_equal(pts, tri + x[i])
        else:
            np.testing.assert_array_equal(pts, x[i:i + 1])
    assert arrays["offsets"][-1] == len(arrays["connectivity"])


def test_dump_base_attributes():
    assert DumpH5.kind == "dump" and DumpH5.style == "h5"
    assert DumpVTK.kind == "dump" and DumpVTK.style == "vtk"
    assert issubclass(DumpH5, dump.Dump) and issubclass(DumpVTK, dump.Dump)
    assert DumpH5.__doc__.startswith("dump ID group-ID h5 N")
    assert DumpVTK.__doc__.startswith("dump ID group-ID vtk N")


def test_h5_empty_group_frame(tmp_path):
    sim = FakeSim()
    sim.local["mask"][:] = 1                      # nobody in 'big'
    d = DumpH5(sim, "d1", "big", 10, str(tmp_path / "e.h5"), [])
    d.write(0)
    with h5py.File(tmp_path / "e.h5", "r") as f:
        g = f["frames"][dump_h5.frame_name(0)]
        assert g.attrs["natoms"] == 0 and g["position"].shape == (0, 3) and g["id"].shape == (0,)
    grid = ET.parse(tmp_path / "e.xdmf").getroot().find("Domain/Grid/Grid")
    item = grid.find("Geometry/DataItem")       # readers fail on empty HDF5 items: inline, no attributes
    assert item.get("Format") == "XML" and item.get("Dimensions") == "0 3"
    assert grid.findall("Attribute") == []


def test_files_read_by_vtk(tmp_path):
    """Optional (skipped without the vtk package): VTK's own readers load what the dumps write."""
    xml_io = pytest.importorskip("vtkmodules.vtkIOXML")
    xdmf_io = pytest.importorskip("vtkmodules.vtkIOXdmf2")
    from vtkmodules.util.numpy_support import vtk_to_numpy
    sim = FakeSim(n=9)
    names = ("id", "type", "velocity", "omega", "orientation", "radius", "mass", "shape")
    for fmt in ("binary", "ascii"):
        d = DumpVTK(sim, "m", "all", 10, str(tmp_path / f"{fmt}_*.vtu"), ["format", fmt])
        d.write(0)
        r = xml_io.vtkXMLUnstructuredGridReader()
        r.SetFileName(str(tmp_path / f"{fmt}_0.vtu"))
        r.Update()
        g = r.GetOutput()
        exp = expected(sim)
        assert g.GetNumberOfPoints() == 9 and g.GetNumberOfCells() == 9 and g.GetCellType(0) == 1
        pd = g.GetPointData()
        for name in names:
            np.testing.assert_array_equal(vtk_to_numpy(pd.GetArray(name)), exp[name])
        np.testing.assert_array_equal(vtk_to_numpy(g.GetPoints().GetData()), exp["position"])
        assert pd.GetScalars().GetName() == "radius"
    h = DumpH5(sim, "h", "big", 10, str(tmp_path / "s.h5"), [])
    snaps = run(sim, h, 3)
    sim.local["mask"][:] = 1
    sim.advance(10)
    h.write(sim.update.ntimestep)                 # an empty frame
    snaps.append((sim.update.ntimestep, sim.update.time, expected(sim, "big")))
    x = xdmf_io.vtkXdmfReader()
    x.SetFileName(str(tmp_path / "s.xdmf"))
    for step, time, exp in snaps:
        x.UpdateTimeStep(time)
        o = x.GetOutputDataObject(0)
        n = len(exp["id"])
        assert o.GetNumberOfPoints() == n
        if n:
            pd = o.GetPointData()
            assert pd.GetScalars().GetName() == "radius"
            for name in names:
                if name == "orientation":     # XDMF: one scalar per component (dump_h5._attributes)
                    got = np.column_stack([vtk_to_numpy(pd.GetArray(f"orientation_{c}")) for c in "wxyz"])
                else:
                    got = vtk_to_numpy(pd.GetArray(name))
                np.testing.assert_array_equal(got, exp[name])
            np.testing.assert_array_equal(vtk_to_numpy(o.GetPoints().GetData()), exp["position"])
