"""Porting from LIGGGHTS: the LIGGGHTS tutorial meshGran (tests/data/liggghts, LIGGGHTS-PUBLIC 3.8.0, GPL)
read by dem gets, on every line dem cannot take, the answer of dem/foreign_names.py; the port written by
following those answers alone (in.meshGran.dem) changes 0 lines that no answer asked for, and runs. The
tutorials packing and chute_wear get their answers too. The table cannot shadow a dem style, a misspelt
name still gets a did-you-mean, and docs/migration.md shows the table as it is."""
import difflib
import os
import re
import shutil
import subprocess
import sys
import time

import pytest

from dem import foreign_names
from dem.errors import DemError
from dem.input import split_words, strip_comment
from dem.registry import KINDS, default_registry
from dem.sim import Sim

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "liggghts")
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INTERPRETER = ("variable", "include", "print", "label", "jump", "next", "if", "echo", "quit")


def commands(text):
    """[(first line number, command text)] of a script: comments cut, `&` continuations joined."""
    out, lines, i = [], text.splitlines(), 0
    while i < len(lines):
        start, words = i + 1, lines[i]
        while words.rstrip().endswith("&") and i + 1 < len(lines):
            i += 1
            words = words.rstrip()[:-1] + " " + lines[i]
        i += 1
        words = " ".join(strip_comment(words).split())
        if words:
            out.append((start, words))
    return out


def name_of(command):
    """(kind, name, args) of a command as the registry looks it up."""
    words = split_words(command)
    at = {"fix": 3, "compute": 3, "dump": 3, "region": 2, "pair_style": 1}.get(words[0])
    if at is None or len(words) <= at:
        return "command", words[0], words[1:]
    kind = {"fix": "fix", "compute": "compute", "dump": "dump", "region": "region", "pair_style": "pair"}[words[0]]
    return kind, words[at], words[at + 1:]


def scan(path):
    """Read a script with dem, a line at a time as a user would: run it, take the error, comment out its
    command, run again. [(line, message)] of every error. Runs become `run 0`: this reads the words, the
    physics is the port's test."""
    lines = open(path).read().splitlines()
    lines = [re.sub(r"^(\s*run\s+)\S+", r"\g<1>0", line) for line in lines]
    errors = []
    for _ in range(len(lines)):
        sim = Sim(screen=False)
        try:
            sim.input.lines("\n".join(lines), name="in.x")
            return errors
        except DemError as err:
            assert err.where and err.where.startswith("in.x:"), str(err)
            lineno = int(err.where.split(":")[1])
            errors.append((lineno, err.message))
            i = lineno - 1
            while True:
                more = lines[i].rstrip().endswith("&")
                lines[i] = "# " + lines[i]
                i += 1
                if not more:
                    break
        finally:
            sim.close()
    raise AssertionError("the scan did not end")


def answers_of(path):
    """Scan a script: ({line: answer text} of the table's names, [(line, message)] of the other errors).
    Every line with a table name must have failed with exactly its row's answer."""
    errors = dict(scan(path))
    answered, others = {}, []
    for lineno, command in commands(open(path).read()):
        row = foreign_names.answer(*name_of(command))
        if row is not None:
            assert lineno in errors, f"line {lineno} ({command}) got no error"
            assert row.text in errors[lineno], (lineno, errors[lineno])
            assert "docs/migration.md" in errors[lineno]
            answered[lineno] = row.text
        elif lineno in errors:
            others.append((lineno, errors.pop(lineno)))
    return answered, others


def named(word, texts):
    """Whether one of the answers names this word (a command or style) as a whole word."""
    pattern = re.compile(rf"(?<![\w/]){re.escape(word)}(?![\w/])")
    return any(pattern.search(text) for text in texts)


def key_word(command):
    """The word an answer would name for this line: the style of fix/compute/dump/region/pair_style lines,
    else the command."""
    kind, name, _ = name_of(command)
    return name if kind != "command" else command.split()[0]


def test_tutorial_meshgran_every_liggghts_line_gets_its_answer_and_the_port_needs_nothing_more():
    """17 lines of meshGran get the table's answer; the other 4 errors come from lines the user has not yet
    fixed (pair_coeff before the pair style; compute 1 and fix ins not defined yet, used by thermo_style,
    run and unfix), lines the port keeps or an answer names. The port: every original line it changes or drops, and every line it adds, is a line that
    got an answer or a line an answer names (pair_coeff, thermo_style, a block region, fix wall/mesh, fix
    insert ...). Manual changes beyond the answers: 0."""
    original = os.path.join(DATA, "in.meshGran")
    answered, others = answers_of(original)
    assert len(answered) == 17
    texts = list(answered.values())
    assert sorted(message for _, message in others) == [
        "pair_coeff before pair_style", "unknown compute ID '1'", "unknown compute ID '1'",
        "unknown fix ID 'ins'"]

    old = commands(open(original).read())
    new = commands(open(os.path.join(DATA, "in.meshGran.dem")).read())
    manual = []
    match = difflib.SequenceMatcher(a=[c for _, c in old], b=[c for _, c in new], autojunk=False)
    for tag, a0, a1, b0, b1 in match.get_opcodes():
        if tag == "equal":
            continue
        for lineno, command in old[a0:a1]:
            if lineno not in answered and not named(key_word(command), texts):
                manual.append(command)
        for _, command in new[b0:b1]:
            if not named(key_word(command), texts):
                manual.append(command)
    assert manual == []


def test_port_of_meshgran_runs_and_fills_the_chute(tmp_path, monkeypatch):
    """The port as written, its runs cut to 5000 + 500 steps: a few hundred spheres streamed in, falling
    onto the CAD chute of fix wall/mesh (the mesh read, scaled by 0.001 and turned by -90 degrees)."""
    shutil.copytree(DATA, tmp_path / "case")
    monkeypatch.chdir(tmp_path / "case")
    text = open("in.meshGran.dem").read()
    text = re.sub(r"^run(\s+)10000 upto", r"run\g<1>5000 upto", text, flags=re.M)
    text = re.sub(r"^run(\s+)40000 upto", r"run\g<1>5500 upto", text, flags=re.M)
    assert text.count("upto") == 2
    started = time.perf_counter()
    with Sim(screen=False) as sim:
        sim.input.lines(text, name="in.meshGran.dem")
        assert sim.update.ntimestep == 5500
        assert 200 <= sim.thermo_keyword("atoms") <= 300
        assert sim.thermo_keyword("f_cad[contacts]") > 0      # the stream has reached the chute
    assert time.perf_counter() - started < 30
    assert os.path.exists("post/meshGran_0.vtu")


@pytest.mark.parametrize("script, unanswered", [
    # packing grows its particles with an atom-style variable (LAMMPS), which dem does not have
    ("in.packing", ["pair_coeff before pair_style", "unknown compute ID '1'", "unknown compute ID '1'",
                    "unknown compute ID '1'", "unknown fix ID 'grow'", "unknown fix ID 'ins'",
                    "unknown variable style 'atom'"]),
    ("in.chute_wear", ["pair_coeff before pair_style", "unknown compute ID '1'", "unknown compute ID '1'",
                       "unknown fix ID 'ins'"]),
])
def test_other_tutorials_get_their_answers(script, unanswered):
    answered, others = answers_of(os.path.join(DATA, script))
    assert answered
    assert sorted(message for _, message in others) == unanswered


# -- the table itself ---------------------------------------------------------------------------------------

def test_no_table_name_is_a_dem_name():
    """An answer for a name dem has would hide dem's own style: none may exist."""
    styles = default_registry().styles
    for kind, name, *_ in foreign_names.ROWS:
        assert kind in KINDS
        assert name not in styles[kind], f"{kind} {name} is dem's own"
        assert kind != "command" or name not in INTERPRETER


def test_every_name_has_a_general_row_and_one_line_answers():
    keys = [(kind, name, when) for kind, name, when, *_ in foreign_names.ROWS]
    assert len(keys) == len(set(keys))
    for kind, name, when, origin, text in foreign_names.ROWS:
        assert (kind, name, None) in keys
        assert "\n" not in text and len(text) < 400
        assert origin in (foreign_names.LIGGGHTS, foreign_names.LAMMPS, foreign_names.BOTH)


def test_styles_the_answers_name_are_dem_styles():
    """An answer that sends the user to a style dem does not have would be a lie: every `fix ID group X`,
    `compute ID group X`, `dump ID group X`, `pair_style X` it names is installed."""
    styles = default_registry().styles
    patterns = {"fix": r"fix ID group ([\w/]+)", "compute": r"compute ID group ([\w/]+)",
                "dump": r"dump ID group ([\w/]+)", "pair": r"pair_style ([\w/]+)"}
    seen = 0
    for *_, text in foreign_names.ROWS:
        for kind, pattern in patterns.items():
            for style in re.findall(pattern, text):
                seen += 1
                assert style in styles[kind], (style, text)
    assert seen > 40


def test_migration_page_shows_the_table():
    page = open(os.path.join(ROOT, "docs", "migration.md")).read()
    assert foreign_names.markdown_table() in page, "run python tools/make_docs.py"
    assert "docs/migration.md" in open(os.path.join(ROOT, "README.md")).read()


# -- hostile cases ------------------------------------------------------------------------------------------

HEAD = "units si\nregion box block 0 0.01 0 0.01 0 0.01\ncreate_box 1 box\n"


def error_of(text):
    with Sim(screen=False) as sim:
        with pytest.raises(DemError) as info:
            sim.input.lines(text, name="in.t")
    return str(info.value)


@pytest.mark.parametrize("line, expected", [
    ("communicat single vel yes", "unknown command 'communicat' (did you mean LIGGGHTS 'communicate'? "
                                  "in dem: dem does not need this line"),
    ("fix m all mesh/surfce file a.stl", "unknown fix style 'mesh/surfce' (did you mean LIGGGHTS "
                                         "'mesh/surface'? in dem: LIGGGHTS's fix mesh/surface + fix wall/gran"),
    ("fix w all wall/plan zplane 0 NULL", "unknown fix style 'wall/plan' (did you mean 'wall/plane'?)"),
    ("fix g all gravty 9.81", "unknown fix style 'gravty' (did you mean 'gravity'?)"),
    ("compute e all erotate/sphre", "(did you mean LAMMPS and LIGGGHTS 'erotate/sphere'? in dem: compute ID "
                                    "group erotate"),
    ("compute e all erotat", "(did you mean 'erotate'?)"),
    ("fix x all nothing/like/it", "unknown fix style 'nothing/like/it'"),
])
def test_misspelt_names_get_did_you_mean(line, expected):
    """A misspelt table name is not answered as if it were right, but pointed at; a misspelt dem name still
    gets dem's name (a table name never wins over a closer dem one)."""
    message = error_of(HEAD + line + "\n")
    assert message.startswith("in.t:4: ")
    assert expected in message


def test_the_line_chooses_the_sharper_answer():
    hooke = error_of(HEAD + "pair_style gran model hooke tangential history\n")
    hertz = error_of(HEAD + "pair_style gran model hertz tangential history\n")
    other = error_of(HEAD + "pair_style gran model hooke/hysteresis\n")
    assert "kn KN en EN mu MU ks KS" in hooke and "dem-hooke-from-hertz" in hooke
    assert "model hertz E 5e6" in hertz and "dem-hooke-from-hertz" not in hertz
    assert other.endswith(foreign_names.answer("pair", "gran").text + " [docs/migration.md]")
    mesh = error_of(HEAD + "fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes cad\n")
    plane = error_of(HEAD + "fix w all wall/gran model hertz tangential history primitive type 1 zplane 0\n")
    assert "wall/mesh file FILE" in mesh and "xplane -0.05 NULL" in plane


def test_cli_answer_names_the_line_without_traceback(tmp_path):
    (tmp_path / "in.t").write_text(HEAD + "communicate single vel yes\n")
    out = subprocess.run([sys.executable, "-m", "dem", "-in", "in.t", "-log", "none"], cwd=tmp_path,
                         capture_output=True, text=True)
    assert out.returncode != 0
    assert "in.t:4: unknown command 'communicate' (LIGGGHTS): dem does not need this line" in out.stderr
    assert "Traceback" not in out.stderr
