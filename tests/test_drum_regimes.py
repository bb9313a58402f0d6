"""Drum flow regimes from markers (dem.tools.drum_regimes): the classification rules in their order, and
the free-flight fraction on a hand-made frame whose answer is known."""
import h5py
import numpy as np
import pytest

from dem.tools import drum_regimes as dr

R = 0.05


def marks(**kw):
    m = {"corotating": 0.5, "carried": 0.0, "free_flight": 0.0, "vm_cv": 0.05}
    m.update(kw)
    return m


@pytest.mark.parametrize("kw, regime", [
    ({"corotating": 0.96, "carried": 0.3, "free_flight": 0.02}, "centrifuging"),
    ({"corotating": 0.94, "carried": 0.06, "free_flight": 0.02}, "pseudo-cataracting"),
    ({"carried": 0.04, "free_flight": 0.011, "vm_cv": 0.5}, "cataracting"),
    ({"free_flight": 0.009, "vm_cv": 0.21}, "avalanching"),
    ({"vm_cv": 0.19}, "cascading"),
])
def test_classification_rules(kw, regime):
    assert dr.classify(marks(**kw)) == regime


def test_free_flight_fraction(tmp_path):
    """Seven bed particles (type 1) of radius 1 mm and one wall sphere (type 2) in a drum of R = 50 mm,
    axis y, periodic depth 10 mm: a touching pair, a particle touching the wall sphere, one touching the
    drum wall, a pair touching across the periodic boundary, and one alone in the middle: 1 of 7 is free
    (in both frames)."""
    x = np.array([[0.0, 0.005, -0.03], [0.0019, 0.005, -0.03],        # a touching pair
                  [0.02, 0.005, 0.0], [0.0219, 0.005, 0.0],          # bed particle on a wall sphere (type 2)
                  [0.0, 0.005, 0.0495],                              # touching the drum wall
                  [-0.02, 0.0003, 0.0], [-0.02, 0.0098, 0.0],        # touching across y = 0 / 10 mm
                  [0.0, 0.005, 0.01]])                               # alone
    types = np.array([1, 1, 1, 2, 1, 1, 1, 1])
    path = tmp_path / "d.h5"
    with h5py.File(path, "w") as f:
        f.attrs["format"] = "dem-dump-h5"
        for step in (0, 100):
            g = f.create_group(f"frames/{step:010d}")
            g.attrs["box_lo"] = [-0.0505, 0.0, -0.0505]
            g.attrs["box_hi"] = [0.0505, 0.01, 0.0505]
            g["position"] = x
            g["radius"] = np.full(len(x), 0.001)
            g["type"] = types
    assert dr.free_flight_fraction(path, R) == pytest.approx(1 / 7)
