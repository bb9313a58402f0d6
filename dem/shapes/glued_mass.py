"""Mass properties of glued convex composites (Grains3D Part III sec 2.3), per unit density.

A component is ``(shape, offset, rotation)``: a convex dem.shapes Shape in its body frame, its centre of mass
at ``offset`` in the composite frame and ``rotation`` (3, 3) turning its body frame into the composite
frame (composite point = offset + rotation @ body point). Components may overlap.

* ``exact_mass_properties``: sums of the components' own volumes, centres and inertia tensors (parallel
  axes). Exact when no two components overlap (slices of a cylinder, the 8 cubes of a cube).
* ``union_mass_properties``: the structured-lattice integration of eq. 7-8 over the union (overlaps counted
  once), kernels in _lattice.pyx; split over MPI ranks by x-slabs.
* ``components_overlap``: whether two components overlap by more than a negligible depth.

Error estimate of the lattice result
------------------------------------
The midpoint rule on a cell is exact for f = 1 and f = x and misses h^2/12 per cell and direction for
x^2, negligible (1e-6 relative at 500 points); the error is the digitisation of the boundary: cells cut by
the surface are counted whole or not at all. Part III Fig. 3 finds it decreasing "in a slightly
non-monotone but overall linear way" with the points per direction n, i.e. e(n) ~ C/n at worst. The same
integration at n/2 then has e(n/2) ~ 2 e(n), so |Q(n) - Q(n/2)| ~ e(n): the difference with the half
resolution estimates the error of the full one when convergence is first order, and bounds it
(over-estimates) when it is faster (curved surfaces with their digitisation errors of random sign
converge faster than 1/n, faces on lattice planes are exact). In general a coarser m gives
|Q(n) - Q(m)| / (n/m - 1) ~ e(n). One coarse lattice is not enough: digitisation errors are
pseudo-random in n and two lattices can err alike (a disc of 500 cells across holds exactly 4 times the
cell centres of one of 250: the n/2 difference of an axis-aligned cylinder at 1000 points is 50 times
below its error). The estimate is therefore the larger of the scaled differences with m = n/2 and
m = 2n/3 (factor 2), costing 1/4 + 4/9 of the rows of the fine lattice. ``error`` is the largest of the
relative estimates of the volume, of the inertia tensor (max |dI_ij| / max principal moment) and of the
centre of mass (|dc| / radius of gyration). tools/glued_convergence.py checks it against the true errors.
"""
import numpy as np

from . import _lattice
from .base import BOX, MARGIN, NPARAM, POLYHEDRON

__all__ = ["union_mass_properties", "exact_mass_properties", "components_overlap", "rotation_to_quaternion",
           "union_bounding_box", "lattice_cells", "DEFAULT_RESOLUTION", "OVERLAP_TOL"]

DEFAULT_RESOLUTION = 500   # Part III: < 0.2 % error on volume and inertia from 500 points per direction
OVERLAP_TOL = 1e-9         # overlap depth, relative to the smaller component's bounding radius, below which
#                            two components only touch (GJK/EPA depths are accurate to ~1e-10 relative)
_PAD = 1e-9                # bounding boxes padded by this x size: row rejection is only a filter
_AXES = np.vstack([np.eye(3), -np.eye(3)])


def _components(components):
    comps = getattr(components, "components", components)
    out = []
    for c in comps:
        shape, off, rot = c
        off = np.asarray(off, dtype=float).reshape(3)
        rot = np.asarray(rot, dtype=float).reshape(3, 3)
        if not (np.all(np.isfinite(off)) and np.all(np.isfinite(rot))):
            raise ValueError("a component offset and rotation must be finite")
        if not (np.allclose(rot.T @ rot, np.eye(3), atol=1e-9) and np.linalg.det(rot) > 0):
            raise ValueError("a component rotation must be a proper rotation matrix")
        out.append((shape, off, rot))
    if not out:
        raise ValueError("no components")
    return out


_WIDEN = 1e-9      # of the tight box (union_bounding_box): far above round-off, far below a cell


def _frame_box(shape, off, rot):
    """Tight bounding box (lo, hi) of a posed component in the composite frame, from its support function:
    the extent along +-e_a is e_a . (off + R s(R^T e_a))."""
    s = shape.support(_AXES @ rot)          # rows: directions R^T (+-e_a) in the body frame
    ext = np.einsum("ij,ij->i", _AXES, s @ rot.T + off)
    return -ext[3:], ext[:3]


def _body_box(shape):
    s = shape.support(_AXES)
    ext = np.einsum("ij,ij->i", _AXES, s)
    return -ext[3:], ext[:3]


def union_bounding_box(components):
    """(lo, hi) of the union of the posed components in the composite frame: the tight box (support
    functions) widened by the relative _WIDEN about its centre. Faces of components that lie on cell
    centres of the tight box (a beam of a cross whose width is an odd number of cells) are then
    consistently just outside every centre, on both sides: without it round-off includes them on one side
    and not the other, which shifts the centre of mass of a symmetric union by a fraction of a cell."""
    boxes = [_frame_box(*c) for c in _components(components)]
    lo, hi = np.min([b[0] for b in boxes], axis=0), np.max([b[1] for b in boxes], axis=0)
    mid, half = 0.5 * (lo + hi), 0.5 * (hi - lo) * (1.0 + _WIDEN)
    return mid - half, mid + half


def lattice_cells(lo, hi, resolution):
    """Cells per direction: ``resolution`` along the longest side, the others in proportion (rounded, at
    least 1), so cells are cubic to within 1/(2 n_a). The lattice is the tight box itself: a face of the
    union lying on a side of the box (a cylinder's end) is then on a cell face and integrated exactly."""
    L = np.asarray(hi, float) - np.asarray(lo, float)
    if not np.all(L > 0):
        raise ValueError("degenerate bounding box")
    return tuple(int(max(1, round(resolution * l / L.max()))) for l in L)


def _pack(comps):
    K = len(comps)
    kinds = np.empty(K, dtype=np.intc)
    params = np.zeros((K, NPARAM))
    rot = np.empty((K, 3, 3))
    off = np.empty((K, 3))
    fbox = np.empty((K, 6))
    bbox = np.empty((K, 6))
    planes, start = [], [0]
    for c, (shape, o, R) in enumerate(comps):
        kinds[c] = shape.kind
        params[c] = shape.params
        params[c, MARGIN] = 0.0             # (the margin: the true body is integrated)
        rot[c], off[c] = R, o
        pad = _PAD * max(shape.bounding_radius, 1e-300)
        flo, fhi = _frame_box(shape, o, R)
        blo, bhi = _body_box(shape)
        fbox[c] = np.r_[flo - pad, fhi + pad]
        bbox[c] = np.r_[blo - pad, bhi + pad]
        if shape.kind == POLYHEDRON:
            eq = np.asarray(shape._planes(), dtype=float)
            planes.append(eq)
            start.append(start[-1] + len(eq))
        else:
            start.append(start[-1])
    planes = np.ascontiguousarray(np.vstack(planes)) if planes else np.zeros((0, 4))
    return (kinds, params, rot, off, planes, np.asarray(start, dtype=np.int64), fbox, bbox)


def _my_slabs(nx, comm):
    if comm is None:
        return 0, nx
    me, P = int(comm.me), int(comm.nprocs)
    return me * nx // P, (me + 1) * nx // P


def _allsum(comm, arr):
    if comm is None:
        return arr
    world = getattr(comm, "world", None)      # dem.comm.mpi.CommMPI: its sum() takes scalars
    if world is not None and hasattr(world, "allreduce"):
        return np.asarray(world.allreduce(arr), dtype=float)
    return np.asarray(comm.sum(arr), dtype=float).reshape(arr.shape)


def lattice_integrate(components, resolution, comm=None, method="rows", box=None):
    """Raw lattice integration: (volume, centre, inertia, cells) at ``resolution`` (see
    union_mass_properties); ``method`` "rows" (row intervals) or "points" (every cell centre tested)."""
    comps = _components(components)
    lo, hi = union_bounding_box(comps) if box is None else box
    n = lattice_cells(lo, hi, resolution)
    centre = 0.5 * (lo + hi)
    packed = _pack(comps)
    start, stop = _my_slabs(n[0], comm)
    kernel = {"rows": _lattice.lattice_sums, "points": _lattice.lattice_sums_points}[method]
    S = kernel(*packed, lo, hi, n, centre, start, stop)
    S = _allsum(comm, S)
    return _moments(S, lo, hi, n, centre) + (n,)


def _moments(S, lo, hi, n, centre):
    N = S[0]
    if N <= 0:
        raise ValueError("no lattice cell centre inside the union: resolution too coarse")
    vcell = float(np.prod((np.asarray(hi) - np.asarray(lo)) / np.asarray(n)))
    d = S[1:4] / N
    M = np.array([[S[4], S[7], S[8]], [S[7], S[5], S[9]], [S[8], S[9], S[6]]])
    Mc = (M - N * np.outer(d, d)) * vcell        # second moment about the centre of mass
    I = np.trace(Mc) * np.eye(3) - Mc
    return N * vcell, centre + d, 0.5 * (I + I.T)


def _relative_difference(a, b):
    (Va, ca, Ia), (Vb, cb, Ib) = a, b
    imax = float(np.abs(np.linalg.eigvalsh(Ia)).max())
    gyr = np.sqrt(imax / Va)
    ev = abs(Va - Vb) / Va
    ei = float(np.abs(Ia - Ib).max()) / imax
    ec = float(np.linalg.norm(ca - cb)) / gyr
    return ev, ei, ec


def union_mass_properties(components, resolution=DEFAULT_RESOLUTION, comm=None, estimate_error=True,
                          method="rows"):
    """Lattice mass properties of the union of the components, per unit density, in the composite frame.

    Returns a dict: ``volume`` (float), ``centre`` (3,) centre of mass, ``inertia`` (3, 3) inertia tensor
    about the centre of mass, ``error`` (float, relative: module doc; 0.0 if not estimate_error),
    ``error_volume``, ``error_inertia``, ``error_centre`` (its parts), ``resolution``, ``cells`` (nx, ny, nz).
    ``comm``: an object with ``.me``, ``.nprocs`` and ``.sum(array)`` (dem.comm communicators): each rank
    integrates a share of the x-slabs and the sums are reduced (every rank gets the result)."""
    resolution = int(resolution)
    if resolution < 2:
        raise ValueError("resolution must be at least 2 points per direction")
    comps = _components(components)
    box = union_bounding_box(comps)
    V, c, I, n = lattice_integrate(comps, resolution, comm, method, box)
    out = {"volume": float(V), "centre": c, "inertia": I, "resolution": resolution, "cells": n,
           "error": 0.0, "error_volume": 0.0, "error_inertia": 0.0, "error_centre": 0.0}
    if estimate_error:
        ev = ei = ec = 0.0
        for m in sorted({max(resolution // 2, 1), max(int(round(2 * resolution / 3)), 1)}):
            if m >= resolution:
                continue
            coarse = lattice_integrate(comps, m, comm, method, box)[:3]
            f = 1.0 / (resolution / m - 1.0)
            dv, di, dc = _relative_difference((V, c, I), coarse)
            ev, ei, ec = max(ev, f * dv), max(ei, f * di), max(ec, f * dc)
        out.update(error=max(ev, ei, ec), error_volume=ev, error_inertia=ei, error_centre=ec)
    return out


def exact_mass_properties(components):
    """(volume, centre (3,), inertia (3, 3) about the centre) of the components summed, per unit density:
    the mass properties of the union when no two components overlap (parallel-axis theorem)."""
    comps = _components(components)
    vols = np.array([s.volume for s, _, _ in comps])
    V = float(vols.sum())
    com = (vols[:, None] * np.array([o for _, o, _ in comps])).sum(0) / V
    I = np.zeros((3, 3))
    for (s, o, R), v in zip(comps, vols):
        d = o - com
        I += R @ np.diag(s.principal_moments) @ R.T + v * (d @ d * np.eye(3) - np.outer(d, d))
    return V, com, 0.5 * (I + I.T)


def aligned_boxes(components):
    """Whether every component is a box and all have their edges along the same three axes (crosses, tile
    spacers, boxes turned by quarter turns of each other): their union is
    then a union of cells of the grid of their face planes, exactly (aligned_boxes_mass_properties)."""
    comps = _components(components)
    return all(s.kind == BOX and _axis_permutation(comps[0][2], R) is not None for s, _, R in comps)


def _axis_permutation(R0, R):
    """|R0^T R| when it is a permutation matrix (R turns a box onto the axes of R0), else None."""
    P = np.abs(R0.T @ R)
    if np.all((abs(P) < 1e-14) | (abs(P - 1.0) < 1e-14)) and np.allclose(P.sum(0), 1.0) and np.allclose(P.sum(1), 1.0):
        return np.round(P)
    return None


def aligned_boxes_mass_properties(components):
    """(volume, centre, inertia about the centre) of a union of boxes turned alike, per unit density,
    exact (to round-off) however they overlap: the face planes of all boxes cut space into a grid of
    cells, each wholly inside or outside the union (tested at its centre), whose box moments are summed
    and turned back into the composite frame."""
    comps = _components(components)
    R = comps[0][2]
    size = np.array([_axis_permutation(R, Rc) @ s.size for s, _, Rc in comps])   # on the common axes
    cen = np.array([R.T @ o for _, o, _ in comps])
    lo, hi = cen - 0.5 * size, cen + 0.5 * size
    cuts = [np.unique(np.r_[lo[:, a], hi[:, a]]) for a in range(3)]
    V, S1, S2 = 0.0, np.zeros(3), np.zeros((3, 3))
    for i in range(len(cuts[0]) - 1):
        for j in range(len(cuts[1]) - 1):
            for k in range(len(cuts[2]) - 1):
                a = np.array([cuts[0][i], cuts[1][j], cuts[2][k]])
                b = np.array([cuts[0][i + 1], cuts[1][j + 1], cuts[2][k + 1]])
                c = 0.5 * (a + b)
                if not np.any(np.all((lo <= c) & (c <= hi), axis=1)):
                    continue
                h = b - a
                v = float(np.prod(h))
                V += v
                S1 += v * c
                S2 += v * (np.outer(c, c) + np.diag(h * h) / 12.0)      # int x x^T over the cell
    com = S1 / V
    M = S2 - V * np.outer(com, com)                                     # about the centre of mass
    I = np.trace(M) * np.eye(3) - M
    return V, R @ com, R @ (0.5 * (I + I.T)) @ R.T


def rotation_to_quaternion(R):
    """Unit quaternion (w, x, y, z), w >= 0, of a proper rotation matrix (Shepperd's method: the largest of
    the four squared components is taken first, so no division by a small number)."""
    R = np.asarray(R, dtype=float).reshape(3, 3)
    t = np.trace(R)
    d = np.diag(R)
    k = int(np.argmax([t, d[0], d[1], d[2]]))
    if k == 0:
        w = 0.5 * np.sqrt(max(1.0 + t, 0.0))
        q = np.array([w, (R[2, 1] - R[1, 2]) / (4 * w), (R[0, 2] - R[2, 0]) / (4 * w), (R[1, 0] - R[0, 1]) / (4 * w)])
    else:
        i = k - 1
        j, l = (i + 1) % 3, (i + 2) % 3
        s = 0.5 * np.sqrt(max(1.0 + 2 * d[i] - t, 0.0))
        q = np.empty(4)
        q[1 + i] = s
        q[0] = (R[l, j] - R[j, l]) / (4 * s)
        q[1 + j] = (R[j, i] + R[i, j]) / (4 * s)
        q[1 + l] = (R[l, i] + R[i, l]) / (4 * s)
    q /= np.linalg.norm(q)
    return q if q[0] >= 0 else -q


def components_overlap(components, tol=OVERLAP_TOL):
    """True when two components overlap by more than ``tol`` x the smaller bounding radius (signed GJK/EPA
    distance of the true bodies): components sharing a face, an edge or a vertex do not overlap."""
    from ..contact.geometry import distance
    comps = _components(components)
    posed = [(s, o, rotation_to_quaternion(R)) for s, o, R in comps]
    for a in range(len(posed)):
        sa, xa, qa = posed[a]
        for b in range(a + 1, len(posed)):
            sb, xb, qb = posed[b]
            if np.linalg.norm(xa - xb) > sa.bounding_radius + sb.bounding_radius:
                continue
            d = distance(sa, xa, qa, sb, xb, qb)[0]
            if d < -tol * min(sa.bounding_radius, sb.bounding_radius):
                return True
    return False
