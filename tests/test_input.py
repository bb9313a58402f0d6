"""The input-script interpreter and variables, driven through a small stub simulation."""
import math
import types

import pytest

from dem.errors import DemError, unknown
from dem.input import Input
from dem.job import Job
from dem.output_names import OutputNames


class Recorder:
    """A registered command that records its arguments (and where it ran) on the sim."""
    style = None

    def __init__(self, sim):
        self.sim = sim

    def __call__(self, args):
        self.sim.calls.append((self.style, args))
        self.sim.where.append(self.sim.input.location)


def recorder(name):
    return type(f"Cmd_{name}", (Recorder,), {"style": name})


class Boom(Recorder):
    style = "boom"

    def __call__(self, args):
        raise DemError("boom went wrong")


class StubRegistry:
    def __init__(self, classes):
        self.styles = {"command": {cls.style: cls for cls in classes}}

    def get(self, kind, style):
        try:
            return self.styles[kind][style]
        except KeyError:
            raise unknown(kind, style, self.styles[kind]) from None


class StubSim:
    THERMO = {"step": 100.0, "atoms": 8.0, "time": 0.5, "xhi": 2.0}

    def __init__(self):
        self.registry = StubRegistry([recorder(n) for n in ("run", "fix", "units", "region")] + [Boom])
        self.calls, self.where, self.screen, self.log = [], [], [], []
        self.comm = types.SimpleNamespace(me=0)
        self.output = types.SimpleNamespace(names=OutputNames())     # print's file checks
        self.job = Job(self)                                         # a script is scanned for its runs
        self.input = Input(self)

    def print(self, text, screen=True):
        self.log.append(text)
        if screen:
            self.screen.append(text)

    def thermo_keyword(self, name):
        if name not in self.THERMO:
            raise DemError(f"unknown thermo keyword '{name}'")
        return self.THERMO[name]


@pytest.fixture
def sim():
    return StubSim()


@pytest.fixture
def workdir(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


def run(sim, text):
    sim.input.lines(text, name="in.test")
    return sim.screen


def error(sim, text, name="in.test"):
    with pytest.raises(DemError) as info:
        sim.input.lines(text, name=name)
    return info.value


# ----------------------------------------------------------------------------------------------------------
# line syntax

def test_comments_blank_lines_and_hash_in_quotes(sim):
    run(sim, "# a whole comment line\n\n   \nfix 1 all nve # trailing comment\nprint 'a # b'  # c\n")
    assert sim.calls == [("fix", ["1", "all", "nve"])]
    assert sim.screen == ["a # b"]


def test_continuation_joins_lines_and_reports_first_line(sim):
    run(sim, "units si\nfix 1 all &\n   nve &\n   extra\nrun 5\n")
    assert sim.calls[1] == ("fix", ["1", "all", "nve", "extra"])
    assert sim.where == ["in.test:1", "in.test:2", "in.test:5"]


def test_quotes_group_words_and_are_removed(sim):
    run(sim, """fix 1 all "a b"  'c  d' don't "" last""")
    assert sim.calls == [("fix", ["1", "all", "a b", "c  d", "don't", "", "last"])]


def test_triple_quotes_span_lines(sim):
    run(sim, 'print """first line\nsecond "quoted" line"""\nrun 1\n')
    assert sim.screen == ['first line\nsecond "quoted" line']
    assert sim.where == ["in.test:3"]


def test_no_substitution_inside_quotes(sim):
    run(sim, "variable x string hi\nfix 1 all \"${x}\" '$x' $x\n")
    assert sim.calls == [("fix", ["1", "all", "${x}", "$x", "hi"])]


def test_substituted_value_with_spaces_splits_into_words(sim):
    run(sim, 'variable args string "1 all nve"\nfix ${args}\n')
    assert sim.calls == [("fix", ["1", "all", "nve"])]


def test_command_classes_are_built_with_the_sim_and_get_args(sim):
    sim.input.one("run 1000 upto")
    assert sim.calls == [("run", ["1000", "upto"])]
    assert sim.where == ["<command>:1"]
    assert sim.input.location is None


# ----------------------------------------------------------------------------------------------------------
# variables

def test_equal_is_evaluated_when_used(sim):
    run(sim, 'variable a equal 2\nvariable b equal "v_a * 10"\nprint $b\n'
             'variable a equal 3\nprint ${b}\n')
    assert sim.screen == ["20", "30"]


def test_equal_with_thermo_keywords(sim):
    run(sim, 'variable s equal "step/4 + atoms"\nprint $s\nprint $(time*xhi)\n')
    assert sim.screen == ["33", "1"]


def test_string_and_delete(sim):
    run(sim, 'variable s string "hello world"\nprint "${s}!"\nvariable s string bye\nprint $s\n'
             'variable s delete\n')
    assert sim.screen == ["hello world!", "bye"]
    assert not sim.input.has_variable("s")


def test_index_and_loop_values(sim):
    run(sim, "variable i index a b\nvariable n loop 3\nvariable p loop 8 12 pad\nvariable q loop 10 pad\n"
             "print $i$n${p}${q}\n")
    assert sim.screen == ["a10801"]
    assert sim.input.variable("p") == "08"


def test_redefinition_rules(sim):
    run(sim, "variable i index 1 2\nvariable i index 9\nvariable a equal 1\nvariable a equal 2\n"
             "variable i loop 5\nprint $i$a\n")
    assert sim.screen == ["12"]
    err = error(sim, "variable a string x\n")
    assert "cannot be redefined as string style" in err.message and err.where == "in.test:1"


def test_variable_interface(sim):
    run(sim, "variable a equal 1.5*2\nvariable w string word\n")
    assert sim.input.variable("a") == "3"
    assert sim.input.variable("w") == "word"
    assert sim.input.evaluate("v_a + 0.25") == 3.25
    assert sim.input.has_variable("a") and not sim.input.has_variable("zz")
    with pytest.raises(DemError, match="undefined variable 'aa'"):
        sim.input.variable("aa")


def test_cli_vars_take_precedence_over_index(sim):
    sim.input.set_cli_vars([("n", ["7"]), ("m", ["x", "y"])])
    run(sim, "variable n index 3\nvariable m index z\nprint $n$m\nnext m\nprint $n$m\n")
    assert sim.screen == ["7x", "7y"]


def test_cli_var_needs_a_value(sim):
    with pytest.raises(DemError, match="needs at least one value"):
        sim.input.set_cli_vars([("n", [])])


# ----------------------------------------------------------------------------------------------------------
# expressions

@pytest.mark.parametrize("expression, value", [
    ("1+2*3", 7), ("(1+2)*3", 9), ("3-2-1", 0), ("8/4/2", 1), ("2*3^2", 18),
    ("2^3^2", 64), ("-2^2", 4), ("2^-1", 0.5), ("- -3", 3), ("7%3", 1), ("-7%3", -1), ("1e3+.5", 1000.5),
    ("1+2==3", 1), ("1 < 2 == 1", 1), ("2 <= 2", 1), ("3 > 4", 0), ("3 >= 4", 0), ("1 != 1", 0),
    ("1<2 && 2<1", 0), ("1<2 || 2<1", 1), ("0 || 0 && 1", 0), ("1 || 0 && 0", 1), ("!0", 1),
    ("!(1==1)", 0), ("1 |^ 1", 0), ("yes + on + true", 3), ("no", 0),
])
def test_precedence_and_operators(sim, expression, value):
    assert sim.input.evaluate(expression) == pytest.approx(value)


@pytest.mark.parametrize("expression, value", [
    ("sqrt(16)", 4), ("exp(0)", 1), ("ln(exp(2))", 2), ("log(1000)", 3), ("abs(-2.5)", 2.5),
    ("sin(PI/2)", 1), ("cos(0)", 1), ("tan(pi/4)", 1), ("asin(1)", math.pi / 2), ("acos(1)", 0),
    ("atan(1)", math.pi / 4), ("atan2(1, -1)", 3 * math.pi / 4), ("floor(-1.5)", -2), ("ceil(1.2)", 2),
    ("round(2.5)", 3), ("round(-2.5)", -3), ("round(2.4)", 2), ("min(3,4)", 3), ("max(3, 2*2)", 4),
    ("sqrt(max(9, step - 84))", 4),
])
def test_functions(sim, expression, value):
    assert sim.input.evaluate(expression) == pytest.approx(value)


@pytest.mark.parametrize("expression, message", [
    ("2*", "bad expression '2*'"),
    ("(1+2", "expected ')'"),
    ("1 2", "unexpected '2'"),
    ("2 $ 3", "unexpected character '$'"),
    ("sqr(4)", "unknown function 'sqr' (did you mean 'sqrt'?)"),
    ("atan2(1)", "takes 2 arguments"),
    ("1/0", "division by zero in '1/0'"),
    ("5 % (1-1)", "modulo by zero"),
    ("sqrt(-1)", "sqrt(-1) is undefined"),
    ("10^400", "too large"),
    ("1e308*10", "'1e308*10' overflows: 1e+308 * 10 is too large"),
    ("1e308+1e308", "overflows"),
    ("-1e308-1e308", "overflows"),
    ("1e300/1e-10", "overflows"),
    ("(-8)^(1/3)", "undefined"),
    ("stpe", "unknown thermo keyword 'stpe'"),
    ("v_nope", "undefined variable 'nope'"),
    ("", "empty expression"),
])
def test_expression_errors(sim, expression, message):
    with pytest.raises(DemError) as info:
        sim.input.evaluate(expression)
    assert message in info.value.message


def test_variable_errors_at_definition(sim):
    err = error(sim, "units si\nvariable a equal 2*(3\n")
    assert err.where == "in.test:2" and "expected ')'" in err.message
    assert "quote an expression" in str(error(sim, "variable a equal 1 + 2\n"))
    assert "did you mean 'equal'" in error(sim, "variable a equl 1\n").message
    assert "wrong number of arguments" in error(sim, "variable a\n").message
    assert "invalid variable name" in error(sim, "variable a-b equal 1\n").message
    assert "empty loop" in error(sim, "variable i loop 0\n").message
    assert "integers" in error(sim, "variable i loop x\n").message
    assert "needs at least one value" in error(sim, "variable i index\n").message


def test_self_reference_is_an_error(sim):
    run(sim, "variable a equal v_b+1\nvariable b equal v_a\n")
    with pytest.raises(DemError, match=r"variable expression 'v_b\+1' refers to itself"):
        sim.input.evaluate("v_a")


def test_non_numeric_variable_in_expression(sim):
    err = error(sim, "variable s string abc\nprint $(v_s+1)\n")
    assert "variable 's' is not a number: 'abc'" in err.message and err.where == "in.test:2"


# ----------------------------------------------------------------------------------------------------------
# substitution

def test_substitution_forms(sim):
    run(sim, "variable a equal 2/3\nvariable x index 5\nvariable long string LONG\n"
             "print ${long}-$x-$(v_a*3)-$(v_a:%.3f)-$(v_x*2:%03d)-$(1e-7)\n")
    assert sim.screen == ["LONG-5-2-0.667-010-1e-07"]


def test_substitution_errors(sim):
    err = error(sim, "units si\nprint ${nope}\n")
    assert err.message == "undefined variable 'nope'" and err.where == "in.test:2"
    assert "did you mean 'speed'" in error(sim, "variable speed equal 1\nprint ${sped}\n").message
    assert "missing '}'" in error(sim, "print ${a\n").message
    assert "missing ')'" in error(sim, "print $(1+(2)\n").message
    assert "bad format" in error(sim, "print $(1:%s)\n").message
    assert "'$' must be followed" in error(sim, "print $\n").message


def test_print_and_if_substitute_their_own_arguments(sim):
    run(sim, "variable a equal 4\nprint 'a=$a, 2a=$(2*v_a), \"${a}\"'\n")
    assert sim.screen == ['a=4, 2a=8, "4"']


# ----------------------------------------------------------------------------------------------------------
# include, print

def test_include_relative_to_working_directory(sim, workdir):
    (workdir / "sub").mkdir()
    (workdir / "sub" / "part.in").write_text("variable inc equal 5\nrun $(v_inc*2)\n")
    (workdir / "main.in").write_text("units si\ninclude sub/part.in\nprint ${inc}\n")
    sim.input.file("main.in")
    assert sim.calls == [("units", ["si"]), ("run", ["10"])]
    assert sim.where == ["main.in:1", "sub/part.in:2"]
    assert sim.screen == ["5"]


def test_error_inside_include_names_the_included_file(sim, workdir):
    (workdir / "part.in").write_text("units si\n\nboom\n")
    (workdir / "main.in").write_text("include part.in\n")
    with pytest.raises(DemError) as info:
        sim.input.file("main.in")
    assert str(info.value) == "part.in:3: boom went wrong"


def test_missing_include_file(sim, workdir):
    err = error(sim, "units si\ninclude nothere.in\n")
    assert err.where == "in.test:2"
    assert "cannot open include file 'nothere.in'" in err.message


def test_missing_input_file(sim, workdir):
    with pytest.raises(DemError, match="cannot open input file 'nothere.in'"):
        sim.input.file("nothere.in")


def test_include_loop_is_an_error(sim, workdir):
    (workdir / "self.in").write_text("include self.in\n")
    with pytest.raises(DemError, match=r"scripts nested more than \d+ deep: does 'self.in' include itself\?"):
        sim.input.file("self.in")


def test_print_to_file_and_append(sim, workdir):
    run(sim, "variable a equal 1.5\nprint 'first $a' file out.txt\nprint second append out.txt screen no\n"
             "print third append out.txt\n")
    assert (workdir / "out.txt").read_text() == "first 1.5\nsecond\nthird\n"
    assert sim.screen == ["first 1.5", "third"]
    assert "quote text" in str(error(sim, "print hello world\n"))
    assert "needs a value" in error(sim, "print hi screen\n").message


# ----------------------------------------------------------------------------------------------------------
# label, jump, next

LOOP_INDEX = """variable a index 1 2 3 4 5
label loop
print "pass $a"
next a
jump SELF loop
print done
"""

LOOP_LOOP = """label loop
variable i loop 5
run $i
next i
jump SELF loop
print "after loop: $(step)"
"""


def test_index_loop_runs_five_times(sim, workdir):
    (workdir / "in.loop").write_text(LOOP_INDEX)
    sim.input.file("in.loop")
    assert sim.screen == [f"pass {i}" for i in range(1, 6)] + ["done"]
    assert not sim.input.has_variable("a")


def test_loop_variable_runs_five_times(sim, workdir):
    (workdir / "in.loop").write_text(LOOP_LOOP)
    sim.input.file("in.loop")
    assert sim.calls == [("run", [str(i)]) for i in range(1, 6)]
    assert sim.where == ["in.loop:3"] * 5
    assert sim.screen == ["after loop: 100"]


def test_nested_loops_and_if_break(sim, workdir):
    (workdir / "in.nest").write_text("""variable i loop 3
label outer
variable j loop 2
label inner
print "$i$j"
next j
jump SELF inner
next i
jump SELF outer
variable k loop 100
label again
if "$k >= 3" then "jump SELF end"
next k
jump SELF again
label end
print k=$k
""")
    sim.input.file("in.nest")
    assert sim.screen == ["11", "12", "21", "22", "31", "32", "k=3"]


def test_jump_to_another_file_with_label(sim, workdir):
    (workdir / "other.in").write_text("print skipped\nlabel here\nprint landed\n")
    (workdir / "main.in").write_text("print start\njump other.in here\nprint never\n")
    sim.input.file("main.in")
    assert sim.screen == ["start", "landed"]


def test_jump_from_string_input(sim, workdir):
    (workdir / "other.in").write_text("print there\n")
    run(sim, "jump other.in\nprint never\n")
    assert sim.screen == ["there"]
    err = error(sim, "units si\njump SELF\n")
    assert err.where == "in.test:2" and "jump SELF needs a script file" in err.message


def test_missing_label(sim, workdir):
    (workdir / "in.bad").write_text("units si\njump SELF nowhere\nlabel somewhere\n")
    with pytest.raises(DemError) as info:
        sim.input.file("in.bad")
    assert str(info.value) == "in.bad:2: label 'nowhere' not found in 'in.bad'"


def test_jump_next_argument_errors(sim, workdir):
    assert "expected jump FILE|SELF [LABEL]" in error(sim, "jump\n").message
    assert "expected jump FILE|SELF [LABEL]" in error(sim, "jump a b c\n").message
    assert "cannot open file 'none.in'" in error(sim, "jump none.in\n").message
    assert "expected next NAME" in error(sim, "next\n").message
    assert "undefined variable 'q'" in error(sim, "next q\n").message
    err = error(sim, "variable e equal 1\nnext e\n")
    assert "only index and loop" in err.message and err.where == "in.test:2"
    assert "same style" in error(sim, "variable x index 1 2\nvariable y loop 2\nnext x y\n").message
    assert "expected label NAME" in error(sim, "label\n").message


# ----------------------------------------------------------------------------------------------------------
# if, echo, quit

@pytest.mark.parametrize("value, expected", [(1, ["one", "also"]), (2, ["two"]), (3, ["three"]), (9, ["other"])])
def test_if_elif_else(sim, value, expected):
    run(sim, f'variable v equal {value}\n'
             'if "${v} == 1" then "print one" "print also" elif "$v == 2" "print two" '
             "elif '$v < 4' 'print three' else 'print other'\n")
    assert sim.screen == expected


def test_if_without_else_and_word_comparison(sim):
    run(sim, 'variable s string sphere\nif "${s} == sphere" then "print yes"\n'
             'if "${s} != sphere" then "print no"\nif "step > 50 && ${s} == sphere" then "run 1"\n')
    assert sim.screen == ["yes"]
    assert sim.calls == [("run", ["1"])]


def test_if_compares_quoted_text(sim):
    """'quoted text' holds any characters (a file name with dots and slashes) and compares as a word."""
    run(sim, 'variable f string out/bed.restart\n'
             'if "\'${f}\' == \'none\'" then "print none" else "print file"\n'
             'if "\'${f}\' == \'out/bed.restart\' && 1 < 2" then "print same"\n')
    assert sim.screen == ["file", "same"]
    assert "only for the conditions of `if`" in error(sim, 'variable x equal "\'a\' + 1"\nprint $(v_x)\n').message


def test_if_errors(sim):
    assert "expected if" in error(sim, 'if "1" "print x"\n').message
    assert "no command" in error(sim, 'if "1" then else "print x"\n').message
    assert "second 'else'" in error(sim, 'if "1" then a else b else c\n').message
    assert "not a number" in error(sim, 'if "sphere + 1" then "print x"\n').message
    err = error(sim, 'units si\nif "1" then "boom"\n')
    assert err.where == "in.test:2" and err.message == "boom went wrong"


def test_echo(sim):
    run(sim, "echo both\nvariable a equal 2\nprint $a\necho none\nprint quiet\n")
    assert sim.screen == ["variable a equal 2", "print $a", "print 2", "2", "echo none", "quiet"]
    sim.screen.clear()
    run(sim, "echo log\nunits si\n")
    assert sim.screen == [] and sim.log[-1] == "units si"
    assert "did you mean 'both'" in error(sim, "echo bth\n").message


def test_quit_stops_all_input_quietly(sim, workdir):
    (workdir / "part.in").write_text("print inner\nquit\nprint never\n")
    (workdir / "main.in").write_text("include part.in\nprint never\n")
    sim.input.file("main.in")
    assert sim.screen == ["inner"]
    assert sim.input.quit_status == 0
    run(sim, "quit 2\nprint never\n")
    assert sim.input.quit_status == 2 and sim.screen == ["inner"]


# ----------------------------------------------------------------------------------------------------------
# error reporting

def test_unknown_command_suggests_registered_and_own_words(sim):
    err = error(sim, "units si\nrn 100\n")
    assert str(err) == "in.test:2: unknown command 'rn' (did you mean 'run'?)"
    assert "did you mean 'print'" in error(sim, "prnt hi\n").message
    assert "did you mean 'variable'" in error(sim, "variabel a equal 1\n").message


def test_unterminated_quote(sim):
    err = error(sim, "units si\n\nprint 'oops\n")
    assert err.where == "in.test:3" and "unterminated quote" in err.message
    assert "closing quote must end the word" in error(sim, 'print "a"b\n').message


def test_command_errors_get_location_once(sim):
    err = error(sim, "units si\nboom\n", name="deck.in")
    assert str(err) == "deck.in:2: boom went wrong"
    with pytest.raises(DemError) as info:
        sim.input.one("boom")
    assert info.value.where == "<command>:1"


def test_a_repeated_line_is_counted(tmp_path, capsys):
    """A loop of create_atoms prints `Created 1 particles` on the screen once and then how many more
    times (in.drum's rough wall printed it 234 times before the first thermo line); a different line, or
    the end, brings the count. The log, where the commands are echoed between them, keeps every line."""
    import dem
    log, script = tmp_path / "log.dem", tmp_path / "in.loop"
    script.write_text("""
region box block 0 1 0 1 0 1
create_box 1 box
variable i loop 5
label again
create_atoms 1 single $(0.1*v_i) 0.5 0.5 radius 0.01 density 1000
next i
jump SELF again
print done
create_atoms 1 single 0.9 0.9 0.9 radius 0.01 density 1000
create_atoms 1 single 0.9 0.1 0.9 radius 0.01 density 1000
""")
    with dem.Simulation(screen=True, log=str(log)) as sim:
        sim.file(str(script))
    assert capsys.readouterr().out.splitlines()[-5:] == [
        "Created 1 particles", "(the line above 4 more times)", "done", "Created 1 particles",
        "(the line above 1 more time)"]
    assert log.read_text().count("Created 1 particles") == 7
