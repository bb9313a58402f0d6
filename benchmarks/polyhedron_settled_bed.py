"""A settled bed of 1000 sharp cubes: `pair_style polyhedron/multipoint` against `convex/gjk`, one core; the
packing is exported for Yade (benchmarks/yade_cube_bed.py).

    python benchmarks/polyhedron_settled_bed.py [--N 1000] [--steps 1000] [--warmup 200] [--repeats 3]
                                                [--settle 150000] [--ke-tol 1e-6] [--dir DIR]
                                                [--export benchmarks/cube_bed_packing.txt]

The bed is the one of benchmarks/cube_bed.py (`setup`: the single source of its parameters): N cubes of
edge 2.418 mm, density 2500, at random non-overlapping positions and orientations in a box periodic in x
and y (17.5 edges wide for N = 1000) with a floor, kn = 1e5 N/m, en = 0.73, mu = 0.55, gamma_t = 2000 1/s,
ks = 28571 N/m, dt = 2e-6 s, gravity, here with a `wall/plane ... point multipoint` floor. It settles
once with each style from the same random start (so each packing is the one its style sees): --settle
steps, then chunks of 10,000 steps until the kinetic energy (translation + rotation) is below --ke-tol
N m g a (m the mass of a cube, a its edge; 1e-6: an rms speed of about 0.2 mm/s), at most --settle-max
steps. The settled states are written once to restarts in --dir (default: a fixed folder under the
system's temporary one, reused by later runs), and the polyhedron/multipoint packing (positions and
quaternions) to --export as plain text (committed: benchmarks/cube_bed_packing.txt).

Timing: a fresh simulation per run reads a restart, runs --warmup steps, then --steps steps, in turn
(A B C A B C ...): polyhedron/multipoint on its bed, convex/gjk on its own bed, and convex/gjk on the
polyhedron/multipoint packing (the crust-rounded cubes lose most of the sharp cubes' corner and edge
contacts there: a bed that is not at rest, with few contacts, shown for completeness). The figures: the
loop time per particle-step (the sum of the run's timers, wall clock), the process CPU time per
particle-step, the contacts at the end of the run (pairs; points for polyhedron/multipoint; points on the
floor) and the loop time per contact-step (pairs + floor points); medians over the repeats and the
medians of the paired ratios.
"""
import argparse
import os
import statistics
import sys
import tempfile
import time

import numpy as np

import dem

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cube_bed import A, LAW, setup  # noqa: E402  (the bed's parameters: one source of truth)

DENSITY = 2500.0
G = 9.81
POLY = "pair_style polyhedron/multipoint"
GJK = "pair_style convex/gjk"
WALL = "point multipoint"
STYLES = {"polyhedron/multipoint": POLY, "convex/gjk": GJK}


def energy_scale(n):
    return n * DENSITY * A ** 3 * G * A


def settle(style, n, steps, steps_max, tol, path, chunk=10000):
    """Settles the bed of cube_bed.setup with `style`; writes the restart `path`."""
    sim = dem.Simulation(screen=False)
    sim.commands(setup("cube", n, pair=STYLES[style], wall=WALL))
    done = 0
    scale = energy_scale(n)
    while True:
        run = steps if done == 0 else chunk
        sim.run(run)
        done += run
        ke = (sim.thermo_keyword("ke") + sim.thermo_keyword("erot")) / scale
        print(f"  {style}: settled {done} steps ({done * 2e-6:.2f} s): kinetic energy {ke:.3g} N m g a, "
              f"{sim.pair.ncontacts} contacts, {getattr(sim.pair, 'npoints', sim.pair.ncontacts)} points", flush=True)
        if ke < tol or done >= steps_max:
            break
    sim.commands(f"write_restart {path}")
    return sim, done, ke


def export(sim, path, n, settled, ke):
    """Positions and quaternions (w x y z, body frame to space frame, the cube's faces normal to the body
    axes), one particle a line, ordered by id; a header of '#' lines gives the box."""
    x = sim.gather("x")
    q = sim.gather("quat")
    lo, hi = [float(v) for v in sim.domain.lo], [float(v) for v in sim.domain.hi]
    with open(path, "w") as f:
        f.write(f"# settled bed of {n} cubes, dem benchmarks/polyhedron_settled_bed.py: polyhedron/multipoint, "
                f"{settled} steps of 2e-6 s, kinetic energy {ke:.3g} N m g a\n")
        f.write(f"# edge {A!r} density {DENSITY!r} floor z = 0, periodic in x and y\n")
        f.write(f"# box {lo[0]!r} {hi[0]!r} {lo[1]!r} {hi[1]!r} {lo[2]!r} {hi[2]!r}\n")
        f.write("# x y z qw qx qy qz\n")
        for xi, qi in zip(x, q):
            f.write(" ".join(f"{v:.17g}" for v in (*xi, *qi)) + "\n")


def timed(style, path, warmup, steps):
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        shape c cube {A}
        read_restart {path}
        {STYLES[style]}
        pair_coeff * * {LAW}
        fix integ all nve/shape
        fix g all gravity {G} vector 0 0 -1
        fix floor all wall/plane zplane 0 NULL {LAW} {WALL}
        thermo 0
    """)
    sim.run(warmup)
    cpu = time.process_time()
    sim.run(steps)
    cpu = time.process_time() - cpu
    up = sim.update
    n = sim.atom.natoms
    loop = sum(up.timers.values())
    p = sim.pair
    nc = p.ncontacts
    floor = next(f for f in sim.modify.fixes if f.id == "floor").ncontacts
    return {"loop": loop / (n * steps), "cpu": cpu / (n * steps), "pair": up.timers["pair"] / (n * steps),
            "contacts": nc, "points": getattr(p, "npoints", nc), "floor": floor,
            "per_contact": loop / (max(nc + floor, 1) * steps),
            "types": dict(getattr(p, "contact_types", {}))}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--N", type=int, default=1000)
    ap.add_argument("--steps", type=int, default=1000)
    ap.add_argument("--warmup", type=int, default=200)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--settle", type=int, default=150000)
    ap.add_argument("--settle-max", type=int, default=400000)
    ap.add_argument("--ke-tol", type=float, default=1e-6)
    ap.add_argument("--dir", default=os.path.join(tempfile.gettempdir(), "dem_polyhedron_settled_bed"),
                    help="folder of the settled beds' restarts (reused when present)")
    ap.add_argument("--export", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                     "cube_bed_packing.txt"),
                    help="plain-text packing for Yade (written when the bed is settled)")
    a = ap.parse_args(argv)
    os.makedirs(a.dir, exist_ok=True)
    beds = {}
    for style in STYLES:
        tag = "poly" if style == "polyhedron/multipoint" else "gjk"
        beds[style] = os.path.join(a.dir, f"{tag}_cube_{a.N}_{a.settle}_{a.ke_tol:g}.restart")
        if not os.path.exists(beds[style]):
            print(f"settling the bed with {style} ({a.settle} steps, then until the kinetic energy is below "
                  f"{a.ke_tol:g} N m g a)...", flush=True)
            sim, settled, ke = settle(style, a.N, a.settle, a.settle_max, a.ke_tol, beds[style])
            if style == "polyhedron/multipoint":
                export(sim, a.export, a.N, settled, ke)
                print(f"packing for Yade: {a.export}", flush=True)
        print(f"settled {style} bed: {beds[style]}", flush=True)
    # the runs: polyhedron/multipoint on its bed; convex/gjk on its own settled bed (the same random start,
    # settled with convex/gjk: at rest, as many contacts); convex/gjk on the polyhedron packing (its rounded
    # edges and corners leave most of the sharp cubes' corner contacts open: not at rest, few contacts)
    runs = {"polyhedron/multipoint": ("polyhedron/multipoint", beds["polyhedron/multipoint"]),
            "convex/gjk (own bed)": ("convex/gjk", beds["convex/gjk"]),
            "convex/gjk (poly packing)": ("convex/gjk", beds["polyhedron/multipoint"])}
    res = {r: [] for r in runs}
    for r in range(a.repeats):
        for label, (style, path) in runs.items():
            t = timed(style, path, a.warmup, a.steps)
            res[label].append(t)
            print(f"run {r + 1} {label:26s} {t['loop'] * 1e6:7.3f} us/particle-step (pair {t['pair'] * 1e6:.3f}) "
                  f"{1 / t['loop']:10.0f} particle-steps/s (CPU {t['cpu'] * 1e6:.3f} us)  "
                  f"contacts {t['contacts']} (points {t['points']}) + floor {t['floor']}  "
                  f"{t['per_contact'] * 1e6:.3f} us/contact-step" + (f"  types {t['types']}" if t["types"] else ""),
                  flush=True)
    if not a.repeats:
        return 0
    print(f"median of {a.repeats} runs of {a.steps} steps after {a.warmup}, N = {a.N}:")
    for label, ts in res.items():
        med = statistics.median(t["loop"] for t in ts)
        cpu = statistics.median(t["cpu"] for t in ts)
        print(f"  {label:26s} {med * 1e6:7.3f} us/particle-step  {1 / med:10.0f} particle-steps/s  "
              f"(CPU time {cpu * 1e6:.3f} us, {1 / cpu:.0f} /s)  "
              f"contacts {ts[-1]['contacts']} (points {ts[-1]['points']}) + floor {ts[-1]['floor']}  "
              f"{statistics.median(t['per_contact'] for t in ts) * 1e6:.3f} us/contact-step")
    for other in list(runs)[1:]:
        ratios = [p["loop"] / g["loop"] for p, g in zip(res["polyhedron/multipoint"], res[other])]
        print(f"  polyhedron/multipoint / {other}: {statistics.median(ratios):.2f}x (median of the paired ratios, "
              f"{min(ratios):.2f}-{max(ratios):.2f})")

if __name__ == "__main__":
    sys.exit(main())
