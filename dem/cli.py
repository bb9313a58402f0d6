"""The `dem` command: dem -in FILE [-var NAME VALUE ...] [-log FILE] [-screen none]; without -in the
script is read from standard input (`dem < in.file`), as LAMMPS does."""
import sys
import time

from . import __version__

from .errors import DemError

USAGE = ("usage: dem -in FILE [-var NAME VALUE ...] [-log FILE|none] [-screen none] [-echo screen|log|both]\n"
         "       dem [options] < FILE   (the script from standard input)\n"
         "       dem -h                 (this, and every installed style)\n"
         "       dem -h NAME            (the documentation of a command or style, e.g. dem -h wall/mesh)\n"
         "       dem --version")


def styles_text():
    """Every installed style by kind, with the plugin that provides it (dem -h)."""
    from .registry import KINDS, default_registry
    reg = default_registry()
    lines = ["installed styles (plugin):"]
    for kind in KINDS:
        names = sorted(reg.styles[kind])
        lines.append(f"  {kind} ({len(names)}): " + ", ".join(f"{n} ({reg.provider(kind, n)})" for n in names))
    return "\n".join(lines)


def style_help(name):
    """The documentation of every installed command or style called `name` (`fix wall/mesh` and a
    `wall/mesh` of another kind would both show), as docs/commands.md has it; an error naming the closest
    names (and dem's equivalent of a LIGGGHTS or LAMMPS name) when there is none."""
    import inspect
    from . import foreign_names
    from .errors import did_you_mean
    from .registry import KINDS, default_registry
    reg = default_registry()
    found = [(kind, reg.styles[kind][name]) for kind in KINDS if name in reg.styles[kind]]
    if not found:
        for kind in KINDS:
            answer = foreign_names.answer(kind, name, ())
            if answer is not None:
                raise DemError(f"dem has no '{name}' ({answer.origin} {kind}): {answer.text} [docs/migration.md]")
        raise DemError(f"no command or style '{name}'"
                       + did_you_mean(name, [n for kind in KINDS for n in reg.styles[kind]]))
    return "\n\n".join(f"{kind} {name} (provided by {reg.provider(kind, name)}):\n\n"
                       + inspect.cleandoc(cls.__doc__ or "(undocumented)") for kind, cls in found)


def parse(argv):
    opts = {"in": None, "var": [], "log": "log.dem", "screen": True, "echo": None}
    i = 0
    while i < len(argv):
        a = argv[i]
        key = a.lstrip("-")
        if key in ("in", "i"):
            opts["in"] = argv[i + 1]
            i += 2
        elif key in ("var", "v"):
            name = argv[i + 1]
            j = i + 2
            values = []
            while j < len(argv) and not argv[j].startswith("-"):
                values.append(argv[j])
                j += 1
            if not values:
                raise DemError(f"-var {name} needs at least one value")
            opts["var"].append((name, values))
            i = j
        elif key in ("log", "l"):
            opts["log"] = None if argv[i + 1] == "none" else argv[i + 1]
            i += 2
        elif key in ("screen", "sc"):
            opts["screen"] = argv[i + 1] != "none"
            i += 2
        elif key in ("echo", "e"):
            opts["echo"] = argv[i + 1]
            i += 2
        elif key in ("h", "help"):
            if i + 1 < len(argv) and not argv[i + 1].startswith("-"):
                print(style_help(argv[i + 1]))
            else:
                print(USAGE)
                print(styles_text())
            raise SystemExit(0)
        elif key == "version":
            print(f"dem {__version__}")
            raise SystemExit(0)
        else:
            raise DemError(f"unknown command-line option '{a}'\n{USAGE}")
    if opts["in"] is None and sys.stdin is not None and sys.stdin.isatty():
        raise DemError(f"no input script (give -in FILE, or the script on standard input)\n{USAGE}")
    return opts


def main(argv=None):
    from .interrupt import SIGNAL_STATE, Interrupted
    SIGNAL_STATE.install()       # SIGINT/SIGTERM: a clean stop (dem/interrupt.py), exit 130/143
    try:
        status = _main(sys.argv[1:] if argv is None else argv)
    except Interrupted as e:     # before the simulation existed, or while it was closed
        SIGNAL_STATE.depth += 1
        print(f"INTERRUPTED: {e.text}", file=sys.stderr, flush=True)
        return e.exit_code
    SIGNAL_STATE.depth += 1      # the process is ending: a late signal only sets the status
    signum = SIGNAL_STATE.take()
    return 128 + signum if signum and status == 0 else status


def _main(argv):
    from .interrupt import SIGNAL_STATE, Interrupted
    from .sim import Sim, fatal
    try:
        opts = parse(argv)
    except (DemError, IndexError) as e:
        print(f"ERROR: {e if isinstance(e, DemError) else 'missing value after an option'}\n{USAGE}"
              if not isinstance(e, DemError) else f"ERROR: {e}", file=sys.stderr)
        return 2
    sim = None
    try:
        sim = Sim(screen=opts["screen"], log=opts["log"], variables=opts["var"])
        sim.print(f"dem {__version__} (Discrete Element Method), started {time.strftime('%Y-%m-%d %H:%M:%S')}")
        sim.print(f"  command line: dem {' '.join(argv)}")
        sim.print(f"  {sim.comm.nprocs} process(es), input {opts['in'] or 'standard input'}, "
                  f"log {opts['log'] or 'none'}")
        if opts["echo"]:
            sim.input.one(f"echo {opts['echo']}")
        if opts["in"] is None:      # MPI launchers give standard input to rank 0 only
            sim.input.lines(sim.comm.bcast(sys.stdin.read() if sim.comm.me == 0 else None), name="<stdin>")
        else:
            sim.file(opts["in"])
        return sim.input.quit_status or 0          # `quit N` sets the exit status
    except DemError as e:
        SIGNAL_STATE.depth += 1      # reporting the error: a signal now must not cut the report short
        return fatal(sim, e)
    except Interrupted as e:
        SIGNAL_STATE.depth += 1
        if sim is None:
            print(f"INTERRUPTED: {e.text}", file=sys.stderr, flush=True)
            return e.exit_code
        return sim.comm.fatal(sim, f"INTERRUPTED: {e.text}", status=e.exit_code)
    except BrokenPipeError:          # output piped into a closed reader (e.g. `| head`)
        sys.stderr.close()
        return 1
    except KeyboardInterrupt:
        print("ERROR: interrupted", file=sys.stderr)
        return 130
    finally:
        if sim is not None:
            sim.close()


if __name__ == "__main__":
    raise SystemExit(main())
