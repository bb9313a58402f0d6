"""Cost of convex particles: a dense bed of cubes (pair_style convex/gjk, fix nve/shape) against the same
bed made of spheres of equal volume (pair_style sphere, fix nve/sphere), one core. Grains3D reports about
5x for cubes over spheres (Part III sec 2.5); the goal here is <= 3x. `--shape cylinder` or `ellipsoid`
times a bed of cylinders (D = L) or ellipsoids (semi-axes 2:1.5:1) of the same volume instead: curved
bodies, whose GJK warm start is a simplex of body-frame points rather than vertices.

    python benchmarks/cube_bed.py [--shape cube|cylinder|ellipsoid] [--N 1000] [--steps 5000] [--repeats 3]
                                  [--settle 150000]

Both beds are built alike: N particles of volume (2.418 mm)^3 (the cubes of Part III sec 4.1: equal
volume to a sphere of radius 1.5 mm) at the same random positions (non-overlapping bounding spheres of
the cubes, 20 % of the volume; cubes randomly oriented), in a box periodic in x and y (17.5 edges wide
for N = 1000) with a floor, kn = 1e5 N/m, en = 0.73, mu = 0.55, density 2500, dt = 2e-6 s (Table 5/6),
with the tangential spring and damping of inputs/in.drum (ks = 2/7 kn, gamma_t = 2000 1/s: without them
friction exerts no force), then settled under gravity for --settle steps (written to a restart once).
The settled beds are timed for --steps steps, alternating cube and sphere runs; the figure is the median
of the paired ratios of the loop time per particle-step (and of the pair stage alone). The GJK calls,
separating-axis pre-tests and margin skips per step are reported too.
"""
import argparse
import os
import statistics
import sys
import tempfile

import dem

A = 0.002418          # cube edge (m): volume of a sphere of radius 1.5 mm
RC = 2.25 ** (1.0 / 3.0) * 1e-3   # radius of the D = L cylinder of that volume: 2 pi RC^3 = 4/3 pi (1.5 mm)^3
LAW = "kn 1e5 en 0.73 mu 0.55 gamma_t 2000 ks 28571"   # as inputs/in.drum (friction needs gamma_t or ks)
KE = 1.125 ** (1.0 / 3.0) * 1e-3   # ellipsoid of semi-axes 2k, 1.5k, k of that volume: 3 k^3 = (1.5 mm)^3
SHAPES = {"cube": (f"cube {A}", A * 3.0 ** 0.5 / 2.0),           # shape command, bounding radius
          "cylinder": (f"cylinder {RC} {2.0 * RC}", RC * 2.0 ** 0.5),
          "ellipsoid": (f"ellipsoid {2.0 * KE} {1.5 * KE} {KE}", 2.0 * KE)}


def styles(kind):
    if kind != "sphere":
        return "pair_style convex/gjk", "fix integ all nve/shape"
    return "pair_style sphere", "fix integ all nve/sphere"


def setup(kind, n, pair=None, wall=""):
    """The input of the unsettled bed: random bounding spheres (the same positions for cubes and spheres:
    the spheres are made with the cubes' bounding radius, then shrunk to the volume of a cube), gravity, a
    floor. `pair` replaces the style's pair_style line, `wall` is appended to the floor's fix (e.g.
    "point multipoint"): benchmarks/polyhedron_settled_bed.py settles the same bed with polyhedron/multipoint."""
    import math
    rb = SHAPES["cube" if kind == "sphere" else kind][1]
    rs = A * (3.0 / (4.0 * math.pi)) ** (1.0 / 3.0)        # sphere of the cube's volume
    L = 17.5 * A * (n / 1000.0) ** (1.0 / 3.0)
    H = n * 4.0 / 3.0 * math.pi * rb ** 3 / (0.2 * L * L)   # bounding spheres at 20 % volume fraction
    if kind != "sphere":
        make = f"create_atoms 1 random {n} 4821 fill shape c density 2500 quat random"
    else:
        make = f"create_atoms 1 random {n} 4821 fill radius {rb} density 2500\n        set group all radius {rs}"
    default_pair, integ = styles(kind)
    pair = pair or default_pair
    return f"""
        boundary p p f
        region box block 0 {L} 0 {L} 0 {H + 2 * A}
        create_box 1 box
        shape c {SHAPES.get(kind, SHAPES["cube"])[0]}
        region fill block 0 {L} 0 {L} {A} {H + A}
        {make}
        {pair}
        pair_coeff * * {LAW}
        {integ}
        fix g all gravity 9.81 vector 0 0 -1
        fix floor all wall/plane zplane 0 NULL {LAW} {wall}
        timestep 2e-6
        thermo 0
    """


def build(kind, n, settle, path):
    """The bed of `setup`, settled under gravity for `settle` steps, written to the restart `path`."""
    sim = dem.Simulation(screen=False)
    sim.commands(setup(kind, n) + f"""
        run {settle}
        write_restart {path}
    """)
    return sim.atom.natoms


def timed(kind, path, steps):
    pair, integ = styles(kind)
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        shape c {SHAPES.get(kind, SHAPES["cube"])[0]}
        read_restart {path}
        {pair}
        pair_coeff * * {LAW}
        {integ}
        fix g all gravity 9.81 vector 0 0 -1
        fix floor all wall/plane zplane 0 NULL {LAW}
        thermo 0
    """)
    sim.run(steps)
    up = sim.update
    loop = sum(up.timers.values())
    n = sim.atom.natoms
    extra = {}
    if kind != "sphere":
        p = sim.pair
        extra = {"gjk": p.ngjk / steps, "pretest": p.nsep / steps, "skip": p.nskip / steps}
    return {"loop": loop / (n * steps), "pair": up.timers["pair"] / (n * steps),
            "integrate": up.timers["integrate"] / (n * steps), "contacts": sim.pair.ncontacts,
            "ke": sim.thermo_keyword("ke"), **extra}


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--shape", choices=sorted(SHAPES), default="cube")
    p.add_argument("--N", type=int, default=1000)
    p.add_argument("--steps", type=int, default=5000)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--settle", type=int, default=150000)
    p.add_argument("--dir", default=None, help="folder of the settled beds (default: a temporary one)")
    a = p.parse_args(argv)
    folder = a.dir or tempfile.mkdtemp(prefix="cube_bed_")
    os.makedirs(folder, exist_ok=True)
    paths = {}
    for kind in (a.shape, "sphere"):
        paths[kind] = os.path.join(folder, f"{kind}_{a.N}_{a.settle}.restart")
        if not os.path.exists(paths[kind]):
            print(f"settling the {kind} bed ({a.settle} steps)...", flush=True)
            build(kind, a.N, a.settle, paths[kind])
    ratios, pair_ratios = [], []
    for r in range(a.repeats):
        c = timed(a.shape, paths[a.shape], a.steps)
        s = timed("sphere", paths["sphere"], a.steps)
        ratios.append(c["loop"] / s["loop"])
        pair_ratios.append(c["pair"] / s["pair"])
        print(f"run {r + 1}: {a.shape}s {c['loop'] * 1e6:.3f} us/particle-step (pair {c['pair'] * 1e6:.3f}, "
              f"integrate {c['integrate'] * 1e6:.3f}; {c['contacts']} contacts, {c['gjk']:.0f} GJK calls, "
              f"{c['pretest']:.0f} pre-test rejections and {c['skip']:.0f} pairs skipped on their margin "
              f"per step), spheres {s['loop'] * 1e6:.3f} "
              f"(pair {s['pair'] * 1e6:.3f}, integrate {s['integrate'] * 1e6:.3f}; {s['contacts']} "
              f"contacts): ratio {ratios[-1]:.2f} (pair {pair_ratios[-1]:.2f})", flush=True)
    print(f"{a.shape} bed / sphere bed, cost per particle-step: {statistics.median(ratios):.2f}x "
          f"(pair stage alone {statistics.median(pair_ratios):.2f}x), N = {a.N}, median of {a.repeats}")


if __name__ == "__main__":
    sys.exit(main())
