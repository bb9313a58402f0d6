#!/usr/bin/env python
"""The cylindrical container of Part III Fig. 19: 250 particles of each shape (equal volume, a sphere of
d = 3 mm) poured into a vertical cylinder of diameter 6.25 d (inputs/in.packing_box -var container
cylinder); the bed height and porosity of each shape, and their ratios to the spheres'.

    python tools/packing_cylinder.py [--shapes sphere cylinder cube tetrahedron cross2d cross3d]
                                     [--settle S ...] [--out packing_cylinder]

Bed height h = 2 <z> (the mean height of the centres is half the bed's in a bed of uniform density) and
porosity 1 - N V / (pi D^2 h / 4); the voxelised porosity 1-3 d above the floor (the script's own) for the
lower bed. Part III gives the ratios of bed heights (sec. 4.1): 3D crosses 5 times the spheres, cylinders
and cubes, 4 times the tetrahedra and 2 times the 2D crosses. Writes `out`.png (the beds seen from the
side, centres coloured by height) and a table on stdout.
"""
import argparse
import math
import os
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
D_EQ = 0.003
SETTLE = {"sphere": 0.5, "cylinder": 0.6, "cube": 0.6, "tetrahedron": 0.8, "cross2d": 1.0, "cross3d": 1.0}


def run(shape, settle):
    import dem
    t0 = time.time()
    sim = dem.Simulation(screen=False, variables=[("shape", [shape]), ("container", ["cylinder"]),
                                                  ("settle", [str(settle)])])
    sim.file(os.path.join(ROOT, "inputs", "in.packing_box"))
    x = sim.gather("x")
    n = len(x)
    h = 2.0 * float(x[:, 2].mean())
    D = 6.25 * D_EQ
    eps = 1.0 - n * math.pi * D_EQ ** 3 / 6 / (math.pi * D * D / 4 * h)
    out = {"n": n, "h": h, "eps": eps, "eps_low": sim.computes["por"].scalar(), "ke": sim.thermo_keyword("ke"),
           "x": x, "wall": time.time() - t0}
    sim.close()
    return out


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--shapes", nargs="+", default=list(SETTLE))
    p.add_argument("--settle", nargs="+", type=float, help="simulated time per shape (s)")
    p.add_argument("--out", default="packing_cylinder")
    a = p.parse_args(argv)
    settle = a.settle or [SETTLE[s] for s in a.shapes]
    res = {}
    for shape, t in zip(a.shapes, settle):
        res[shape] = run(shape, t)
        r = res[shape]
        print(f"{shape}: {r['n']} particles, bed height {1e3 * r['h']:.1f} mm, porosity {100 * r['eps']:.1f} % "
              f"(voxels 1-3 d: {100 * r['eps_low']:.1f} %), kinetic energy {r['ke']:.2e} J, {r['wall']:.0f} s",
              flush=True)
    ref = res.get("sphere")
    print("shape        h (mm)  h/d   porosity  1-3 d   h / h_sphere")
    for shape, r in res.items():
        ratio = f"{r['h'] / ref['h']:.2f}" if ref else "-"
        print(f"{shape:12s} {1e3 * r['h']:6.1f} {r['h'] / D_EQ:5.1f} {100 * r['eps']:8.1f} {100 * r['eps_low']:7.1f}   {ratio}")

    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(2 * len(res), 6))
    FigureCanvasAgg(fig)
    top = max(r["x"][:, 2].max() for r in res.values()) * 1e3 + 3
    for k, (shape, r) in enumerate(res.items()):
        ax = fig.add_subplot(1, len(res), k + 1)
        x = r["x"] * 1e3
        ax.scatter(x[:, 0], x[:, 2], s=12, c=x[:, 2], cmap="viridis", vmin=0, vmax=top)
        R = 6.25 * D_EQ / 2 * 1e3
        ax.plot([-R, -R, R, R], [top, 0, 0, top], "k-", lw=1)
        ax.axhline(1e3 * r["h"], color="r", lw=0.8)
        ax.set_xlim(-R - 1, R + 1)
        ax.set_ylim(-1, top)
        ax.set_aspect("equal")
        ax.set_title(f"{shape}\n{100 * r['eps']:.0f} %", fontsize=9)
        ax.set_xlabel("x (mm)")
        if k == 0:
            ax.set_ylabel("z (mm); red: h = 2 <z>")
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=100)
    print(a.out + ".png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
