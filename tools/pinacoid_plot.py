"""Figures of a pinacoid packing (inputs/in.pinacoid_packing; Descantes 2022 Figs. 7-9): the solid fraction
profile, the stress profiles against the hydrostatic weight of the bed, the coordination by contact type
along z and the pair correlation g(r), from the files the input writes.

    python tools/pinacoid_plot.py PREFIX [-o FIGURE.png] [--deq D]

PREFIX.profile.dat (fix ave/profile: step time bin coord phi szz sxx syy count zs zd zt ztot ziso) and
PREFIX.rdf.dat (fix ave/vector of compute rdf), or the same names ending in .txt (the copies kept in
docs/data); the last block of each (the final average) is drawn.
Heights are in d_eq (default 0.6484, the input's mean pinacoid, d_sph = 1). Hydrostatic reference:
sigma_zz(z) = rho g integral_z^top phi dz (rho = g = 1), the weight of the solid above z per unit area.
g(r): compute rdf normalises by the number density of the whole box, which is partly empty above the
bed; the curve is drawn divided by its mean over the outer quarter of its range (so it tends to 1 there:
a shape, not the paper's absolute level, which is normalised on the packing).
"""
import argparse

import numpy as np

from dem.shapes import pinacoid_volume
from dem.tools.profile_files import data_file, last_block

DEQ = (6 * pinacoid_volume(*3 * [0.5 ** 0.5], 60.0) / np.pi) ** (1 / 3)   # the input's mean pinacoid


def hydrostatic(z, phi):
    """rho g times the solid above each bin centre (rho = g = 1), by the trapezoid rule from the top."""
    dz = z[1] - z[0]
    above = np.cumsum(phi[::-1])[::-1] * dz - 0.5 * phi * dz
    return above


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("prefix")
    ap.add_argument("-o", "--output", default=None)
    ap.add_argument("--deq", type=float, default=DEQ)
    a = ap.parse_args(argv)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    p = last_block(data_file(a.prefix, "profile"))
    g = last_block(data_file(a.prefix, "rdf"))
    z = p["coord"] / a.deq
    fig, ax = plt.subplots(1, 4, figsize=(15, 4.2))
    ax[0].plot(p["phi"], z, "k-")
    ax[0].axvline(0.67, color="r", ls=":", label="Descantes bulk 0.67")
    ax[0].axhspan(3, 6, color="0.9", label="bulk 3-6 $d_{eq}$")
    ax[0].set(xlabel="solid fraction", ylabel="z / $d_{eq}$", xlim=(0, 1), title="Fig. 7")
    ax[0].legend(fontsize=8)
    ref = hydrostatic(p["coord"], p["phi"])
    for k, style in (("szz", "k-"), ("sxx", "b--"), ("syy", "g-.")):
        ax[1].plot(p[k], z, style, label=r"$\sigma_{%s}$" % k[1:])
    ax[1].plot(ref, z, "r:", label=r"$\rho g \int \phi\, dz$")
    ax[1].set(xlabel="stress ($\\rho g d_{sph}$)", title="Fig. 8")
    ax[1].legend(fontsize=8)
    for k, style in (("zs", "b-"), ("zd", "g-"), ("zt", "m-"), ("ztot", "k-"), ("ziso", "k--")):
        ax[2].plot(p[k], z, style, label=k)
    ax[2].axhspan(3, 6, color="0.9")
    ax[2].set(xlabel="coordination", title="Fig. 9b")
    ax[2].legend(fontsize=8)
    r, gr = g["coord"], g["c_g"]
    outer = r >= 0.75 * r.max()
    ax[3].plot(r / a.deq, gr / gr[outer].mean(), "k-")
    ax[3].axhline(1, color="0.5", lw=0.5)
    ax[3].set(xlabel="r / $d_{eq}$", ylabel="g(r) / its mean at large r", title="Fig. 9a")
    for axis in ax[:3]:
        axis.set_ylim(0, z.max())
    fig.tight_layout()
    out = a.output or a.prefix + "_profiles.png"
    fig.savefig(out, dpi=90)
    print("wrote", out)


if __name__ == "__main__":
    main()
