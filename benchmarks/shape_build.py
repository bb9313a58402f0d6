"""CPU time to build a `shape ... polyhedron` from N points: the convex hull, its faces and edges
(dem/shapes/topology.py), the mass properties and the crust core (dem/shapes/polyhedron.py).

    python benchmarks/shape_build.py [--n 1000 20000] [--repeats 3] [--cloud sphere|ball]

`sphere`: N points on a sphere of radius 1 mm, every point a hull vertex (the worst case, a finely scanned
grain); `ball`: N points uniform in the ball (most inside the hull). The median CPU time of `repeats`
builds is printed per N, with the numbers of hull vertices and core vertices. scipy is imported before the
clock starts (its import is paid once per run, not per shape).
"""
import argparse
import time

import numpy as np
import scipy.spatial  # noqa: F401  (imported before timing)

from dem.shapes.polyhedron import Polyhedron


def cloud(kind, n, seed=1):
    rng = np.random.default_rng(seed)
    P = rng.normal(size=(n, 3))
    P /= np.linalg.norm(P, axis=1)[:, None]
    if kind == "ball":
        P *= rng.random(n)[:, None] ** (1.0 / 3.0)
    return 1e-3 * P


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, nargs="+", default=[1000, 20000])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--cloud", choices=("sphere", "ball"), default="sphere")
    args = ap.parse_args()
    for n in args.n:
        P = cloud(args.cloud, n)
        times = []
        for _ in range(args.repeats):
            t = time.process_time()
            s = Polyhedron(P)
            times.append(time.process_time() - t)
        print(f"{args.cloud} N={n}: {np.median(times):.3f} s CPU (median of {args.repeats}; "
              f"{len(s.vertices)} hull vertices, {len(s.core_vertices)} core vertices)", flush=True)


if __name__ == "__main__":
    main()
