"""dump png"""
import os

from dem.dump import Dump
from dem.errors import DemError
from dem.files import check_target, ensure_dir

from ._common import find_drum, up_direction
from .render import render_cross_section


class DumpPNG(Dump):
    """dump ID group png N FILE [drum FIX-ID | axis x|y|z centre C1 C2 [radius R]] [slice S] [vmax V] [size PX]

    Pictures of the particles seen along an axis (a drum's cross-section, Part III Fig. 20), coloured by
    translational velocity magnitude from blue (0) to red (V, default: the fastest particle of the
    frame), one PNG per frame: a `*` in FILE is replaced by the step (without one, each frame replaces
    the last). `drum FIX-ID` takes axis, centre and radius from a fix wall/drum; otherwise `axis` (default
    y) and `centre` (the two other coordinates, in x, y, z order; default the box centre), `radius` the
    circle drawn (optional). The vertical of the picture is opposite to gravity. `size` in pixels
    (default 700). Needs matplotlib. Example: `dump pic all png 50000 drum_*.png drum drum vmax 0.5`.

    What is drawn: by default the projection along the axis, every particle of the group, the nearer to
    the viewer on top: a sphere is a disc of its radius, a shaped particle (`shape`) the outline of its
    body in its present orientation and size, i.e. the convex hull of the projected vertices of its surface
    mesh (one filled polygon per convex piece of its shape). `slice S`: only the particles cut by the plane
    across the axis at coordinate S along it (e.g. `slice 0.012` for the plane y = 0.012), each drawn as
    its true section by that plane: a disc of the sphere's section, the polygon where the plane cuts the
    mesh of each convex piece of a shaped particle; particles the plane misses are not drawn (a particle
    is cut at its position in the box, not at its periodic images). Mesh walls (`fix wall/mesh`) are drawn
    as their section by the picture's plane (the slice, or the plane through the centre), grey lines."""

    style = "png"
    keywords = {"fields": None, "drum": 1, "axis": 1, "centre": 2, "radius": 1, "slice": 1, "vmax": 1,
                "size": 1}

    def __init__(self, sim, did, group, every, path, args):
        self.drum_id = None
        self.axis = 1
        self.centre2 = None
        self.drum_radius = None
        self.slice = None
        self.vmax = None
        self.size = 700
        super().__init__(sim, did, group, every, path, args)
        try:
            import matplotlib  # noqa: F401  (checked now rather than at the first frame, mid-run)
        except ImportError:
            raise DemError(f"dump {did} png needs matplotlib (pip install matplotlib)") from None

    def keyword(self, word, values):
        try:
            if word == "drum":
                self.drum_id = values[0]
            elif word == "axis":
                if values[0] not in ("x", "y", "z"):
                    raise DemError(f"dump {self.id}: axis must be x, y or z")
                self.axis = "xyz".index(values[0])
            elif word == "centre":
                self.centre2 = [float(values[0]), float(values[1])]
            elif word == "radius":
                self.drum_radius = float(values[0])
            elif word == "slice":
                self.slice = float(values[0])
            elif word == "vmax":
                self.vmax = float(values[0])
            elif word == "size":
                self.size = int(values[0])
            else:
                super().keyword(word, values)
        except ValueError:
            raise DemError(f"dump {self.id}: {word} needs number(s), got {' '.join(values)}") from None

    def gathered_fields(self):
        names = ["id", "position", "velocity", "radius"]
        if len(self.sim.shapes):
            names += ["orientation", "shape"]      # to pose the shaped particles' meshes
        return names

    def view(self):
        if self.drum_id is not None:
            drum = find_drum(self.sim, self.drum_id, f"dump {self.id} png")
            return drum.axis, drum.centre, drum.radius
        dom = self.sim.domain
        centre = 0.5 * (dom.lo + dom.hi)
        if self.centre2 is not None:
            centre[[d for d in range(3) if d != self.axis]] = self.centre2
        return self.axis, centre, self.drum_radius

    def write_frame(self, frame):
        axis, centre, rdrum = self.view()
        path = self.path.replace("*", str(frame.step))
        check_target(path, f"dump {self.id}")
        ensure_dir(path)
        title = f"step {frame.step}   t = {frame.time:.4g} s"
        drum = self.sim.modify.find(self.drum_id) if self.drum_id else None
        if drum is not None:
            title += f"   {drum.omega * 60 / (2 * 3.141592653589793):.3g} rpm"
        arrays = frame.arrays
        shaped = {}
        if len(self.sim.shapes) and "shape" in arrays and "orientation" in arrays:
            shaped = {"shapes": self.sim.shapes, "shape": arrays["shape"], "quat": arrays["orientation"]}
        section = None
        if self.slice is not None:
            section = self.slice - float(centre[axis])
            title += f"   slice {'xyz'[axis]} = {self.slice:.4g}"
        render_cross_section(path, arrays["position"], arrays["velocity"], arrays["radius"],
                             axis=axis, centre=centre, drum_radius=rdrum, up=up_direction(self.sim),
                             vmax=self.vmax, title=title, size_px=self.size, section=section,
                             spin=drum.omega if drum is not None else 0.0,
                             walls=[w for w in (f.surface_mesh() for f in self.sim.modify.fixes) if w is not None],
                             **shaped)
        self.last_path = os.path.abspath(path)
