"""The one hook a plugin implements. Plugins only announce classes; the core builds and calls them.

A plugin is a module registered in the entry-point group ``dem`` (``setup.py``/``pyproject.toml``)::

    entry_points={"dem": ["myplugin = my_package"]}

whose module defines::

    from dem.hookspecs import hookimpl

    @hookimpl
    def dem_styles():
        return [FixMyThing, PairMyLaw]

Each class carries ``kind`` (one of ``command, pair, fix, region, dump, shape, compute``) and ``style``
(the name used in input scripts, e.g. ``"wall/plane"``); its docstring is its documentation.
"""
import pluggy

hookspec = pluggy.HookspecMarker("dem")
hookimpl = pluggy.HookimplMarker("dem")


@hookspec
def dem_styles():
    """Return a list of style classes (each with ``kind`` and ``style`` attributes)."""
