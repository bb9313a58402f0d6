"""Plot the time series written by `fix print/series` (or any file of columns with a `# step time name
...` header) to a PNG: one panel per column, against time, step or t* = (t - t0) Omega.

    dem-plot drum.dat [--x time|step|tstar] [--rpm 40] [--columns c_vm c_cn ...] [-o drum_series.png]

The picture goes to the current folder (drum_series.png for drum.dat) unless -o names another. Each panel
is labelled `name [unit]` with what the column is above it, as the file's `# quantity [unit]:` line says
(fix print/series writes it); a thermo keyword is known without it; else the panel shows the name alone.

(also `python -m dem.tools.plot_series ...`, or `python tools/plot_series.py ...` in the source tree.)
"""
import argparse
import math
import os
import sys


def read_series(path):
    """(column names, {name: numpy array}) of a print/series file."""
    import numpy as np
    names = None
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                if names is None:
                    names = line[1:].split()
                continue
            if line.strip():
                rows.append([float(w) for w in line.split()])
    if names is None or not rows:
        raise SystemExit(f"{path}: no header or no data")
    data = np.array(rows)
    return names, {n: data[:, k] for k, n in enumerate(names)}


def series_quantities(path, names):
    """{column name: (quantity, unit)} of a series file: its `# quantity [unit]:` line, else the thermo
    keywords' table (a file from before that line, or written by another program)."""
    from ..quantities import THERMO, parse_header_line
    found = None
    with open(path) as f:
        for line in f:
            if not line.startswith("#"):
                break
            found = parse_header_line(line) or found
    if found is None or len(found) != len(names):
        found = [None] * len(names)
    return {n: q or THERMO.get(n) for n, q in zip(names, found) if q or n in THERMO}


def label_panel(ax, name, quantities):
    """The y label `name [unit]` and, above the panel, what the column is."""
    from ..quantities import label
    described = quantities.get(name)
    ax.set_ylabel(label(name, described))
    if described:
        ax.set_title(described[0], loc="left", fontsize=9)


def figure(path, x="time", rpm=None, columns=None):
    """The matplotlib Figure of a series file: one labelled panel per column."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    names, cols = read_series(path)
    quantities = series_quantities(path, names)
    ys = columns or [n for n in names if n not in ("step", "time")]
    missing = [n for n in ys if n not in cols]
    if missing:
        raise SystemExit(f"{path}: no column {', '.join(missing)} (the columns: {' '.join(names)})")
    if x == "tstar":
        if not rpm:
            raise SystemExit("--x tstar needs --rpm")
        xs = (cols["time"] - cols["time"][0]) * rpm * 2 * math.pi / 60
        xlabel = "t* = t Omega"
    else:
        xs = cols[x]
        xlabel = "time [s]" if x == "time" else "step"
    fig = Figure(figsize=(8, 1.9 * len(ys) + 0.6))
    FigureCanvasAgg(fig)
    axes = fig.subplots(len(ys), 1, sharex=True, squeeze=False)[:, 0]
    for ax, name in zip(axes, ys):
        ax.plot(xs, cols[name], lw=1)
        label_panel(ax, name, quantities)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel(xlabel)
    fig.suptitle(os.path.basename(path))
    fig.tight_layout()
    return fig


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("series")
    p.add_argument("--x", default="time", choices=["time", "step", "tstar"])
    p.add_argument("--rpm", type=float, default=None, help="rotation rate for t* = (t - t0) Omega")
    p.add_argument("--columns", nargs="*", default=None)
    p.add_argument("-o", "--output", default=None)
    a = p.parse_args(argv)
    fig = figure(a.series, a.x, a.rpm, a.columns)
    out = a.output or os.path.splitext(os.path.basename(a.series))[0] + "_series.png"   # in the current folder
    fig.savefig(out, dpi=100)
    print(out)


if __name__ == "__main__":
    sys.exit(main())
