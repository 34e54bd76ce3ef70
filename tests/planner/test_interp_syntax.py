"""Interpreter syntax: RS274/NGC and Fanuc-style spelling, comments, delimiters, expressions."""

from __future__ import annotations

import numpy as np
import pytest

from planner.core.errors import PlannerError, ProgramError, SourceError
from planner.core.program import MoveKind
from planner.gcode.interpreter import parse_file, parse_program


def ends(text: str, **kw) -> np.ndarray:
    return np.array([m.end for m in parse_program(text, **kw).moves])


def one_error(text: str, **kw) -> SourceError:
    with pytest.raises(ProgramError) as ei:
        parse_program(text, "t.nc", **kw)
    assert len(ei.value.errors) == 1, str(ei.value)
    return ei.value.errors[0]


def test_compact_and_spaced_forms_are_the_same():
    a = parse_program("G01 F100\nG02X10.Y5.R7.\n")
    b = parse_program("g1 f100\ng2 x 10 y 5 r 7\n")
    c = parse_program("G1F100\nG 0 2 X1 0 Y5 R7")  # spaces anywhere, like LinuxCNC
    for p in (b, c):
        assert len(p.moves) == len(a.moves) == 1
        np.testing.assert_array_equal(p.moves[0].end, a.moves[0].end)
        assert p.moves[0].arc.center == a.moves[0].arc.center


@pytest.mark.parametrize(
    "text,value", [("X.5", 0.5), ("X-.5", -0.5), ("X+2", 2.0), ("X3.", 3.0), ("X007", 7.0), ("X-0.25", -0.25)]
)
def test_number_forms(text, value):
    assert ends(f"G0 {text}")[0][0] == value


def test_line_numbers_block_delete_comments_percent():
    text = "%\nN10 G0 X1 (comment) Y2 ; rest\n/G0 X99\nN20 G0 X3 (a)(b)\n%\nG0 X1000\n"
    # the block delete switch on: the '/' line is skipped
    e = ends(text, block_delete=True)
    np.testing.assert_array_equal(e, [[1, 2, 0], [3, 2, 0]])
    # off, as LinuxCNC starts and as rs274 reads: the '/' line runs
    e = ends(text)
    np.testing.assert_array_equal(e[:, 0], [1, 99, 3])


def test_several_g_words_of_different_groups_in_one_block():
    p = parse_program("G17 G21 G90 G94 G54 G0 X1 Y1\nG91 G1 X1 F60\n")
    np.testing.assert_array_equal(p.moves[1].end, [2, 1, 0])
    assert p.moves[1].feed_mm_s == pytest.approx(1.0)


def test_two_g_codes_of_one_group_is_an_error():
    e = one_error("G0 G1 X1 F10")
    assert "same modal group" in e.message and e.line == 1
    e = one_error("G17 G18")
    assert "same modal group" in e.message


def test_error_format_file_line_col():
    with pytest.raises(ProgramError) as ei:
        parse_program("G0 X0\nG1 F10\n  G1 X1 Q5\n", "part.nc")
    err = ei.value.errors[0]
    assert (err.file, err.line, err.col) == ("part.nc", 3, 9)
    assert str(err) == ("part.nc:3:9: error: Q word with no code that uses it (G05, G64, M61, G73, G76, G83, "
                        "M66, M67, M68)")
    assert str(ei.value).startswith("part.nc:3:9: error: ")
    assert isinstance(ei.value, PlannerError) and isinstance(ei.value, ValueError)
    assert ei.value.line == 3


def test_issue_example_message():
    e = one_error("G0 X0 Y0\nG1 F100\nG2 X4.1 Y0 R2")
    assert e.message == "arc radius 2.000 mm too small to reach end point (half chord 2.050 mm)"
    assert (e.line, e.col) == (3, 12)


def test_all_errors_are_collected():
    text = "G0 X0\nG1 X1\nG5 X1\nM19\nG1 Q1 F10 X2\nG0 X3\nB5\n"
    with pytest.raises(ProgramError) as ei:
        parse_program(text, "p.nc")
    assert [e.line for e in ei.value.errors] == [2, 3, 4, 5, 7]


def test_error_limit():
    with pytest.raises(ProgramError) as ei:
        parse_program("M19\n" * 500, max_errors=10)
    assert len(ei.value.errors) == 10 and ei.value.truncated
    assert "too many errors" in str(ei.value)


@pytest.mark.parametrize(
    "line,fragment,col",
    [
        ("G1 X1.2.3 F1", "unexpected number text", 8),
        ("G1 X F1", "letter 'X' without a number", 4),
        ("G1 X1 (open", "unclosed comment", 7),
        ("G1 X1 (a (b) c)", "nested comment", 10),
        ("G1 X1 ) F1", "')' without '('", 7),
        ("G1 X1 $ F1", "unexpected character '$'", 7),
        ("G1 X1 N5 F1", "N word (line number) must begin the block", 7),
        ("G1 X1 X2 F1", "two X words", 4),
        ("G1 E5 F1", "E word with no G33, G33.1, G76, M67 or M68 to use it", 4),
        ("G0 X1e5", "E word with no G33, G33.1, G76, M67 or M68 to use it", 6),
        ("G0 X99999999999", "out of range", 4),
        ("G1 X1 F1000000000000", "F value 1e+12 out of range (|value| < 1e12)", 7),
        ("o100 sub", "o100 sub without its o100 endsub", 1),
        ("G0 % X1", "unexpected character '%'", 4),
        ("% X1", "'%' must be alone", 1),
    ],
)
def test_syntax_errors(line, fragment, col):
    e = one_error(line)
    assert fragment in e.message
    assert e.col == col, e


def test_windows_line_endings_and_latin1(tmp_path):
    f = tmp_path / "w.nc"
    f.write_bytes(b"(T\xfcrk\xe7e yorum)\r\nG0 X1\r\nG0 Y2\r\n")
    p = parse_file(f)
    assert [m.line for m in p.moves] == [2, 3]
    assert p.name == str(f)


def test_parse_file_missing(tmp_path):
    with pytest.raises(PlannerError, match="cannot read"):
        parse_file(tmp_path / "nope.nc")


def test_expressions_and_parameters():
    text = (
        "#<z_safe> = 5\n#1 = [2 * 3]\n"
        "G0 X[1 + 2 * sqrt[4]] Y#1 Z#<Z_SAFE>\n"
        "G0 X[ATAN[1]/[1]] Y[COS[60] * 10] Z[2 ** 3]\n"
        "G0 X[7 MOD 3] Y[ABS[-2] + FIX[2.7] + FUP[2.1] + ROUND[2.5]] Z[-#1]\n"
        "#<a> = 1 G0 X#<a>\n"  # assignment takes effect after the line
    )
    with pytest.raises(ProgramError, match="named parameter #<a> is not defined"):
        parse_program(text)
    e = ends(text.rsplit("\n", 2)[0] + "\n")
    np.testing.assert_allclose(e, [[5, 6, 5], [45, 5, 8], [1, 2 + 2 + 3 + 3, -6]])


def test_expression_errors():
    assert "outside the function's domain" in one_error("G0 X[SQRT[-1]]").message
    assert "arithmetic error" in one_error("G0 X[1/0]").message
    assert "expected ']'" in one_error("G0 X[1+2").message
    assert "nested too deeply" in one_error("G0 X" + "[" * 2000 + "1" + "]" * 2000).message
    assert "the most a block may have" in one_error("G0 X" + "[" * 3000 + "1" + "]" * 3000).message


def test_fanuc_program_number_and_trailing_dots():
    p = parse_program("%\nO0001 (PART)\nG0G90X0Y0\nG1X15.Y0.F250.\n%\n")
    assert len(p.moves) == 1 and p.moves[0].kind is MoveKind.LINE
    assert p.moves[0].feed_mm_s == pytest.approx(250 / 60)


def test_comments_before_opening_percent():
    p = parse_program("(header)\n\n%\nG0 X1\n%\nG0 X2\n")
    assert len(p.moves) == 1 and p.line_count == 6


def test_text_after_end_is_ignored():
    p = parse_program("G0 X1\nM30\nthis is not G-code at all\n")
    assert len(p.moves) == 1


def test_missing_program_end_is_accepted():
    # LinuxCNC complains about a missing M2/M30/% only at the end of the file; we accept it.
    assert len(parse_program("G0 X1").moves) == 1


def test_empty_program():
    p = parse_program("")
    assert len(p.moves) == 0 and p.events == ()
    np.testing.assert_array_equal(p.end_position, [0, 0, 0])
    assert len(p.move_frames) == 0 and p.frame_at(0).is_identity


def test_a_byte_order_mark_before_the_first_line_is_no_gcode(tmp_path) -> None:
    """Windows editors write a UTF-8 byte-order mark first; it is an encoding marker that no
    editor shows, so it is read as nothing and line 1's columns are counted without it."""
    path = tmp_path / "bom.ngc"
    path.write_bytes(b"\xef\xbb\xbfG21 G1 X1 F100\nM2\n")
    assert [m.end[0] for m in parse_file(path).moves] == [1]
    with pytest.raises(ProgramError) as ei:
        parse_program("\ufeffG21 G1 X1 Q5 F100\n")
    (err,) = ei.value.errors
    assert (err.line, err.col) == (1, 11)


@pytest.mark.parametrize("text", ["G1 X1\0 F100", "#1=1\nG1 X#1\x01 F100", "G1 X1 \x7f"])
def test_a_control_byte_in_a_program_is_named_not_written_raw(text: str) -> None:
    message = one_error(text).message
    assert message.startswith("unexpected character U+00") and message.isprintable(), repr(message)
