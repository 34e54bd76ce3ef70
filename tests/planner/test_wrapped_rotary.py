"""Wrapped rotary axes (LinuxCNC's WRAPPED_ROTARY, ``wrapped = true`` on a rotary axis): an
absolute target is reached the short way (a turn of at most half a turn), incremental moves
go as programmed, the travel limits do not apply, and the DRO reads modulo 360."""

from __future__ import annotations

from dataclasses import replace

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.widgets.dro import format_position
from planner.core.machine import load_machine
from planner.gcode.interpreter import parse_program
from planner.geometry.softlimits import check_program
from resources import shipped_machine

PAPER = load_machine(str(shipped_machine("paper_yzca")))
C = PAPER.axis_names.index("C")
WRAPPED = replace(PAPER, axes=tuple(replace(a, wrapped=a.name == "C") for a in PAPER.axes))


@settings(max_examples=200, deadline=None)
@given(st.lists(st.floats(-5000.0, 5000.0, allow_nan=False).map(lambda v: round(v, 3)),
                min_size=1, max_size=12))
def test_absolute_targets_go_the_short_way_and_read_in_0_360(targets: list[float]) -> None:
    text = "G21 G90\n" + "".join(f"G0 C{t:.3f}\n" for t in targets) + "M2\n"
    prog = parse_program(text, machine=WRAPPED)
    by_line = {m.line: m for m in prog.moves}
    here = 0.0
    for line, target in enumerate(targets, start=2):
        move = by_line.get(line)
        if move is None:              # already there, modulo 360
            assert (target - here) % 360.0 == pytest.approx(0.0, abs=1e-6) or \
                (target - here) % 360.0 == pytest.approx(360.0, abs=1e-6)
            continue
        turn = move.end[C] - move.start[C]
        assert -180.0 < turn <= 180.0 + 1e-9                           # the short way
        assert (move.end[C] - target) % 360.0 == pytest.approx(0.0, abs=1e-6) or \
            (move.end[C] - target) % 360.0 == pytest.approx(360.0, abs=1e-6)
        shown = float(format_position(move.end[C], True, True).rstrip("°"))
        assert 0.0 <= shown < 360.0
        assert shown == pytest.approx(target % 360.0, abs=1e-3) or shown == pytest.approx(0.0, abs=1e-3)
        here = move.end[C]


def test_incremental_moves_go_as_programmed_and_the_travel_does_not_apply() -> None:
    prog = parse_program("G21 G91\nG0 C1000\nG0 C-30\nM2\n", machine=WRAPPED)
    assert [m.end[C] for m in prog.moves] == [1000.0, 970.0]
    assert not check_program(prog, WRAPPED)
    # the same on the axis as configured (not wrapped): absolute goes the long way, and the
    # travel holds it
    prog = parse_program("G21 G90\nG0 C350\nG0 C10\nM2\n", machine=PAPER)
    assert [m.end[C] for m in prog.moves] == [350.0, 10.0]
    prog = parse_program("G21 G90\nG0 C170\nG0 C350\nG0 C10\nG0 C350\nM2\n", machine=WRAPPED)
    # +170, then exactly half a turn (+180), then on past 360, then back the short way
    assert [m.end[C] for m in prog.moves] == [170.0, 350.0, 370.0, 350.0]
    prog = parse_program("G21 G90\nG0 C350\nM2\n", machine=WRAPPED)
    assert prog.moves[0].end[C] == -10.0                                    # 350 is 10 back
