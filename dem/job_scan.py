"""The runs a script will make, read from its text before it starts, for the job's progress (dem/job.py).

The scan keeps, in order, the commands that decide the job's steps: each `run` (its text, substituted only
when the job asks for its length, since its variables may be defined by the script itself), each
`reset_timestep` (for `run N upto`), each `read_restart` (an unknown step), and the variables each command
defines (`variable`, `next`, also inside `if` and `run ... every`), which would make a later run's length
unknown if it reads them. A script whose runs cannot be known in advance gets a reason instead: a run
inside an `if`, a loop (label ... jump SELF back over a run), a jump forward or to another file, an
include, or a command named by a variable. A loop without a run in it (e.g. create_atoms in a loop) is
fine: it changes no step count.
"""
from dataclasses import dataclass, field

from .errors import DemError
from .input import _if_branches, _Source, split_words, strip_comment

NOT_IN_BRANCH = ("run", "jump", "include", "label")   # inside `if` / `run every`: the runs are not known
STEP_UNKNOWN = ("read_restart",)                     # the step after it is the file's
STEP = "*step"                                       # in Entry.defines: the step may change (inside an if)


@dataclass
class Entry:
    lineno: int
    kind: str = ""             # "run", "reset" (reset_timestep), "restart" or "" (defines variables only)
    text: str = ""             # the command, comment cut, not substituted
    defines: set = field(default_factory=set)    # variables set; "*" for one named by a variable


@dataclass
class Plan:
    entries: list = field(default_factory=list)
    reason: str = ""           # why the runs are not known in advance; "" when they are

    def runs(self):
        return [e for e in self.entries if e.kind == "run"]


def scan(name, lines):
    """The Plan of a script's lines (never raises: a line the reader will refuse makes the plan unknown)."""
    source, commands = _Source(name, lines), []
    try:
        while (text := source.next_command()) is not None:
            words = split_words(strip_comment(text))
            if words:
                commands.append((source.lineno, words, strip_comment(text).strip()))
    except DemError:
        return Plan(reason=f"line {source.lineno} cannot be read")
    try:
        return _plan(commands)
    except _Unknown as why:
        return Plan(reason=str(why))


class _Unknown(Exception):
    pass


def _plan(commands):
    labels = {}
    for index, (_, words, _) in enumerate(commands):
        if words[0] == "label" and len(words) > 1:
            labels.setdefault(words[1], index)       # a jump reads the file from its start: the first wins
    runs = [index for index, (_, words, _) in enumerate(commands) if words[0] == "run"]
    plan = Plan()
    for index, (lineno, words, text) in enumerate(commands):
        first = words[0]
        where = f"line {lineno} '{_short(text)}'"
        if "$" in first:
            raise _Unknown(f"{where} names its command with a variable")
        if first == "quit":
            break                                   # later runs never happen
        if first == "include":
            raise _Unknown(f"{where} includes a file")
        if first == "jump":
            _check_loop(words, index, labels, runs, where)
            continue
        entry = Entry(lineno)
        if first == "run":
            entry.kind, entry.text = "run", text
            if "every" in words:
                for command in words[words.index("every") + 2:]:
                    _inner(command, entry, where)
        elif first == "reset_timestep":
            entry.kind, entry.text = "reset", text
        elif first in STEP_UNKNOWN:
            entry.kind = "restart"
        elif first == "if":
            for command in _if_commands(words, f"{where} is not a valid if"):
                _inner(command, entry, where)
        else:
            entry.defines |= _defined(words)
        if entry.kind or entry.defines:
            plan.entries.append(entry)
    return plan


def _check_loop(words, index, labels, runs, where):
    """A jump back to a label with no run between them repeats commands that change no step count."""
    if len(words) != 3 or words[1] != "SELF" or "$" in words[2]:
        raise _Unknown(f"{where} jumps where the scan cannot follow")
    target = labels.get(words[2])
    if target is None or target > index:
        raise _Unknown(f"{where} jumps forward")
    if any(target < run < index for run in runs):
        raise _Unknown(f"{where} repeats a run in a loop")


def _if_commands(words, invalid):
    """Every command of every branch of an `if` line's words (_Unknown with `invalid` when it is not one)."""
    try:
        branches = _if_branches(words[1:])
    except DemError:
        raise _Unknown(invalid) from None
    return [command for _, branch in branches for command in branch]


def _inner(command, entry, where):
    """A command inside `if` or `run ... every`: it may run or not, or many times."""
    try:
        words = split_words(command)
    except DemError:
        raise _Unknown(f"{where} holds a command that cannot be read") from None
    if not words:
        return
    if "$" in words[0] or words[0] in NOT_IN_BRANCH:
        raise _Unknown(f"{where} holds '{_short(command)}', which may or may not happen")
    if words[0] == "if":
        for inner in _if_commands(words, f"{where} holds an if that is not valid"):
            _inner(inner, entry, where)
    elif words[0] == "reset_timestep" or words[0] in STEP_UNKNOWN:
        entry.defines.add(STEP)                     # the step afterwards is not known
    else:
        entry.defines |= _defined(words)


def _defined(words):
    """The variables a command sets (`variable NAME ...`, `next NAME ...`)."""
    if words[0] == "variable" and len(words) > 1:
        names = words[1:2]
    elif words[0] == "next":
        names = words[1:]
    else:
        return set()
    return {"*" if "$" in n else n for n in names}


def _short(text, size=40):
    text = " ".join(text.split())
    return text if len(text) <= size else text[:size - 3] + "..."
