"""Drum analysis plots after Part III sec 4.2.3, from runs of inputs/in.drum at several rotation rates:

* mean translational velocity <|v|> / (Omega R) against t* = t Omega (Fig. 26), from the series files;
* time-averaged coordination number against the rotation rate (Fig. 25), from the series files (average
  over the last half of each run);
* probability density of the time-averaged particle velocity / (Omega R) (Fig. 27), from the HDF5 dumps
  (per-particle average of |v| over the frames of the last half of the run);
* with --h5, the flow regime of each run from measured markers (dem.tools.drum_regimes: co-rotating
  fractions, free flight, intermittency) printed as a table and drawn as the map of Fig. 30, next to what
  Part III's text says of 3D crosses with --paper cross3d.

    dem-drum-analysis --rpm 20 40 80 --series d20.dat d40.dat d80.dat [--h5 d20.h5 d40.h5 d80.h5]
                      [--radius 0.05] [--label "dem, 3D crosses"] [--paper cross3d] [-o drum]

(also `python -m dem.tools.drum_analysis ...`, or `python tools/drum_analysis.py ...` in the source tree.)

writes drum_vmean.png, drum_coordination.png and (with --h5) drum_pdf.png and drum_regimes.png. The series
files must hold the columns c_vm (compute vmean ... drum ...: already divided by Omega R), c_cn (compute
coord), c_surf (compute repose) and c_co, c_co[2] (compute corotate), and may hold c_cp (compute coord
points), as inputs/in.drum writes them; their first line is taken as t = 0 of the rotation.
"""
import argparse
import math
import sys

import numpy as np

from . import drum_regimes
from .plot_series import read_series


def _figure(w=7, h=4.5):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(w, h))
    FigureCanvasAgg(fig)
    return fig, fig.add_subplot(111)


def time_averaged_speed(path, radius, omega, last_half=True):
    """Per-particle |v| of the bed (type 1: not the particles glued to a rough wall, which turn with it)
    averaged over the frames (of the last half) of an HDF5 dump, / (Omega R)."""
    import h5py
    ids0, acc, n = None, 0.0, 0
    with h5py.File(path, "r", locking=False) as f:
        for g in drum_regimes.frames(f, last_half):
            bed = g["type"][()] == 1
            ids = g["id"][()][bed]
            order = np.argsort(ids)
            ids = ids[order]
            if ids0 is not None and not np.array_equal(ids, ids0):
                raise ValueError(f"{path}: the bed's particles change between frames")
            ids0, acc, n = ids, acc + np.sqrt((g["velocity"][()][bed][order] ** 2).sum(1)), n + 1
    return acc / n / (omega * radius)


REGIMES_HEADER = ("rpm  corotating  carried  free_flight  vm     vm_cv  angle  angle_std  coordination  coord_points  "
                  "roughness_mm  regime")


def read_regimes(path):
    """The regime table that main prints (kept as docs/data/drum_sweep/**/regimes.txt): {column: array},
    the regime names as a list."""
    with open(path) as f:
        head = f.readline().split()
        rows = [line.split() for line in f if line.strip()]
    return {name: [r[k] for r in rows] if name == "regime" else np.array([float(r[k]) for r in rows])
            for k, name in enumerate(head)}


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--rpm", nargs="+", type=float, required=True)
    p.add_argument("--series", nargs="+", required=True)
    p.add_argument("--h5", nargs="*", default=None)
    p.add_argument("--radius", type=float, default=0.05)
    p.add_argument("--label", default="dem")
    p.add_argument("--paper", choices=["cross3d"], default=None, help="add Part III's regimes of this shape")
    p.add_argument("-o", "--output", default="drum")
    a = p.parse_args(argv)
    if len(a.series) != len(a.rpm) or (a.h5 and len(a.h5) != len(a.rpm)):
        raise SystemExit("give one series file (and one h5 file) per rotation rate")
    outputs = []

    fig, ax = _figure()
    cn_mean = []
    for rpm, path in zip(a.rpm, a.series):
        _, c = read_series(path)
        w = rpm * 2 * math.pi / 60
        tstar = (c["time"] - c["time"][0]) * w
        ax.plot(tstar, c["c_vm"], lw=1, label=f"{rpm:g} rpm")
        half = len(c["c_cn"]) // 2
        cn_mean.append(float(np.mean(c["c_cn"][half:])))
    ax.set_xlabel("t* = t Omega")
    ax.set_ylabel("<|v|> / (Omega R)")
    ax.legend()
    ax.grid(alpha=0.3)
    outputs.append(f"{a.output}_vmean.png")
    fig.savefig(outputs[-1], dpi=100)

    fig, ax = _figure()
    ax.plot(a.rpm, cn_mean, "o-")
    ax.set_xlabel("rotation rate (rpm)")
    ax.set_ylabel("time-averaged coordination number")
    ax.grid(alpha=0.3)
    outputs.append(f"{a.output}_coordination.png")
    fig.savefig(outputs[-1], dpi=100)

    if a.h5:
        fig, ax = _figure()
        for rpm, path in zip(a.rpm, a.h5):
            s = time_averaged_speed(path, a.radius, rpm * 2 * math.pi / 60)
            hist, edges = np.histogram(s, bins=40, density=True)
            ax.plot(0.5 * (edges[1:] + edges[:-1]), hist, label=f"{rpm:g} rpm")
        ax.set_xlabel("time-averaged |v| / (Omega R)")
        ax.set_ylabel("PDF")
        ax.legend()
        ax.grid(alpha=0.3)
        outputs.append(f"{a.output}_pdf.png")
        fig.savefig(outputs[-1], dpi=100)

        lacking = sorted({c for path in a.series for c in drum_regimes.missing_columns(path)})
        if lacking:
            print(f"no regimes: the series lack the columns {' '.join(lacking)} (inputs/in.drum writes them)")
    if a.h5 and not lacking:
        print(REGIMES_HEADER)
        found = {}
        for rpm, series, h5 in zip(a.rpm, a.series, a.h5):
            m = drum_regimes.markers(series, h5, a.radius)
            found[rpm] = drum_regimes.classify(m)
            print(f"{rpm:<4g} {m['corotating']:10.3f} {m['carried']:8.3f} {m['free_flight']:12.4f} {m['vm']:6.3f} "
                  f"{m['vm_cv']:6.3f} {m['angle']:6.1f} {m['angle_std']:10.1f} {m['coordination']:13.2f} "
                  f"{m['coord_points']:13.2f} {1e3 * m['roughness']:13.2f}  {found[rpm]}")
        rows = [(a.label, found)]
        if a.paper == "cross3d":
            rows.insert(0, ("Part III (text), 3D crosses", drum_regimes.PAPER_CROSS3D))
        outputs.append(f"{a.output}_regimes.png")
        drum_regimes.regime_map(rows, outputs[-1])
    for o in outputs:
        print(o)


if __name__ == "__main__":
    sys.exit(main())
