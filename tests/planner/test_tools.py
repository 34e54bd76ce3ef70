"""The tool table (LinuxCNC's .tbl format) and the tool codes: T, M6, M61 Q, G43, G43 H,
G43.1, G43.2, G49, read as LinuxCNC 2.9 reads them."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.core.errors import PlannerError, ProgramError
from planner.core.program import EventKind, ToolNumber
from planner.core.tools import Tool, ToolTable, format_tbl, parse_tbl
from planner.gcode.interpreter import parse_program

TABLE = parse_tbl("T1 P1 Z10 D6 ;6 mm flat\n"
                  "T2 P5 X0.1 Z-3.5 D3 ;3 mm ball\n"
                  "; a comment line\n"
                  "\n"
                  "T17 P17 Z125.25\n", "tools.tbl")


def ends(text: str, **kw) -> list[tuple[int, tuple[float, ...]]]:
    prog = parse_program(text, "t.nc", tools=kw.pop("tools", TABLE), **kw)
    return [(m.line, tuple(float(v) for v in m.end)) for m in prog.moves]


def test_the_tbl_format_is_read_as_linuxcnc_writes_it() -> None:
    t2 = TABLE.get(2)
    assert t2 == Tool(2, 5, (("X", 0.1), ("Z", -3.5)), 3.0, "3 mm ball")
    assert TABLE.get(17).pocket == 17 and TABLE.get(17).length_mm == 125.25
    assert [t.number for t in TABLE] == [1, 2, 17]
    assert TABLE.get(1).label() == "T1 (6 mm flat)" and TABLE.get(17).label() == "T17"


@pytest.mark.parametrize("text, where", [
    ("T1 Z10\nT1 Z3\n", "tools.tbl:2: T1 is given twice"),
    ("T1 Z10\nP3 Z1\n", "tools.tbl:2:1: a tool line needs a T word"),
    ("T1 Z1 Z2\n", "tools.tbl:1:7: two Z words"),
    ("T1 K3\n", "tools.tbl:1:4: K is not a tool table word"),
    ("T1.5 Z1\n", "tools.tbl:1: T1.5 must be a whole number"),
    ("T0 Z1\n", "tools.tbl:1: tool number T0 must be"),
    ("T1 Z1e9\n", "tools.tbl:1: T1 offset Z1e+09 must be a number within"),
    ("T1 D-2\n", "tools.tbl:1: T1 diameter D-2 must be"),
    ("T1 Z=3\n", "tools.tbl:1:4: expected a letter and a number"),
])
def test_a_bad_tool_table_is_named_by_line_and_word(text: str, where: str) -> None:
    with pytest.raises(PlannerError) as exc:
        parse_tbl(text, "tools.tbl")
    assert where in str(exc.value)


_num = st.floats(-1000, 1000, allow_nan=False).map(lambda v: round(v, 4))
_tool = st.builds(
    lambda n, p, z, x, d, text: Tool(n, p, tuple(a for a in (("X", x), ("Z", z)) if a[1] is not None),
                                     d, text),
    st.integers(1, 99_999), st.integers(0, 999), st.one_of(st.none(), _num), st.one_of(st.none(), _num),
    st.floats(0, 100, allow_nan=False), st.text(st.characters(blacklist_categories=("Cc", "Cs", "Zl", "Zp")),
                                                max_size=20).map(str.strip))


@settings(max_examples=200, deadline=None)
@given(st.lists(_tool, max_size=8, unique_by=lambda t: t.number))
def test_writing_and_reading_a_table_gives_it_back(tools: list[Tool]) -> None:
    table = ToolTable.of(tools)
    assert parse_tbl(format_tbl(table)) == table


@settings(max_examples=300, deadline=None)
@given(st.text(alphabet="TPDXYZIJQK0123456789.-+e ;\n\t#", max_size=80))
def test_any_text_is_a_table_or_a_planner_error_naming_its_line(text: str) -> None:
    try:
        parse_tbl(text, "f.tbl")
    except PlannerError as exc:
        assert str(exc).startswith("f.tbl:")


def test_m6_loads_the_selected_tool_and_g43_applies_its_length() -> None:
    assert ends("T1 M6\nG0 Z5\nG43\nG0 Z5\n") == [(2, (0.0, 0.0, 5.0)), (4, (0.0, 0.0, 15.0))]  # G43 first
    # T alone only selects; M6 loads; G43 uses what is in the spindle
    assert ends("T1 M6\nT2\nG43\nG0 Z5\n")[-1] == (4, (0.0, 0.0, 15.0))


def test_g43_h_g43_1_g43_2_and_g49() -> None:
    out = ends("G43 H2\nG0 X1 Z5\nG49\nG0 Z5\nG43.1 Z2\nG0 Z5\nG43.2 H1\nG0 Z5\nG43.2 Z-1\nG0 Z5\n")
    assert out == [(2, (1.1, 0.0, 1.5)), (4, (1.1, 0.0, 5.0)), (6, (1.1, 0.0, 7.0)),
                   (8, (1.1, 0.0, 17.0)), (10, (1.1, 0.0, 16.0))]


def test_an_inch_program_gives_dynamic_offsets_in_inches_and_table_offsets_in_mm() -> None:
    out = ends("G20\nG43.1 Z1\nG0 Z0\nG43 H1\nG0 Z0\n")
    assert out[0][1][2] == pytest.approx(25.4) and out[1][1][2] == pytest.approx(10.0)


def test_m61_sets_the_tool_in_the_spindle_without_a_change() -> None:
    prog = parse_program("M61 Q2\nG43\nG0 Z0\n", "t.nc", tools=TABLE)
    assert prog.moves[0].end[2] == -3.5
    (ev,) = [e for e in prog.events if e.kind is EventKind.TOOL_SET]
    assert ev.payload == ToolNumber(2) and ev.stops


def test_the_tool_in_the_spindle_at_the_start_is_used_by_g43() -> None:
    assert ends("G43\nG0 Z0\n", tool_in_spindle=17) == [(2, (0.0, 0.0, 125.25))]


def test_the_work_position_subtracts_the_tool_offset_like_linuxcncs_relative_dro() -> None:
    prog = parse_program("G43 H1\nG0 Z5\n", "t.nc", tools=TABLE)
    assert np.allclose(prog.frame_at(len(prog.moves) - 1).tool, (0.0, 0.0, 10.0))


@pytest.mark.parametrize("text, where", [
    ("T3\n", "t.nc:1:1: error: tool T3 is not in the tool table"),
    ("G43 H3\n", "t.nc:1:5: error: tool T3 is not in the tool table"),
    ("T1 M6\nG43.2 H9\n", "t.nc:2:7: error: tool T9 is not in the tool table"),
    ("M61\n", "t.nc:1:1: error: M61 needs a Q word"),
    ("M61 Q4\n", "t.nc:1:5: error: tool T4 is not in the tool table"),
    ("G10 L1 P3 Z1\n", "t.nc:1:8: error: G10 L1 P3: tool T3 is not in the tool table"),
    ("G1 G43.1 Z1 F100\n", "t.nc:1:4: error: cannot use two G codes that both use axis values"),
    ("G43.2\n", "t.nc:1:1: error: G43.2 needs an H word or axis words"),
    ("G43 H1.5\n", "t.nc:1:5: error: tool number H1.5 must be a whole number"),
    ("H1\n", "t.nc:1:1: error: H word with no G43, G43.2 or G76"),
    ("Q1\n", "t.nc:1:1: error: Q word with no code that uses it"),
])
def test_tool_mistakes_are_refused_at_their_word(text: str, where: str) -> None:
    with pytest.raises(ProgramError) as exc:
        parse_program(text, "t.nc", tools=TABLE)
    assert where in str(exc.value)


def test_without_a_table_any_tool_is_known_with_zero_offsets_as_linuxcncs_reference_runs() -> None:
    assert ends("T7 M6\nG43 H7\nG0 Z5\n", tools=None) == [(3, (0.0, 0.0, 5.0))]


def test_cnc_plan_reads_a_tool_table(tmp_path, capsys) -> None:
    from cli.plan import main

    prog = tmp_path / "p.nc"
    prog.write_text("G21 G90\nT1 M6\nG43\nG0 Z5\nM30\n")
    (tmp_path / "t.tbl").write_text("T1 P1 Z10 ;six\n")
    out = tmp_path / "canon.jsonl"
    assert main([str(prog), "--tools", str(tmp_path / "t.tbl"), "--samples", str(tmp_path / "s.npz")]) == 0
    with np.load(tmp_path / "s.npz") as z:
        assert z["q"][-1, 2] == pytest.approx(15.0)          # machine Z: 5 + the 10 mm tool
    (tmp_path / "bad.tbl").write_text("T1 P1 Z10\nT1 Z3\n")
    assert main([str(prog), "--tools", str(tmp_path / "bad.tbl"), "--canon", str(out)]) == 2
    assert f"{tmp_path / 'bad.tbl'}:2: T1 is given twice" in capsys.readouterr().err
    assert not out.exists()
    (tmp_path / "t.tbl").write_text("T2 P2 Z10\n")                 # T1 is not in this table
    assert main([str(prog), "--tools", str(tmp_path / "t.tbl"), "--canon", str(out)]) == 2
    assert "p.nc:2:1: error: tool T1 is not in the tool table" in capsys.readouterr().err


def test_cutter_compensation_takes_the_radius_from_the_tool_table() -> None:
    """G41/G42 offset the path by half the diameter of D's tool, or of the tool in the spindle
    without D or with D0 (LinuxCNC's rule); a tool with no diameter runs the programmed path."""
    from planner.core.tools import parse_tbl
    from planner.gcode.interpreter import parse_program

    table = parse_tbl("T1 P1 Z10 D6 ;end mill\nT2 P2 Z5 ;probe\n")

    def last_y(text: str, **kw: object) -> float:
        return float(parse_program(text, tools=table, **kw).moves[-1].end[1])

    # along +X with the tool on the left (G41): 3 mm to +Y; on the right (G42): 3 mm to -Y
    assert last_y("G21 F100 T1 M6\nG41 D1 G1 X10\n") == pytest.approx(3.0)
    assert last_y("G21 F100\nG42 G1 X10\n", tool_in_spindle=1) == pytest.approx(-3.0)
    assert last_y("G21 F100\nG41 D0 G1 X10\n", tool_in_spindle=1) == pytest.approx(3.0)
    assert last_y("G21 F100\nG41 D2 G1 X10\nG40\n", tool_in_spindle=1) == 0.0          # diameter 0
    with pytest.raises(ProgramError, match="tool T7 is not in the tool table"):
        parse_program("G21 F100\nG41 D7 G1 X10\n", tools=table)


def test_g10_tool_data_from_the_program() -> None:
    """G10 L1 sets a tool's data as given (R is the radius), L10 so that the current position
    reads the given value with that tool, L11 the same in G59.3 without G92; a later G43 uses it,
    and the program carries the changed tools for the machine to keep."""
    from dataclasses import replace

    from planner.core.machine import MachineSpec
    from planner.core.program import EventKind
    from planner.core.tools import parse_tbl
    from planner.gcode.interpreter import parse_program

    table = parse_tbl("T1 P1 Z20 D6 ;end mill\n")
    machine = replace(MachineSpec.default(),
                      work_offsets={"G54": (0.0, 0.0, -30.0), "G59.3": (0.0, 0.0, -100.0)})
    p = parse_program("G21 G90 F100\nG0 Z50\nG92 Z40\nG10 L10 P1 Z0\nG43 H1\nG0 Z1\nG10 L1 P1 Z7 R3\nG43 H1\n"
                      "G0 Z1\nG10 L11 P1 Z0\nM2\n", machine=machine, tools=table)
    # Z50 in G54 (-30) is machine 20; G92 Z40 there is a G92 offset of 10; L10 Z0 makes T1's
    # length 20 + 30 - 10 = 40, so Z1 is machine 1 - 30 + 10 + 40 = 21; L1 Z7: Z1 is -12;
    # L11 Z0 there, in G59.3 (-100) without G92: -12 + 100 = 88
    assert [round(m.end[2], 6) for m in p.moves] == [20.0, 21.0, -12.0]
    tools = p.tool_sets
    assert [t.length_mm for t in tools] == [40.0, 7.0, 88.0] and tools[1].diameter_mm == 6.0
    assert [e.kind for e in p.events if e.kind is EventKind.TOOL_DATA] == [EventKind.TOOL_DATA] * 3
    for text, words in (("G10 L1 Z1\n", "needs P with the tool number"),
                        ("G10 L1 P9 Z1\n", "tool T9 is not in the tool table"),
                        ("G10 L1 P1 R-1\n", "radius cannot be negative")):
        with pytest.raises(ProgramError, match=words):
            parse_program(text, tools=table)


def test_g10_l0_reloads_nothing_and_is_refused_with_a_tool_in_the_spindle() -> None:
    """G10 L0 (LinuxCNC: reload the tool table file, which G10 L1/L10/L11 have written): the
    table the program reads is already the machine's, so the motion is unchanged; with a tool
    in the spindle LinuxCNC refuses it, and so does this."""
    from tools.linuxcnc_oracle import RS274, run_linuxcnc

    table = parse_tbl("T1 P1 Z10 D6\n")
    plain = "G21 F100\nT1 M6\nG43\nG1 X5 Z-1\nM6 T0\nG49\n{}G1 X10 Z-2\nM2\n"
    with_l0 = parse_program(plain.format("G10 L0\n"), "l0.ngc", tools=table)
    without = parse_program(plain.format(""), "p.ngc", tools=table)
    assert [m.end.tolist() for m in with_l0.moves] == [m.end.tolist() for m in without.moves]
    loaded = "G21 F100\nT1 M6\nG10 L0\nG1 X1\nM2\n"
    with pytest.raises(ProgramError) as caught:
        parse_program(loaded, "l0.ngc", tools=table)
    err = caught.value.errors[0]
    assert (err.line, err.col) == (3, 5) and "with tool 1 in the spindle" in err.message
    if RS274 is not None:
        # LinuxCNC refuses the same block; the stand-alone rs274 also refuses it after T0 M6 or
        # M61 Q0 (it still names tool 1 loaded then), where this has unloaded the tool
        assert run_linuxcnc(loaded, table).error_block == loaded.splitlines()[err.line - 1] == "G10 L0"
        assert "loaded tool <1>" in run_linuxcnc(plain.format("G10 L0\n"), table).error
