"""Pictures of a drum's cross-section (Part III Fig. 20): particles seen along the drum axis, coloured by their
translational velocity magnitude (blue: slow, red: fast). Used by `dump png` and by dem-frames
(dem.tools.drum_frames: frames of an HDF5 dump). Needs matplotlib (drawn without pyplot, any backend).

Two pictures: the projection along the axis (every particle; spheres as discs, shaped particles as the
outline of their projected body, the nearest drawn on top) or a slice (the particles cut by one plane
across the axis, each drawn as its true section: discs of the sphere's section, polygons of the shaped
bodies' sections). A shaped particle is a union of convex pieces (``shapes.convex_pieces(row)``, body
frame, scale 1): each piece is drawn as its own filled polygon of the particle's colour, the convex hull
of its projected posed vertices (projection) or of the points where its triangle edges cross the plane
(slice)."""
import math

import numpy as np

from dem.errors import DemError


def _figure(size_px, dpi=100):
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError:
        raise DemError("drum pictures need matplotlib (pip install matplotlib, or pip install -e .[plot])") \
            from None
    fig = Figure(figsize=(size_px / dpi, size_px / dpi), dpi=dpi)
    FigureCanvasAgg(fig)
    return fig


def view_basis(axis, up=(0.0, 0.0, 1.0)):
    """(right, up, toward the viewer) for a view along the axis index `axis` seen from its + side."""
    e = np.zeros(3)
    e[axis] = 1.0
    up = np.asarray(up, dtype=float)
    up = up - np.dot(up, e) * e
    if np.linalg.norm(up) < 1e-12:           # looking along the vertical: pick another "up"
        up = np.zeros(3)
        up[(axis + 1) % 3] = 1.0
    up /= np.linalg.norm(up)
    return np.cross(up, e), up, e


def convex_hulls_2d(points, valid=None):
    """Convex hulls of n point sets at once (Andrew's monotone chain, vectorised over the sets).

    points (n, m, 2); valid (n, m) bool (default: all), the points of each set that count. Returns
    (hull (n, 2m, 2), count (n,)): the first count[i] rows of hull[i] are the hull's vertices,
    counter-clockwise, without repeats or collinear points (within rounding); count < 3 for an empty or
    degenerate set (a point, a segment)."""
    points = np.asarray(points, dtype=float)
    n, m = points.shape[:2]
    hull = np.zeros((n, 2 * max(m, 1), 2))
    if n == 0 or m == 0:
        return hull, np.zeros(n, dtype=np.int64)
    if valid is None:
        valid = np.ones((n, m), dtype=bool)
    rows = np.arange(n)
    anyvalid = valid.any(axis=1)
    first = np.argmax(valid, axis=1)
    # the points that do not count become copies of a point that does: duplicates leave no trace
    P = np.where(valid[..., None], points, points[rows, first][:, None, :])
    # collinear within rounding (points on a side, as where a face's diagonal crosses a slice): not vertices
    extent = (P.max(axis=1) - P.min(axis=1)).max(axis=1)
    tol = 1e-10 * extent * extent
    order = np.lexsort((P[..., 1], P[..., 0]), axis=-1)
    P = np.take_along_axis(P, order[..., None], axis=1)

    def chain(P):
        S = np.empty_like(P)
        k = np.zeros(n, dtype=np.int64)
        for j in range(m):
            p = P[:, j]
            while True:
                can = k >= 2
                if not can.any():
                    break
                a = S[rows, np.maximum(k - 2, 0)]
                b = S[rows, np.maximum(k - 1, 0)]
                cross = (b[:, 0] - a[:, 0]) * (p[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (p[:, 0] - a[:, 0])
                pop = can & (cross <= tol)
                if not pop.any():
                    break
                k -= pop
            S[rows, k] = p
            k += 1
        return S, k

    lower, kl = chain(P)
    upper, ku = chain(P[:, ::-1])
    count = (kl - 1) + (ku - 1)
    col = np.arange(2 * m)
    # hull = lower[:kl - 1] then upper[:ku - 1]
    src_lower = col[None, :] < (kl - 1)[:, None]
    iu = np.clip(col[None, :] - (kl - 1)[:, None], 0, m - 1)
    hull = np.where(src_lower[..., None], np.concatenate([lower, np.zeros_like(lower)], axis=1),
                    np.take_along_axis(upper, iu[..., None], axis=1))
    count = np.where(anyvalid, count, 0)
    return hull, count


def _drop_interior(P, ndir=16):
    """Points (n, m, 2) -> valid (n, m): False for points strictly inside the polygon of the extreme points in
    `ndir` directions (Akl-Toussaint): they cannot be hull vertices, and the hull runs faster without them."""
    ang = np.arange(ndir) * (2 * np.pi / ndir)
    dirs = np.stack([np.cos(ang), np.sin(ang)], axis=1)
    ext = np.take_along_axis(P, np.argmax(P @ dirs.T, axis=1)[..., None], axis=1)   # (n, ndir, 2), ccw
    inside = np.ones(P.shape[:2], dtype=bool)
    for k in range(ndir):
        a, b = ext[:, k], ext[:, (k + 1) % ndir]
        e = b - a
        cross = e[:, 0, None] * (P[..., 1] - a[:, 1, None]) - e[:, 1, None] * (P[..., 0] - a[:, 0, None])
        inside &= (cross > 0.0) | (np.einsum("ni,ni->n", e, e) == 0.0)[:, None]    # a repeated point: no edge
    return ~inside


def _edges(faces):
    """Unique undirected edges (e, 2) of triangles (k, 3)."""
    e = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    return np.unique(np.sort(e, axis=1), axis=0)


def shaped_polygons(shapes, shape, rel, quat, radius, basis, section=None):
    """Polygons of shaped particles in picture coordinates.

    shapes: the shape table (``convex_pieces(row)``: list of body-frame (vertices, faces) at scale 1, and
    ``radius[row]``: the row's bounding radius); shape (n,) rows (>= 0), rel (n, 3) centres relative to
    the picture's centre, quat (n, 4) orientations (w, x, y, z; body -> world), radius (n,) bounding radii
    (the scale is radius / shapes.radius[row]); basis (right, up, toward) of the picture (view_basis).
    section None: the outline of each convex piece projected along `toward` (convex hull of its projected
    posed vertices); a number d: the section of each piece with the plane rel . toward = d (convex hull of
    the points where its triangle edges cross the plane; a piece the plane misses or only touches gives no
    polygon). Returns (owner, polygons): polygons[k] a (p, 2) counter-clockwise array of particle
    owner[k] (index into the n particles), in particle order."""
    from dem.thermo import quat_to_matrix

    shape = np.asarray(shape).reshape(-1)
    n = len(shape)
    rel = np.asarray(rel, dtype=float).reshape(n, 3)
    quat = np.asarray(quat, dtype=float).reshape(n, 4)
    quat = quat / np.linalg.norm(quat, axis=1, keepdims=True)
    radius = np.asarray(radius, dtype=float).reshape(n)
    B = np.array(basis, dtype=float).reshape(3, 3)        # rows: right, up, toward
    centre = rel @ B.T                                     # (n, 3): h, u, depth of the centres
    owners, polys, keys = [], [], []
    for row in np.unique(shape):
        idx = np.flatnonzero(shape == row)
        M = np.einsum("ij,njk->nik", B, quat_to_matrix(quat[idx]))       # body -> (h, u, depth)
        M *= (radius[idx] / float(shapes.radius[int(row)]))[:, None, None]
        for piece, (V, F) in enumerate(shapes.convex_pieces(int(row))):
            V = np.asarray(V, dtype=float).reshape(-1, 3)
            Q = np.einsum("nik,mk->nmi", M, V) + centre[idx, None, :]      # (ni, m, 3) posed vertices
            sel = np.arange(len(idx))
            if section is None:
                pts = Q[..., :2]
                valid = _drop_interior(pts) if pts.shape[1] > 16 else np.ones(pts.shape[:2], dtype=bool)
            else:
                d = Q[..., 2] - float(section)
                hit = (d.min(axis=1) < 0.0) & (d.max(axis=1) > 0.0)
                sel, Q, d = sel[hit], Q[hit], d[hit]
                E = _edges(np.asarray(F, dtype=np.int64).reshape(-1, 3))
                da, db = d[:, E[:, 0]], d[:, E[:, 1]]
                crossing = da * db < 0.0
                t = np.where(crossing, da / np.where(crossing, da - db, 1.0), 0.0)
                qa, qb = Q[:, E[:, 0], :2], Q[:, E[:, 1], :2]
                pts = np.concatenate([qa + t[..., None] * (qb - qa), Q[..., :2]], axis=1)
                valid = np.concatenate([crossing, d == 0.0], axis=1)
            if len(sel) == 0:
                continue
            # keep only the columns some set needs (valid points first, in order)
            width = int(valid.sum(axis=1).max())
            if width < pts.shape[1]:
                keep = np.argsort(~valid, axis=1, kind="stable")[:, :width]
                pts = np.take_along_axis(pts, keep[..., None], axis=1)
                valid = np.take_along_axis(valid, keep, axis=1)
            hull, count = convex_hulls_2d(pts, valid)
            for j in np.flatnonzero(count >= 3):
                owners.append(int(idx[sel[j]]))
                polys.append(hull[j, :count[j]])
                keys.append((int(idx[sel[j]]), piece))
    order = sorted(range(len(keys)), key=keys.__getitem__)
    return np.array([owners[k] for k in order], dtype=np.int64), [polys[k] for k in order]


PAD = 1.15      # half the picture's width over the drum radius (or the particles' extent): room for the guides


def scale_length(span):
    """The scale bar's length: 1, 2 or 5 times a power of ten, at most a fifth of `span`."""
    raw = span / 5.0
    k = math.floor(math.log10(raw))
    for m in (5.0, 2.0, 1.0):
        if m * 10.0 ** k <= raw * (1 + 1e-12):
            return m * 10.0 ** k
    return 10.0 ** k


def _length_label(length):
    return f"{length * 1e3:g} mm" if length < 0.1 else f"{length:g} m"


def _axis_label(vec):
    """'x', '-z'... for a unit vector along a coordinate axis, else the vector's components."""
    k = int(np.argmax(np.abs(vec)))
    if abs(abs(vec[k]) - 1.0) < 1e-9:
        return ("-" if vec[k] < 0 else "") + "xyz"[k]
    return "(" + ", ".join(f"{c:.2g}" for c in vec) + ")"


def _draw_guides(ax, lim, right, upv, drum_radius, spin):
    """Scale bar, picture axes and a drum's turning direction (see render_cross_section)."""
    from matplotlib.patches import FancyArrowPatch
    bar = scale_length(2 * lim)
    x0, y0 = -0.95 * lim, -0.95 * lim
    ax.plot([x0, x0 + bar], [y0, y0], color="k", lw=3, solid_capstyle="butt")
    ax.text(x0 + 0.5 * bar, y0 + 0.02 * lim, _length_label(bar), ha="center", va="bottom", fontsize=9)
    a, ox, oy = 0.12 * lim, 0.78 * lim, -0.95 * lim
    for (dx, dy), vec in (((a, 0.0), right), ((0.0, a), upv)):
        ax.add_patch(FancyArrowPatch((ox, oy), (ox + dx, oy + dy), arrowstyle="-|>", mutation_scale=10,
                                     color="k", lw=1))
        ax.text(ox + 1.15 * dx + (0.02 * lim if dy else 0.0), oy + 1.1 * dy, _axis_label(vec), fontsize=9,
                ha="left" if dx else "center", va="center" if dx else "bottom")
    if drum_radius:
        r, t0, t1 = 1.07 * drum_radius, math.radians(35.0), math.radians(65.0)
        if spin < 0:
            t0, t1 = t1, t0
        ax.add_patch(FancyArrowPatch((r * math.cos(t0), r * math.sin(t0)), (r * math.cos(t1), r * math.sin(t1)),
                                     connectionstyle=f"arc3,rad={0.13 if spin > 0 else -0.13}",
                                     arrowstyle="-|>", mutation_scale=14, color="k", lw=1.5))


def wall_sections(walls, centre, basis, section):
    """Segments (m, 2, 2) in the picture's coordinates where the triangle meshes `walls` [(vertices (nv, 3),
    triangles (nt, 3)), ...] cross the picture's plane (at `section` along the viewing axis from centre, 0
    for a projection)."""
    right, upv, toward = basis
    out = []
    for vertices, triangles in walls:
        rel = np.asarray(vertices, dtype=float) - np.asarray(centre, dtype=float)
        p = rel[np.asarray(triangles)]                              # (nt, 3, 3)
        s = p @ toward - float(section or 0.0)                      # (nt, 3): signed distances
        ends = []
        for k in range(3):                                          # edge k -> k+1 crossing the plane
            a, b = p[:, k], p[:, (k + 1) % 3]
            sa, sb = s[:, k], s[:, (k + 1) % 3]
            cross = (sa < 0.0) != (sb < 0.0)
            t = np.where(cross, sa / np.where(cross, sa - sb, 1.0), 0.0)
            ends.append((cross, a + t[:, None] * (b - a)))
        hits = np.stack([c for c, _ in ends], axis=1)
        two = hits.sum(axis=1) == 2
        pts = np.stack([q for _, q in ends], axis=1)[two]           # (m, 3 edges, 3)
        pts = pts[hits[two]].reshape(-1, 2, 3)
        out.append(np.stack([pts @ right, pts @ upv], axis=2))
    return np.concatenate(out) if out else np.zeros((0, 2, 2))


def render_cross_section(path, x, v, radius, axis=1, centre=(0.0, 0.0, 0.0), drum_radius=None,
                         up=(0.0, 0.0, 1.0), vmax=None, title=None, size_px=700, cmap="jet", shapes=None,
                         shape=None, quat=None, section=None, spin=0.0, walls=()):
    """Write a PNG of particles (positions x, velocities v, radii) seen along `axis` (0, 1, 2), centred on
    `centre`; the drum outline of radius drum_radius; colours from 0 to vmax (default: the largest
    speed).

    section None: the projection along the axis, every particle drawn, the nearer to the viewer last (on
    top). A number: the slice by the plane at `section` along the axis from `centre` (coordinate
    centre[axis] + section), only the particles it cuts, each as its section. Spheres are discs; with
    `shapes` (the shape table: convex_pieces, radius, and kind: its sphere rows are discs too), `shape`
    (n,) rows (-1: sphere) and `quat` (n, 4), the shaped particles are drawn as the polygons of
    shaped_polygons (one per convex piece).

    Also drawn: a scale bar (bottom left), the directions of the picture's axes (bottom right) and, with a
    drum whose spin (rad/s about the viewing axis, counter-clockwise as seen: positive) is not 0, an arrow
    along its rim in the direction it turns; `walls` (mesh walls: [(vertices, triangles), ...]) as their
    section by the picture's plane, grey lines."""
    from matplotlib.collections import EllipseCollection, LineCollection, PathCollection
    from matplotlib.patches import Circle
    from matplotlib.path import Path

    x = np.asarray(x, dtype=float).reshape(-1, 3)
    v = np.asarray(v, dtype=float).reshape(-1, 3)
    radius = np.asarray(radius, dtype=float).reshape(-1)
    basis = view_basis(axis, up)
    right, upv, toward = basis
    rel = x - np.asarray(centre, dtype=float)
    h, u, depth = rel @ right, rel @ upv, rel @ toward
    speed = np.sqrt(np.einsum("ij,ij->i", v, v))
    vmax = float(vmax) if vmax else (float(speed.max()) if len(speed) and speed.max() > 0 else 1.0)
    shaped = np.zeros(len(x), dtype=bool)
    if shapes is not None and shape is not None and quat is not None and len(shapes):
        from dem.shapes import SPHERE
        shape = np.asarray(shape).reshape(-1)
        shaped = shape >= 0
        kind = getattr(shapes, "kind", None)
        if kind is not None:            # sphere rows of the table: discs of the particle's radius
            shaped[shaped] = np.asarray(kind)[shape[shaped]] != SPHERE
    # spheres: discs of their radius (projection) or of their section's radius (slice)
    disc = radius.copy()
    drawn = ~shaped
    if section is not None:
        dd = depth - float(section)
        drawn &= np.abs(dd) < radius
        disc = np.sqrt(np.maximum(radius ** 2 - dd ** 2, 0.0))
    fig = _figure(size_px)
    ax = fig.add_axes([0.02, 0.02, 0.82, 0.9])
    ax.set_aspect("equal")
    ax.set_axis_off()
    segments = wall_sections(walls, centre, basis, section)
    if len(segments):
        ax.add_collection(LineCollection(segments, colors="0.35", linewidths=1.5))
    if drum_radius:
        ax.add_patch(Circle((0.0, 0.0), drum_radius, fill=False, lw=1.5, color="k"))
        lim = PAD * drum_radius
    else:
        lim = PAD * max(np.abs(np.r_[h, u]).max() + radius.max() if len(h) else 1.0,
                        np.abs(segments).max() if len(segments) else 0.0, 1e-12)
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    _draw_guides(ax, lim, right, upv, drum_radius if spin else None, spin)
    coll = None
    if not shaped.any():
        order = np.flatnonzero(drawn)[np.argsort(depth[drawn], kind="stable")]
        if len(order):
            coll = EllipseCollection(2 * disc[order], 2 * disc[order], np.zeros(len(order)), units="xy",
                                     offsets=np.column_stack([h[order], u[order]]),
                                     offset_transform=ax.transData, cmap=cmap, edgecolors="k", linewidths=0.2)
            coll.set_array(speed[order])
    else:
        # one collection of paths (discs and polygons) in depth order: nearer particles on top
        ids = np.flatnonzero(shaped)
        owner, polys = shaped_polygons(shapes, shape[ids], rel[ids], quat[ids], radius[ids], basis,
                                       section=section)
        owner = ids[owner]
        spheres = np.flatnonzero(drawn)
        who = np.concatenate([spheres, owner])
        paths = [Path.circle((h[i], u[i]), disc[i]) for i in spheres]
        paths += [Path(np.vstack([p, p[:1]]), closed=True) for p in polys]
        order = np.argsort(depth[who], kind="stable")
        if len(order):
            coll = PathCollection([paths[k] for k in order], cmap=cmap, edgecolors="k", linewidths=0.2)
            coll.set_array(speed[who[order]])
    if coll is not None:
        coll.set_clim(0.0, vmax)
        ax.add_collection(coll)
        cax = fig.add_axes([0.86, 0.15, 0.03, 0.65])
        bar = fig.colorbar(coll, cax=cax)
        bar.set_label("|v| (m/s)")
    if title:
        ax.set_title(title, fontsize=10)
    fig.savefig(path)
    return path
