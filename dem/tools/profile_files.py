"""Reading the files of fix ave/profile, ave/vector and print/series, for the plotting tools."""
import os

import numpy as np


def data_file(prefix, kind):
    """PREFIX.KIND.dat as an input writes it, else PREFIX.KIND.txt (the copies kept in docs/data: *.dat
    files are not committed)."""
    dat = f"{prefix}.{kind}.dat"
    return dat if os.path.exists(dat) else f"{prefix}.{kind}.txt"


def last_block(path):
    """Rows of the last step in a series file, as a dict of columns."""
    with open(path) as f:
        names = [line for line in f if line.startswith("# step")][-1][1:].split()
    a = np.atleast_2d(np.loadtxt(path, comments="#"))
    a = a[a[:, 0] == a[-1, 0]]
    return {n: a[:, k] for k, n in enumerate(names)}
