"""One file, one output: the files claimed by the log, the dumps and the periodic restarts, so that the
command that would put a second output on a file (two HDF5 dumps mixing their frames, a dump truncating
the log, a restart replacing a dump) is refused, naming both uses. Names may hold one `*` (the step)."""
import os
import re

from .errors import DemError
from .files import check_target


def _key(path):
    return os.path.normcase(os.path.abspath(path))


def _matches(name, pattern):
    """A file name (or pattern) is one of the files of a pattern whose `*` stands for a step number."""
    if "*" not in pattern:
        return False
    regex = "[0-9*]+".join(re.escape(part) for part in pattern.split("*"))
    return re.fullmatch(regex, name) is not None


def clash(a, b):
    a, b = _key(a), _key(b)
    return a == b or _matches(a, b) or _matches(b, a)


class OutputNames:
    def __init__(self):
        self.claims = {}      # owner (e.g. "dump 1") -> [(file, use)]

    def check(self, paths, use, owner=None):
        """DemError if one of `paths` is a file of another owner's output, or names something other than a
        regular file (a name with `*` is checked as each of its files is written)."""
        for path in paths:
            if "*" not in path:
                check_target(path, use)
            for other, entries in self.claims.items():
                if other == owner:
                    continue
                for theirs, their_use in entries:
                    if clash(path, theirs):
                        raise DemError(f"{use}: file '{path}' is already written by {their_use} ('{theirs}'): "
                                       f"two outputs on one file destroy each other",
                                       hint="give each output its own file name")

    def claim(self, owner, paths, use):
        """Check, then record `paths` as the files of `owner` (replacing what it had)."""
        self.check(paths, use, owner)
        self.claims[owner] = [(p, use) for p in paths]

    def release(self, owner):
        self.claims.pop(owner, None)
