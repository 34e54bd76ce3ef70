"""M67 (with the next move) and M68 (at once) as the interpreter reads them: LinuxCNC's words
and refusals, the motion unchanged, each recorded for the machine (which has no analog
outputs and refuses to run them)."""

from __future__ import annotations

import pytest

from planner.core.program import AnalogOutput
from planner.gcode.interpreter import parse_program
from tests.planner.refusals import refused_at
from tools.linuxcnc_oracle import RS274, motion_alike


def test_analog_outputs_are_recorded_with_their_line_index_and_value() -> None:
    p = parse_program("G21 F100\nM68 E0 Q5\nG1 X1\nM67 E2.4 Q-1.5\nG1 X2\nM68 E1\nM2\n")
    assert p.analog_outputs == (AnalogOutput("M68", 2, 0, 5.0), AnalogOutput("M67", 4, 2, -1.5),
                                AnalogOutput("M68", 6, 1, -1.0))       # LinuxCNC: no Q sets -1
    assert [m.end[0] for m in p.moves] == [1.0, 2.0]
    assert parse_program("G21 G1 X1 F100\nM2\n").analog_outputs == ()


@pytest.mark.parametrize(("text", "col_word", "reason"), [
    ("M67 Q1\n", "M67", "M67 needs an E word"),
    ("M68 E-1 Q1\n", "E-1", "M68 needs an E word"),
    ("G21 F100 G41.1 D2\nG1 X5\nM68 E0 Q1\n", "M68", "cannot set an analog output with cutter compensation"),
    ("M62 P0 E1\n", "E1", "E word with no G33, G33.1, G76, M67 or M68"),
])
def test_refusals_name_the_word_and_the_reason(text: str, col_word: str, reason: str) -> None:
    refused_at(text, col_word, reason)


@pytest.mark.skipif(RS274 is None, reason="LinuxCNC's rs274 is not installed (make test installs it as root)")
def test_the_motion_around_them_is_what_linuxcnc_makes() -> None:
    motion_alike("G21 F100\nM68 E0 Q5\nG1 X1\nM67 E3 Q2.5 G1 Y4\nG0 Z2\nM2\n")
