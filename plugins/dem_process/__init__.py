"""Plugin: processes and their analysis, for packings and rotating drums (Part III sec 4.1, 4.2).

Fixes: `insert` (random insertion without overlap), `remove` (deletion inside a region: an outlet),
`damping/potyondy` (local non-viscous damping), `print/series` (time series of thermo keywords to a
file), `ave/profile` (time-averaged profiles along an axis), `ave/vector` (time-averaged compute vectors
to a file).
Computes: `ke`, `erotate`, `coord`, `vmean`, `porosity`, `repose`, `corotate`; analysis of packings and
flows (docs/analysis.md): `contact/types`, `stress`, `rdf`, `nematic`.
Dump: `png` (drum cross-section pictures)."""
from dem.hookspecs import hookimpl

from .compute_basic import ComputeCoord, ComputeERotate, ComputeKE, ComputeVMean
from .compute_contact_types import ComputeContactTypes
from .compute_drum import ComputeCorotate, ComputeRepose
from .compute_nematic import ComputeNematic
from .compute_porosity import ComputePorosity
from .compute_rdf import ComputeRDF
from .compute_stress import ComputeStress
from .dump_png import DumpPNG
from .fix_ave_profile import FixAveProfile
from .fix_ave_vector import FixAveVector
from .fix_damping_potyondy import FixDampingPotyondy
from .fix_insert import FixInsert
from .fix_print_series import FixPrintSeries
from .fix_remove import FixRemove

STYLES = [FixInsert, FixRemove, FixDampingPotyondy, FixPrintSeries, ComputeKE, ComputeERotate,
          ComputeCoord, ComputeVMean, ComputePorosity, ComputeRepose, ComputeCorotate, DumpPNG,
          ComputeContactTypes, ComputeStress, ComputeRDF, ComputeNematic, FixAveProfile, FixAveVector]


@hookimpl
def dem_styles():
    return STYLES
