"""The input-script interpreter (LAMMPS syntax).

Each command goes through the same steps: join ``&`` continuations (and triple-quoted text spanning lines),
cut the ``#`` comment, substitute ``${name}``, ``$x`` and ``$(expression[:format])`` outside quotes, split
into words (quotes group words and are removed), then run it: the interpreter's own commands here, any
other word through the registry as ``cls(sim)(args)``. A DemError leaving a command carries ``where``
("file:line").

A quote opens only at the start of a word (so ``don't`` is a plain word) and must close at the end of one.
"""
import os
import re

from .errors import DemError, unknown, unknown_style
from .files import open_output
from .variable import Variables, format_number

MAX_DEPTH = 64  # nested include / lines calls: deeper is an include loop
ECHO_MODES = ("none", "screen", "log", "both")
_FORMAT = re.compile(r"%[-+ #0]*\d*(?:\.\d+)?[eEfFgGdi]\Z")


class _Quit(Exception):
    """Raised by ``quit``: unwinds every script being read, quietly."""


# ---------------------------------------------------------------------------------------------------------
# line syntax

def _scan(text, comments=True):
    """Quoted spans ``[(start, end)]`` of a line (quote characters included) and where its comment starts."""
    spans, i, n = [], 0, len(text)
    while i < n:
        char = text[i]
        if char == "#" and comments:
            return spans, i
        if char in "\"'" and (i == 0 or text[i - 1].isspace()):
            quote = '"""' if text.startswith('"""', i) else char
            end = text.find(quote, i + len(quote))
            if end < 0:
                raise DemError(f"unterminated quote {quote} in: {text.strip()}")
            spans.append((i, end + len(quote)))
            i = end + len(quote)
        else:
            i += 1
    return spans, n


def strip_comment(text):
    return text[:_scan(text)[1]]


def split_words(text):
    """Words of a (substituted, comment-free) line; quotes group words and are removed."""
    spans = dict(_scan(text, comments=False)[0])
    words, i, n = [], 0, len(text)
    while i < n:
        if text[i].isspace():
            i += 1
        elif i in spans:
            end = spans[i]
            size = 3 if text.startswith('"""', i) else 1
            words.append(text[i + size:end - size])
            if end < n and not text[end].isspace():
                raise DemError(f"a closing quote must end the word: {text[i:end + 1]}")
            i = end
        else:
            start = i
            while i < n and not text[i].isspace():
                i += 1
            words.append(text[start:i])
    return words


def _closing_paren(text, open_at):
    depth = 0
    for i in range(open_at, len(text)):
        depth += {"(": 1, ")": -1}.get(text[i], 0)
        if depth == 0:
            return i
    raise DemError(f"missing ')' in: {text[open_at - 1:].strip()}")


class _Source:
    """A script being read: its name for messages, its raw lines and the reading position."""

    def __init__(self, name, lines, path=None):
        self.name, self.lines, self.path = name, lines, path
        self.pos = 0            # index of the next raw line
        self.lineno = 0         # first line of the command being run
        self.jump = None        # (path, lines, label) asked for by `jump`, done once its command returns
        self.label = None       # label searched for after a jump: commands are skipped until found
        self.jump_from = None   # location of that jump, for "label not found"

    @classmethod
    def from_file(cls, path, what="input file"):
        return cls(path, _read_lines(path, what), path)

    def next_command(self):
        """Text of the next command: '&' continuations joined, triple quotes over several lines kept
        together; None at the end."""
        if self.pos >= len(self.lines):
            return None
        self.lineno = self.pos + 1
        text = self._take()
        while self.pos < len(self.lines):
            stripped = text.rstrip()
            if stripped.endswith("&"):
                text = stripped[:-1] + " " + self._take()
            elif text.count('"""') % 2:
                text += "\n" + self._take()
            else:
                break
        if text.rstrip().endswith("&"):  # continuation on the last line: nothing to join
            text = text.rstrip()[:-1]
        return text

    def _take(self):
        self.pos += 1
        return self.lines[self.pos - 1]


def _read_lines(path, what):
    try:
        with open(path, encoding="utf-8") as handle:
            return handle.read().splitlines()
    except OSError as err:
        raise DemError(f"cannot open {what} '{path}': {err.strerror}") from None
    except UnicodeDecodeError:
        raise DemError(f"{what} '{path}' is not a text file") from None


def _usage(args, low, high, usage):
    if not low <= len(args) <= high:
        raise DemError(f"wrong number of arguments: expected {usage}")


# ---------------------------------------------------------------------------------------------------------
# the interpreter

class Input:
    def __init__(self, sim):
        self.sim = sim
        self.variables = Variables(sim.thermo_keyword)
        self.echo = "log"      # LAMMPS default: commands go to the log file
        self.quit_status = None   # set by `quit`
        self._stack = []          # _Source being read, innermost last
        self._skip_jump = False   # set when `next` exhausts a variable: the next jump is skipped
        self._own = {"variable": self.variables.define, "include": self._include, "print": self._print,
                     "label": self._label, "jump": self._jump, "next": self._next, "if": self._if,
                     "echo": self._echo_command, "quit": self._quit}

    # -- public interface ----------------------------------------------------------------------------------
    def file(self, path):
        """Run a whole script file."""
        self._job(_Source.from_file(path))

    def lines(self, text, name="<string>"):
        """Run several lines of text; errors are reported as name:line."""
        self._job(_Source(name, text.splitlines()))

    def _job(self, source):
        """A script read from outside any script is a job: its runs are scanned first (jpct, jeta)."""
        if self._stack:
            self._run(source)
            return
        self.sim.job.begin(source.name, source.lines)
        try:
            self._run(source)
        finally:
            self.sim.job.end()

    def one(self, line):
        """Run one command (as from sim.command); inside a running script it keeps that script's location."""
        if self._stack:
            self._command(line)
        else:
            self._run(_Source("<command>", [line]))

    def set_cli_vars(self, pairs):
        """Index variables from ``-var NAME V1 V2 ...``, defined before the script so that they win."""
        for name, values in pairs:
            if not values:
                raise DemError(f"-var {name} needs at least one value")
            self.variables.define_index(name, values)

    def evaluate(self, expression):
        """Value of an equal-style expression."""
        return self.variables.evaluate(expression)

    def variable(self, name):
        """Current value of a variable as text (equal style is evaluated now)."""
        return self.variables.text(name)

    def has_variable(self, name):
        return self.variables.has(name)

    @property
    def location(self):
        """'file:line' of the command being run, or None outside any script."""
        if not self._stack:
            return None
        source = self._stack[-1]
        return f"{source.name}:{source.lineno}"

    @property
    def script_line(self):
        """Line of the command being run when it is read from the outermost script, else None."""
        return self._stack[0].lineno if len(self._stack) == 1 else None

    def find_file(self, path):
        """A file a command reads: `path` as given (relative to the folder dem runs in), or else relative to
        the folder of the script being read (so an input finds the files shipped beside it from any
        folder); the path as given when neither exists (the reader's error names it)."""
        if os.path.isabs(path) or os.path.exists(path):
            return path
        for source in reversed(self._stack):
            if source.path:
                beside = os.path.join(os.path.dirname(os.path.abspath(source.path)), path)
                if os.path.exists(beside):
                    return beside
                break
        return path

    def substitute(self, text, quotes=True):
        """Replace ${name}, $x and $(expression[:format]); with ``quotes``, quoted text is left alone."""
        if "$" not in text:
            return text
        spans = _scan(text, comments=False)[0] if quotes else []
        pieces, done = [], 0
        for start, end in spans + [(len(text), len(text))]:
            pieces += [self._substitute_plain(text[done:start]), text[start:end]]
            done = end
        return "".join(pieces)

    # -- reading -------------------------------------------------------------------------------------------
    def _run(self, source):
        if len(self._stack) >= MAX_DEPTH:
            raise DemError(f"scripts nested more than {MAX_DEPTH} deep: does '{source.name}' include itself?")
        self._stack.append(source)
        try:
            self._read(source)
        except _Quit:
            if len(self._stack) > 1:
                raise
        finally:
            self._stack.pop()

    def _read(self, source):
        while (text := source.next_command()) is not None:
            if source.label is not None:
                self._look_for_label(source, text)
                continue
            self._command(text)
            if source.jump is not None:
                self._do_jump(source)
        if source.label is not None:
            err = DemError(f"label '{source.label}' not found in '{source.name}'")
            err.where = source.jump_from
            raise err

    def _look_for_label(self, source, text):
        # skipped lines are not substituted: their variables may not exist yet
        try:
            words = split_words(strip_comment(text))
        except DemError as err:
            err.where = f"{source.name}:{source.lineno}"
            raise
        if len(words) >= 2 and words[0] == "label" and words[1] == source.label:
            source.label = None

    def _do_jump(self, source):
        path, lines, label = source.jump
        source.jump = None
        source.name, source.path, source.lines = path, path, lines
        source.pos, source.label = 0, label

    # -- one command ---------------------------------------------------------------------------------------
    def _command(self, text):
        try:
            self._echo(text)
            line = strip_comment(text)
            substituted = self.substitute(line)
            if substituted != line:
                self._echo(substituted)
            words = split_words(substituted)
            if words:
                self._dispatch(words[0], words[1:])
        except DemError as err:
            if err.where is None:
                err.where = self.location
            raise
        except MemoryError:     # a size no check caught: still a clear error at the line that asked for it
            err = DemError("not enough memory for this command (is a count or a size far too large?)")
            err.where = self.location
            raise err from None

    def _dispatch(self, word, args):
        own = self._own.get(word)
        if own is not None:
            own(args)
            return
        commands = self.sim.registry.styles["command"]
        if word not in commands:
            raise unknown_style("command", word, [*commands, *self._own], args)
        self.sim.registry.get("command", word)(self.sim)(args)

    def _is_root(self):
        # under MPI every rank reads the script; only rank 0 writes files
        return self.sim.comm.me == 0

    def _echo(self, text):
        if self.echo == "log":
            self.sim.print(text, screen=False)
        elif self.echo != "none":
            self.sim.print(text)

    # -- substitution --------------------------------------------------------------------------------------
    def _substitute_plain(self, text):
        pieces, done = [], 0
        while (dollar := text.find("$", done)) >= 0:
            value, done_next = self._reference(text, dollar)
            pieces += [text[done:dollar], value]
            done = done_next
        pieces.append(text[done:])
        return "".join(pieces)

    def _reference(self, text, dollar):
        """(value, index after the reference) for the '$' at ``dollar``."""
        after = text[dollar + 1:dollar + 2]
        if after == "{":
            close = text.find("}", dollar)
            if close < 0:
                raise DemError(f"missing '}}' in: {text[dollar:].strip()}")
            return self.variable(text[dollar + 2:close]), close + 1
        if after == "(":
            close = _closing_paren(text, dollar + 1)
            return self._immediate(text[dollar + 2:close]), close + 1
        if after and (after.isalnum() or after == "_"):
            return self.variable(after), dollar + 2
        raise DemError(f"'$' must be followed by a name, {{name}} or (expression): {text[dollar:].strip()}")

    def _immediate(self, content):
        """$(expression) or $(expression:format)."""
        expression, colon, fmt = content.rpartition(":")
        if not colon:
            return format_number(self.evaluate(content))
        if not _FORMAT.match(fmt):
            raise DemError(f"bad format '{fmt}' in $({content}): use a C format such as %.3f or %d")
        value = self.evaluate(expression)
        return fmt % (int(value) if fmt[-1] in "di" else value)

    # -- the interpreter's own commands --------------------------------------------------------------------
    def _include(self, args):
        _usage(args, 1, 1, "include FILE")
        self._run(_Source.from_file(args[0], "include file"))

    def _print(self, args):
        usage = 'print "text" [screen yes|no] [file FILE] [append FILE]'
        if not args:
            raise DemError(f"wrong number of arguments: expected {usage}")
        options = args[1:]
        if len(options) % 2:
            raise DemError(f"print: '{options[-1]}' needs a value, expected {usage}",
                           hint="quote text that contains spaces")
        screen, target = True, None
        for key, value in zip(options[::2], options[1::2]):
            if key == "screen" and value in ("yes", "no"):
                screen = value == "yes"
            elif key in ("file", "append"):
                target = (value, "w" if key == "file" else "a")
            elif key != "universe" or value not in ("yes", "no"):  # universe: one partition only, ignored
                raise DemError(f"print: unexpected '{key} {value}', expected {usage}",
                               hint="quote text that contains spaces")
        text = self.substitute(args[0], quotes=False)
        if screen:
            self.sim.print(text)
        if target is not None:          # never into the log or another output's file (every rank checks)
            self.sim.output.names.check([target[0]], "print")
        if target is not None and self._is_root():
            _write(target, text)

    def _label(self, args):
        _usage(args, 1, 1, "label NAME")

    def _jump(self, args):
        _usage(args, 1, 2, "jump FILE|SELF [LABEL]")
        if self._skip_jump:
            self._skip_jump = False
            return
        source = self._stack[-1]
        if args[0] != "SELF":
            lines = _read_lines(args[0], "file")
            path = args[0]
        elif source.path is None:
            raise DemError(f"jump SELF needs a script file, but '{source.name}' was not read from one")
        else:
            path, lines = source.path, source.lines
        source.jump = (path, lines, args[1] if len(args) > 1 else None)
        source.jump_from = self.location

    def _next(self, args):
        if self.variables.advance(args):
            self._skip_jump = True

    def _if(self, args):
        for condition, commands in _if_branches(args):
            if condition is None or self._condition(condition):
                for command in commands:
                    self.one(command)
                return

    def _condition(self, text):
        value = self.variables.evaluate(self.substitute(text, quotes=False), strings=True)
        if isinstance(value, str):
            raise DemError(f"if condition '{text}' is the word '{value}', not a comparison or number")
        return value != 0.0

    def _echo_command(self, args):
        _usage(args, 1, 1, "echo none|screen|log|both")
        if args[0] not in ECHO_MODES:
            raise unknown("echo mode", args[0], ECHO_MODES)
        self.echo = args[0]

    def _quit(self, args):
        _usage(args, 0, 1, "quit [STATUS]")
        try:
            self.quit_status = int(args[0]) if args else 0
        except ValueError:
            raise DemError(f"quit status must be an integer, not '{args[0]}'") from None
        raise _Quit


def _if_branches(args):
    """[(condition or None for else, [commands])] of an if command."""
    usage = 'if "condition" then "command" ... [elif "condition" "command" ...] [else "command" ...]'
    if len(args) < 3 or args[1] != "then":
        raise DemError(f"wrong arguments: expected {usage}")
    branches, i = [(args[0], [])], 2
    while i < len(args):
        word = args[i]
        if word in ("elif", "else") and not branches[-1][1]:
            raise DemError(f"if: no command before '{word}', expected {usage}")
        if word == "elif":
            if branches[-1][0] is None or i + 1 >= len(args):
                raise DemError(f"if: misplaced 'elif', expected {usage}")
            branches.append((args[i + 1], []))
            i += 2
        elif word == "else":
            if branches[-1][0] is None:
                raise DemError(f"if: a second 'else', expected {usage}")
            branches.append((None, []))
            i += 1
        else:
            branches[-1][1].append(word)
            i += 1
    if not branches[-1][1]:
        raise DemError(f"if: no command after the last condition, expected {usage}")
    return branches


def _write(target, text):
    path, mode = target
    handle = open_output(path, "print", mode)
    try:
        with handle:
            handle.write(text + "\n")
    except OSError as err:
        raise DemError(f"print: cannot write '{path}': {err.strerror}") from None
