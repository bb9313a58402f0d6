"""Built-in glued composites: component lists ``[(shape, offset, rotation), ...]`` for dem.shapes.Glued.

Dimensions (Part III gives none for the crosses; these are dem's choices, stated in docs/shapes.md):
* ``cross2d(L, aspect)``: two beams of length L and square section w = L / aspect, along x and y, crossing
  at their middles (default aspect 4: each arm sticks out 1.5 w from the central w-cube).
* ``cross3d(L, aspect)``: three such beams along x, y and z.
* ``tile_spacer(L, W, T)``: the 2D cross of a tile spacer (Part III Fig. 13): two plates L x W x T along x
  and y, thickness T along z.
* ``sliced_cylinder(R, L, N)``: the cylinder of radius R and length L (axis z) cut into N equal slices
  (Part III Fig. 6b).
* ``cube_of_cubes(A)``: the cube of edge A made of 8 cubes of edge A/2 (Part III sec 3.3).
* ``sphere_cylinder(R, L, N)``: glued spheres filling the cylinder (R, L), N = 9 or 54 (Part III Fig. 10,
  after Kodam et al.): 9 = one layer of spheres of radius L/2 (one on the axis, 8 on the ring at R - L/2);
  54 = two layers of spheres of radius L/4 at z = +-L/4, each of 27 (one on the axis, 8 on the ring at
  (R - L/4)/2, 18 on the ring at R - L/4). Every sphere touches the cylinder's surface or lies inside it.
* ``multisphere(spheres)``: glued spheres (x, y, z, r) as other codes' clumps.
"""
import numpy as np

from .primitives import Box, Cylinder, Sphere, cube

EYE = np.eye(3)
DEFAULT_ASPECT = 4.0


def _beams(L, aspect, axes, crust):
    if not aspect > 1.0:
        raise ValueError("cross: aspect (beam length / width) must be > 1")
    w = L / aspect
    out = []
    for a in axes:
        size = [w, w, w]
        size[a] = L
        out.append((Box(*size, crust=crust), np.zeros(3), EYE))
    return out


def cross2d(L, aspect=DEFAULT_ASPECT, crust=None):
    return _beams(L, aspect, (0, 1), crust)


def cross3d(L, aspect=DEFAULT_ASPECT, crust=None):
    return _beams(L, aspect, (0, 1, 2), crust)


def tile_spacer(L, W, T, crust=None):
    if not (L > W > 0 and T > 0):
        raise ValueError("tilespacer: need L > W > 0 and T > 0")
    return [(Box(L, W, T, crust=crust), np.zeros(3), EYE), (Box(W, L, T, crust=crust), np.zeros(3), EYE)]


def sliced_cylinder(R, L, N, crust=None):
    N = int(N)
    if N < 1:
        raise ValueError("slicedcylinder: N must be >= 1")
    h = L / N
    z = -L / 2.0 + h * (np.arange(N) + 0.5)
    return [(Cylinder(R, h, crust=crust), np.array([0.0, 0.0, zc]), EYE) for zc in z]


def cube_of_cubes(A, crust=None):
    q = A / 4.0
    return [(cube(A / 2.0, crust=crust), np.array([sx, sy, sz]) * q, EYE)
            for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]


def _ring(n, rho, z):
    t = 2.0 * np.pi * np.arange(n) / n
    return [(rho * np.cos(a), rho * np.sin(a), z) for a in t]


def sphere_cylinder(R, L, N, crust=None):
    N = int(N)
    if N == 9:
        r = L / 2.0
        if not R > r:
            raise ValueError("spherecylinder 9: needs R > L/2")
        centres = [(0.0, 0.0, 0.0)] + _ring(8, R - r, 0.0)
    elif N == 54:
        r = L / 4.0
        if not R > r:
            raise ValueError("spherecylinder 54: needs R > L/4")
        centres = []
        for z in (-r, r):
            centres += [(0.0, 0.0, z)] + _ring(8, 0.5 * (R - r), z) + _ring(18, R - r, z)
    else:
        raise ValueError("spherecylinder: N is 9 or 54 (Part III Fig. 10)")
    return multisphere([(x, y, z, r) for x, y, z in centres], crust=crust)


def multisphere(spheres, crust=None):
    S = np.asarray(spheres, dtype=float).reshape(-1, 4)
    if not len(S):
        raise ValueError("multisphere: give at least one sphere (x y z r)")
    return [(Sphere(r, crust=crust), np.array([x, y, z]), EYE) for x, y, z, r in S]
