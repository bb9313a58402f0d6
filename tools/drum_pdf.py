"""Part III Fig. 27 for several shapes side by side: the PDF of the bed's time-averaged particle velocity
/ (Omega R) (dem.tools.drum_analysis.time_averaged_speed: the last half of each run), one panel per shape,
and a table of its widths (the standard deviation and the 5-95 % range): the PDF narrows as the bed turns
into a rigid layer.

    python tools/drum_pdf.py H5:RPM:LABEL [H5:RPM:LABEL ...] [--radius 0.05] [-o drum_pdf.png]
"""
import argparse
import math

import numpy as np

from dem.tools.drum_analysis import time_averaged_speed


def widths(speed):
    """(mean, std, 5-95 % range) of the time-averaged speeds."""
    lo, hi = np.percentile(speed, [5, 95])
    return float(np.mean(speed)), float(np.std(speed)), float(hi - lo)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("runs", nargs="+", help="H5:RPM:LABEL")
    p.add_argument("--radius", type=float, default=0.05, help="drum radius (m)")
    p.add_argument("-o", "--output", default="drum_pdf.png")
    a = p.parse_args(argv)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    runs = [item.rsplit(":", 2) for item in a.runs]
    labels = list(dict.fromkeys(label for _, _, label in runs))
    fig, axes = plt.subplots(1, len(labels), figsize=(4.5 * len(labels), 3.8), sharey=True, squeeze=False)
    print("shape  rpm  mean  std  range_5_95")
    for path, rpm, label in runs:
        s = time_averaged_speed(path, a.radius, float(rpm) * 2 * math.pi / 60)
        mean, std, spread = widths(s)
        print(f"{label}  {rpm}  {mean:.3f}  {std:.3f}  {spread:.3f}")
        hist, edges = np.histogram(s, bins=np.linspace(0.0, max(2.0, s.max()), 61), density=True)
        axes[0, labels.index(label)].plot(0.5 * (edges[1:] + edges[:-1]), hist, label=f"{rpm} rpm")
    for ax, label in zip(axes[0], labels):
        ax.set_title(label)
        ax.set_xlabel("time-averaged |v| / (Omega R)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[0, 0].set_ylabel("PDF")
    fig.tight_layout()
    fig.savefig(a.output, dpi=100)
    print(a.output)


if __name__ == "__main__":
    main()
