"""dump gsd read by OVITO's own GSD reader: every particle's type carries the surface mesh of its shape
(composites and polyhedra included), posed by the orientation and scaled by the radius, so that OVITO
draws the true shapes; and, where OVITO can render (it needs a Vulkan driver: apt-get install libvulkan1
mesa-vulkan-drivers), the drawn sizes against the shapes' own."""
import numpy as np
import pytest

import dem

ovito_io = pytest.importorskip("ovito.io")
pytest.importorskip("gsd.hoomd")

SCENE = """boundary p p f
region box block 0 0.03 0 0.03 0 0.03
create_box 1 box
shape x cross3d 0.004 aspect 4
shape t tetrahedron 0.004
shape c cube 0.004
pair_style glued/convex
pair_coeff * * kn 1000 en 0.5 mu 0.5 ks 300
fix nve all nve/shape
create_atoms 1 single 0.004 0.015 0.015 shape x quat 0.9 0.3 0.2 0.1 density 2500 omega 30 0 0
create_atoms 1 single 0.011 0.015 0.015 shape t scale 1.5 density 2500
create_atoms 1 single 0.026 0.015 0.015 shape c density 2500
create_atoms 1 single 0.019 0.005 0.015 radius 0.002 density 2500
timestep 1e-6
dump g all gsd 10 out/p.gsd
run 20
"""


@pytest.fixture
def scene(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False)
    sim.commands(SCENE)
    sim.close()
    return sim, tmp_path / "out" / "p.gsd"


def test_ovito_reads_the_true_shapes(scene):
    """Types: sphere, then the shape table's rows by name, each with its surface mesh at bounding radius 1
    (float32 in the file); per particle the radius, orientation (OVITO's x y z w), position from the box
    centre and id; per frame the step and time. GSD stores single precision: compared to 1e-6."""
    sim, path = scene
    pipeline = ovito_io.import_file(str(path))
    assert pipeline.source.num_frames == 3
    data = pipeline.compute(2)
    types = data.particles.particle_types.types
    assert [t.name for t in types] == ["sphere", "x", "t", "c"]
    table = sim.shapes
    for k, t in enumerate(types[1:]):
        verts, faces = table.mesh(k)
        assert t.mesh is not None and t.mesh.face_count == len(faces)
        np.testing.assert_allclose(t.mesh.get_vertices(), verts / table.radius[k], atol=1e-6)
    p = data.particles
    np.testing.assert_array_equal(np.asarray(p["Particle Type"]), [1, 2, 3, 0])
    np.testing.assert_array_equal(np.asarray(p["id"]), sim.gather("tag"))
    np.testing.assert_allclose(np.asarray(p["Radius"]), sim.gather("radius"), rtol=1e-6)
    np.testing.assert_allclose(np.asarray(p["Orientation"]), sim.gather("quat")[:, [1, 2, 3, 0]], atol=1e-6)
    np.testing.assert_allclose(np.asarray(p["Position"]), sim.gather("x") - 0.015, atol=1e-8)
    assert np.abs(np.asarray(p["Orientation"])[0] - [0, 0, 0, 1]).max() > 0.1    # the cross is turned
    assert data.attributes["Timestep"] == 20
    assert data.attributes["dem/time"] == pytest.approx(sim.update.time)


def test_ovito_draws_them_to_size(scene):
    """Rendered by OVITO (front view, orthographic): the cube's silhouette is its edge wide (4 mm), the
    sphere's its diameter (4 mm), the tetrahedron's (edge 6 mm, seen along a two-fold axis: a square) 6 /
    sqrt(2) = 4.24 mm; within 2 pixels of about 50 (the renderer's edges).
    """
    from ovito.vis import TachyonRenderer, Viewport
    _, path = scene
    pipeline = ovito_io.import_file(str(path))
    pipeline.add_to_scene()
    pipeline.source.data.cell.vis.enabled = False
    viewport = Viewport(type=Viewport.Type.Front)
    viewport.zoom_all()
    try:
        viewport.render_image(size=(600, 300), filename=str(path.with_suffix(".png")), renderer=TachyonRenderer(),
                              background=(1, 1, 1))
    except RuntimeError as e:
        pipeline.remove_from_scene()
        pytest.skip(f"OVITO cannot render here: {str(e).splitlines()[0]}")
    pipeline.remove_from_scene()
    import matplotlib.image
    image = matplotlib.image.imread(str(path.with_suffix(".png")))
    columns = np.flatnonzero((image[..., :3].sum(axis=-1) < 2.9).any(axis=0))
    runs = np.split(columns, np.flatnonzero(np.diff(columns) > 1) + 1)
    widths = [int(r[-1] - r[0] + 1) for r in runs]
    assert len(widths) == 4                          # the cross, the tetrahedron, the sphere, the cube
    cross, tetrahedron, sphere, cube = widths
    assert cube > 40 and abs(sphere - cube) <= 2
    assert abs(tetrahedron - cube * 6 / 4 / np.sqrt(2)) <= 2


@pytest.mark.parametrize("line, message", [
    ("dump g all gsd 10 p_*.gsd", "dump gsd writes every frame into one file: no '\\*'"),
    ("dump g all gsd 10 p.gsd fields id", "unknown gsd dump keyword 'fields'"),
    ("dump g all gsd 0 p.gsd", "N must be"),
    ("dump g all gsd 10", "dump needs: dump ID group style N file"),
])
def test_bad_lines(tmp_path, monkeypatch, line, message):
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False)
    sim.commands("region box block 0 1 0 1 0 1\ncreate_box 1 box")
    with pytest.raises(dem.DemError, match=message):
        sim.command(line)


def test_without_the_gsd_package(tmp_path, monkeypatch):
    import sys
    monkeypatch.chdir(tmp_path)
    monkeypatch.setitem(sys.modules, "gsd.hoomd", None)
    sim = dem.Simulation(screen=False)
    sim.commands("region box block 0 1 0 1 0 1\ncreate_box 1 box")
    with pytest.raises(dem.DemError, match=r"dump gsd needs the gsd package \(pip install gsd\)"):
        sim.command("dump g all gsd 10 p.gsd")
