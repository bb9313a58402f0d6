#!/usr/bin/env python
"""The Beverloo study of inputs/in.hopper: one settled fill, discharged through each orifice, the mass flow
rate against Beverloo's correlation for a round orifice, W = C rho_b sqrt(g) (D - k d)^(5/2).

    python tools/hopper_beverloo.py --run [--np 2] [--orifices 15 18 21 24 27 30] [--workdir hopper_study]
    python tools/hopper_beverloo.py                  # analyse the runs of --workdir, write the plot and table

--run fills the hopper once (`dem -in inputs/in.hopper -var discharge 0`, its restart `settled.restart`),
then discharges that bed through each orifice (`-var from settled_settled.restart -var D ...`, series `hopper_dDD.dat`).
The flow rate of an orifice is the slope of the discharged mass against time (least squares) over the
steady part of the discharge: from `--skip` s after the first particle left (the flow starting) to the end
of the run or until half the bed has left, whichever comes first. The bulk density rho_b is that of the
settled bed in the cone above the orifice: the particles whose centres lie within 12 mm of the axis and
10-40 mm above the plate, their volume over the cylinder's (centres counted: exact on average for a
uniform packing). Fit: W^(2/5) is linear in D, W^(2/5) = (C rho_b sqrt(g))^(2/5) (D - k d), which gives
C and k; also drawn: the correlation with C = 0.58 and k = 1.5 (Beverloo et al. 1961, the usual values).
Output: `--plot` (PNG) and the table on stdout (D, W, the fit, the correlation).
"""
import argparse
import glob
import math
import os
import re
import subprocess
import sys

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ORIFICES = (15, 18, 21, 24, 27, 30)     # mm: inputs/meshes/orifice_dDD.stl
D_PARTICLE = 0.003                      # m, inputs/in.hopper
RHO = 2500.0                            # kg/m3
G = 9.81


def dem_command(np_):
    cmd = [sys.executable, "-m", "dem"]
    return (["mpiexec", "-n", str(np_)] + cmd) if np_ > 1 else cmd


def run(workdir, orifices, np_, fill, discharge, n):
    os.makedirs(workdir, exist_ok=True)
    link = os.path.join(workdir, "inputs")
    if not os.path.exists(link):
        os.symlink(os.path.join(ROOT, "inputs"), link)
    base = dem_command(np_) + ["-in", "inputs/in.hopper", "-var", "N", str(n)]
    if not os.path.exists(os.path.join(workdir, "settled_settled.restart")):
        subprocess.run(base + ["-var", "fill", str(fill), "-var", "discharge", "0", "-var", "out", "settled",
                               "-log", "fill.log", "-screen", "none"], cwd=workdir, check=True)
    for d in orifices:
        subprocess.run(base + ["-var", "from", "settled_settled.restart", "-var", "D", str(d),
                               "-var", "discharge", str(discharge), "-var", "out", f"hopper_d{d}",
                               "-log", f"hopper_d{d}.log", "-screen", "none"], cwd=workdir, check=True)


def bulk_density(restart):
    """rho_b of the settled bed above the orifice (see the module doc)."""
    with h5py.File(restart, "r") as f:
        x = np.asarray(f["fields/x"])
        r = np.asarray(f["fields/radius"])
    inside = (np.hypot(x[:, 0], x[:, 1]) < 0.012) & (x[:, 2] > 0.010) & (x[:, 2] < 0.040)
    volume = math.pi * 0.012 ** 2 * 0.030
    return RHO * float(np.sum(4.0 / 3.0 * math.pi * r[inside] ** 3)) / volume


def flow_rate(path, skip, total_mass):
    """(W kg/s, window (t0, t1), particles in it) from a series file of inputs/in.hopper."""
    data = np.loadtxt(path, comments="#")
    header = open(path).readline().split()[1:]
    t, mass = data[:, header.index("time")], data[:, header.index("f_out[mass]")]
    started = np.flatnonzero(mass > 0)
    if len(started) < 2:
        return None
    t0 = t[started[0]] + skip
    stop = np.flatnonzero(mass > 0.5 * total_mass)
    t1 = t[stop[0]] if len(stop) else t[-1]
    sel = (t >= t0) & (t <= t1)
    if sel.sum() < 10:
        return None
    slope = np.polyfit(t[sel], mass[sel], 1)[0]
    count = data[sel, header.index("f_out[removed]")]
    return float(slope), (float(t0), float(t1)), int(count[-1] - count[0])


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--workdir", default="hopper_study")
    p.add_argument("--run", action="store_true", help="run the fill and the discharges first")
    p.add_argument("--np", type=int, default=1, help="MPI ranks of each run")
    p.add_argument("--orifices", type=int, nargs="+", default=list(ORIFICES), help="orifice diameters (mm)")
    p.add_argument("--n", type=int, default=5000, help="particles")
    p.add_argument("--fill", type=float, default=0.3, help="fill and settle time (s)")
    p.add_argument("--discharge", type=float, default=0.35, help="discharge time (s)")
    p.add_argument("--skip", type=float, default=0.05, help="start-up left out of the fit (s)")
    p.add_argument("--plot", default="hopper_beverloo.png")
    a = p.parse_args(argv)
    if a.run:
        run(a.workdir, a.orifices, a.np, a.fill, a.discharge, a.n)
    restart = os.path.join(a.workdir, "settled_settled.restart")
    rho_b = bulk_density(restart)
    with h5py.File(restart, "r") as f:
        total = float(np.sum(np.asarray(f["fields/rmass"])))
    rows = []
    for path in sorted(glob.glob(os.path.join(a.workdir, "hopper_d*.dat"))):
        d = int(re.search(r"hopper_d(\d+)\.dat$", path).group(1))
        res = flow_rate(path, a.skip, total)
        if res:
            rows.append((d * 1e-3, *res))
    rows.sort()
    D = np.array([r[0] for r in rows])
    W = np.array([r[1] for r in rows])
    slope, intercept = np.polyfit(D, W ** 0.4, 1)
    k = -intercept / slope / D_PARTICLE
    C = slope ** 2.5 / (rho_b * math.sqrt(G))
    print(f"bulk density rho_b = {rho_b:.1f} kg/m3 (solid fraction {rho_b / RHO:.3f}); d = {D_PARTICLE * 1e3:g} mm")
    print(f"fit: C = {C:.3f}, k = {k:.2f}   (Beverloo: C = 0.58, k = 1.5)")
    print("| D (mm) | D/d | W dem (g/s) | window (s) | particles | W fit (g/s) | W Beverloo 0.58, 1.5 (g/s) |")
    print("|---|---|---|---|---|---|---|")
    for d, w, (t0, t1), count in rows:
        fit = C * rho_b * math.sqrt(G) * max(d - k * D_PARTICLE, 0.0) ** 2.5
        bev = 0.58 * rho_b * math.sqrt(G) * (d - 1.5 * D_PARTICLE) ** 2.5
        print(f"| {d * 1e3:g} | {d / D_PARTICLE:.1f} | {w * 1e3:.1f} | {t0:.3f}-{t1:.3f} | {count} | "
              f"{fit * 1e3:.1f} | {bev * 1e3:.1f} |")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.5, 4))
    dd = np.linspace(D.min() * 0.9, D.max() * 1.05, 100)
    ax.plot(D * 1e3, W * 1e3, "o", label="dem (fix wall/mesh hopper)")
    ax.plot(dd * 1e3, C * rho_b * math.sqrt(G) * np.clip(dd - k * D_PARTICLE, 0, None) ** 2.5 * 1e3, "-",
            label=f"Beverloo fit C = {C:.2f}, k = {k:.2f}")
    ax.plot(dd * 1e3, 0.58 * rho_b * math.sqrt(G) * np.clip(dd - 1.5 * D_PARTICLE, 0, None) ** 2.5 * 1e3, "--",
            label="Beverloo C = 0.58, k = 1.5")
    ax.set_xlabel("orifice diameter D (mm)")
    ax.set_ylabel("mass flow rate W (g/s)")
    ax.set_title(f"hopper discharge, spheres d = {D_PARTICLE * 1e3:g} mm")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.plot, dpi=120)
    print(f"wrote {a.plot}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
