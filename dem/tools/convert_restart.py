"""Convert a restart file of an older version to the current format (docs/restart.md):

    dem-convert-restart OLD NEW [--trust]

(also `python -m dem.tools.convert_restart ...`, or `python tools/convert_restart.py ...` in the source tree.)

Version 3 (HDF5 without a whole-file checksum): its datasets' own CRC-32 checksums are checked, but HDF5
opens the file unchecked, and a damaged file can make the HDF5 library fail in any way (an error, a hang,
a crash of this converter): convert files you know to be whole. Versions 1 and 2 (Python pickles):
loading a pickle can run any code it contains: convert only files you wrote yourself (`--trust` says so).
The converted state is checked as read_restart checks it."""
import argparse
import pickle
import sys

import h5py

from dem import restart, restart_file, verified_file
from dem.errors import DemError


def old_state(p, a):
    """The state of the old file `a.old` (an argparse error for a file that is not an old restart)."""
    problem = verified_file.check(a.old, restart_file.KIND)
    if problem is None:
        p.error(f"'{a.old}' is a restart of version {restart_file.file_version(a.old)}: nothing to convert")
    reason, text = problem
    if reason == verified_file.PLAIN_HDF5:      # unchecked: see the risk above
        try:
            with h5py.File(a.old, "r") as f:
                version3 = f.attrs.get("format") == restart_file.MAGIC and int(f.attrs.get("version", -1)) == 3
        except Exception as e:
            p.error(f"'{a.old}' cannot be read (a damaged file?): {type(e).__name__}: {e}")
        if not version3:
            p.error(f"'{a.old}' is not a dem restart file of version 3")
        return restart_file.read_unchecked(a.old)
    if reason != verified_file.FOREIGN or restart_file.file_version(a.old) is not None:
        p.error(f"'{a.old}' {text}")
    if not a.trust:
        p.error("loading a pickle can run code: give --trust for a file you wrote yourself")
    with open(a.old, "rb") as fh:
        state = pickle.load(fh)
    if not isinstance(state, dict) or not str(state.pop("format", "")).startswith("dem-restart-"):
        p.error(f"'{a.old}' is not a dem restart file")
    return state


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("old")
    p.add_argument("new")
    p.add_argument("--trust", action="store_true", help="the old file is your own (a pickle: it is unpickled)")
    a = p.parse_args(argv)
    try:
        state = old_state(p, a)
        state.setdefault("time_anchor", [state["step"], state["time"]])   # older files: from their step on
        restart_file.write(a.new, state, restart.VERSION)
        restart.load(a.new)
    except DemError as e:
        p.error(str(e))
    print(f"wrote {a.new} (version {restart.VERSION}, step {state['step']})")


if __name__ == "__main__":
    sys.exit(main())
