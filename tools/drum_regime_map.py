"""Part III Fig. 30 for several shapes: the flow regime of each run against the rotation rate, one row per
shape, from the regime tables that dem-drum-analysis prints (docs/data/drum_sweep/**/regimes.txt), with the
regimes Part III's text names for 3D crosses and (from its ref. [39]) spheres.

    python tools/drum_regime_map.py TABLE:LABEL [TABLE:LABEL ...] [--no-paper] [-o drum_regime_map.png]
"""
import argparse

from dem.tools import drum_regimes
from dem.tools.drum_analysis import read_regimes


def rows_of(tables, paper=True):
    """[(label, {rpm: regime})], the paper's rows first."""
    rows = [("Part III (text), spheres [39]", drum_regimes.PAPER_SPHERES),
            ("Part III (text), 3D crosses", drum_regimes.PAPER_CROSS3D)] if paper else []
    for item in tables:
        path, _, label = item.partition(":")
        t = read_regimes(path)
        rows.append((f"dem, {label or path}", {float(r): g for r, g in zip(t["rpm"], t["regime"])}))
    return rows


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("tables", nargs="+", help="TABLE:LABEL")
    p.add_argument("--no-paper", action="store_true", help="leave out Part III's rows")
    p.add_argument("-o", "--output", default="drum_regime_map.png")
    a = p.parse_args(argv)
    drum_regimes.regime_map(rows_of(a.tables, not a.no_paper), a.output)
    print(a.output)


if __name__ == "__main__":
    main()
