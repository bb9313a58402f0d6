#!/usr/bin/env python
"""The cylindrical container of Part III Fig. 19: 250 particles of each shape (equal volume, a sphere of
d = 3 mm) poured into a vertical cylinder of diameter 6.25 d (inputs/in.packing_box -var container
cylinder); the bed height and porosity of each shape, and their ratios to the spheres'.

    python tools/packing_cylinder.py [--shapes sphere cylinder cube tetrahedron cross2d cross3d]
                                     [--settle S ...] [--out packing_cylinder]

Bed height h = 2 <z> (the mean height of the centres is half the bed's in a bed of uniform density) and
porosity 1 - N V / (pi D^2 h / 4); the voxelised porosity 1-3 d above the floor (the script's own) for the
lower bed. Part III gives the ratios of bed heights (sec. 4.1): 3D crosses 5 times the spheres, cylinders
and cubes, 4 times the tetrahedra and 2 times the 2D crosses, and notes a crown along the wall, about half
a beam length wide, where the 3D crosses leave almost nothing but void: the radial profile of the solid
fraction (voxels of d / 20 in rings of d / 4 from the wall inwards, between 1 d above the floor and 1 d
under the bed height h) shows it. Writes `out`.png (the beds seen from the side, centres coloured by
height), `out`_radial.png and `out`_radial.txt (the profiles) and a table on stdout.
"""
import argparse
import math
import os
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
D_EQ = 0.003
RING = 0.25 * D_EQ              # width of the rings of the radial profile
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
           "x": x, "radial": radial_profile(sim, D / 2, D_EQ, h - D_EQ), "wall": time.time() - t0}
    sim.close()
    return out


def radial_profile(sim, R, zlo, zhi):
    """Solid fraction in rings of width RING from the wall (radius R) inwards (the innermost one narrower
    when R is not a whole number of rings), between zlo and zhi: solid and grid points of nested cylinders
    (compute porosity on grids of spacing RING / 5, which then share one lattice), differenced. Rows:
    distance of the ring's middle from the wall, solid fraction."""
    nring = math.ceil(R / RING - 1e-9)
    radii = [max(R - (nring - k) * RING, 0.0) for k in range(nring + 1)]
    points, solid = [0.0], [0.0]
    for k, r in enumerate(radii[1:], 1):
        sim.commands(f"region radial{k} cylinder z 0 0 {r!r} {zlo!r} {zhi!r}\n"
                     f"compute radial{k} all porosity radial{k} dx {RING / 5!r}")
        compute = sim.computes[f"radial{k}"]
        cell = float(np.prod(compute.grid()[1]))
        vector = compute.vector()
        points.append(vector[2] * cell)         # the region's volume as the grid samples it
        solid.append(vector[3])
    rows = [(R - 0.5 * (radii[k] + radii[k - 1]), (solid[k] - solid[k - 1]) / (points[k] - points[k - 1]))
            for k in range(1, nring + 1)]
    return np.array(rows[::-1])         # from the wall inwards


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

    with open(a.out + "_radial.txt", "w") as f:
        f.write("# solid fraction in rings of width d/4 from the cylinder wall inwards, 1 d above the floor to "
                "1 d under the bed height; d = 3 mm\n# shape  wall_distance_over_d  solid_fraction\n")
        for shape, r in res.items():
            for dist, phi in r["radial"]:
                f.write(f"{shape} {dist / D_EQ:.3f} {phi:.4f}\n")
    fig = Figure(figsize=(6, 4))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    for shape, r in res.items():
        ax.plot(r["radial"][:, 0] / D_EQ, r["radial"][:, 1], "o-", ms=3, label=shape)
    ax.set(xlabel="distance from the wall / d", ylabel="solid fraction", xlim=(0, 6.25 / 2), ylim=(0, None),
           title="250 particles in a cylinder of 6.25 d: radial profile")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.out + "_radial.png", dpi=100)
    print(a.out + "_radial.png, " + a.out + "_radial.txt")
    return 0


if __name__ == "__main__":
    sys.exit(main())
