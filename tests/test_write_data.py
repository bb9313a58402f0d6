"""write_data: a LAMMPS data file (atom_style sphere) that read_data gives back as the same particles, spheres
and shaped ones (dem's extras in the Atoms lines' comments), laid out as LAMMPS reads it."""
import math

import numpy as np
import pytest

import dem

SPHERES = """
units si
boundary p f f
region box block 0 0.02 0 0.01 0 0.01
create_box 2 box
create_atoms 1 random 30 4821 box radius 0.0005 density 2500 v 0.1 -0.2 0.3 omega 1 2 3
create_atoms 2 random 10 99 box radius 0.0008 density 1200
"""
SHAPED = """
units si
boundary f f f
region box block 0 0.02 0 0.02 0 0.02
create_box 1 box
shape c cube 0.002
shape e ellipsoid 0.001 0.0015 0.002
create_atoms 1 single 0.005 0.005 0.005 shape c density 1250 quat 0.9 0.1 0.2 0.3 omega 5 -3 2
create_atoms 1 single 0.015 0.005 0.005 shape e scale 1.3 density 3000 quat random seed 7 v 0.1 0 0
create_atoms 1 single 0.010 0.015 0.010 radius 0.0006 density 2500
"""
FIELDS = ("tag", "type", "x", "image", "v", "omega", "radius", "rmass", "inertia", "quat", "shape")


def state(sim):
    return {name: sim.gather(name) for name in FIELDS}


def round_trip(tmp_path, setup, reread_prefix=""):
    a = dem.Simulation(screen=False).commands(setup)
    path = tmp_path / "state.data"
    a.command(f"write_data {path}")
    b = dem.Simulation(screen=False).commands(f"units si\n{reread_prefix}read_data {path}\n")
    return a, b, path


def assert_same(a, b):
    sa, sb = state(a), state(b)
    for name in FIELDS:
        assert sa[name].shape == sb[name].shape, name
        assert np.allclose(sa[name], sb[name], rtol=1e-14, atol=0), name
    assert np.array_equal(a.domain.lo, b.domain.lo) and np.array_equal(a.domain.hi, b.domain.hi)
    assert a.atom.ntypes == b.atom.ntypes and a.atom.natoms == b.atom.natoms


def test_spheres_round_trip(tmp_path):
    a, b, _ = round_trip(tmp_path, SPHERES)
    a.atom.local("image")[:3, 0] = [2, -1, 0]     # periodic images survive too
    a.command(f"write_data {tmp_path / 'again.data'}")
    b = dem.Simulation(screen=False).commands(f"boundary p f f\nread_data {tmp_path / 'again.data'}")
    assert_same(a, b)
    assert list(b.gather("x")[:, 0]) == list(a.gather("x")[:, 0])      # bitwise: 17 digits


def test_shaped_round_trip(tmp_path):
    a, b, path = round_trip(tmp_path, SHAPED)     # the header's shape commands define the shapes
    assert_same(a, b)
    assert b.shapes.names == ["c", "e"]
    # with the shapes defined by the script, read_data uses them
    c = dem.Simulation(screen=False).commands(f"shape c cube 0.002\nshape e ellipsoid 0.001 0.0015 0.002\n"
                                              f"read_data {path}")
    assert_same(a, c)


def test_unknown_shape_is_an_error_and_leaves_nothing(tmp_path):
    _, _, path = round_trip(tmp_path, SHAPED)
    sim = dem.Simulation(screen=False).command("shape c cube 0.002")
    with pytest.raises(dem.DemError, match="unknown shape 'e'"):
        sim.command(f"read_data {path}")
    assert not sim.domain.box_exist and sim.atom.natoms == 0 and sim.shapes.names == ["c"]


def parse_lammps(path):
    """The data file as LAMMPS's read_data parses it: the first line skipped, `#` starts a comment, header
    keywords at the line ends, then sections headed by a keyword line followed by one blank line."""
    lines = path.read_text().splitlines()
    header, sections, current, style = {}, {}, None, None
    i = 1
    while i < len(lines):
        raw = lines[i]
        text = raw.split("#")[0].strip()
        i += 1
        if not text:
            continue
        if text[0].isalpha():
            current = text
            if current == "Atoms":
                style = raw.split("#")[1].strip()
            assert lines[i].strip() == "", f"a blank line follows the section keyword {current}"
            sections[current] = []
            continue
        if current is None:
            w = text.split()
            if w[-1] in ("atoms", "types"):
                header[" ".join(w[1:])] = int(w[0])
            else:
                header[" ".join(w[2:])] = (float(w[0]), float(w[1]))
        else:
            sections[current].append(text.split())
    return header, sections, style


def test_lammps_conventions(tmp_path):
    a, _, path = round_trip(tmp_path, SHAPED)
    header, sections, style = parse_lammps(path)
    assert header == {"atoms": 3, "atom types": 1, "xlo xhi": (0.0, 0.02), "ylo yhi": (0.0, 0.02),
                      "zlo zhi": (0.0, 0.02)}
    assert style == "sphere" and list(sections) == ["Atoms", "Velocities"]
    rows = sections["Atoms"]
    assert all(len(r) == 10 for r in rows)                      # id type diameter density x y z ix iy iz
    assert [int(r[0]) for r in rows] == [1, 2, 3] and all(int(r[1]) == 1 for r in rows)
    m = a.gather("rmass")
    x = a.gather("x")
    for k, r in enumerate(rows):
        d, rho = float(r[2]), float(r[3])
        assert rho * math.pi / 6 * d ** 3 == pytest.approx(m[k], rel=1e-14)     # LAMMPS's mass is dem's
        assert [float(v) for v in r[4:7]] == list(x[k])
    assert float(rows[0][3]) == pytest.approx(1250, rel=1e-14) and float(rows[2][2]) == 0.0012
    assert all(len(r) == 7 for r in sections["Velocities"])    # id vx vy vz wx wy wz
    assert [float(v) for v in sections["Velocities"][0][4:]] == [5.0, -3.0, 2.0]
