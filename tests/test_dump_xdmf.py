"""dump h5's XDMF read by VTK's XDMF reader as ParaView users open it: from a relative file name in the
output folder; the posed surfaces of shaped particles carry the particle's values per triangle."""
import os
import xml.etree.ElementTree as ET

import h5py
import numpy as np
import pytest

import dem
from test_dump_custom import CUBES, SCRIPT

xdmf_io = pytest.importorskip("vtkmodules.vtkIOXdmf2")
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402


def data_items(path):
    return [d.text for d in ET.parse(path).getroot().iter("DataItem") if d.get("Format") == "HDF"]


def read_at(name, time):
    r = xdmf_io.vtkXdmfReader()
    r.SetFileName(name)
    r.UpdateInformation()
    r.UpdateTimeStep(time)
    return r.GetOutputDataObject(0)


@pytest.mark.parametrize("paths", ["relative", "absolute"])
def test_xdmf_opened_from_a_relative_name(tmp_path, monkeypatch, paths):
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False)
    sim.commands(SCRIPT + f"dump h all h5 20 out/sp.h5 xdmf_paths {paths}\nrun 40\n")
    items = data_items(tmp_path / "out" / "sp.xdmf")
    assert items
    h5 = str(tmp_path / "out" / "sp.h5") if paths == "absolute" else "sp.h5"
    assert all(t.split(":")[0] == h5 for t in items)     # relative: to the XDMF file's folder
    monkeypatch.chdir(tmp_path / "out")
    for name in ("sp.xdmf", "./sp.xdmf", str(tmp_path / "out" / "sp.xdmf")):
        o = read_at(name, sim.update.time)
        assert o.GetNumberOfPoints() == 12, name
        np.testing.assert_array_equal(vtk_to_numpy(o.GetPointData().GetArray("id")), sim.gather("tag"))
    monkeypatch.chdir(tmp_path)
    assert read_at("out/sp.xdmf", sim.update.time).GetNumberOfPoints() == 12
    # Xdmf3 (ParaView's "Xdmf3 Reader") prefixes a relative data item with the folder of the XDMF name it
    # was given, or with that whole name when it has no folder part: only absolute items survive that
    xml_dir = "sp.xdmf"
    resolved = [t.split(":")[0] if t.startswith("/") else xml_dir + t.split(":")[0] for t in items]
    assert all(os.path.exists(os.path.join(tmp_path, "out", p)) for p in resolved) == (paths == "absolute")


def test_surfaces_carry_particle_values_per_triangle(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False)
    sim.commands(CUBES + "dump h all h5 20 cubes.h5 fields id position radius\nrun 40\n")
    with h5py.File(tmp_path / "cubes.h5", "r") as f:
        assert sorted(f["frames"]) == ["0000000000", "0000000020", "0000000040"]
        s = f["frames/0000000040/surface"]
        tri, pid = s["triangles"][:], s["id"][:]
        owner = pid[tri[:, 0]]
        assert np.all(pid[tri] == owner[:, None])       # a triangle belongs to one particle
        np.testing.assert_array_equal(s["cell_id"][:], owner)
    tag, v, w = sim.gather("tag"), sim.gather("v"), sim.gather("omega")
    row = np.searchsorted(tag, owner)
    for name in ("cubes.xdmf", str(tmp_path / "cubes.xdmf")):
        o = read_at(name, sim.update.time)
        assert o.GetNumberOfBlocks() == 2
        points, surf = o.GetBlock(0), o.GetBlock(1)
        assert points.GetNumberOfPoints() == 8
        assert surf.GetNumberOfCells() == len(tri) and surf.GetNumberOfPoints() == len(pid)
        cd = surf.GetCellData()
        np.testing.assert_array_equal(vtk_to_numpy(cd.GetArray("cell_id")), owner)
        np.testing.assert_array_equal(vtk_to_numpy(cd.GetArray("velocity")), v[row])
        np.testing.assert_array_equal(vtk_to_numpy(cd.GetArray("omega")), w[row])
        np.testing.assert_array_equal(vtk_to_numpy(cd.GetArray("type")), sim.gather("type")[row])
        np.testing.assert_array_equal(vtk_to_numpy(cd.GetArray("shape")), 0)
        assert np.abs(vtk_to_numpy(cd.GetArray("velocity"))).max() > 0      # falling: colourable by speed
    # the first frame (before the insertion) has no particle: an empty collection, same kind of data set
    o = read_at("cubes.xdmf", 0.0)
    assert o.GetClassName() == "vtkMultiBlockDataSet" and o.GetNumberOfBlocks() == 0



PVPYTHON_READ = """
import sys
import numpy as np
from paraview import servermanager
from paraview.simple import XDMFReader, Xdmf3ReaderS, Xdmf3ReaderT
from vtkmodules.util.numpy_support import vtk_to_numpy
path, time = sys.argv[1], float(sys.argv[2])
for name, make in (("xdmf", lambda: XDMFReader(FileNames=[path])), ("xdmf3s", lambda: Xdmf3ReaderS(FileName=[path])),
                   ("xdmf3t", lambda: Xdmf3ReaderT(FileName=[path]))):
    r = make()
    r.UpdatePipeline(time)
    d = servermanager.Fetch(r)
    while not d.IsA("vtkDataSet"):
        d = d.GetBlock(0)
    pd = d.GetPointData()
    arrays = {pd.GetArray(i).GetName(): vtk_to_numpy(pd.GetArray(i)) for i in range(pd.GetNumberOfArrays())}
    np.savez(f"{name}.npz", **arrays)
"""


def test_orientation_read_by_paraviews_readers(tmp_path, monkeypatch):
    """ParaView's own readers (pvpython, where ParaView is installed: Debian's is 5.11), on cubes turned
    in flight: the "Xdmf Reader" gives the four columns of the quaternion as the HDF5 holds them (it read
    the 4-column Vector of before as 80 tuples of 3 for 60 particles); the Xdmf3 readers skip them and
    read the rest right. Nothing is read wrong."""
    import shutil
    import subprocess
    pvpython = shutil.which("pvpython")
    if pvpython is None:
        pytest.skip("ParaView's pvpython is not installed (apt-get install paraview)")
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False)
    sim.commands(CUBES + "dump h all h5 20 cubes.h5 surface no\nrun 40\n")
    sim.close()                      # the Xdmf3 readers abort on an HDF5 file open for writing
    (tmp_path / "read.py").write_text(PVPYTHON_READ)
    out = subprocess.run([pvpython, "read.py", str(tmp_path / "cubes.xdmf"), repr(sim.update.time)],
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    with h5py.File(tmp_path / "cubes.h5", "r") as f:
        frame = f["frames"][sorted(f["frames"])[-1]]
        quat, velocity = frame["orientation"][()], frame["velocity"][()]
    assert np.abs(quat - [1, 0, 0, 0]).max() > 1e-3                 # turned: the columns differ
    xdmf = np.load(tmp_path / "xdmf.npz")
    np.testing.assert_array_equal(np.column_stack([xdmf[f"orientation_{c}"] for c in "wxyz"]), quat)
    np.testing.assert_array_equal(xdmf["velocity"], velocity)
    for name in ("xdmf3s", "xdmf3t"):
        arrays = np.load(tmp_path / f"{name}.npz")
        assert not any(k.startswith("orientation") for k in arrays.files)
        np.testing.assert_array_equal(arrays["velocity"], velocity)
