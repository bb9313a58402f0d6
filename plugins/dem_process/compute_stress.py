"""compute stress"""
import numpy as np

from dem.compute import Compute

from .analysis import (STRESS_NAMES, contact_moment, kinetic_moment, mass_moments, region_of, region_volume,
                       selection, voigt)


class ComputeStress(Compute):
    """compute ID group stress [region REGION-ID] [volume V] [kinetic yes|no]

    Mean stress tensor of a granular volume, Moreau's per-particle form of the Love-Weber formula
    (Descantes 2022 eq. 12):

        sigma = -(1/V) sum_particles sym( sum_contacts F (x) (P - G) )  [+ (1/V) sum m v' (x) v']

    F the force a particle receives at contact point P, G its centre of mass, the outer sum over the group's
    particles whose centre lies in the region; sign: compression positive (a column at rest under gravity
    has sigma_zz > 0 equal to the weight above per unit area). Summed over both bodies of a contact, the
    two terms give F (x) (G_j - G_i), the centre-to-centre branch vector of Love-Weber (minimum image: the
    ghost copy is the image in contact); split per particle, each gets its own lever, which for two equal
    spheres or equal face-to-face cubes is half the branch vector. Every contact point of every pair style
    is tallied (sphere, convex/gjk, glued/convex, polyhedron/multipoint), and wall contacts too (walls act
    from the first step of a run: `run 0` tallies pair contacts only). A rolling-resistance couple only has
    an antisymmetric part and drops out of sym(). Not included: eq. 12's rotational-inertia term
    [W(omega)W(omega) + W(domega/dt)] I, of order m omega^2 d^2 against contact forces (zero at rest).

    V: `volume V`, else the region's volume inside the box (block clipped to the box; cylinder, sphere),
    else the box volume. `kinetic yes` adds the kinetic (streaming-free) part, the velocities about the
    mass-weighted mean of the selection (default no: eq. 12 has none; it matters only in collisional flows).

    Vector: [sxx, syy, szz, sxy, sxz, syz] (Pa); scalar: the pressure (sxx + syy + szz) / 3. The contact
    sums are tallied per particle only while such a compute exists (dem/tally.py); evaluate in a run (or
    after `run 0`). Profiles along an axis: `fix ave/profile ... sxx ...`.

    Example: `compute sig all stress region bulk` then `thermo_style custom step c_sig c_sig[3]`."""

    style = "stress"
    usage = "[region REGION-ID] [volume V] [kinetic yes|no]"
    size_vector = 6
    vector_names = STRESS_NAMES
    tallies = ("stress",)

    def __init__(self, sim, cid, group, args):
        super().__init__(sim, cid, group, args)
        a = self.parser()
        kw = a.keywords(0, {"region": 1, "volume": 1, "kinetic": 1})
        what = f"compute {cid} stress"
        self.region = region_of(sim, kw["region"][0], what) if "region" in kw else None
        self.volume = a.to_float(kw["volume"][0], "volume") if "volume" in kw else None
        if self.volume is not None and self.volume <= 0:
            raise a.error("volume must be > 0")
        word = kw.get("kinetic", ["no"])[0]
        if word not in ("yes", "no"):
            raise a.error(f"kinetic must be yes or no, got '{word}'")
        self.kinetic = word == "yes"

    def _volume(self):
        if self.volume is not None:
            return self.volume
        if self.region is not None:
            return region_volume(self.sim, self.region, f"compute {self.id} stress")
        self.sim.domain.require_box(f"compute {self.id} stress")
        return float(np.prod(self.sim.domain.prd))

    def compute_vector(self):
        sim = self.sim
        sel = selection(sim, self.groupbit, self.region)
        atom = sim.atom
        parts = [contact_moment(sim, sel, f"compute {self.id} stress").reshape(9)]
        if self.kinetic:
            parts.append(mass_moments(atom.data["rmass"][:atom.nlocal][sel], atom.data["v"][:atom.nlocal][sel]))
        total = sim.comm.sum_values(np.concatenate(parts))
        t = total[:9].reshape(3, 3)
        if self.kinetic:
            t = t + kinetic_moment(total[9:])
        return voigt(t) / self._volume()

    def compute_scalar(self):
        return float(np.mean(self.vector()[:3]))
