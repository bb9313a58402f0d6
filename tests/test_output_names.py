"""Two outputs on one file are refused at the command that would make the clash, naming both uses: two
HDF5 dumps (their frames would mix), a dump on the log (truncated), a restart on a dump (replaced)."""
import pytest

import dem
from dem.errors import DemError

BOX = """units si
region box block 0 0.01 0 0.01 0 0.01
create_box 1 box
create_atoms 1 single 0.005 0.005 0.005 radius 0.001 density 2500
"""


@pytest.fixture
def sim(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    s = dem.Simulation(screen=False, log="log.dem")
    s.commands(BOX)
    yield s
    s.close()


def refused(sim, line, *names):
    with pytest.raises(DemError) as info:
        sim.command(line)
    text = str(info.value)
    for name in names:
        assert name in text, text
    assert "two outputs on one file" in text
    return text


def test_two_h5_dumps_on_one_file(sim):
    sim.command("dump a all h5 5 out.h5")
    refused(sim, "dump b all h5 10 ./out.h5", "dump b (h5)", "dump a (h5)", "out.h5")
    assert list(sim.output.dumps) == ["a"]
    sim.command("undump a")
    sim.command("dump b all h5 10 out.h5")         # free again once undumped


def test_dump_named_like_the_log(sim, tmp_path):
    refused(sim, "dump d all h5 5 log.dem", "dump d (h5)", "the log file")
    refused(sim, "dump v all vtk 5 out.vtu pvd log.dem", "dump v (vtk)", "the log file")
    assert "create_box" in (tmp_path / "log.dem").read_text()       # the log was not truncated


@pytest.mark.parametrize("line, use", [
    ("fix s all print/series 5 log.dem ke", "fix s print/series"),
    ("fix p all ave/profile 1 5 log.dem z 4 count", "fix p ave/profile"),
    ("print hello file log.dem", "print"),
    ("print hello append log.dem", "print"),
])
def test_series_profiles_and_prints_named_like_the_log(sim, tmp_path, line, use):
    """A series, profile or print file on the log was accepted and the log lost."""
    refused(sim, line, use, "the log file")
    assert "create_box" in (tmp_path / "log.dem").read_text()


def test_a_series_file_is_free_again_after_unfix(sim):
    sim.command("fix s all print/series 5 s.dat ke")
    refused(sim, "fix t all print/series 5 s.dat ke", "fix t print/series", "fix s print/series")
    refused(sim, "dump d all custom 5 s.dat id", "dump d", "fix s print/series")
    sim.command("fix s all print/series 5 s.dat ke")       # the same fix again: its own file
    sim.command("unfix s")
    sim.command("fix t all print/series 5 s.dat ke")


def test_restart_named_like_a_dump(sim, tmp_path):
    sim.command("dump d all h5 5 out.h5")
    refused(sim, "restart 10 r.a out.h5", "restart", "dump d (h5)")
    refused(sim, "write_restart out.h5", "write_restart", "dump d (h5)")
    refused(sim, "write_restart out.xdmf", "write_restart", "dump d (h5)")
    sim.command("dump v all vtk 5 frames_*.vtu")
    refused(sim, "restart 10 frames_*.vtu", "restart", "dump v (vtk)")
    refused(sim, "write_restart frames_100.vtu", "write_restart", "dump v (vtk)")
    assert sim.output.restart_every == 0


def test_dump_named_like_a_restart(sim):
    sim.command("restart 10 r.*")
    refused(sim, "dump d all h5 5 r.100", "dump d (h5)", "restart")
    sim.command("restart 0")                        # off: the name is free
    sim.command("dump d all h5 5 r.100")


def test_distinct_names_and_restart_alternation_pass(sim):
    sim.command("dump a all h5 5 a.h5")
    sim.command("dump b all h5 5 b.h5")
    sim.command("restart 10 r.a r.b")
    sim.command("restart 20 r.a r.b")              # the same output again
    sim.command("write_restart r.a")                # a one-off restart over the periodic one's file
