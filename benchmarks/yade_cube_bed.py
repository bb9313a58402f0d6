"""Yade's Polyhedra on the settled cube bed of benchmarks/polyhedron_settled_bed.py, one thread.

    yade -n -j 1 -x benchmarks/yade_cube_bed.py [--packing benchmarks/cube_bed_packing.txt] [--steps 20]
                                                [--warmup 10] [--repeats 3] [--damping 0.2]

(Debian's `yade` package, 2023.02a: `apt-get install yade`; -n: no GUI, -j 1: one thread, -x: exit at
the end.) The packing file holds the box and one cube a line (centre, quaternion w x y z); each cube
becomes a Polyhedra body from its 8 world-frame corners (`utils.polyhedron`), density 2500, in a periodic
cell of the file's box width in x and y (Yade's Polyhedra functors take the cell's shift: the bed is
bi-periodic as dem's; the cell is periodic in z too, three bed heights tall), on a fixed `Wall` at z = 0
(its infinite bound needs the collider's allowBiggerThanPeriod), under gravity 9.81, dt = 2e-6 s, all
bodies at rest at the start. Setup and caveats: benchmarks/README.md.

The law is Yade's own, Law2_PolyhedraGeom_PolyhedraPhys_Volumetric: F_n = k_n V (V the overlap volume,
volumePower 1), a tangential spring k_s with Coulomb's cap, no viscous damping (NewtonIntegrator's
non-viscous damping --damping instead). Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys makes k_n = Y / 2 and
k_s = Y P / 2 of two equal materials. Y is chosen so that a face/face contact of two cubes (V = a^2 delta)
has dem's linear stiffness kn = 1e5 N/m: k_n = kn / a^2, Y = 2 kn / a^2 = 3.42e10 (N/m^3); P so that k_s
is dem's ks = 28571 N/m: P = ks / k_n; friction angle atan(0.55). (Edge and corner contacts are softer
than dem's: their overlap volume grows as delta^2 or delta^3.)

Timing: --warmup steps, then --repeats runs of --steps steps, timed with the wall clock and the process
CPU time around O.run(steps, True); particle-steps/s, loop time per particle-step and per contact-step,
contacts (cube/cube and cube/floor interactions with a positive overlap volume and depth) at the end of
each run, and the failed intersections (Yade's CGAL intersection of two near-parallel faces fails: a
warning, silenced unless --warnings, and an interaction with the volume of a whole cube and zero depth,
which the law treats as no force; their cubes then sink into each other). A Yade step costs about 1 ms
per cube here: keep --steps small.
"""
import argparse
import math
import statistics
import sys
import time

from yade import O, log, utils
from yade.wrapper import (ForceResetter, InsertionSortCollider, Bo1_Polyhedra_Aabb, Bo1_Wall_Aabb,
                          InteractionLoop, Ig2_Polyhedra_Polyhedra_PolyhedraGeom,
                          Ig2_Wall_Polyhedra_PolyhedraGeom,
                          Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys, Law2_PolyhedraGeom_PolyhedraPhys_Volumetric,
                          NewtonIntegrator, PolyhedraMat)
from yade.minieigenHP import Matrix3, Vector3

KN = 1e5          # dem's normal stiffness (N/m), benchmarks/cube_bed.py LAW
KS = 28571.0      # dem's tangential spring (N/m)
MU = 0.55
DENSITY = 2500.0


def read_packing(path):
    edge = box = None
    rows = []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "#":
                if len(w) > 2 and w[1] == "edge":
                    edge = float(w[2])
                elif len(w) > 2 and w[1] == "box":
                    box = [float(v) for v in w[2:8]]
                continue
            rows.append([float(v) for v in w])
    return edge, box, rows


def corners(row, a):
    x, y, z, qw, qx, qy, qz = row
    n = math.sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
    qw, qx, qy, qz = qw / n, qx / n, qy / n, qz / n
    r = ((1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qw * qz), 2 * (qx * qz + qw * qy)),
         (2 * (qx * qy + qw * qz), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qw * qx)),
         (2 * (qx * qz - qw * qy), 2 * (qy * qz + qw * qx), 1 - 2 * (qx * qx + qy * qy)))
    h = a / 2
    out = []
    for sx in (-h, h):
        for sy in (-h, h):
            for sz in (-h, h):
                out.append(Vector3(x + r[0][0] * sx + r[0][1] * sy + r[0][2] * sz,
                                   y + r[1][0] * sx + r[1][1] * sy + r[1][2] * sz,
                                   z + r[2][0] * sx + r[2][1] * sy + r[2][2] * sz))
    return out


def contacts(nfloor):
    """Cube/cube and cube/floor interactions with a positive overlap volume and depth, the largest overlap
    volume, and the failed ones (a positive volume, zero depth: the law applies no force)."""
    pairs = wall = failed = 0
    vmax = 0.0
    for i in O.interactions:
        if not i.isReal or not (i.geom.penetrationVolume > 0):
            continue
        if not i.geom.equivalentPenetrationDepth > 0:
            failed += 1     # CGAL's intersection failed: the volume of a whole cube, depth 0, no force
            continue
        vmax = max(vmax, i.geom.penetrationVolume)
        if min(i.id1, i.id2) < nfloor:
            wall += 1
        else:
            pairs += 1
    return pairs, wall, vmax, failed


def main(argv):
    ap = argparse.ArgumentParser(prog="yade -n -j 1 -x benchmarks/yade_cube_bed.py")
    ap.add_argument("--packing", default="benchmarks/cube_bed_packing.txt")
    ap.add_argument("--steps", type=int, default=20)
    ap.add_argument("--warmup", type=int, default=10)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--damping", type=float, default=0.2)
    ap.add_argument("--dt", type=float, default=2e-6)
    ap.add_argument("--warnings", action="store_true",
                    help="show the warnings of Yade's polyhedron intersection (Polyhedra_support.cpp; silenced by "
                         "default: hundreds a step in this bed, their output would be timed too)")
    ap.add_argument("--verlet", type=float, default=0.1,
                    help="InsertionSortCollider.verletDist, per unit of the edge (dem's skin: 0.17 edge)")
    a = ap.parse_args(argv)
    if a.steps < 1 or a.warmup < 1:
        raise SystemExit("--steps and --warmup must be >= 1 (Yade's O.run(0) runs for ever)")
    if not a.warnings:
        log.setLevel("Polyhedra_support.cpp", log.ERROR)
    edge, box, rows = read_packing(a.packing)
    kn_vol = KN / edge ** 2                 # N/m^3: k_n V = KN delta for a face/face contact
    mat = PolyhedraMat(density=DENSITY, young=2 * kn_vol, poisson=KS / kn_vol, frictionAngle=math.atan(MU))
    O.materials.append(mat)
    lx, ly = box[1] - box[0], box[3] - box[2]
    top = max(r[2] for r in rows) + edge
    O.periodic = True
    O.cell.hSize = Matrix3(lx, 0, 0, 0, ly, 0, 0, 0, 3 * top)   # Yade's cell is periodic in z too: room above
    # the floor: Yade's Wall (a plane, Ig2_Wall_Polyhedra_PolyhedraGeom); its bound is infinite along x and
    # y, which the periodic collider accepts with allowBiggerThanPeriod (meant for such floors). A fixed
    # Polyhedra slab instead meets the cubes lying flat on it face to face, exactly the degenerate case in
    # which Yade's CGAL intersection fails (warnings, the whole cube's volume taken as the overlap).
    O.bodies.append(utils.wall(0.0, axis=2, sense=1, material=mat))
    nfloor = len(O.bodies)
    for r in rows:
        O.bodies.append(utils.polyhedron(corners(r, edge), material=mat))
    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Polyhedra_Aabb(), Bo1_Wall_Aabb()], verletDist=a.verlet * edge,
                              allowBiggerThanPeriod=True),
        InteractionLoop([Ig2_Polyhedra_Polyhedra_PolyhedraGeom(), Ig2_Wall_Polyhedra_PolyhedraGeom()],
                        [Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys()],
                        [Law2_PolyhedraGeom_PolyhedraPhys_Volumetric()]),
        NewtonIntegrator(damping=a.damping, gravity=(0, 0, -9.81)),
    ]
    O.dt = a.dt
    n = len(rows)
    print(f"Yade {O.numThreads} thread(s): {n} cubes of edge {edge} m, cell {lx:.6g} x {ly:.6g} (periodic), "
          f"Y = {2 * kn_vol:.4g}, P = {KS / kn_vol:.4g}, damping {a.damping}, dt {a.dt}", flush=True)
    t = time.perf_counter()
    O.run(a.warmup, True)
    pc, wc, vmax, bad = contacts(nfloor)
    print(f"warm-up {a.warmup} steps: {time.perf_counter() - t:.2f} s, contacts {pc} cube/cube, {wc} cube/floor, "
          f"largest overlap volume {vmax / edge ** 3:.3g} a^3, {bad} failed intersections", flush=True)
    res, cpus = [], []
    for k in range(a.repeats):
        t, c = time.perf_counter(), time.process_time()
        O.run(a.steps, True)
        dt, cpu = time.perf_counter() - t, time.process_time() - c
        cpus.append(cpu / (n * a.steps))
        pc, wc, vmax, bad = contacts(nfloor)
        ps = dt / (n * a.steps)
        res.append(ps)
        zmax = max(b.state.pos[2] for b in O.bodies if b.dynamic)
        umax = max(b.state.vel.norm() for b in O.bodies if b.dynamic)
        print(f"run {k + 1}: {a.steps} steps in {dt:.2f} s: {ps * 1e6:.1f} us/particle-step, {1 / ps:.0f} "
              f"particle-steps/s (CPU {cpu / (n * a.steps) * 1e6:.1f} us), contacts {pc} cube/cube + {wc} cube/floor, "
              f"{dt / ((pc + wc) * a.steps) * 1e6:.1f} us/contact-step (max speed {umax:.3g} m/s, top {zmax:.4g} m, "
              f"largest overlap volume {vmax / edge ** 3:.3g} a^3, {bad} failed intersections)",
              flush=True)
    med = statistics.median(res)
    cpu = statistics.median(cpus)
    print(f"Yade Polyhedra, median of {a.repeats}: {med * 1e6:.1f} us/particle-step, {1 / med:.0f} particle-steps/s "
          f"(CPU time {cpu * 1e6:.1f} us, {1 / cpu:.0f} /s), "
          f"contacts {pc} + {wc} (floor), {med * n / (pc + wc) * 1e6:.1f} us/contact-step")


main(sys.argv[1:])
