"""inputs/in.pinacoid_packing (Descantes 2022 sec. 3.1) shortened so that it cannot rot: 60 pinacoids in a
3 x 3 d_sph box, kn / 100, 10 T_inertia; the Table 1 time scales, every output it writes and the figures of
tools/pinacoid_plot.py."""
import importlib.util
import math
import os
import shutil

import numpy as np

import dem
import dem.law

SCRIPT = os.path.join(os.path.dirname(__file__), os.pardir, "inputs", "in.pinacoid_packing")


def test_pinacoid_packing_input_runs(tmp_path):
    """Table 1 with rho = g = d_sph = 1: V = 0.143, T_inertia = sqrt(d_eq), dt = T_inertia / 400 sqrt(soft)
    / 80 and kn = rho V / (2 T_stiffness^2) (closed forms, to round-off). The solid fraction profile holds
    the particles' volume: over a profile spanning the whole column (zmax 30 d_eq; the short run is not
    settled), sum(phi) dz Lx^2 equals the volume of the pinacoids (the voxel count of compute porosity at
    d_eq / 20 per voxel: 0.5 %). All outputs are written; the profile is written once, at the end, so
    it averages the whole window (`fall` 6.1 puts the window off the multiples of its length)."""
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        sim = dem.Simulation(screen=False, variables=[("N", ["60"]), ("Lx", ["3"]), ("soft", ["100"]),
                                                      ("fall", ["6.1"]), ("damp", ["2"]), ("rest", ["2"]),
                                                      ("out", ["tiny"]), ("zmax", ["30"])])
        sim.file(SCRIPT)
    finally:
        os.chdir(cwd)
    V = (0.5 ** 1.5) / 6 * (3 - 1 / math.tan(math.pi / 3))
    assert abs(V - 0.143) < 5e-4
    deq = (6 * V / math.pi) ** (1 / 3)
    tst = math.sqrt(deq) / 400 * 10
    assert math.isclose(sim.update.dt, tst / 80, rel_tol=1e-12)
    assert math.isclose(sim.pair.table[1, 1, dem.law.KN], V / (2 * tst ** 2), rel_tol=1e-12)
    assert sim.atom.natoms == 60 and sim.pair.law == "descantes"
    for name in ("tiny.profile.dat", "tiny.rdf.dat", "tiny.restart", "tiny.h5", "tiny.xdmf", "tiny_0.png"):
        assert (tmp_path / name).exists(), name
    a = np.loadtxt(tmp_path / "tiny.profile.dat")
    a = a[a[:, 0] == a[-1, 0]]
    assert len(a) == 60
    dz = a[1, 3] - a[0, 3]
    assert a[-1, 3] + dz / 2 > sim.gather("x")[:, 2].max() + 0.5        # the profile spans every body
    assert a[0, 0] == sim.update.ntimestep            # one block, written at the end: the whole window
    assert len(np.loadtxt(tmp_path / "tiny.profile.dat")) == 60
    s = sim.gather("radius") / sim.shapes.rows[0].bounding_radius      # the scale of each pinacoid
    assert math.isclose(a[:, 4].sum() * dz * 9.0, (V * s ** 3).sum(), rel_tol=5e-3)

    # the figures of tools/pinacoid_plot.py from these files
    spec = importlib.util.spec_from_file_location(
        "pinacoid_plot", os.path.join(os.path.dirname(__file__), os.pardir, "tools", "pinacoid_plot.py"))
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)
    assert math.isclose(tool.DEQ, deq, rel_tol=1e-12)
    tool.main([str(tmp_path / "tiny"), "-o", str(tmp_path / "fig.png")])
    assert (tmp_path / "fig.png").stat().st_size > 10000
    for kind in ("profile", "rdf"):            # the copies kept in docs/data end in .txt
        shutil.copy(tmp_path / f"tiny.{kind}.dat", tmp_path / f"kept.{kind}.txt")
    tool.main([str(tmp_path / "kept"), "-o", str(tmp_path / "kept.png")])
    assert (tmp_path / "kept.png").stat().st_size > 10000


def test_pinacoid_packing_goes_on_from_a_settled_bed(tmp_path):
    """`-var prepared 1 -var from F` reads the bed an earlier run wrote and rests it for `rest` more
    T_inertia before averaging: same particles, the step goes on from the file's, every output again."""
    cwd = os.getcwd()
    os.chdir(tmp_path)
    tiny = [("N", ["30"]), ("Lx", ["2.5"]), ("soft", ["100"]), ("fall", ["3.1"]), ("damp", ["1"]),
            ("rest", ["1"])]
    try:
        first = dem.Simulation(screen=False, variables=tiny + [("out", ["a"])])
        first.file(SCRIPT)
        reader = dem.Simulation(screen=False)
        reader.command("read_restart a.restart")
        again = dem.Simulation(screen=False, variables=tiny + [("out", ["b"]), ("prepared", ["1"]),
                                                              ("from", ["a.restart"])])
        again.file(SCRIPT)
    finally:
        os.chdir(cwd)
    steps_rest = round(0.75 * 1 * math.sqrt((6 * 0.5 ** 1.5 / 6 * (3 - 1 / math.tan(math.pi / 3)) / math.pi)
                                            ** (1 / 3)) / again.update.dt)
    averaging = first.update.ntimestep - reader.update.ntimestep        # the same in both runs
    assert again.atom.natoms == 30 and averaging > 0
    # the rest ends on the next multiple of the window's length (where the averages are written)
    rested = again.update.ntimestep - averaging
    assert rested % averaging == 0 and 0 <= rested - (reader.update.ntimestep + steps_rest) < averaging
    assert np.loadtxt(tmp_path / "b.profile.dat")[-1, 0] == again.update.ntimestep   # the whole window
    for name in ("b.profile.dat", "b.rdf.dat", "b.restart"):
        assert (tmp_path / name).exists(), name


def test_pinacoid_packing_stiffens_a_softer_bed(tmp_path):
    """`-var stiffen S0` raises the contact stiffness of a bed settled with `soft` S0 to the run's `soft` in
    ten geometric steps of 0.1 T_inertia each, then rests it: at the end the pair and the floor have the
    run's kn (closed form, to round-off), and the ten steps come before the rest. Without `prepared 1`
    the word is refused with a message (there is no bed to stiffen)."""
    cwd = os.getcwd()
    os.chdir(tmp_path)
    tiny = [("N", ["30"]), ("Lx", ["2.5"]), ("fall", ["3.1"]), ("damp", ["1"]), ("rest", ["1"])]
    try:
        dem.Simulation(screen=False, variables=tiny + [("soft", ["100"]), ("out", ["a"])]).file(SCRIPT)
        reader = dem.Simulation(screen=False)
        reader.command("read_restart a.restart")
        stiff = dem.Simulation(screen=False, variables=tiny + [("soft", ["10"]), ("stiffen", ["100"]),
                                                               ("out", ["b"]), ("prepared", ["1"]),
                                                               ("from", ["a.restart"])])
        stiff.file(SCRIPT)
        refused = dem.Simulation(screen=False, variables=tiny + [("stiffen", ["100"])])
        refused.file(SCRIPT)
    finally:
        os.chdir(cwd)
    V = (0.5 ** 1.5) / 6 * (3 - 1 / math.tan(math.pi / 3))
    tin = math.sqrt((6 * V / math.pi) ** (1 / 3))
    kn = V / (2 * (tin / 400 * math.sqrt(10)) ** 2)
    assert math.isclose(stiff.pair.table[1, 1, dem.law.KN], kn, rel_tol=1e-12)
    assert math.isclose(stiff.modify.find("floor").law["kn"], kn, rel_tol=1e-12)
    dt = stiff.update.dt
    nlast = 100 * round(0.25 * tin / dt / 100)                    # the averaging window (rest 1)
    rest_end = stiff.update.ntimestep - nlast
    stiffened = reader.update.ntimestep + 10 * round(0.1 * tin / dt)
    # the rest starts after the ten stages and runs up to the next multiple of the window's length
    assert rest_end % nlast == 0 and 0 <= rest_end - (stiffened + round(0.75 * tin / dt)) < nlast
    assert refused.input.quit_status == 2 and refused.atom.natoms == 0
