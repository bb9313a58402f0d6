"""The core's set-up and run commands, one module per theme (the Command base class is dem/command.py):

    box.py        units, dimension, boundary, region, create_box
    particles.py  atom_style, atom_modify, group
    models.py     pair_style, pair_coeff, fix, unfix
    run.py        timestep, neighbor, neigh_modify, run, reset_timestep
    output.py     thermo, thermo_style, thermo_modify, dump, dump_modify, undump
    parallel.py   processors, comm_modify, newton

Commands with more to them have modules of their own: compute.py, create_atoms.py, read_data.py,
restart.py, balance.py; the `shape` command lives with the shapes (shapes/command.py).
"""
from .box import Boundary, CreateBox, Dimension, RegionCommand, Units, find_region
from .models import FixCommand, PairCoeff, PairStyle, Unfix
from .output import DumpCommand, DumpModify, ThermoCommand, ThermoModify, ThermoStyle, Undump
from .parallel import CommModify, Newton, Processors
from .particles import AtomModify, AtomStyle, GroupCommand
from .run import NeighborCommand, NeighModify, ResetTimestep, Run, Timestep

COMMANDS = [Units, Dimension, Boundary, RegionCommand, CreateBox, AtomStyle, AtomModify, CommModify, Newton,
            Processors, Timestep, NeighborCommand, NeighModify, ThermoCommand, ThermoStyle, ThermoModify,
            PairStyle, PairCoeff, FixCommand, Unfix, DumpCommand, DumpModify, Undump, Run, ResetTimestep, GroupCommand]

__all__ = ["COMMANDS", "find_region"]
