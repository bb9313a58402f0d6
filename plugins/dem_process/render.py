"""Pictures of a drum's cross-section (Part III Fig. 20): particles drawn as discs seen along the drum axis,
coloured by their translational velocity magnitude (blue: slow, red: fast). Used by `dump png` and by
tools/drum_frames.py (frames of an HDF5 dump). Needs matplotlib (drawn without pyplot, any backend)."""
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


def render_cross_section(path, x, v, radius, axis=1, centre=(0.0, 0.0, 0.0), drum_radius=None,
                         up=(0.0, 0.0, 1.0), vmax=None, title=None, size_px=700, cmap="jet"):
    """Write a PNG of particles (positions x, velocities v, radii) seen along `axis` (0, 1, 2), centred on
    `centre`; the drum outline of radius drum_radius; colours from 0 to vmax (default: the largest
    speed). Particles nearer to the viewer are drawn last (on top)."""
    from matplotlib.collections import EllipseCollection
    from matplotlib.patches import Circle

    x = np.asarray(x, dtype=float).reshape(-1, 3)
    v = np.asarray(v, dtype=float).reshape(-1, 3)
    radius = np.asarray(radius, dtype=float).reshape(-1)
    right, upv, toward = view_basis(axis, up)
    rel = x - np.asarray(centre, dtype=float)
    h, u, depth = rel @ right, rel @ upv, rel @ toward
    speed = np.sqrt(np.einsum("ij,ij->i", v, v))
    order = np.argsort(depth, kind="stable")
    vmax = float(vmax) if vmax else (float(speed.max()) if len(speed) and speed.max() > 0 else 1.0)
    fig = _figure(size_px)
    ax = fig.add_axes([0.02, 0.02, 0.82, 0.9])
    ax.set_aspect("equal")
    ax.set_axis_off()
    if drum_radius:
        ax.add_patch(Circle((0.0, 0.0), drum_radius, fill=False, lw=1.5, color="k"))
        lim = 1.03 * drum_radius
    else:
        lim = 1.03 * max(np.abs(np.r_[h, u]).max() + radius.max() if len(h) else 1.0, 1e-12)
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    if len(h):
        coll = EllipseCollection(2 * radius[order], 2 * radius[order], np.zeros(len(h)), units="xy",
                                 offsets=np.column_stack([h[order], u[order]]), offset_transform=ax.transData,
                                 cmap=cmap, edgecolors="k", linewidths=0.2)
        coll.set_array(speed[order])
        coll.set_clim(0.0, vmax)
        ax.add_collection(coll)
        cax = fig.add_axes([0.86, 0.15, 0.03, 0.65])
        bar = fig.colorbar(coll, cax=cax)
        bar.set_label("|v| (m/s)")
    if title:
        ax.set_title(title, fontsize=10)
    fig.savefig(path)
    return path
