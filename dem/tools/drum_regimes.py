"""Flow regimes of a rotating drum from measured markers (Part III sec. 4.2, Fig. 30), for dem-drum-analysis.

Markers of one run, over the last half of its rotation (`markers`):
* co-rotating fraction (compute corotate, c_co) and the fraction co-rotating at the top (c_co[2]);
* free-flight fraction: bed particles (type 1) whose centre is farther than r_i + 1.25 r_max from every
  other particle's centre (r the bounding radii; periodic along the drum axis) and farther than 1.25 r_i
  from the drum wall: touching nothing, with a clear gap (a quarter of the largest radius: in a dense bed
  at rest or carried by the wall, neighbours sit at contact distance give or take round-off), from the
  HDF5 frames;
* the mean and the coefficient of variation (std / mean) of <|v|> / (Omega R) (c_vm), the mean and the
  standard deviation of the surface angle (c_surf), the mean coordination (c_cn: per pair) and, where the
  series has it, the mean coordination counted per contact point (c_cp, `compute coord points`: as
  Grains3D counts the contacts of glued composites);
* the roughness of the free surface: the rms distance of the surface particles from compute repose's
  line (dem_process.compute_drum.surface_fit), from the HDF5 frames: how flat the surface is.

Classification (`classify`), tested in this order; the thresholds are dem's, stated here, not fitted to
the paper:
* centrifuging: at least 95 % of the bed co-rotates with the drum;
* pseudo-cataracting: at least 5 % of the bed is carried over the top with the wall (co-rotating within
  45 degrees of the top, near the wall), the rest does not co-rotate;
* cataracting: at least 1 % of the bed in free flight;
* avalanching: the flow is intermittent: the mean velocity varies by 20 % or more (std / mean);
* cascading (or rolling): a steady flow of the surface layer.
"""
import math

import numpy as np

from .plot_series import read_series

REGIMES = ("avalanching", "cascading", "cataracting", "pseudo-cataracting", "centrifuging")
COLOURS = {"avalanching": "#4477aa", "cascading": "#66ccee", "cataracting": "#228833",
           "pseudo-cataracting": "#ccbb44", "centrifuging": "#ee6677", "transition": "#bbbbbb"}
CENTRIFUGING = 0.95
CARRIED = 0.05
FREE_FLIGHT = 0.01
GAP = 0.25             # the clear gap of a particle in free flight, times the largest radius
INTERMITTENT = 0.2

# Part III sec. 4.2.1, 3D crosses, the regimes the text names at each rate (Fig. 30 is a sketch: "values of
# critical Omega for regime transitions are qualitative only"); 80 rpm: "a transition from avalanching to
# cataracting"
PAPER_CROSS3D = {5: "avalanching", 20: "avalanching", 80: "transition", 125: "cataracting",
                 150: "pseudo-cataracting", 200: "centrifuging", 250: "centrifuging"}
# spheres, from Part III's account of its ref. [39] (sec. 4.2.1): ballistic flights at 150-200 rpm, centrifuging
# from about 220 rpm
PAPER_SPHERES = {150: "cataracting", 200: "cataracting", 250: "centrifuging"}


def frames(f, last_half):
    """The frame groups of an open dem HDF5 dump in step order (names are zero-padded steps), or the last
    half of them."""
    names = sorted(f["frames"])
    return [f["frames"][n] for n in (names[len(names) // 2:] if last_half else names)]


def surface_roughness(path, axis=1, last_half=True):
    """Mean roughness of the free surface (compute repose's: the rms distance of the top of the bed in each
    bin from the fitted line, m) over the frames (of the last half) of an HDF5 dump of a drum whose
    axis `axis` is horizontal, z up."""
    import h5py
    from dem_process.compute_drum import SURFACE_GAP, surface_fit   # the installed plugin (compute repose's fit)
    if axis == 2:
        raise ValueError("surface_roughness: the drum axis must be horizontal (x or y), z up")
    across = 1 - axis                                       # the horizontal direction of the cross-section
    rough = []
    with h5py.File(path, "r", locking=False) as f:
        for g in frames(f, last_half):
            bed = g["type"][()] == 1
            x = g["position"][()][bed]
            gap = SURFACE_GAP * float(g["radius"][()][bed].max())
            rough.append(surface_fit(x[:, across], x[:, 2], gap=gap)[4])
    return float(np.mean(rough)) if rough else math.nan


def free_flight_fraction(path, radius, axis=1, last_half=True):
    """Mean fraction of the bed (type 1) touching nothing, over the frames (of the last half) of an HDF5
    dump of a drum of radius `radius` centred on the axis `axis` (through the origin)."""
    import h5py
    from scipy.spatial import cKDTree
    fractions = []
    with h5py.File(path, "r", locking=False) as f:
        for g in frames(f, last_half):
            x = g["position"][()]
            r = g["radius"][()]
            bed = g["type"][()] == 1
            lo, hi = g.attrs["box_lo"], g.attrs["box_hi"]
            box = np.full(3, 1e3 * float(np.max(hi - lo)))          # open along the other two axes
            box[axis] = hi[axis] - lo[axis]
            y = np.mod(x - lo, box)
            dist, _ = cKDTree(y, boxsize=box).query(y[bed], k=2)
            reach = r[bed] + (1.0 + GAP) * r.max()
            others = [k for k in range(3) if k != axis]
            wall = radius - np.sqrt((x[bed][:, others] ** 2).sum(1))
            free = (dist[:, 1] > reach) & (wall > (1.0 + GAP) * r[bed])
            fractions.append(free.mean() if bed.any() else 0.0)
    return float(np.mean(fractions)) if fractions else 0.0


COLUMNS = ("c_vm", "c_co", "c_co[2]", "c_surf", "c_cn")     # the series columns the markers read


def missing_columns(series):
    names, _ = read_series(series)
    return [c for c in COLUMNS if c not in names]


def markers(series, h5=None, radius=0.05, axis=1):
    """The markers of one run (module doc) as a dict; free_flight is NaN without an HDF5 dump."""
    _, c = read_series(series)
    half = len(c["time"]) // 2
    last = {k: np.asarray(v[half:], float) for k, v in c.items()}
    vm = last["c_vm"]
    return {"corotating": float(np.mean(last["c_co"])),
            "carried": float(np.mean(last["c_co[2]"])),
            "free_flight": free_flight_fraction(h5, radius, axis) if h5 else math.nan,
            "vm": float(np.mean(vm)),
            "vm_cv": float(np.std(vm) / np.mean(vm)) if np.mean(vm) > 0 else 0.0,
            "angle": float(np.mean(last["c_surf"])),
            "angle_std": float(np.std(last["c_surf"])),
            "coordination": float(np.mean(last["c_cn"])),
            "coord_points": float(np.mean(last["c_cp"])) if "c_cp" in last else math.nan,
            "roughness": surface_roughness(h5, axis) if h5 else math.nan}


def classify(m):
    """The regime of a run from its markers (module doc)."""
    if m["corotating"] >= CENTRIFUGING:
        return "centrifuging"
    if m["carried"] >= CARRIED:
        return "pseudo-cataracting"
    if m["free_flight"] >= FREE_FLIGHT:
        return "cataracting"
    if m["vm_cv"] >= INTERMITTENT:
        return "avalanching"
    return "cascading"


def regime_map(rows, path):
    """Fig. 30 as dots: one line per (label, {rpm: regime}) in rows, coloured by regime."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D
    fig = Figure(figsize=(8, 1.2 + 0.6 * len(rows)))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(111)
    for k, (label, regimes) in enumerate(rows):
        for rpm, regime in sorted(regimes.items()):
            ax.scatter([rpm], [k], s=260, color=COLOURS[regime], edgecolor="k", zorder=3)
    ax.set_yticks(range(len(rows)))
    ax.set_yticklabels([label for label, _ in rows])
    ax.set_ylim(-0.7, len(rows) - 0.3)
    ax.set_xlabel("rotation rate (rpm)")
    ax.grid(axis="x", alpha=0.3)
    handles = [Line2D([], [], marker="o", ls="", markersize=10, markerfacecolor=COLOURS[r], markeredgecolor="k",
                      label=r) for r in REGIMES + ("transition",)]
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.35 if len(rows) < 3 else -0.2),
              ncol=3, fontsize=8, frameon=False)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
