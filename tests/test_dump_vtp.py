"""dump vtp: particles as VTK PolyData points, read back by OVITO's own VTP reader (positions, ids,
radii, orientations, velocities, the half sizes of boxes and superquadrics) and by VTK's XML reader
(ParaView's), exactly."""
import numpy as np
import pytest

import dem

SCRIPT = """units si
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01
create_box 2 box
shape c box 0.001 0.002 0.003
shape q superquadric 0.001 0.0015 0.002 4 6
shape t tetrahedron 0.002
create_atoms 1 single 0 0 0 shape c density 2500 quat 0.9238795 0 0.3826834 0
create_atoms 2 single 0.005 0 0 radius 0.001 density 2500
create_atoms 1 single -0.005 0 0 shape q density 2500 quat 0.5 0.5 0.5 0.5
create_atoms 2 single 0 0.005 0 shape t density 2500
set atom 1 vx 0.1 vz -0.2
set atom 3 omega 0 3.0 0
pair_style convex/gjk
pair_coeff * * kn 1000 en 0.5
fix nve all nve/shape
timestep 1e-5
dump o all vtp 10 frames/p_*.vtp
run 20
"""


def _run(tmp_path, monkeypatch, keywords=""):
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False)
    sim.commands(SCRIPT.replace("frames/p_*.vtp", "frames/p_*.vtp " + keywords))
    return sim


def test_read_by_ovito(tmp_path, monkeypatch):
    ovito_io = pytest.importorskip("ovito.io")
    sim = _run(tmp_path, monkeypatch)
    pipeline = ovito_io.import_file(str(tmp_path / "frames" / "p_*.vtp"))
    assert pipeline.num_frames == 3
    p = pipeline.compute(2).particles
    assert p.count == 4
    np.testing.assert_array_equal(np.asarray(p["Particle Identifier"]), sim.gather("tag"))
    np.testing.assert_allclose(np.asarray(p["Position"]), sim.gather("x"), rtol=1e-15)
    np.testing.assert_allclose(np.asarray(p["Velocity"]), sim.gather("v"), rtol=1e-15)
    np.testing.assert_allclose(np.asarray(p["Angular Velocity"]), sim.gather("omega"), rtol=1e-15)
    np.testing.assert_allclose(np.asarray(p["Mass"]), sim.gather("rmass"), rtol=1e-15)
    # OVITO's quaternions are (x, y, z, w); dem's (w, x, y, z)
    np.testing.assert_allclose(np.asarray(p["Orientation"]), sim.gather("quat")[:, [1, 2, 3, 0]], rtol=1e-15)
    shape = np.asarray(p["Aspherical Shape"])
    np.testing.assert_allclose(shape[0], [0.0005, 0.001, 0.0015], rtol=1e-6)    # the box's half sides
    np.testing.assert_allclose(shape[2], [0.001, 0.0015, 0.002], rtol=1e-6)     # the superquadric's
    np.testing.assert_array_equal(shape[[1, 3]], 0.0)          # sphere, tetrahedron: spheres for OVITO
    # the sphere keeps its radius, as does the tetrahedron (its bounding sphere); OVITO zeroes the radius
    # of a particle it draws from its half sizes
    radius = np.asarray(p["Radius"])
    np.testing.assert_allclose(radius[[1, 3]], sim.gather("radius")[[1, 3]], rtol=1e-7)
    roundness = np.asarray(p["Superquadric Roundness"])
    np.testing.assert_allclose(roundness[2], [2 / 6, 2 / 4], rtol=1e-6)     # OVITO's 2/n2, 2/n1
    assert roundness[0].max() <= 0.01 + 1e-7                                 # a box looks sharp
    sim.close()


@pytest.mark.parametrize("fmt", ["binary", "ascii"])
def test_read_by_vtk_exactly_with_times_in_the_pvd(tmp_path, monkeypatch, fmt):
    vtk = pytest.importorskip("vtk")
    from vtk.util.numpy_support import vtk_to_numpy
    sim = _run(tmp_path, monkeypatch, f"format {fmt}")
    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(str(tmp_path / "frames" / "p_20.vtp"))
    reader.Update()
    out = reader.GetOutput()
    assert out.GetNumberOfPoints() == 4 and out.GetNumberOfVerts() == 4
    pd = out.GetPointData()
    got = {pd.GetArrayName(i): vtk_to_numpy(pd.GetArray(i)) for i in range(pd.GetNumberOfArrays())}
    np.testing.assert_array_equal(vtk_to_numpy(out.GetPoints().GetData()), sim.gather("x"))
    for name, field in (("id", "tag"), ("type", "type"), ("v", "v"), ("omega", "omega"), ("radius", "radius"),
                        ("mass", "rmass"), ("shape", "shape")):
        np.testing.assert_array_equal(got[name], sim.gather(field), err_msg=name)
    np.testing.assert_array_equal(got["Orientation"], sim.gather("quat")[:, [1, 2, 3, 0]])
    np.testing.assert_array_equal(got["blockiness1"], [200.0, 2.0, 4.0, 2.0])
    pvd = (tmp_path / "frames" / "p.pvd").read_text()
    assert pvd.count("<DataSet") == 3 and 'file="p_20.vtp"' in pvd
    assert f'timestep="{sim.update.time!r}"' in pvd
    sim.close()


def test_file_name_must_end_in_vtp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False)
    with pytest.raises(dem.DemError, match=r"must end in \.vtp"):
        sim.commands(SCRIPT.replace("frames/p_*.vtp", "frames/p_*.vtu"))
