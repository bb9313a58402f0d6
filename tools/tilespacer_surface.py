"""Free surface of the tile-spacer drum (inputs/in.tilespacer_drum; Part III sec 3.4, Fig. 15-16) from its
HDF5 dump, as the paper takes it from its pictures: the bed seen along the drum axis, the highest point of
any tile spacer in each column is the free surface.

    python tools/tilespacer_surface.py tiles.h5 [--radius 0.15] [--bin 0.005] [--after T] [--out tiles]

The posed surfaces of the dump (the corners of each spacer's two plates and points along the edges of its
triangles) are projected on the cross-section (x, z); the bed's horizontal extent is cut into columns of
width --bin, and the highest point in each column marks the surface. A least-squares line through the
columns of the central 70 % of the extent (as `compute repose`) gives the angle of each frame (signed:
positive when the surface rises towards +x). Written: OUT_surface.csv (time, signed angle, then the
profile heights of every column centre, NaN where a column is empty), OUT_surface.png (profiles every
0.5 s, drawn as dem's pictures show the drum: x growing to the left, and the angle against time) and, on
the screen, the statistics of the angle's magnitude from --after s of rotation on (default: from the first
avalanche, leaving out the ramp and the bed's first tilt as a block): mean, standard deviation, range,
and the avalanches (falls of the magnitude by more than 3 degrees within 0.25 s).
"""
import argparse
import sys

import numpy as np

TRIM = 0.15            # fraction of the bed's extent left out at each end of the line fit (compute repose)
FALL = 3.0             # degrees: an avalanche is a fall of the angle by more than this ...
WINDOW = 0.25          # ... within this many seconds
EDGE_SAMPLES = 4       # points along each triangle edge, besides its ends


def frame_points(g):
    """World points of a frame's posed surfaces: the vertices and EDGE_SAMPLES points along each edge."""
    s = g["surface"]
    pts = s["points"][()]
    tri = s["triangles"][()]
    out = [pts]
    for a, b in ((0, 1), (1, 2), (2, 0)):
        pa, pb = pts[tri[:, a]], pts[tri[:, b]]
        for k in range(1, EDGE_SAMPLES + 1):
            f = k / (EDGE_SAMPLES + 1)
            out.append(pa + f * (pb - pa))
    return np.concatenate(out)


def surface_profile(x, z, width, radius):
    """Column centres across the drum (width `width`, from -radius to radius) and the highest z in each
    (NaN where empty)."""
    edges = np.arange(-radius, radius + 0.5 * width, width)
    centres = 0.5 * (edges[1:] + edges[:-1])
    top = np.full(len(centres), np.nan)
    k = np.clip(np.digitize(x, edges) - 1, 0, len(centres) - 1)
    order = np.argsort(z)                   # the last write of each column is its highest point
    top[k[order]] = z[order]
    return centres, top


def surface_angle(centres, top, trim=TRIM):
    """Angle (degrees) of the least-squares line through the central columns of the occupied extent."""
    ok = np.isfinite(top)
    if ok.sum() < 3:
        return np.nan
    lo, hi = centres[ok].min(), centres[ok].max()
    span = hi - lo
    use = ok & (centres >= lo + trim * span) & (centres <= hi - trim * span)
    if use.sum() < 2:
        return np.nan
    slope = np.polyfit(centres[use], top[use], 1)[0]
    return float(np.degrees(np.arctan(slope)))


def avalanches(t, angle, fall=FALL, window=WINDOW):
    """Times at which the angle has fallen by more than `fall` degrees from its maximum over the previous
    `window` seconds (each fall counted once: the next one must start after the angle rose again)."""
    out = []
    armed = True
    for i in range(len(t)):
        back = (t >= t[i] - window) & (t <= t[i])
        peak = np.nanmax(angle[back])
        if armed and peak - angle[i] > fall:
            out.append(t[i])
            armed = False
        elif not armed and angle[i] >= peak - 0.5:
            armed = True
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dump")
    ap.add_argument("--radius", type=float, default=0.15)
    ap.add_argument("--bin", type=float, default=0.005)
    ap.add_argument("--after", type=float, default=None,
                    help="statistics from this time of rotation on (s; default: from the first avalanche)")
    ap.add_argument("--out", default=None, help="prefix of the outputs (default: the dump's name)")
    a = ap.parse_args(argv)
    import h5py
    rows = []
    with h5py.File(a.dump, "r", locking=False) as f:
        for name in sorted(f["frames"], key=int):
            g = f["frames"][name]
            p = frame_points(g)
            c, top = surface_profile(p[:, 0], p[:, 2], a.bin, a.radius)
            rows.append((float(g.attrs["time"]), surface_angle(c, top), top))
    if not rows:
        raise SystemExit(f"{a.dump}: no frame")
    t = np.array([r[0] for r in rows])
    t -= t[0]                                          # time of rotation (the dump starts with it)
    angle = np.array([r[1] for r in rows])
    tops = np.array([r[2] for r in rows])
    prefix = a.out or a.dump.rsplit(".", 1)[0]
    np.savetxt(prefix + "_surface.csv", np.column_stack([t, angle, tops]), delimiter=",",
               header="time_s,angle_deg," + ",".join(f"z_at_{x * 1000:.1f}mm" for x in c), comments="")
    mag = np.abs(angle)
    if a.after is None:                                # the bed tilts as a block until its first avalanche
        first = avalanches(t, mag)
        a.after = first[0] if first else 0.0
    late = t >= a.after
    aval = avalanches(t[late], mag[late])
    if late.any():
        v = mag[late]
        print(f"{len(t)} frames over {t[-1]:.2f} s of rotation; from {a.after:.3f} s on ({late.sum()} frames): "
              f"angle mean {np.nanmean(v):.1f} deg, std {np.nanstd(v):.1f}, range {np.nanmin(v):.1f} to "
              f"{np.nanmax(v):.1f}; {len(aval)} avalanches (falls > {FALL} deg within {WINDOW} s) at "
              + ", ".join(f"{x:.2f}" for x in aval) + " s")
    else:
        print(f"{len(t)} frames over {t[-1]:.2f} s: none after {a.after} s")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    th = np.linspace(0, 2 * np.pi, 200)
    ax1.plot(a.radius * 1000 * np.cos(th), a.radius * 1000 * np.sin(th), color="0.6", lw=1)
    picks = np.unique(np.searchsorted(t, np.arange(0.0, t[-1] + 1e-9, 0.5)))
    cmap = plt.get_cmap("viridis")
    for n, i in enumerate(picks):
        ax1.plot(c * 1000, tops[i] * 1000, color=cmap(n / max(len(picks) - 1, 1)), lw=1.2, label=f"{t[i]:.1f} s")
    ax1.set_aspect("equal")
    ax1.invert_xaxis()                                 # as dem's pictures: seen along +y, -x to the right
    ax1.set_xlabel("x (mm)")
    ax1.set_ylabel("z (mm)")
    ax1.set_title(f"free surface (highest point per {a.bin * 1000:g} mm column)")
    ax1.legend(fontsize=7, ncol=2, loc="lower left")
    ax2.plot(t, mag, lw=1)
    for x in aval:
        ax2.axvline(x, color="r", lw=0.6, alpha=0.5)
    ax2.set_xlabel("time of rotation (s)")
    ax2.set_ylabel("|surface angle| (deg)")
    ax2.set_title("angle of the free surface (red: avalanches)")
    fig.tight_layout()
    fig.savefig(prefix + "_surface.png", dpi=110)
    print(f"wrote {prefix}_surface.csv and {prefix}_surface.png")


if __name__ == "__main__":
    sys.exit(main())
