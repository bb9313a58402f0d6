"""read_restart and the shape table: particles hold the row index of their shape, so the restart's shapes
are restored with them; shapes the script defines before read_restart must be the restart's, the same in
the same order (numbers compared by value), else the restart is refused naming both definitions (a
different row there gave the saved cubes the shape of a cross, silently)."""
import pytest

import dem

SHAPES = ["shape cu cube 0.002", "shape el ellipsoid 0.002 0.001 0.001"]
WRITE = """units si
boundary f f f
region box block 0 0.02 0 0.02 0 0.02
create_box 1 box
{shapes}
create_atoms 1 single 0.005 0.01 0.01 shape cu density 2500
create_atoms 1 single 0.015 0.01 0.01 shape el density 2500
write_restart {path}
"""


@pytest.fixture(scope="module")
def restart(tmp_path_factory):
    path = tmp_path_factory.mktemp("restart") / "shapes.restart"
    dem.Simulation(screen=False).commands(WRITE.format(shapes="\n".join(SHAPES), path=path))
    return path


def particle_shapes(sim):
    """Per particle (by id): the name, kind and sizes of its shape."""
    return [(*sim.shapes.definitions[k][:2], *map(float, sim.shapes.definitions[k][2:]))
            for k in sim.gather("shape")]


@pytest.mark.parametrize("before", [[], SHAPES, ["shape cu cube 2e-3"] + SHAPES[1:],
                                    SHAPES + ["shape big sphere 0.01"]],
                         ids=["none", "the same", "the same by value", "the same and one more"])
def test_the_restart_shapes_are_the_particles_shapes(restart, before):
    sim = dem.Simulation(screen=False)
    sim.commands("\n".join(["units si"] + before + [f"read_restart {restart}"]))
    assert particle_shapes(sim) == [("cu", "cube", 0.002), ("el", "ellipsoid", 0.002, 0.001, 0.001)]


@pytest.mark.parametrize("before, saved, defined", [
    (SHAPES[::-1], SHAPES[0], SHAPES[1]),                                           # swapped
    (["shape cu cube 0.003", SHAPES[1]], SHAPES[0], "shape cu cube 0.003"),         # another size
    (["shape cu cross3d 0.002", SHAPES[1]], SHAPES[0], "shape cu cross3d 0.002"),    # another kind
    (SHAPES[:1], SHAPES[1], None),                                                  # one missing
], ids=["swapped", "size", "kind", "missing"])
def test_other_shapes_before_read_restart_are_an_error_naming_both(restart, before, saved, defined):
    sim = dem.Simulation(screen=False)
    lines = ["units si"] + before + [f"read_restart {restart}"]
    with pytest.raises(dem.DemError) as err:
        sim.commands("\n".join(lines))
    assert err.value.where == f"<string>:{len(lines)}"
    message = str(err.value)
    assert f"of the restart is '{saved}'" in message, message
    assert (f"the script defined '{defined}'" if defined else "the script defined no shape") in message, message
