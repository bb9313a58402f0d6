"""tools/packing_cylinder.py: the radial solid-fraction profile against a sphere, whose share of each
ring is known in closed form."""
import importlib.util
import math
import os

import pytest

import dem

spec = importlib.util.spec_from_file_location(
    "packing_cylinder", os.path.join(os.path.dirname(__file__), os.pardir, "tools", "packing_cylinder.py"))
tool = importlib.util.module_from_spec(spec)
spec.loader.exec_module(tool)


def test_radial_profile_of_a_sphere():
    """A sphere of radius a = 3 rings, centred on the axis, profiled over its height: ring [r0, r1] holds
    V(r1) - V(r0) of it, V(r) = 4 pi / 3 (a^3 - (a^2 - r^2)^1.5) (the sphere inside a cylinder of radius r).
    The grid spacing is a / 15, so the voxel count of a curved surface errs by ~0.5 % (measured 0.05,
    0.34 and 0.51 % in the three rings); asserted within 1.5 %. A profile read from the axis instead of
    the wall would swap the outer and inner rings (0.50 and 0.97)."""
    a = 3 * tool.RING
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary f f f
        region box block -0.01 0.01 -0.01 0.01 -0.01 0.01
        create_box 1 box
        create_atoms 1 single 0 0 0 radius {a!r}
    """)
    prof = tool.radial_profile(sim, a, -a, a)
    volume = lambda r: 4 * math.pi / 3 * (a ** 3 - (a * a - r * r) ** 1.5)   # noqa: E731
    assert len(prof) == 3
    for k, (dist, phi) in enumerate(prof):           # from the wall inwards
        r1 = a - k * tool.RING
        r0 = r1 - tool.RING
        assert dist == pytest.approx(a - 0.5 * (r0 + r1), rel=1e-12)
        exact = (volume(r1) - volume(r0)) / (math.pi * (r1 * r1 - r0 * r0) * 2 * a)
        assert phi == pytest.approx(exact, rel=0.015)
    sim.close()
