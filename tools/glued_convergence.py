"""Convergence of the lattice mass properties with the points per direction (Grains3D Part III Fig. 3).

Relative error of the volume and of the moment of inertia tensor (largest |I_ij - I_ij,exact| over the
largest principal moment) of a sphere, a cylinder and two overlapping cylinders (orthogonal, equal: the
union of a Steinmetz pair, exact by inclusion-exclusion), against the closed forms, with the error estimate
of union_mass_properties (differences with coarser lattices), whether it covers the true error, and the
time per integration (the fine lattice plus the two coarse ones).

    python tools/glued_convergence.py [--points 10 20 50 ...] [--turned] [--png fig3.png]

``--turned`` poses each body in a random orientation (faces no longer on lattice planes).
"""
import argparse
import time

import numpy as np

from dem.contact.geometry import rotation
from dem.shapes import Cylinder, Sphere
from dem.shapes import glued_mass as gm

RY90 = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])
RX90 = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])


def cases(R):
    s = Sphere(1.0)
    c = Cylinder(1.0, 2.0)
    out = [("sphere", [(s, np.zeros(3), R)], s.volume, R @ s.inertia @ R.T),
           ("cylinder", [(c, np.zeros(3), R)], c.volume, R @ c.inertia @ R.T)]
    r, L = 1.0, 3.0
    cyl = Cylinder(r, L)
    V = 2 * cyl.volume - 16 * r ** 3 / 3                      # minus the Steinmetz bicylinder
    mx = cyl.volume * (L ** 2 / 12 + r ** 2 / 4) - 64 * r ** 5 / 45
    mz = cyl.volume * r ** 2 / 2 - 16 * r ** 5 / 15
    M = np.diag([mx, mx, mz])
    I = np.trace(M) * np.eye(3) - M
    out.append(("2 cylinders", [(cyl, np.zeros(3), R @ RY90), (cyl, np.zeros(3), R @ RX90)], V, R @ I @ R.T))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--points", type=int, nargs="+", default=[10, 20, 50, 100, 200, 300, 500, 750, 1000])
    ap.add_argument("--turned", action="store_true", help="random orientation of each body")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--png", help="plot the errors (matplotlib) to this file")
    args = ap.parse_args(argv)
    R = np.eye(3)
    if args.turned:
        q = np.random.default_rng(args.seed).normal(size=4)
        R = rotation(q / np.linalg.norm(q))
    results = {}
    print("%-12s %6s %13s %13s %13s %9s %8s" % ("body", "points", "err volume", "err inertia", "estimate", "time [s]",
                                              "covered"))
    covered = []
    for name, comps, V, I in cases(R):
        imax = np.abs(np.linalg.eigvalsh(I)).max()
        rows = []
        for n in args.points:
            t = time.perf_counter()
            p = gm.union_mass_properties(comps, n)
            dt = time.perf_counter() - t
            ev = abs(p["volume"] / V - 1)
            ei = float(np.abs(p["inertia"] - I).max() / imax)
            rows.append((n, ev, ei, p["error"], dt))
            covered.append(p["error"] >= max(ev, ei))
            print("%-12s %6d %13.3e %13.3e %13.3e %9.3f %8s" % (name, n, ev, ei, p["error"], dt,
                                                             "yes" if covered[-1] else "NO"))
        results[name] = np.array(rows)
    print("estimate >= true error in %d of %d cases" % (sum(covered), len(covered)))
    if args.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, axes = plt.subplots(1, 2, figsize=(10, 4))
        for name, r in results.items():
            for ax, col in zip(axes, (1, 2)):
                ax.loglog(r[:, 0], np.maximum(r[:, col], 1e-16), "o-", label=name)
        for ax, title in zip(axes, ("(a) volume", "(b) moment of inertia tensor")):
            ax.axhline(2e-3, color="grey", ls=":", lw=1)
            ax.set_xlabel("points per direction")
            ax.set_ylabel("relative error")
            ax.set_title(title)
            ax.legend()
        fig.tight_layout()
        fig.savefig(args.png, dpi=120)
        print("wrote", args.png)
    return results


if __name__ == "__main__":
    main()
