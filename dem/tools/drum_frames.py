"""PNG frames of a drum from a dem HDF5 dump (`dump ID group h5 N file.h5`): particles seen along the drum
axis, coloured by translational velocity magnitude from blue (0) to red (vmax), like Part III Fig. 20.

    dem-frames drum.h5 [--axis y] [--centre C1 C2] [--radius 0.05] [--frames all|last|K,..]
               [--vmax V] [--up 0 0 1] [--size 700] [--out DIR]

(also `python -m dem.tools.drum_frames ...`, or `python tools/drum_frames.py ...` in the source tree.)

Frames are written as DIR/<name>_<step>.png (DIR defaults to the dump's folder). The HDF5 layout is that
of dem.dump_h5 (/frames/<step>/position, velocity, radius; attributes step, time). Shaped particles are
drawn as `dump png` draws them (the same renderer), from the shape table the dump holds (/shapes) and
each particle's shape, orientation and radius: the outline of each convex piece. Needs h5py and
matplotlib. The same pictures can be written during a run with `dump ID group png N file_*.png`.
"""
import argparse
import os
import sys

import numpy as np


def read_frames(path):
    """[(step, time, {name: array})] of a dem HDF5 dump, in step order: the per-particle fields (a frame's
    groups, e.g. the posed surfaces of shaped particles, are left out)."""
    import h5py
    out = []
    with h5py.File(path, "r", locking=False) as f:
        if f.attrs.get("format") != "dem-dump-h5":
            raise SystemExit(f"{path}: not a dem HDF5 dump")
        for name in sorted(f["frames"]):
            g = f["frames"][name]
            arrays = {k: g[k][()] for k in g if isinstance(g[k], h5py.Dataset)}
            out.append((int(g.attrs["step"]), float(g.attrs["time"]), arrays))
    return out


class StoredShapes:
    """The shape table of a dem HDF5 dump (/shapes) as the renderer asks for it: ``radius`` (the rows'
    bounding radii), ``kind`` and ``convex_pieces(row)``, the connected parts of the row's stored surface
    mesh at scale 1 (one for a convex shape, one per component of a composite)."""

    def __init__(self, group):
        self.radius = group["bounding_radius"][()]
        self.kind = group["kind"][()]
        self.meshes = [(group[f"mesh_{k}/vertices"][()], group[f"mesh_{k}/faces"][()])
                       for k in range(int(group.attrs["count"]))]
        self._pieces = {}          # row -> its pieces, found once for all the frames

    def __len__(self):
        return len(self.meshes)

    def convex_pieces(self, row):
        if row not in self._pieces:
            self._pieces[row] = self._split(row)
        return self._pieces[row]

    def _split(self, row):
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import connected_components
        V, F = self.meshes[row]
        edges = np.concatenate([F[:, [0, 1]], F[:, [1, 2]]])
        graph = coo_matrix((np.ones(len(edges)), (edges[:, 0], edges[:, 1])), shape=(len(V), len(V)))
        _, label = connected_components(graph, directed=False)
        pieces = []
        for part in np.unique(label[F[:, 0]]):
            faces = F[label[F[:, 0]] == part]
            used = np.unique(faces)
            index = np.full(len(V), -1)
            index[used] = np.arange(len(used))
            pieces.append((V[used], index[faces]))
        return pieces


def read_shapes(path):
    """The dump's shape table (StoredShapes), or None when it holds none."""
    import h5py
    with h5py.File(path, "r", locking=False) as f:
        return StoredShapes(f["shapes"]) if "shapes" in f else None


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("dump")
    p.add_argument("--axis", default="y", choices="xyz")
    p.add_argument("--centre", nargs=2, type=float, default=[0.0, 0.0],
                   help="the axis position in the two other coordinates, x y z order")
    p.add_argument("--radius", type=float, default=0.05, help="drum radius drawn (0: none)")
    p.add_argument("--frames", default="all", help="all, last, or frame indices K,K,.. (negative from the end)")
    p.add_argument("--vmax", type=float, default=None, help="velocity of the red end (default: per frame max)")
    p.add_argument("--up", nargs=3, type=float, default=[0.0, 0.0, 1.0], help="the upward direction")
    p.add_argument("--size", type=int, default=700, help="picture size in pixels")
    p.add_argument("--out", default=None, help="folder of the PNG files (default: the dump's)")
    a = p.parse_args(argv)
    from dem_process.render import render_cross_section   # the installed plugin (dump png draws the same)

    frames = read_frames(a.dump)
    if not frames:
        raise SystemExit(f"{a.dump}: no frame")
    if a.frames == "last":
        frames = frames[-1:]
    elif a.frames != "all":
        frames = [frames[int(k)] for k in a.frames.split(",")]
    axis = "xyz".index(a.axis)
    centre = np.zeros(3)
    centre[[d for d in range(3) if d != axis]] = a.centre
    out = a.out or os.path.dirname(os.path.abspath(a.dump))
    os.makedirs(out, exist_ok=True)
    stem = os.path.splitext(os.path.basename(a.dump))[0]
    shapes = read_shapes(a.dump)
    for step, time, arr in frames:
        path = os.path.join(out, f"{stem}_{step}.png")
        shaped = {}
        if shapes is not None and "shape" in arr and "orientation" in arr:
            shaped = {"shapes": shapes, "shape": arr["shape"], "quat": arr["orientation"]}
        render_cross_section(path, arr["position"], arr["velocity"], arr["radius"], axis=axis, centre=centre,
                             drum_radius=a.radius or None, up=a.up, vmax=a.vmax,
                             title=f"step {step}   t = {time:.4g} s", size_px=a.size, **shaped)
        print(path)


if __name__ == "__main__":
    sys.exit(main())
