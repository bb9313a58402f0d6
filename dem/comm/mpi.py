"""MPI communication: spatial domain decomposition over MPI.COMM_WORLD (see docs/parallel.md).

The box is cut into a Px x Py x Pz grid of sub-boxes (`processors`, or the grid with the least sub-box
surface for the box shape); cut positions are fractions of the box per axis, so shrink-wrapped boxes keep
their decomposition and `balance` / `fix balance` can shift them. A rank owns the particles inside its
sub-box and keeps ghost images of every particle within `cutghost` (largest pair cutoff: two largest
bounding radii + skin) of it:

* `exchange()` (rebuild steps only): particles that left the sub-box move to their new owner with every
  per-particle field (contact and wall histories, fix state); one Alltoall of counts + one Alltoallv.
* `borders()` (rebuild steps): six swaps, -x +x -y +y -z +z, each a Sendrecv with the neighbouring rank
  of the grid (the rank itself when the grid has one rank along a periodic axis), sending the particles
  within `cutghost` of that face, ghosts received in earlier axes included (edges and corners), with the
  periodic shift applied by the rank at the box edge. Sub-boxes must be at least `cutghost` wide: one hop.
* `forward()` every other step: x, v, omega, quat of the same send lists (13 doubles per ghost);
  `reverse()`: force and torque on ghosts back to their owners (6 doubles), in reverse swap order.

All per-step messages are uppercase mpi4py calls on numpy buffers kept between steps. Reductions are
Allreduce on one-element buffers. Errors: a DemError reaches every rank alike (input errors, and checks
made on reduced values); `fatal` waits a few seconds for every rank to report it, then aborts the job, so
an error seen by one rank only never hangs. Any other exception aborts through the exception hook.
"""
import sys
import time
import traceback

import numpy as np
from mpi4py import MPI

from ..atom import FORWARD_FIELDS
from ..errors import DemError
from .serial import Comm
from .swap import Forward, Reverse, Swap

ERROR_WAIT = 5.0            # seconds to wait for the other ranks to stop with the same error
ABORT_GRACE = 0.5           # seconds for the process manager to forward a rank's last words before Abort
REVERSE_FIELDS = ("f", "torque")
AXES = "xyz"


def install_abort_hook(world):
    """An uncaught exception on one rank prints its traceback and aborts the whole job (never a hang)."""

    def hook(kind, value, tb):
        try:
            # one write, then a pause: Abort kills the job at once, and output the process manager has not
            # forwarded yet would be lost (seen: a traceback cut after its first lines)
            text = "".join(traceback.format_exception(kind, value, tb))
            sys.stderr.write(f"{text}ERROR on rank {world.Get_rank()}: uncaught {kind.__name__}: aborting the "
                             f"MPI job\n")
            sys.stderr.flush()
            time.sleep(ABORT_GRACE)
        finally:
            world.Abort(1)

    sys.excepthook = hook


def divisors(n):
    return [k for k in range(1, n + 1) if n % k == 0]


class CommMPI(Comm):
    def __init__(self, sim, world=None):
        super().__init__(sim)
        self.world = world if world is not None else MPI.COMM_WORLD
        self.me = self.world.Get_rank()
        self.nprocs = self.world.Get_size()
        self.user_grid = (0, 0, 0)
        self.procgrid = None
        self.myloc = None
        self.procneigh = None
        self.split = None
        self.swaps = []
        self._f_in, self._f_out = np.zeros(1), np.zeros(1)
        self._i_in, self._i_out = np.zeros(1, np.int64), np.zeros(1, np.int64)
        self._cost_mark = None
        self.reset_stats()
        install_abort_hook(self.world)

    # ----- reductions ---------------------------------------------------------------------------
    def _allreduce(self, value, op):
        if isinstance(value, (bool, np.bool_, int, np.integer)):
            self._i_in[0] = value
            self.world.Allreduce(self._i_in, self._i_out, op)
            return int(self._i_out[0])
        self._f_in[0] = value
        self.world.Allreduce(self._f_in, self._f_out, op)
        return float(self._f_out[0])

    def sum(self, value):
        return self._allreduce(value, MPI.SUM)

    def max(self, value):
        return self._allreduce(value, MPI.MAX)

    def min(self, value):
        return self._allreduce(value, MPI.MIN)

    def max_values(self, values):
        self.world.Allreduce(MPI.IN_PLACE, values, MPI.MAX)
        return values

    def sum_values(self, values):
        values = np.ascontiguousarray(values, dtype=np.float64)
        self.world.Allreduce(MPI.IN_PLACE, values, MPI.SUM)
        return values

    def min_avg_max(self, values):
        """(min, average, max) over ranks of a small float array, elementwise: three Allreduces."""
        v = np.ascontiguousarray(values, dtype=np.float64)
        lo, total, hi = np.empty_like(v), np.empty_like(v), np.empty_like(v)
        self.world.Allreduce(v, lo, MPI.MIN)
        self.world.Allreduce(v, total, MPI.SUM)
        self.world.Allreduce(v, hi, MPI.MAX)
        return lo, total / self.nprocs, hi

    def any(self, flag):
        return bool(self._allreduce(int(bool(flag)), MPI.MAX))

    def bcast(self, obj):
        return self.world.bcast(obj, root=0)

    def allgather(self, obj):
        return self.world.allgather(obj)

    def barrier(self):
        self.world.Barrier()

    def _gather(self, arr, root=0):
        """Rows of `arr` from every rank, in rank order: on `root` (None: on every rank)."""
        arr = np.ascontiguousarray(arr)
        tail, dtype = arr.shape[1:], arr.dtype
        rowbytes = dtype.itemsize * int(np.prod(tail, dtype=np.int64))
        counts = np.zeros(self.nprocs, np.int64)
        self.world.Allgather(np.array([len(arr)], np.int64), counts)
        total = int(counts.sum())
        nbytes = [int(c) * rowbytes for c in counts]
        displs = [0] + list(np.cumsum(nbytes)[:-1].astype(int))
        send = [arr.reshape(-1).view(np.uint8), MPI.BYTE]
        if root is None or self.me == root:
            out = np.empty((total,) + tail, dtype)
            recv = [out.reshape(-1).view(np.uint8), (nbytes, displs), MPI.BYTE]
        else:
            out, recv = np.empty((0,) + tail, dtype), None
        if root is None:
            self.world.Allgatherv(send, recv)
        else:
            self.world.Gatherv(send, recv, root=root)
        return out

    def gather_rows(self, tags, values):
        return self._gather(tags), self._gather(values)

    def allgather_rows(self, tags, values):
        return self._gather(tags, None), self._gather(values, None)

    # ----- processor grid ----------------------------------------------------------------------
    def set_processors(self, grid):
        super().set_processors(grid)
        if self.procgrid is not None:
            raise DemError("processors must come before the box is filled (before create_atoms, read_data "
                           "or read_restart)")
        self.user_grid = tuple(grid)

    def setup_grid(self, x=None):
        """Choose the grid (once, when particles are first placed): the factorisation of the rank count
        allowed by `processors` with the least total sub-box surface, for the extent of the particles
        being placed (x) when given, else of the box: a bed filling the lower half of a tall box is cut
        along its width, not its height. `settle_grid` may revise it at the first run."""
        if self.procgrid is not None:
            return
        dom = self.sim.domain
        dom.require_box("a parallel run")
        prd = dom.prd.copy()
        if x is not None and len(x):
            x = np.asarray(x, dtype=float).reshape(-1, 3)
            prd = self._extent(x.min(axis=0), x.max(axis=0))
        best = self._least_surface_grid(prd)
        if best is None:
            raise DemError(f"processors {' '.join(str(u) if u else '*' for u in self.user_grid)}: "
                           f"{self.nprocs} ranks cannot be arranged so")
        self._use_grid(best)

    def _extent(self, lo, hi):
        """The extent the grid is fitted to: that of the particles (lo, hi) within the box, at least 5 % of
        the box along each axis."""
        dom = self.sim.domain
        return np.maximum(np.minimum(hi, dom.hi) - np.maximum(lo, dom.lo), 0.05 * dom.prd)

    def _least_surface_grid(self, prd, uncut=None):
        """The grid allowed by `processors` (and leaving axis `uncut` whole) with the least total sub-box
        surface for an extent prd; None if there is none."""
        P = self.nprocs
        best, best_area = None, None
        for px in divisors(P):
            for py in divisors(P // px):
                grid = (px, py, P // px // py)
                if any(u and u != g for u, g in zip(self.user_grid, grid)):
                    continue
                if uncut is not None and grid[uncut] > 1:
                    continue
                area = (prd[0] * prd[1] / (grid[0] * grid[1]) + prd[1] * prd[2] / (grid[1] * grid[2])
                        + prd[0] * prd[2] / (grid[0] * grid[2]))
                if best_area is None or area < best_area * (1 - 1e-12):
                    best, best_area = grid, area
        return best

    def _use_grid(self, grid, why=""):
        """Take `grid` with even cuts: this rank's place in it and its neighbours along each axis."""
        dom = self.sim.domain
        self.procgrid = grid
        px, py, pz = grid
        me = self.me
        self.myloc = (me % px, (me // px) % py, me // (px * py))
        self.split = [np.linspace(0.0, 1.0, p + 1) for p in grid]
        self.procneigh = []
        for d in range(3):
            pair = []
            for step in (-1, 1):
                loc = list(self.myloc)
                loc[d] += step
                if not 0 <= loc[d] < grid[d]:
                    if not dom.periodic[d]:
                        pair.append(MPI.PROC_NULL)
                        continue
                    loc[d] %= grid[d]
                pair.append(self.rank_of_loc(loc))
            self.procneigh.append(pair)
        self.sim.print(f"Processor grid: {px} x {py} x {pz} ({self.nprocs} MPI ranks){why}")

    def settle_grid(self):
        """At the first run, for a grid dem chose itself (not read from a restart): under gravity, particles
        end up in a bed across the gravity axis whatever their extent when they were placed, so a grid
        that cuts along that axis leaves the ranks above the bed idle. Take the least-surface grid that
        leaves that axis whole (when `processors` allows one), then balance the cuts by particle count
        so that every rank starts with its share. `processors` set by the user is kept as given."""
        if self.grid_settled:
            return
        self.grid_settled = True
        self.setup_grid()
        g = self.sim.modify.acceleration()
        down = int(np.argmax(np.abs(g))) if g is not None else None
        if down is None or self.user_grid[down]:
            return
        dom, atom = self.sim.domain, self.sim.atom
        if self.procgrid[down] > 1:
            prd = dom.prd.copy()
            if self.sum(atom.nlocal):
                x = atom.data["x"][:atom.nlocal]     # -lo and hi of the particles, in one reduction
                bounds = self.max_values(np.r_[-x.min(axis=0, initial=np.inf), x.max(axis=0, initial=-np.inf)])
                prd = self._extent(-bounds[:3], bounds[3:])
            grid = self._least_surface_grid(prd, uncut=down)
            if grid is None:
                return
            self._use_grid(grid, f", instead, as gravity points along {AXES[down]}")
        if self.sum(atom.nlocal):
            self.balance("".join(a for d, a in enumerate(AXES) if d != down), "count", 1.0)
        self.sim.neighbor.invalidate()

    def rank_of_loc(self, loc):
        px, py, _ = self.procgrid
        return (loc[2] * py + loc[1]) * px + loc[0]

    def cuts(self, d):
        """Absolute positions of the P+1 sub-box boundaries along axis d (same on every rank)."""
        dom = self.sim.domain
        c = dom.lo[d] + dom.prd[d] * self.split[d]
        c[0], c[-1] = dom.lo[d], dom.hi[d]
        return c

    def rank_of(self, x):
        """Owner rank of positions x (outside the box: the sub-box at that edge)."""
        rank = np.zeros(len(x), np.int64)
        stride = 1
        for d in range(3):
            if self.procgrid[d] > 1:
                c = np.searchsorted(self.cuts(d)[1:-1], x[:, d], side="right")
                rank += c * stride
            stride *= self.procgrid[d]
        return rank

    def owned_mask(self, x):
        x = np.asarray(x, dtype=float).reshape(-1, 3)
        self.setup_grid(x)
        return self.rank_of(x) == self.me

    def subbox(self):
        lo = np.array([self.cuts(d)[self.myloc[d]] for d in range(3)])
        hi = np.array([self.cuts(d)[self.myloc[d] + 1] for d in range(3)])
        return lo, hi

    # ----- fields -------------------------------------------------------------------------------
    def harmonize_fields(self):
        """Every rank must hold the same fields with the same widths (a contact history may have grown
        its partner slots on one rank only): widen to the largest width found on any rank."""
        atom = self.sim.atom
        names = list(atom.fields)
        n = np.array([len(names), -len(names)], np.int64)
        out = np.empty_like(n)
        self.world.Allreduce(n, out, MPI.MAX)
        if out[0] != -out[1]:
            raise DemError(f"per-particle fields differ between ranks ({-out[1]} to {out[0]} fields)")
        widths = np.array([int(np.prod(atom.fields[k][0], dtype=np.int64)) for k in names], np.int64)
        wmax = np.empty_like(widths)
        self.world.Allreduce(widths, wmax, MPI.MAX)
        for name, w, wm in zip(names, widths, wmax):
            if wm != w:
                tail, dtype, fill, border = atom.fields[name]
                if len(tail) != 1:
                    raise DemError(f"per-particle field '{name}' has different shapes on different ranks")
                atom.add_field(name, (int(wm),), dtype, fill, border)

    def layout(self, names):
        """[(name, byte offset, bytes, dtype, trailing shape)], bytes per particle."""
        atom = self.sim.atom
        out, off = [], 0
        for name in names:
            tail, dtype = atom.fields[name][:2]
            nb = dtype.itemsize * int(np.prod(tail, dtype=np.int64))
            out.append((name, off, nb, dtype, tail))
            off += nb
        return out, off

    def pack_bytes(self, idx, layout, rowbytes, override=None):
        data = self.sim.atom.data
        m = len(idx)
        buf = np.empty((m, rowbytes), np.uint8)
        for name, off, nb, dtype, tail in layout:
            src = override[name] if override and name in override else data[name][idx]
            buf[:, off:off + nb] = np.ascontiguousarray(src).reshape(m, nb // dtype.itemsize).view(np.uint8)
        return buf

    @staticmethod
    def unpack_bytes(buf, layout):
        m = len(buf)
        return {name: np.ascontiguousarray(buf[:, off:off + nb]).view(dtype).reshape((m,) + tuple(tail))
                for name, off, nb, dtype, tail in layout}

    # ----- particles ----------------------------------------------------------------------------
    def exchange(self):
        """Send every owned particle outside the sub-box, with all its fields, to its owner."""
        t0 = time.perf_counter()
        self.setup_grid()
        atom = self.sim.atom
        atom.nghost = 0
        self.swaps = []
        self.harmonize_fields()
        n = atom.nlocal
        dest = self.rank_of(atom.data["x"][:n])
        leave = np.flatnonzero(dest != self.me)
        order = leave[np.argsort(dest[leave], kind="stable")]
        sendcounts = np.bincount(dest[order], minlength=self.nprocs).astype(np.int64)
        recvcounts = np.empty(self.nprocs, np.int64)
        self.world.Alltoall(sendcounts, recvcounts)
        layout, rowbytes = self.layout(list(atom.fields))
        sbuf = self.pack_bytes(order, layout, rowbytes)
        rbuf = np.empty((int(recvcounts.sum()), rowbytes), np.uint8)
        sb, rb = [int(c) * rowbytes for c in sendcounts], [int(c) * rowbytes for c in recvcounts]
        sd, rd = [0] + list(np.cumsum(sb)[:-1].astype(int)), [0] + list(np.cumsum(rb)[:-1].astype(int))
        self.world.Alltoallv([sbuf.reshape(-1), (sb, sd), MPI.BYTE], [rbuf.reshape(-1), (rb, rd), MPI.BYTE])
        if len(order):
            keep = np.ones(n, bool)
            keep[order] = False
            atom.keep(keep)
        if len(rbuf):
            atom.unpack(self.unpack_bytes(rbuf, layout))
        self.stats["exchange_bytes"] += sbuf.size
        self.stats["migrated"] += len(order)
        self.stats["exchange"] += time.perf_counter() - t0

    def check_widths(self):
        """Sub-boxes at least one ghost cutoff wide (ghosts come from the adjacent rank only)."""
        dom, cut = self.sim.domain, self.cutghost
        for d in range(3):
            if dom.periodic[d] and dom.prd[d] < 2.0 * cut:
                raise DemError(f"periodic box length {dom.prd[d]:g} along {AXES[d]} is less than twice the "
                               f"ghost cutoff {cut:g} (largest particle diameter + skin)")
            if self.procgrid[d] > 1:
                w = float(np.min(np.diff(self.cuts(d))))
                if w < cut:
                    raise DemError(f"sub-boxes along {AXES[d]} are {w:g} wide, less than the ghost cutoff "
                                   f"{cut:g} (largest particle diameter + skin)",
                                   hint=f"use fewer ranks along {AXES[d]} ('processors'), or a larger box")

    def borders(self):
        t0 = time.perf_counter()
        self.setup_grid()
        self.check_widths()
        atom, dom = self.sim.atom, self.sim.domain
        atom.nghost = 0
        cut = self.cutghost
        sublo, subhi = self.subbox()
        names = atom.border_fields()
        layout, rowbytes = self.layout(names)
        self.swaps = []
        count_s, count_r = np.zeros(1, np.int64), np.zeros(1, np.int64)
        for d in range(3):
            if self.procgrid[d] == 1 and not dom.periodic[d]:
                continue
            nlast = atom.nlocal + atom.nghost      # both directions send from what is here now
            for direction in (0, 1):
                s = Swap()
                s.sendproc = self.procneigh[d][direction]
                s.recvproc = self.procneigh[d][1 - direction]
                s.local = s.sendproc == self.me
                s.buffers = {}
                if s.sendproc == MPI.PROC_NULL:
                    s.sendlist = np.zeros(0, np.int64)
                else:
                    xd = atom.data["x"][:nlast, d]
                    sel = xd < sublo[d] + cut if direction == 0 else xd >= subhi[d] - cut
                    s.sendlist = np.flatnonzero(sel).astype(np.int64)
                s.shift = None
                edge = 0 if direction == 0 else self.procgrid[d] - 1
                if dom.periodic[d] and self.myloc[d] == edge:
                    s.shift = np.zeros(3)
                    s.shift[d] = dom.prd[d] if direction == 0 else -dom.prd[d]
                xs = atom.data["x"][s.sendlist]
                if s.shift is not None:
                    xs += s.shift
                sbuf = self.pack_bytes(s.sendlist, layout, rowbytes, {"x": xs})
                if s.local:
                    rbuf = sbuf
                else:
                    count_s[0] = len(s.sendlist)
                    count_r[0] = 0
                    self.world.Sendrecv(count_s, s.sendproc, 1, count_r, s.recvproc, 1)
                    rbuf = np.empty((int(count_r[0]), rowbytes), np.uint8)
                    self.world.Sendrecv([sbuf.reshape(-1), MPI.BYTE], s.sendproc, 2,
                                        [rbuf.reshape(-1), MPI.BYTE], s.recvproc, 2)
                s.first, s.nrecv = atom.nlocal + atom.nghost, len(rbuf)
                atom.grow(s.first + s.nrecv)
                for name, values in self.unpack_bytes(rbuf, layout).items():
                    atom.data[name][s.first:s.first + s.nrecv] = values
                atom.nghost += s.nrecv
                self.swaps.append(s)
        self.stats["borders"] += time.perf_counter() - t0

    def _columns(self, fields):
        data = self.sim.atom.data
        cols, col = [], 0
        for name in fields:
            arr = data[name]
            if arr.dtype != np.float64:
                raise DemError(f"forward/reverse communication of '{name}': only float fields")
            k = arr.shape[1] if arr.ndim == 2 else 1
            cols.append((name, arr if arr.ndim == 2 else arr.reshape(-1, 1), col))
            col += k
        return cols, col

    def _sendrecv(self, s, sbuf, key, n, dest, source, tag):
        """Send sbuf to `dest` and receive n rows from `source` for swap s (sbuf itself when the swap stays on
        this rank); returns (received buffer, seconds spent waiting, bytes sent)."""
        if s.local:
            return sbuf, 0.0, 0
        rbuf = s.buffer(key, n, sbuf.shape[1])
        t = time.perf_counter()
        self.world.Sendrecv([sbuf, MPI.DOUBLE], dest, tag, [rbuf, MPI.DOUBLE], source, tag)
        return rbuf, time.perf_counter() - t, sbuf.nbytes

    def _communicate(self, way, fields, swaps):
        """The loop forward and reverse share: per swap, every field packed side by side into one buffer,
        one Sendrecv, the received columns stored; `way` (Forward or Reverse) says which rows go where."""
        t0 = time.perf_counter()
        cols, width = self._columns(fields)
        wait, nbytes = 0.0, 0
        for s in swaps:
            nsend, nrecv = way.sizes(s)
            dest, source = way.ends(s)
            sbuf = s.buffer((way.name, "send", width), nsend, width)
            if nsend:                       # a swap at a wall edge only receives (or only sends)
                for name, rows, col in cols:
                    way.pack(s, name, rows, sbuf, col)
            rbuf, w, b = self._sendrecv(s, sbuf, (way.name, "recv", width), nrecv, dest, source, way.tag)
            wait += w
            nbytes += b
            if nrecv:
                for name, rows, col in cols:
                    way.store(s, rbuf, col, rows)
        st = self.stats
        st[way.name] += time.perf_counter() - t0
        st["wait"] += wait
        st[way.name + "_bytes"] += nbytes

    def forward(self, fields=FORWARD_FIELDS):
        """Refresh the ghosts' copies of `fields` (float fields) from their owners."""
        if not self.swaps:
            return
        self._communicate(Forward, fields, self.swaps)
        self.stats["nforward"] += 1

    def reverse(self, fields=REVERSE_FIELDS):
        """Add what was accumulated on ghosts (forces, torques) to their owners, in reverse swap order."""
        if not self.swaps:
            return
        self._communicate(Reverse, fields, self.swaps[::-1])

    # ----- restarts -----------------------------------------------------------------------------
    def gather_restart(self, state):
        """Every rank's particles (all fields, and the reference positions of the last neighbor build)
        on rank 0, in rank order, plus the decomposition (reused when read on the same grid)."""
        self.harmonize_fields()
        atom = self.sim.atom
        n = atom.nlocal
        state["fields"] = {name: self._gather(atom.data[name][:n]) for name in atom.fields}
        state["field_specs"] = {k: (v[0], v[1].str, v[2], v[3]) for k, v in atom.fields.items()}
        xhold = state["neighbor"]["xhold"]
        if self.any(xhold is None or len(xhold) != n):
            state["neighbor"]["xhold"] = None
        else:
            state["neighbor"]["xhold"] = self._gather(xhold)
        state["comm"] = {"procgrid": self.procgrid, "split": [s.copy() for s in self.split]}
        return state

    def scatter_restart(self, state):
        """This rank's share of a restart read by every rank: owners by the positions of the last
        neighbor build (where the run that wrote it had them), so the run continues as it was."""
        fields = state["fields"]
        xhold = state["neighbor"]["xhold"]
        where = xhold if xhold is not None and len(xhold) == len(fields["x"]) else fields["x"]
        info = state.get("comm")
        grid = tuple(int(p) for p in info["procgrid"]) if info else None
        if (self.procgrid is None and grid and int(np.prod(grid)) == self.nprocs
                and not any(u and u != g for u, g in zip(self.user_grid, grid))):
            self._use_grid(grid)            # the run continues on the decomposition it had
        self.setup_grid(where)
        self.grid_settled = True
        if grid == tuple(self.procgrid):
            self.split = [np.array(s, dtype=float) for s in info["split"]]
        mine = self.owned_mask(where) if len(where) else np.zeros(0, bool)
        return ({name: values[mine] for name, values in fields.items()},
                xhold[mine] if xhold is not None and len(xhold) == len(mine) else None)

    # ----- load balance -------------------------------------------------------------------------
    def _cost(self):
        t = self.sim.update.timers
        return t["pair"] + t["neigh"] + t["integrate"] + t["modify"]

    def _weights(self, weight):
        """Per-particle weights: 1 (count), or this rank's measured compute time since the last balance
        spread over its particles (time)."""
        n = self.sim.atom.nlocal
        if weight == "time":
            cost = self._cost()
            used = cost - (self._cost_mark or 0.0)
            if self._cost_mark is None or used <= 0.0 or self.any(used <= 0.0):
                return np.ones(n)
            return np.full(n, used / max(n, 1))
        return np.ones(n)

    def imbalance(self, weight="count"):
        """Largest over average load: particles per rank (count) or compute time (time)."""
        load = float(np.sum(self._weights(weight)))
        total = self.sum(load)
        return self.max(load) / (total / self.nprocs) if total > 0 else 1.0

    def min_width(self):
        nb, modify = self.sim.neighbor, self.sim.modify
        rmax = modify.max_radius()
        skin = nb.skin if nb.skin is not None else 0.2 * rmax
        return max(self.cutghost, 2.0 * rmax + skin)

    def balance(self, dims="xyz", weight="count", thresh=1.0):
        """Shift the cuts along `dims` so that every slab of the grid holds the same weight (bisection
        on each cut, one Allreduce per iteration), keeping sub-boxes one ghost cutoff wide. The
        particles move at the next exchange. Returns the imbalance before."""
        self.setup_grid()
        before = self.imbalance(weight)
        if before <= thresh:
            return before
        atom, dom = self.sim.atom, self.sim.domain
        n = atom.nlocal
        w = self._weights(weight)
        total = self.sum(float(w.sum()))
        width = self.min_width()
        for d in range(3):
            P = self.procgrid[d]
            if AXES[d] not in dims or P == 1 or total <= 0:
                continue
            frac = (atom.data["x"][:n, d] - dom.lo[d]) / dom.prd[d]
            order = np.argsort(frac, kind="stable")
            fs = frac[order]
            cw = np.concatenate([[0.0], np.cumsum(w[order])])
            target = total * np.arange(1, P) / P
            lo, hi = np.zeros(P - 1), np.ones(P - 1)
            below = np.empty(P - 1)
            for _ in range(48):
                mid = 0.5 * (lo + hi)
                local = cw[np.searchsorted(fs, mid, side="left")]
                self.world.Allreduce(np.ascontiguousarray(local), below, MPI.SUM)
                low = below < target
                lo, hi = np.where(low, mid, lo), np.where(low, hi, mid)
            c = np.concatenate([[0.0], 0.5 * (lo + hi), [1.0]])
            m = width / dom.prd[d] * (1.0 + 1e-9)
            if P * m < 1.0:
                for k in range(1, P):
                    c[k] = max(c[k], c[k - 1] + m)
                for k in range(P - 1, 0, -1):
                    c[k] = min(c[k], c[k + 1] - m)
                self.split[d] = c
        self._cost_mark = self._cost()
        self.sim.neighbor.invalidate()
        return before

    # ----- errors and statistics ----------------------------------------------------------------
    def fatal(self, sim, text, status=1):
        """A DemError (or an interrupt) on this rank: rank 0 reports it; if the other ranks do not all stop
        with it within ERROR_WAIT seconds (an error seen by this rank only, a signal that reached a rank
        blocked in a collective outside a run), this rank reports it and aborts the job with `status`."""
        if self.me == 0:
            print(text, file=sys.stderr, flush=True)
            if sim is not None:
                sim.print(text, screen=False)
        if sim is not None:
            try:
                sim.close()
            except Exception:
                pass
        request = self.world.Ibarrier()
        deadline = time.monotonic() + ERROR_WAIT
        while not request.Test():
            if time.monotonic() > deadline:
                if self.me != 0:
                    print(f"{text} (rank {self.me})", file=sys.stderr, flush=True)
                print(f"ERROR on rank {self.me}: the other ranks did not stop with this error: aborting the "
                      f"MPI job", file=sys.stderr, flush=True)
                time.sleep(ABORT_GRACE)
                self.world.Abort(status)
            time.sleep(0.002)
        return status

    def reset_stats(self):
        self.stats = dict.fromkeys(("forward", "reverse", "wait", "exchange", "borders"), 0.0)
        self.stats.update(dict.fromkeys(("forward_bytes", "reverse_bytes", "exchange_bytes", "migrated",
                                         "nforward"), 0))

    def report(self, nsteps=0):
        """Summary lines: time in communication (max over ranks) and volume sent per step and rank."""
        st = self.stats
        steps = max(nsteps, 1)
        t = {k: self.max(st[k]) for k in ("forward", "reverse", "wait", "exchange", "borders")}
        ghosts = self.sum(self.sim.atom.nghost) / self.nprocs
        per_step = (self.sum(st["forward_bytes"] + st["reverse_bytes"] + st["exchange_bytes"])
                    / self.nprocs / steps)
        migrated = self.sum(st["migrated"])
        lines = [
            f"Comm ({self.procgrid[0]}x{self.procgrid[1]}x{self.procgrid[2]} ranks): per step "
            f"{1e6 * (t['forward'] + t['reverse']) / steps:.1f} us forward+reverse (of which "
            f"{1e6 * t['wait'] / steps:.1f} us waiting), {1e6 * (t['exchange'] + t['borders']) / steps:.1f} us "
            f"exchange+borders",
            f"Comm volume: {per_step / 1024:.1f} KiB sent per step and rank, {ghosts:.0f} ghosts per rank, "
            f"{self.sum(self.sim.atom.nlocal) / self.nprocs:.0f} particles per rank, {migrated} migrations",
        ]
        self.reset_stats()
        return lines
