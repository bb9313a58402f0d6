"""dump style h5: every frame of a dump in one HDF5 file, plus an XDMF sidecar for ParaView."""
import os
from xml.sax.saxutils import quoteattr

import numpy as np

from .dump import Dump, atomic_write, ensure_dir
from .errors import DemError

FORMAT = "dem-dump-h5"
VERSION = 1

# XDMF attribute name and type of each field (position is the geometry)
XDMF_NAMES = {
    "id": "id",
    "type": "type",
    "velocity": "velocity",
    "omega": "omega",
    "orientation": "orientation",
    "radius": "radius",
    "mass": "mass",
    "shape": "shape",
}


def frame_name(step):
    """Name of the HDF5 group of a frame under /frames (zero-padded: sorts by step)."""
    return f"{int(step):010d}"


def _number_type(dtype):
    dtype = np.dtype(dtype)
    if dtype.kind == "f":
        return "Float", dtype.itemsize
    if dtype.kind == "i":
        return "Int", dtype.itemsize
    if dtype.kind == "u":
        return ("UChar", 1) if dtype.itemsize == 1 else ("UInt", dtype.itemsize)
    raise TypeError(f"no XDMF number type for {dtype}")


def _attribute_type(shape):
    # an (n, 4) array must be a Vector: the XDMF readers make Matrix one tuple of all values
    return "Scalar" if len(shape) == 1 else "Vector"


def _data_item(h5name, path, shape, dtype):
    ntype, precision = _number_type(dtype)
    dims = " ".join(str(int(d)) for d in shape)
    return (f'<DataItem Dimensions="{dims}" NumberType="{ntype}" Precision="{precision}" '
            f'Format="HDF">{_escape(h5name)}:{path}</DataItem>')


def _escape(text):
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def xdmf_grid(h5name, step, time, datasets):
    """XDMF text of one frame. `datasets`: {field: (shape, dtype)} of the frame's datasets. Radius comes
    first (the active scalar); a frame without particles gets an empty inline geometry (the readers
    fail on empty HDF5 data items)."""
    base = f"/frames/{frame_name(step)}"
    n = int(datasets["position"][0][0])
    lines = [f'      <Grid Name="step_{int(step)}" GridType="Uniform">',
             f'        <Time Value="{float(time)!r}"/>',
             f'        <Topology TopologyType="Polyvertex" NumberOfElements="{n}" NodesPerElement="1"/>',
             '        <Geometry GeometryType="XYZ">']
    if n == 0:
        lines.append('          <DataItem Dimensions="0 3" NumberType="Float" Precision="8" Format="XML">'
                     '</DataItem>')
    else:
        lines.append("          " + _data_item(h5name, f"{base}/position", *datasets["position"]))
    lines.append("        </Geometry>")
    order = sorted((f for f in datasets if f != "position"), key=lambda f: f != "radius")
    for field in order if n else ():
        shape, dtype = datasets[field]
        lines.append(f'        <Attribute Name={quoteattr(XDMF_NAMES[field])} '
                     f'AttributeType="{_attribute_type(shape)}" Center="Node">')
        lines.append("          " + _data_item(h5name, f"{base}/{field}", shape, dtype))
        lines.append("        </Attribute>")
    lines.append("      </Grid>")
    return "\n".join(lines) + "\n"


def xdmf_document(grids, name="particles"):
    """The whole XDMF file: a temporal collection of the given frame grids (texts of xdmf_grid)."""
    head = ('<?xml version="1.0" encoding="utf-8"?>\n'
            '<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>\n'
            '<Xdmf Version="3.0" xmlns:xi="http://www.w3.org/2001/XInclude">\n'
            '  <Domain>\n'
            f'    <Grid Name={quoteattr(name)} GridType="Collection" CollectionType="Temporal">\n')
    tail = "    </Grid>\n  </Domain>\n</Xdmf>\n"
    return head + "".join(grids) + tail


class DumpH5(Dump):
    """dump ID group-ID h5 N file.h5 [fields name ...]

    Writes every frame of the dump into ONE HDF5 file (h5py), and an XDMF sidecar ``file.xdmf`` (same
    folder, same name with the extension replaced) that ParaView opens as a time series of point sets
    ("Xdmf Reader" or "Xdmf3 Reader"); draw spheres with a Glyph filter: Sphere glyph, Scale Array
    ``radius``, scale factor 2 (glyph radius 0.5), no orientation.

    Example::

        dump snap all h5 1000 out/pour.h5
        dump grains big h5 500 big.h5 fields id position velocity radius

    Layout of the file (version 1)::

        /                      attributes: format="dem-dump-h5", version=1, dump_id, group, units
        /frames/0000001000     one group per frame (zero-padded step), attributes:
                                 step (int), time (float), natoms (int), box_lo, box_hi (3 floats)
            id           (n,)   int64    particle id          (ordered by id)
            type         (n,)   int32
            position     (n,3)  float64
            velocity     (n,3)  float64
            omega        (n,3)  float64  angular velocity
            orientation  (n,4)  float64  unit quaternion w x y z
            radius       (n,)   float64
            mass         (n,)   float64
            shape        (n,)   int32    shape index (-1: sphere)

    Keyword ``fields`` limits the per-particle datasets (``position`` is always written); default: all.

    The file is created at the first frame (a script that stops before its first run leaves no file;
    an existing file of that name is then replaced). It is opened for each frame and closed (flushed)
    right after: between frames it is complete, so it can be read while the run goes on (ParaView,
    h5py, in this process or another) and after a crash. The writer does not lock the file; a reader in
    this same process must have closed it before the next frame is written. The XDMF sidecar is
    rewritten atomically after every frame. A frame written again at the same step (two runs meeting at
    a step) replaces the earlier one.
    """

    style = "h5"
    keywords = {"fields": None}

    def __init__(self, sim, did, group, every, path, args):
        super().__init__(sim, did, group, every, path, args)
        if "*" in self.path:
            raise DemError(f"dump {did}: dump h5 writes all frames into one file: no '*' in its name "
                           f"('{self.path}')", hint="use dump vtk for one file per frame")
        if not self.path or self.path.endswith(os.sep):
            raise DemError(f"dump {did}: bad file name '{self.path}'")
        root, ext = os.path.splitext(self.path)
        self.xdmf_path = (root if ext else self.path) + ".xdmf"
        self._grids = {}          # step -> XDMF text of the frame (insertion order)
        self._created = False     # the file was created by this dump (later opens append)

    # ----- files ----------------------------------------------------------------------------------
    def _open(self):
        """Open the file for one frame: created (replacing an old one) at the first frame, appended to
        afterwards. Not locked, so that other programs may read it meanwhile."""
        try:
            import h5py
        except ImportError:
            raise DemError("dump h5 needs the h5py package (pip install h5py)") from None
        ensure_dir(self.path)
        mode = "a" if self._created else "w"
        try:
            try:
                f = h5py.File(self.path, mode, locking=False)
            except TypeError:      # h5py without the locking option
                f = h5py.File(self.path, mode)
        except OSError as e:
            raise DemError(f"dump {self.id}: cannot open '{self.path}' to write step "
                           f"{self.sim.update.ntimestep}: {e}",
                           hint="is the file open in this process (h5py)? close it before the run, or "
                                "open it with h5py.File(path, 'r', locking=False)") from None
        if not self._created:
            f.attrs["format"] = FORMAT
            f.attrs["version"] = VERSION
            f.attrs["dump_id"] = str(self.id)
            f.attrs["group"] = str(self.group)
            f.attrs["units"] = str(getattr(self.sim, "units", ""))
            f.require_group("frames")
            self._created = True
        return f

    def write_frame(self, frame):
        with self._open() as f:
            frames = f.require_group("frames")
            name = frame_name(frame.step)
            if name in frames:
                del frames[name]
            g = frames.create_group(name)
            g.attrs["step"] = np.int64(frame.step)
            g.attrs["time"] = np.float64(frame.time)
            g.attrs["natoms"] = np.int64(frame.count)
            g.attrs["box_lo"] = frame.lo
            g.attrs["box_hi"] = frame.hi
            datasets = {}
            for field in self.fields:
                data = frame.arrays[field]
                g.create_dataset(field, data=data)
                datasets[field] = (data.shape, data.dtype)
        self._grids.pop(frame.step, None)
        self._grids[frame.step] = xdmf_grid(os.path.basename(self.path), frame.step, frame.time, datasets)
        atomic_write(self.xdmf_path, xdmf_document(self._grids.values(), name=str(self.id)))
