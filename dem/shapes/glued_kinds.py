"""The glued composite kinds of the `shape` command (dem/shapes/glued.py, Part III):

    shape NAME glued component KIND params... [at X Y Z] [rotate AX AY AZ DEG] [crust C] component ...
    shape NAME glued file F
    shape NAME cross2d L [aspect A] | cross3d L [aspect A] | tilespacer L W T | slicedcylinder R L N
    shape NAME cube8 A | spherecylinder R L 9|54 | multisphere X Y Z R [X Y Z R ...]
    ... [crust C] [resolution N] [db FILE|none]

A component is any convex kind of the shape command with its parameters, placed with its centre of mass
at (X, Y, Z) of the composite's frame (default the origin) and turned by DEG degrees about the axis
(AX, AY, AZ). A file lists one component per line, in the same words without `component` (`#` starts a
comment). `crust C` after the last component gives every component that crust (default: 5 % of each
component's inradius). Overlapping components make the mass properties come from the lattice
integration at `resolution` points along the longest side (default 500, Part III sec 2.3), cached in the
shape database `db` (default $DEM_SHAPE_DB, else ~/.cache/dem/shapes.h5; `none`: no cache).
"""
import os

import numpy as np

from ..files import check_target
from . import glued_builtins as gb
from .base import check_lengths
from .convex_kinds import SHAPE_KINDS
from .glued import DEFAULT_RESOLUTION, Glued

COMMON = {"crust": 1, "resolution": 1, "db": 1}


def axis_angle(axis, degrees):
    """Rotation matrix of `degrees` about `axis`."""
    u = np.asarray(axis, dtype=float)
    n = np.linalg.norm(u)
    if not n > 0:
        raise ValueError("rotate: the axis must not be zero")
    u = u / n
    t = np.radians(degrees)
    K = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return np.eye(3) + np.sin(t) * K + (1 - np.cos(t)) * K @ K


class GluedKind:
    """Base of the composite kinds: `components(a, values)` from the numbers given; the common keywords
    are read here. `raw` tells the shape command to hand over the words."""
    kind = "shape"
    raw = True
    style = None
    usage = ""

    def __init__(self, sim):
        self.sim = sim

    def parse(self, a, start):
        """The Glued shape from the words of Args `a` from `start`."""
        i, values = start, []
        while i < len(a) and a[i] not in COMMON:
            values.append(a.float(i, f"{self.style} parameter"))
            i += 1
        opts = a.keywords(i, COMMON)
        crust = a.to_float(opts["crust"][0], "crust") if "crust" in opts else None
        try:
            check_lengths(values, f"{self.style} parameters")
        except ValueError as e:
            raise a.error(str(e)) from None
        return self.build(a, lambda: self.components(a, values, crust), opts)

    def build(self, a, make, opts):
        resolution = DEFAULT_RESOLUTION
        if "resolution" in opts:
            resolution = a.to_int(opts["resolution"][0], "resolution")
            if not 8 <= resolution <= 5000:
                raise a.error(f"resolution must be in 8..5000, got {resolution}")
        db = opts.get("db", [None])[0]
        if db is not None and db.strip().lower() != "none":
            check_target(os.path.expanduser(db), f"{a.what}: db")
        try:
            comps = make()
            return Glued(comps, resolution=resolution, db=db, comm=self.sim.comm, name=self.style)
        except (ValueError, OSError) as e:
            raise a.error(str(e)) from None

    def components(self, a, values, crust):
        raise NotImplementedError


def _fixed(style, n, factory, usage, doc, optional=None):
    """A built-in composite of n numbers (optional: name and default of one more keyword value)."""

    def components(self, a, values, crust):
        if len(values) != n:
            raise a.error(f"{style} needs {n} number(s): {usage}")
        return factory(*values, crust=crust)

    return type("Shape" + style.title(), (GluedKind,), {"style": style, "usage": usage, "__doc__": doc,
                                                        "components": components})


class ShapeCross(GluedKind):
    """shape NAME cross2d|cross3d L [aspect A]: beams of length L and square section L/A (default A = 4)."""
    usage = "L [aspect A] [crust C] [resolution N] [db FILE|none]"

    def parse(self, a, start):
        spec = dict(COMMON, aspect=1)
        if start >= len(a):
            raise a.error(f"{self.style} needs the beam length L")
        L = a.float(start, "beam length L", positive=True)
        try:
            check_lengths([L], "beam length L")
        except ValueError as e:
            raise a.error(str(e)) from None
        opts = a.keywords(start + 1, spec)
        aspect = a.to_float(opts["aspect"][0], "aspect") if "aspect" in opts else gb.DEFAULT_ASPECT
        crust = a.to_float(opts["crust"][0], "crust") if "crust" in opts else None
        factory = gb.cross2d if self.style == "cross2d" else gb.cross3d
        return self.build(a, lambda: factory(L, aspect, crust=crust), opts)


class ShapeCross2d(ShapeCross):
    __doc__ = ShapeCross.__doc__
    style = "cross2d"


class ShapeCross3d(ShapeCross):
    __doc__ = ShapeCross.__doc__
    style = "cross3d"


class ShapeMultisphere(GluedKind):
    """shape NAME multisphere X Y Z R [X Y Z R ...]: glued spheres (a clump)."""
    style = "multisphere"
    usage = "X Y Z R [X Y Z R ...] [crust C] [resolution N] [db FILE|none]"

    def components(self, a, values, crust):
        if not values or len(values) % 4:
            raise a.error("multisphere needs groups of 4 numbers: X Y Z R")
        return gb.multisphere(np.reshape(values, (-1, 4)), crust=crust)


class ShapeGlued(GluedKind):
    """shape NAME glued component KIND params... [at X Y Z] [rotate AX AY AZ DEG] [component ...] | file F
    [crust C] [resolution N] [db FILE|none]

    A non-convex particle glued from convex components (Grains3D Part III): KIND is any convex kind of the
    shape command with its parameters, placed with its centre of mass at (X, Y, Z) and turned by DEG
    degrees about (AX, AY, AZ). A file lists one component per line in the same words without
    `component` (`#` comments). Mass properties: exact without overlaps and for boxes with common axes,
    else the lattice at `resolution` points along the longest side (default 500), cached in the shape
    database `db` (default $DEM_SHAPE_DB, else ~/.cache/dem/shapes.h5). Contacts: pair_style
    glued/convex. See docs/composites.md.

    Example::

        shape tee glued component box 0.006 0.001 0.001 component box 0.001 0.001 0.004 at 0 0 -0.0025
    """
    style = "glued"
    usage = ("component KIND params... [at X Y Z] [rotate AX AY AZ DEG] ... | file F  "
             "[crust C] [resolution N] [db FILE|none]")

    def parse(self, a, start):
        words = list(a.words[start:])
        tail = len(words)
        for k, w in enumerate(words):     # the common keywords follow the components
            if w in COMMON and (k == 0 or words[k - 1] not in ("at", "rotate")):
                tail = k
                break
        opts = a.keywords(start + tail, COMMON)
        crust = a.to_float(opts["crust"][0], "crust") if "crust" in opts else None
        body = words[:tail]
        if body[:1] == ["file"]:
            if len(body) != 2:
                raise a.error("glued file F takes only the file name (then crust, resolution, db)")
            lines = self._read(a, body[1])
        else:
            if not body or body[0] != "component":
                raise a.error("glued needs 'component KIND params...' (one per component) or 'file F'")
            lines, cur = [], None
            for w in body:
                if w == "component":
                    cur = []
                    lines.append((f"component {len(lines) + 1}", cur))
                else:
                    cur.append(w)
        return self.build(a, lambda: [self._component(a, where, ws, crust) for where, ws in lines], opts)

    def _read(self, a, path):
        try:
            with open(path, "rb") as f:
                data = f.read()
        except OSError as e:
            raise a.error(f"cannot read component file '{path}': {e.strerror}") from None
        try:
            if b"\0" in data:              # UTF-8 text never holds a NUL byte; binary files mostly do
                raise UnicodeDecodeError("utf-8", data, data.index(b"\0"), data.index(b"\0") + 1, "NUL")
            text = data.decode("utf-8-sig")
        except UnicodeDecodeError as e:
            raise a.error(f"component file '{path}' is not a text file (byte {e.start} is "
                          f"0x{data[e.start]:02x}): it lists one component per line, e.g. "
                          f"'box 0.001 0.001 0.002 at 0 0 0'") from None
        out = []
        for n, line in enumerate(text.splitlines(), 1):
            ws = line.split("#", 1)[0].split()
            if ws:
                out.append((f"{path} line {n}", ws))
        if not out:
            raise a.error(f"component file '{path}' lists no component")
        return out

    def _component(self, a, where, ws, crust):
        if not ws:
            raise a.error(f"{where}: empty component")
        kinds = {c.style: c for c in SHAPE_KINDS}
        cls = kinds.get(ws[0])
        if cls is None:
            raise a.error(f"{where}: unknown component kind '{ws[0]}' (convex kinds: {', '.join(kinds)})")
        off, rot, values, i = np.zeros(3), np.eye(3), [], 1
        while i < len(ws):
            w = ws[i]
            if w == "at":
                if len(ws) < i + 4:
                    raise a.error(f"{where}: 'at' needs X Y Z")
                off = np.array([a.to_float(v, f"{where}: at") for v in ws[i + 1:i + 4]])
                try:
                    check_lengths(off, f"{where}: at")
                except ValueError as e:
                    raise a.error(str(e)) from None
                i += 4
            elif w == "rotate":
                if len(ws) < i + 5:
                    raise a.error(f"{where}: 'rotate' needs AX AY AZ DEG")
                v = [a.to_float(x, f"{where}: rotate") for x in ws[i + 1:i + 5]]
                try:
                    rot = axis_angle(v[:3], v[3]) @ rot
                except ValueError as e:
                    raise a.error(f"{where}: {e}") from None
                i += 5
            else:
                values.append(a.to_float(w, f"{where}: {ws[0]} parameter"))
                i += 1
        if cls.nparams is not None and len(values) != cls.nparams:
            raise a.error(f"{where}: {ws[0]} needs {cls.nparams} number(s): {cls.usage}")
        try:
            shape = cls(self.sim).build(values, crust, None)
        except ValueError as e:
            raise a.error(f"{where}: {e}") from None
        return shape, off, rot


GLUED_KINDS = [
    ShapeGlued, ShapeCross2d, ShapeCross3d, ShapeMultisphere,
    _fixed("tilespacer", 3, gb.tile_spacer, "L W T [crust C] [resolution N] [db FILE|none]",
           "shape NAME tilespacer L W T: a tile spacer (Part III Fig. 13), plates L x W x T along x and y."),
    _fixed("slicedcylinder", 3, gb.sliced_cylinder, "R L N [crust C]",
           "shape NAME slicedcylinder R L N: the cylinder (radius R, length L, axis z) cut into N equal "
           "slices (Part III Fig. 6b)."),
    _fixed("cube8", 1, gb.cube_of_cubes, "A [crust C]",
           "shape NAME cube8 A: the cube of edge A glued from 8 cubes of edge A/2 (Part III sec 3.3)."),
    _fixed("spherecylinder", 3, gb.sphere_cylinder, "R L 9|54 [crust C] [resolution N] [db FILE|none]",
           "shape NAME spherecylinder R L N: the cylinder (R, L) as N = 9 or 54 glued spheres (Part III "
           "Fig. 10)."),
]
