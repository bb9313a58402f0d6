"""Style registry: loads every plugin of the entry-point group ``dem`` once, at start-up (never per step),
and maps (kind, style name) to a class. A duplicate name is an error naming both providers."""
import pluggy

from . import hookspecs
from .errors import DemError, unknown_style

KINDS = ("command", "pair", "fix", "region", "dump", "shape", "compute")


class Registry:
    def __init__(self, extra_plugins=()):
        self.pm = pluggy.PluginManager("dem")
        self.pm.add_hookspecs(hookspecs)
        self.pm.load_setuptools_entrypoints("dem")
        for plugin in extra_plugins:
            self.pm.register(plugin)
        self.styles = {kind: {} for kind in KINDS}
        self._provider = {}
        for plugin in self.pm.get_plugins():
            name = self.pm.get_name(plugin)
            impl = getattr(plugin, "dem_styles", None)
            if impl is None:
                continue
            for cls in impl() or []:
                self.add(cls, name)

    def add(self, cls, provider="user"):
        kind, style = getattr(cls, "kind", None), getattr(cls, "style", None)
        if kind not in self.styles or not style:
            raise DemError(f"plugin '{provider}' announces {cls!r} without a valid kind/style")
        key = (kind, style)
        if key in self._provider and self.styles[kind][style] is not cls:
            raise DemError(f"{kind} style '{style}' is provided twice: by '{self._provider[key]}' "
                           f"and by '{provider}'")
        self.styles[kind][style] = cls
        self._provider[key] = provider

    def get(self, kind, style, args=()):
        """The class of a style; `args` (the words after the style) choose the LIGGGHTS/LAMMPS answer of an
        unknown one (`pair_style gran model hooke`)."""
        try:
            return self.styles[kind][style]
        except KeyError:
            raise unknown_style(kind, style, self.styles[kind], args) from None

    def provider(self, kind, style):
        return self._provider[(kind, style)]


_cached = None


def default_registry():
    """The registry of installed plugins, built once per process."""
    global _cached
    if _cached is None:
        _cached = Registry()
    return _cached
