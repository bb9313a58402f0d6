#!/usr/bin/env python
"""A single particle in the rotating drum of Part III sec. 4.2 (Fig. 21): a sphere and a 3D cross of the
same volume at 150 rpm, their trajectories in the drum's cross-section, how high they are carried (the
angle from the bottom, in the sense of the rotation, at which they leave the wall and fall back) and the
ratio of their translational to rotational kinetic energy.

    python tools/drum_single.py [--rpm 150] [--time 2] [--shapes sphere cross3d] [--rough 1|0] [--out drum_single]

Each run is inputs/in.drum with N = 1 (its rough wall of carried spheres, or the smooth wall with --rough 0;
the Table 6 law, dt = 2e-6 s):
the particle is inserted, settles, then the drum turns at --rpm (0.02 s ramp) for --time s, the particle
sampled every 1 ms (position, velocity, spin). Output: `out`.png (the trajectories, as Fig. 21) and a
table on stdout: the angle's median, 90th and 99th percentiles and maximum, the fraction of the time
spent above 45 degrees, the energy ratio's median, the turns done.
"""
import argparse
import math
import os
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
R = 0.05                     # drum radius (m), inputs/in.drum
RHO = 2500.0


def run(shape, rpm, duration, rough, every=500):
    import dem
    sim = dem.Simulation(screen=False, variables=[("shape", [shape]), ("N", ["1"]), ("rotate", ["0"]),
                                                  ("rpm", [str(rpm)]), ("rough", [str(rough)]),
                                                  ("out", [f"single_{shape}"])])
    sim.file(os.path.join(ROOT, "inputs", "in.drum"))
    sim.command("undump last")                       # the script's final picture, written every step
    bed = sim.groups.bit("bed")
    rows = []
    steps = int(round(duration / sim.update.dt))
    for _ in range(steps // every):
        sim.run(every)
        mask = sim.atom.local("mask")
        i = int(np.flatnonzero(mask & bed)[0])
        x, v, w = sim.atom.local("x")[i], sim.atom.local("v")[i], sim.atom.local("omega")[i]
        m = float(sim.atom.local("rmass")[i])
        inertia = sim.atom.local("inertia")[i] if "inertia" in sim.atom.data else None
        if shape == "sphere":
            erot = 0.5 * 0.4 * m * float(sim.atom.local("radius")[i]) ** 2 * float(w @ w)
        else:                 # principal moments, spin in the body frame
            from dem.thermo import quat_to_matrix
            rot = quat_to_matrix(sim.atom.local("quat")[i:i + 1])[0]
            wb = rot.T @ w
            erot = 0.5 * float(np.sum(inertia * wb * wb))
        rows.append([sim.update.time, x[0], x[2], 0.5 * m * float(v @ v), erot])
    return np.array(rows), sim.modify.find("drum").angle / (2 * math.pi)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--rpm", type=float, default=150.0)
    p.add_argument("--time", type=float, default=2.0, help="rotation time (s)")
    p.add_argument("--shapes", nargs="+", default=["sphere", "cross3d"])
    p.add_argument("--rough", type=int, default=1, choices=(0, 1), help="the drum's wall: rough (1) or smooth")
    p.add_argument("--out", default="drum_single")
    a = p.parse_args(argv)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(a.shapes), figsize=(4.2 * len(a.shapes), 4.4))
    axes = np.atleast_1d(axes)
    print("| shape | turns | angle median (deg) | 90 % | 99 % | max | time above 45 deg | E_trans / E_rot median |")
    print("|---|---|---|---|---|---|---|---|")
    for ax, shape in zip(axes, a.shapes):
        data, turns = run(shape, a.rpm, a.time, a.rough)
        t, x, z, et, er = data.T
        keep = t > t[0] + 0.05                       # past the ramp
        phi = np.degrees(np.arctan2(-x, -z))[keep]   # from the bottom, in the sense of the rotation
        ratio = et[keep] / np.maximum(er[keep], 1e-300)
        q = np.percentile(phi, [50, 90, 99])
        print(f"| {shape} | {turns:.2f} | {q[0]:.1f} | {q[1]:.1f} | {q[2]:.1f} | {phi.max():.1f} | "
              f"{np.mean(phi > 45) * 100:.1f} % | {np.median(ratio):.2f} |")
        ax.add_patch(plt.Circle((0, 0), R * 1e3, fill=False, color="k"))
        ax.plot(x[keep] * 1e3, z[keep] * 1e3, lw=0.5)
        ax.set_aspect("equal")
        ax.set_xlim(-55, 55)
        ax.set_ylim(-55, 55)
        ax.set_title(f"{shape}, {a.rpm:g} rpm, {a.time:g} s, {'rough' if a.rough else 'smooth'} wall")
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("z (mm)")
    fig.tight_layout()
    fig.savefig(f"{a.out}.png", dpi=110)
    print(f"wrote {a.out}.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
