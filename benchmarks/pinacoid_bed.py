"""Cost of the pinacoid packing of Descantes 2022 (inputs/in.pinacoid_packing) in its dense stage, on 1 and
2 MPI ranks: a settled bed that the input wrote (${out}.restart) is tiled T x T times along the periodic x
and y (its particles repeated, so the tiled bed is as settled as the original), then run at rest with the
input's contact and time step, one rank count after the other (1, 2, 1, 2 ...).

    python benchmarks/pinacoid_bed.py BED.restart [--tile 2] [--soft 1] [--steps 2000] [--repeats 2]

A bed of 500 pinacoids (`-var N 500 -var Lx 4.47`) tiled 2 x 2 is 2000 pinacoids in an 8.94 d_sph box, the
paper's 25 per d_sph^2, close to its 2500 in 10 x 10. Prints the loop time per particle-step of each run.
Results: benchmarks/README.md and docs/validation.md.
"""
import argparse
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

import dem
from dem.shapes import pinacoid_volume

# inputs/in.pinacoid_packing, Table 1 (units of d_sph, rho = g = 1): the mean pinacoid, L = G = E
E = 1 / math.sqrt(2)
V = float(pinacoid_volume(E, E, E, 60.0))     # (a numpy scalar would print as np.float64(...) in the script)
T_INERTIA = math.sqrt((6 * V / math.pi) ** (1 / 3))


def tiled_data(restart, tile, path):
    """Writes the bed of `restart` repeated tile x tile times along x and y as a data file; returns its
    number of particles."""
    with tempfile.TemporaryDirectory() as tmp:
        one = os.path.join(tmp, "one.data")
        sim = dem.Simulation(screen=False)
        sim.command(f"read_restart {restart}")
        sim.command(f"write_data {one}")
        lines = open(one).read().splitlines()
    head, atoms, vels, section = [], [], [], None
    for line in lines:
        word = line.split("#")[0].strip()
        if word.startswith("Atoms"):
            section = atoms
        elif word.startswith("Velocities"):
            section = vels
        elif section is not None and word:
            section.append(line)
        elif section is None:
            head.append(line)
    box = {}
    for line in head:
        m = re.match(r"\s*(\S+)\s+(\S+)\s+([xyz])lo\s+[xyz]hi", line)
        if m:
            box[m.group(3)] = (float(m.group(1)), float(m.group(2)))
    n = len(atoms)
    out = []
    for line in head:
        if line.strip().endswith("atoms"):
            line = f"{n * tile * tile} atoms"
        for a in "xy":
            if line.strip().endswith(f"{a}lo {a}hi"):
                lo, hi = box[a]
                line = f"{lo!r} {lo + tile * (hi - lo)!r} {a}lo {a}hi"
        out.append(line)
    lx = box["x"][1] - box["x"][0]
    ly = box["y"][1] - box["y"][0]
    out += ["", "Atoms # sphere", ""]
    copies = [(a, b) for a in range(tile) for b in range(tile)]
    for c, (a, b) in enumerate(copies):
        for line in atoms:
            w, _, extra = line.partition("#")
            f = w.split()
            f[0] = str(int(f[0]) + c * n)
            f[4] = repr(float(f[4]) + a * lx)
            f[5] = repr(float(f[5]) + b * ly)
            out.append(" ".join(f) + (" #" + extra if extra else ""))
    out += ["", "Velocities", ""]
    for c in range(len(copies)):
        for line in vels:
            f = line.split()
            f[0] = str(int(f[0]) + c * n)
            out.append(" ".join(f))
    open(path, "w").write("\n".join(out) + "\n")
    return n * tile * tile


def script(data, soft, steps):
    tst = T_INERTIA / 400 * math.sqrt(soft)
    kn = V / (2 * tst ** 2)
    return f"""units si
boundary p p f
read_data {data}
pair_style polyhedron/multipoint law descantes
pair_coeff * * kn {kn!r} en 0 mu 0
fix integrate all nve/shape
fix gravity all gravity 1 vector 0 0 -1
fix floor all wall/plane zplane 0 NULL kn {kn!r} en 0 mu 0 point multipoint law descantes
timestep {tst / 80!r}
neighbor 0.1 bin
thermo {steps}
run {steps}
"""


def loop_time(log):
    m = re.findall(r"Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) particles", open(log).read())
    t, _, steps, n = m[-1]
    return float(t), int(steps), int(n)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("restart")
    ap.add_argument("--tile", type=int, default=2)
    ap.add_argument("--soft", type=float, default=1.0)
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    a = ap.parse_args(argv)
    mpi = shutil.which("mpiexec", path=os.path.dirname(sys.executable)) or shutil.which("mpiexec")
    with tempfile.TemporaryDirectory() as tmp:
        data = os.path.join(tmp, "bed.data")
        n = tiled_data(os.path.abspath(a.restart), a.tile, data)
        inp = os.path.join(tmp, "in.bed")
        open(inp, "w").write(script(data, a.soft, a.steps))
        print(f"{n} pinacoids, soft {a.soft:g}, {a.steps} steps a run")
        for rep in range(a.repeats):
            for r in a.ranks:
                log = os.path.join(tmp, f"log.{r}")
                subprocess.run([mpi, "-n", str(r), sys.executable, "-m", "dem", "-in", inp, "-log", log,
                                "-screen", "none"], check=True, cwd=tmp)
                t, steps, n = loop_time(log)
                print(f"run {rep + 1}, {r} rank(s): loop {t:.1f} s, {1e6 * t / (steps * n):.2f} us per "
                      f"particle-step, {steps * n / t / 1e3:.0f} k particle-steps/s", flush=True)


if __name__ == "__main__":
    main()
