"""Part III Fig. 25 for several shapes: the time-averaged coordination number against the rotation rate,
from the regime tables that dem-drum-analysis prints (docs/data/drum_sweep/**/regimes.txt; read by
dem.tools.drum_analysis.read_regimes).

    python tools/drum_coordination.py TABLE:LABEL [TABLE:LABEL ...] [-o drum_coordination.png]

A table has a header line (rpm ... coordination ...) and one row per rate. Where it also has the
coordination per contact point (coord_points: crosses touching at two beams count 2), that is drawn dashed
in the same colour (convex shapes touch at one point: their two counts are the same).
"""
import argparse

import numpy as np

from dem.tools.drum_analysis import read_regimes


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("tables", nargs="+", help="TABLE:LABEL")
    p.add_argument("-o", "--output", default="drum_coordination.png")
    a = p.parse_args(argv)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8.5, 4))
    for item in a.tables:
        path, _, label = item.partition(":")
        t = read_regimes(path)
        order = np.argsort(t["rpm"])
        line, = ax.plot(t["rpm"][order], t["coordination"][order], "o-", label=label or path)
        points = t.get("coord_points", np.full(len(order), np.nan))[order]
        if np.isfinite(points).any() and not np.allclose(points, t["coordination"][order]):
            ax.plot(t["rpm"][order], points, "s--", color=line.get_color(),
                    label=f"{label or path}, per contact point")
    ax.set_xlabel("rotation rate (rpm)")
    ax.set_ylabel("time-averaged coordination number")
    ax.set_title("Part III Fig. 25 with dem's runs (the last half of each)")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    fig.savefig(a.output, dpi=100)
    print(a.output)


if __name__ == "__main__":
    main()
