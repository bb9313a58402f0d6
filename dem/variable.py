"""Input-script variables (styles equal, index, loop, string) and the arithmetic of equal-style expressions.

Expressions are parsed by hand into a tree of closures (never Python ``eval``) and cached by text, so an
expression a fix evaluates every step is parsed once. Precedence follows LAMMPS, lowest first::

    || |^   &&   == !=   < <= > >=   + -   * / %   ^   unary - and !

Binary operators associate left to right (``2^3^2`` is 64) and unary minus binds tighter than ``^``
(``-2^2`` is 4), as in LAMMPS. Comparisons and logic give 1.0 or 0.0.
"""
import contextlib
import functools
import math
import re

from .errors import DemError, did_you_mean, unknown


def format_number(value):
    """Text of a number as substituted into a script: 15 significant digits, integers without a dot."""
    return "%.15g" % value


# ---------------------------------------------------------------------------------------------------------
# expressions

_TOKEN = re.compile(r"""\s*(?:
    (?P<num>(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)
  | (?P<name>[A-Za-z_][A-Za-z0-9_]*(?:\[\w+\])?)
  | (?P<text>'[^']*')
  | (?P<op>==|!=|<=|>=|&&|\|\||\|\^|[-+*/^%<>!(),])
)""", re.VERBOSE)

_PRECEDENCE = {"||": 1, "|^": 1, "&&": 2, "==": 3, "!=": 3, "<": 4, "<=": 4, ">": 4, ">=": 4,
               "+": 5, "-": 5, "*": 6, "/": 6, "%": 6, "^": 7}

_CONSTANTS = {"PI": math.pi, "pi": math.pi, "on": 1.0, "off": 0.0, "true": 1.0, "false": 0.0,
              "yes": 1.0, "no": 0.0}


# parentheses and unary operators nested deeper than this are refused: the parser and the evaluation
# recurse once per level, and a clear error beats Python's recursion limit
MAX_NESTING = 200


def _round(x):
    # C round(): halves go away from zero (Python's round() goes to even)
    return math.copysign(math.floor(abs(x) + 0.5), x)


# name: (number of arguments, function)
FUNCTIONS = {
    "sqrt": (1, math.sqrt), "exp": (1, math.exp), "ln": (1, math.log), "log": (1, math.log10),
    "abs": (1, abs), "sin": (1, math.sin), "cos": (1, math.cos), "tan": (1, math.tan),
    "asin": (1, math.asin), "acos": (1, math.acos), "atan": (1, math.atan), "atan2": (2, math.atan2),
    "floor": (1, math.floor), "ceil": (1, math.ceil), "round": (1, _round), "min": (2, min), "max": (2, max),
}


def _tokenize(text):
    tokens, pos = [], 0
    text = text.rstrip()
    while pos < len(text):
        match = _TOKEN.match(text, pos)
        if match is None or match.end() == pos:
            bad = text[pos:].lstrip()[:1]
            hint = "use v_NAME for a variable inside an expression" if bad == "$" else None
            raise DemError(f"bad expression '{text}': unexpected character '{bad}'", hint)
        kind = match.lastgroup
        tokens.append((kind, match.group(kind)))
        pos = match.end()
    return tokens


class _Parser:
    """Recursive descent over the tokens, building closures ``node(ctx) -> value``. ``ctx`` answers
    ``number(name)`` for v_name and ``thermo(name)`` for any other bare name."""

    def __init__(self, text, strings):
        self.text = text
        self.strings = strings  # boolean (if-command) mode: unknown bare words are strings
        self.tokens = _tokenize(text)
        self.pos = 0
        self.depth = 0

    def error(self, what):
        return DemError(f"bad expression '{self.text}': {what}")

    def peek(self):
        return self.tokens[self.pos] if self.pos < len(self.tokens) else (None, None)

    def take(self):
        token = self.peek()
        if token[0] is None:
            raise self.error("it ends too early")
        self.pos += 1
        return token

    def expect(self, op):
        kind, value = self.peek()
        if kind is None:
            raise self.error(f"expected '{op}' at the end")
        if (kind, value) != ("op", op):
            raise self.error(f"expected '{op}' but found '{value}'")
        self.pos += 1

    def parse(self):
        if not self.tokens:
            raise DemError("empty expression")
        node = self.binary(1)
        if self.pos < len(self.tokens):
            raise self.error(f"unexpected '{self.tokens[self.pos][1]}'")
        return node

    def nested(self):
        self.depth += 1
        if self.depth > MAX_NESTING:
            raise DemError(f"expression too deeply nested (more than {MAX_NESTING} levels of parentheses or "
                           f"unary operators): {self.text[:40]}...")

    def binary(self, min_level):
        left = self.unary()
        while True:
            kind, op = self.peek()
            level = _PRECEDENCE.get(op, 0) if kind == "op" else 0
            if level < min_level or level == 0:
                return left
            self.pos += 1
            left = _binary_node(op, left, self.binary(level + 1), self.text, self.strings)

    def unary(self):
        kind, op = self.peek()
        if kind == "op" and op in ("-", "!", "+"):
            self.pos += 1
            self.nested()
            operand = self.unary()
            self.depth -= 1
            return _unary_node(op, operand, self.strings)
        return self.primary()

    def primary(self):
        kind, value = self.take()
        if kind == "num":
            number = float(value)
            return lambda ctx: number
        if kind == "op" and value == "(":
            self.nested()
            node = self.binary(1)
            self.expect(")")
            self.depth -= 1
            return node
        if kind == "name":
            return self.name(value)
        if kind == "text":      # 'quoted text' (if conditions): any characters, compared as a word
            if not self.strings:
                raise self.error(f"quoted text {value} is only for the conditions of `if`")
            text = value[1:-1]
            return lambda ctx: text
        raise self.error(f"unexpected '{value}'")

    def name(self, word):
        if self.peek() == ("op", "("):
            return self.call(word)
        if word in _CONSTANTS:
            constant = _CONSTANTS[word]
            return lambda ctx: constant
        if word.startswith("v_"):
            if len(word) == 2:
                raise self.error("'v_' needs a variable name")
            var = word[2:]
            return lambda ctx: ctx.number(var)
        if self.strings:
            return lambda ctx: ctx.thermo_or_word(word)
        return lambda ctx: ctx.thermo(word)

    def call(self, name):
        if name not in FUNCTIONS:
            raise unknown("function", name, FUNCTIONS)
        nargs, func = FUNCTIONS[name]
        self.expect("(")
        args = [self.binary(1)]
        while self.peek() == ("op", ","):
            self.pos += 1
            args.append(self.binary(1))
        self.expect(")")
        if len(args) != nargs:
            raise self.error(f"{name}() takes {nargs} argument{'s' if nargs > 1 else ''}, not {len(args)}")
        strings = self.strings

        def node(ctx):
            values = [_as_number(arg(ctx), strings) for arg in args]
            try:
                return float(func(*values))
            except (ValueError, OverflowError):
                shown = ", ".join(format_number(v) for v in values)
                raise DemError(f"{name}({shown}) is undefined or too large") from None
        return node


def _as_number(value, strings):
    # only boolean-mode expressions can hold words; they may be compared, never computed with
    if strings and isinstance(value, str):
        raise DemError(f"'{value}' is not a number or a known name")
    return value


def _unary_node(op, operand, strings):
    if op == "-":
        return lambda ctx: -_as_number(operand(ctx), strings)
    if op == "!":
        return lambda ctx: 0.0 if _as_number(operand(ctx), strings) else 1.0
    return lambda ctx: _as_number(operand(ctx), strings)


def _power(a, b):
    try:
        return math.pow(a, b)
    except (ValueError, OverflowError):
        raise DemError(f"{format_number(a)}^{format_number(b)} is undefined or too large") from None


def _arithmetic(op, text):
    """The function computing ``a op b`` on numbers; zero divisors are user errors naming the expression."""
    def divide(a, b):
        if b == 0.0:
            raise DemError(f"division by zero in '{text}'")
        return finite(a / b, a, b)

    def finite(value, a, b):
        """An overflow of finite numbers is an error (it printed `inf`)."""
        if math.isinf(value) and math.isfinite(a) and math.isfinite(b):
            raise DemError(f"'{text}' overflows: {format_number(a)} {op} {format_number(b)} is too large")
        return value

    def modulo(a, b):
        if b == 0.0:
            raise DemError(f"modulo by zero in '{text}'")
        return math.fmod(a, b)

    return {
        "+": lambda a, b: finite(a + b, a, b), "-": lambda a, b: finite(a - b, a, b),
        "*": lambda a, b: finite(a * b, a, b), "/": divide, "%": modulo, "^": _power,
        "<": lambda a, b: float(a < b), "<=": lambda a, b: float(a <= b),
        ">": lambda a, b: float(a > b), ">=": lambda a, b: float(a >= b),
        "==": lambda a, b: float(a == b), "!=": lambda a, b: float(a != b),
        "&&": lambda a, b: float(bool(a) and bool(b)), "||": lambda a, b: float(bool(a) or bool(b)),
        "|^": lambda a, b: float(bool(a) != bool(b)),
    }[op]


def _binary_node(op, left, right, text, strings):
    compute = _arithmetic(op, text)
    if not strings:
        return lambda ctx: compute(left(ctx), right(ctx))

    def node(ctx):
        a, b = left(ctx), right(ctx)
        if op in ("==", "!=") and (isinstance(a, str) or isinstance(b, str)):
            same = _as_text(a) == _as_text(b)
            return float(same if op == "==" else not same)
        return compute(_as_number(a, True), _as_number(b, True))
    return node


def _as_text(value):
    return value if isinstance(value, str) else format_number(value)


@functools.lru_cache(maxsize=4096)
def compile_expression(text, strings=False):
    """Parse an expression once into ``node(ctx) -> float`` (or a word, in boolean mode with ``strings``)."""
    return _Parser(text, strings).parse()


# ---------------------------------------------------------------------------------------------------------
# variables

_VALID_NAME = re.compile(r"[A-Za-z0-9_]+\Z")


class _Index:
    style = "index"

    def __init__(self, name, args):
        if not args:
            raise DemError(f"variable {name} index needs at least one value")
        self.values, self.at = list(args), 0

    def text(self, variables):
        return self.values[self.at]

    def advance(self):
        """Step to the next value; True when there is none left."""
        self.at += 1
        return self.at >= len(self.values)


class _Loop:
    style = "loop"

    def __init__(self, name, args):
        usage = f"variable {name} loop N [pad] or variable {name} loop N1 N2 [pad]"
        pad = bool(args) and args[-1] == "pad"
        bounds = args[:-1] if pad else args
        if len(bounds) not in (1, 2):
            raise DemError(f"wrong number of arguments: expected {usage}")
        try:
            numbers = [int(word) for word in bounds]
        except ValueError:
            raise DemError(f"loop bounds must be integers: {' '.join(bounds)}") from None
        self.first, self.last = (1, numbers[0]) if len(numbers) == 1 else numbers
        if self.last < self.first or (len(numbers) == 1 and self.last < 1):
            raise DemError(f"empty loop: {' '.join(bounds)} (expected {usage})")
        self.now = self.first
        self.width = len(str(self.last)) if pad else 0

    def text(self, variables):
        return str(self.now).zfill(self.width)

    def advance(self):
        self.now += 1
        return self.now > self.last


class _Equal:
    style = "equal"

    def __init__(self, name, args):
        if len(args) != 1:
            raise DemError(f"variable {name} equal expects one expression, found {len(args)} words",
                           hint=f'quote an expression with spaces: variable {name} equal "1 + 2"')
        self.expression = args[0]
        self.node = compile_expression(self.expression)  # syntax errors show at the definition

    def text(self, variables):
        return format_number(variables.number_of(self))


class _String:
    style = "string"

    def __init__(self, name, args):
        if len(args) != 1:
            raise DemError(f"variable {name} string expects one value, found {len(args)} words",
                           hint=f'quote text with spaces: variable {name} string "a b"')
        self.value = args[0]

    def text(self, variables):
        return self.value


STYLES = {cls.style: cls for cls in (_Equal, _Index, _Loop, _String)}
_ADVANCING = ("index", "loop")


class NotStatic(DemError):
    """An expression evaluated under `Variables.static` asked for the simulation's state."""


class Variables:
    """The named variables of one simulation. ``thermo(name) -> float`` answers bare names in expressions."""

    def __init__(self, thermo):
        self._thermo = thermo
        self._vars = {}
        self._evaluating = set()  # equal variables being evaluated, to catch self-reference
        self._used = None         # under `static`: the names of the variables read

    @contextlib.contextmanager
    def static(self):
        """Evaluate ahead of time (the job's later run lengths): yields the set of the variables read, and a
        bare name (step, time, c_ID...) raises NotStatic, since its value changes as the job goes on."""
        outer, self._used = self._used, set()
        try:
            yield self._used
        finally:
            used, self._used = self._used, outer
            if outer is not None:
                outer |= used

    # -- definition ----------------------------------------------------------------------------------------
    def define(self, args):
        """The ``variable NAME STYLE ARGS...`` command."""
        if len(args) < 2:
            raise DemError("wrong number of arguments: expected variable NAME STYLE ARGS...")
        name, style, rest = args[0], args[1], args[2:]
        _check_name(name)
        if style == "delete":
            if rest:
                raise DemError(f"wrong number of arguments: expected variable {name} delete")
            self._vars.pop(name, None)
            return
        if style not in STYLES:
            raise unknown("variable style", style, [*STYLES, "delete"])
        old = self._vars.get(name)
        if old is not None and style in _ADVANCING:
            return  # LAMMPS: an existing variable wins, so -var on the command line overrides the script
        if old is not None and old.style != style:
            raise DemError(f"variable '{name}' is {old.style} style and cannot be redefined as {style} style")
        self._vars[name] = STYLES[style](name, rest)

    def define_index(self, name, values):
        self.define([name, "index", *values])

    def has(self, name):
        return name in self._vars

    def names(self):
        return list(self._vars)

    def style(self, name):
        return self._get(name).style

    # -- values --------------------------------------------------------------------------------------------
    def _get(self, name):
        if self._used is not None:
            self._used.add(name)
        try:
            return self._vars[name]
        except KeyError:
            raise DemError(f"undefined variable '{name}'{did_you_mean(name, self._vars)}") from None

    def text(self, name):
        """Current value as text (equal style is evaluated now)."""
        return self._get(name).text(self)

    def number(self, name):
        """Current value as a number, for v_name in expressions."""
        var = self._get(name)
        if var.style == "equal":
            return self.number_of(var)
        value = var.text(self)
        try:
            return float(value)
        except ValueError:
            raise DemError(f"variable '{name}' is not a number: '{value}'") from None

    def number_of(self, var):
        if id(var) in self._evaluating:
            raise DemError(f"variable expression '{var.expression}' refers to itself")
        self._evaluating.add(id(var))
        try:
            return var.node(self)
        except RecursionError:
            raise DemError(f"variable expression too deeply nested: {var.expression[:40]}...") from None
        finally:
            self._evaluating.discard(id(var))

    def evaluate(self, text, strings=False):
        """Value of an expression; with ``strings`` (if-conditions) unknown words compare as text."""
        try:
            return compile_expression(text, strings)(self)
        except RecursionError:      # e.g. thousands of chained operators: a tree too deep to evaluate
            raise DemError(f"expression too deeply nested: {text[:40]}...") from None

    def thermo(self, name):
        if self._used is not None:
            raise NotStatic(f"'{name}' is a value of the simulation's state")
        if self._thermo is None:
            raise DemError(f"unknown name '{name}' in expression")
        return float(self._thermo(name))

    def thermo_or_word(self, name):
        try:
            return self.thermo(name)
        except DemError:
            return name

    # -- next ----------------------------------------------------------------------------------------------
    def advance(self, names):
        """The ``next`` command: advance each variable, deleting exhausted ones; True if any ran out."""
        if not names:
            raise DemError("wrong number of arguments: expected next NAME [NAME ...]")
        found = [self._get(name) for name in names]
        styles = {var.style for var in found}
        if not styles <= set(_ADVANCING):
            bad = next(n for n, v in zip(names, found) if v.style not in _ADVANCING)
            raise DemError(f"next cannot advance '{bad}': only index and loop variables have a next value")
        if len(styles) > 1:
            raise DemError(f"next: variables {' '.join(names)} must all be of the same style")
        exhausted = False
        for name, var in zip(names, found):
            if var.advance():
                del self._vars[name]
                exhausted = True
        return exhausted


def _check_name(name):
    if not _VALID_NAME.match(name):
        raise DemError(f"invalid variable name '{name}': use letters, digits and underscores")
