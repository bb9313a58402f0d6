"""Pairwise geometry of posed convex shapes (Python entry points to the nogil kernels in dem/contact/_gjk.pyx).

Poses: ``x`` is the centre of mass (3-vector), ``q`` a unit quaternion (w, x, y, z) rotating the body frame
into the world. Shapes are dem.shapes objects. Per-pair Python calls are for tests, tools and setup only;
pair styles call ``crust_contact`` / ``signed_distance`` from Cython (see ``contact_batch``).

* ``distance``: signed distance of the true bodies (GJK; EPA when they overlap, negative then).
* ``contact``: Grains3D crust contact of the rounded bodies core (+) ball(crust) (see dem/shapes/base.py):
  None when apart, else (overlap, normal from b to a, contact point).
"""
import functools

import numpy as np

from ..shapes.table import ShapeTable
from . import _gjk

__all__ = ["distance", "contact", "rotation", "DEFAULT_TOL"]

DEFAULT_TOL = 1e-10   # relative accuracy of GJK distances (duality gap) and EPA depths
CONTACT_NONE, CONTACT_CRUST, CONTACT_EPA, CONTACT_FALLBACK = (int(c) for c in _gjk.ContactCode)


def _vec(x, n):
    a = np.ascontiguousarray(x, dtype=float).reshape(-1)
    if a.shape != (n,):
        raise ValueError("expected %d components, got %r" % (n, x))
    return a


@functools.lru_cache(maxsize=256)
def _pair(shape_a, shape_b):
    """The two shapes as a two-row table (rows 0 and 1), as the kernels take shapes (cached: tests and
    tools query the same shapes many times)."""
    return ShapeTable([shape_a, shape_b]).view()


def rotation(q):
    """Rotation matrix (body -> world) of a quaternion (w, x, y, z)."""
    from ..shapes._support import rotation_matrix
    return rotation_matrix(_vec(q, 4))


def distance(shape_a, x_a, q_a, shape_b, x_b, q_b, tol=DEFAULT_TOL, guess=None):
    """(distance, point_a, point_b): closest points when apart; when the bodies overlap, distance is minus
    the penetration depth and the points are the deepest points (point_a - point_b = depth * n_ab)."""
    d, pa, pb, status = _gjk.pair_distance(_pair(shape_a, shape_b), _vec(x_a, 3), _vec(q_a, 4), _vec(x_b, 3),
                                           _vec(q_b, 4), tol, guess)
    if status < 0:
        raise RuntimeError("EPA failed on a degenerate configuration")
    return d, pa, pb


def contact(shape_a, x_a, q_a, shape_b, x_b, q_b, tol=DEFAULT_TOL, guess=None, with_code=False):
    """None, or (overlap, normal, point) of the rounded bodies: overlap > 0, unit normal from b to a (the
    direction a must move to separate), point midway between the two surfaces. ``with_code`` appends
    how it was found: 1 crust (GJK on the cores), 2 EPA on the cores, 3 degenerate fallback."""
    code, ov, n, p = _gjk.pair_contact(_pair(shape_a, shape_b), _vec(x_a, 3), _vec(q_a, 4), _vec(x_b, 3),
                                       _vec(q_b, 4), tol, guess)
    if code == CONTACT_NONE:
        return None
    return (ov, n, p, code) if with_code else (ov, n, p)
