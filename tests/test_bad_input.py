"""Bad input: every row is a script whose last line is wrong. It must stop with a DemError naming that
line and what is wrong (never a Python traceback, never silently accepted); files written before the
bad line stay complete."""
import subprocess
import sys

import numpy as np
import pytest

import dem

BOX = """units si
boundary p p f
region box block 0 0.01 0 0.01 0 0.01
create_box 1 box
"""
ATOMS = BOX + "create_atoms 1 random 20 5 box radius 0.0005 density 2500\n"
PAIR = ATOMS + "pair_style sphere\n"
READY = PAIR + """pair_coeff * * kn 1000 en 0.5
fix nve all nve/sphere
timestep 1e-6
"""
RANDOM = BOX + "create_atoms 1 random 5 7 box radius 0.0005 "

# (script, message fragment, run through `dem -in` as a subprocess?)
ROWS = [
    # numbers that are not numbers
    (RANDOM + "density abc\n", "density must be a number, got 'abc'", True),
    (BOX + "create_atoms 1 single 0.005 0.005 0.005 seed abc\n", "seed must be an integer, got 'abc'", False),
    (RANDOM + "seed 3\n", "random takes its seed as SEED", False),
    (RANDOM + "attempts many\n", "attempts must be an integer, got 'many'", False),
    (PAIR + "pair_coeff a* * kn 1000 en 0.5\n", "bad type I 'a*'", True),
    (PAIR + "pair_coeff * 1*x kn 1000 en 0.5\n", "bad type J '1*x'", False),
    (READY + "run nan\n", "N must be an integer, got 'nan'", True),
    (READY + "run inf\n", "N must be an integer, got 'inf'", False),
    (READY + "run 1.5\n", "N must be an integer, got '1.5'", False),
    # nan and inf refused where they are parsed
    (BOX + "create_atoms 1 single 0.005 0.005 0.005 radius nan\n", "radius must be a finite number, got 'nan'",
     True),
    (BOX + "neighbor nan bin\n", "skin must be a finite number, got 'nan'", False),
    (BOX + "timestep inf\n", "dt must be a finite number, got 'inf'", False),
    (PAIR + "pair_coeff * * kn 1000 en 0.5 mu nan\n", "mu must be a finite number, got 'nan'", True),
    (PAIR + "pair_coeff * * kn nan en 0.5\n", "kn must be a finite number, got 'nan'", False),
    (PAIR + "pair_coeff * * kn 1000 en 0.5 ks inf\n", "ks must be a finite number, got 'inf'", False),
    (RANDOM + "density nan\n", "density must be a finite number, got 'nan'", False),
    (READY + "fix g all gravity nan\n", "magnitude must be a finite number, got 'nan'", False),
    (READY + "fix g all gravity 9.81 vector 0 nan -1\n", "direction must be a finite number", False),
    ("units si\nregion box block 0 nan 0 1 0 1\n", "bound must be a finite number, got 'nan'", True),
    ("units si\nregion c cylinder z 0 0 inf 0 1\n", "radius must be a finite number, got 'inf'", False),
    (READY + "fix w all wall/plane zplane nan NULL\n", "wall position must be a number or NULL, got 'nan'",
     False),
    (READY + "set group all vx nan\n", "vx must be a finite number, got 'nan'", False),
    (READY + "thermo_modify overlap nan\n", "overlap must be a finite number", False),
    # ranges
    (PAIR + "pair_coeff * * kn 0 en 0.5\n", "kn must be > 0", False),
    (PAIR + "pair_coeff * * kn 1000 en -0.1\n", "en must be in [0, 1]", False),
    (PAIR + "pair_coeff * * kn 1000 en 0.5 mu -0.1\n", "mu must be >= 0", False),
    (PAIR + "pair_coeff * * kn 1000 en 0.5 gamma_t -1\n", "gamma_t must be >= 0", False),
    (PAIR + "pair_coeff * * kn 1000 en 0.5 ks -1\n", "ks must be >= 0", False),
    (PAIR + "pair_coeff * * kn 1000 en 0.5 mu_roll -1\n", "mu_roll must be >= 0", False),
    (RANDOM + "density 0\n", "density must be > 0", False),
    (BOX + "create_atoms 1 single 0.005 0.005 0.005 radius -1\n", "radius must be > 0", False),
    ("units si\nregion box block 0 1 0 1 1 0\n", "each upper bound must exceed the lower bound", False),
    (READY + "set group all type 1.7\n", "type must be an integer, got '1.7'", False),
    # expressions too deep for a recursive parser
    (BOX + "print $(" + "(" * 2000 + "1" + ")" * 2000 + ")\n", "expression too deeply nested", True),
    (BOX + "variable x equal " + "-" * 3000 + "1\n", "expression too deeply nested", False),
    (BOX + "print $(" + "+".join(["1"] * 5000) + ")\n", "expression too deeply nested", False),
    # absurd sizes: refused before any memory is asked for
    ("units si\nregion box block 0 1 0 1 0 1\ncreate_box 1e9 box\n", "more than dem supports (1000)", True),
    (BOX + "create_atoms 1 random 1e13 5 box radius 0.0005\n", "more than dem can create at once", True),
    (BOX + "create_atoms 1 lattice box sc 1e-9 radius 1e-10\n", "more than dem can create at once", False),
    # words nobody reads
    (READY + "run 100 bogus\n", "unknown keyword 'bogus'", True),
    (READY + "run 10 every 5\n", "every M needs at least one command", False),
    (READY + "fix 1 all nve/sphere bogus 1 2\n", "takes no arguments, got 'bogus 1 2'", True),
    (READY + "fix 1 all nve/shape 3\n", "takes no arguments, got '3'", False),
    (READY + "compute k all ke extra\n", "expected 0 argument(s), got 1", False),
    (READY + "compute k all erotate extra\n", "expected 0 argument(s), got 1", False),
    (BOX + "atom_style sphere extra\n", "unexpected argument(s) 'extra'", False),
    (BOX + "neighbor 0.001 bin extra\n", "unexpected argument(s) 'extra'", False),
    (READY + "group g type 1\ngroup g delete extra\n", "expected 2 argument(s), got 3", False),
    (BOX + "restart 10 a b c\n", "unexpected argument(s) 'c'", False),
    (BOX + "newton maybe\n", "newton must be yes or no, got 'maybe'", False),
    (BOX + "comm_modify vel yes bogus 1\n", "unknown keyword 'bogus'", False),
    (READY + "fix p all print/series 10 out.dat step append maybe\n", "append must be yes or no", False),
    (READY + "read_data a.data b.data\n", "expected 1 argument(s), got 2", False),
]


def last_line(script):
    return len(script.splitlines())


@pytest.mark.parametrize("script, message, cli", ROWS, ids=[f"{i}-{r[1][:30]}" for i, r in enumerate(ROWS)])
def test_bad_input_is_a_clear_error(tmp_path, monkeypatch, script, message, cli):
    monkeypatch.chdir(tmp_path)
    if cli:
        (tmp_path / "in.test").write_text(script)
        out = subprocess.run([sys.executable, "-m", "dem", "-in", "in.test", "-log", "none"],
                             capture_output=True, text=True, cwd=tmp_path)
        assert out.returncode == 1, out.stderr
        assert "Traceback" not in out.stderr, out.stderr
        assert f"in.test:{last_line(script)}: " in out.stderr, out.stderr
        assert message in out.stderr, out.stderr
        return
    sim = dem.Simulation(screen=False)
    with pytest.raises(dem.DemError) as err:
        sim.commands(script)
    assert err.value.where == f"<string>:{last_line(script)}", str(err.value)
    assert message in str(err.value)


def test_files_written_before_the_bad_line_stay_complete(tmp_path):
    h5py = pytest.importorskip("h5py")
    script = READY + "dump d all h5 10 out.h5\nrun 20\nprint BEFORE\npair_coeff * * kn 1000 en 0.5 mu nan\n"
    (tmp_path / "in.test").write_text(script)
    out = subprocess.run([sys.executable, "-m", "dem", "-in", "in.test", "-log", "log.test"],
                         capture_output=True, text=True, cwd=tmp_path)
    assert out.returncode == 1 and "Traceback" not in out.stderr
    log = (tmp_path / "log.test").read_text()
    assert "Loop time" in log and "BEFORE" in log and "mu must be a finite number" in log
    with h5py.File(tmp_path / "out.h5", "r") as h5:
        assert sorted(int(k) for k in h5["frames"]) == [0, 10, 20]


def test_log_in_a_missing_folder_is_created_and_an_unwritable_one_is_an_error(tmp_path):
    (tmp_path / "in.test").write_text("units si\n")
    out = subprocess.run([sys.executable, "-m", "dem", "-in", "in.test", "-log", "logs/run/log.test"],
                         capture_output=True, text=True, cwd=tmp_path)
    assert out.returncode == 0 and (tmp_path / "logs/run/log.test").read_text().startswith("dem ")
    (tmp_path / "file").write_text("")
    out = subprocess.run([sys.executable, "-m", "dem", "-in", "in.test", "-log", "file/log.test"],
                         capture_output=True, text=True, cwd=tmp_path)
    assert out.returncode == 1 and "Traceback" not in out.stderr
    assert "the log file (-log): cannot write 'file/log.test'" in out.stderr


def test_foreign_files_are_not_restart_files(tmp_path):
    h5py = pytest.importorskip("h5py")
    lammps = tmp_path / "lmp.restart"
    lammps.write_bytes(b"LammpS RestartT\x00" + bytes(range(256)) * 4)   # a LAMMPS binary restart's magic
    with h5py.File(tmp_path / "other.h5", "w") as h5:
        h5["x"] = np.arange(3)
    np.save(tmp_path / "other.npy", np.arange(3))
    for path in (lammps, tmp_path / "other.npy"):
        with pytest.raises(dem.DemError, match="is not a dem restart file"):
            dem.Simulation(screen=False).command(f"read_restart {path}")
    # an HDF5 file is never opened unchecked: without dem's checksum header it may be an old dem restart
    with pytest.raises(dem.DemError, match="is an HDF5 file without dem's checksum header .* or not a dem file"):
        dem.Simulation(screen=False).command(f"read_restart {tmp_path / 'other.h5'}")


def test_mu_without_ks_or_gamma_t_warns_once_naming_the_line(capsys):
    sim = dem.Simulation()
    sim.commands(PAIR + "pair_coeff * * kn 1000 en 0.5 mu 0.5\npair_coeff * * kn 1000 en 0.5 mu 0.4\n")
    warnings = [line for line in capsys.readouterr().out.splitlines() if line.startswith("WARNING")]
    assert len(warnings) == 1
    assert f"<string>:{last_line(PAIR) + 1}: pair_coeff: mu is given but ks, gamma_t and beta_t are 0" in warnings[0]
    sim.commands("pair_coeff * * kn 1000 en 0.5 mu 0.5 ks 100\n")
    assert "WARNING" not in capsys.readouterr().out
