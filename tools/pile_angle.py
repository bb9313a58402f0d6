"""The slope a pile keeps after the gate of inputs/in.cohesive_pour opens, for several works of adhesion w
(JKR) and rolling-resistance coefficients mu_roll (EPSD2): how cohesion and rolling resistance steepen a
pile (docs/contact_law.md).

    python tools/pile_angle.py [--w 0 0.3 1.0] [--mu-roll 0 0.05 0.1 0.2] [--jobs 2] [--out docs/data/pile_angle]

Each case runs the input (w with mu_roll 0, and mu_roll with w 0: the dry pile) in its own process and
measures the surface of the final pile from the particles' positions: the pile seen along y is cut into
columns one diameter wide along x, the top of each column (the highest particle top of the column that
rises from the floor without a gap of more than a diameter) marks the surface, and a least-squares line
through the columns whose surface lies between 15 % and 85 % of the pile's height (leaving out the
crest against the wall and the toe) gives the angle (none when the pile stands as poured). Written:
OUT.csv (w, mu_roll, angle in degrees, columns used, rms distance of the surface from the line, height
of the pile, its front: the last column more than one layer of grains high), OUT.png (the surfaces and their lines) and
the input's last picture of each case (OUT_wW_mu_rollM.png).
"""
import argparse
import csv
import math
import os
import sys
import tempfile
from concurrent.futures import ProcessPoolExecutor

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
INPUT = os.path.join(HERE, "..", "inputs", "in.cohesive_pour")
D = 0.002                       # the input's diameter
LOW, HIGH = 0.15, 0.85          # the part of the pile's height the line is fitted to


def surface(x, z, r):
    """(column centres, surface heights) of a pile at rest: columns one diameter wide along x, the highest
    particle top in each."""
    cx, top = [], []
    for lo in np.arange(0.0, x.max() + D, D):
        sel = (x >= lo) & (x < lo + D)
        if np.any(sel):
            cx.append(lo + 0.5 * D)
            top.append(float(np.max(z[sel] + r[sel])))
    return np.array(cx), np.array(top)


def angle(cx, top):
    """(degrees, columns used, rms, line) of the line through the surface between LOW and HIGH of its
    height; NaN when fewer than 3 columns lie there (the pile stands as poured: no slope to fit)."""
    h = top.max()
    sel = (top > LOW * h) & (top < HIGH * h)
    if sel.sum() < 3:
        return math.nan, int(sel.sum()), math.nan, (math.nan, math.nan)
    slope, icpt = np.polyfit(cx[sel], top[sel], 1)
    rms = float(np.sqrt(np.mean((top[sel] - (slope * cx[sel] + icpt)) ** 2)))
    return math.degrees(math.atan(abs(slope))), int(sel.sum()), rms, (slope, icpt)


def run_case(w, mu_roll):
    import dem
    with tempfile.TemporaryDirectory() as folder:
        cwd = os.getcwd()
        os.chdir(folder)
        try:
            sim = dem.Simulation(screen=False, variables=[("w", [str(w)]), ("mu_roll", [str(mu_roll)]),
                                                             ("out", ["pile"])])
            sim.file(INPUT)
            x, r = sim.gather("x"), sim.gather("radius")
            pictures = sorted(os.listdir("pile"))
            with open(os.path.join("pile", max(p for p in pictures if p.endswith(".png"))), "rb") as f:
                picture = f.read()
        finally:
            os.chdir(cwd)
    cx, top = surface(x[:, 0], x[:, 2], r)
    deg, used, rms, line = angle(cx, top)
    front = float(cx[top > 1.5 * D].max()) if np.any(top > 1.5 * D) else math.nan     # beyond one layer
    return {"w": w, "mu_roll": mu_roll, "angle": deg, "columns": used, "rms": rms, "cx": cx, "top": top,
            "line": line, "height": float(top.max()), "front": front, "picture": picture}


def plot(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 4))
    for res in results:
        lab = f"w {res['w']:g} J/m2, mu_roll {res['mu_roll']:g}: {res['angle']:.1f} deg"
        p = ax.plot(res["cx"] * 1e3, res["top"] * 1e3, ".-", label=lab)
        s, c = res["line"]
        if np.isfinite(s):
            xs = np.array([res["cx"].min(), res["cx"].max()])
            ax.plot(xs * 1e3, (s * xs + c) * 1e3, "--", color=p[0].get_color(), lw=0.8)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("surface height (mm)")
    ax.set_ylim(bottom=0)
    ax.set_aspect("equal")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--w", type=float, nargs="+", default=[0.0, 0.15, 0.3, 0.5, 1.0])
    p.add_argument("--mu-roll", type=float, nargs="+", default=[0.05, 0.1, 0.2, 0.3])
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--out", default="pile_angle")
    a = p.parse_args(argv)
    cases = [(w, 0.0) for w in a.w] + [(0.0, m) for m in a.mu_roll if m > 0]
    with ProcessPoolExecutor(a.jobs) as pool:
        results = list(pool.map(run_case, *zip(*cases)))
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    with open(a.out + ".csv", "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["w", "mu_roll", "angle_deg", "columns", "rms_m", "height_m", "front_m"])
        for res in results:
            out.writerow([res["w"], res["mu_roll"], f"{res['angle']:.2f}", res["columns"], f"{res['rms']:.3g}",
                          f"{res['height']:.4g}", f"{res['front']:.4g}"])
            print(f"w {res['w']:g} J/m2, mu_roll {res['mu_roll']:g}: {res['angle']:.1f} degrees "
                  f"({res['columns']} columns, rms {res['rms'] * 1e3:.2f} mm), height {res['height'] * 1e3:.1f} "
                  f"mm, front at {res['front'] * 1e3:.0f} mm")
            with open(f"{a.out}_w{res['w']:g}_mu_roll{res['mu_roll']:g}.png", "wb") as f:
                f.write(res["picture"])
    plot(results, a.out + ".png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
