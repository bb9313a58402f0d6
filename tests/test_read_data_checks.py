"""read_data refuses malformed files with the file line and what is wrong, before creating anything."""
import pytest

import dem

HEAD = """LAMMPS data file

2 atoms
1 atom types

0 0.02 xlo xhi
0 0.02 ylo yhi
0 0.02 zlo zhi

Atoms # sphere

"""
GOOD = ["1 1 0.001 2500 0.005 0.005 0.005", "2 1 0.001 2500 0.01 0.01 0.01"]
VEL = "\nVelocities\n\n1 0 0 0 0 0 0\n"

CASES = [
    # (file text, message fragment)
    (HEAD + GOOD[0] + "\n", "header says 2 atoms, the Atoms section has 1 lines"),
    (HEAD + GOOD[0] + "\n2 1 0.001 2500 0.01\n", ":13: an Atoms line of atom_style sphere has 7 or 10 values"),
    (HEAD.replace("2 atoms", "3.5 atoms"), ":3: atoms must be an integer, got '3.5'"),
    (HEAD.replace("0 0.02 xlo", "0 x xlo"), ":6: xhi must be a finite number, got 'x'"),
    (HEAD + "\n".join(GOOD) + "\n\nVelocities\n\n1 0 abc 0 0 0 0\n", ":17: velocity must be a finite number"),
    (HEAD + "\n".join(GOOD) + "\n\nVelocities\n\n1 0 0 0\n", ":17: a Velocities line has 7 values"),
    (HEAD + "\n".join(GOOD) + VEL + "1 1 0 0 0 0 0\n", "a second velocity for atom id 1"),
    (HEAD + GOOD[0] + "\n2 1 0.001 0 0.01 0.01 0.01\n", ":13: density must be > 0, got 0"),
    (HEAD + GOOD[0] + "\n2 1 0.001 -5 0.01 0.01 0.01\n", ":13: density must be > 0, got -5"),
    (HEAD + GOOD[0] + "\n2 1 nan 2500 0.01 0.01 0.01\n", ":13: diameter must be a finite number, got 'nan'"),
    (HEAD.replace("2 atoms", "0 atoms") + "\n", "the Atoms section is empty"),
    (HEAD.replace("Atoms # sphere", ""), "no Atoms section"),
    (HEAD.replace("Atoms # sphere", "Atoms # full") + "\n".join(GOOD) + "\n",
     ":10: Atoms section of atom_style 'full'"),
    (HEAD + GOOD[0] + "\n1 1 0.001 2500 0.01 0.01 0.01\n", ":13: atom id 1 already given on line 12"),
    (HEAD + GOOD[0] + "\n2 1.7 0.001 2500 0.01 0.01 0.01\n", ":13: atom type must be an integer, got '1.7'"),
    (HEAD + GOOD[0] + "\n2 2 0.001 2500 0.01 0.01 0.01\n", ":13: atom type 2 out of range 1..1"),
    (HEAD + "\n".join(GOOD) + "\n\nBonds\n\n1 1 1 2\n", ":15: section 'Bonds' is not supported"),
    (HEAD.replace("1 atom types", "1e9 atom types") + "\n".join(GOOD) + "\n", "must be in 1..1000"),
    # numbers too large for the arrays or the arithmetic (damaged files): refused, not an OverflowError
    (HEAD + GOOD[0] + "\n99999999999999999999 1 0.001 2500 0.01 0.01 0.01\n",
     ":13: atom id must be in 1..9223372036854775807, got 99999999999999999999"),
    (HEAD + GOOD[0] + "\n2 99999999999999999999 0.001 2500 0.01 0.01 0.01\n",
     ":13: atom type 99999999999999999999 out of range 1..1"),
    (HEAD + GOOD[0] + "\n2 1 0.001 2500 0.01 0.01 0.01 0 99999999999999999999 0\n",
     ":13: image flags must be in -2147483647..2147483647"),
    (HEAD + GOOD[0] + "\n2 1 1e300 2500 0.01 0.01 0.01\n", ":13: diameter 1e300 and density 2500 give an infinite mass"),
]


@pytest.mark.parametrize("text, message", CASES, ids=[c[1][:40] for c in CASES])
def test_malformed_data_file(tmp_path, text, message):
    path = tmp_path / "bad.data"
    path.write_text(text)
    sim = dem.Simulation(screen=False)
    with pytest.raises(dem.DemError) as err:
        sim.commands(f"units si\nread_data {path}\n")
    assert message in str(err.value) and err.value.where == "<string>:2"
    assert not sim.domain.box_exist and sim.atom.natoms == 0     # nothing half-made


def test_non_utf8_data_file(tmp_path):
    path = tmp_path / "bad.data"
    path.write_bytes(HEAD.encode() + b"1 1 0.001 2500 0.005 0.005 0.005 \xff\xfe\n")
    with pytest.raises(dem.DemError, match="is not a text"):
        dem.Simulation(screen=False).command(f"read_data {path}")


def test_huge_quaternion_components_keep_their_direction(tmp_path):
    path = tmp_path / "q.data"
    path.write_text(HEAD + GOOD[0] + "\n" + GOOD[1] + " # quat 1e308 1e308 1e308 1e308\n")
    sim = dem.Simulation(screen=False).command(f"read_data {path}")
    assert sim.atom.data["quat"][sim.gather("tag").tolist().index(2)].tolist() == [0.5, 0.5, 0.5, 0.5]


def test_good_file_still_reads(tmp_path):
    path = tmp_path / "good.data"
    path.write_text(HEAD + "\n".join(GOOD) + VEL)
    sim = dem.Simulation(screen=False).command(f"read_data {path}")
    assert sim.atom.natoms == 2 and sim.gather("tag").tolist() == [1, 2]


def test_atom_outside_a_fixed_boundary(tmp_path):
    """Along a fixed boundary an atom outside the box is an error naming its line (it would be lost at the
    first step, or on no rank at all under MPI); along a periodic one it is wrapped as usual."""
    path = tmp_path / "out.data"
    path.write_text(HEAD + GOOD[0] + "\n2 1 0.001 2500 0.03 0.01 0.01\n")
    sim = dem.Simulation(screen=False)
    with pytest.raises(dem.DemError, match=r"out.data:13: atom 2 lies outside the box \(x = 0.03 beyond xhi "
                                           r"0.02, a fixed boundary\)"):
        sim.commands(f"boundary f f f\nread_data {path}\n")
    assert not sim.domain.box_exist
    sim = dem.Simulation(screen=False).commands(f"boundary p f f\nread_data {path}\n")
    assert sim.atom.natoms == 2
