"""inputs/in.incline (Descantes 2022 sec. 3.2) shortened so that it cannot rot: 60 flowing and 12 substrate
pinacoids in a 2.5 x 2.5 d_sph cell, kn / 100, 10 steps per T_stiffness, a few T_inertia; the Table 2 time
scales and law, the fixed rough bottom, both ways in (prepare, or start from the prepared restart), every
output and the figures of tools/incline_plot.py."""
import importlib.util
import math
import os

import numpy as np

import dem
import dem.law

HERE = os.path.dirname(__file__)
SCRIPT = os.path.join(HERE, os.pardir, "inputs", "in.incline")
TINY = [("N", ["60"]), ("Nb", ["12"]), ("Lx", ["2.5"]), ("Ly", ["2.5"]), ("soft", ["100"]), ("dtn", ["10"]),
        ("prep", ["1"]), ("flow", ["2"]), ("avg", ["1"]), ("zmax", ["60"]), ("theta", ["42"])]


def _run(tmp_path, extra):
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        sim = dem.Simulation(screen=False, variables=TINY + extra)
        sim.file(SCRIPT)
    finally:
        os.chdir(cwd)
    return sim


def _by_tag(sim, name):
    tag = sim.gather("tag")
    return sim.gather(name)[np.argsort(tag)]


def test_incline_input_runs(tmp_path):
    """Table 2 with rho = g = d_sph = 1: T_stiffness = T_inertia / 800 sqrt(soft), dt = T_stiffness / dtn,
    kn = rho V / (2 T_stiffness^2), en 0 with beta_t 1 (gamma_t = gamma_n critical), mu 0.4, gravity
    (0, sin 42, -cos 42) (closed forms, to round-off). The substrate (type 2) does not move at all while the
    layer flows (bitwise), in a run prepared here and in one started from the prepared restart, which
    also gives the same final state as the first (bitwise: the same commands after the restart). The
    profile's mean count sums to the 60 flowing particles (all inside its bounds); all outputs exist."""
    sim = _run(tmp_path, [("out", ["a"])])
    V = (0.5 ** 1.5) / 6 * (3 - 1 / math.tan(math.pi / 3))
    deq = (6 * V / math.pi) ** (1 / 3)
    tst = math.sqrt(deq) / 800 * 10
    assert math.isclose(sim.update.dt, tst / 10, rel_tol=1e-12)
    row = sim.pair.table[1, 1]
    assert math.isclose(row[dem.law.KN], V / (2 * tst ** 2), rel_tol=1e-12)
    assert (row[dem.law.BETA], row[dem.law.BETA_T], row[dem.law.MU]) == (1.0, 1.0, 0.4)
    assert sim.pair.law == "descantes"
    g = sim.modify.find("gravity").g
    assert np.allclose(g, [0, math.sin(math.radians(42)), -math.cos(math.radians(42))], rtol=0, atol=1e-15)
    types = _by_tag(sim, "type")
    assert (types == 2).sum() == 12 and (types == 1).sum() == 60
    for name in ("a.profile.dat", "a.phi.dat", "a.series.dat", "a.summary.txt", "a_prep.restart", "a.h5"):
        assert (tmp_path / name).exists(), name
    p = np.loadtxt(tmp_path / "a.profile.dat")
    p = p[p[:, 0] == p[-1, 0]]
    assert math.isclose(p[:, 4].sum(), 60, rel_tol=1e-12)

    again = _run(tmp_path, [("out", ["b"]), ("prepared", ["1"]), ("from", ["a_prep.restart"])])
    reader = dem.Simulation(screen=False)
    reader.command(f"read_restart {tmp_path / 'a_prep.restart'}")
    base = _by_tag(reader, "type") == 2
    for s in (sim, again):
        assert np.array_equal(_by_tag(s, "x")[base], _by_tag(reader, "x")[base])
        assert np.array_equal(_by_tag(s, "quat")[base], _by_tag(reader, "quat")[base])
        assert not _by_tag(s, "v")[base].any()
    assert np.array_equal(_by_tag(again, "x"), _by_tag(sim, "x"))

    spec = importlib.util.spec_from_file_location("incline_plot", os.path.join(HERE, os.pardir, "tools",
                                                                               "incline_plot.py"))
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)
    runs = tool.main([str(tmp_path / "a"), str(tmp_path / "b"), "-o", str(tmp_path / "fig.png"), "--table"])
    assert (tmp_path / "fig.png").stat().st_size > 10000
    assert runs[0]["theta"] == 42 and math.isclose(runs[0]["z"][1] - runs[0]["z"][0], 0.25, rel_tol=1e-9)
