"""dem: Discrete Element Method for granular media made of particles of real shape."""
from .errors import DemError
from .sim import Sim

Simulation = Sim
__version__ = "0.1.0"
__all__ = ["Sim", "Simulation", "DemError"]
