"""Cost of glued composites: a settled bed of 3D crosses (pair_style glued/convex) against a bed of as many
convex cylinders of equal volume (pair_style convex/gjk), one core. Grains3D reports composites at 5-10x
convex particles (Part III sec 2.5); the goal here is <= 3x.

    python benchmarks/glued_bed.py [--nx 7] [--nz 12] [--steps 2000] [--repeats 3] [--settle 8000]

Both beds: nx * nx * nz particles (default 588) on a simple cubic lattice of spacing 1.014 bounding
diameters, turned at random, in a box periodic in x and y with a floor, density 2500, kn = 2000 N/m,
en = 0.3, mu = 0.5, gamma_t = 2000 1/s, ks = 2/7 kn, dt = 4e-6 s, under a tenfold gravity (98.1 m/s2) for
--settle steps (the crosses' kinetic energy falls 1000-fold by 8000 steps), written to a restart once.
Crosses: beams 2 x 0.5 x 0.5 mm (volume 1.25e-9 m3); cylinders: D = L of the same volume. The settled
beds are then timed for --steps steps from the restart, alternating cross and cylinder runs; the figures
are the medians of the paired ratios of the loop time and of the pair stage per particle-step, and the
pair stage per GJK query. The composite's broad-phase statistics per step are reported: component pairs of
the listed particle pairs whose bounding spheres overlap, those of them in the piece candidates (within the
skin when the candidates were built), those not proven apart since (tested by the components' spheres),
those left by their boxes (each one GJK query), and the contact points found.
"""
import argparse
import math
import os
import statistics
import tempfile

import dem

BEAM = 0.002
VOLUME = 3 * BEAM * (BEAM / 4) ** 2 - 2 * (BEAM / 4) ** 3      # the cross3d of aspect 4
RC = (VOLUME / (2 * math.pi)) ** (1.0 / 3.0)                   # D = L cylinder of that volume
SHAPES = {"cross": (f"cross3d {BEAM}", "glued/convex", math.sqrt(BEAM ** 2 / 4 + BEAM ** 2 / 32)),
          "cylinder": (f"cylinder {RC} {2 * RC}", "convex/gjk", RC * math.sqrt(2.0))}
LAW = "kn 2000 en 0.3 mu 0.5 gamma_t 2000 ks 571"
SETTINGS = """pair_style      {pair}
pair_coeff      * * {law}
fix             integrate all nve/shape
fix             gravity all gravity 98.1 vector 0 0 -1
fix             floor all wall/plane zplane 0 NULL
neighbor        {skin} bin
thermo          0
"""


def build(kind, nx, nz, settle, path):
    shape, pair, rb = SHAPES[kind]
    a = 2.028 * rb                       # lattice spacing: bounding spheres 1.4 % apart
    L = nx * a
    sim = dem.Simulation(screen=False)
    sim.commands(f"""units si
boundary        p p f
region          box block 0 {L} 0 {L} 0 {2 * nz * a}
create_box      1 box
shape           x {shape}
region          fill block 0 {L} 0 {L} 0 {nz * a}
create_atoms    1 lattice fill sc {a} shape x quat random density 2500
timestep        4e-6
""" + SETTINGS.format(pair=pair, law=LAW, skin=0.1 * rb))
    sim.run(settle)
    sim.command(f"write_restart {path}")
    return sim.atom.natoms


def timed(kind, path, steps):
    shape, pair, rb = SHAPES[kind]
    sim = dem.Simulation(screen=False)
    sim.commands(f"shape x {shape}\nread_restart {path}\n" + SETTINGS.format(pair=pair, law=LAW, skin=0.1 * rb))
    sim.run(10)                                         # setup outside the timing
    if kind == "cross":
        sim.pair.stats.update(dict.fromkeys(sim.pair.stats, 0.0))
    sim.run(steps)
    t = sim.update.timers
    loop = sum(t.values())
    out = {"loop": loop, "pair": t["pair"], "n": sim.atom.natoms, "contacts": sim.pair.ncontacts}
    if kind == "cross":
        out.update({k: v / steps for k, v in sim.pair.stats.items() if k != "contacts"})
    else:
        out["gjk"] = (sim.pair.ngjk) / (steps + 10)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--nx", type=int, default=7)
    ap.add_argument("--nz", type=int, default=12)
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--settle", type=int, default=8000)
    ap.add_argument("--dir", default=os.path.join(tempfile.gettempdir(), "dem_glued_bed"))
    args = ap.parse_args()
    os.makedirs(args.dir, exist_ok=True)
    os.environ.setdefault("DEM_SHAPE_DB", os.path.join(args.dir, "shapes.h5"))
    paths = {}
    for kind in SHAPES:
        paths[kind] = os.path.join(args.dir, f"{kind}_{args.nx}_{args.nz}_{args.settle}.restart")
        if not os.path.exists(paths[kind]):
            print(f"settling {kind} bed ...", flush=True)
            build(kind, args.nx, args.nz, args.settle, paths[kind])
    ratios, pratios, rows = [], [], []
    for r in range(args.repeats):
        c = timed("cross", paths["cross"], args.steps)
        y = timed("cylinder", paths["cylinder"], args.steps)
        ratios.append(c["loop"] / y["loop"])
        pratios.append(c["pair"] / y["pair"])
        rows.append((c, y))
        print(f"run {r}: crosses loop {c['loop']:.3f} s (pair {c['pair']:.3f}), cylinders loop {y['loop']:.3f} s "
              f"(pair {y['pair']:.3f}): {ratios[-1]:.2f}x (pair {pratios[-1]:.2f}x)", flush=True)
    c, y = rows[-1]
    ps = args.steps * c["n"]
    print(f"\n{c['n']} particles, {args.steps} steps; contacts at the end: crosses {c['contacts']}, "
          f"cylinders {y['contacts']}")
    print(f"loop per particle-step: crosses {1e6 * c['loop'] / ps:.2f} us, cylinders {1e6 * y['loop'] / ps:.2f} us")
    print(f"pair per GJK query: crosses {1e9 * c['pair'] / (c['gjk'] * args.steps):.0f} ns, "
          f"cylinders {1e9 * y['pair'] / (y['gjk'] * args.steps):.0f} ns")
    print(f"crosses per step: component pairs {c['piece_pairs']:.0f}, listed (piece candidates) "
          f"{c['piece_listed']:.0f}, not proven apart since {c['piece_spheres']:.0f} (sphere-tested), after boxes "
          f"(GJK) {c['piece_candidates']:.0f}, contact points {c['points']:.0f}, candidate builds "
          f"{c['piece_builds'] * args.steps:.0f} in {args.steps} steps; cylinders: GJK {y['gjk']:.0f}")
    print(f"median ratio crosses / cylinders: loop {statistics.median(ratios):.2f}x, pair "
          f"{statistics.median(pratios):.2f}x")


if __name__ == "__main__":
    main()
