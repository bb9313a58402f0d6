#!/usr/bin/env python
"""Cube-wall impact (Grains3D Part III sec 3.3, Fig. 12): height of the centre and spin omega_x over the
first two impacts, for the five initial orientations of the paper, in one PNG.

    python tools/cube_impact_plot.py --run [--dir out] [-o cube_impact.png]   # run inputs/in.cube_impact
    python tools/cube_impact_plot.py --run --glued [--model A|B] [-o glued_cube_impact.png]
    python tools/cube_impact_plot.py cube_0_0.dat cube_25_25.dat ... [-o cube_impact.png]

The series files are those written by inputs/in.cube_impact (fix print/series: step time z omega_x
...); the legend is taken from the file name (cube_TX_TY[_centroid].dat). --run runs the five cases
twice (about 7 s each on one core), with the wall's single deepest point (solid lines, Grains3D's true
cube) and with `point centroid` (dashed: faces and edges pushed at their middle, the role of the
paper's 8 glued cubes), and writes their series to --dir first.

--glued (Fig. 12 proper): --run runs the five cases with the true cube (inputs/in.cube_impact, deepest
point) and with the glued convex cube (inputs/in.glued_cube_impact, 8 cubes of half the edge, Model B
or --model A; about 35 s each), series glued_cube_TX_TY[_A].dat. Whenever glued series are among the
files, the PNG has one column per case, z (top) and omega_x (bottom), true cube solid, glued dashed.
"""
import argparse
import os
import re
import sys

CASES = [(0, 0), (10, 10), (25, 25), (75, 75), (30, 0)]
HERE = os.path.dirname(os.path.abspath(__file__))
INPUT = os.path.join(HERE, os.pardir, "inputs", "in.cube_impact")
GLUED_INPUT = os.path.join(HERE, os.pardir, "inputs", "in.glued_cube_impact")


def read_series(path):
    import numpy as np
    names, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                names = names or line[1:].split()
            elif line.strip():
                rows.append([float(w) for w in line.split()])
    if names is None or not rows:
        raise SystemExit(f"{path}: no header or no data")
    data = np.array(rows)
    return {n: data[:, k] for k, n in enumerate(names)}


def run_glued_cases(folder, tend=0.45, model="B", cases=CASES, true_cube=True):
    """The five cases with the glued cube (and, with true_cube, the true cube): the series' paths."""
    import dem
    os.makedirs(folder, exist_ok=True)
    paths = []
    for tx, ty in cases:
        runs = [(INPUT, f"cube_{tx}_{ty}.dat", [("point", ["deepest"])])] if true_cube else []
        runs.append((GLUED_INPUT, f"glued_cube_{tx}_{ty}{'_A' if model == 'A' else ''}.dat",
                     [("model", [model])]))
        for inp, name, extra in runs:
            path = os.path.join(folder, name)
            sim = dem.Simulation(screen=False, variables=[("tx", [str(tx)]), ("ty", [str(ty)]),
                                                          ("out", [path]), ("tend", [str(tend)])] + extra)
            sim.file(inp)
            sim.close()
            paths.append(path)
            print(f"({tx}, {ty}) {os.path.basename(inp)}: written {path}", flush=True)
    return paths


def plot_glued(paths, output):
    """One column per case: z (top) and omega_x (bottom); true cube solid, glued cube dashed."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    groups = {}
    for path in paths:
        base = os.path.basename(path)
        m = re.search(r"cube_(-?\d+(?:\.\d+)?)_(-?\d+(?:\.\d+)?)", base)
        if not m:
            raise SystemExit(f"{path}: name is not [glued_]cube_TX_TY[...].dat")
        kind = ("glued A" if base.endswith("_A.dat") else "glued") if base.startswith("glued") else (
            "centroid" if "_centroid" in base else "true")
        groups.setdefault((m.group(1), m.group(2)), []).append((kind, read_series(path)))
    keys = [k for k in ((str(tx), str(ty)) for tx, ty in CASES) if k in groups]
    keys += [k for k in groups if k not in keys]
    fig = Figure(figsize=(3.0 * len(keys), 5.6))
    FigureCanvasAgg(fig)
    styles = {"true": dict(color="C0", lw=1.2, ls="-", label="true cube (1 point)"),
              "glued": dict(color="C3", lw=1.2, ls="--", label="glued cube, 8 cubes (Model B)"),
              "glued A": dict(color="C2", lw=1.2, ls=":", label="glued cube, 8 cubes (Model A)"),
              "centroid": dict(color="C1", lw=1.0, ls="-.", label="true cube, point centroid")}
    for c, key in enumerate(keys):
        ax1 = fig.add_subplot(2, len(keys), c + 1)
        ax2 = fig.add_subplot(2, len(keys), len(keys) + c + 1)
        for kind, s in groups[key]:
            ax1.plot(s["time"], s["c_b[3]"] * 1e3, **styles[kind])
            ax2.plot(s["time"], s["c_b[7]"], **styles[kind])
        ax1.set_title(rf"($\theta_x$, $\theta_y$) = ({key[0]}°, {key[1]}°)", fontsize=9)
        ax2.set_xlabel("t (s)")
        ax1.set_ylim(bottom=0)
        if c == 0:
            ax1.set_ylabel("height of the centre z (mm)")
            ax2.set_ylabel(r"$\omega_x$ (rad/s)")
            ax1.legend(fontsize=7, loc="upper right")
        for ax in (ax1, ax2):
            ax.tick_params(labelsize=7)
    fig.suptitle("Cube-wall impact, true cube vs glued convex cube (Grains3D Part III sec 3.3, Fig. 12)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(output, dpi=130)
    print(f"written {output}")


def run_cases(folder, tend=0.45, points=("deepest", "centroid")):
    import dem
    os.makedirs(folder, exist_ok=True)
    paths = []
    for point in points:
        for tx, ty in CASES:
            path = os.path.join(folder, f"cube_{tx}_{ty}{'_centroid' if point == 'centroid' else ''}.dat")
            sim = dem.Simulation(screen=False, variables=[("tx", [str(tx)]), ("ty", [str(ty)]),
                                                          ("out", [path]), ("tend", [str(tend)]),
                                                          ("point", [point])])
            sim.file(INPUT)
            sim.close()
            paths.append(path)
            print(f"({tx}, {ty}) {point}: written {path}", flush=True)
    return paths


def plot(paths, output):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(11, 4.2))
    FigureCanvasAgg(fig)
    ax1, ax2 = fig.add_subplot(1, 2, 1), fig.add_subplot(1, 2, 2)
    colors = {}
    for path in paths:
        s = read_series(path)
        base = os.path.basename(path)
        m = re.search(r"cube_(-?\d+(?:\.\d+)?)_(-?\d+(?:\.\d+)?)", base)
        key = (m.group(1), m.group(2)) if m else base
        centroid = "_centroid" in base
        if key not in colors:
            colors[key] = f"C{len(colors)}"
        label = (f"({key[0]}°, {key[1]}°)" if m else base) if not centroid else None
        z = s.get("c_b[3]")
        w = s.get("c_b[7]")
        style = dict(color=colors[key], lw=1, ls="--" if centroid else "-")
        ax1.plot(s["time"], z * 1e3, label=label, **style)
        ax2.plot(s["time"], w, **style)
    ax2.plot([], [], color="k", lw=1, label="deepest point (Grains3D true cube)")
    ax2.plot([], [], color="k", lw=1, ls="--", label="point centroid")
    ax2.legend(fontsize=8)
    ax1.set_xlabel("t (s)")
    ax1.set_ylabel("height of the centre z (mm)")
    ax2.set_xlabel("t (s)")
    ax2.set_ylabel(r"$\omega_x$ (rad/s)")
    ax1.legend(title=r"($\theta_x$, $\theta_y$)", fontsize=8)
    ax1.set_title("true cube, one contact point (Part III Fig. 12a)", fontsize=9)
    ax2.set_title("spin about x (Part III Fig. 12b)", fontsize=9)
    fig.tight_layout()
    fig.savefig(output, dpi=130)
    print(f"written {output}")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("series", nargs="*")
    p.add_argument("--run", action="store_true", help="run the five cases first")
    p.add_argument("--dir", default="cube_impact", help="folder of the series written by --run")
    p.add_argument("--glued", action="store_true",
                   help="true cube vs glued cube (inputs/in.glued_cube_impact): runs and plots them")
    p.add_argument("--model", choices=("A", "B"), default="B", help="model of the glued cube (--glued --run)")
    p.add_argument("--tend", type=float, default=0.45)
    p.add_argument("-o", "--output", default="cube_impact.png")
    a = p.parse_args(argv)
    paths = list(a.series)
    if a.run:
        paths += run_glued_cases(a.dir, a.tend, a.model) if a.glued else run_cases(a.dir, a.tend)
    if not paths:
        p.error("give series files or --run")
    if a.glued or any(os.path.basename(q).startswith("glued") for q in paths):
        plot_glued(paths, a.output)
    else:
        plot(paths, a.output)


if __name__ == "__main__":
    sys.exit(main())
