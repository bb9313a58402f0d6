"""A full disk (ENOSPC) while the log, a series or a profile is written: a clear error naming the file and
the line, never a traceback. The full disk is a file object whose writes fail as on a full device (a
device target is refused before, dem.files)."""
import errno

import pytest

import dem

SCRIPT = """units si
region box block 0 0.01 0 0.01 0 0.01
create_box 1 box
create_atoms 1 single 0.005 0.005 0.005 radius 0.001 density 2500
pair_style sphere
pair_coeff * * kn 1000 en 0.5
fix nve all nve/sphere
timestep 1e-6
thermo 0
"""


class FullDisk:
    def __init__(self, name):
        self.name = name

    def write(self, text):
        raise OSError(errno.ENOSPC, "No space left on device")

    def flush(self):
        pass

    def close(self):
        pass


def test_log(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False, log="log.dem")
    sim.commands(SCRIPT)
    sim.logfile = FullDisk("log.dem")
    with pytest.raises(dem.DemError, match="the log file \\(-log\\): cannot write 'log.dem': No space left on device"):
        sim.command('print "one more line"')
    sim.command('print "the log is closed: no error again"')
    sim.close()


@pytest.mark.parametrize("line, handle", [
    ("fix s all print/series 5 s.dat ke", lambda fix: fix),
    ("fix s all ave/profile 1 5 s.dat z 4 count", lambda fix: fix.file),
])
def test_series_and_profiles(tmp_path, monkeypatch, line, handle):
    monkeypatch.chdir(tmp_path)
    sim = dem.Simulation(screen=False)
    sim.commands(SCRIPT + line)
    handle(sim.modify.find("s")).fh = FullDisk("s.dat")
    with pytest.raises(dem.DemError, match="fix s .*: cannot write 's.dat': No space left on device") as err:
        sim.command("run 10")
    assert err.value.where == "<command>:1"
    sim.close()
