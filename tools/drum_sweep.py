#!/usr/bin/env python
"""Runs inputs/in.drum over the rotation rates of Part III sec. 4.2 (5, 20, 42, 80, 150, 200, 250 rpm), one
run after another, each in its own log, series, HDF5 dump and pictures under --dir:

    python tools/drum_sweep.py [--rpm 250 200 150 80 42 20 5] [--turns 2] [--max-time 1.5] [--min-time 0.5]
                               [--time T ...] [--dir drum_sweep] [--np 1] [-- extra in.drum arguments, e.g. -var shape sphere]

Each rate turns for `turns` drum turns, but at least --min-time and at most --max-time seconds (a turn takes
12 s at 5 rpm), or --time seconds, one per rate; every run fills and settles the same bed first (the same insertion seed). A run whose log
already ends with in.drum's "final:" line is skipped, so the sweep can be resumed. Then, in --dir,

    dem-drum-analysis --rpm 5 20 ... --series drum_5.dat drum_20.dat ... --h5 drum_5.h5 drum_20.h5 ... --paper cross3d

draws Fig. 25-27, classifies the regimes and draws the map of Fig. 30.
"""
import argparse
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def rotate_time(rpm, turns, tmin, tmax):
    return min(tmax, max(tmin, turns * 60.0 / rpm))


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    extra = []
    if "--" in argv:
        k = argv.index("--")
        argv, extra = argv[:k], argv[k + 1:]
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--rpm", nargs="+", type=float, default=[250, 200, 150, 80, 42, 20, 5])
    p.add_argument("--turns", type=float, default=2.0)
    p.add_argument("--min-time", type=float, default=0.5)
    p.add_argument("--max-time", type=float, default=1.5)
    p.add_argument("--time", nargs="+", type=float, help="rotation time (s) per rate")
    p.add_argument("--dir", default="drum_sweep")
    p.add_argument("--np", type=int, default=1, help="MPI ranks per run")
    a = p.parse_args(argv)
    if a.time and len(a.time) != len(a.rpm):
        p.error("give one --time per --rpm")
    os.makedirs(a.dir, exist_ok=True)
    for k, rpm in enumerate(a.rpm):
        name = os.path.join(a.dir, f"drum_{rpm:g}")
        log = name + ".log"
        if os.path.exists(log) and "final:" in open(log).read():
            print(f"{rpm:g} rpm: done before, skipped")
            continue
        t = a.time[k] if a.time else rotate_time(rpm, a.turns, a.min_time, a.max_time)
        cmd = ["dem", "-in", os.path.join(ROOT, "inputs", "in.drum"), "-var", "rpm", f"{rpm:g}",
               "-var", "rotate", f"{t:g}", "-var", "out", name, "-log", log, "-screen", "none"] + extra
        if a.np > 1:
            cmd = ["mpiexec", "-n", str(a.np)] + cmd
        print(f"{rpm:g} rpm: {t:g} s of rotation ({t * rpm / 60:.2f} turns)", flush=True)
        r = subprocess.run(cmd)
        if r.returncode:
            print(f"{rpm:g} rpm: dem failed (exit {r.returncode}), see {log}", file=sys.stderr)
            return r.returncode
    return 0


if __name__ == "__main__":
    sys.exit(main())
