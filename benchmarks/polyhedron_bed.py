"""Cost of `pair_style polyhedron/multipoint` against `convex/gjk` on the same bed of cubes, one core.

    python benchmarks/polyhedron_bed.py [--n 10] [--steps 500] [--repeats 3] [--jitter 0.02]

The bed is built, not settled: n^3 cubes of Part III sec 4.1 (edge 2.418 mm, density 2500) on a simple
cubic lattice, 0.1 um into each other face to face (every cube touches its 6 neighbours, 4 points per
face pair with polyhedron/multipoint), each turned by a random rotation of up to `--jitter` rad (then
faces meet at edges and corners too), in a box periodic in x and y with a `wall/plane ... point multipoint`
floor, under gravity, kn = 1e5, en = 0.73, mu = 0.55, gamma_t = 2000, ks = 2/7 kn, dt = 2e-6 s. The two
styles run the same input, alternating, `--steps` steps each after the setup; the figure is the loop time
per particle-step (median of the repeats) and the contacts and points per step.
"""
import argparse
import statistics
import time

import numpy as np

import dem

A = 0.002418
LAW = "kn 1e5 en 0.73 mu 0.55 gamma_t 2000 ks 28571"


def bed(style, n, jitter, seed=5):
    L = n * (A - 1e-7)
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
units si
boundary p p f
region box block 0 {L!r} 0 {L!r} -0.001 {2 * L!r}
create_box 1 box
shape c cube {A}
""")
    rng = np.random.default_rng(seed)
    lines = []
    for i in range(n):
        for j in range(n):
            for k in range(n):
                ax = rng.normal(size=3)
                ax /= np.linalg.norm(ax)
                th = rng.uniform(0, jitter)
                q = [np.cos(th / 2), *(np.sin(th / 2) * ax)]
                x = [(c + 0.5) * (A - 1e-7) for c in (i, j, k)]
                lines.append(f"create_atoms 1 single {x[0]!r} {x[1]!r} {x[2] - 1e-7!r} shape c density 2500 "
                             f"quat {' '.join(repr(float(c)) for c in q)}")
    sim.commands("\n".join(lines) + f"""
pair_style {style}
pair_coeff * * {LAW}
fix integ all nve/shape
fix gravity all gravity 9.81 vector 0 0 -1
fix floor all wall/plane zplane 0 NULL {LAW} point multipoint
timestep 2e-6
thermo 0
""")
    sim.run(0)
    return sim


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=10)
    ap.add_argument("--steps", type=int, default=500)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--jitter", type=float, default=0.02)
    a = ap.parse_args()
    res = {"polyhedron/multipoint": [], "convex/gjk": []}
    info = {}
    for _ in range(a.repeats):
        for style in res:
            sim = bed(style, a.n, a.jitter)
            t = time.perf_counter()
            sim.run(a.steps)
            res[style].append((time.perf_counter() - t) / (a.steps * a.n ** 3))
            info[style] = (sim.pair.ncontacts, getattr(sim.pair, "npoints", sim.pair.ncontacts))
    for style, ts in res.items():
        med = statistics.median(ts)
        print(f"{style:24s} {med * 1e6:7.2f} us/particle-step  {1 / med:10.0f} particle-steps/s  "
              f"contacts {info[style][0]}  points {info[style][1]}")
    p, g = (statistics.median(res[s]) for s in res)
    print(f"ratio polyhedron/multipoint / convex/gjk: {p / g:.2f}")


if __name__ == "__main__":
    main()
