"""Feed modes as LinuxCNC 2.9 defines them: G94 units per minute, G93 inverse time (each feed
move lasts 1/F minutes and needs its own F), G95 units per revolution of the programmed spindle
speed; G94 and G95 clear the feed rate, G93 does not; G61.1 is shown as the mode in effect."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.core.errors import ProgramError
from planner.core.program import EventKind, SpindleSpeed
from planner.gcode.interpreter import parse_program


def durations(text: str, digits: int = 6) -> list[float]:
    return [round(m.length_mm / m.feed_mm_s, digits) for m in parse_program(text).moves
            if m.kind.name != "RAPID"]


def test_inverse_time_lines_and_arcs_last_one_over_f_minutes() -> None:
    assert durations("G21 G90 G93\nG1 X10 F6\nG1 Y10 F12\nG2 X30 Y10 R10 F2\nG3 X10 Y10 R10 F60\n") == \
        [10.0, 5.0, 30.0, 1.0]


def test_feed_per_revolution_follows_the_programmed_spindle_speed() -> None:
    # 0.1 mm/rev at 1000 rpm = 100 mm/min; at 2000 rpm (an S change) twice as fast
    assert durations("G21 G90 S1000 M3\nG95 F0.1\nG1 X10\nS2000\nG1 X20\n") == [6.0, 3.0]


@pytest.mark.parametrize("text, line, words", [
    ("G21 F100\nG94\nG1 X1\n", 3, "feed rate is zero"),                 # G94 clears F
    ("G21 G94 F100 S100 M3\nG95\nG1 X1\n", 3, "feed rate is zero"),    # so does G95
    ("G21 G93\nG1 X1 F10\nG1 X2\n", 3, "every feed move needs its F word"),
    ("G21 G93 F10\nG81 X1 Z-1 R1 F10\n", 2, "inverse time feed (G93) with canned cycles"),
    ("G21 G95 F0.1\nG1 X1\n", 2, "needs a spindle speed: S is 0"),
    ("G21 G96 M3\n", 1, "G96 needs an S word"),
    ("G21 G96 S100 M3\nG95 F0.1\nG1 X1\n", 3, "G95 feed per revolution in G96"),
    ("G21 G96 S100 M3\nG33.1 Z-5 K1\n", 2, "G33.1 in G96"),
    ("G21 D5 S100\n", 1, "D word with no G41, G41.1, G42, G42.1 or G96"),
])
def test_feed_mode_refusals(text: str, line: int, words: str) -> None:
    with pytest.raises(ProgramError) as exc:
        parse_program(text)
    (err,) = exc.value.errors
    assert err.line == line and words in err.message, err


def test_constant_surface_speed_is_a_mode_the_motion_does_not_see() -> None:
    """G96 D S as LinuxCNC 2.9 reads it (rs274: SET_SPINDLE_MODE(0, D), the moves unchanged):
    S is then a cutting speed, not rpm. This spindle has no speed output to follow X with, so
    the operator is told, and the speed counted (spin-up waits, the panel) is what LinuxCNC
    commands near X0: D, else the spindle's highest; G97 S is rpm again."""
    p = parse_program("G21 F100\nG96 M3 S200\nG1 X10\nG96 D2500 S100\nG1 X20\nG97 S1000\nG1 X30\nM2\n")
    assert [m.end[0] for m in p.moves] == [10, 20, 30]
    assert [e.payload_as(SpindleSpeed).signed_rpm for e in p.events
            if e.kind is EventKind.SPINDLE][:3] == [24000.0, 2500.0, 1000.0]
    notes = [e.message for e in p.events if e.kind is EventKind.MESSAGE]
    assert notes[0].startswith("G96 constant surface speed S200 m/min: this spindle has no speed output")
    assert "S100 m/min up to 2500 rpm" in notes[1] and "counted at 2500 rpm" in notes[1]
    # a surface speed is no spindle speed: S in G96 leaves the speed counted alone
    q = parse_program("G20 F10\nG96 D900 S300 M4\nS400\nG1 X1\n")
    assert [e.payload_as(SpindleSpeed).signed_rpm for e in q.events
            if e.kind is EventKind.SPINDLE] == [-900.0]
    assert "S300 ft/min" in [e.message for e in q.events if e.kind is EventKind.MESSAGE][0]


def test_g93_does_not_clear_f_and_rapids_keep_their_speed() -> None:
    p = parse_program("G21 F300\nG93\nG0 X5\nG94 F300\nG1 X10\n")
    assert [round(m.feed_mm_s, 6) for m in p.moves][1:] == [5.0]


def test_modal_codes_show_feed_and_path_modes() -> None:
    p = parse_program("G21 G93 G61.1\nG1 X1 F10\nG94 G64 F100\nG1 X2\n")
    assert [text.split()[3] + " " + text.split()[-1] for _, text in p.modal] == \
        ["G93 G61.1", "G94 G64"]           # the set-up's entry is replaced: no move came before


@settings(max_examples=100, deadline=None)
@given(f=st.floats(0.01, 1e4), x=st.floats(-1e3, 1e3).filter(lambda v: abs(v) > 1e-3),
       y=st.floats(-1e3, 1e3), scale=st.sampled_from(["G20", "G21"]))
def test_inverse_time_duration_whatever_the_length_and_units(f: float, x: float, y: float,
                                                             scale: str) -> None:
    (d,) = durations(f"{scale} G90 G93\nG1 X{x:.4f} Y{y:.4f} F{f:.6f}\n", digits=15)
    assert d == pytest.approx(60.0 / float(f"{f:.6f}"), rel=1e-9)
