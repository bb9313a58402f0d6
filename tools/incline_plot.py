"""Figures and bulk values of pinacoid flows down a rough incline (inputs/in.incline; Descantes 2022 Figs.
11-16): profiles of solid fraction, coordination, velocity (with a Bagnold fit), spin against
-gamma_dot/2, stresses against the weight of the layer, stress ratio against tan(theta), inertial number
and granular temperature, the kinetic energy in time, and the bulk coordination and solid fraction
against the inertial number next to the paper's fits.

    python tools/incline_plot.py PREFIX [PREFIX ...] [-o FIGURE.png] [--table] [--dpi 80]
                                 [--panels all|profiles|bulk] [--palette N]

Each PREFIX is one run (one tilt): PREFIX.profile.dat, PREFIX.phi.dat (fix ave/profile, the last block:
the final average), PREFIX.series.dat (fix print/series) and PREFIX.summary.txt (theta, d_eq...), as the
input writes them, or the .dat files' copies ending in .txt (as kept in docs/data). Heights are from the
floor, in d_eq. The bulk is the band from 5 d_eq (the paper's "z > 5 d_eq") to 2 d_eq below the free
surface, the surface being the highest bin whose solid fraction is at least half the largest one of the
profile. sigma_zz is drawn as computed (contacts, Moreau) and with its kinetic part rho phi T_zz added,
which steady flow balances against the weight of the layer above (rho g cos(theta) times the solid above
z). `--table` prints the bulk values as a Markdown table.

Flow or not, from the kinetic energy series: "arrested" when the mean downslope velocity of the layer is
below 0.05 sqrt(g d_eq) at the end, "accelerating" / "slowing" when its kinetic energy grows or falls by
more than 10 % per 10 T_inertia (a straight line through log KE from 10 T_inertia after the tilt to the
end: the runs of inputs/in.incline start from a layer still landing, see docs/validation.md), "steady"
otherwise (the 10 % is this tool's choice, stated so). The table also gives the change of the mean
kinetic energy over the averaging window from the window before it.

The averages: fix ave/profile writes on steps that are multiples of Nfreq (as LAMMPS's fix ave/chunk),
so the last block covers the whole window only when the window starts on such a step; the tool says so
when the last block ends before the series does or covers less than the window.
"""
import argparse

import numpy as np

from dem.tools.profile_files import data_file, last_block

BULK_FROM = 5.0          # d_eq above the floor (Descantes sec. 3.2.2)
BELOW_SURFACE = 2.0      # d_eq: the top of the bulk band under the free surface
TREND_FROM = 10.0        # T_inertia after the tilt: the kinetic energy's trend is fitted from there on
PINACOID_VOLUME = 0.5 ** 1.5 / 6 * (3 - 1 / np.tan(np.pi / 3))   # d_sph^3, the input's V


def nfreq_of(path):
    """Nfreq of a fix ave/profile file, from its header ("... written every N"), or None."""
    with open(path) as f:
        for line in f:
            if not line.startswith("#"):
                break
            if "written every" in line:
                return int(line.split("written every")[1].split()[0])
    return None


def series(path):
    with open(path) as f:
        names = f.readline()[1:].split()
    a = np.atleast_2d(np.loadtxt(path, comments="#"))
    return {n: a[:, k] for k, n in enumerate(names)}


def summary(path):
    words = open(path).read().split()
    return {k: float(v) for k, v in zip(words[::2], words[1::2])}


def bagnold(zb, v, h):
    """Least-squares fit of v = v0 + A (h^1.5 - (h - zb)^1.5), zb the height above the flow's base and
    h its depth (Bagnold's profile, Silbert et al. 2001): v0 (slip at the base), A and R^2."""
    shape = h ** 1.5 - np.clip(h - zb, 0, None) ** 1.5
    m = np.column_stack([np.ones_like(zb), shape])
    (v0, a), *_ = np.linalg.lstsq(m, v, rcond=None)
    fit = v0 + a * shape
    r2 = 1 - ((v - fit) ** 2).sum() / ((v - v.mean()) ** 2).sum()
    return v0, a, r2


def run(prefix):
    """One run's profiles (heights in d_eq, velocities in sqrt(g d_eq), stresses in rho g d_sph) and bulk
    values."""
    s = summary(prefix + ".summary.txt")
    p = last_block(data_file(prefix, "profile"))
    phi = last_block(data_file(prefix, "phi"))["phi"]
    ts = series(data_file(prefix, "series"))
    deq = s["deq"]
    z = p["coord"] / deq
    dz = (z[1] - z[0]) * deq
    surface = z[np.nonzero(phi >= 0.5 * phi.max())[0].max()]
    bulk = (z >= BULK_FROM) & (z <= surface - BELOW_SURFACE)
    vy = p["vy"] / np.sqrt(deq)
    gdot = np.gradient(p["vy"], dz)
    th = np.radians(s["theta"])
    weight = np.cumsum(phi[::-1])[::-1] * dz - 0.5 * phi * dz          # rho g times the solid above
    mu = np.abs(p["syz"]) / p["szz"]
    # the kinetic part of sigma_zz, rho phi T_zz (rho = 1), for the momentum balance against the weight
    szz_kin = p["szz"] + phi * p["Tzz"]
    # the flow's base: the lowest bin moving at more than 5 % of the fastest one (below it the layer
    # rests on the substrate)
    fast = np.nan_to_num(vy) > 0.05 * np.nanmax(vy)
    base = z[np.argmax(fast)] if fast.any() else z[0]
    flowing = (z >= base) & (z < surface) & np.isfinite(vy)
    v0, a, r2 = bagnold(z[flowing] - base, vy[flowing], surface - base)
    w = lambda x: float(np.nanmean(x[bulk])) if bulk.any() else float("nan")
    out = dict(theta=s["theta"], z=z, phi=phi, vy=vy, wx=p["wx"] * np.sqrt(deq),
               half_gdot=-0.5 * gdot * np.sqrt(deq), szz=p["szz"], syz=np.abs(p["syz"]),
               sxx=p["sxx"], syy=p["syy"], weight=weight * np.cos(th), mu=mu, I=p["I"],
               T=p["T"] / deq, ztot=p["ztot"], zs=p["zs"], zd=p["zd"], zt=p["zt"], bulk=bulk,
               surface=surface, base=base, t=(ts["time"] - ts["time"][0]) / np.sqrt(deq), ke=ts["c_ke"],
               bagnold=(v0, a, r2), maxov=float(ts["maxov"].max()))
    out["szz_kin"] = szz_kin
    # kinetic energy per flowing particle in rho V g d_eq (V the mean pinacoid's volume, 0.1428 d_sph^3)
    out["ke_per"] = ts["c_ke"] / (s["N"] * PINACOID_VOLUME * deq)
    out.update(balance=w(szz_kin / out["weight"]), phi_b=w(phi), z_b=w(p["ztot"]), I_b=w(p["I"]), mu_b=w(mu),
               v_max=float(np.nanmax(vy)),
               zs_b=w(p["zs"]), zd_b=w(p["zd"]), zt_b=w(p["zt"]))
    # spin against -gamma_dot/2 in the bulk (Fig. 13b): the ratio of the band's means
    out["spin_ratio"] = w(out["wx"]) / w(out["half_gdot"])
    # steadiness: the kinetic energy over the averaging window against the window before it
    t_avg = s["avg"] * np.sqrt(deq)
    t = ts["time"]
    last = t >= t[-1] - t_avg
    before = (t >= t[-1] - 2 * t_avg) & ~last
    out["ke_drift"] = (float(ts["c_ke"][last].mean() / ts["c_ke"][before].mean() - 1) if before.any()
                       else np.nan)
    out["v_mean"] = float(ts["c_v[3]"][last].mean() / np.sqrt(deq))
    out["v_end"] = float(ts["c_v[3]"][-1] / np.sqrt(deq))
    out["v_drift"] = (float(ts["c_v[3]"][last].mean() / ts["c_v[3]"][before].mean() - 1)
                      if before.any() and ts["c_v[3]"][before].mean() > 0 else np.nan)
    out["maxov_last"] = float(ts["maxov"][last].max())
    # the trend: a straight line through log(KE) from TREND_FROM T_inertia after the tilt to the end, as the
    # change of KE per 10 T_inertia
    late = out["t"] >= TREND_FROM
    if late.sum() > 2 and np.all(ts["c_ke"][late] > 0):
        slope = np.polyfit(out["t"][late], np.log(ts["c_ke"][late]), 1)[0]
        out["ke_trend"] = float(np.exp(10 * slope) - 1)
    else:
        out["ke_trend"] = np.nan
    if out["v_end"] < 0.05:
        out["verdict"] = "arrested"
    elif out["ke_trend"] > 0.10:
        out["verdict"] = "accelerating"
    elif out["ke_trend"] < -0.10:
        out["verdict"] = "slowing"
    else:
        out["verdict"] = "steady"
    # does the profiles' last block average the whole window? (blocks are written on multiples of Nfreq)
    nfreq = nfreq_of(data_file(prefix, "profile"))
    step_end = int(ts["step"][-1])
    step_prof = int(last_block(data_file(prefix, "profile"))["step"][0])
    dt = float((t[-1] - t[0]) / (ts["step"][-1] - ts["step"][0]))
    window_steps = int(round(t_avg / dt))
    covered = min(nfreq or window_steps, step_prof - (step_end - window_steps))
    out["profile_window"] = covered / window_steps
    if step_prof != step_end or covered < window_steps:
        print(f"WARNING: {data_file(prefix, 'profile')}: the last block (step {step_prof}) averages {covered} "
              f"of the window's {window_steps} steps (the run ends at step {step_end}; blocks are written on "
              f"multiples of Nfreq = {nfreq}): the profiles are not the average of the last "
              f"{s['avg']:g} T_inertia")
    return out


def table(runs):
    print("| tilt | flow (KE per 10 T_inertia from 10 T_inertia on; over the last window) | "
          "mean v_y / sqrt(g d_eq) | v_max / sqrt(g d_eq) | "
          "bulk solid fraction | bulk Z | shares s/d/t % | bulk I | bulk syz/szz | tan | "
          "w_x / (-gamma_dot/2) | Bagnold R^2 | sigma_zz (+ kinetic) / weight | largest overlap / d_sph |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in runs:
        tot = r["zs_b"] + r["zd_b"] + r["zt_b"]
        sh = "/".join(f"{100 * r[k] / tot:.0f}" for k in ("zs_b", "zd_b", "zt_b")) if tot > 0 else "-"
        print(f"| {r['theta']:g} | {r['verdict']} ({100 * r['ke_trend']:+.0f} %; "
              f"{100 * r['ke_drift']:+.0f} %) | "
              f"{r['v_mean']:.2f} | "
              f"{r['v_max']:.2f} | {r['phi_b']:.3f} | {r['z_b']:.2f} | {sh} | {r['I_b']:.2f} | "
              f"{r['mu_b']:.3f} | {np.tan(np.radians(r['theta'])):.3f} | {r['spin_ratio']:.2f} | "
              f"{r['bagnold'][2]:.3f} | "
              f"{r['balance']:.3f} | {r['maxov_last']:.1e} |")


class _Skip:
    """Stands for a panel that is not drawn."""
    def __getattr__(self, name):
        return lambda *args, **kw: None


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("prefix", nargs="+")
    ap.add_argument("-o", "--output", default="incline_profiles.png")
    ap.add_argument("--table", action="store_true")
    ap.add_argument("--dpi", type=float, default=80)
    ap.add_argument("--palette", type=int, default=0, metavar="N",
                    help="save the PNG with a palette of N colours (Pillow; 64 keeps the figures of "
                         "docs/figures small), 0: full colour")
    ap.add_argument("--panels", choices=("all", "profiles", "bulk"), default="all",
                    help="all ten panels, the eight profiles (Figs. 12-14, 16a, 16d) or the two others "
                         "(kinetic energy in time, Fig. 16b-c)")
    a = ap.parse_args(argv)
    runs = sorted((run(p) for p in a.prefix), key=lambda r: r["theta"])
    if a.table:
        table(runs)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    chosen = {"all": range(10), "profiles": range(8), "bulk": (8, 9)}[a.panels]
    shape, size = {"all": ((2, 5), (22, 9)), "profiles": ((2, 4), (17.6, 9)),
                   "bulk": ((1, 2), (11, 4.5))}[a.panels]
    fig, axes = plt.subplots(*shape, figsize=size)
    ax = [_Skip()] * 10
    for k, axis in zip(chosen, axes.ravel()):
        ax[k] = axis
    colours = plt.cm.viridis(np.linspace(0, 0.9, len(runs)))
    for r, c in zip(runs, colours):
        lab = f"{r['theta']:g}°"
        z = r["z"]
        ax[0].plot(r["phi"], z, color=c, label=lab)
        ax[1].plot(r["ztot"], z, color=c, label=lab)
        ax[2].plot(r["vy"], z, color=c, label=lab)
        v0, A, _ = r["bagnold"]
        zb = np.clip(z - r["base"], 0, r["surface"] - r["base"])
        h = r["surface"] - r["base"]
        sel = (z >= r["base"]) & (z < r["surface"])
        ax[2].plot((v0 + A * (h ** 1.5 - (h - zb) ** 1.5))[sel], z[sel], ":", color=c)
        ax[3].plot(r["wx"], z, color=c, label=lab)
        ax[3].plot(r["half_gdot"], z, ":", color=c)
        ax[4].plot(r["szz"], z, color=c, label=lab)
        ax[4].plot(r["syz"], z, "--", color=c)
        ax[4].plot(r["szz_kin"], z, "-.", color=c)
        ax[4].plot(r["weight"], z, ":", color=c)
        ax[5].plot(r["mu"], z, color=c, label=lab)
        ax[5].axvline(np.tan(np.radians(r["theta"])), color=c, ls=":")
        ax[6].plot(r["I"], z, color=c, label=lab)
        ax[7].plot(r["T"], z, color=c, label=lab)
        ax[8].plot(r["t"], r["ke_per"], color=c, label=lab)
        ax[9].plot(r["I_b"], r["z_b"], "o", color=c)
        ax[9].plot(r["I_b"], 10 * r["phi_b"], "s", color=c)
    i = np.linspace(0, 1.2, 50)
    ax[9].plot(i, 4.5 - 3.62 * np.sqrt(i), "k:", label="Z = 4.5 - 3.62 I^0.5 (paper)")
    ax[9].plot(i, 10 * (0.50 - 0.07 * i), "k--", label="10 nu = 10 (0.50 - 0.07 I) (paper)")
    ax[9].set(xlabel="bulk I", ylabel="bulk Z (o), 10 x solid fraction (s)", title="Fig. 16b-c")
    titles = [("solid fraction", "Fig. 12a"), ("coordination Z", "Fig. 12b"),
              ("v_y / sqrt(g d_eq) (: Bagnold fit)", "Fig. 13a"),
              ("w_x sqrt(d_eq/g) (: -gamma_dot/2)", "Fig. 13b"),
              ("sigma_zz, + kinetic (-.), |sigma_yz| (--), weight (:)", "Fig. 14a"),
              ("|sigma_yz| / sigma_zz (: tan theta)", "Fig. 14b"), ("inertial number I", "Fig. 16a"),
              ("granular temperature T / (g d_eq)", "Fig. 16d")]
    for k, (xl, tt) in enumerate(titles):
        ax[k].set(xlabel=xl, ylabel="z / d_eq", title=tt)
        ax[k].axhline(BULK_FROM, color="0.8", lw=0.8)
    top = max(r["surface"] for r in runs) + 3
    for k in range(8):
        ax[k].set_ylim(0, top)
    ax[5].set_xlim(0, 1.5)
    ax[6].set_xlim(0, 2)
    ax[8].set(xlabel="t / T_inertia (after the tilt)", ylabel="kinetic energy per particle / (rho V g d_eq)",
              yscale="log", title="Fig. 11b")
    for k in (0, 8, 9):
        ax[k].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.output, dpi=a.dpi)
    if a.palette:
        from PIL import Image
        Image.open(a.output).convert("RGB").quantize(colors=a.palette).save(a.output, optimize=True)
    print("wrote", a.output)
    return runs


if __name__ == "__main__":
    main()
