"""Primitive convex shapes with closed-form mass properties, in their body (principal) frame.

All constructors take full sizes unless said otherwise: ``Box(a, b, c)`` edge lengths, ``Cylinder(radius,
length)`` along z, ``Cone(radius, height)`` along z with the apex up (the centre of mass, h/4 above the
base, is the origin), ``Ellipsoid(a, b, c)`` semi-axes, ``Superquadric(a, b, c, n1, n2)`` half sizes and
exponents of (|x/a|^n2 + |y/b|^n2)^(n1/n2) + |z/c|^n1 <= 1 (n1, n2 >= 2; n = 2 is the ellipsoid, large
n tends to the box). ``crust`` defaults to a small fraction of the inradius (see base.py).
"""
import numpy as np

from .base import (BOX, CONE, CYLINDER, ELLIPSOID, SPHERE, SUPERQUADRIC, Shape, orient_outward, packed_params,
                   uv_mesh)
from .topology import box_topology


def _positive(name, **kw):
    for k, v in kw.items():
        if not (np.isfinite(v) and v > 0):
            raise ValueError("%s: %s must be positive, got %r" % (name, k, v))


class Sphere(Shape):
    kind = SPHERE
    name = "sphere"

    def __init__(self, radius, crust=None):
        _positive(self.name, radius=radius)
        r = self.radius = float(radius)
        self.params = packed_params(r)
        self.volume = 4.0 / 3.0 * np.pi * r ** 3
        self.principal_moments = np.full(3, 0.4 * self.volume * r * r)
        self.bounding_radius = self.inradius = r
        self._init_crust(crust)

    def _make_core(self):   # the exact erosion of a sphere is a sphere
        self.core_kind, self.core_params = SPHERE, packed_params(self.radius - self.crust)
        self.core_vertices = self.vertices

    def mesh(self, resolution=24):
        r = self.radius
        return uv_mesh(lambda e, o: r * np.c_[np.cos(e) * np.cos(o), np.cos(e) * np.sin(o), np.sin(e)],
                       max(resolution // 2, 3), max(resolution, 3))

    def scaled(self, factor):
        return Sphere(self.radius * factor, crust=self._scaled_crust(factor))


class Box(Shape):
    kind = BOX
    name = "box"

    def __init__(self, a, b, c, crust=None):
        _positive(self.name, a=a, b=b, c=c)
        self.size = np.array([a, b, c], dtype=float)
        h = self.size / 2.0
        self.params = packed_params(*h)
        self.volume = float(np.prod(self.size))
        s2 = self.size ** 2
        self.principal_moments = self.volume / 12.0 * np.array([s2[1] + s2[2], s2[0] + s2[2], s2[0] + s2[1]])
        self.bounding_radius = float(np.linalg.norm(h))
        self.inradius = float(h.min())
        self.topology = box_topology(h)
        self._init_crust(crust)

    def _make_core(self):
        self.core_kind, self.core_params = BOX, packed_params(*(self.size / 2.0 - self.crust))
        self.core_vertices = self.vertices

    def mesh(self, resolution=None):
        h = self.size / 2.0
        V = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], float) * h
        F = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
             (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
        return V, orient_outward(V, F)

    def scaled(self, factor):
        s = Box(*(self.size * factor), crust=self._scaled_crust(factor))
        s.name = self.name
        return s


def cube(a, crust=None):
    """A cube of edge a (a Box)."""
    s = Box(a, a, a, crust=crust)
    s.name = "cube"
    return s


class Cylinder(Shape):
    kind = CYLINDER
    name = "cylinder"

    def __init__(self, radius, length, crust=None):
        _positive(self.name, radius=radius, length=length)
        r, L = self.radius, self.length = float(radius), float(length)
        self.params = packed_params(r, L / 2.0)
        V = self.volume = np.pi * r * r * L
        ixx = V * (3.0 * r * r + L * L) / 12.0
        self.principal_moments = np.array([ixx, ixx, 0.5 * V * r * r])
        self.bounding_radius = float(np.hypot(r, L / 2.0))
        self.inradius = min(r, L / 2.0)
        self._init_crust(crust)

    def _make_core(self):
        c = self.crust
        self.core_kind, self.core_params = CYLINDER, packed_params(self.radius - c, self.length / 2.0 - c)
        self.core_vertices = self.vertices

    def mesh(self, resolution=24):
        n = max(resolution, 3)
        t = 2 * np.pi * np.arange(n) / n
        r, hh = self.radius, self.length / 2.0
        rim = np.c_[r * np.cos(t), r * np.sin(t)]
        V = np.vstack([[0, 0, -hh], np.c_[rim, np.full(n, -hh)], np.c_[rim, np.full(n, hh)], [0, 0, hh]])
        F = []
        for j in range(n):
            k = (j + 1) % n
            F += [(0, 1 + k, 1 + j), (1 + j, 1 + k, 1 + n + k), (1 + j, 1 + n + k, 1 + n + j),
                  (2 * n + 1, 1 + n + j, 1 + n + k)]
        return V, orient_outward(V, F)

    def scaled(self, factor):
        return Cylinder(self.radius * factor, self.length * factor, crust=self._scaled_crust(factor))


class Cone(Shape):
    """Right circular cone, axis z, apex up; body origin at the centre of mass (h/4 above the base)."""
    kind = CONE
    name = "cone"

    def __init__(self, radius, height, crust=None):
        _positive(self.name, radius=radius, height=height)
        r, h = self.radius, self.height = float(radius), float(height)
        self.zbase, self.zapex = -h / 4.0, 3.0 * h / 4.0
        self.params = packed_params(r, self.zbase, self.zapex)
        V = self.volume = np.pi * r * r * h / 3.0
        ixx = V * (3.0 / 20.0 * r * r + 3.0 / 80.0 * h * h)
        self.principal_moments = np.array([ixx, ixx, 0.3 * V * r * r])
        self.bounding_radius = max(self.zapex, float(np.hypot(r, self.zbase)))
        self.inradius = min(h / 4.0, 0.75 * r * h / np.hypot(r, h))
        self._init_crust(crust)

    @property
    def max_crust(self):   # insphere radius: the eroded cone vanishes there
        r, h = self.radius, self.height
        return r * h / (r + np.hypot(r, h))

    def _make_core(self):
        # erosion = (eroded infinite cone: same half angle, apex lowered by c/sin) & (base raised by c)
        r, h, c = self.radius, self.height, self.crust
        sin = r / np.hypot(r, h)
        zb, za = self.zbase + c, self.zapex - c / sin
        self.core_kind, self.core_params = CONE, packed_params(r * (za - zb) / h, zb, za)
        self.core_vertices = self.vertices

    def mesh(self, resolution=24):
        n = max(resolution, 3)
        t = 2 * np.pi * np.arange(n) / n
        r = self.radius
        V = np.vstack([[0, 0, self.zbase], np.c_[r * np.cos(t), r * np.sin(t), np.full(n, self.zbase)],
                       [0, 0, self.zapex]])
        F = []
        for j in range(n):
            k = (j + 1) % n
            F += [(0, 1 + k, 1 + j), (1 + j, 1 + k, n + 1)]
        return V, orient_outward(V, F)

    def scaled(self, factor):
        return Cone(self.radius * factor, self.height * factor, crust=self._scaled_crust(factor))


class Ellipsoid(Shape):
    kind = ELLIPSOID
    name = "ellipsoid"

    def __init__(self, a, b, c, crust=None):
        _positive(self.name, a=a, b=b, c=c)
        self.semi_axes = s = np.array([a, b, c], dtype=float)
        self.params = packed_params(*s)
        V = self.volume = 4.0 / 3.0 * np.pi * float(np.prod(s))
        s2 = s * s
        self.principal_moments = V / 5.0 * np.array([s2[1] + s2[2], s2[0] + s2[2], s2[0] + s2[1]])
        self.bounding_radius, self.inradius = float(s.max()), float(s.min())
        self._init_crust(crust)

    @property
    def max_crust(self):   # smallest principal radius of curvature (margin rule exact below it)
        return float(self.semi_axes.min() ** 2 / self.semi_axes.max())

    def mesh(self, resolution=24):
        a, b, c = self.semi_axes
        return uv_mesh(lambda e, o: np.c_[a * np.cos(e) * np.cos(o), b * np.cos(e) * np.sin(o), c * np.sin(e)],
                       max(resolution // 2, 3), max(resolution, 3))

    def scaled(self, factor):
        return Ellipsoid(*(self.semi_axes * factor), crust=self._scaled_crust(factor))


def _spow(t, e):
    return np.sign(t) * np.abs(t) ** e


class Superquadric(Shape):
    """(|x/a|^n2 + |y/b|^n2)^(n1/n2) + |z/c|^n1 <= 1 with n1, n2 >= 2 (convex and smooth).

    Support: closed form (see _support.pyx). Mass properties: closed form with Gamma functions, from
    the Dirichlet integral over the positive octant,
    int u^al v^be w^ga = G((al+1)/n2) G((be+1)/n2) / (n2^2 G((al+be+2)/n2 + 1))
                         * B((ga+1)/n1, (al+be+2)/n1 + 1) / n1            (unit half sizes).
    Bounding radius and curvature (crust limit) are computed numerically.
    """
    kind = SUPERQUADRIC
    name = "superquadric"

    def __init__(self, a, b, c, n1, n2, crust=None):
        _positive(self.name, a=a, b=b, c=c)
        if not (n1 >= 2.0 and n2 >= 2.0 and np.isfinite(n1) and np.isfinite(n2)):
            raise ValueError("superquadric: exponents n1, n2 must be >= 2 (convex and smooth), got %r, %r"
                             % (n1, n2))
        self.half = h = np.array([a, b, c], dtype=float)
        self.n1, self.n2 = float(n1), float(n2)
        self.params = packed_params(a, b, c, n1, n2)
        a, b, c = h
        I0 = self._octant(0, 0, 0)
        self.volume = float(8.0 * a * b * c * I0)
        sx2 = 8.0 * a ** 3 * b * c * self._octant(2, 0, 0)
        sy2 = 8.0 * a * b ** 3 * c * self._octant(0, 2, 0)
        sz2 = 8.0 * a * b * c ** 3 * self._octant(0, 0, 2)
        self.principal_moments = np.array([sy2 + sz2, sx2 + sz2, sx2 + sy2])
        self.inradius = float(h.min())     # contains the ellipsoid (a, b, c) and touches it on the axes
        self.bounding_radius = self._bounding_radius()
        self._max_crust = self._min_curvature_radius()
        self._init_crust(crust)

    def _octant(self, al, be, ga):
        from scipy.special import gammaln      # imported on use: keeps `import dem` light
        n1, n2 = self.n1, self.n2
        lj2 = (gammaln((al + 1) / n2) + gammaln((be + 1) / n2) - gammaln((al + be + 2) / n2 + 1.0)
               - 2.0 * np.log(n2))
        p, q = (ga + 1) / n1, (al + be + 2) / n1 + 1.0
        lb = gammaln(p) + gammaln(q) - gammaln(p + q) - np.log(n1)
        return float(np.exp(lj2 + lb))

    def _surface(self, eta, om):
        e1, e2 = 2.0 / self.n1, 2.0 / self.n2
        a, b, c = self.half
        ce = _spow(np.cos(eta), e1)
        return np.c_[a * ce * _spow(np.cos(om), e2), b * ce * _spow(np.sin(om), e2), c * _spow(np.sin(eta), e1)]

    def _bounding_radius(self):
        from scipy.optimize import minimize
        g = np.linspace(0.0, np.pi / 2, 201)
        E, O = np.meshgrid(g, g, indexing="ij")
        r2 = (self._surface(E.ravel(), O.ravel()) ** 2).sum(1)
        k = int(np.argmax(r2))
        f = lambda t: -float((self._surface(t[:1], t[1:]) ** 2).sum())
        res = minimize(f, [E.ravel()[k], O.ravel()[k]], bounds=[(0, np.pi / 2)] * 2, method="L-BFGS-B",
                       options={"ftol": 1e-15, "gtol": 1e-12})
        return float(np.sqrt(max(-res.fun, r2[k])))

    def _min_curvature_radius(self):
        """Smallest principal radius of curvature, from the gradient and Hessian of the implicit function
        on a dense sample of the open positive octant (smooth there; axes are flat for n > 2), x 0.95."""
        g = np.linspace(1e-3, np.pi / 2 - 1e-3, 120)
        E, O = np.meshgrid(g, g, indexing="ij")
        P = self._surface(E.ravel(), O.ravel())
        a, b, c = self.half
        n1, n2 = self.n1, self.n2
        u, v, w = P[:, 0] / a, P[:, 1] / b, P[:, 2] / c
        S = u ** n2 + v ** n2
        e = n1 / n2
        gr = np.c_[n1 * S ** (e - 1) * u ** (n2 - 1) / a, n1 * S ** (e - 1) * v ** (n2 - 1) / b,
                   n1 * w ** (n1 - 1) / c]
        H = np.zeros((len(P), 3, 3))
        k2 = n1 * (e - 1) * n2 * S ** (e - 2)
        H[:, 0, 0] = k2 * u ** (2 * n2 - 2) / a ** 2 + n1 * S ** (e - 1) * (n2 - 1) * u ** (n2 - 2) / a ** 2
        H[:, 1, 1] = k2 * v ** (2 * n2 - 2) / b ** 2 + n1 * S ** (e - 1) * (n2 - 1) * v ** (n2 - 2) / b ** 2
        H[:, 0, 1] = H[:, 1, 0] = k2 * (u * v) ** (n2 - 1) / (a * b)
        H[:, 2, 2] = n1 * (n1 - 1) * w ** (n1 - 2) / c ** 2
        gn = np.linalg.norm(gr, axis=1)
        nrm = gr / gn[:, None]
        Pm = np.eye(3)[None] - nrm[:, :, None] * nrm[:, None, :]
        K = Pm @ H @ Pm / gn[:, None, None]
        kmax = np.linalg.eigvalsh(K)[:, -1].max()
        return 0.95 / kmax

    @property
    def max_crust(self):
        return min(self._max_crust, self.inradius)

    def mesh(self, resolution=24):
        return uv_mesh(self._surface, max(resolution // 2, 3), max(resolution, 3))

    def scaled(self, factor):
        return Superquadric(*(self.half * factor), self.n1, self.n2, crust=self._scaled_crust(factor))
