"""Communication: ghost images of particles and global reductions.

`make_comm` picks the implementation: the serial `Comm` (`serial.py`, also the base class that declares
every method the rest of the code calls), or `CommMPI` (`mpi.py`: spatial domain decomposition over MPI,
see docs/parallel.md) when the process was launched by mpiexec with more than one rank. Serial runs never
import mpi4py.
"""
import os

from ..errors import DemError
from .serial import Comm

# environment variables by which MPI launchers announce the world size (MPICH/Hydra, Open MPI, PMIx)
WORLD_SIZE_VARIABLES = ("PMI_SIZE", "OMPI_COMM_WORLD_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS")


def launched_world_size():
    """World size announced by an MPI launcher, without initialising MPI (1 when not launched)."""
    for name in WORLD_SIZE_VARIABLES:
        try:
            n = int(os.environ.get(name, "1"))
        except ValueError:
            continue
        if n > 1:
            return n
    return 1


def make_comm(sim):
    """Serial `Comm`, or `CommMPI` under mpiexec with more than one rank."""
    if launched_world_size() > 1:
        try:
            from .mpi import CommMPI      # here, not above: importing mpi4py initialises MPI
        except ImportError as e:
            raise DemError(f"launched on several MPI ranks but mpi4py cannot be imported ({e})",
                           hint="pip install 'dem[mpi]' (mpi4py and the mpich wheel)") from None
        comm = CommMPI(sim)
        if comm.nprocs > 1:
            return comm
    return Comm(sim)


__all__ = ["Comm", "make_comm", "launched_world_size", "WORLD_SIZE_VARIABLES"]
