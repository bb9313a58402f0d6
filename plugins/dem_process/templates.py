"""Particle templates for insertion: what one inserted particle is (bounding radius, mass, inertia, shape
index), drawn from a size distribution.

A template draws bounding radii (`draw_radius`), gives per-particle properties (`properties`) and its
mean volume (`mean_volume`, for mass fractions); spheres here, shapes in dem.shapes.command.ShapeTemplate.
`fix insert` keeps one template index per particle (its `mix`: several templates with fractions); the
overlap test of insertion uses bounding spheres (conservative for non-spherical shapes)."""
import math

import numpy as np

from dem.args import number
from dem.errors import DemError


KINDS = ("uniform", "gaussian", "lognormal", "discrete")
USAGE = "R, 'uniform RMIN RMAX', 'gaussian MEAN SD', 'lognormal MEDIAN SIGMA' or 'discrete R1 F1 R2 F2 ...'"


def _is_number(word):
    try:
        number(word)
        return True
    except ValueError:
        return False


class RadiusDistribution:
    """`R` | `uniform RMIN RMAX` | `gaussian MEAN SD` (truncated to [max(0.1 MEAN, MEAN - 3 SD),
    MEAN + 3 SD]) | `lognormal MEDIAN SIGMA` (ln R normal of mean ln MEDIAN and standard deviation SIGMA,
    truncated at +-3 SIGMA) | `discrete R1 F1 R2 F2 ...` (the sizes R_k in number fractions F_k,
    normalised to sum 1). Truncation clips draws to the bounds."""

    def __init__(self, words, what):
        self.words = list(words)
        self.values, self.weights = None, None
        try:
            if words[0] in ("uniform", "gaussian", "lognormal"):
                self.kind, self.a, self.b = words[0], number(words[1]), number(words[2])
                if self.kind == "uniform" and not 0 < self.a <= self.b:
                    raise DemError(f"{what}: radius uniform needs 0 < RMIN <= RMAX")
                if self.kind != "uniform" and (self.a <= 0 or self.b < 0):
                    raise DemError(f"{what}: radius {self.kind} needs {'MEAN' if self.kind == 'gaussian' else 'MEDIAN'}"
                                   f" > 0 and {'SD' if self.kind == 'gaussian' else 'SIGMA'} >= 0")
            elif words[0] == "discrete":
                pairs = words[1:]
                if not pairs or len(pairs) % 2:
                    raise IndexError
                self.kind, self.a, self.b = "discrete", 0.0, 0.0
                self.values = np.array([number(w) for w in pairs[::2]])
                self.weights = np.array([number(w) for w in pairs[1::2]])
                if (self.values <= 0).any() or (self.weights < 0).any() or self.weights.sum() <= 0:
                    raise DemError(f"{what}: radius discrete needs sizes > 0 and fractions >= 0 (not all 0)")
                self.weights = self.weights / self.weights.sum()
            else:
                self.kind, self.a, self.b = "fixed", number(words[0]), 0.0
                if self.a <= 0:
                    raise DemError(f"{what}: radius must be > 0")
        except (ValueError, IndexError):
            raise DemError(f"{what}: radius needs {USAGE}, got '{' '.join(words)}'") from None

    @staticmethod
    def nwords(words, i):
        """Number of words after `radius` at position i (discrete: the numbers that follow)."""
        if i + 1 >= len(words) or words[i + 1] not in KINDS:
            return 1
        if words[i + 1] != "discrete":
            return 3
        rest, k = words[i + 2:], 0
        while k < len(rest) and _is_number(rest[k]):
            k += 1
        return 1 + k

    def bounds(self):
        if self.kind == "uniform":
            return self.a, self.b
        if self.kind == "gaussian":
            return max(0.1 * self.a, self.a - 3 * self.b), self.a + 3 * self.b
        if self.kind == "lognormal":
            return self.a * math.exp(-3 * self.b), self.a * math.exp(3 * self.b)
        if self.kind == "discrete":
            return float(self.values.min()), float(self.values.max())
        return self.a, self.a

    def draw(self, rng, n):
        if self.kind == "uniform":
            return self.a + (self.b - self.a) * rng.random(n)
        if self.kind == "gaussian":
            lo, hi = self.bounds()
            return np.clip(self.a + self.b * rng.standard_normal(n), lo, hi)
        if self.kind == "lognormal":
            return self.a * np.exp(self.b * np.clip(rng.standard_normal(n), -3.0, 3.0))
        if self.kind == "discrete":
            return self.values[rng.choice(len(self.values), size=n, p=self.weights)]
        return np.full(n, self.a)

    def mean_cube(self):
        """E[R^3] of the distribution as drawn (clipping included): the mean volume per unit R^3, for
        mass fractions of mixtures. Gaussian and lognormal by quadrature over the standard normal."""
        if self.kind == "fixed":
            return self.a ** 3
        if self.kind == "uniform":
            return (self.b ** 4 - self.a ** 4) / (4 * (self.b - self.a)) if self.b > self.a else self.a ** 3
        if self.kind == "discrete":
            return float((self.weights * self.values ** 3).sum())
        z = np.linspace(-10.0, 10.0, 200001)
        pdf = np.exp(-0.5 * z * z) / math.sqrt(2 * math.pi)
        if self.kind == "gaussian":
            lo, hi = self.bounds()
            r = np.clip(self.a + self.b * z, lo, hi)
        else:
            r = self.a * np.exp(self.b * np.clip(z, -3.0, 3.0))
        return float(((r ** 3 * pdf)[1:] + (r ** 3 * pdf)[:-1]).sum() * 0.5 * (z[1] - z[0]))


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

    def mean_volume(self):
        return 4.0 / 3.0 * math.pi * self.distribution.mean_cube()

    def properties(self, radius):
        """Per-particle fields for atom.add: rmass, inertia (n, 3), shape."""
        m = self.density * self.volume(radius)
        inertia = (0.4 * m * radius ** 2)[:, None] * np.ones(3)
        return {"rmass": m, "inertia": inertia, "shape": np.full(len(radius), -1, dtype=np.int32)}
