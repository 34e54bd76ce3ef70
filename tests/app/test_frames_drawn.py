"""One coordinate model from the interpreter to the screen: under G10 L2 R (a turned system),
G92, G52 and G43 every move's end is drawn where the program put it, which is where the DRO
reads the machine standing there (``Frame.to_program`` of the program's frame at that move),
and where the preview's and the backplot's tool marker are put (both show the DRO's work
position)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from app.toolpath import build_toolpath
from planner.core.tools import parse_tbl
from planner.gcode.interpreter import parse_program

TOOLS = parse_tbl("T1 P1 Z10 D6\nT2 P2 X0.5 Y-0.25 Z-3.5 D3\n", "tools.tbl")


def _num(v: float) -> str:
    return f"{v:.6f}"


@st.composite
def programs(draw: st.DrawFn) -> tuple[str, list[tuple[float, float, float]]]:
    """A program of absolute moves with offset changes between them, at one of the scales
    x0.001 to x1000, and the programmed end point of each move (program coordinates)."""
    scale = draw(st.sampled_from([0.001, 1.0, 1000.0]))
    coord = st.floats(-50.0, 50.0, allow_nan=False).map(lambda v: round(v * scale, 6))
    lines = ["G21 G90 G17 F600"]
    ends: list[tuple[float, float, float]] = []
    here: tuple[float, float, float] | None = None
    for _ in range(draw(st.integers(2, 12))):
        change = draw(st.sampled_from(["move", "move", "g10", "g92", "g52", "g43", "g49", "system",
                                       "g92.1"]))
        if change == "g10":
            p = draw(st.integers(1, 2))
            x, y, z = draw(coord), draw(coord), draw(coord)
            r = draw(st.floats(-180.0, 180.0, allow_nan=False).map(lambda v: round(v, 3)))
            lines.append(f"G10 L2 P{p} X{_num(x)} Y{_num(y)} Z{_num(z)} R{r}")
        elif change in ("g92", "g52"):
            if here is None:            # G92 names where the tool stands: it must have moved
                continue
            x, y, z = draw(coord), draw(coord), draw(coord)
            lines.append(f"{change.upper()} X{_num(x)} Y{_num(y)} Z{_num(z)}")
        elif change == "g43":
            lines.append(f"G43 H{draw(st.integers(1, 2))}")
        elif change == "g49":
            lines.append("G49")
        elif change == "g92.1":
            lines.append("G92.1")
        elif change == "system":
            lines.append(draw(st.sampled_from(["G54", "G55"])))
        else:
            end = (draw(coord), draw(coord), draw(coord))
            lines.append(f"G{draw(st.integers(0, 1))} X{_num(end[0])} Y{_num(end[1])} Z{_num(end[2])}")
            ends.append(end)
            here = end
    return "\n".join(lines) + "\nM2\n", ends


@given(programs())
def test_every_move_is_drawn_and_read_where_the_program_put_it(case) -> None:  # type: ignore[no-untyped-def]
    text, ends = case
    program = parse_program(text, "frames.ngc", tools=TOOLS)
    path = build_toolpath(program)
    # a move of no length is dropped: each move kept is compared with the end programmed on
    # its own line
    assert len(program.moves) <= len(ends)
    drawn, read, wanted = [], [], []
    for k, move in enumerate(program.moves):
        drawn.append(path.all.points[path.move_points(k)[1] - 1])
        read.append(program.frame_at(k).to_program(move.end))       # the DRO standing there
        assert path.frame_of(k) == program.frame_at(k)
        wanted.append(_programmed_on(text, move.line))
    if not wanted:
        return
    tol = 1e-9 * max(1.0, float(np.max(np.abs(wanted))))
    np.testing.assert_allclose(drawn, wanted, atol=tol, rtol=0)
    np.testing.assert_allclose(read, wanted, atol=tol, rtol=0)


def _programmed_on(text: str, line: int) -> tuple[float, float, float]:
    words = dict((w[0], float(w[1:])) for w in text.splitlines()[line - 1].split()[1:])
    return words["X"], words["Y"], words["Z"]


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
