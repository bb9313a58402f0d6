#!/usr/bin/env python
"""Cylinder-wall impact, tilt sweep (Grains3D Part III sec 3.2, Figs 7 and 11): post-impact velocity of
the centre of mass V+ and spin omega_y+ against the tilt, for the true cylinder, the glued cylinder of N
slices and the glued-sphere cylinders of 9 and 54 spheres, with the rigid-body impulse solution, in one PNG.

    python tools/glued_cylinder_plot.py [--step 5] [--N 6] [--model B] [--table sweep.dat]
                                        [-o docs/figures/glued_cylinder_impact.png]
    python tools/glued_cylinder_plot.py --read sweep.dat [-o out.png]

The sweep runs inputs/in.cylinder_impact, inputs/in.glued_cylinder_impact (-var N, -var model) and
inputs/in.sphere_cylinder_impact (-var N 9|54) at tilts 0, step, ..., 90 degrees (each run well under a
second; about 30 s for the default step of 5 degrees) and writes the table (body tilt V+ omega+ mass I_yy)
to --table; --read plots such a table without running anything.

Curves: eq. 22-23 of Part III with e = e_n (solid black: the paper's analytic curve), the same with the
restitution e_eff the contact law gives at an eccentric contact point (dashed black, see
tests/test_cylinder_impact.py), and for each glued-sphere body the impulse solution of that body itself
(thin dotted, its colour): the lowest sphere's lever (R - r) cos(tilt) - z_l sin(tilt), its own mass and
inertia, e_eff. At 0 and 90 deg the contact is a surface or a line: the impulse solution is V+ = e_n,
omega+ = 0 (drawn as black stars).
"""
import argparse
import math
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
INPUTS = os.path.join(HERE, os.pardir, "inputs")
DEFAULT_PNG = os.path.normpath(os.path.join(HERE, os.pardir, "docs", "figures", "glued_cylinder_impact.png"))
R, L, M, EN = 0.004, 0.0053, 3.1e-4, 0.85
I_YY = M * (3 * R * R + L * L) / 12.0
RC = math.hypot(R, L / 2.0)
ALPHA = math.atan(L / (2.0 * R))
BETA = -math.log(EN) / math.sqrt(math.pi ** 2 + math.log(EN) ** 2)     # gamma_n / omega_0 (eq. 16)


def impulse(d, e, m=M, inertia=I_YY, v0=1.0):
    """(V+, omega_y+) of a vertical impulse at lever d, restitution e at the contact point (eq. 22-23)."""
    p = (1.0 + e) * m * v0 * inertia / (inertia + m * d * d)
    return -v0 + p / m, -d * p / inertia


def e_eff(d, m=M, inertia=I_YY):
    z = BETA * math.sqrt(1.0 + m * d * d / inertia)
    return math.exp(-math.pi * z / math.sqrt(1.0 - z * z))


def corner_lever(th):
    return RC * math.cos(ALPHA + th)


def sphere_lever(th, n):
    r, zl = (L / 2.0, 0.0) if n == 9 else (L / 4.0, L / 4.0)
    return (R - r) * math.cos(th) - zl * math.sin(th)


def bodies(N, model):
    return [("true", "in.cylinder_impact", []),
            (f"glued{N}{model}", "in.glued_cylinder_impact", [("N", [str(N)]), ("model", [model])]),
            ("spheres9", "in.sphere_cylinder_impact", [("N", ["9"])]),
            ("spheres54", "in.sphere_cylinder_impact", [("N", ["54"])])]


def run_sweep(tilts, N=6, model="B"):
    """Rows (body, tilt, V+, omega+, mass, I_yy)."""
    import dem
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, inp, extra in bodies(N, model):
            for tilt in tilts:
                sim = dem.Simulation(screen=False, variables=[("tilt", [str(tilt)]),
                                                              ("out", [os.path.join(tmp, "s.dat")])] + extra)
                sim.file(os.path.join(INPUTS, inp))
                sim.close()
                v, w = sim.atom.local("v")[0], sim.atom.local("omega")[0]
                rows.append((name, tilt, float(v[2]), float(w[1]), float(sim.atom.local("rmass")[0]),
                             float(sim.atom.local("inertia")[0, 1])))
                print(f"{name:10s} tilt {tilt:3d}: V+ {v[2]:8.4f} m/s  omega+ {w[1]:8.2f} rad/s", flush=True)
    return rows


def write_table(rows, path):
    with open(path, "w") as f:
        f.write("# body tilt V+ omega+ mass I_yy (tools/glued_cylinder_plot.py)\n")
        for r in rows:
            f.write(f"{r[0]} {r[1]} {r[2]:.10g} {r[3]:.10g} {r[4]:.10g} {r[5]:.10g}\n")


def read_table(path):
    rows = []
    with open(path) as f:
        for line in f:
            if line.strip() and not line.startswith("#"):
                w = line.split()
                rows.append((w[0], int(float(w[1]))) + tuple(float(x) for x in w[2:6]))
    if not rows:
        raise SystemExit(f"{path}: no rows")
    return rows


STYLE = {"true": dict(marker="o", color="C0", label="true cylinder"),
         "spheres9": dict(marker="s", color="C2", label="9 glued spheres"),
         "spheres54": dict(marker="^", color="C3", label="54 glued spheres")}


def plot(rows, output):
    import numpy as np
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fine = np.linspace(0.5, 89.5, 400)
    fig = Figure(figsize=(11, 4.6))
    FigureCanvasAgg(fig)
    axes = fig.subplots(1, 2)
    for k, (ax, what) in enumerate(zip(axes, ("V$^+$ (m/s)", r"$\omega_y^+$ (rad/s)"))):
        ax.plot(fine, [impulse(corner_lever(math.radians(t)), EN)[k] for t in fine], "k-", lw=1.2,
                label="eq. 22-23, $e_n$")
        ax.plot(fine, [impulse(corner_lever(math.radians(t)), e_eff(corner_lever(math.radians(t))))[k]
                       for t in fine], "k--", lw=1.0, label="eq. 22-23, $e_{eff}$")
        ax.plot([0, 90], [EN if k == 0 else 0.0] * 2, "k*", ms=10, label="surface / line contact")
        for name in dict.fromkeys(r[0] for r in rows):
            sel = [r for r in rows if r[0] == name]
            label = f"glued cylinder, {name[5:-1]} slices, model {name[-1]}"
            style = dict(STYLE.get(name, dict(marker="x", color="C1", label=label)))
            if name.startswith("glued"):
                style.update(ms=9, mew=1.6)
            else:
                style.update(mfc="none", ms=6)
            ax.plot([r[1] for r in sel], [r[2 + k] for r in sel], ls="none", **style)
            if name.startswith("spheres"):
                n, m, iyy = int(name[7:]), sel[0][4], sel[0][5]
                levers = [sphere_lever(math.radians(t), n) for t in fine]
                own = [impulse(d, e_eff(d, m, iyy), m, iyy)[k] for d in levers]
                ax.plot(fine, own, ":", color=style["color"], lw=1.0)
        ax.set_xlabel("tilt (degrees)")
        ax.set_ylabel(what)
        ax.set_xlim(-3, 93)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7.5, loc="lower right")
    axes[0].set_title("post-impact velocity (Part III Figs 7a, 11a,c)", fontsize=9)
    axes[1].set_title("post-impact spin (dotted: each glued-sphere body's own solution)", fontsize=9)
    fig.suptitle("Cylinder-wall impact at 1 m/s: D = 8 mm, L = 5.3 mm, kn = 1e5 N/m, $e_n$ = 0.85, "
                 "dt = 5e-6 s", fontsize=10)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(output)), exist_ok=True)
    fig.savefig(output, dpi=130)
    print(f"wrote {output}")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--read", metavar="TABLE", help="plot this table, run nothing")
    p.add_argument("--table", default="glued_cylinder_sweep.dat", help="where the sweep's table goes")
    p.add_argument("--step", type=int, default=5, help="tilt step in degrees (default 5)")
    p.add_argument("--N", type=int, default=6, help="slices of the glued cylinder (default 6)")
    p.add_argument("--model", choices=("A", "B"), default="B")
    p.add_argument("-o", "--output", default=DEFAULT_PNG)
    a = p.parse_args(argv)
    if a.read:
        rows = read_table(a.read)
    else:
        tilts = sorted(set(range(0, 90, a.step)) | {90})
        rows = run_sweep(tilts, a.N, a.model)
        write_table(rows, a.table)
        print(f"wrote {a.table}")
    plot(rows, a.output)


if __name__ == "__main__":
    sys.exit(main())
