"""dem-plot labels each panel `name [unit]` with what the column is: thermo keywords from their table
(dem/quantities.py, the one the thermo keywords are checked against), computes and fixes as their style
declares, written by fix print/series into its header; the name alone where nothing is known."""
import pytest

import dem
from dem.errors import DemError
from dem.quantities import THERMO, header_line, parse_header_line
from dem.tools import plot_series

DRUM = """
boundary f p f
region box block -0.06 0.06 0 0.03 -0.06 0.06
create_box 1 box
region inside cylinder y 0 0 0.05 EDGE EDGE
create_atoms 1 random 60 3 inside radius 0.003 density 2500
pair_style sphere
pair_coeff * * kn 1e4 en 0.5
fix integ all nve/sphere
fix drum all wall/drum y 0 0 0.05 rpm 30 kn 1e4 en 0.5
compute surf all repose drum
compute vm all vmean drum drum
compute fast all vmean
variable twice equal 2*ke
timestep 1e-5
thermo 0
"""


def series(tmp_path, words):
    path = tmp_path / "d.dat"
    with dem.Simulation(screen=False) as sim:
        sim.commands(DRUM + f"fix s all print/series 5 {path} {words}\nrun 10\n")
    return path


def labels(path, columns=None):
    fig = plot_series.figure(str(path), columns=columns)
    return [(ax.get_ylabel(), ax.get_title(loc="left")) for ax in fig.axes]


def test_panels_name_their_quantity_and_unit(tmp_path):
    path = series(tmp_path, "ke c_surf c_surf[3] c_vm c_fast[5] f_drum[revs] f_drum[torque] v_twice c_surf[2]")
    assert labels(path) == [
        ("ke [J]", "translational kinetic energy"),
        ("c_surf [deg]", "angle of repose"),
        ("c_surf[3] [m]", "surface height at the axis"),
        ("c_vm [-]", "mean speed / (Omega R)"),
        ("c_fast[5] [m/s]", "largest speed"),
        ("f_drum[revs] [-]", "drum turns"),
        ("f_drum[torque] [N m]", "torque of the walls on the particles"),
        ("v_twice", ""),                          # a variable declares nothing: its name
        ("c_surf[2] [-]", "surface slope"),
    ]
    fig = plot_series.figure(str(path))
    assert fig.axes[-1].get_xlabel() == "time [s]"


def test_a_file_without_the_quantity_line(tmp_path):
    """Series written before the line (or by another program): thermo keywords still, others by name."""
    path = series(tmp_path, "ke c_surf")
    lines = path.read_text().splitlines()
    assert lines[1].startswith("# quantity [unit]: step [-] | simulated time [s] | ")
    path.write_text("\n".join(lines[:1] + lines[2:]) + "\n")
    assert labels(path) == [("ke [J]", "translational kinetic energy"), ("c_surf", "")]


def test_unknown_column_is_a_clear_error(tmp_path):
    path = series(tmp_path, "ke")
    with pytest.raises(SystemExit, match="no column c_nothing"):
        plot_series.figure(str(path), columns=["c_nothing"])


def test_the_header_line_reads_back():
    described = [("angle of repose", "deg"), None, ("torque", "N m")]
    assert parse_header_line(header_line(described)) == described
    assert parse_header_line("# step time ke") is None
    for quantity, unit in THERMO.values():          # nothing in the table would break the line apart
        assert "|" not in quantity + unit and "[" not in quantity and unit


def test_every_keyword_of_the_table_is_a_thermo_keyword():
    """The table is the thermo keywords' list: each one evaluates, and a name not in it is refused."""
    with dem.Simulation(screen=False) as sim:
        sim.commands(DRUM + "run 0\n")
        for name in THERMO:
            float(sim.thermo_keyword(name))          # a name of the table that thermo lacks raises here
        with pytest.raises(DemError, match="unknown thermo keyword 'kee'.*'ke'"):
            sim.command("thermo_style custom step kee")
