"""Plugin: the wall fixes, `wall/plane` (fixed planes) and `wall/drum` (a rotating cylinder with optional
ends). Every wall is a set of surfaces (dem/contact/_surface.pxd) handed to one kernel (`_walls.pyx`) and
the shared law; a new wall style builds its surfaces table in a subclass of WallFix."""
from dem.hookspecs import hookimpl

from .fix_wall_drum import FixWallDrum
from .fix_wall_plane import FixWallPlane


@hookimpl
def dem_styles():
    return [FixWallPlane, FixWallDrum]
