"""dump style gsd: frames in one HOOMD-blue GSD file, whose per-type shapes OVITO draws: every particle
with its true shape (composites, polyhedra, cylinders ...), posed by its orientation and scaled by its
radius."""
import numpy as np

from .dump import Dump
from .errors import DemError
from .files import check_target, ensure_dir

SPHERE_TYPE = "sphere"     # GSD type 0: the spheres; type k + 1 is row k of the shape table


class DumpGSD(Dump):
    """dump ID group-ID gsd N file.gsd

    Writes every frame into one GSD file (the format of HOOMD-blue, through the `gsd` package: pip
    install gsd) that OVITO opens with every particle drawn in its true shape: GSD's per-type shapes
    (``particles/type_shapes``) hold the surface mesh of each row of the shape table, which OVITO poses
    at each particle by its orientation and scales by its radius. Type 0 is ``sphere`` (the spheres,
    drawn with their radius), type k + 1 the shape table's row k under its name; the particle's dem type
    is not written.

    Per particle: ``position`` (relative to the box centre: GSD boxes are centred on the origin),
    ``orientation`` (w x y z), ``typeid``, ``diameter`` (twice the bounding radius), ``velocity``,
    ``mass``, and ``log/particles/id`` (dem's particle id; OVITO reads it as a particle property). Per
    frame: the step (``configuration/step``), the box lengths, and the time (``log/dem/time``). The
    first frame replaces an old file; the file is valid after every frame, so OVITO can load it while
    the run goes on.

    Example::

        dump ov all gsd 2000 drum.gsd

    Open ``drum.gsd`` in OVITO (File > Load File): the crosses, tetrahedra or polyhedra appear as such.
    """

    style = "gsd"
    keywords = {}

    def __init__(self, sim, did, group, every, path, args):
        super().__init__(sim, did, group, every, path, args)
        if "*" in self.path:
            raise DemError(f"dump {did}: dump gsd writes every frame into one file: no '*' in '{self.path}'")
        try:
            import gsd.hoomd  # noqa: F401  (the writer: checked now, not at the first frame)
        except ImportError:
            raise DemError(f"dump {did}: dump gsd needs the gsd package (pip install gsd)") from None
        self._started = False
        self._shapes = None        # type_shapes, made again only when the shape table grows

    def gathered_fields(self):
        return ["id", "position", "orientation", "velocity", "mass", "radius", "shape"]

    def type_shapes(self):
        """GSD shapes of the types: the spheres', then each shape row's surface mesh at bounding radius 1
        (OVITO scales a type's mesh by the particle's radius)."""
        table = self.sim.shapes
        if self._shapes is not None and len(self._shapes) == len(table) + 1:     # rows are only added
            return self._shapes
        shapes = [{"type": "Sphere", "diameter": 2.0}]
        for k in range(len(table)):
            verts, faces = table.mesh(k)
            shapes.append({"type": "Mesh", "vertices": (verts / float(table.radius[k])).tolist(),
                           "indices": np.asarray(faces).tolist()})
        self._shapes = shapes
        return shapes

    def write_frame(self, frame):
        import gsd.hoomd
        a = frame.arrays
        g = gsd.hoomd.Frame()
        g.configuration.step = frame.step
        g.configuration.box = [*(frame.hi - frame.lo), 0.0, 0.0, 0.0]
        g.particles.N = frame.count
        g.particles.types = [SPHERE_TYPE] + list(self.sim.shapes.names)
        g.particles.type_shapes = self.type_shapes()
        g.particles.typeid = (np.asarray(a["shape"]) + 1).astype(np.uint32)
        g.particles.position = a["position"] - 0.5 * (frame.lo + frame.hi)
        g.particles.orientation = a["orientation"]
        g.particles.diameter = 2.0 * a["radius"]
        g.particles.velocity = a["velocity"]
        g.particles.mass = a["mass"]
        g.log["particles/id"] = np.asarray(a["id"], dtype=np.int64)
        g.log["dem/time"] = np.array([frame.time])
        check_target(self.path, f"dump {self.id}")
        ensure_dir(self.path)
        with gsd.hoomd.open(self.path, "a" if self._started else "w") as f:
            f.append(g)
        self._started = True
