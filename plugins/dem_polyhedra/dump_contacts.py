"""dump style contacts: the contact points of pair_style polyhedron/multipoint as VTK PolyData, for ParaView."""
import numpy as np

from dem.dump import Frame
from dem.dump_vtp import DumpVTP
from dem.errors import DemError

TYPE_NAMES = ("vertex_face", "edge_edge", "edge_face", "face_face", "sphere")   # type 1 .. 5


class DumpContacts(DumpVTP):
    """dump ID all contacts N file_*.vtp [format binary|ascii] [pvd file.pvd|none]

    Every contact point of `pair_style polyhedron/multipoint` at the steps the dump writes, one VTK XML
    PolyData file per frame (a vertex per point) and a .pvd collection for ParaView (as ``dump vtp``).
    Point data: ``type`` (the pair's contact type: 1 vertex/face, 2 edge/edge, 3 edge/face, 4 face/face,
    5 a pair with a sphere), ``normal`` (unit, from the second particle towards the first), ``force``
    (on the first particle at this point: normal and tangential), ``overlap`` (the pair's shared maximum
    overlap, m) and ``ids`` (the two particles). The kernel records the points it applies, on those steps
    only (no second geometry path); wall contacts are not included. In ParaView: open the .pvd with the
    particles' dump (``dump vtk``), then a Glyph filter (arrows oriented by ``force`` or ``normal``, coloured
    by ``type``). The group must be all (a pair belongs to no single group).

    Example::

        dump cp all contacts 1000 post/contacts_*.vtp
    """

    style = "contacts"
    keywords = {"format": 1, "pvd": 1}
    records_contact_points = True      # read by pair_style polyhedron/multipoint (pair_polyhedron.py)
    writes_walls = False

    def __init__(self, sim, did, group, every, path, args):
        super().__init__(sim, did, group, every, path, args)
        if group != "all":
            raise DemError(f"dump {did} contacts: a contact belongs to two particles: use group all")

    def gather(self, step):
        sim = self.sim
        pair = sim.pair
        if pair is None or not hasattr(pair, "contact_points"):
            raise DemError(f"dump {self.id} contacts needs pair_style polyhedron/multipoint (the pair style "
                           f"is {getattr(pair, 'style', 'not set')})")
        if pair.contact_points_step != step:
            raise DemError(f"dump {self.id} contacts: no contact points were recorded at step {step} (the pair "
                           "style records them when it computes a step the dump writes)")
        pts = pair.contact_points
        values = np.column_stack([pts["point"], pts["normal"], pts["force"], pts["overlap"], pts["type"]])
        ids, values = sim.comm.gather_rows(pts["ids"], values)
        if sim.comm.me != 0:
            return None
        order = np.lexsort((values[:, 2], values[:, 1], values[:, 0], ids[:, 1], ids[:, 0]))  # any rank count
        ids, values = ids[order], values[order]
        arrays = {"position": np.ascontiguousarray(values[:, 0:3]), "normal": np.ascontiguousarray(values[:, 3:6]),
                  "force": np.ascontiguousarray(values[:, 6:9]), "overlap": np.ascontiguousarray(values[:, 9]),
                  "type": values[:, 10].astype(np.int32), "ids": np.ascontiguousarray(ids)}
        return Frame(step, sim.update.time, sim.domain.lo, sim.domain.hi, arrays)

    def point_data(self, frame):
        return ([(name, frame.arrays[name]) for name in ("type", "normal", "force", "overlap", "ids")],
                ' Scalars="type" Vectors="force"')
