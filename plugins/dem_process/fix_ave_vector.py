"""fix ave/vector"""
import numpy as np

from dem.compute import find_compute
from dem.errors import DemError
from dem.fix import Fix, Stage

from .series_file import SeriesFile, sample_step


class FixAveVector(Fix):
    """fix ID group ave/vector Nevery Nfreq FILE c_ID ...

    Time average of the vectors of computes, written as a table (LAMMPS's `fix ave/time ... mode vector`):
    every Nevery steps the vectors are sampled, every Nfreq steps (a multiple of Nevery) their mean over
    the samples since the last write is written, one line per element: `step time row coord c_ID ...`, coord
    the element's coordinate where the compute gives one (`compute rdf`: the bin centre r) else the row
    number. The computes must have vectors of one length. Samples are taken at the end of a step; only
    rank 0 writes. The group is not used.

    Example (Descantes Fig. 9a): `compute g all rdf 200 0.02` then `fix gr all ave/vector 2000 10000 rdf.dat
    c_g`, and plot columns 4 and 5 of the last block."""

    style = "ave/vector"
    stages = Stage.END_OF_STEP

    def __init__(self, sim, fid, group, args):
        super().__init__(sim, fid, group, args)
        what = f"fix {fid} ave/vector"
        usage = "fix ID group ave/vector Nevery Nfreq FILE c_ID ..."
        if len(args) < 4:
            raise DemError(f"{what}: expected at least 4 arguments; usage: {usage}")
        try:
            self.every, self.nfreq = int(args[0]), int(args[1])
        except ValueError:
            raise DemError(f"{what}: Nevery and Nfreq must be integers, got '{args[0]}' '{args[1]}'") from None
        if self.every < 1 or self.nfreq < 1 or self.nfreq % self.every:
            raise DemError(f"{what}: Nevery and Nfreq must be >= 1 and Nfreq a multiple of Nevery")
        self.names = args[3:]
        self.computes = []
        for w in self.names:
            if not w.startswith("c_") or "[" in w:
                raise DemError(f"{what}: '{w}' is not a compute vector (c_ID)")
            c = find_compute(sim, w[2:])
            if not c.size_vector:
                raise DemError(f"{what}: compute {c.id} ({c.style}) has no vector")
            self.computes.append(c)
        sizes = {c.size_vector for c in self.computes}
        if len(sizes) > 1:
            lengths = ", ".join(f"{c.id}: {c.size_vector}" for c in self.computes)
            raise DemError(f"{what}: the vectors differ in length ({lengths})")
        self.size = sizes.pop()
        coords = self.computes[0].coords
        self.coords = np.asarray(coords, float) if coords is not None else np.arange(1, self.size + 1, dtype=float)
        self.sums = np.zeros((self.size, len(self.computes)))
        self.nsamples = 0
        self.last = None
        self.file = SeriesFile(sim, args[2], what, "# step time row coord " + " ".join(self.names),
                               f"fix {self.id}")

    def end_of_step(self):
        up = self.sim.update
        step = sample_step(self)
        if step is None:
            return
        with up.as_output_of_step(step):      # evaluated as the output of step `step` (computes cache by step)
            for k, c in enumerate(self.computes):
                self.sums[:, k] += np.asarray(c.vector(), float)
            self.nsamples += 1
            if step % self.nfreq == 0:
                mean = self.sums / self.nsamples
                self.file.write([f"{step} {up.time:.10g} {r + 1} {self.coords[r]:.10g} "
                                 + " ".join(f"{v:.10g}" for v in mean[r]) for r in range(self.size)])
                self.sums[:] = 0.0
                self.nsamples = 0

    def unfix(self):
        self.file.close()
