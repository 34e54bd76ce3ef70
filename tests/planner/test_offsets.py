"""Coordinate systems and offsets as LinuxCNC 2.9 keeps them: G10 L2/L20, G54-G59.3, G92,
G92.1/.2/.3, G52, G28/G28.1, G30/G30.1, the parameters behind them (#5161-, #5181-, #5210-#5220,
#5221-...), what a program starts from (the machine's parameters) and what it leaves (OFFSETS
events with the parameter sets the machine keeps)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.core.errors import ProgramError
from planner.core.machine import MachineSpec
from planner.core.program import EventKind, Program
from planner.gcode.interpreter import PERSISTENT_PARAMETERS, parse_program
from tools.linuxcnc_oracle import RS274, motion_alike, refused_alike

DATA = Path(__file__).resolve().parents[1] / "data" / "linuxcnc_interp"


def ends(p: Program) -> list[list[float]]:
    return [[round(v, 6) for v in m.end.tolist()] for m in p.moves]


def test_linuxcnc_g52_g92_interaction_parameters() -> None:
    """LinuxCNC's test prints #5210-#5219 after each code. Its harness keeps parameters in inch
    user units; read in G21 here, the machine's units are millimetres and the numbers are the same."""
    folder = DATA / "g52-g92-interaction"
    text = (folder / "test.ngc").read_text().replace("G20", "G21")
    got = [e.message for e in parse_program(text).events if e.kind is EventKind.MESSAGE]
    want = [line.strip() for line in (folder / "expected").read_text().splitlines()
            if line.strip() and "N....." not in line]
    assert len(want) == 18 and got == want


def test_g10_l2_and_l20_set_systems_and_moves_follow() -> None:
    p = parse_program("G21 G90\nG10 L2 P1 X100 Y50 Z-10\nG0 X0 Y0 Z0\nG10 L20 P2 X0 Y0\nG55 G0 X1 Y1\n"
                      "G10 L2 P0 Z5\nG0 Z0\nM2\n")
    assert ends(p) == [[100, 50, -10], [101, 51, -10], [101, 51, 5]]
    last = p.parameter_sets[-1]
    assert (last[5221], last[5222], last[5223]) == (100, 50, -10)            # G54
    assert (last[5241], last[5242], last[5243], last[5220]) == (100, 50, 5, 2)   # G55, in use


def test_g92_g52_and_their_cancels_move_the_program_zero() -> None:
    p = parse_program("G21 G90\nG0 X10\nG92 X0\nG0 X5\nG92.2\nG0 X5\nG92.3\nG0 X1\nG92.1\nG52 X100\nG0 X0\n"
                      "M2\n")
    assert [e[0] for e in ends(p)] == [10, 15, 5, 11, 100]


def test_g28_g30_go_to_their_stored_positions_and_g28_1_stores() -> None:
    p = parse_program("G21 G90\nG0 X10 Y20 Z30\nG28.1\nG0 X0 Y0 Z0\nG28 Z5\nG0 X1 Y1 Z1\nG28\n"
                      "G30.1\nG0 X0 Y0 Z0\nG30 X3\n", parameters={5181: 1.0, 5182: 2.0, 5183: 3.0})
    # G28 Z5: through Z5 to the stored Z only; G28 alone: every axis; G30 X3: through X3 to G30's X
    assert ends(p) == [[10, 20, 30], [0, 0, 0], [0, 0, 5], [0, 0, 30], [1, 1, 1], [10, 20, 30],
                       [0, 0, 0], [3, 0, 0], [10, 0, 0]]


def test_a_program_starts_from_the_machines_parameters() -> None:
    params = {5210: 1.0, 5211: -5.0, 5161: 7.0, 5381: 300.0}     # G92 X-5 on, G28 X7, G59.3 X300
    p = parse_program("G21 G90\nG0 X0\nG28 X0\nG59.3 G0 X0\n#1 = #5381\nG54 G0 X#1\nM2\n", parameters=params)
    assert [e[0] for e in ends(p)] == [-5.0, 7.0, 295.0]
    machine = replace(MachineSpec.default(), work_offsets={"G54": (1.0, 0.0, 0.0)})
    p = parse_program("G21 G90\nG0 X0\nM2\n", machine=machine, parameters={5221: 99.0})
    assert ends(p)[0][0] == 1.0                                      # the machine's G54 counts


def test_offsets_events_stop_the_motion_and_carry_every_persistent_parameter() -> None:
    p = parse_program("G21 G90 F100\nG1 X1\nG10 L2 P3 X7\nG1 X2\nM2\n")
    (ev,) = [e for e in p.events if e.kind is EventKind.OFFSETS]
    assert ev.after_move == 0 and ev.stops and "G56" in ev.message
    assert set(p.parameter_sets[0]) == PERSISTENT_PARAMETERS and p.parameter_sets[0][5261] == 7.0


@pytest.mark.parametrize("text, col, words", [
    ("G10 P1 X1\n", 1, "G10 needs an L word"),
    ("G10 L2 P10 X1\n", 8, "needs P0-P9"),
    ("G10 L20 P1 X0 R30\n", 15, "R not allowed in G10 L20"),
    ("G10 L3 P1 X1\n", 5, "not a G10 this control knows"),
    ("G92 G1 X1 F10\n", 1, "cannot use two G codes that both use axis values (G92 and a motion code)"),
    ("G21 G41 F10\nG10 L2 P0 X1\n", 1, "with cutter compensation on"),
])
def test_refusals(text: str, col: int, words: str) -> None:
    with pytest.raises(ProgramError) as exc:
        parse_program(text)
    (err,) = exc.value.errors
    assert words in err.message and err.col == col, err


@settings(max_examples=80, deadline=None)
@given(x=st.floats(-100, 100), y=st.floats(-100, 100), gx=st.floats(-50, 50), system=st.integers(1, 9),
       inch=st.booleans())
def test_g10_l20_then_the_current_position_reads_the_value(x: float, y: float, gx: float, system: int,
                                                           inch: bool) -> None:
    """Whatever the G92 offset, the units and the system: after G10 L20 Pn X.. the position read in
    that system (#<_x> after selecting it) is the value given."""
    units = "G20" if inch else "G21"
    code = ["G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3"][system - 1]
    text = (f"{units} G90\nG0 X{x:.4f} Y{y:.4f}\nG92 X{gx:.4f}\nG10 L20 P{system} X1.5\n{code}\n"
            "(debug,#<_x>)\nM2\n")
    (msg,) = [e.message for e in parse_program(text).events if e.kind is EventKind.MESSAGE]
    assert float(msg) == pytest.approx(1.5, abs=1e-6)
    np.testing.assert_allclose(1.5, float(msg), atol=1e-6)


@pytest.mark.parametrize("name", ["g10-l2-while-active", "g10-l20-while-active"])
def test_linuxcnc_rotated_coordinate_system(name: str) -> None:
    """LinuxCNC's tests/interp/g10: G10 L2 R and L20 on the system in use, read through the
    position parameters #5420/#5421, and the moves in program coordinates (--canon)."""
    import re

    from planner.gcode.canon import canon_records

    folder = DATA / name
    program = parse_program((folder / "test.ngc").read_text())
    text = (folder / "expected").read_text()
    want = re.findall(r'MESSAGE\("(.*)"\)', text)
    assert len(want) == {"g10-l2-while-active": 10, "g10-l20-while-active": 8}[name]
    assert [e.message for e in program.events if e.kind is EventKind.MESSAGE] == want
    # LinuxCNC's moves (inch, 4 decimals); the first goes from the start point to itself, which
    # a Program drops (the later ones to the same program point move the machine: offsets changed)
    lc_moves = [[float(v) * 25.4 for v in m.split(",")[:3]]
                for m in re.findall(r"STRAIGHT_(?:FEED|TRAVERSE)\((.*)\)", text)]
    assert lc_moves[0] == [0.0, 0.0, 0.0]
    lc_moves = lc_moves[1:]
    ours = [r["args"][:3] for r in canon_records(program) if r["call"].startswith("straight")]
    assert len(ours) == len(lc_moves)
    np.testing.assert_allclose(ours, lc_moves, atol=0.5e-4 * 25.4)


def test_rotated_system_turns_lines_arcs_cycles_and_polar_words() -> None:
    from planner.gcode.canon import canon_records

    text = ("G21 G90 F100\nG10 L2 P1 X10 Y0 R90\nG54 G0 X0 Y0\nG1 X5\nG2 X5 Y0 I-2.5 J0\nG91 G1 Y1\n"
            "G90 G81 X1 Y1 Z-1 R1\nG80\nG0 @2 ^0\nG10 L20 P1 X0\nG0 X1\nM2\n")
    p = parse_program(text)
    assert ends(p) == [[10, 0, 0], [10, 5, 0], [10, 5, 0], [9, 5, 0], [9, 5, 1], [9, 1, 1], [9, 1, -1],
                       [9, 1, 1], [10, 2, 1], [10, 3, 1]]
    arc = next(r for r in canon_records(p) if r["call"] == "arc_feed")
    assert [round(v, 9) for v in arc["args"][:4]] == [5.0, 0.0, 2.5, 0.0]        # program coordinates
    # a G18 arc there lies in the plane of Z and the turned X: from the origin to program X1 (the
    # machine's cos 30, sin 30) about the centre Z 0.866 X 0.5, as rs274 writes it; half way it
    # is 0.134 below, at half the turned X
    g18 = parse_program("G21 F100\nG10 L2 P1 R30\nG18 G2 X1 Z0 R1\nM2\n")
    move = g18.moves[-1]
    c30, s30 = np.cos(np.radians(30.0)), np.sin(np.radians(30.0))
    np.testing.assert_allclose(move.end, [c30, s30, 0.0], atol=1e-12)
    np.testing.assert_allclose(move.evaluate(np.array([move.length_mm / 2]))[0][0],
                               [0.5 * c30, 0.5 * s30, c30 - 1.0], atol=1e-12)
    arc = next(r for r in canon_records(g18) if r["call"] == "arc_feed")
    assert [round(v, 9) for v in arc["args"][:4]] == [0.0, 1.0, round(c30, 9), 0.5]
    assert arc["plane"] == "XZ"
    with pytest.raises(ProgramError, match="R not allowed in G10 L20"):
        parse_program("G10 L20 P1 X0 R10\n")


@settings(max_examples=60, deadline=None)
@given(r=st.floats(-360, 360), x=st.floats(-50, 50), y=st.floats(-50, 50), ox=st.floats(-100, 100),
       oy=st.floats(-100, 100))
def test_rotation_keeps_distances_and_reads_back(r: float, x: float, y: float, ox: float, oy: float) -> None:
    """A rotated system moves the tool to a point at the same distance from its origin, and the
    position read back (#5420, #5421) is the one programmed."""
    text = (f"G21 G90\nG10 L2 P1 X{ox:.4f} Y{oy:.4f} R{r:.4f}\nG0 X{x:.4f} Y{y:.4f}\n"
            "(debug,#5420 #5421)\nM2\n")
    p = parse_program(text)
    end = p.moves[-1].end if p.moves else np.array([float(f"{ox:.4f}"), float(f"{oy:.4f}"), 0.0])
    dist = float(np.hypot(end[0] - float(f"{ox:.4f}"), end[1] - float(f"{oy:.4f}")))
    assert dist == pytest.approx(float(np.hypot(float(f"{x:.4f}"), float(f"{y:.4f}"))), abs=1e-6)
    (msg,) = [e.message for e in p.events if e.kind is EventKind.MESSAGE]
    rx, ry = (float(v) for v in msg.split())
    assert rx == pytest.approx(float(f"{x:.4f}"), abs=1e-6)
    assert ry == pytest.approx(float(f"{y:.4f}"), abs=1e-6)


@pytest.mark.parametrize("name, count", [("g10-l1-l10", 34), ("g10-l11", 4), ("g10-with-g92", 18),
                                         ("machine-coord-params", 13)])
def test_linuxcnc_tool_data_offsets_and_position_parameters(name: str, count: int) -> None:
    """LinuxCNC's G10 L1/L10/L11 (rotated systems and G92 included), G92 with every system and
    the position parameters #5021-, #5401-, #5420-, message by message. Its test harness keeps
    parameters in inch user units and its output went through awk (runs of spaces collapsed):
    read in G21 on this millimetre machine, the numbers are the same."""
    import re

    from planner.core.tools import parse_tbl

    folder = DATA / name
    text = (folder / "test.ngc").read_text().replace("g20", "g21").replace("G20", "G21")
    program = parse_program(text, tools=parse_tbl((folder / "test.tbl").read_text()))
    want = re.findall(r'MESSAGE\("(.*)"\)', (folder / "expected").read_text())
    assert len(want) == count
    got = [re.sub(" {2,}", " ", e.message) for e in program.events if e.kind is EventKind.MESSAGE]
    assert got == want


@pytest.mark.skipif(RS274 is None, reason="LinuxCNC's rs274 is not installed (make test installs it as root)")
@pytest.mark.parametrize("text", [
    "G21 G90\nG43.1 @2\nG1 X1 F100\nM2\n",
    "G21 G90\nG92 @2\nM2\n",
    "G21 G90\nG28 @2 ^30\nM2\n",
    "G21 G90\nG10 L20 P1 @2\nM2\n",
    "G21 G90\nG52 @2\nM2\n",
    "G21 G90\n@2\nM2\n",
])
def test_polar_words_move_or_are_refused_as_linuxcnc_refuses_them(text: str) -> None:
    # the codes whose axis words are data (offsets, G28, G43.1) take no polar words
    theirs, ours = refused_alike(text)
    assert theirs == ours


@pytest.mark.skipif(RS274 is None, reason="LinuxCNC's rs274 is not installed (make test installs it as root)")
@pytest.mark.parametrize("block", ["G92.1 G92 X1", "G92.2 G10 L2 P1 X1", "G92.3 G28", "G52 X1 G92.1",
                                   "G92 X3\nG92.2 G52 Y2", "G92 X3\nG92.2\nG92.3 G10 L20 P1 Y4"])
def test_g92_1_to_g92_3_go_beside_a_code_of_group_0_after_it(block: str) -> None:
    # LinuxCNC 2.9 has them in a group of their own, run after G10, G28, G52 and G92
    text = f"G21 G90 F600\nG0 X1 Y1 Z1\n{block}\nG1 X2 Y3\nG0 X5 Y-1\nM2\n"
    motion_alike(text)


@pytest.mark.parametrize("code", ["G92", "G52"])
def test_g92_and_g52_without_an_axis_word_are_refused_as_linuxcnc_refuses_them(code: str) -> None:
    with pytest.raises(ProgramError) as info:
        parse_program(f"G21 G90\n{code}\nM2\n")
    err = info.value.errors[0]
    assert (err.line, err.col) == (2, 1)
    assert f"{code} needs an axis word (all axes missing with G52 or G92)" in err.message


@pytest.mark.skipif(RS274 is None, reason="LinuxCNC's rs274 is not installed (make test installs it as root)")
@pytest.mark.parametrize("code", ["G92", "G52"])
def test_linuxcnc_refuses_the_same_bare_g92_and_g52(code: str) -> None:
    theirs, ours = refused_alike(f"G21 G90\n{code}\nM2\n")
    assert theirs == ours == code
