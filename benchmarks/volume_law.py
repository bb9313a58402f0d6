"""`law volume` against `law descantes` of pair_style polyhedron/multipoint (docs/polyhedra.md).

    python benchmarks/volume_law.py [--pairs 500] [--reps 20] [--settle 0.05] [--repeats 2]

1. One query of two overlapping sharp polytopes (the poses of benchmarks/polytope_vs_epa.py: overlap
   0.1-1 % of the inradius), in one nogil loop: the separating axes with the contact points (what `law
   descantes` needs) against the overlap volume with its gradient (dem/contact/_volume.pyx; `law volume`
   runs the separating axes too, for the census and the apart test).
2. The same bed: `inputs/in.polyhedra_box` (120 bodies poured into a box) run for --settle s with each law,
   alternating (A B A B), CPU time of the process: the laws' costs on their own beds (the volume law's
   bed has deeper, more numerous contacts: docs/polyhedra.md).
"""
import argparse
import os
import resource
import statistics
import subprocess
import sys

import numpy as np

from dem.contact import _polytope, _volume
from dem.contact.polytope import topology_view
from dem.shapes import Polyhedron, cube, pinacoid, tetrahedron

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from polytope_vs_epa import poses  # noqa: E402  (one recipe for overlapping pairs)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def queries(args):
    rng = np.random.default_rng(7)
    e = 0.5 ** 0.5
    cases = [("cube-cube", cube(1.0), cube(1.0)), ("tetrahedron-tetrahedron", tetrahedron(1.5), tetrahedron(1.5)),
             ("pinacoid-pinacoid", pinacoid(e, e, e), pinacoid(e, e, e)),
             ("poly20-poly20", Polyhedron(rng.normal(size=(20, 3))), Polyhedron(rng.normal(size=(20, 3))))]
    print("| pair | separating axes + points | overlap volume | ratio |")
    print("|---|---|---|---|")
    for name, A, B in cases:
        xa, qa, xb, qb = poses(rng, A, B, args.pairs)
        tv = topology_view([A, B])
        ia, ib = np.zeros(args.pairs, np.int32), np.ones(args.pairs, np.int32)
        ftol = 1e-9 * (A.bounding_radius + B.bounding_radius)
        t_pts, _ = _polytope.time_pairs(tv, ia, ib, xa, qa, xb, qb, args.reps, ftol, True)
        t_vol, hits = _volume.time_pairs(tv, ia, ib, xa, qa, xb, qb, args.reps)
        assert hits == args.pairs * args.reps
        print(f"| {name} | {t_pts * 1e6:.2f} us | {t_vol * 1e6:.2f} us | {t_vol / t_pts:.2f} |")


def box_run(law, settle):
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
    subprocess.run([sys.executable, "-m", "dem", "-in", os.path.join(ROOT, "inputs", "in.polyhedra_box"),
                    "-var", "law", law, "-var", "settle", str(settle), "-var", "out", f"volume_law_{law}",
                    "-log", "none", "-screen", "none"], check=True, cwd=os.environ.get("TMPDIR", "/tmp"))
    return resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - before


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pairs", type=int, default=500)
    ap.add_argument("--reps", type=int, default=20)
    ap.add_argument("--settle", type=float, default=0.05)
    ap.add_argument("--repeats", type=int, default=2)
    args = ap.parse_args()
    queries(args)
    times = {"descantes": [], "volume": []}
    for _ in range(args.repeats):
        for law in times:
            times[law].append(box_run(law, args.settle))
    ratios = [v / d for v, d in zip(times["volume"], times["descantes"])]
    for law, t in times.items():
        print(f"in.polyhedra_box, settle {args.settle} s, law {law}: CPU {', '.join(f'{x:.1f}' for x in t)} s")
    print(f"volume / descantes: median {statistics.median(ratios):.2f} ({', '.join(f'{r:.2f}' for r in ratios)})")


if __name__ == "__main__":
    main()
