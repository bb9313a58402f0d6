"""The output file of an averaging fix (ave/profile, ave/vector): opened on rank 0 when the fix is
defined (replaced), a header line, blocks of lines flushed at each write."""
from dem.errors import DemError
from dem.files import open_output


def sample_step(fix):
    """The step an averaging fix samples at its END_OF_STEP call (every `fix.every` steps, once per step:
    `fix.last` is updated), or None. END_OF_STEP runs before the step counter moves on."""
    step = fix.sim.update.ntimestep + 1
    if step % fix.every or step == fix.last:
        return None
    fix.last = step
    return step


class SeriesFile:
    def __init__(self, sim, path, what, header, owner):
        self.fh = None
        self.path, self.what = path, what
        sim.output.names.claim(owner, [path], what)     # on every rank: all refuse it together
        if sim.comm.me != 0:
            return
        self.fh = open_output(path, what)
        self.header = header

    def comment(self, line):
        if self.fh is not None:
            self.fh.write(line + "\n")

    def write(self, lines):
        if self.fh is None:
            return
        try:
            if self.header is not None:
                self.fh.write(self.header + "\n")
                self.header = None
            self.fh.write("\n".join(lines) + "\n")
            self.fh.flush()
        except OSError as e:            # a full disk
            raise DemError(f"{self.what}: cannot write '{self.path}': {e.strerror or e}") from None

    def close(self):
        if self.fh is not None:
            self.fh.close()
            self.fh = None
