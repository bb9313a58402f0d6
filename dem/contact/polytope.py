"""Python entry points (tests, tools) to the sharp-polytope kernels of dem/contact/_polytope.pyx.

Poses as in dem.contact.geometry: ``x`` the centre of mass, ``q`` a unit quaternion (w, x, y, z) body -> world.
Shapes are polytope shapes (Box, cube, Polyhedron, tetrahedron, pinacoid); their topology comes from
``shape.topology`` (dem/shapes/topology.py). Pair styles call the nogil functions of _polytope.pxd instead.

* ``penetration``: exact depth and normal (separating axes on the Gauss map), and which features gave it.
* ``contact``: the same plus the contact type and the points on the contact plane (None when apart).
"""
import functools
from collections import namedtuple

import numpy as np

from ..shapes.topology import pack_topology
from . import _polytope, _volume

AXIS_NONE, AXIS_FACE_A, AXIS_FACE_B, AXIS_EDGE = (int(a) for a in _polytope.AxisKind)
PC_NONE, PC_VERTEX_FACE, PC_EDGE_EDGE, PC_EDGE_FACE, PC_FACE_FACE = (int(c) for c in _polytope.PolyContactType)
TYPE_NAMES = {PC_NONE: "none", PC_VERTEX_FACE: "vertex/face", PC_EDGE_EDGE: "edge/edge",
              PC_EDGE_FACE: "edge/face", PC_FACE_FACE: "face/face"}
MAXP = _polytope.MAXP
FEATURE_TOL = 1e-9     # default ftol per unit of the two bounding radii

Penetration = namedtuple("Penetration", "depth normal axis fa fb")
PolytopeContact = namedtuple("PolytopeContact", "depth normal type points axis fa fb nfa nfb")


@functools.lru_cache(maxsize=256)
def _pair(shape_a, shape_b):
    for s in (shape_a, shape_b):
        if getattr(s, "topology", None) is None:
            raise ValueError("%s is not a polytope" % s.name)
    return _polytope.TopologyView(pack_topology([shape_a, shape_b]))


def topology_view(shapes):
    """The packed topology of a list of shapes (rows in that order) as the kernels take it."""
    return _polytope.TopologyView(pack_topology(shapes))


def _vec(x, n):
    a = np.ascontiguousarray(x, dtype=float).reshape(-1)
    if a.shape != (n,):
        raise ValueError("expected %d components, got %r" % (n, x))
    return a


def penetration(shape_a, x_a, q_a, shape_b, x_b, q_b, box_path=True):
    """Penetration(depth, normal, axis, fa, fb): depth > 0 when the bodies overlap (else <= 0: a separating
    axis exists), unit normal from b to a, axis AXIS_FACE_A (fa: face of a), AXIS_FACE_B (fb: face of b) or
    AXIS_EDGE (fa, fb: the edges), ids into shape.topology. Two boxes take the closed-form 15-axis path
    unless ``box_path`` is false (the general loop; tests compare the two)."""
    r = _polytope.pair(_pair(shape_a, shape_b), 0, 1, _vec(x_a, 3), _vec(q_a, 4), _vec(x_b, 3), _vec(q_b, 4),
                       points=False, box_path=box_path)
    return Penetration(r[1], r[2], r[3], r[4], r[5])


def contact(shape_a, x_a, q_a, shape_b, x_b, q_b, ftol=None, box_path=True):
    """None when apart, else PolytopeContact(depth, normal, type, points (k, 3), axis, fa, fb, nfa, nfb):
    the shared overlap, the normal from b to a, the contact type (PC_*; TYPE_NAMES), 1 <= k <= MAXP points
    on the contact plane in a canonical order, the axis as ``penetration``, and the vertex counts of the
    two contacting features. ``ftol`` (a length; default FEATURE_TOL times the two bounding radii) selects
    the vertices whose support is within ftol of the extreme as a body's contacting feature. Boxes take
    their closed-form paths unless ``box_path`` is false (tests)."""
    view = _pair(shape_a, shape_b)
    if ftol is None:
        ftol = -1.0
    r = _polytope.pair(view, 0, 1, _vec(x_a, 3), _vec(q_a, 4), _vec(x_b, 3), _vec(q_b, 4), ftol=float(ftol),
                       box_path=box_path)
    if not r[0]:
        return None
    return PolytopeContact(r[1], r[2], r[6], r[7], r[3], r[4], r[5], r[8], r[9])


Overlap = namedtuple("Overlap", "volume area moment centroid")


def overlap_volume(shape_a, x_a, q_a, shape_b, x_b, q_b):
    """Overlap(volume, area, moment, centroid) of two posed polytopes (dem/contact/_volume.pyx): the volume
    V of their intersection, its gradients S = dV/dx_a and M = dV/dtheta_a (about x_a), its centroid (nan
    when apart)."""
    view = _pair(shape_a, shape_b)
    return Overlap(*_volume.pair(view, 0, 1, _vec(x_a, 3), _vec(q_a, 4), _vec(x_b, 3), _vec(q_b, 4)))


def overlap_halfspace(shape, x, q, normal, offset):
    """Overlap of a posed polytope and the half-space normal . x <= offset (a plane wall's solid side)."""
    view = _pair(shape, shape)
    return Overlap(*_volume.halfspace(view, 0, _vec(x, 3), _vec(q, 4), _vec(normal, 3), float(offset)))
