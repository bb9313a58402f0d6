"""Plugin: fixes `gravity` and `wall/plane`."""
from dem.hookspecs import hookimpl

from .fix_gravity import FixGravity
from .fix_wall_plane import FixWallPlane


@hookimpl
def dem_styles():
    return [FixGravity, FixWallPlane]
