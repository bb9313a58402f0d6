"""Per-particle storage: a struct of arrays, owned particles first (``nlocal``), then ghost images
(``nghost``). Every particle is one rigid body (rule 6): position, velocity, angular velocity and angular
momentum, orientation (unit quaternion w, x, y, z), mass, principal inertia and a shape index. Spheres use
``shape = -1``, meaning a solid sphere of the particle's own ``radius``.

Styles declare extra per-particle fields (``add_field``: wall history, contact history...); they grow,
move, migrate and are written to restarts with the particle. Arrays are reallocated on growth: never keep
a view across calls.
"""
import numpy as np

from .errors import DemError

# name: (trailing shape, dtype, fill value, copied to ghosts)
CORE_FIELDS = {
    "tag": ((), np.int64, 0, True),
    "type": ((), np.int32, 1, True),
    "mask": ((), np.int32, 1, True),
    "image": ((3,), np.int32, 0, False),
    "x": ((3,), np.float64, 0.0, True),
    "v": ((3,), np.float64, 0.0, True),
    "f": ((3,), np.float64, 0.0, False),
    "omega": ((3,), np.float64, 0.0, True),
    "angmom": ((3,), np.float64, 0.0, True),
    "torque": ((3,), np.float64, 0.0, False),
    "quat": ((4,), np.float64, 0.0, True),
    "radius": ((), np.float64, 0.0, True),
    "rmass": ((), np.float64, 0.0, True),
    "inertia": ((3,), np.float64, 0.0, True),
    "shape": ((), np.int32, -1, True),
}
# fields refreshed on ghosts every step (forward communication); the rest only when ghosts are made
FORWARD_FIELDS = ("x", "v", "omega", "quat")


class Atom:
    def __init__(self):
        self.nlocal = 0
        self.nghost = 0
        self.nmax = 0
        self.fields = {}
        self.data = {}
        self.natoms = 0          # global count of owned particles
        self.max_tag = 0         # largest tag ever given (global)
        self.ntypes = 1
        self.pending = {}        # fields read from a restart before the style declaring them exists
        for name, spec in CORE_FIELDS.items():
            self._declare(name, *spec)
        self.grow(64)

    # ----- storage --------------------------------------------------------------------------------
    def _declare(self, name, tail, dtype, fill, border):
        self.fields[name] = (tuple(tail), np.dtype(dtype), fill, border)
        self.data[name] = self._alloc(name, self.nmax)

    def _alloc(self, name, n):
        tail, dtype, fill, _ = self.fields[name]
        arr = np.empty((n,) + tail, dtype=dtype)
        arr[...] = fill
        if name == "quat":
            arr[:, 0] = 1.0
        return arr

    def add_field(self, name, tail=(), dtype=np.float64, fill=0, border=False):
        """Declare a per-particle field (idempotent for an identical declaration)."""
        spec = (tuple(tail), np.dtype(dtype), fill, border)
        if name in self.fields:
            if self.fields[name][:2] != spec[:2]:
                old = self.data[name]
                self.fields[name] = spec
                self.data[name] = self._alloc(name, self.nmax)
                n = min(old.shape[0], self.nmax)
                common = tuple(slice(0, min(a, b)) for a, b in zip(old.shape[1:], spec[0]))
                self.data[name][(slice(0, n),) + common] = old[(slice(0, n),) + common]
            return self.data[name]
        self._declare(name, *spec)
        if name in self.pending:
            self.grow(self.nlocal)
            values = self.pending.pop(name)
            if values.shape[1:] == spec[0] and len(values) == self.nlocal:
                self.data[name][:self.nlocal] = values
        return self.data[name]

    def remove_field(self, name):
        if name in self.fields and name not in CORE_FIELDS:
            del self.fields[name]
            del self.data[name]

    def grow(self, n):
        """Make room for at least n particles (owned + ghosts)."""
        if n <= self.nmax:
            return
        new = max(n, int(self.nmax * 1.5) + 16)
        for name in self.fields:
            arr = self._alloc(name, new)
            arr[:self.nmax] = self.data[name][:self.nmax]
            self.data[name] = arr
        self.nmax = new

    @property
    def nall(self):
        return self.nlocal + self.nghost

    def __getattr__(self, name):
        data = self.__dict__.get("data")
        if data is not None and name in data:
            return data[name][:self.nlocal + self.nghost]
        raise AttributeError(name)

    def local(self, name):
        return self.data[name][:self.nlocal]

    # ----- adding and removing owned particles ----------------------------------------------------
    def add(self, x, radius, rmass, type_=1, v=None, omega=None, tags=None, **extra):
        """Append owned particles (arrays of equal length). Ghosts are dropped: call before borders()."""
        x = np.atleast_2d(np.asarray(x, dtype=np.float64))
        n = len(x)
        self.nghost = 0
        self.grow(self.nlocal + n)
        s = slice(self.nlocal, self.nlocal + n)
        for name in self.fields:
            self.data[name][s] = self._alloc(name, n)
        self.data["x"][s] = x
        self.data["radius"][s] = radius
        self.data["rmass"][s] = rmass
        self.data["type"][s] = type_
        inertia = 0.4 * np.asarray(rmass, dtype=float) * np.asarray(radius, dtype=float) ** 2
        self.data["inertia"][s] = inertia[:, None] if inertia.ndim else inertia
        if v is not None:
            self.data["v"][s] = v
        if omega is not None:
            self.data["omega"][s] = omega
        for name, value in extra.items():
            self.data[name][s] = value
        if tags is None:
            tags = np.arange(self.max_tag + 1, self.max_tag + 1 + n)
        self.data["tag"][s] = tags
        self.nlocal += n
        if n:
            self.max_tag = max(self.max_tag, int(np.max(tags)))
        if np.any(self.data["type"][s] < 1) or np.any(self.data["type"][s] > self.ntypes):
            raise DemError(f"particle type out of range 1..{self.ntypes}")
        return s

    def keep(self, keep_mask):
        """Keep only the owned particles where keep_mask is True (order preserved); drops ghosts."""
        keep_mask = np.asarray(keep_mask, dtype=bool)
        idx = np.flatnonzero(keep_mask)
        for name in self.fields:
            arr = self.data[name]
            arr[:len(idx)] = arr[idx]
        self.nlocal = len(idx)
        self.nghost = 0

    def permute(self, order):
        """Reorder the owned particles (order: a permutation of range(nlocal)); drops ghosts."""
        n = self.nlocal
        for name in self.fields:
            arr = self.data[name]
            arr[:n] = arr[:n][order]
        self.nghost = 0

    def pack(self, idx):
        """Copies of every field for owned particles idx (for migration and restarts)."""
        return {name: self.data[name][idx].copy() for name in self.fields}

    def unpack(self, packed):
        """Append particles packed by pack() (fields missing in `packed` get their fill value)."""
        n = len(packed["tag"])
        self.nghost = 0
        self.grow(self.nlocal + n)
        s = slice(self.nlocal, self.nlocal + n)
        for name in self.fields:
            if name in packed:
                src = np.asarray(packed[name])
                dst = self.data[name][s]
                if src.shape[1:] == dst.shape[1:]:
                    dst[...] = src
                else:   # a field whose trailing size changed since it was written
                    dst[...] = self._alloc(name, n)
                    common = tuple(slice(0, min(a, b)) for a, b in zip(src.shape[1:], dst.shape[1:]))
                    dst[(slice(None),) + common] = src[(slice(None),) + common]
            else:
                self.data[name][s] = self._alloc(name, n)
        self.nlocal += n
        return s

    def border_fields(self):
        return [name for name, spec in self.fields.items() if spec[3]]
