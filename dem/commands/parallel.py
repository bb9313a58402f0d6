"""Commands about the MPI decomposition: processors, and comm_modify / newton (accepted for LAMMPS
compatibility)."""
from ..command import Command


class Ignored(Command):
    """Accepted for LAMMPS compatibility and ignored (the behaviour is always what dem does)."""
    usage = "..."

    def __call__(self, words):
        pass


class CommModify(Ignored):
    """comm_modify [vel yes|no] [mode single|multi] [cutoff C] [group G]: accepted for LAMMPS
    compatibility (ghosts always carry velocities; the ghost cutoff follows the particle sizes)."""
    style = "comm_modify"
    usage = "[vel yes|no] [mode single|multi] [cutoff C] [group G]"

    def __call__(self, words):
        a = self.args(words)
        kw = a.keywords(0, {"vel": 1, "mode": 1, "cutoff": 1, "group": 1})
        if "vel" in kw:
            a.yes_no(kw["vel"][0], "vel")
        if "cutoff" in kw:
            a.to_float(kw["cutoff"][0], "cutoff")


class Newton(Ignored):
    """newton on|off [on|off]: accepted for LAMMPS compatibility (dem applies Newton's third law in half
    lists)."""
    style = "newton"
    usage = "on|off [on|off]"

    def __call__(self, words):
        a = self.args(words)
        a.need(1)
        a.done(2)
        for word in a.words:
            a.yes_no(word, "newton")


class Processors(Command):
    """processors Px Py Pz

    The grid of sub-boxes of an MPI run (Px x Py x Pz = number of ranks); `*` lets dem choose that
    factor: the grid with the least sub-box surface for the extent of the particles first placed, and
    at the first run, under a `fix gravity`, the least-surface grid that does not cut along gravity
    (the particles will settle across it), its cuts balanced by particle count. Example:
    `processors * * 2` forces a cut along z. Must come before particles are created; serial runs only
    check it."""
    style = "processors"
    usage = "Px Py Pz"

    def __call__(self, words):
        a = self.args(words)
        a.need(3)
        grid = tuple(0 if w == "*" else a.int(k, f"P{'xyz'[k]}", positive=True) for k, w in
                     enumerate(a.words[:3]))
        if len(a) > 3:
            raise a.error(f"processors takes three values (Px Py Pz), got extra '{a[3]}'")
        self.sim.comm.set_processors(grid)
