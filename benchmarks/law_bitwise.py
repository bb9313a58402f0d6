"""Do two builds give the same trajectories? Runs small beds of every geometry and law with the installed
dem and saves each particle's final state (x, v, omega, quat, f, torque, by id); `compare` says whether two
saves are bitwise equal. Used when the contact law's code moves (the law in parts): save with the old build,
save with the new one, compare.

    python benchmarks/law_bitwise.py save DIR [--cases sphere cube ...]
    python benchmarks/law_bitwise.py compare DIR_OLD DIR_NEW

Each case builds its bed (insertion or random placement), lets it fall and collide, and stops after its
steps (the last 2000 with a dense bed: sphere bed of ../shared/bench/sphere-bed, settled cubes, crosses and
polyhedra)."""
import argparse
import os
import sys

import numpy as np

import dem

HERE = os.path.dirname(os.path.abspath(__file__))
SPHERE_DATA = os.path.join(HERE, "..", "..", "shared", "bench", "sphere-bed", "bed_8000.data")
FIELDS = ("x", "v", "omega", "quat", "f", "torque")
HOOKE = "kn 1e5 en 0.5 mu 0.5 gamma_t 2000 ks 28571"
SPHERE_BED = f"""
    units si
    boundary f f fm
    read_data {SPHERE_DATA}
    pair_style sphere
    pair_coeff * * {{law}}
    fix 1 all nve/sphere
    fix 2 all gravity 9.81 vector 0 0 -1
    fix walls all wall/plane xplane 0 $(xhi) yplane 0 $(yhi) zplane 0 NULL
    neighbor 0.0001 bin
    timestep 1.646e-6
    thermo 0
"""
SHAPED_BED = """
    boundary p p f
    region box block 0 0.024 0 0.024 0 0.08
    create_box 1 box
    shape c {shape}
    region fill block 0 0.024 0 0.024 0.003 0.077
    create_atoms 1 random {n} 4821 fill shape c density 2500 quat random
    pair_style {pair}
    pair_coeff * * {law}
    fix integ all nve/shape
    fix g all gravity 98.1 vector 0 0 -1
    fix floor all wall/plane zplane 0 NULL {wall}
    neighbor 0.0003 bin
    timestep 2e-6
    thermo 0
"""
DRUM = """
    boundary f p f
    region box block -0.021 0.021 0 0.02 -0.021 0.021
    create_box 1 box
    shape c cube 0.0025
    region fill cylinder y 0 0 0.017 0 0.02
    create_atoms 1 random 90 4821 fill shape c density 2500 quat random
    pair_style convex/gjk
    pair_coeff * * {law}
    fix integ all nve/shape
    fix g all gravity 98.1 vector 0 0 -1
    fix drum all wall/drum y 0 0 0.02 rpm 40
    neighbor 0.0003 bin
    timestep 2e-6
    thermo 0
"""
HOPPER = os.path.join(HERE, "..", "inputs", "meshes", "hopper.stl")
MESH = f"""
    boundary f f f
    region box block -0.055 0.055 -0.055 0.055 -0.06 0.17
    create_box 1 box
    pair_style sphere
    pair_coeff * * {{law}}
    fix integ all nve/sphere
    fix g all gravity 98.1 vector 0 0 -1
    fix hopper all wall/mesh file {HOPPER}
    fix plug all wall/plane zplane 0 NULL
    region feed cylinder z 0 0 0.045 0.07 0.16
    create_atoms 1 random 1000 4821 feed radius 0.003 density 2500
    neighbor 0.0005 bin
    timestep 5e-6
    thermo 0
"""
POLY_BOX = os.path.join(HERE, "..", "inputs", "in.polyhedra_box")
CASES = {
    # name: (input, steps)
    "sphere": (SPHERE_BED.format(law="kn 1000 en 0.5 mu 0.5 gamma_t 4210.85 ks 285.714 mu_roll 0.05"), 2000),
    "sphere_hertz": (SPHERE_BED.format(law="model hertz E 5e6 nu 0.3 en 0.5 mu 0.5 mu_roll 0.1"), 2000),
    "cube": (SHAPED_BED.format(shape="cube 0.002418", n=200, pair="convex/gjk", law=HOOKE, wall=""), 30000),
    "cube_hertz": (SHAPED_BED.format(shape="cube 0.002418", n=200, pair="convex/gjk",
                                     law="model hertz E 1e8 nu 0.3 en 0.5 mu 0.5", wall=""), 30000),
    "glued": (SHAPED_BED.format(shape="cross3d 0.003", n=150, pair="glued/convex", law=HOOKE, wall=""), 30000),
    "glued_a": (SHAPED_BED.format(shape="cross3d 0.003", n=150, pair="glued/convex model A", law=HOOKE,
                                  wall=""), 30000),
    "drum": (DRUM.format(law=HOOKE), 30000),
    "mesh": (MESH.format(law="kn 5000 en 0.5 mu 0.5 ks 1429 mu_roll 0.05"), 20000),
    "mesh_hertz": (MESH.format(law="model hertz E 1e7 nu 0.3 en 0.5 mu 0.5"), 20000),
    "polyhedra": (f"variable N index 20\nvariable settle index 0.12\nvariable law index grains3d\n"
                  f"variable out index /tmp/law_bitwise_poly\ninclude {POLY_BOX}", None),
    "polyhedra_descantes": (f"variable N index 20\nvariable settle index 0.12\nvariable law index descantes\n"
                            f"variable out index /tmp/law_bitwise_poly\ninclude {POLY_BOX}", None),
}


def state(sim):
    out = {}
    for name in ("tag",) + FIELDS:
        out[name] = sim.gather(name)
    return out


def save(folder, cases):
    os.makedirs(folder, exist_ok=True)
    for name in cases:
        text, steps = CASES[name]
        sim = dem.Simulation(screen=False, log=None)
        sim.commands(text)
        if steps:
            sim.run(steps)
        np.savez(os.path.join(folder, name + ".npz"), **state(sim))
        print(f"{name}: {sim.atom.natoms} particles, step {sim.update.ntimestep}, {sim.pair.ncontacts} contacts", flush=True)


def compare(a, b):
    same = True
    for name in sorted(os.listdir(a)):
        if not name.endswith(".npz") or not os.path.exists(os.path.join(b, name)):
            continue
        x, y = np.load(os.path.join(a, name)), np.load(os.path.join(b, name))
        bad = [f for f in ("tag",) + FIELDS if x[f].shape != y[f].shape or
               not np.array_equal(x[f].view(np.uint8), y[f].view(np.uint8))]
        worst = max((float(np.max(np.abs(x[f] - y[f]))) for f in bad if x[f].shape == y[f].shape), default=0.0)
        print(f"{name[:-4]}: {len(x['tag'])} particles, " +
              ("bitwise identical" if not bad else f"DIFFER in {', '.join(bad)} (largest {worst:.3g})"))
        same = same and not bad
    return same


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = p.add_subparsers(dest="what", required=True)
    s = sub.add_parser("save")
    s.add_argument("dir")
    s.add_argument("--cases", nargs="+", choices=sorted(CASES), default=sorted(CASES))
    c = sub.add_parser("compare")
    c.add_argument("old")
    c.add_argument("new")
    a = p.parse_args(argv)
    if a.what == "save":
        save(a.dir, a.cases)
        return 0
    return 0 if compare(a.old, a.new) else 1


if __name__ == "__main__":
    sys.exit(main())
