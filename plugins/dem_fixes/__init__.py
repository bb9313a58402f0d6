"""Plugin: fix `gravity`."""
from dem.hookspecs import hookimpl

from .fix_gravity import FixGravity


@hookimpl
def dem_styles():
    return [FixGravity]
