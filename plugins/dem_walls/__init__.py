"""Plugin: the wall fixes, `wall/plane` (fixed planes), `wall/drum` (a rotating cylinder with optional
ends) and `wall/mesh` (a rigid triangle mesh from STL or OBJ, at rest or moving). The plane and drum walls
are sets of surfaces (dem/contact/_surface.pxd) handed to one kernel (`_walls.pyx`), a new such style
builds its surfaces table in a subclass of WallFix; the mesh has its own kernel (`_wall_mesh.pyx`). All
apply the shared law (dem/law/apply.pxd)."""
from dem.hookspecs import hookimpl

from .fix_wall_drum import FixWallDrum
from .fix_wall_mesh import FixWallMesh
from .fix_wall_plane import FixWallPlane


@hookimpl
def dem_styles():
    return [FixWallPlane, FixWallDrum, FixWallMesh]
