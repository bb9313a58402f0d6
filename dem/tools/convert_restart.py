"""Convert a restart file of version 1 or 2 (a Python pickle, written by dem before version 3) to the
current format (docs/restart.md):

    dem-convert-restart OLD NEW --trust

(also `python -m dem.tools.convert_restart ...`, or `python tools/convert_restart.py ...` in the source tree.)

Loading a pickle can run any code it contains: convert only files you wrote yourself (`--trust` says so).
The converted state is checked as read_restart checks it."""
import argparse
import pickle
import sys

from dem import restart, restart_file
from dem.errors import DemError


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("old")
    p.add_argument("new")
    p.add_argument("--trust", action="store_true", help="the old file is your own (it is unpickled)")
    a = p.parse_args(argv)
    if not a.trust:
        p.error("loading a pickle can run code: give --trust for a file you wrote yourself")
    if restart_file.file_version(a.old) is not None:
        p.error(f"'{a.old}' is not an old (pickle) restart file")
    with open(a.old, "rb") as fh:
        state = pickle.load(fh)
    if not isinstance(state, dict) or not str(state.pop("format", "")).startswith("dem-restart-"):
        p.error(f"'{a.old}' is not a dem restart file")
    try:
        restart_file.write(a.new, state, restart.VERSION)
        restart.load(a.new)
    except DemError as e:
        p.error(str(e))
    print(f"wrote {a.new} (version {restart.VERSION}, step {state['step']})")


if __name__ == "__main__":
    sys.exit(main())
