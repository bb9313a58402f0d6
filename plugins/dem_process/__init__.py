"""Plugin: processes and their analysis, for packings and rotating drums (Part III sec 4.1, 4.2).

Fixes: `insert` (random insertion without overlap), `damping/potyondy`
(local non-viscous damping), `print/series` (time series of thermo keywords to a file).
Computes: `ke`, `erotate`, `coord`, `vmean`, `porosity`, `repose`, `corotate`.
Dump: `png` (drum cross-section pictures)."""
from dem.hookspecs import hookimpl

from .compute_basic import ComputeCoord, ComputeERotate, ComputeKE, ComputeVMean
from .compute_drum import ComputeCorotate, ComputeRepose
from .compute_porosity import ComputePorosity
from .dump_png import DumpPNG
from .fix_damping_potyondy import FixDampingPotyondy
from .fix_insert import FixInsert
from .fix_print_series import FixPrintSeries

STYLES = [FixInsert, FixDampingPotyondy, FixPrintSeries, ComputeKE, ComputeERotate,
          ComputeCoord, ComputeVMean, ComputePorosity, ComputeRepose, ComputeCorotate, DumpPNG]


@hookimpl
def dem_styles():
    return STYLES
