"""User-facing errors. A DemError is a user mistake or a physical failure that the run reports in one clear
line (the input interpreter prefixes file:line); anything else is a bug and keeps its traceback."""
import difflib

from . import foreign_names


class DemError(Exception):
    """An error the user can act on. `where` is "file:line" once the interpreter knows it."""

    def __init__(self, message, hint=None):
        super().__init__(message)
        self.message = message
        self.hint = hint
        self.where = None

    def __str__(self):
        text = f"{self.where}: {self.message}" if self.where else self.message
        if self.hint:
            text += f"\n  hint: {self.hint}"
        return text


def did_you_mean(word, choices):
    """' (did you mean 'x'?)' for the closest valid word, or '' when nothing is close."""
    close = difflib.get_close_matches(word, list(choices), n=1, cutoff=0.6)
    return f" (did you mean '{close[0]}'?)" if close else ""


def unknown(kind, word, choices):
    return DemError(f"unknown {kind} '{word}'{did_you_mean(word, choices)}")


def unknown_style(kind, word, choices, args=()):
    """An unknown command (kind "command") or style of a registry kind. A LIGGGHTS or LAMMPS name of
    dem.foreign_names is answered with dem's equivalent (a did-you-mean would point at an unrelated dem
    word: communicate -> compute); a misspelt one gets did-you-mean among dem's and the table's names,
    with the table's answer when the closest is the table's."""
    what = "command" if kind == "command" else f"{kind} style"
    found = foreign_names.answer(kind, word, args)
    if found is not None:
        return DemError(f"unknown {what} '{word}' ({found.origin}): {found.text} [docs/migration.md]")
    foreign = [name for name in foreign_names.names(kind) if name not in choices]
    close = difflib.get_close_matches(word, [*choices, *foreign], n=1, cutoff=0.6)
    if close and close[0] in foreign:
        found = foreign_names.answer(kind, close[0], args)
        return DemError(f"unknown {what} '{word}' (did you mean {found.origin} '{close[0]}'? in dem: "
                        f"{found.text} [docs/migration.md])")
    return DemError(f"unknown {what} '{word}'" + (f" (did you mean '{close[0]}'?)" if close else ""))
