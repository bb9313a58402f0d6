"""Rotating-drum benchmark: particle-steps per second of the 3000-sphere drum of `inputs/in.drum -var shape
sphere` (Part III Table 6: kn 1e5, dt 2e-6, R = 50 mm, 24 mm periodic) on one core, while it rotates at 40 rpm.

    python benchmarks/drum.py [--N 3000] [--steps 20000] [--repeats 3] [--rpm 40]

The bed is filled and settled once (0.17 s of physical time, as in.drum), then the rotating
phase is timed `repeats` times from the same settled state (the first 0.05 s of rotation: the bed turns
as a rigid body and starts to flow); the median is printed with the stage times of the last run.
"""
import argparse
import os
import statistics
import sys
import tempfile
import time

import dem

LAW = "kn 1e5 en 0.73 mu 0.55 gamma_t 2000 ks 28571"



def settled_bed(n, path):
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        boundary f p f
        region box block -0.0505 0.0505 0 0.024 -0.0505 0.0505
        create_box 1 box
        region inside cylinder y 0 0 0.05 EDGE EDGE
        pair_style sphere
        pair_coeff * * {LAW}
        fix integrate all nve/sphere
        fix gravity all gravity 9.81 vector 0 0 -1
        fix drum all wall/drum y 0 0 0.05 rpm 0 {LAW}
        fix ins all insert 4821 inside count {n} radius 0.0015 density 2500
        timestep 2e-6
        neighbor 0.0003 bin
        thermo 0
        run 60000
        fix calm all damping/potyondy alpha 0.7
        run 25000
        unfix calm
        unfix ins
        write_restart {path}
    """)


def rotate(path, rpm, steps):
    sim = dem.Simulation(screen=False)
    sim.commands(f"""
        read_restart {path}
        pair_style sphere
        pair_coeff * * {LAW}
        fix integrate all nve/sphere
        fix gravity all gravity 9.81 vector 0 0 -1
        fix drum all wall/drum y 0 0 0.05 rpm {rpm} ramp 0.02 {LAW}
        timestep 2e-6
        neighbor 0.0003 bin
        thermo 0
    """)
    t0 = time.perf_counter()
    sim.run(steps)
    return time.perf_counter() - t0, sim


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--N", type=int, default=3000)
    p.add_argument("--steps", type=int, default=20000)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--rpm", type=float, default=40)
    a = p.parse_args()
    path = os.path.join(tempfile.mkdtemp(prefix="dem-drum-"), "bed.restart")
    t0 = time.perf_counter()
    settled_bed(a.N, path)
    print(f"fill + settle (85000 steps): {time.perf_counter() - t0:.1f} s")
    rates, sim = [], None
    for _ in range(a.repeats):
        wall, sim = rotate(path, a.rpm, a.steps)
        rates.append(a.N * a.steps / wall)
    print(f"drum, {a.N} spheres, {a.rpm:g} rpm, {a.steps} steps x {a.repeats}: "
          f"median {statistics.median(rates) / 1e6:.3f} M particle-steps/s "
          f"({statistics.median(rates) / a.N:.0f} steps/s; runs: "
          f"{', '.join(f'{r / 1e6:.3f}' for r in rates)})")
    up = sim.update
    total = sum(up.timers.values())
    print("stage times of the last run: " + ", ".join(f"{k} {v:.2f} s ({100 * v / total:.0f} %)"
                                                      for k, v in up.timers.items()))
    print(f"contacts per particle {2 * sim.pair.ncontacts / sim.atom.natoms:.2f}")


if __name__ == "__main__":
    sys.exit(main())
