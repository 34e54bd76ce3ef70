"""One coordinate model from the interpreter to the screen: under G10 L2 R (a turned system),
G92, G52 and G43 every move's end is drawn where the program put it, which is where the DRO
reads the machine standing there (``Frame.to_program`` of the program's frame at that move),
and where the preview's and the backplot's tool marker are put (both show the DRO's work
position)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings

from app.toolpath import build_toolpath
from planner.core.tools import parse_tbl
from planner.gcode.interpreter import parse_program
from tests.planner.test_frame_model import programs

TOOLS = parse_tbl("T1 P1 Z10 D6\nT2 P2 X0.5 Y-0.25 Z-3.5 D3\n", "tools.tbl")


@settings(max_examples=120, deadline=None)
@given(programs())
def test_every_move_is_drawn_and_read_where_the_program_put_it(case) -> None:  # type: ignore[no-untyped-def]
    """The programs of the frame model's test (every coordinate system with its rotation, G52,
    G92, G43 / G43 H / G43.1 / G43.2 / G49, tools of both signs, x0.001 to x1000): each move's
    end as the preview and the backplot draw it (the tool path) is the point its line asked
    for, and so is what the DRO reads with the machine standing there."""
    text, moves, scale, tools, in_spindle = case
    program = parse_program(text, tools=tools, tool_in_spindle=in_spindle)
    path = build_toolpath(program)
    by_line = {m.line: m for m in program.moves}
    checked = 0
    tol = 1e-9 * max(scale, 1.0) * 1000
    for line, target in moves:
        move = by_line.get(line)
        if move is None:              # no motion (already there)
            continue
        k = move.index
        assert path.frame_of(k) == program.frame_at(k)
        drawn = path.all.points[path.move_points(k)[1] - 1]
        np.testing.assert_allclose(drawn, target, atol=tol, rtol=1e-12)
        np.testing.assert_allclose(program.frame_at(k).to_program(move.end), target, atol=tol, rtol=1e-12)
        checked += 1
    assert checked or not by_line


def test_a_turned_system_with_g92_and_a_tool_offset_is_drawn_in_program_coordinates() -> None:
    """The case by hand: G55 turned 30 degrees at X100 Y50, G92 shifting X by 5, T1's 10 mm
    length: the square programmed at X0-10 Y0-10 is drawn there, not where the machine runs it."""
    text = ("G21 G90 F600\nG10 L2 P2 X100 Y50 Z0 R30\nG55\nG0 X0 Y0 Z0\nG92 X-5 Y0 Z0\nG43 H1\n"
            "G1 X10 Y0 Z1\nG1 X10 Y10 Z1\nG1 X0 Y10 Z1\nM2\n")
    program = parse_program(text, "square.ngc", tools=TOOLS)
    path = build_toolpath(program)
    ends = [path.all.points[path.move_points(k)[1] - 1] for k in range(len(program.moves))]
    np.testing.assert_allclose(ends, [(0, 0, 0), (10, 0, 1), (10, 10, 1), (0, 10, 1)], atol=1e-9)
    machine = program.moves[1].end           # X10 Y0 of the turned, shifted system, tool 10 long
    np.testing.assert_allclose(machine, (100 + 15 * np.cos(np.pi / 6), 50 + 15 * np.sin(np.pi / 6), 11),
                               atol=1e-9)
    assert program.frame_at(1).rotation_deg == pytest.approx(30.0)
