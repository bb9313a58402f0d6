"""Time-integration fixes: `nve/sphere` (leap-frog, isotropic rotation) and `nve/shape` (leap-frog with
Omelyan's revised leap-frog for the rotation of non-spherical bodies)."""
from . import _integrate
from .fix import Fix, Stage


class FixNVESphere(Fix):
    """fix ID group nve/sphere

    Leap-frog Verlet (Grains3D eq. 9) of position and velocity, and of the angular velocity with the
    isotropic moment of inertia of a sphere. Velocities are half-step values."""

    style = "nve/sphere"
    stages = Stage.INTEGRATE
    time_integrate = True

    def __init__(self, sim, fid, group, args):
        super().__init__(sim, fid, group, args)
        self.no_args()

    def integrate(self):
        sim = self.sim
        a = sim.atom.data
        _integrate.nve_sphere(a["x"], a["v"], a["f"], a["omega"], a["torque"], a["rmass"], a["inertia"],
                              a["mask"], int(self.groupbit), sim.atom.nlocal, sim.update.dt)


class FixNVEShape(Fix):
    """fix ID group nve/shape

    Leap-frog Verlet for translation; for rotation Omelyan's revised leap-frog on the angular momentum
    (Descantes 2022 eq. 8-11): the orientation is updated by a Cayley transform, which keeps it
    orthonormal by construction. Works for every particle (spheres included); needed for
    non-spherical shapes."""

    style = "nve/shape"
    stages = Stage.INTEGRATE
    time_integrate = True

    def __init__(self, sim, fid, group, args):
        super().__init__(sim, fid, group, args)
        self.no_args()

    def setup(self):
        a = self.sim.atom.data
        _integrate.angmom_from_omega(a["omega"], a["angmom"], a["quat"], a["inertia"], self.sim.atom.nlocal)

    def integrate(self):
        sim = self.sim
        a = sim.atom.data
        _integrate.nve_shape(a["x"], a["v"], a["f"], a["omega"], a["angmom"], a["quat"], a["torque"],
                             a["rmass"], a["inertia"], a["mask"], int(self.groupbit), sim.atom.nlocal,
                             sim.update.dt)


INTEGRATORS = [FixNVESphere, FixNVEShape]
