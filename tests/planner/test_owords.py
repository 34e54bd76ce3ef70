"""The O-word language (subroutines, if/elseif/else, while, do-while, repeat, break, continue,
return values, subroutine files, parameter scopes) read as LinuxCNC 2.9 reads it: LinuxCNC's own
interpreter tests (tests/data/linuxcnc_interp) message by message and move by move, the
refusals with file:line:col, and mutated programs that may only fail with ProgramError."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import planner.gcode.flow as flow
from planner.core.errors import ProgramError
from planner.core.machine import AxisSpec, MachineSpec
from planner.core.program import Coolant, CoolantSwitch, EventKind, Program
from planner.gcode.canon import canon_records
from planner.gcode.interpreter import parse_program
from tools.linuxcnc_oracle import RS274, canon_calls, motion_alike, refused_alike

DATA = Path(__file__).resolve().parents[1] / "data" / "linuxcnc_interp"
_MESSAGE = re.compile(r'^\s*N\.+\s+MESSAGE\("(.*)"\)\s*$')
_MOVE = re.compile(r"^\s*N\.+\s+STRAIGHT_(TRAVERSE|FEED)\((.*)\)\s*$")


def messages(program: Program) -> list[str]:
    return [e.message for e in program.events if e.kind is EventKind.MESSAGE]


def read(text: str, **kw: object) -> Program:
    return parse_program(text, name="t.ngc", **kw)


# ---------------------------------------------------------------------- LinuxCNC's own tests
@pytest.mark.parametrize("name", ["do-while-break", "oword-bug315", "return-value"])
def test_linuxcnc_debug_messages_in_the_same_order(name: str) -> None:
    """Control flow seen through (DEBUG,...) messages, parameters shown as LinuxCNC shows them."""
    folder = DATA / name
    want = [m.group(1) for line in (folder / "expected").read_text().splitlines()
            if (m := _MESSAGE.match(line))]
    assert want, "the reference has messages"
    got = messages(parse_program((folder / "test.ngc").read_text(), name="test.ngc"))
    assert got == want


@pytest.mark.parametrize("name, files", [("sub-call-from-sub", "subs"), ("subs-follow-main", None)])
def test_linuxcnc_subroutine_files_and_subs_after_the_main_program(name: str, files: str | None) -> None:
    """(PRINT,...) lines; LinuxCNC's test script drops the first word of each."""
    folder = DATA / name
    canon = re.compile(r"^\s*(\d+\s+)?N\.")
    want = [line.strip() for line in (folder / "expected").read_text().splitlines()
            if line.strip() and not canon.match(line)]
    dirs = (str(folder / files),) if files else ()
    got = messages(parse_program((folder / "test.ngc").read_text(), name="test.ngc", subroutine_dirs=dirs))
    assert [" ".join(m.split()[1:]) for m in got] == want


def _linuxcnc_moves(expected: Path, inch: bool) -> list[tuple[str, tuple[float, ...]]]:
    scale = 25.4 if inch else 1.0
    out = []
    for line in expected.read_text().splitlines():
        m = _MOVE.match(line)
        if m:
            values = [float(v) for v in m.group(2).split(",")[:3]]
            out.append((m.group(1).lower(), tuple(round(v * scale, 2) for v in values)))
    return out


def _moves(program: Program) -> list[tuple[str, tuple[float, ...]]]:
    return [(r["call"][9:], tuple(round(v, 2) for v in r["args"][:3])) for r in canon_records(program)]


def test_linuxcnc_flowsnake_recursive_subroutines_move_for_move() -> None:
    """Three recursion levels of a named subroutine with local named parameters: 192 moves."""
    folder = DATA / "flowsnake"
    program = parse_program((folder / "flowsnake.ngc").read_text(), name="flowsnake.ngc")
    want = _linuxcnc_moves(folder / "expected", inch=False)
    assert len(want) > 150 and _moves(program) == want


def test_linuxcnc_parameters_set_by_expression_numbers() -> None:
    folder = DATA / "namedparam-bug424"
    program = parse_program((folder / "test.ngc").read_text(), name="test.ngc")
    assert _moves(program) == _linuxcnc_moves(folder / "expected", inch=True)


def test_linuxcnc_exists_of_named_numbered_and_indirect_parameters() -> None:
    folder = DATA / "exists"
    axes = tuple(AxisSpec(n, drive_position=i) for i, n in enumerate("XYZ"))
    spec = MachineSpec("XYZA", axes + (AxisSpec("A", rotary=True, drive_position=3),))
    program = parse_program((folder / "test.ngc").read_text(), name="test.ngc", machine=spec)
    assert _moves(program) == _linuxcnc_moves(folder / "expected", inch=False)


def test_linuxcnc_nested_sub_definition_in_a_file_is_an_error_naming_that_file() -> None:
    folder = DATA / "nested-sub-error"
    with pytest.raises(ProgramError) as exc:
        parse_program((folder / "test.ngc").read_text(), name="test.ngc",
                      subroutine_dirs=(str(folder / "subs"),))
    (err,) = exc.value.errors
    assert err.line == 2 and "nested.ngc:2:1" in err.message and "sub inside another sub" in err.message


# ---------------------------------------------------------------------- semantics
def test_repeat_continue_and_parameter_scopes() -> None:
    p = read("""G21 G90 F100
#<_g> = 5
#<local> = 7
o10 sub
  (debug,in sub: g=#<_g> local=#<local> arg=#1)
  #<local> = 1
  #<_g> = [#<_g> + 1]
o10 endsub
#1 = 42
o10 call [3]
(debug,after: g=#<_g> local=#<local> #1)
#<k> = 0
o20 repeat [4]
  #<k> = [#<k> + 1]
  o30 if [#<k> EQ 2]
    o20 continue
  o30 endif
  G1 X#<k>
o20 endrepeat
M2
""")
    assert messages(p) == ["in sub: g=5.000000 local=###### arg=3.000000",
                           "after: g=6.000000 local=7.000000 42.000000"]
    assert [m.end[0] for m in p.moves] == [1.0, 3.0, 4.0]


def test_moves_of_a_subroutine_file_carry_the_line_of_the_call(tmp_path: Path) -> None:
    (tmp_path / "hole.ngc").write_text("o<hole> sub\nG0 X#1 Y#2\nG1 Z-1\nG0 Z1\no<hole> endsub\nM2\n")
    p = read("G21 G90 F100\nG0 Z1\no<hole> call [5] [6]\no<hole> call [7] [8]\nM2\n",
             subroutine_dirs=(str(tmp_path),))
    assert [m.line for m in p.moves] == [2, 3, 3, 3, 4, 4, 4]
    np.testing.assert_allclose(p.moves[-1].end, [7, 8, 1])


def test_an_error_in_a_subroutine_file_names_that_file_and_its_line(tmp_path: Path) -> None:
    (tmp_path / "bad.ngc").write_text("o<bad> sub\nG1 X1 Q3\no<bad> endsub\n")
    with pytest.raises(ProgramError) as exc:
        read("G21 F100\no<bad> call\n", subroutine_dirs=(str(tmp_path),))
    (err,) = exc.value.errors
    assert (err.file, err.line) == (str(tmp_path / "bad.ngc"), 2) and "Q word" in err.message


@pytest.mark.parametrize("text, line, words", [
    ("o1 if [1]\nG0 X1\n", 1, "o1 if without its o1 endif"),
    ("o1 while [1]\no2 endwhile\n", 2, "o2 endwhile without o2 while"),
    ("o1 break\n", 1, "o1 break outside a loop labelled o1"),
    ("o1 return\n", 1, "return outside a subroutine"),
    ("o1 sub\no1 endsub\no1 sub\no1 endsub\n", 3, "o1 sub is defined twice"),
    ("o1 if [1]\no1 else\no1 elseif [1]\no1 endif\n", 3, "elseif after o1 else"),
    ("o7 call\n", 1, "no o7 sub in this program"),
    ("o<nothere> call\n", 1, "no nothere.ngc in the subroutine folders (no subroutine folder is configured)"),
    ("o1 if [1 +]\no1 endif\n", 1, "expected a number"),
    ("o1 while 1\no1 endwhile\n", 1, "expected '['"),
    ("o1 sub\no1 call\no1 endsub\no1 call\n", 2, "nested deeper than 50"),
    ("o1 repeat [2] [3]\no1 endrepeat\n", 1, "needs one count in brackets"),
    # Fanuc-style subprograms
    ("G21 F100\nM98\nM2\n", 2, "M98 needs a P word"),
    ("G21 F100\nM98 P7\nM2\n", 2, "M98 P7: no O7 in this program"),
    ("G21 F100\nM98 P1 L1.5\nM2\nO1\nM99\n", 2, "M98 L1.5"),
    ("G21 F100\nM98 P1 Q2\nM2\nO1\nM99\n", 2, "M98 takes only P and L words, not Q"),
    ("G21 F100\no1 sub\nM99\no1 endsub\no1 call\nM2\n", 3, "M99 inside an O-word subroutine"),
    # a count or a number that is infinite, or too large for a whole number, is refused at its word
    ("o1 repeat [10**308*10]\no1 endrepeat\n", 1, "o1 repeat [inf]: the count is out of range"),
    ("o1 repeat [10**10]\no1 endrepeat\n", 1, "the count is out of range (|count| < 1e9)"),
    ("o1 sub\no1 endsub\no[10**308*10] call\n", 3, "the subroutine number inf is not a whole number"),
    ("G21 F100\nM98 P[10**308*10]\nM2\n", 2, "M98 Pinf: a subprogram number is a whole number from 0"),
    ("G21 F100\nM98 P1 L[10**308*10]\nM2\nO1\nM99\n", 2, "M98 Linf: the runs of a subprogram"),
])
def test_refusals_name_the_line_and_what_is_wrong(text: str, line: int, words: str) -> None:
    with pytest.raises(ProgramError) as exc:
        read(text)
    (err,) = exc.value.errors
    assert err.line == line and words in err.message, err


def test_an_endless_loop_is_stopped_with_a_clear_error(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(flow, "MAX_EXECUTED", 10_000)
    with pytest.raises(ProgramError) as exc:
        read("#<a> = 0\no1 while [1]\n#<a> = [#<a> + 1]\no1 endwhile\n")
    assert "more than 10,000 blocks run (an endless loop?)" in exc.value.errors[0].message


def test_programs_without_o_words_take_the_plain_path_and_read_the_same() -> None:
    text = "G21 G90 F100\nG1 X1 Y2\nG2 X3 Y2 R1\nO0001\nM2\n"
    plain = read(text)
    with_sub = read("o99 sub\no99 endsub\n" + text)
    assert _moves(plain) == _moves(with_sub) and len(plain.moves) == 2


# ---------------------------------------------------------------------- fuzz
_PROGRAMS = [p.read_text() for p in sorted(DATA.glob("*/test.ngc")) + [DATA / "flowsnake" / "flowsnake.ngc"]
             if "o" in p.read_text().lower()]


@settings(max_examples=120, deadline=None)
@given(which=st.integers(0, len(_PROGRAMS) - 1),
       edits=st.lists(st.tuples(st.sampled_from(["drop", "dup", "relabel", "swap"]), st.integers(0, 200)),
                      min_size=1, max_size=3))
def test_mutated_o_word_programs_fail_only_with_program_errors(which: int,
                                                                edits: list[tuple[str, int]]) -> None:
    lines = _PROGRAMS[which].splitlines()
    for op, k in edits:
        if not lines:
            break
        k %= len(lines)
        if op == "drop":
            del lines[k]
        elif op == "dup":
            lines.insert(k, lines[k])
        elif op == "swap" and k + 1 < len(lines):
            lines[k], lines[k + 1] = lines[k + 1], lines[k]
        else:
            lines[k] = re.sub(r"o(\d+)", lambda m: f"o{int(m.group(1)) + 1}", lines[k], count=1, flags=re.I)
    try:
        program = read("\n".join(lines), max_errors=5)
    except ProgramError as exc:
        assert all(e.line >= 1 and e.col >= 1 for e in exc.errors)
        return
    assert all(np.isfinite(m.end).all() for m in program.moves)


def test_subroutine_folders_of_the_machine_configuration(tmp_path: Path) -> None:
    """[planner] subroutine_dirs, relative to the configuration file: cnc-plan and the panel's
    reading (through the machine) find o<name> there; saving the configuration keeps them."""
    import subprocess
    import sys

    from app.machine.config import load_config, save_config
    from resources import shipped_machine

    (tmp_path / "subs").mkdir()
    (tmp_path / "subs" / "square.ngc").write_text(
        "o<square> sub\nG1 X#1 Y0\nG1 Y#1\nG1 X0\nG1 Y0\no<square> endsub\n")
    text = shipped_machine("xyz_mill").read_text(encoding="utf-8")
    text = text.replace('interpolation = "exact"', 'interpolation = "exact"\nsubroutine_dirs = ["subs"]')
    assert 'subroutine_dirs = ["subs"]' in text
    config = tmp_path / "machine.toml"
    config.write_text(text, encoding="utf-8")
    program = tmp_path / "p.ngc"
    program.write_text("G21 G90 F600\no<square> call [5]\nM2\n")
    from planner.core.machine import load_machine

    machine = load_machine(config)
    assert machine.subroutine_paths() == (str(tmp_path / "subs"),)
    assert len(parse_program(program.read_text(), machine=machine).moves) == 4     # the square
    run = subprocess.run([sys.executable, "-m", "cli.plan", str(program), "--config", str(config), "--json"],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    saved = save_config(load_config(config), tmp_path / "saved.toml")
    assert saved.machine.planner.subroutine_dirs == ("subs",)
    assert 'subroutine_dirs = ["subs"]' in (tmp_path / "saved.toml").read_text()


@pytest.mark.parametrize("name", ["m70m72-restore.0", "m73-flood-mist-restore.0", "m73autorestore.0"])
def test_linuxcnc_m70_m73_modal_state_save_and_restore(name: str) -> None:
    """LinuxCNC's tests/m70-m73: the moves and the (DEBUG,...) messages after M70/M72/M73."""
    folder = DATA / "m70-m73" / name
    program = parse_program((folder / "test.ngc").read_text(), name="test.ngc")
    want_messages = [m.group(1) for line in (folder / "expected").read_text().splitlines()
                     if (m := _MESSAGE.match(line))]
    assert messages(program) == want_messages
    inch = "USE_LENGTH_UNITS(CANON_UNITS_INCHES)" in (folder / "expected").read_text().split("MESSAGE")[0]
    # LinuxCNC writes zero-length moves (a G53 G0 X0 Y0 Z0 at the origin); a Program has none
    want, last = [], (0.0, 0.0, 0.0)
    for kind, end in _linuxcnc_moves(folder / "expected", inch=inch):
        if end != last:
            want.append((kind, end))
        last = end
    assert _moves(program) == want
    # coolant: LinuxCNC's MIST_ON / FLOOD_ON / *_OFF before the program end, as the events' 1 / 2 / 0
    lc_coolant: list[float] = []
    text = (folder / "expected").read_text()
    # M2's reset (from its SET_FEED_MODE on) switches the coolant off; programs ending with '%' have none
    before_end = text[:text.rindex("SET_FEED_MODE(0, 0)")] if "PROGRAM_END" in text else text
    for line in before_end.splitlines():
        call = line.split()[-1] if line.strip() else ""
        value = {"MIST_ON()": 1.0, "FLOOD_ON()": 2.0, "MIST_OFF()": 0.0, "FLOOD_OFF()": 0.0}.get(call)
        if value is not None and not (value == 0.0 and lc_coolant[-1:] == [0.0]):
            lc_coolant.append(value)
    as_number = {Coolant.MIST_ON: 1.0, Coolant.FLOOD_ON: 2.0, Coolant.ALL_OFF: 0.0}
    assert [as_number[e.payload_as(CoolantSwitch).switch] for e in program.events
            if e.kind is EventKind.COOLANT] == lc_coolant
    if name == "m73-flood-mist-restore.0":      # this one is about coolant only
        assert lc_coolant == [1.0, 2.0, 0.0, 1.0, 2.0]


def test_m72_without_a_saved_state_and_m73_in_the_program_are_refused() -> None:
    with pytest.raises(ProgramError, match="M72: no modal state saved"):
        read("M72\n")
    with pytest.raises(ProgramError, match="M73 saves the state for the return of a subroutine"):
        read("M73\n")


def test_a_reused_loop_label_is_refused_as_linuxcnc_does() -> None:
    """LinuxCNC keeps one place per label for subs, do, repeat and while: a second repeat with
    the same label stops it with "duplicate O-word label"."""
    text = ("G21 F600\no200 repeat [2]\nG91 G1 X1\nG90\no200 endrepeat\n"
            "o200 repeat [3]\nG91 G1 Y1\nG90\no200 endrepeat\nM2\n")
    with pytest.raises(ProgramError) as ei:
        parse_program(text)
    (err,) = ei.value.errors
    assert err.line == 6 and "duplicate O-word label" in err.message and "line 2" in err.message
    # LinuxCNC 2.9 holds if labels too; a do closed by its while is one loop
    with pytest.raises(ProgramError, match="label: o1 if uses the label of the if at line 2"):
        parse_program("G21 F600\no1 if [1]\nG1 X1\no1 endif\no1 if [1]\nG1 X2\no1 endif\nM2\n")
    with pytest.raises(ProgramError, match="duplicate O-word label: o1 while"):
        parse_program("G21 F600\n#1=0\no1 if [1]\nG1 X1\no1 endif\no1 while [#1 LT 1]\n#1=1\n"
                      "o1 endwhile\nM2\n")
    assert parse_program("G21 F600\no2 do\nG91 G1 X1\nG90\no2 while [0]\nM2\n").moves
    # a subroutine called twice runs its own if twice: one place, no duplicate
    assert len(parse_program("o5 sub\no6 if [1]\nG91 G1 X1\nG90\no6 endif\no5 endsub\nG21 F600\n"
                             "o5 call\no5 call\nM2\n").moves) == 2


def test_a_label_is_held_per_subroutine_and_only_once_run_as_linuxcnc_holds_it() -> None:
    """LinuxCNC qualifies a local label by the subroutine it is written in and takes its place
    when the statement first runs (LinuxCNC's own lathe_g7x_face_boring.ngc and
    qt_auto_probe_tool.ngc reuse labels so): a repeat inside o100 and a sub o101 do not clash,
    nor do two ifs in branches of which one runs; the same if label run twice at two places
    does (rs274: "5: duplicate O-word label")."""
    other_sub = ("G21 F600\no100 sub\no101 repeat [2]\nG91 G1 X1\nG90\no101 endrepeat\no100 endsub\n"
                 "o101 sub\nG1 Y5\no101 endsub\no100 call\no101 call\nM2\n")
    assert [tuple(m.end) for m in read(other_sub).moves] == [(1, 0, 0), (2, 0, 0), (2, 5, 0)]
    branches = ("G21 F600\n#1=1\no1 if [#1]\no2 if [1]\nG1 X1\no2 endif\no1 else\no2 if [1]\nG1 X2\n"
                "o2 endif\no1 endif\nM2\n")
    assert [tuple(m.end) for m in read(branches).moves] == [(1, 0, 0)]
    # the same if label in two subroutines: each sub's own
    two_subs = ("G21 F600\no1 sub\no9 if [1]\nG1 X1\no9 endif\no1 endsub\n"
                "o2 sub\no9 if [1]\nG1 X2\no9 endif\no2 endsub\no1 call\no2 call\nM2\n")
    assert [m.end[0] for m in read(two_subs).moves] == [1, 2]
    both_run = ("G21 F600\no1 if [1]\no2 if [1]\nG1 X1\no2 endif\no1 endif\no3 if [1]\no2 if [1]\nG1 X2\n"
                "o2 endif\no3 endif\nM2\n")
    with pytest.raises(ProgramError) as ei:
        read(both_run)
    (err,) = ei.value.errors
    assert (err.line, err.col) == (8, 1) and "o2 if uses the label of the if at line 3" in err.message


@settings(max_examples=200, deadline=None)
@given(st.lists(st.sampled_from(["G1 X1", "(o100 sub)", "o100 sub", "  O<x> call", "N10 o2 while [1]",
                                 "/o3 if [1]", "X0 Y1 ; o5 endsub", "", "o", "O12", "%"]), max_size=30),
       st.integers(1, 40))
def test_control_flow_is_found_whichever_piece_holds_it(lines, piece_chars):
    """The look for O-word statements, piece by piece, finds what one search of the whole text
    finds (a statement never spans two pieces: pieces end at line ends)."""
    from planner.gcode.oword import _ANY_RE, has_control_flow

    text = "\n".join(lines)
    assert has_control_flow(text, piece_chars) == (_ANY_RE.search(text) is not None)


def test_fanuc_subprograms_run_as_linuxcnc_runs_them() -> None:
    """M98 P<n> L<count> runs the block from the line "O<n>" to its M99 count times (LinuxCNC
    2.9 and its rs274: CAM posts for Mach3 and Fanuc write them); it takes no arguments and
    works on the caller's parameters; L0 runs it not at all; an M99 in the main program ends
    it as M02 does."""
    text = "G21 F100\nM98 P100 L2\nG1 X5\nM98 P100 L0\nM98 P0100\nM2\nO100 (sub)\nG91 G1 Y1\nG90\nM99\n"
    p = read(text)
    assert [tuple(m.end[:2]) for m in p.moves] == [(0, 1), (0, 2), (5, 2), (5, 3)]
    assert [m.line for m in p.moves] == [8, 8, 3, 8]          # the subprogram's own line
    shared = read("G21 F100\n#1=3\nM98 P1\nG1 X#1\nM2\nO1\n#1=4\nM99\n")
    assert [m.end[0] for m in shared.moves] == [4]
    ends = read("G21 F100\nG1 X1\nO100\nG1 Y1\nM99\nG1 Z1\nM2\n")
    assert [tuple(m.end) for m in ends.moves] == [(1, 0, 0), (1, 1, 0)]
    assert [e.line for e in ends.events if e.kind is EventKind.END] == [5]
    # a Fanuc program number or name alone at the top is no call and changes nothing (LinuxCNC's
    # m98m99/13-named-program)
    assert len(read("O0001 (PART)\nG21 G1 X1 F100\nM30\n").moves) == 1
    assert len(read("%\nO<MyProgram>\nG21 G1 X1 F100\nM30\n%\n").moves) == 1


def test_a_subroutine_number_from_a_parameter_or_an_expression() -> None:
    """O#<name> call and O[expression] call, as LinuxCNC 2.9 reads them (its
    oword-bug315-p2 and m98m99/14 tests): the subroutine of the number they come to."""
    text = ("G21 F100\no1 sub\nG1 X1\no1 endsub\no2 sub\nG1 X2\no2 endsub\n#<sub>=2\no#<sub> call\n"
            "#5=1\no#5 call\no[#<sub> * 1] call\nM2\n")
    assert [m.end[0] for m in read(text).moves] == [2, 1, 2]
    with pytest.raises(ProgramError, match="not a whole number"):
        read("G21 F100\no2 sub\nG1 X2\no2 endsub\no[1.5] call\nM2\n")


M98_CASES = ["01-basics", "02-variables", "05-M98-loops", "07-nested-subs", "08-sub-follows-main",
             "10-M98-P001", "14-o-expression-call"]


@pytest.mark.parametrize("name", M98_CASES)
def test_linuxcnc_m98_m99_tests_move_for_move_and_print_for_print(name: str) -> None:
    """LinuxCNC's own tests of Fanuc-style subprograms (tests/interp/m98m99): the moves and
    the (PRINT,...) lines of its expected output, in order (most of its scripts drop each line's
    first word, the call counter; a move to where the tool is, which LinuxCNC writes and a
    Program does not hold, is left out)."""
    folder = DATA / "m98m99" / name
    lines = (folder / "expected").read_text().splitlines()
    counted = bool(re.match(r"^\s*\d+\s+N\.", lines[0]))   # the script kept the counter
    canon = re.compile(r"^\s*(\d+\s+)?N\.")
    want_prints = [line.strip() for line in lines if line.strip() and not canon.match(line)]
    want_moves, here = [], (0.0, 0.0, 0.0)
    for call, args, scale in canon_calls("\n".join(re.sub(r"^\s*\d+\s+", "", x) for x in lines)):
        if call in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED"):
            end = tuple(round(float(v) * scale, 3) for v in args[:3])
            if end != here:
                want_moves.append((call.lower()[9:], end))
            here = end
    got_prints, got_moves = [], []
    for path in sorted(folder.glob("*.ngc")):
        program = parse_program(path.read_text(), name=path.name)
        got_prints += [m if counted else " ".join(m.split()[1:]) for m in messages(program)]
        got_moves += [(r["call"][9:], tuple(round(v, 3) for v in r["args"][:3]))
                      for r in canon_records(program)]
    assert len(want_prints) + len(want_moves) > 0, "the reference shows something"
    assert got_prints == want_prints
    assert got_moves == want_moves


def test_an_abort_comment_ends_the_program_with_its_text() -> None:
    """LinuxCNC 2.9's (ABORT,...) comment (its tests/interp/abort-hot-comment): the program stops
    there with the text, parameters shown as DEBUG shows them, as the error at its line; one
    in a branch not taken does nothing."""
    text = ("G21 F100\n#42=0\n#<named>=4711\no100 while [#42 lt 100]\no200 if [#42 eq 20]\n"
            "  (abort, MixedCase param42=#42 named=#<named>)\no200 endif\nG1 X[#42]\n#42=[#42+1]\n"
            "o100 endwhile\nM2\n")
    with pytest.raises(ProgramError) as ei:
        read(text)
    (err,) = ei.value.errors
    assert err.line == 6 and err.message.endswith("MixedCase param42=20.000000 named=4711.000000")
    assert len(read(text.replace("eq 20", "eq 200")).moves) == 99      # X0 is where it stands


def test_what_follows_the_closing_percent_is_not_read_subroutines_included() -> None:
    # LinuxCNC's own m98m99 test-illegal-sub-after-percent: a sub defined after the closing
    # '%' is not there for the call
    text = "%\nG21 G0 X1 Y2\no2 call\n%\no2 sub\nG0 Z3\no2 endsub\n"
    with pytest.raises(ProgramError) as info:
        parse_program(text)
    err = info.value.errors[0]
    assert (err.line, err.col) == (3, 1) and "no o2 sub" in err.message
    # before the closing '%' it is
    p = parse_program("%\no2 sub\nG0 Z3\no2 endsub\nG21 G0 X1 Y2\no2 call\n%\no3 sub\no3 endsub\n")
    assert [m.end.tolist() for m in p.moves] == [[1.0, 2.0, 0.0], [1.0, 2.0, 3.0]]


# A sub is defined as the program runs through it, or as a call finds it ahead (LinuxCNC 2.9's
# offset map; each outcome below checked with its rs274): a sub inside an if is defined only when
# that branch runs; met a second time it is refused, as is another definition of its label.
_IF = "o10 if [#1 GT 0]\no100 sub\nG1 X[#1] F100\no100 endsub\no10 endif\n"
SUB_DEFINITIONS = {
    "inside an if that runs": ("#1 = 1\n" + _IF + "o100 call [5]\nG0 X0\nM2\n", None, [5.0, 0.0]),
    "inside an if not run": ("#1 = 0\n" + _IF + "o100 call [5]\nG0 X0\nM2\n", 7, None),
    "called, then met inside an if": ("o100 call [5]\n#1 = 1\n" + _IF + "M2\n", 4, None),
    "called, then met in the flow": ("o100 call [5]\nG0 X1\no100 sub\nG1 X[#1] F100\no100 endsub\n"
                                     "G0 X0\nM2\n", 3, None),
    "inside a loop run twice": ("#2 = 0\no20 while [#2 LT 2]\no100 sub\nG1 X[#1] F100\no100 endsub\n"
                                "#2 = [#2 + 1]\no20 endwhile\no100 call [5]\nM2\n", 3, None),
    "one in each branch": ("#<m> = 0\no1 if [#<m> EQ 1]\no100 sub\nG1 X1 F100\no100 endsub\no1 else\n"
                           "o100 sub\nG1 X2 F100\no100 endsub\no1 endif\no100 call\nM2\n", None, [2.0]),
    "defined twice in the flow": ("o1 sub\nG1 X1 F100\no1 endsub\no1 sub\nG1 X2 F100\no1 endsub\n"
                                  "o1 call\nM2\n", 4, None),
    "two ahead, after the end": ("o1 call\nM2\no1 sub\nG1 X1 F100\no1 endsub\no1 sub\nG1 X2 F100\n"
                                 "o1 endsub\n", None, [1.0]),
}


@pytest.mark.parametrize("case", list(SUB_DEFINITIONS))
def test_a_sub_is_defined_as_the_program_runs_through_it(case: str) -> None:
    text, refused_at, xs = SUB_DEFINITIONS[case]
    if refused_at is not None:
        with pytest.raises(ProgramError) as exc:
            read(text)
        (err,) = exc.value.errors
        assert err.line == refused_at, err
        return
    program = read(text)
    assert [float(m.end[0]) for m in program.moves] == xs


@pytest.mark.skipif(RS274 is None, reason="LinuxCNC's rs274 is not installed (make test installs it)")
@pytest.mark.parametrize("case", list(SUB_DEFINITIONS))
def test_a_sub_is_defined_where_linuxcnc_defines_it(case: str) -> None:
    text, refused_at, _xs = SUB_DEFINITIONS[case]
    if refused_at is None:
        motion_alike(text)
        return
    theirs, ours = refused_alike(text)
    assert ours == text.splitlines()[refused_at - 1]
    # a call to a sub not defined: rs274 seeks it ahead and names the block where the file ended
    assert theirs == (text.splitlines()[-1] if case == "inside an if not run" else ours)


# ------------------------------------------------------------------ the call after M6
def _after_m6(tmp_path, body: str = "G0 Z[#1]\nG10 L1 P#5400 Z#1"):
    """A machine whose M6 calls o<after> [7] (LinuxCNC's REMAP of M6 as an ngc)."""
    import dataclasses

    from planner.core.machine import MachineSpec

    (tmp_path / "after.ngc").write_text(f"o<after> sub\n{body}\no<after> endsub\n")
    return dataclasses.replace(MachineSpec.default(), shipped_subroutine_dir=str(tmp_path),
                               after_tool_change="o<after> call [7]")


def test_m6_that_changes_the_tool_calls_the_machines_routine(tmp_path) -> None:
    from planner.core.program import EventKind
    from planner.core.tools import Tool, ToolTable

    machine = _after_m6(tmp_path)
    tools = ToolTable({1: Tool(1, 1, (("Z", 3.0),)), 2: Tool(2, 2, (("Z", 4.0),))})
    # a plain program (the bulk reader's kind) and the same with the tool already in
    p = parse_program("G0 X1\nT2 M6\nG43 H2\nG0 X2 Z0\nM2\n", "a.ngc", machine, tools=tools,
                      tool_in_spindle=1)
    kinds = [(e.kind, e.line) for e in p.events]
    assert (EventKind.TOOL_CHANGE, 2) in kinds and (EventKind.TOOL_DATA, 2) in kinds
    assert p.tool_sets[0].length_mm == 7.0          # the routine's G10 L1, then G43 H2 with it
    assert p.moves[-1].end[2] == pytest.approx(7.0)
    assert any(m.line == 2 and m.end[2] == pytest.approx(7.0) for m in p.moves)   # its move, at the M6 line
    same = parse_program("T1 M6\nG0 X1\nM2\n", "b.ngc", machine, tools=tools, tool_in_spindle=1)
    assert not any(e.kind is EventKind.TOOL_DATA for e in same.events)
    # M61 changes the tool without a change: no call
    m61 = parse_program("M61 Q2\nG0 X1\nM2\n", "c.ngc", machine, tools=tools, tool_in_spindle=1)
    assert not any(e.kind is EventKind.TOOL_DATA for e in m61.events)


def test_an_error_in_the_routine_after_m6_names_its_file_and_line(tmp_path) -> None:
    machine = _after_m6(tmp_path, "G0 Z1\nG0 X1 X2")
    with pytest.raises(ProgramError) as caught:
        parse_program("T2 M6\nG0 X1\nM2\n", "a.ngc", machine)
    (e,) = caught.value.errors
    assert e.file.endswith("after.ngc") and e.line == 3 and "two X words" in e.message
