"""The cost of a mesh wall: a settled bed of spheres in an open box whose floor and four sides are planes
(`fix wall/plane`) or triangle meshes of 160 to 10^5 triangles (`fix wall/mesh`), one core.

    python benchmarks/mesh_wall.py [--N 4000] [--cuts 2 32 100] [--steps 1000] [--warmup 100] [--repeats 3]

The bed: N spheres of diameter 2 mm (density 2500, kn = 2000 N/m, en = 0.5, mu = 0.5, ks = 571.4 N/m, the
law of inputs/in.pour), poured into a box 40 x 40 mm (planes) and settled for 60,000 steps (dt 3e-6 s), once;
its restart is reused by every run. The meshes: the same box (floor and four sides, 60 mm tall), each face
cut into c x c squares of 2 triangles: 10 c^2 triangles (c = 4: 160, 32: 10,240, 100: 100,000), written as
ASCII STL in a temporary folder. A run reads the restart, defines the walls, runs --warmup steps, then
--steps steps; the runs go in turn (planes, mesh c1, mesh c2, ..., again), --repeats times. Figures: the
loop time per particle-step (wall clock), the time of the fixes (the `Modify` timer: gravity, integration
and the walls) per step, the wall contacts, the mesh index (cells, entries) and its build time (in
`init`); medians over the repeats, and the paired ratio of each mesh to the planes.
"""
import argparse
import os
import statistics
import sys
import tempfile
import time

import numpy as np

import dem

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "plugins"))
from dem_walls.mesh import weld  # noqa: E402

L, H = 0.04, 0.06
LAW = "kn 2000 en 0.5 mu 0.5 gamma_t 0 ks 571.4"
PLANES = f"fix walls all wall/plane xplane 0 {L} yplane 0 {L} zplane 0 NULL"


def settings(walls):
    return f"""
pair_style      sphere
pair_coeff      * * {LAW}
fix             integrate all nve/sphere
fix             gravity all gravity 9.81 vector 0 0 -1
{walls}
timestep        3e-6
neighbor        0.0002 bin
thermo          0
"""


def settle(n, path):
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
units           si
boundary        f f fm
region          box block 0 {L} 0 {L} 0 0.16
create_box      1 box
region          fill block 0 {L} 0 {L} 0.0 0.1
create_atoms    1 random {n} 12345 fill radius 0.001 density 2500
""" + settings(PLANES) + f"""
run             60000
write_restart   {path}
""")


def box_mesh(path, cuts):
    """Floor and four sides of the box [0, L]^2 x [0, H], each face cut into cuts x cuts squares."""
    s = np.linspace(0.0, 1.0, cuts + 1)
    a, b = np.meshgrid(s[:-1], s[:-1], indexing="ij")
    a, b = a.ravel(), b.ravel()
    h = 1.0 / cuts
    corners = [(a, b), (a + h, b), (a + h, b + h), (a, b + h)]
    tris = []
    for axis, value in ((2, 0.0), (0, 0.0), (0, L), (1, 0.0), (1, L)):
        u, v = [d for d in range(3) if d != axis]
        size = np.array([L, L, H])
        quad = []
        for ca, cb in corners:
            p = np.zeros((len(a), 3))
            p[:, axis] = value
            p[:, u] = ca * size[u]
            p[:, v] = cb * size[v]
            quad.append(p)
        tris.append(np.stack([quad[0], quad[1], quad[2]], axis=1))
        tris.append(np.stack([quad[0], quad[2], quad[3]], axis=1))
    mesh = weld(np.concatenate(tris))
    mesh.write_stl(path, binary=False)
    return len(mesh.triangles)


def timed(restart, walls, steps, warmup):
    sim = dem.Simulation(screen=False)
    sim.commands(f"read_restart {restart}\n" + settings(walls))
    t0 = time.perf_counter()
    sim.run(warmup)
    setup = time.perf_counter() - t0
    sim.run(steps)
    timers = sim.update.timers
    loop = sum(timers.values())
    fix = sim.modify.find("walls")
    index = getattr(fix, "index", None)
    return {"us": loop / steps / sim.atom.natoms * 1e6, "modify_ms": timers["modify"] / steps * 1e3,
            "contacts": fix.ncontacts, "setup_s": setup,
            "cells": index.cells if index is not None else 0, "entries": index.entries if index is not None else 0}


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--N", type=int, default=4000)
    p.add_argument("--cuts", type=int, nargs="+", default=[4, 32, 100])
    p.add_argument("--steps", type=int, default=1000)
    p.add_argument("--warmup", type=int, default=100)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--dir", default=os.path.join(tempfile.gettempdir(), "dem_mesh_wall_bench"))
    a = p.parse_args(argv)
    os.makedirs(a.dir, exist_ok=True)
    restart = os.path.join(a.dir, f"bed_{a.N}.restart")
    if not os.path.exists(restart):
        settle(a.N, restart)
    variants = {"planes": PLANES}
    ntri = {"planes": 0}
    for c in a.cuts:
        path = os.path.join(a.dir, f"box_{c}.stl")
        ntri[f"mesh {c}"] = box_mesh(path, c)
        variants[f"mesh {c}"] = f"fix walls all wall/mesh file {path}"
    results = {k: [] for k in variants}
    for _ in range(a.repeats):
        for name, walls in variants.items():
            results[name].append(timed(restart, walls, a.steps, a.warmup))
    base = [r["us"] for r in results["planes"]]
    print(f"| walls | triangles | us / particle-step | fixes ms / step | wall contacts | ratio to planes | "
          f"cells | entries | setup + {a.warmup} steps (s) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, rows in results.items():
        med = {k: statistics.median(r[k] for r in rows) for k in rows[0]}
        ratio = statistics.median(r["us"] / b for r, b in zip(rows, base))
        print(f"| {name} | {ntri[name]:,} | {med['us']:.3f} | {med['modify_ms']:.3f} | {int(med['contacts'])} | "
              f"{ratio:.2f} | {int(med['cells']):,} | {int(med['entries']):,} | {med['setup_s']:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
