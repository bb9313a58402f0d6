"""Time per penetration query of two overlapping sharp polytopes: the separating-axis kernel
(dem/contact/_polytope.pyx, depth only and depth + contact points) against dem's EPA (signed distance:
GJK then EPA, dem.contact._gjk.distance_batch) and Coal's penetration (coal.distance on overlapping
convexes), for two cubes, two pinacoids (Descantes 2022) and two 20-vertex polyhedra.

    python benchmarks/polytope_vs_epa.py [--pairs 500] [--reps 20]

Both dem paths are timed in one nogil Cython loop over all pairs. Coal has no batch API in Python: its
side is a Python loop over coal.ComputeDistance functors (the accurate settings of tests/test_gjk.py), printed
per call with the cost of a trivial call (two far spheres) beside it, as an idea of the Python overhead.
"""
import argparse
import time

import numpy as np

from dem.contact import geometry as G
from dem.contact import _gjk, _polytope
from dem.contact.polytope import topology_view
from dem.shapes import Polyhedron, ShapeTable, cube, pinacoid


def poses(rng, A, B, m):
    xa, qa, xb, qb = (np.zeros((m, 3)), np.zeros((m, 4)), np.zeros((m, 3)), np.zeros((m, 4)))
    for k in range(m):
        q1, q2 = rng.normal(size=4), rng.normal(size=4)
        q1 /= np.linalg.norm(q1)
        q2 /= np.linalg.norm(q2)
        u = rng.normal(size=3)
        u /= np.linalg.norm(u)
        lo, hi = 0.0, A.bounding_radius + B.bounding_radius
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            if G.distance(A, np.zeros(3), q1, B, u * mid, q2)[0] > 0:
                hi = mid
            else:
                lo = mid
        xa[k], qa[k], qb[k] = 0.0, q1, q2
        xb[k] = u * (hi - rng.uniform(1e-3, 1e-2) * min(A.inradius, B.inradius))
    return xa, qa, xb, qb


def coal_floor(coal, reps=20000):
    a, b = coal.Sphere(1.0), coal.Sphere(1.0)
    cd = coal.ComputeDistance(a, b)
    ta, tb = coal.Transform3s(np.eye(3), np.zeros(3)), coal.Transform3s(np.eye(3), np.array([5.0, 0, 0]))
    req, res = coal.DistanceRequest(), coal.DistanceResult()
    t0 = time.perf_counter()
    for _ in range(reps):
        cd(ta, tb, req, res)
    return (time.perf_counter() - t0) / reps


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pairs", type=int, default=500)
    ap.add_argument("--reps", type=int, default=20)
    args = ap.parse_args()
    rng = np.random.default_rng(7)
    try:
        import coal
    except ImportError:          # pragma: no cover
        coal = None
    e = 0.5 ** 0.5        # Descantes' pinacoid, L = G = E = d / sqrt(2), alpha 60 deg (Table 1)
    cases = [("cube-cube", cube(1.0), cube(1.0)),
             ("pinacoid-pinacoid", pinacoid(e, e, e), pinacoid(e, e, e)),
             ("poly20-poly20", Polyhedron(rng.normal(size=(20, 3))), Polyhedron(rng.normal(size=(20, 3))))]
    for name, A, B in cases:
        m = args.pairs
        xa, qa, xb, qb = poses(rng, A, B, m)
        tv = topology_view([A, B])
        ia, ib = np.zeros(m, np.int32), np.ones(m, np.int32)
        ftol = 1e-9 * (A.bounding_radius + B.bounding_radius)
        t_sat, h1 = _polytope.time_pairs(tv, ia, ib, xa, qa, xb, qb, args.reps, ftol, False)
        t_pts, h2 = _polytope.time_pairs(tv, ia, ib, xa, qa, xb, qb, args.reps, ftol, True)
        table = ShapeTable([A, B]).view()
        x = np.ascontiguousarray(np.vstack([xa, xb]))
        quat = np.ascontiguousarray(np.vstack([qa, qb]))
        shape = np.r_[np.zeros(m, np.int32), np.ones(m, np.int32)].astype(np.int32)
        pi, pj = np.arange(m, dtype=np.int32), np.arange(m, 2 * m, dtype=np.int32)
        dist, pa, pb = np.zeros(m), np.zeros((m, 3)), np.zeros((m, 3))
        t0 = time.perf_counter()
        for _ in range(args.reps):
            guess = np.zeros((m, 3))
            _gjk.distance_batch(table, shape, x, quat, pi, pj, G.DEFAULT_TOL, guess, dist, pa, pb)
        t_epa = (time.perf_counter() - t0) / (args.reps * m)
        line = "%-18s SAT depth %7.0f ns  SAT+points %7.0f ns  dem EPA %7.0f ns" % (
            name, 1e9 * t_sat, 1e9 * t_pts, 1e9 * t_epa)
        if coal is not None:
            def conv(s):
                V, F = s.mesh()
                pts = coal.StdVec_Vec3s()
                for p in V:
                    pts.append(np.asarray(p, float))
                tris = coal.StdVec_Triangle()
                for f in F:
                    tris.append(coal.Triangle(int(f[0]), int(f[1]), int(f[2])))
                return coal.Convex(pts, tris)
            ga, gb = (coal.Box(1.0, 1.0, 1.0), coal.Box(1.0, 1.0, 1.0)) if name == "cube-cube" else (conv(A), conv(B))
            cd = coal.ComputeDistance(ga, gb)
            tf = [(coal.Transform3s(G.rotation(qa[k]), xa[k]), coal.Transform3s(G.rotation(qb[k]), xb[k]))
                  for k in range(m)]
            req, res = coal.DistanceRequest(), coal.DistanceResult()
            req.gjk_variant = coal.GJKVariant.NesterovAcceleration     # the settings of tests/test_gjk.py
            req.gjk_convergence_criterion_type = coal.GJKConvergenceCriterionType.Absolute
            req.gjk_tolerance = 1e-11
            req.gjk_max_iterations = 2000
            req.epa_tolerance = 1e-10
            req.epa_max_iterations = 500
            t0 = time.perf_counter()
            for _ in range(args.reps):
                for ta, tb in tf:
                    cd(ta, tb, req, res)
            t_coal = (time.perf_counter() - t0) / (args.reps * m)
            fl = coal_floor(coal)
            line += "  coal %7.0f ns per Python call (a trivial call: %4.0f ns)" % (1e9 * t_coal, 1e9 * fl)
        print(line, "hits", h1 // args.reps, h2 // args.reps, "of", m)


if __name__ == "__main__":
    main()
