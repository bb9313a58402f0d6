"""The restart file: a restart state (a tree of dicts, lists, arrays and scalars) as an HDF5 file, never
executable, the whole file with a SHA-256 checksum in its header (dem.verified_file: checked before HDF5
opens it) and every dataset with a CRC-32, each value typed exactly so that a continued run is bitwise the
same (layout: docs/restart.md). `file_version` checks the file, `read` the datasets, `validate` the
physics."""
import zlib
from urllib.parse import quote, unquote

import numpy as np

from . import verified_file
from .errors import DemError

MAGIC = "dem-restart"
KIND = "restart"              # of the checked file's header (verified_file)
CONVERT_HINT = "convert it with `dem-convert-restart OLD NEW` (docs/restart.md)"
DAMAGED_HINT = "the file cannot be repaired: continue from an earlier restart (e.g. the other file of `restart N A B`)"
PICKLE_OPCODE = 0x80          # first byte of a pickle (protocol 2 and later): the old restart files
QUAT_TOL = 1e-6               # largest | |q| - 1 | of an orientation read back
FINITE_FIELDS_KIND = "f"      # every floating-point per-particle field must be finite
REQUIRED = ("step", "time", "time_anchor", "dt", "lo", "hi", "boundary", "nlost", "ntypes", "natoms", "max_tag", "groups",
            "fields", "field_specs", "neighbor", "fixes", "pair", "shapes")


def _crc(data):
    return zlib.crc32(np.ascontiguousarray(data).tobytes()) & 0xFFFFFFFF


def _put(group, name, value):
    """Store one value under `name`: a dataset (arrays, numbers, strings) or a group (containers), with its
    kind in an attribute."""
    if isinstance(value, dict):
        g = group.create_group(name)
        g.attrs["kind"] = "dict"
        for key, item in value.items():
            if not isinstance(key, str):
                raise DemError(f"write_restart: state key {key!r} is not a string")
            _put(g, quote(key, safe=""), item)
        return
    if isinstance(value, (list, tuple)):
        g = group.create_group(name)
        g.attrs["kind"] = "list" if isinstance(value, list) else "tuple"
        g.attrs["length"] = len(value)
        for i, item in enumerate(value):
            _put(g, str(i), item)
        return
    if value is None:
        kind, data = "none", np.zeros(0, np.uint8)
    elif isinstance(value, np.generic) and value.dtype.kind in "biuf":     # np.float64 is a float: first
        kind, data = "npscalar", np.array(value)
    elif isinstance(value, bool):
        kind, data = "bool", np.array(value, dtype=np.bool_)
    elif isinstance(value, int):                   # any size (random generator states): as decimal text
        kind, data = "int", np.frombuffer(str(value).encode(), np.uint8)
    elif isinstance(value, float):
        kind, data = "float", np.array(value, dtype=np.float64)
    elif isinstance(value, str):
        kind, data = "str", np.frombuffer(value.encode(), np.uint8)
    elif isinstance(value, np.ndarray) and value.dtype.kind in "biuf":
        kind, data = "array", value
    elif isinstance(value, np.ndarray) and value.dtype.kind == "U":
        kind, data = "strarray", np.array([s.encode() for s in value.ravel()], dtype="S").reshape(value.shape)
    else:
        raise DemError(f"write_restart: cannot store a value of type {type(value).__name__} ('{name}')")
    ds = group.create_dataset(name, data=data)
    ds.attrs["kind"] = kind
    ds.attrs["crc32"] = _crc(data)


def _get(node, path):
    kind = node.attrs.get("kind")
    if hasattr(node, "keys"):                  # a group (h5py is imported where files are read)
        if kind == "dict":
            return {unquote(k): _get(node[k], f"{path}/{k}") for k in node}
        if kind in ("list", "tuple"):
            items = [_get(node[str(i)], f"{path}/{i}") for i in range(int(node.attrs["length"]))]
            return items if kind == "list" else tuple(items)
        raise ValueError(f"{path}: unknown group kind {kind!r}")
    data = node[()]
    if _crc(data) != int(node.attrs.get("crc32", -1)):
        raise ValueError(f"{path}: checksum mismatch (the file is damaged)")
    if kind == "none":
        return None
    if kind == "bool":
        return bool(data)
    if kind == "int":
        return int(data.tobytes().decode())
    if kind == "float":
        return float(data)
    if kind == "str":
        return data.tobytes().decode()
    if kind == "npscalar":
        return data[()]
    if kind == "array":
        return np.asarray(data)
    if kind == "strarray":
        return np.array([s.decode() for s in np.asarray(data).ravel()]).reshape(data.shape)
    raise ValueError(f"{path}: unknown dataset kind {kind!r}")


def write(path, state, version):
    with verified_file.hdf5_writer(path, KIND) as f:
        f.attrs["format"] = MAGIC
        f.attrs["version"] = version
        for key, value in state.items():
            _put(f, quote(key, safe=""), value)


def examine(path):
    """("version", N) for a whole restart file of version N, ("pickle", None) for an old pickle restart (by
    its first byte, never loaded), else ("error", message, hint). Checks the whole file before h5py opens
    it; never raises (under MPI rank 0 examines the file and broadcasts the verdict)."""
    problem = verified_file.check(path, KIND)
    if problem is None:
        import h5py                 # here, not at start-up (40 ms: every run imports this module)
        try:
            with h5py.File(path, "r") as f:
                if f.attrs.get("format") != MAGIC:
                    return "error", f"read_restart: '{path}' is not a dem restart file", None
                return "version", int(f.attrs.get("version", -1))
        except Exception as e:     # checked whole: only a file dem did not write this way gets here
            return "error", f"read_restart: '{path}' is damaged: {type(e).__name__}: {e}", DAMAGED_HINT
    reason, text = problem
    if reason == verified_file.FOREIGN and _first_byte(path) == PICKLE_OPCODE:
        return "pickle", None
    hint = {verified_file.PLAIN_HDF5: f"if it is a dem restart of version 3 (written before whole-file checksums), "
                                     f"{CONVERT_HINT}",
            verified_file.DAMAGED: DAMAGED_HINT, verified_file.EMPTY: DAMAGED_HINT}.get(reason)
    return "error", f"read_restart: '{path}' {text}", hint


def _first_byte(path):
    try:
        with open(path, "rb") as fh:
            first = fh.read(1)
    except OSError:
        return None
    return first[0] if first else None


def file_version(path, comm=None):
    """The version of the checked restart file at `path` (None: an old pickle file, version 2 or older),
    or a DemError when it is damaged or no restart file. Under MPI (`comm`) rank 0 reads the file and
    broadcasts what it found."""
    verdict = examine(path) if comm is None or comm.me == 0 else None
    if comm is not None:
        verdict = comm.bcast(verdict)
    if verdict[0] == "error":
        raise DemError(verdict[1], hint=verdict[2])
    return verdict[1]


def read(path, checked=False):
    """The state stored in `path` (a DemError naming the file and the damaged part if any). The whole file
    is checked first unless `checked` says file_version did so already."""
    if not checked:
        file_version(path)
    return read_unchecked(path)


def read_unchecked(path):
    """The state of an HDF5 restart whose whole-file checksum was checked, or that has none (a version-3
    file that dem-convert-restart converts: HDF5 reads it unchecked, so only files you trust)."""
    import h5py
    try:
        with h5py.File(path, "r") as f:
            return {unquote(k): _get(f[k], k) for k in f}
    except (ValueError, KeyError, OSError, RuntimeError, UnicodeDecodeError) as e:
        raise DemError(f"read_restart: '{path}' is damaged: {e}") from None


def validate(state, path):
    """Physical checks of a state read back: finite values, unit quaternions, positive masses and radii,
    unique ids, fields of one length that match their declarations."""
    def bad(what):
        raise DemError(f"read_restart: '{path}': {what}")

    missing = [key for key in REQUIRED if key not in state]
    if missing:
        bad(f"incomplete state (no {', '.join(missing)})")
    anchor = np.asarray(state["time_anchor"], dtype=float)
    if anchor.shape != (2,) or not np.all(np.isfinite(anchor)) or not 0 <= anchor[0] <= state["step"]:
        bad(f"invalid time anchor {state['time_anchor']!r} (step, time where dt last changed)")
    fields, specs = state["fields"], state["field_specs"]
    lo, hi = np.asarray(state["lo"], float), np.asarray(state["hi"], float)
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi)) and np.all(hi > lo)):
        bad(f"invalid box {lo.tolist()} - {hi.tolist()}")
    n = len(fields.get("tag", ()))
    for name, arr in fields.items():
        if not isinstance(arr, np.ndarray) or len(arr) != n:
            bad(f"field '{name}' does not hold one row per particle ({n})")
        spec = specs.get(name)
        if spec is None or arr.shape[1:] != tuple(spec[0]) or arr.dtype != np.dtype(spec[1]):
            bad(f"field '{name}' ({arr.dtype}, {arr.shape[1:]}) does not match its declaration {spec}")
        if arr.dtype.kind == FINITE_FIELDS_KIND and not np.all(np.isfinite(arr)):
            bad(f"field '{name}' has non-finite values")
    for name in ("tag", "x", "rmass", "radius", "quat"):
        if name not in fields:
            bad(f"field '{name}' missing")
    tag = fields["tag"]
    if np.any(tag <= 0) or len(np.unique(tag)) != n:
        bad("particle ids are not unique positive numbers")
    if np.any(fields["rmass"] <= 0) or np.any(fields["radius"] <= 0):
        bad("masses and radii must be positive")
    norm = np.linalg.norm(fields["quat"], axis=1) if n else np.zeros(0)
    if np.any(np.abs(norm - 1.0) > QUAT_TOL):
        bad(f"orientations are not unit quaternions (largest | |q| - 1 | = {np.max(np.abs(norm - 1.0)):.3g})")
    xhold = state.get("neighbor", {}).get("xhold")
    if xhold is not None and not np.all(np.isfinite(xhold)):
        bad("neighbor reference positions have non-finite values")
