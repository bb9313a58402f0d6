"""dump contacts: the contact points of pair_style polyhedron/multipoint as VTK PolyData, read back by VTK's
own reader. A cube resting off-centre on another one on a floor: at the frames, 4 face/face points at the
corners of the overlap square, the normal from the upper cube (id 2) to the lower one (id 1), and the
recorded forces on cube 1 are what the pass applied: cube 2 touches nothing else, so its force is its
weight minus their sum (to round-off)."""
import os

import numpy as np
import pytest

import dem

A = 0.002          # cube edge
OFF = (0.0003, 0.0002)
M = 2500 * A ** 3


def stacked(every="2000", extra=""):
    return f"""units si
boundary p p f
region box block -0.005 0.005 -0.005 0.005 0 0.01
create_box 1 box
shape c cube {A}
create_atoms 1 single 0 0 {A / 2} shape c density 2500
create_atoms 1 single {OFF[0]} {OFF[1]} {1.5 * A} shape c density 2500
pair_style polyhedron/multipoint
pair_coeff * * kn 1e5 en 0.1 mu 0.5 ks 28571 gamma_t 2000
fix integ all nve/shape
fix g all gravity 9.81 vector 0 0 -1
fix floor all wall/plane zplane 0 NULL kn 1e5 en 0.1 mu 0.5 point multipoint
timestep 1e-6
dump cp all contacts {every} cp_*.vtp {extra}
"""


def read_vtp(path):
    vtk = pytest.importorskip("vtk")
    from vtk.util.numpy_support import vtk_to_numpy
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(str(path))
    r.Update()
    out = r.GetOutput()
    pd = out.GetPointData()
    arrays = {pd.GetArrayName(i): vtk_to_numpy(pd.GetArray(i)) for i in range(pd.GetNumberOfArrays())}
    return vtk_to_numpy(out.GetPoints().GetData()), arrays


@pytest.mark.parametrize("fmt", ["binary", "ascii"])
def test_points_of_a_resting_cube(tmp_path, monkeypatch, fmt):
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False)
    sim.commands(stacked(extra=f"format {fmt}"))
    sim.run(6000)
    assert sorted(os.listdir(tmp_path)) == ["cp.pvd", "cp_0.vtp", "cp_2000.vtp", "cp_4000.vtp", "cp_6000.vtp"]
    pts, a = read_vtp(tmp_path / "cp_6000.vtp")
    assert len(pts) == 4 and list(a["type"]) == [4, 4, 4, 4]
    np.testing.assert_array_equal(a["ids"], [[1, 2]] * 4)
    # the overlap square's corners: x in [OFF_x - A/2, A/2], y in [OFF_y - A/2, A/2], at the shared face
    # (the cubes moved by less than 1e-6 m: overlaps of ~1e-9 m, friction holds the offset)
    want = [(OFF[0] - A / 2, OFF[1] - A / 2), (OFF[0] - A / 2, A / 2), (A / 2, OFF[1] - A / 2), (A / 2, A / 2)]
    got = sorted(tuple(np.round(p, 5)) for p in pts[:, :2])
    np.testing.assert_allclose(got, sorted(want), atol=1e-6)
    np.testing.assert_allclose(pts[:, 2], A, atol=1e-6)
    np.testing.assert_allclose(a["normal"], [[0, 0, -1]] * 4, atol=1e-5)
    assert np.all(a["overlap"] > 0) and np.all(a["overlap"] < 1e-7)
    # the forces: the pass that made this frame applied them; cube 2's force is its weight minus their sum
    f2 = sim.gather("f")[1]
    np.testing.assert_allclose(f2, [0, 0, -M * 9.81] - a["force"].sum(axis=0), rtol=0, atol=1e-12 * M * 9.81 * 1e3)
    assert a["force"][:, 2].sum() == pytest.approx(-M * 9.81, rel=0.3)     # roughly its weight (still settling)
    # the points held by the pair style are the file's
    np.testing.assert_array_equal(sim.pair.contact_points["point"][np.lexsort(sim.pair.contact_points["point"].T[::-1])],
                                  pts[np.lexsort(pts.T[::-1])])
    sim.close()


def test_points_are_kept_only_for_the_frames(tmp_path, monkeypatch):
    """Between frames the pair style keeps no points (no cost); a run with no contacts dump never does."""
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False)
    sim.commands(stacked(every="1000"))
    sim.run(1500)
    assert sim.pair.contact_points is None and sim.pair.contact_points_step is None
    sim.run(500)
    assert sim.pair.contact_points_step == 2000 and len(sim.pair.contact_points["point"]) == 4
    sim.close()


def test_contacts_need_the_multipoint_pair_style(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False)
    text = stacked().replace("pair_style polyhedron/multipoint", "pair_style convex/gjk")
    with pytest.raises(dem.DemError, match="needs pair_style polyhedron/multipoint"):
        sim.commands(text + "run 10\n")
    sim.close()
    with pytest.raises(dem.DemError, match="use group all"):
        dem.Simulation(screen=False).commands(stacked().replace("dump cp all", "group one id 1\ndump cp one"))


@pytest.mark.parametrize("ks", ["28571", "0"])
def test_many_points_grow_the_buffer(tmp_path, monkeypatch, ks):
    """16 columns of 3 cubes (1 um apart sideways), each cube overlapping the one below by 1e-8 m: 32
    face/face pairs, 128 points at the first frame, past the pass's first buffer (64 rows): it grows and
    the pass resumes, with the keyed history (ks > 0) and without it (ks = 0); each pair once, 4 points."""
    monkeypatch.chdir(tmp_path)
    side, up = A + 1e-6, A - 1e-8
    atoms = "".join(f"create_atoms 1 single {(i - 1.5) * side} {(j - 1.5) * side} {(k + 0.5) * up + 0.001} "
                    "shape c density 2500\n" for i in range(4) for j in range(4) for k in range(3))
    sim = dem.Simulation(screen=False)
    sim.commands(f"""units si
boundary f f f
region box block -0.01 0.01 -0.01 0.01 0 0.01
create_box 1 box
shape c cube {A}
{atoms}pair_style polyhedron/multipoint
pair_coeff * * kn 1e5 en 0.5 mu 0.5 ks {ks} gamma_t 2000
fix integ all nve/shape
timestep 1e-7
dump cp all contacts 10 cp_*.vtp
run 0
""")
    pts, a = read_vtp(tmp_path / "cp_0.vtp")
    assert len(pts) == 128 and np.all(a["type"] == 4)
    pairs, counts = np.unique(a["ids"], axis=0, return_counts=True)
    assert len(pairs) == 32 and np.all(counts == 4)
    assert np.all(np.abs(a["normal"][:, 2]) == 1.0)
    assert len(sim.pair._rec) > 64          # the buffer did grow (white box: the path this test is for)
    sim.close()
