"""Argument parsing for commands and styles: numbers with the command's usage in every error message,
and `keyword value ...` tails with suggestions for misspelt keywords."""
import math

from .errors import DemError, did_you_mean

# an integer input larger than this is a typo or an overflow, never a count dem could hold
MAX_INT = 2 ** 63 - 1


def number(word):
    """float(word) for a finite value only: nan and inf are refused (as LAMMPS does), since none of
    them is a usable coefficient, bound or count. ValueError otherwise."""
    value = float(word)
    if not math.isfinite(value):
        raise ValueError(f"non-finite number '{word}'")
    return value


def integer(word):
    """int(word), also for an integral float such as 1e5; ValueError for anything else (1.7, nan, inf)."""
    try:
        return int(word)
    except ValueError:
        pass
    value = number(word)
    if value != int(value) or abs(value) > MAX_INT:
        raise ValueError(f"not an integer '{word}'")
    return int(value)


def float_error(word, name):
    """The message for a word that is not a finite number."""
    try:
        float(word)
    except ValueError:
        return f"{name} must be a number, got '{word}'"
    return f"{name} must be a finite number, got '{word}'"


class Args:
    def __init__(self, words, usage, what):
        self.words = list(words)
        self.usage = usage
        self.what = what

    def error(self, message):
        return DemError(f"{self.what}: {message}; usage: {self.usage}")

    def need(self, n):
        if len(self.words) < n:
            raise self.error(f"expected at least {n} argument(s), got {len(self.words)}")

    def exactly(self, n):
        if len(self.words) != n:
            raise self.error(f"expected {n} argument(s), got {len(self.words)}")

    def __len__(self):
        return len(self.words)

    def __getitem__(self, i):
        try:
            return self.words[i]
        except IndexError:
            raise self.error("missing argument") from None

    def float(self, i, name="value", positive=False, nonneg=False):
        value = self.to_float(self[i], name)
        word = self[i]
        if positive and not value > 0:
            raise self.error(f"{name} must be > 0, got {word}")
        if nonneg and value < 0:
            raise self.error(f"{name} must be >= 0, got {word}")
        return value

    def int(self, i, name="value", positive=False, nonneg=False):
        word = self[i]
        value = self.to_int(word, name)
        if positive and value <= 0:
            raise self.error(f"{name} must be > 0, got {word}")
        if nonneg and value < 0:
            raise self.error(f"{name} must be >= 0, got {word}")
        return value

    def floats(self, start, n, name="values"):
        return [self.float(start + k, name) for k in range(n)]

    def keywords(self, start, spec):
        """Parse `key v1 v2 ...` pairs from position `start`. spec: {key: number of values}. Returns
        {key: [values...]} with values as strings; unknown keys raise with a suggestion."""
        out = {}
        i = start
        while i < len(self.words):
            key = self.words[i]
            if key not in spec:
                raise self.error(f"unknown keyword '{key}'{did_you_mean(key, spec)}")
            n = spec[key]
            if i + n > len(self.words) - 1:
                raise self.error(f"keyword '{key}' needs {n} value(s)")
            out[key] = self.words[i + 1:i + 1 + n]
            i += 1 + n
        return out

    def to_float(self, word, name):
        try:
            return number(word)
        except ValueError:
            raise self.error(float_error(word, name)) from None

    def to_int(self, word, name):
        try:
            return integer(word)
        except ValueError:
            raise self.error(f"{name} must be an integer, got '{word}'") from None

    def done(self, used):
        """Refuse words after the first `used` ones: a word dem does not read is an error, never ignored."""
        if len(self.words) > used:
            raise self.error(f"unexpected argument(s) '{' '.join(self.words[used:])}'")

    def yes_no(self, word, name):
        if word in ("yes", "on", "1"):
            return True
        if word in ("no", "off", "0"):
            return False
        raise self.error(f"{name} must be yes or no, got '{word}'")


def parse_types(word, ntypes, what="type"):
    """LAMMPS type ranges: '*', '2', '2*', '*3', '1*4'. Returns a list of ints."""
    if "*" in word:
        lo, hi = word.split("*", 1)
        try:
            lo = int(lo) if lo else 1
            hi = int(hi) if hi else ntypes
        except ValueError:
            raise DemError(f"bad {what} '{word}': use N, N*, *N, N*M or *") from None
    else:
        try:
            lo = hi = int(word)
        except ValueError:
            raise DemError(f"bad {what} '{word}': use N, N*, *N, N*M or *") from None
    if lo < 1 or hi > ntypes or lo > hi:
        raise DemError(f"{what} '{word}' out of range 1..{ntypes}")
    return list(range(lo, hi + 1))
