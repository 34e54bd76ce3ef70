"""The one model of coordinates (``planner.core.frames.Frame``) against the interpreter, over
programs mixing the coordinate systems G54-G59.3 with their XY rotation (G10 L2 R), G52, G92
and the tool length offsets G43 / G43 H / G43.1 / G43.2 / G49 with tools of positive and
negative length, at scales from x0.001 to x1000:

- what the Work DRO reads (the program's frame at a move, ``Program.frame_at``, applied to the
  machine position) is the point the program asked for: the tool tip in program coordinates;
- touch-off (``Frame.origin_for``, LinuxCNC's G10 L20) at any point, then ``G0`` to the touched
  value, lands at that point in machine coordinates.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.core.frames import SYSTEM_NAMES, Frame, system_parameter_base
from planner.core.machine import MachineSpec
from planner.core.tools import Tool, ToolTable
from planner.gcode.codes import G
from planner.gcode.interpreter import parse_program

SCALES = (0.001, 1.0, 1000.0)
AXES = ("X", "Y", "Z")


def _tools(l1: float, l2: float) -> ToolTable:
    return ToolTable().with_tool(Tool(1, 1, (("Z", l1),), 6.0)).with_tool(Tool(2, 2, (("Z", l2),), 3.0))


def n(v: float) -> str:
    """A G-code number (no exponent: an E would be a word)."""
    return f"{v:.10f}"


Case = tuple[str, list[tuple[int, tuple[float, float, float]]], float, ToolTable, int]


@st.composite
def programs(draw: st.DrawFn) -> Case:
    """(text, [(line, programmed X Y Z) of each move], scale, tool table, tool in the spindle)."""
    scale = draw(st.sampled_from(SCALES))
    value = st.floats(-50.0, 50.0, allow_nan=False).map(lambda v: round(v * scale, 6))
    l1 = round(draw(st.floats(0.5, 40.0)) * scale, 6)
    l2 = round(-draw(st.floats(0.5, 40.0)) * scale, 6)
    lines = ["G21 G90 G17 G40 G80"]
    moves: list[tuple[int, tuple[float, float, float]]] = []
    for _ in range(draw(st.integers(3, 14))):
        kind = draw(st.sampled_from(["system", "g52", "g92", "g92.1", "g43", "g43h", "g43.1", "g43.2", "g49",
                                     "move", "move", "move"]))
        if kind == "system":
            p = draw(st.integers(1, 9))
            r = draw(st.sampled_from([0.0, 0.0, 30.0, -45.0, 90.0, 12.5]))
            lines.append(f"G10 L2 P{p} X{n(draw(value))} Y{n(draw(value))} Z{n(draw(value))} R{r:g}")
            lines.append(SYSTEM_NAMES[p - 1])
        elif kind in ("g52", "g92"):
            lines.append(f"{kind.upper()} X{n(draw(value))} Y{n(draw(value))} Z{n(draw(value))}")
        elif kind == "g92.1":
            lines.append("G92.1")
        elif kind == "g43":
            lines.append("G43")
        elif kind == "g43h":
            lines.append(f"G43 H{draw(st.integers(1, 2))}")
        elif kind == "g43.1":
            lines.append(f"G43.1 Z{n(draw(value))}")
        elif kind == "g43.2":
            lines.append(f"G43.2 H{draw(st.integers(1, 2))}")
        elif kind == "g49":
            lines.append("G49")
        else:
            target = (draw(value), draw(value), draw(value))
            g = draw(st.sampled_from([0, 1]))
            lines.append(f"G{g} X{n(target[0])} Y{n(target[1])} Z{n(target[2])} F600")
            moves.append((len(lines), target))
    lines.append("M2")
    return "\n".join(lines) + "\n", moves, scale, _tools(l1, l2), draw(st.sampled_from([1, 2]))


@settings(max_examples=120, deadline=None)
@given(programs())
def test_the_work_dro_reads_the_programmed_point_after_every_line(case) -> None:
    text, moves, scale, tools, in_spindle = case
    prog = parse_program(text, tools=tools, tool_in_spindle=in_spindle)
    by_line = {m.line: m for m in prog.moves}
    checked = 0
    for line, target in moves:
        move = by_line.get(line)
        if move is None:              # no motion (already there)
            continue
        dro = prog.frame_at(move.index).to_program(move.end)
        np.testing.assert_allclose(dro, target, atol=1e-9 * max(scale, 1.0) * 1000, rtol=1e-12)
        checked += 1
    assert checked or not any(by_line)


@st.composite
def touch_offs(draw: st.DrawFn) -> tuple[Frame, np.ndarray, int, float, float]:
    """A frame in force (G54 with a rotation, G92, a tool of either sign), a machine point,
    an axis and the value the tip should read there."""
    scale = draw(st.sampled_from(SCALES))
    value = st.floats(-100.0, 100.0, allow_nan=False).map(lambda v: round(v * scale, 6))
    g5x = (draw(value), draw(value), draw(value))
    g92 = draw(st.sampled_from([(0.0, 0.0, 0.0), (draw(value), draw(value), draw(value))]))
    tool = (0.0, 0.0, draw(st.sampled_from([0.0, 1.0, -1.0])) * round(draw(st.floats(0.5, 40.0)) * scale, 6))
    rotation = draw(st.sampled_from([0.0, 30.0, -45.0, 90.0, 12.5]))
    frame = Frame(AXES, g5x, g92, tool, rotation, 1)
    point = np.array([draw(value), draw(value), draw(value)])
    return frame, point, draw(st.integers(0, 2)), draw(value), scale


@settings(max_examples=200, deadline=None)
@given(touch_offs())
def test_touch_off_then_g0_to_the_touched_value_lands_there(case) -> None:
    frame, point, axis, value, scale = case
    origin = frame.origin_for(point, axis, value)
    touched = Frame(AXES, origin, frame.g92, frame.tool, frame.rotation_deg, 1)
    tol = 1e-9 * max(scale, 1.0) * 1000
    reads = touched.to_program(point)
    assert reads[axis] == pytest.approx(value, abs=tol)                       # the tip reads it
    others = [k for k in range(3) if k != axis]
    np.testing.assert_allclose(reads[others], frame.to_program(point)[others], atol=tol)   # the rest kept
    # the interpreter, started elsewhere with the offsets the panel has in force, goes there
    # with G0 to what the tip reads (the touched value on its axis): the touched point
    machine = replace(MachineSpec.default(), work_offsets={"G54": origin})
    parameters = {system_parameter_base(1) + 9: frame.rotation_deg, 5210: 1.0 if any(frame.g92) else 0.0,
                  **{5211 + k: frame.g92[k] for k in range(3)}}
    far = point + np.array([7.0, -5.0, 3.0]) * scale
    words = [value if k == axis else float(reads[k]) for k in range(3)]
    prog = parse_program("G21 G90 G54\nG0 " + " ".join(f"{a}{n(w)}" for a, w in zip(AXES, words)) + "\nM2\n",
                         machine=machine, start_position=far, parameters=parameters,
                         tool_offset=(G.G43_1, frame.tool))
    assert len(prog.moves) == 1
    np.testing.assert_allclose(prog.moves[-1].end, point, atol=tol)


def test_the_frame_at_a_stop_is_what_the_lines_before_it_set() -> None:
    """Stopped on a line before move k: an offset set on a later line for move k is not in
    force yet (the G43 after an M6), one set on an earlier line is (a G43 before an M0)."""
    from planner.core.tools import Tool, ToolTable
    from planner.gcode.interpreter import parse_program

    table = ToolTable({1: Tool(1, 1, (("Z", 5.0),), 0.0, ""), 2: Tool(2, 2, (("Z", -12.5),), 0.0, "")})
    prog = parse_program("G21 G90\nG43 H1\nG0 Z20\nM0\nG43 H2\nG0 Z30\nM2\n", tools=table, tool_in_spindle=1)
    k = len(prog.moves) - 1                        # the move after the M0 and the second G43
    assert prog.frame_before(k, 4).tool[2] == 5.0          # at the M0 (line 4): H1 still
    assert prog.frame_before(k, 5).tool[2] == -12.5        # at line 5 the G43 H2 is in
    assert prog.frame_at(k).tool[2] == -12.5
