"""Chung & Ooi (2011) benchmark tests: run the eight inputs of inputs/validation/, compare with theory,
draw the figures (docs/figures/chung_ooi_N.png) and write the numbers (docs/data/chung_ooi/*.csv).

    python tools/chung_ooi.py [--out docs] [--quick]

L. Chung and J. Y. Ooi, Benchmark tests for verifying discrete element modelling codes at particle impact
level, Granular Matter 13 (2011) 643-656. Materials and sizes: see the header of each input (the paper's
tables as the public reproductions give them: Yade's scripts for tests 1-4, Kratos's DEM benchmarks and
PySPH's chung_test_* examples for 5-8).

Theory, written here from the textbooks (not from dem):

* Hertz (Johnson, Contact Mechanics, 1985, sec. 11.1), elastic impact at relative speed v:
  delta_max = (15 m* v^2 / (16 Y* sqrt(R*)))^(2/5), F_max = 4/3 Y* sqrt(R*) delta_max^(3/2),
  t_c = 2.8682 delta_max / v (2 Gamma(7/5) sqrt(pi) / Gamma(9/10)).
* Rigid-body impulse theory with Coulomb friction (Maw, Barber & Fawcett, Wear 38 (1976) 101; Kharaz et
  al., Powder Technol. 120 (2001) 281; exact in gross sliding): normal impulse J_n = m* (1 + e) v_n; the
  tangential impulse is mu J_n if the contact slides throughout, i.e. if the initial slip
  s0 > mu (1 + e) v_n m* w_t (w_t = sum over the free bodies of 1/m + R^2/I: 7/2 / m of one sphere on a
  fixed body), else the slip stops (J_t = s0 / w_t) in the rigid limit. Elastic bodies in the sticking
  range deviate from the rigid limit (the tangential compliance reverses the slip: Maw et al.); there the
  reference is the Hertz-Mindlin law itself integrated at t_c / 20000 (`mindlin_reference`, the
  continuum solution of the model with Mindlin-Deresiewicz no-slip stiffness 8 G* a and the Coulomb cap,
  what the paper's Hertz-Mindlin codes solve).
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
IMPACT = 2.0 * math.gamma(1.4) * math.sqrt(math.pi) / math.gamma(0.9)
RIGID = 1e20

# E (Pa), nu, rho (kg/m^3)
MAT = {"glass": (4.8e10, 0.20, 2800), "limestone": (2.0e10, 0.25, 2500),
       "al_alloy_t2": (7e10, 0.30, 2699), "mg_alloy": (4e10, 0.35, 1800),
       "al_oxide": (3.8e11, 0.23, 4000), "cast_iron": (1e11, 0.25, 7000),
       "steel": (2.08e11, 0.30, 7850), "polyethylene": (1e9, 0.40, 1400),
       "al_alloy": (7e10, 0.33, 2700), "nylon": (2.5e9, 0.40, 1000), "copper": (1.2e11, 0.35, 8900)}


# ------------------------------------------------------------------------------------------------- theory
def ystar_gstar(m1, m2=None):
    """Y*, G* of two materials (m2 None: a rigid body)."""
    E1, n1, _ = MAT[m1]
    E2, n2 = (RIGID, n1) if m2 is None else MAT[m2][:2]
    G1, G2 = E1 / (2 * (1 + n1)), E2 / (2 * (1 + n2))
    return 1 / ((1 - n1 ** 2) / E1 + (1 - n2 ** 2) / E2), 1 / ((2 - n1) / G1 + (2 - n2) / G2)


def hertz(ystar, meff, reff, v):
    """(delta_max, F_max, t_c) of an elastic Hertz impact at relative normal speed v."""
    d = (15 * meff * v * v / (16 * ystar * math.sqrt(reff))) ** 0.4
    return d, 4.0 / 3.0 * ystar * math.sqrt(reff) * d ** 1.5, IMPACT * d / v


def rigid_body(s0, vn, e, mu, meff, wt):
    """Tangential impulse of the rigid-body theory: mu J_n while sliding throughout, else s0 / wt."""
    jn = meff * (1 + e) * vn
    return np.minimum(mu * jn, np.abs(s0) / wt) * np.sign(s0), jn


def mindlin_reference(s0, vn, e, mu, meff, wt, ystar, gstar, reff, steps=20000):
    """Tangential impulse (array over s0) of the Hertz-Mindlin law integrated at t_c / steps: normal
    F = 4/3 Y* sqrt(R*) d^1.5 + gn u_n (u_n the approach speed), tangential -kt xi - gt u_t capped at mu |F| (spring reset to the
    cap), kt = 8 G* a, a = sqrt(R* d), dashpots 2 sqrt(5/6) beta sqrt(S m*) (S = 2 Y* a, kt)."""
    s0 = np.asarray(s0, float)
    vn = np.broadcast_to(np.asarray(vn, float), s0.shape).copy()
    beta = 0.0 if e >= 1 else -math.log(e) / math.sqrt(math.log(e) ** 2 + math.pi ** 2)
    dt = hertz(ystar, meff, reff, vn.max())[2] / steps
    nsteps = int(1.5 * hertz(ystar, meff, reff, vn.min())[2] / dt) + 10
    d, un = np.zeros_like(s0), vn.copy()      # overlap, approach speed
    xi, ut, jt = np.zeros_like(s0), s0.copy(), np.zeros_like(s0)
    c = 2 * math.sqrt(5 / 6) * beta
    for _ in range(nsteps):
        d += un * dt
        on = d > 0
        if not on.any():
            break
        dp = np.where(on, d, 0.0)
        a = np.sqrt(reff * dp)
        fn = np.where(on, 4.0 / 3.0 * ystar * a * dp + c * np.sqrt(2 * ystar * a * meff) * un, 0.0)
        kt = 8 * gstar * a
        gt = c * np.sqrt(kt * meff)
        xi = np.where(on, xi + ut * dt, 0.0)
        ft = np.where(on, -kt * xi - gt * ut, 0.0)
        cap = mu * np.abs(fn)
        over = np.abs(ft) > cap
        ft = np.where(over, cap * np.sign(ft), ft)
        xi = np.where(over & (kt > 0), -(ft + gt * ut) / np.where(kt > 0, kt, 1.0), xi)
        un -= fn / meff * dt
        ut += ft * wt * dt
        jt -= ft * dt
    return jt


# --------------------------------------------------------------------------------------------------- runs
def run_input(n, out, extra=()):
    """Run one input with the installed dem (from the output's folder: `python -m dem` run in the source
    tree would import its sources, which lack the compiled kernels after a plain `pip install .`)."""
    cmd = [sys.executable, "-m", "dem", "-in", os.path.join(ROOT, "inputs", "validation", f"in.chung_ooi_{n}"),
           "-log", "none", "-screen", "none", "-var", "out", os.path.abspath(out)]
    for k, v in extra:
        cmd += ["-var", k, str(v)]
    subprocess.run(cmd, check=True, cwd=os.path.dirname(os.path.abspath(out)))


def read_dump(path):
    """{id: row dict} of the first and the last frame of a dump custom file."""
    frames, cols, rows = [], None, None
    with open(path) as f:
        lines = f.read().splitlines()
    i = 0
    while i < len(lines):
        if lines[i].startswith("ITEM: NUMBER OF ATOMS"):
            nat = int(lines[i + 1])
        elif lines[i].startswith("ITEM: ATOMS"):
            cols = lines[i].split()[2:]
            rows = {}
            for line in lines[i + 1:i + 1 + nat]:
                vals = dict(zip(cols, map(float, line.split())))
                rows[int(vals["id"])] = vals
            frames.append(rows)
            i += nat
        i += 1
    return frames[0], frames[-1]


def mass(mat, r):
    return 4.0 / 3.0 * math.pi * r ** 3 * MAT[mat][2]


def series_metrics(t, gap, v, m, dt):
    """(contact time, largest overlap, largest force) from a time series of overlap and velocity."""
    inside = gap > 0
    tc = inside.sum() * dt
    f = np.abs(np.diff(v)) * m / dt                   # force on step k from v_{k+1/2} - v_{k-1/2}
    return tc, gap.max(), f.max()


def test_normal(n, work, steps=400):
    """Tests 1 and 2: contact time, largest overlap and force against Hertz; returns rows."""
    out = os.path.join(work, f"chung_ooi_{n}.txt")
    run_input(n, out, [("steps", steps)])
    data = np.loadtxt(out)
    dt = data[1, 1] - data[0, 1]
    rows, curves = [], []
    if n == 1:
        cases = [("glass", 2, 3, 4, 5), ("limestone", 6, 7, 8, 9)]
        R, v = 0.01, 20.0
        for mat, x1, v1, x2, v2 in cases:
            m = mass(mat, R)
            gap = 2 * R - (data[:, x2] - data[:, x1])
            ys, _ = ystar_gstar(mat, mat)
            theory = hertz(ys, m / 2, R / 2, v)
            meas = series_metrics(data[:, 1], gap, data[:, v1], m, dt)
            rows.append((mat, theory, meas))
            f = np.r_[0, np.abs(np.diff(data[:, v1])) * m / dt]
            curves.append((mat, gap, f, ys, R / 2))
    else:
        cases = [("al_alloy_t2", 2, 3), ("mg_alloy", 4, 5)]
        R, v = 0.1, 0.2
        for mat, z, vz in cases:
            m = mass(mat, R)
            gap = R - data[:, z]
            ys, _ = ystar_gstar(mat)
            theory = hertz(ys, m, R, v)
            meas = series_metrics(data[:, 1], gap, data[:, vz], m, dt)
            rows.append((mat, theory, meas))
            f = np.r_[0, np.abs(np.diff(data[:, vz])) * m / dt]
            curves.append((mat, gap, f, ys, R))
    return rows, curves


def test_restitution(work, law):
    out = os.path.join(work, f"chung_ooi_3_{law}.txt")
    run_input(3, out, [("law", law)])
    first, last = read_dump(out)
    rows = []
    for i in sorted(last):
        mat = "al_oxide" if i <= 5 else "cast_iron"
        en = 0.2 * (1 + (i - 1) % 5)
        rows.append((mat, en, last[i]["vz"] / -first[i]["vz"]))
    return rows


def oblique_wall(n, work, mats, R, vn, e, mu, extra=(), spin=False):
    """Tests 4, 5, 6 (sphere on the rigid plane). Returns {mat: dict of arrays}."""
    out = os.path.join(work, f"chung_ooi_{n}.txt")
    run_input(n, out, extra)
    first, last = read_dump(out)
    ids = sorted(last)
    per = len(ids) // len(mats)
    res = {}
    for k, mat in enumerate(mats):
        sel = ids[k * per:(k + 1) * per]
        m = mass(mat, R)
        I = 0.4 * m * R * R
        v0 = np.array([[first[i]["vx"], first[i]["vz"], first[i]["omegay"]] for i in sel])
        v1 = np.array([[last[i]["vx"], last[i]["vz"], last[i]["omegay"]] for i in sel])
        vn0 = -v0[:, 1]
        s0 = v0[:, 0] - R * v0[:, 2]                   # contact point's slip along x
        wt = 1 / m + R * R / I
        ys, gs = ystar_gstar(mat)
        jt_rb, jn = rigid_body(s0, vn0, e, mu, m, wt)
        jt_ref = mindlin_reference(s0, vn0, e, mu, m, wt, ys, gs, R)
        d = {"s0": s0, "vn0": vn0, "vx0": v0[:, 0], "w0": v0[:, 2],
             "vx": v1[:, 0], "vz": v1[:, 1], "w": v1[:, 2]}
        for tag, jt in (("rb", jt_rb), ("ref", jt_ref)):
            d["vx_" + tag] = v0[:, 0] - jt / m
            d["w_" + tag] = v0[:, 2] + jt * R / I           # torque of -jt x at -R z: (-R z) x (-jt x) = R jt y
            d["vz_" + tag] = e * vn0
        res[mat] = d
    return res


def pairs(n, work, mats, R1, R2, vn_rel, e, mu, fixed_second):
    """Tests 7, 8: pairs along x. Returns {key: dict of arrays} (relative slip along z)."""
    out = os.path.join(work, f"chung_ooi_{n}.txt")
    run_input(n, out)
    first, last = read_dump(out)
    ids = sorted(last)
    npair = len(ids) // 2
    groups = {}
    for p in range(npair):
        a, b = ids[2 * p], ids[2 * p + 1]
        t = int(first[a]["type"])
        groups.setdefault((t, p // (npair // (2 if n == 8 else 4))), []).append((a, b))
    res = {}
    for (t, block), lst in groups.items():
        mat = mats[(t - 1) % 2]
        m1, m2 = mass(mat, R1), mass(mat, R2)
        I1, I2 = 0.4 * m1 * R1 ** 2, 0.4 * m2 * R2 ** 2
        wt = 1 / m1 + R1 ** 2 / I1 + (0 if fixed_second else 1 / m2 + R2 ** 2 / I2)
        meff = m1 if fixed_second else m1 * m2 / (m1 + m2)
        g = lambda fr, i, k: fr[i][k]
        # contact point of 1 (at +R1 x): v1 + w1 y x R1 x = vz1 - R1 w1 ; of 2 (at -R2 x): vz2 + R2 w2
        s0 = np.array([(g(first, a, "vz") - R1 * g(first, a, "omegay")) - (g(first, b, "vz") + R2 * g(first, b, "omegay"))
                       for a, b in lst])
        w10 = np.array([g(first, a, "omegay") for a, b in lst])
        ys, gs = ystar_gstar(mat, mat)
        reff = R1 * R2 / (R1 + R2)
        jt_rb, _ = rigid_body(s0, vn_rel, e, mu, meff, wt)
        jt_ref = mindlin_reference(s0, vn_rel, e, mu, meff, wt, ys, gs, reff)
        d = {"s0": s0, "w0": w10,
             "vz1": np.array([g(last, a, "vz") for a, b in lst]), "w1": np.array([g(last, a, "omegay") for a, b in lst]),
             "vx1": np.array([g(last, a, "vx") for a, b in lst])}
        # impulse -jt on 1 along z (opposing its slip), lever R1 x: d w1 = R1 jt / I1 ... sign: torque of
        # F = -jt z at r = R1 x is R1 x x (-jt z) = R1 jt y
        for tag, jt in (("rb", jt_rb), ("ref", jt_ref)):
            d["vz1_" + tag] = -jt / m1
            d["w1_" + tag] = w10 + R1 * jt / I1
        sense = "" if n == 8 else ("opposite" if block < 2 else "same")
        res[(mat, sense)] = d
    return res


# -------------------------------------------------------------------------------------------------- main
def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join(ROOT, "docs"))
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "chung_ooi"))
    ap.add_argument("--no-plots", action="store_true")
    args = ap.parse_args(argv)
    os.makedirs(args.work, exist_ok=True)
    datadir = os.path.join(args.out, "data", "chung_ooi")
    figdir = os.path.join(args.out, "figures")
    os.makedirs(datadir, exist_ok=True)
    os.makedirs(figdir, exist_ok=True)
    t0 = time.time()
    report = []

    # tests 1, 2
    normal = {}
    for n in (1, 2):
        rows, curves = test_normal(n, args.work)
        normal[n] = (rows, curves)
        with open(os.path.join(datadir, f"test{n}.csv"), "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["material", "tc_hertz_s", "tc_dem_s", "dmax_hertz_m", "dmax_dem_m", "fmax_hertz_N", "fmax_dem_N"])
            for mat, th, me in rows:
                w.writerow([mat, th[2], me[0], th[0], me[1], th[1], me[2]])
                report.append(f"test {n} {mat}: t_c {me[0]*1e6:.3f} us (Hertz {th[2]*1e6:.3f}, {me[0]/th[2]-1:+.2%}), "
                              f"delta_max {me[1]*1e6:.3f} um ({me[1]/th[0]-1:+.1e}), F_max {me[2]:.1f} N ({me[2]/th[1]-1:+.1e})")
    # test 3
    rest = {law: test_restitution(args.work, law) for law in ("hertz", "hooke")}
    with open(os.path.join(datadir, "test3.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["law", "material", "en", "rebound_ratio"])
        for law, rows in rest.items():
            for mat, en, r in rows:
                w.writerow([law, mat, en, r])
            report.append(f"test 3 {law}: max |e - en| = {max(abs(r - en) for _, en, r in rows):.1e}")
    # tests 4-6
    t4 = {}
    for law in ("hertz", "hooke"):
        t4[law] = oblique_wall(4, args.work, ["al_oxide"], 0.0025, 3.9, 0.98, 0.092, [("law", law)])["al_oxide"]
        os.replace(os.path.join(args.work, "chung_ooi_4.txt"), os.path.join(args.work, f"chung_ooi_4_{law}.txt"))
    t5 = oblique_wall(5, args.work, ["steel", "polyethylene"], 1e-5, 5.0, 1.0, 0.3)
    t6 = oblique_wall(6, args.work, ["al_alloy", "nylon"], 0.1, 0.2, 0.5, 0.4)
    t7 = pairs(7, args.work, ["al_alloy", "copper"], 0.1, 0.1, 0.4, 0.5, 0.4, False)
    t8 = pairs(8, args.work, ["al_alloy", "nylon"], 0.1, 0.5, 0.2, 0.5, 0.4, True)

    def dump_csv(name, table):
        keys = list(table.keys())
        with open(os.path.join(datadir, name), "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(keys)
            for row in zip(*(table[k] for k in keys)):
                w.writerow(["%.8g" % x for x in row])

    for law, d in t4.items():
        th = np.degrees(np.arctan2(d["s0"], d["vn0"]))
        dump_csv(f"test4_{law}.csv", {"incidence_deg": th, **{k: d[k] for k in ("vx", "vz", "w", "vx_rb", "w_rb", "vx_ref", "w_ref")}})
    for name, res in (("test5", t5), ("test6", t6)):
        for mat, d in res.items():
            dump_csv(f"{name}_{mat}.csv", {k: d[k] for k in ("s0", "vn0", "vx", "vz", "w", "vx_rb", "w_rb", "vx_ref", "w_ref")})
    for name, res in (("test7", t7), ("test8", t8)):
        for (mat, sense), d in res.items():
            dump_csv(f"{name}_{mat}{'_' + sense if sense else ''}.csv", d)

    # agreement numbers
    def worst(d, a, b, scale):
        return float(np.max(np.abs(d[a] - d[b])) / scale)

    for law, d in t4.items():
        slide = np.abs(d["s0"]) > 3.5 * 0.092 * 1.98 * d["vn0"] * 1.02
        report.append(f"test 4 {law}: gross sliding ({slide.sum()} angles) |v't - rigid| <= "
                      f"{worst({k: v[slide] for k, v in d.items()}, 'vx', 'vx_rb', 3.9):.1e} V; all angles vs Mindlin "
                      f"reference <= {worst(d, 'vx', 'vx_ref', 3.9):.1e} V, R w' <= "
                      f"{worst(d, 'w', 'w_ref', 3.9 / 0.0025):.1e} V")
    for name, res, R, mu, e, vn in (("test 5", t5, 1e-5, 0.3, 1.0, 5.0), ("test 6", t6, 0.1, 0.4, 0.5, 0.2)):
        for mat, d in res.items():
            scale = mu * (1 + e) * vn
            report.append(f"{name} {mat}: |v't - Mindlin reference| <= {worst(d, 'vx', 'vx_ref', scale):.1e} mu(1+e)v_n, "
                          f"R|w' - ref| <= {worst(d, 'w', 'w_ref', scale / R):.1e} mu(1+e)v_n; vs rigid body "
                          f"{worst(d, 'vx', 'vx_rb', scale):.2f}")
    for name, res in (("test 7", t7), ("test 8", t8)):
        for (mat, sense), d in res.items():
            scale = 0.4 * 1.5 * (0.4 if name == "test 7" else 0.2)
            report.append(f"{name} {mat} {sense}: |v'z - ref| <= {worst(d, 'vz1', 'vz1_ref', scale):.1e}, "
                          f"R|w' - ref| <= {worst(d, 'w1', 'w1_ref', scale / 0.1):.1e} mu(1+e)v_n")

    if not args.no_plots:
        plots(figdir, normal, rest, t4, t5, t6, t7, t8)
    report.append(f"total {time.time() - t0:.1f} s")
    with open(os.path.join(datadir, "summary.txt"), "w") as f:
        f.write("\n".join(report) + "\n")
    print("\n".join(report))


def plots(figdir, normal, rest, t4, t5, t6, t7, t8):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    def save(fig, name):
        fig.tight_layout()
        fig.savefig(os.path.join(figdir, name), dpi=90)
        plt.close(fig)

    for n in (1, 2):
        fig, ax = plt.subplots(figsize=(5, 3.6))
        for mat, gap, f, ys, reff in normal[n][1]:
            d = np.linspace(0, gap.max(), 100)
            ax.plot(d * 1e6, 4 / 3 * ys * math.sqrt(reff) * d ** 1.5 / 1e3, "k-", lw=1)
            sel = gap > 0
            ax.plot(gap[sel][::8] * 1e6, f[sel][::8] / 1e3, "o", ms=3, label=f"dem, {mat.split('_')[0]}")
        ax.plot([], [], "k-", label="Hertz")
        ax.set_xlabel("overlap (um)")
        ax.set_ylabel("normal force (kN)")
        ax.set_title(f"Chung & Ooi test {n}")
        ax.legend()
        save(fig, f"chung_ooi_{n}.png")

    fig, ax = plt.subplots(figsize=(5, 3.6))
    ax.plot([0, 1], [0, 1], "k-", lw=1, label="e = en")
    for law, mk in (("hertz", "o"), ("hooke", "x")):
        for mat in ("al_oxide", "cast_iron"):
            pts = [(en, r) for m, en, r in rest[law] if m == mat]
            ax.plot(*zip(*pts), mk, label=f"dem {law}, {mat}")
    ax.set_xlabel("restitution coefficient given (en)")
    ax.set_ylabel("rebound ratio -v'/v")
    ax.set_title("Chung & Ooi test 3")
    ax.legend(fontsize=7)
    save(fig, "chung_ooi_3.png")

    fig, axs = plt.subplots(1, 3, figsize=(12, 3.6))
    R = 0.0025
    for law, mk in (("hertz", "o"), ("hooke", "x")):
        d = t4[law]
        th = np.degrees(np.arctan2(d["s0"], d["vn0"]))
        for ax, y, yrb, yref in ((axs[0], d["vx"] / d["vx0"], d["vx_rb"] / d["vx0"], d["vx_ref"] / d["vx0"]),
                                 (axs[1], d["w"], d["w_rb"], d["w_ref"]),
                                 (axs[2], np.degrees(np.arctan((d["vx"] - R * d["w"]) / d["vz"])),
                                  np.degrees(np.arctan((d["vx_rb"] - R * d["w_rb"]) / d["vz_rb"])),
                                  np.degrees(np.arctan((d["vx_ref"] - R * d["w_ref"]) / d["vz_ref"])))):
            ax.plot(th, y, mk, label=f"dem {law}")
            if law == "hertz":
                ax.plot(th, yrb, "k--", lw=1, label="rigid body")
                ax.plot(th, yref, "k-", lw=1, label="Hertz-Mindlin, t_c/20000")
    for ax, lab in zip(axs, ("tangential restitution v't/vt", "spin after (rad/s)", "rebound angle of the contact point (deg)")):
        ax.set_xlabel("incidence (deg)")
        ax.set_ylabel(lab)
    axs[0].legend(fontsize=7)
    fig.suptitle("Chung & Ooi test 4 (Al oxide, 3.9 m/s)")
    save(fig, "chung_ooi_4.png")

    for name, res, R, mu, e in (("5", t5, 1e-5, 0.3, 1.0), ("6", t6, 0.1, 0.4, 0.5)):
        fig, axs = plt.subplots(1, 2, figsize=(9, 3.6))
        for mat, d in res.items():
            vn = d["vn0"]
            if name == "5":
                x = d["s0"] / (mu * vn)
                ys = [((d["vx"] - R * d["w"]) / (mu * d["vz"]), (d["vx_ref"] - R * d["w_ref"]) / (mu * d["vz_ref"]),
                       (d["vx_rb"] - R * d["w_rb"]) / (mu * d["vz_rb"])),
                      (R * d["w"] / (mu * vn), R * d["w_ref"] / (mu * vn), R * d["w_rb"] / (mu * vn))]
                labs = ("v'_ct / (mu v'_n)", "R w' / (mu v_n)")
                xl = "v_t / (mu v_n)"
            else:
                x = d["s0"] / vn
                ys = [((d["vx"] - R * d["w"]) / d["vz"], (d["vx_ref"] - R * d["w_ref"]) / d["vz_ref"],
                       (d["vx_rb"] - R * d["w_rb"]) / d["vz_rb"]),
                      (d["w"], d["w_ref"], d["w_rb"])]
                labs = ("tan recoil v'_st / v'_n", "spin after (rad/s)")
                xl = "tan incidence v_st / v_n"
            for ax, (y, yref, yrb), lab in zip(axs, ys, labs):
                l, = ax.plot(x, y, "o", ms=4, label=f"dem, {mat}")
                ax.plot(x, yref, "-", color=l.get_color(), lw=1)
                ax.plot(x, yrb, "--", color=l.get_color(), lw=1)
                ax.set_xlabel(xl)
                ax.set_ylabel(lab)
        axs[0].plot([], [], "k-", label="Hertz-Mindlin, t_c/20000")
        axs[0].plot([], [], "k--", label="rigid body")
        axs[0].legend(fontsize=7)
        if name == "5":
            axs[0].set_xlim(0, 14)
            axs[1].set_xlim(0, 20)
        fig.suptitle(f"Chung & Ooi test {name}")
        save(fig, f"chung_ooi_{name}.png")

    for name, res in (("7", t7), ("8", t8)):
        fig, axs = plt.subplots(1, 2, figsize=(9, 3.6))
        for (mat, sense), d in res.items():
            x = d["w0"]
            for ax, y, yref, yrb, lab in ((axs[0], d["vz1"], d["vz1_ref"], d["vz1_rb"], "tangential velocity after, sphere 1 (m/s)"),
                                          (axs[1], d["w1"], d["w1_ref"], d["w1_rb"], "spin after, sphere 1 (rad/s)")):
                l, = ax.plot(x, y, "o", ms=4, label=f"dem, {mat} {sense}")
                ax.plot(x, yref, "-", color=l.get_color(), lw=1)
                ax.plot(x, yrb, "--", color=l.get_color(), lw=1)
                ax.set_xlabel("initial spin w0 (rad/s)")
                ax.set_ylabel(lab)
                ax.set_xscale("log")
        axs[0].plot([], [], "k-", label="Hertz-Mindlin, t_c/20000")
        axs[0].plot([], [], "k--", label="rigid body")
        axs[0].legend(fontsize=7)
        fig.suptitle(f"Chung & Ooi test {name}")
        save(fig, f"chung_ooi_{name}.png")


if __name__ == "__main__":
    main()
