"""Shared by the test modules: the `mpiexec` that MPI tests launch (`from conftest import MPIEXEC`)."""
import os
import shutil
import sys


def find_mpiexec():
    """The mpiexec beside this Python (a virtual environment's), else the first on PATH; None without one."""
    for folder in (os.path.dirname(sys.executable), None):
        found = shutil.which("mpiexec", path=folder) if folder else shutil.which("mpiexec")
        if found:
            return found
    return None


MPIEXEC = find_mpiexec()
