"""G33.1 rigid tapping as the interpreter reads it: feed moves at the pitch (no spindle
encoder), the spindle reversed at the bottom, LinuxCNC's RIGID_TAP call in --canon."""

from __future__ import annotations

import pytest

from planner.core.program import EventKind, SpindleSpeed
from planner.gcode.interpreter import parse_program
from tests.planner.refusals import refused_at
from tools.linuxcnc_oracle import RS274, motion_alike

TAP = "G21 S500 M3\nG0 X5 Z2\nG33.1 X6 Z-10 K1.25 I2\nG0 Z5\nM2\n"


def test_rigid_tapping_runs_as_feed_moves_at_the_pitch_and_backs_out_to_its_start() -> None:
    p = parse_program(TAP)
    into, out = p.moves[1], p.moves[2]
    assert into.end.tolist() == [6.0, 0.0, -10.0] and out.end.tolist() == [5.0, 0.0, 2.0]
    assert into.feed_mm_s == pytest.approx(1.25 * 500 / 60)
    assert out.feed_mm_s == pytest.approx(2 * into.feed_mm_s)
    assert into.exact_stop and out.exact_stop
    spindle = [(e.after_move, e.payload_as(SpindleSpeed).signed_rpm) for e in p.events
               if e.kind is EventKind.SPINDLE and e.line == 3]
    assert spindle == [(1, -1000.0), (2, 500.0)]               # reversed I times faster, then forward
    assert p.taps == (1,)


def test_rigid_tapping_in_inches_and_counterclockwise() -> None:
    p = parse_program("G20 S600 M4\nG33.1 Z-0.5 K0.05\nM2\n")
    assert p.moves[0].feed_mm_s == pytest.approx(0.05 * 25.4 * 600 / 60)
    assert [e.payload_as(SpindleSpeed).signed_rpm for e in p.events
            if e.kind is EventKind.SPINDLE and e.line == 2] == [600.0, -600.0]


@pytest.mark.parametrize(("text", "col_word", "reason"), [
    ("G21\nG33.1 Z-10 K1\n", "G33.1", "spindle not turning"),
    ("G21 S500 M3\nG33.1 Z-10\n", "G33.1", "needs a K word"),
    ("G21 S500 M3\nG33.1 Z-10 K1 F100\n", "F100", "the feed is the pitch K times the spindle speed"),
    ("G21 S500 M3\nG33.1 Z-10 K0\n", "K0", "must be above 0"),
    ("G21 S500 M3\nG33.1 Z-10 K1\nE2\n", "E2", "E word with no G33, G33.1, G76, M67 or M68"),
])
def test_rigid_tapping_refusals(text: str, col_word: str, reason: str) -> None:
    refused_at(text, col_word, reason)


@pytest.mark.skipif(RS274 is None, reason="LinuxCNC's rs274 is not installed (make test installs it as root)")
@pytest.mark.parametrize("text", [
    TAP,
    "G21 S800 M3\nG10 L2 P1 X10 Y20 Z-5 R30\nG0 X1 Y1 Z3\nG33.1 Z-6 K1\nG0 X4\nG33.1 Z-4 K0.8 I1.5\nM2\n",
    "G20 S600 M4\nG0 Z0.1\nG91 G33.1 Z-0.5 K0.05\nG90 G0 X1\nM2\n",
])
def test_rigid_tapping_is_the_rigid_tap_call_linuxcnc_makes(text: str) -> None:
    motion_alike(text)
