"""Shape database: lattice mass properties of glued composites computed once and kept (Grains3D Part III sec
2.3: "computed once and for all for a certain shape and then stored in a shape database").

An HDF5 file (h5py), one group per entry under ``/entries``, named by the sha256 of

    definition text + resolution + ALGORITHM_VERSION

The definition text (``definition_text``) is canonical: per component its kind, its parameters and (for
polyhedra) body-frame vertices written to full precision (``float.hex``), its offset and rotation; crusts
do not change the body and are left out. An entry stores the full definition text, the resolution, the
version and a sha256 checksum of those and of the stored numbers; it is used only when all of them match
exactly, so a hash collision, a stale entry (older algorithm), a foreign or a tampered entry is never used
(it is recomputed and replaced). The whole file carries a SHA-256 checksum in its header
(``dem.verified_file``), checked before HDF5 opens it: a damaged or truncated file never reaches the HDF5
library (which could hang or crash on it). A file that cannot be read or fails the check gives a warning
and the properties are recomputed; writing goes to a temporary file renamed over the old one (atomic on
POSIX), under an advisory lock, and under MPI only rank 0 writes (``cached_union_mass_properties``
broadcasts). A path that is not a regular file (a device, a FIFO: ``dem.files``) is neither read nor
written (a warning); a damaged database, an empty file or an HDF5 file without the header (a database of
an older dem) is moved aside to ``PATH.corrupt`` when the next entry is stored; any other file is left as
it is and nothing is stored in it.

Path: ``ShapeDB(path)``; ``default_db()`` uses the environment variable ``DEM_SHAPE_DB`` if set, else
``~/.cache/dem/shapes.h5``; the value ``none`` disables the cache.
"""
import hashlib
import os
import warnings

import numpy as np

from .. import verified_file
from ..errors import DemError
from ..files import check_target, replace_file
from .base import KIND_NAMES, MARGIN, POLYHEDRON

__all__ = ["ShapeDB", "definition_text", "default_db", "cached_union_mass_properties", "ALGORITHM_VERSION",
           "ShapeDBWarning"]

ALGORITHM_VERSION = 1     # bump when the lattice integration changes its results
KIND = "shapes"           # of the checked file's header (verified_file)
# what verified_file.check may find that is ours to set aside (anything else is somebody else's file)
SET_ASIDE = (verified_file.DAMAGED, verified_file.EMPTY, verified_file.PLAIN_HDF5)
_FIELDS = ("volume", "centre", "inertia", "error")


class ShapeDBWarning(UserWarning):
    pass


def _hex(values):
    return " ".join(float(v).hex() for v in np.asarray(values, dtype=float).ravel())


def definition_text(components):
    """Canonical text of a composite's definition (what determines its mass properties)."""
    from .glued_mass import _components
    lines = ["glued %d" % len(_components(components))]
    for shape, off, rot in _components(components):
        params = np.array(shape.params, dtype=float)
        params[MARGIN] = 0.0
        lines.append("component %s" % KIND_NAMES.get(shape.kind, str(shape.kind)))
        lines.append("params " + _hex(params))
        if shape.kind == POLYHEDRON:
            lines.append("vertices %d %s" % (len(shape.vertices), _hex(shape.vertices)))
        lines.append("offset " + _hex(off))
        lines.append("rotation " + _hex(rot))
    return "\n".join(lines) + "\n"


def _key(definition, resolution):
    text = "%s\nresolution %d\nversion %d\n" % (definition, int(resolution), ALGORITHM_VERSION)
    return hashlib.sha256(text.encode()).hexdigest()


def _checksum(definition, resolution, version, arrays):
    h = hashlib.sha256()
    h.update(("%s\n%d\n%d\n" % (definition, int(resolution), int(version))).encode())
    for name in _FIELDS:
        h.update(name.encode())
        h.update(np.ascontiguousarray(arrays[name], dtype="<f8").tobytes())
    return h.hexdigest()


def _props_arrays(props):
    return {"volume": np.array([float(props["volume"])]),
            "centre": np.asarray(props["centre"], dtype=float).reshape(3),
            "inertia": np.asarray(props["inertia"], dtype=float).reshape(3, 3),
            "error": np.array([float(props.get("error", 0.0))])}


class ShapeDB:
    """``get(definition, resolution)`` -> dict (volume, centre, inertia, error, resolution) or None;
    ``put(definition, resolution, props)`` stores props (a dict with those keys)."""

    def __init__(self, path):
        self.path = os.path.abspath(os.path.expanduser(str(path)))

    def __repr__(self):
        return "ShapeDB(%r)" % self.path

    def _warn(self, msg):
        warnings.warn("shape database %s: %s" % (self.path, msg), ShapeDBWarning, stacklevel=3)

    def _regular(self):
        """False, with a warning, when the path names a device, a FIFO, a folder... (opening a FIFO would
        block; replacing a device would destroy it)."""
        try:
            check_target(self.path, "shape database")
        except DemError as e:
            warnings.warn(str(e), ShapeDBWarning, stacklevel=3)
            return False
        return True

    def get(self, definition, resolution):
        if not os.path.exists(self.path) or not self._regular():
            return None
        problem = verified_file.check(self.path, KIND)
        if problem is not None:
            self._warn("not read: it %s; recomputing" % problem[1])
            return None
        import h5py
        key = _key(definition, resolution)
        try:
            with h5py.File(self.path, "r") as f:
                g = f.get("entries/" + key)
                if g is None:
                    return None
                return self._read(g, definition, resolution)
        except Exception as e:          # checked whole: a file dem did not write so; recompute, never crash
            self._warn("unreadable (%s: %s); recomputing" % (type(e).__name__, e))
            return None

    def _read(self, g, definition, resolution):
        try:
            stored = g.attrs["definition"]
            stored = stored.decode() if isinstance(stored, bytes) else str(stored)
            res, version, checksum = int(g.attrs["resolution"]), int(g.attrs["version"]), str(g.attrs["checksum"])
            arrays = {name: np.asarray(g[name][()], dtype=float) for name in _FIELDS}
        except Exception as e:
            self._warn("entry %s is incomplete (%s); recomputing" % (g.name, e))
            return None
        if stored != definition or res != int(resolution) or version != ALGORITHM_VERSION:
            self._warn("entry %s belongs to another definition, resolution or version; recomputing" % g.name)
            return None
        if checksum != _checksum(stored, res, version, arrays) or arrays["centre"].shape != (3,) \
                or arrays["inertia"].shape != (3, 3) or not all(np.all(np.isfinite(a)) for a in arrays.values()):
            self._warn("entry %s fails its checksum; recomputing" % g.name)
            return None
        return {"volume": float(arrays["volume"][0]), "centre": arrays["centre"], "inertia": arrays["inertia"],
                "error": float(arrays["error"][0]), "resolution": res}

    def put(self, definition, resolution, props):
        """Store (replacing an entry of the same key); False with a warning if the file cannot be written."""
        key = _key(definition, resolution)
        arrays = _props_arrays(props)

        def write(tmp):
            with verified_file.hdf5_writer(tmp, KIND) as out:
                self._copy_entries(out, skip=key)
                g = out.require_group("entries").create_group(key)
                g.attrs["definition"] = definition
                g.attrs["resolution"] = int(resolution)
                g.attrs["version"] = ALGORITHM_VERSION
                g.attrs["checksum"] = _checksum(definition, resolution, ALGORITHM_VERSION, arrays)
                for name in _FIELDS:
                    g.create_dataset(name, data=arrays[name])

        if not self._regular():      # before the lock file is made beside it
            return False
        try:
            os.makedirs(os.path.dirname(self.path), exist_ok=True)
            with _Lock(self.path + ".lock"):
                replace_file(self.path, write, "shape database")
        except DemError as e:
            self._warn("not written (%s)" % e)
            return False
        except Exception as e:
            self._warn("not written (%s: %s)" % (type(e).__name__, e))
            return False
        return True

    def _copy_entries(self, out, skip):
        """Copy the readable entries of the current file into ``out``: a damaged database (or an empty file,
        or one of an older dem, without checksum) is set aside, unopened; any other file is not ours to
        move: DemError."""
        if not os.path.exists(self.path):
            return
        problem = verified_file.check(self.path, KIND)
        if problem is not None:
            reason, text = problem
            if reason not in SET_ASIDE:
                raise DemError("'%s' %s: left as it is" % (self.path, text))
            aside = self.path + ".corrupt"
            self._warn("it %s; moved to %s and started anew" % (text, aside))
            os.replace(self.path, aside)
            return
        import h5py
        try:
            with h5py.File(self.path, "r") as f:
                entries = f.get("entries")
                if entries is None:
                    return
                dst = out.require_group("entries")
                for name in entries:
                    if name != skip:
                        try:
                            f.copy(entries[name], dst, name=name)
                        except Exception:
                            pass
        except Exception as e:      # checked whole: a file dem did not write so
            aside = self.path + ".corrupt"
            self._warn("unreadable (%s); moved to %s and started anew" % (e, aside))
            os.replace(self.path, aside)


class _Lock:
    """Advisory exclusive lock on a side file (concurrent writers wait for each other); no-op if the
    platform has no fcntl."""

    def __init__(self, path):
        self.path, self.fh = path, None

    def __enter__(self):
        try:
            import fcntl
        except ImportError:
            return self
        self.fh = open(self.path, "a")
        fcntl.flock(self.fh, fcntl.LOCK_EX)
        return self

    def __exit__(self, *exc):
        if self.fh is not None:
            import fcntl
            fcntl.flock(self.fh, fcntl.LOCK_UN)
            self.fh.close()
        return False


def default_db():
    """The ShapeDB of ``$DEM_SHAPE_DB`` (``none``: None, no cache), else of ``~/.cache/dem/shapes.h5``."""
    path = os.environ.get("DEM_SHAPE_DB")
    if path is None or path == "":
        path = os.path.join("~", ".cache", "dem", "shapes.h5")
    if path.strip().lower() == "none":
        return None
    return ShapeDB(path)


def _resolve_db(db):
    if db is None:
        return default_db()
    if isinstance(db, ShapeDB):
        return db
    if db is False or (isinstance(db, str) and db.strip().lower() == "none"):
        return None
    return ShapeDB(db)


def cached_union_mass_properties(components, resolution=500, db=None, comm=None):
    """``union_mass_properties`` through the shape database: ``db`` a ShapeDB, a path, None for the default
    (default_db) or "none"/False for no cache. Under MPI (``comm`` with ``.me`` and ``.bcast``) rank 0 reads
    and writes the file and broadcasts; all ranks compute together when it is missing. Returns the dict of
    union_mass_properties (from the cache: volume, centre, inertia, error, resolution, and cached=True)."""
    from .glued_mass import union_mass_properties
    db = _resolve_db(db)
    resolution = int(resolution)
    me = int(getattr(comm, "me", 0)) if comm is not None else 0
    bcast = getattr(comm, "bcast", None) if comm is not None else None
    definition = definition_text(components) if db is not None else None
    found = db.get(definition, resolution) if (db is not None and me == 0) else None
    if bcast is not None:
        found = bcast(found)
    if found is not None:
        found["cached"] = True
        return found
    props = union_mass_properties(components, resolution, comm=comm)
    if db is not None and me == 0:
        db.put(definition, resolution, props)
    props["cached"] = False
    return props
