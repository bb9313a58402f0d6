"""Particle templates for insertion: what one inserted particle is (bounding radius, mass, inertia, shape
index), drawn from a size distribution.

Only spheres exist now. The hook for shapes and mixtures: a template class with `bounding radius` draws
(`draw_radius`) and per-particle properties (`properties`); `fix insert` keeps one template index per
particle, so a mixture `mix T1 F1 T2 F2 ...` only has to choose the index with the given number fractions
(the overlap test of insertion uses bounding spheres: conservative for non-spherical shapes)."""
import math

import numpy as np

from dem.args import number
from dem.errors import DemError


class RadiusDistribution:
    """`R` | `uniform RMIN RMAX` | `gaussian MEAN SD` (truncated to [max(0.1 MEAN, MEAN - 3 SD),
    MEAN + 3 SD])."""

    def __init__(self, words, what):
        self.words = list(words)
        try:
            if words[0] == "uniform":
                self.kind, self.a, self.b = "uniform", number(words[1]), number(words[2])
                if not 0 < self.a <= self.b:
                    raise DemError(f"{what}: radius uniform needs 0 < RMIN <= RMAX")
            elif words[0] == "gaussian":
                self.kind, self.a, self.b = "gaussian", number(words[1]), number(words[2])
                if self.a <= 0 or self.b < 0:
                    raise DemError(f"{what}: radius gaussian needs MEAN > 0 and SD >= 0")
            else:
                self.kind, self.a, self.b = "fixed", number(words[0]), 0.0
                if self.a <= 0:
                    raise DemError(f"{what}: radius must be > 0")
        except (ValueError, IndexError):
            raise DemError(f"{what}: radius needs R, 'uniform RMIN RMAX' or 'gaussian MEAN SD', got "
                           f"'{' '.join(words)}'") from None

    @staticmethod
    def nwords(words, i):
        """Number of words after `radius` at position i."""
        return 3 if i + 1 < len(words) and words[i + 1] in ("uniform", "gaussian") else 1

    def bounds(self):
        if self.kind == "uniform":
            return self.a, self.b
        if self.kind == "gaussian":
            return max(0.1 * self.a, self.a - 3 * self.b), self.a + 3 * self.b
        return self.a, self.a

    def draw(self, rng, n):
        if self.kind == "uniform":
            return self.a + (self.b - self.a) * rng.random(n)
        if self.kind == "gaussian":
            lo, hi = self.bounds()
            return np.clip(self.a + self.b * rng.standard_normal(n), lo, hi)
        return np.full(n, self.a)


class SphereTemplate:
    """Solid spheres of one density and a radius distribution."""

    def __init__(self, distribution, density):
        self.distribution = distribution
        self.density = density

    def draw_radius(self, rng, n):
        return self.distribution.draw(rng, n)

    def max_radius(self):
        return self.distribution.bounds()[1]

    def volume(self, radius):
        return 4.0 / 3.0 * math.pi * np.asarray(radius, dtype=float) ** 3

    def properties(self, radius):
        """Per-particle fields for atom.add: rmass, inertia (n, 3), shape."""
        m = self.density * self.volume(radius)
        inertia = (0.4 * m * radius ** 2)[:, None] * np.ones(3)
        return {"rmass": m, "inertia": inertia, "shape": np.full(len(radius), -1, dtype=np.int32)}
