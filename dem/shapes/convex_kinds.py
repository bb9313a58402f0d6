"""The convex kinds of the `shape` command: each a style of kind ``shape`` whose `make` builds a
:class:`dem.shapes.Shape` from the numbers given (the composites are in dem/shapes/glued_kinds.py; the
command itself, which looks a kind up in the registry, in dem/shapes/command.py).
"""
import numpy as np

from .base import check_lengths

from .polyhedron import Polyhedron, nonconvex_note, pinacoid, read_mesh, tetrahedron
from .primitives import Box, Cone, Cylinder, Ellipsoid, Sphere, Superquadric, cube


class ShapeKind:
    """Base of shape styles: `nparams` numbers (None: any count handled by `make`), `make(values, crust,
    file)` returns a dem.shapes.Shape."""
    kind = "shape"
    style = None
    usage = ""
    nparams = 0

    def __init__(self, sim):
        self.sim = sim

    def make(self, values, crust, file):
        raise NotImplementedError

    def build(self, values, crust, file):
        """make() after checking that the numbers are finite and bounded (base.check_lengths)."""
        check_lengths(values, f"{self.style} parameters")
        return self.make(values, crust, file)


def _simple(style_name, factory, n, usage, doc):
    cls = type("Shape" + style_name.title().replace("/", ""), (ShapeKind,),
               {"style": style_name, "usage": usage, "nparams": n, "__doc__": doc,
                "make": lambda self, v, crust, file: factory(*v, crust=crust)})
    return cls


SHAPE_KINDS = [
    _simple("sphere", Sphere, 1, "R", "shape NAME sphere R\n\n    Sphere of radius R (through the shape "
            "table: spheres mixed with convex bodies; a plain sphere needs no shape)."),
    _simple("box", Box, 3, "A B C", "shape NAME box A B C\n\n    Box of edge lengths A, B, C along the body "
            "axes x, y, z."),
    _simple("cube", cube, 1, "A", "shape NAME cube A\n\n    Cube of edge A."),
    _simple("cylinder", Cylinder, 2, "R L", "shape NAME cylinder R L\n\n    Circular cylinder of radius R "
            "and length L, axis along body z."),
    _simple("cone", Cone, 2, "R H", "shape NAME cone R H\n\n    Right circular cone of base radius R and "
            "height H, axis body z, apex up; the centre of mass (H/4 above the base) is the body origin."),
    _simple("ellipsoid", Ellipsoid, 3, "A B C", "shape NAME ellipsoid A B C\n\n    Ellipsoid of semi-axes "
            "A, B, C."),
    _simple("superquadric", Superquadric, 5, "A B C N1 N2",
            "shape NAME superquadric A B C N1 N2\n\n    (|x/A|^N2 + |y/B|^N2)^(N1/N2) + |z/C|^N1 <= 1, half "
            "sizes A B C, exponents N1, N2 >= 2."),
    _simple("tetrahedron", tetrahedron, 1, "EDGE", "shape NAME tetrahedron EDGE\n\n    Regular tetrahedron."),
]


class ShapePinacoid(ShapeKind):
    """shape NAME pinacoid L G E [ALPHA]

    Descantes' pinacoid: length L, width G, thickness E, end-face angle ALPHA (degrees, default 60)."""
    style = "pinacoid"
    usage = "L G E [ALPHA]"
    nparams = None

    def make(self, values, crust, file):
        if len(values) not in (3, 4):
            raise ValueError("pinacoid needs L G E [ALPHA]")
        return pinacoid(*values, crust=crust)


class ShapePolyhedron(ShapeKind):
    """shape NAME polyhedron X1 Y1 Z1 X2 Y2 Z2 ... | shape NAME polyhedron file F.obj|F.stl

    Convex hull of the given points (at least 4 distinct, not all coplanar; repeated points are merged),
    or of the vertices of an OBJ or STL file. The body frame is the principal frame through the centre of
    mass. A polyhedron thinner than 1e-6 of its largest extent is an error (its crust and faces would be
    round-off). A mesh that is not convex gets a warning with the volume its hull adds (closed meshes; an
    open one: the vertices inside the hull): a non-convex grain is `shape NAME glued` of convex parts."""
    style = "polyhedron"
    usage = "X Y Z X Y Z ... | file F"
    nparams = None

    def make(self, values, crust, file):
        if file is not None:
            if values:
                raise ValueError("give either vertices or a file")
            V, T = read_mesh(file)
            shape = Polyhedron(V, crust=crust, name=str(file).rsplit("/", 1)[-1].rsplit(".", 1)[0])
            note = nonconvex_note(V, T, shape)
            if note:
                where = self.sim.input.location
                self.sim.warning(f"{where + ': ' if where else ''}shape polyhedron file {file}: {note}")
            return shape
        if len(values) < 12 or len(values) % 3:
            raise ValueError("a polyhedron needs at least 4 points (x y z each) or 'file F'")
        return Polyhedron(np.array(values).reshape(-1, 3), crust=crust)


SHAPE_KINDS += [ShapePinacoid, ShapePolyhedron]
