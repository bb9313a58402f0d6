"""Time per contact query: dem's crust contact (GJK on cores, EPA when deeper) vs Coal's collide on the
same geometry (Coal shapes = our cores with a swept-sphere radius equal to the crust, so both libraries
solve the same problem), for cube-cube, cylinder-cylinder and 20-vertex polyhedra.

    python benchmarks/gjk_vs_coal.py [--pairs 2000] [--rounds 11]

Our side is timed from the Cython batch loop ``dem.contact._gjk.contact_batch`` (nogil, one call for all pairs):
that is the path a pair style takes. Coal has no batch API in Python, so its side is a Python loop over
``coal.ComputeCollision`` functors with prebuilt transforms; its per-call Python overhead is measured on
a trivial query (two far-apart spheres, answered in closed form) and reported so it can be taken off.
Runs alternate (ours, Coal, Coal, ours, ...) and the median of the per-round ratios is printed.
"""
import argparse
import time

import numpy as np

from dem.contact import _gjk
from dem.contact import geometry as G
from dem.shapes import Cylinder, Polyhedron, ShapeTable, cube
from dem.shapes.polyhedron import hull_mesh

try:
    import coal
except ImportError:           # pragma: no cover
    raise SystemExit("pip install coal")


def coal_rounded(s):
    p = s.core_params
    if s.name == "cube":
        g, off = coal.Box(*(2 * p[:3])), 0.0
    elif s.name == "cylinder":
        g, off = coal.Cylinder(p[0], 2 * p[1]), 0.0
    else:
        V, F, _ = hull_mesh(s.core_vertices)
        pts = coal.StdVec_Vec3s()
        for v in V:
            pts.append(np.asarray(v, float))
        tris = coal.StdVec_Triangle()
        for f in F:
            tris.append(coal.Triangle(int(f[0]), int(f[1]), int(f[2])))
        g, off = coal.Convex(pts, tris), 0.0
    g.setSweptSphereRadius(s.crust)
    return g, off


def make_pairs(rng, shapes, npairs, depth_in_crusts):
    """Pairs of posed particles overlapping by depth_in_crusts * (crust_a + crust_b) along a random line."""
    ns = len(shapes)
    shape = np.empty(2 * npairs, np.int32)
    x = np.empty((2 * npairs, 3))
    quat = np.empty((2 * npairs, 4))
    for k in range(npairs):
        i, j = 2 * k, 2 * k + 1
        shape[i], shape[j] = rng.integers(ns), rng.integers(ns)
        A, B = shapes[shape[i]], shapes[shape[j]]
        qa, qb = rng.normal(size=4), rng.normal(size=4)
        qa /= np.linalg.norm(qa)
        qb /= np.linalg.norm(qb)
        u = rng.normal(size=3)
        u /= np.linalg.norm(u)
        lo, hi = 0.0, A.bounding_radius + B.bounding_radius
        for _ in range(50):
            m = 0.5 * (lo + hi)
            if G.distance(A, np.zeros(3), qa, B, u * m, qb)[0] > 0:
                hi = m
            else:
                lo = m
        x[i], x[j] = 0.0, u * (hi - depth_in_crusts * (A.crust + B.crust))
        quat[i], quat[j] = qa, qb
    pi = np.arange(0, 2 * npairs, 2, dtype=np.int32)
    return shape, x, quat, pi, pi + 1


def time_ours(table, shape, x, quat, pi, pj, reps, tol):
    m = len(pi)
    guess = np.zeros((m, 3))
    code, ov, n, p = np.zeros(m, np.int32), np.zeros(m), np.zeros((m, 3)), np.zeros((m, 3))
    t0 = time.perf_counter()
    for _ in range(reps):
        guess[:] = 0.0                      # cold start, as Coal
        _gjk.contact_batch(table.view(), shape, x, quat, pi, pj, tol, guess, code, ov, n, p)
    return (time.perf_counter() - t0) / (reps * m), code


def coal_setup(shapes, shape, x, quat, pi, pj):
    """Functors and transforms per pair; the geometries are returned too: the functors keep raw pointers."""
    geoms = [coal_rounded(s) for s in shapes]
    calls = []
    for i, j in zip(pi, pj):
        (ga, oa), (gb, ob) = geoms[shape[i]], geoms[shape[j]]
        Ra, Rb = G.rotation(quat[i]), G.rotation(quat[j])
        calls.append((coal.ComputeCollision(ga, gb), coal.Transform3s(Ra, x[i] + Ra @ [0, 0, oa]),
                      coal.Transform3s(Rb, x[j] + Rb @ [0, 0, ob])))
    return calls, geoms


def time_coal(calls, reps, tol):
    req = coal.CollisionRequest(coal.CONTACT, 1)
    req.gjk_tolerance = tol
    req.epa_tolerance = tol
    res = coal.CollisionResult()
    n = 0
    t0 = time.perf_counter()
    for _ in range(reps):
        for cc, ta, tb in calls:
            res.clear()
            n += cc(ta, tb, req, res) > 0
    return (time.perf_counter() - t0) / (reps * len(calls)), n


def coal_floor(reps=20000):
    a, b = coal.Sphere(1.0), coal.Sphere(1.0)
    cc = coal.ComputeCollision(a, b)
    ta, tb = coal.Transform3s(np.eye(3), np.zeros(3)), coal.Transform3s(np.eye(3), np.array([5.0, 0, 0]))
    req, res = coal.CollisionRequest(coal.CONTACT, 1), coal.CollisionResult()
    t0 = time.perf_counter()
    for _ in range(reps):
        res.clear()
        cc(ta, tb, req, res)
    return (time.perf_counter() - t0) / reps


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--pairs", type=int, default=2000)
    ap.add_argument("--rounds", type=int, default=11)
    ap.add_argument("--tol", type=float, default=1e-6,
                    help="GJK/EPA relative tolerance for both (Coal's default 1e-6; dem's default 1e-10)")
    args = ap.parse_args()
    rng = np.random.default_rng(0)
    cases = {
        "cube-cube": [cube(1.0)],
        "cylinder-cylinder": [Cylinder(0.5, 1.2)],
    }
    # 20-vertex hulls: 20 random points on an ellipsoid are all hull vertices
    polys = []
    for _ in range(10):
        u = rng.normal(size=(20, 3))
        polys.append(Polyhedron(u / np.linalg.norm(u, axis=1)[:, None] * [0.6, 0.5, 0.4]))
    assert all(len(p.vertices) == 20 for p in polys)
    cases["polyhedron20"] = polys
    floor = coal_floor()
    print("tolerance %g; Coal Python per-call floor (far spheres, closed form): %.2f us" % (args.tol, floor * 1e6))
    print("%-18s %-8s %10s %10s %10s %8s %8s" % ("pair", "regime", "ours us", "coal us", "coal-floor",
                                                   "ratio", "ratio*"))
    for name, shapes in cases.items():
        table = ShapeTable(shapes)
        for regime, depth in (("crust", 0.5), ("epa", 3.0)):
            shape, x, quat, pi, pj = make_pairs(rng, shapes, args.pairs, depth)
            calls, keep = coal_setup(shapes, shape, x, quat, pi, pj)
            reps_ours = max(1, 200000 // args.pairs)
            r, r_floor, to, tc = [], [], [], []
            for k in range(args.rounds):
                order = (0, 1) if k % 2 == 0 else (1, 0)
                for o in order:
                    if o == 0:
                        t_ours, code = time_ours(table, shape, x, quat, pi, pj, reps_ours, args.tol)
                    else:
                        t_coal, nc = time_coal(calls, 5, args.tol)
                to.append(t_ours)
                tc.append(t_coal)
                r.append(t_coal / t_ours)
                r_floor.append(max(t_coal - floor, 1e-12) / t_ours)
            paths = np.bincount(code, minlength=4)
            print("%-18s %-8s %10.2f %10.2f %10.2f %8.2f %8.2f   (our paths: crust %d, epa %d, fallback %d; "
                  "coal contacts %d/%d)" % (name, regime, np.median(to) * 1e6, np.median(tc) * 1e6,
                                            (np.median(tc) - floor) * 1e6, np.median(r), np.median(r_floor),
                                            paths[1], paths[2], paths[3], nc // 5, len(pi)))
    print("ratio = Coal time / our time (median over alternating rounds); ratio* takes Coal's Python floor off")


if __name__ == "__main__":
    main()
