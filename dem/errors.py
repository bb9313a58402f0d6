"""User-facing errors. A DemError is a user mistake or a physical failure that the run reports in one clear
line (the input interpreter prefixes file:line); anything else is a bug and keeps its traceback."""
import difflib


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
