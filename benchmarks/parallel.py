"""Parallel benchmark: the sphere bed (../shared/bench/sphere-bed, input benchmarks/bed/in.bed) and a
drum-like uneven bed (the same bed cut by an inclined free surface: three times more particles on one
side) on 1 and 2 MPI ranks, with and without load balancing; then the communication volume per step
against the particles per rank (2 and 4 ranks, 8000 and 32000 spheres: volume only, 4 ranks may
oversubscribe the machine).

    pip install '.[mpi]'
    python benchmarks/parallel.py [--steps 300] [--repeats 3] [--data-dir DIR] [--no-volume]

Runs alternate (1 rank, 2 ranks, ...) and the speedup is the median of the paired ratios (the machine
may be shared and noisy). Results are recorded in docs/parallel.md.
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.path.join(HERE, "..", "..", "shared", "bench", "sphere-bed")
IN_BED = os.path.join(HERE, "bed", "in.bed")


def mpiexec():
    return shutil.which("mpiexec", path=os.path.dirname(sys.executable)) or shutil.which("mpiexec")


def script(extra):
    """benchmarks/bed/in.bed with `extra` commands after read_data (processors before it)."""
    lines = open(IN_BED).read().splitlines()
    out = []
    for line in lines:
        if line.startswith("read_data"):
            out += [e for e in extra if e.startswith("processors")]
            out.append(line)
            out += [e for e in extra if not e.startswith("processors")]
        else:
            out.append(line)
    return "\n".join(out) + "\n"


def heap(src, dst, low=0.15):
    """The bed below an inclined surface z < H (low + (1 - low) x / L): a drum-like heap."""
    lines = open(src).read().splitlines()
    start = next(i for i, l in enumerate(lines) if l.startswith("Atoms")) + 2
    end = next((i for i in range(start, len(lines)) if not lines[i].strip()), len(lines))
    rows = [l.split() for l in lines[start:end]]
    L = max(float(r[4]) for r in rows)
    H = max(float(r[6]) for r in rows)
    keep = [r for r in rows if float(r[6]) < H * (low + (1 - low) * float(r[4]) / L)]
    head = [l if not l.strip().endswith(" atoms") else f"{len(keep)} atoms" for l in lines[:start]]
    with open(dst, "w") as f:
        f.write("\n".join(head) + "\n" + "\n".join(" ".join(r) for r in keep) + "\n")
    return len(keep)


def run(work, text, nprocs, data, steps):
    path = os.path.join(work, f"in.{nprocs}")
    with open(path, "w") as f:
        f.write(text)
    cmd = [sys.executable, "-m", "dem", "-in", path, "-var", "NSTEP", str(steps), "-var", "data", data,
           "-log", "none"]
    if nprocs > 1:
        cmd = [mpiexec(), "-n", str(nprocs)] + cmd
    out = subprocess.run(cmd, cwd=work, capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    if out.returncode:
        raise SystemExit(f"{' '.join(cmd)} failed:\n{out.stdout[-2000:]}\n{out.stderr[-2000:]}")
    return out.stdout


def loop_time(out):
    return float(re.search(r"Loop time of ([0-9.eE+-]+)", out).group(1))


def comm_lines(out):
    return [l for l in out.splitlines() if l.startswith(("Comm", "Balance", "Processor grid"))]


def capacity(work, data, steps, repeats):
    """How many cores the machine really gives two processes: throughput of two serial runs at once
    over one alone (2.0 on two idle cores). Bounds any 2-rank speedup measured here."""
    alone, both = [], []
    for _ in range(repeats):
        alone.append(loop_time(run(work, script([]), 1, data, steps)))
        path = os.path.join(work, "in.cap")
        with open(path, "w") as f:
            f.write(script([]))
        cmd = [sys.executable, "-m", "dem", "-in", path, "-var", "NSTEP", str(steps), "-var", "data", data,
               "-log", "none"]
        procs = [subprocess.Popen(cmd, cwd=work, stdout=subprocess.PIPE, text=True) for _ in range(2)]
        both.append(statistics.mean(loop_time(p.communicate()[0]) for p in procs))
    cap = 2 * statistics.median(a / b for a, b in zip(alone, both))
    print(f"\nMachine capacity: two serial runs at once give {cap:.2f}x the throughput of one "
          f"(alone {statistics.median(alone):.3f} s, together {statistics.median(both):.3f} s each)")
    return cap


def compare(work, name, data, steps, repeats, variants):
    """variants: [(label, nprocs, extra commands)]; the first is the reference (1 rank)."""
    times = {label: [] for label, _, _ in variants}
    last = {}
    for _ in range(repeats):
        for label, nprocs, extra in variants:
            out = run(work, script(extra), nprocs, data, steps)
            times[label].append(loop_time(out))
            last[label] = out
    ref = variants[0][0]
    print(f"\n{name}: {steps} steps, {repeats} alternating repeats")
    for label, nprocs, _ in variants:
        med = statistics.median(times[label])
        line = f"  {label:<28} loop median {med:7.3f} s"
        if label != ref:
            speedup = statistics.median(r / t for r, t in zip(times[ref], times[label]))
            line += f"  speedup {speedup:4.2f}  efficiency {100 * speedup / nprocs:3.0f} %"
        print(line)
        for c in comm_lines(last[label]):
            print(f"      {c}")


def volume(work, sizes, nprocs_list, steps):
    print(f"\nCommunication volume per step and rank ({steps} steps; timing not meaningful when "
          f"oversubscribed)")
    print(f"  {'N':>6} {'ranks':>5} {'particles/rank':>14} {'ghosts/rank':>11} {'KiB/step/rank':>13} "
          f"{'bytes/particle/step':>19}")
    for n in sizes:
        data = os.path.join(work, f"bed_{n}.data")
        for p in nprocs_list:
            out = run(work, script(["processors * * 1"]), p, data, steps)
            m = re.search(r"Comm volume: ([0-9.]+) KiB sent per step and rank, (\d+) ghosts per rank, (\d+) "
                          r"particles per rank", out)
            kib, ghosts, local = float(m.group(1)), int(m.group(2)), int(m.group(3))
            print(f"  {n:>6} {p:>5} {local:>14} {ghosts:>11} {kib:>13.1f} {1024 * kib / local:>19.1f}")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--steps", type=int, default=300)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--data-dir", default=SHARED)
    p.add_argument("--no-volume", action="store_true")
    args = p.parse_args()
    if mpiexec() is None:
        raise SystemExit("mpiexec not found: pip install '.[mpi]'")
    work = tempfile.mkdtemp(prefix="dem-parallel-")
    try:
        for n in (8000, 32000):
            shutil.copy(os.path.join(args.data_dir, f"bed_{n}.data"), work)
        bed = os.path.join(work, "bed_32000.data")
        drum = os.path.join(work, "heap.data")
        nheap = heap(bed, drum)
        capacity(work, bed, args.steps, args.repeats)
        compare(work, "Sphere bed, 32000 spheres", bed, args.steps, args.repeats,
                [("1 rank", 1, []), ("2 ranks", 2, ["processors * * 1"])])
        compare(work, f"Drum-like heap, {nheap} spheres (inclined free surface)", drum, args.steps,
                args.repeats,
                [("1 rank", 1, []),
                 ("2 ranks, even cuts", 2, ["processors 2 1 1"]),
                 ("2 ranks, balance (count)", 2, ["processors 2 1 1", "balance 1.02 shift x"]),
                 ("2 ranks, fix balance (time)", 2, ["processors 2 1 1", "balance 1.02 shift x",
                                                     "fix lb all balance 100 1.02 shift x weight time"])])
        if not args.no_volume:
            volume(work, (8000, 32000), (2, 4), 20)
    finally:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
