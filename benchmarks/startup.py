"""Start-up cost: the CPU time (user + system, of the child process) of `dem -in` on a three-line script
against LAMMPS's `lmp -in` on the same three lines, alternating (dem, lmp, dem, lmp ...).

    python benchmarks/startup.py [--repeats 9]
"""
import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile

from bed.run import lammps_binary

SCRIPT = "units si\nregion box block 0 1 0 1 0 1\ncreate_box 1 box\n"


def cpu_of(cmd, cwd, env=None):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, cwd=cwd, env=env, check=True, capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=9)
    a = p.parse_args()
    import sysconfig
    env = dict(os.environ, OMP_NUM_THREADS="1")
    env["LD_LIBRARY_PATH"] = sysconfig.get_config_var("LIBDIR") + ":" + env.get("LD_LIBRARY_PATH", "")
    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(tmp, "in.three"), "w") as f:
            f.write(SCRIPT)
        with open(os.path.join(tmp, "in.three.lammps"), "w") as f:
            f.write("units si\nregion box block 0 1 0 1 0 1\ncreate_box 1 box\n")
        dem, lmp = [], []
        for _ in range(a.repeats):
            dem.append(cpu_of([sys.executable, "-m", "dem", "-in", "in.three", "-log", "none"], tmp))
            lmp.append(cpu_of([lammps_binary(), "-in", "in.three.lammps", "-log", "none"], tmp, env))
    print(f"dem  start-up CPU: median {statistics.median(dem):.3f} s (range {min(dem):.3f}-{max(dem):.3f})")
    print(f"lmp  start-up CPU: median {statistics.median(lmp):.3f} s (range {min(lmp):.3f}-{max(lmp):.3f})")
    print(f"ratio dem / lmp: {statistics.median(dem) / statistics.median(lmp):.1f}")


if __name__ == "__main__":
    sys.exit(main())
