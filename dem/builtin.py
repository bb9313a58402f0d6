"""The core's own styles, announced through the same entry-point group (`dem`) as every plugin."""
from .balance import BALANCE_STYLES
from .commands import COMMANDS
from .compute import COMMANDS as COMPUTE_COMMANDS
from .create_atoms import CreateAtoms, SetCommand
from .dump_custom import DumpCustom
from .dump_gsd import DumpGSD
from .dump_h5 import DumpH5
from .dump_vtk import DumpVTK
from .dump_vtp import DumpVTP
from .hookspecs import hookimpl
from .fix_python import PYTHON_FIXES
from .integrate import INTEGRATORS
from .read_data import ReadData
from .region import REGIONS
from .restart import RESTART_COMMANDS
from .shapes.command import SHAPE_STYLES
from .write_data import WriteData


@hookimpl
def dem_styles():
    return (COMMANDS + COMPUTE_COMMANDS + [CreateAtoms, SetCommand, ReadData, WriteData] + RESTART_COMMANDS
            + REGIONS + INTEGRATORS + PYTHON_FIXES + BALANCE_STYLES + SHAPE_STYLES + [DumpH5, DumpVTK, DumpVTP, DumpCustom, DumpGSD])
