"""M48-M53 as LinuxCNC 2.9 reads them, and the overrides a program's moves run with: tapping
(G74/G84, G33.1) turns the feed and spindle overrides off for its moves, as LinuxCNC does,
M49/M50 P0/M51 P0 turn them off until M48/M50/M51 (or M72) turn them on."""

from __future__ import annotations

import pytest

from planner.core.errors import ProgramError
from planner.core.program import FEED_HOLD_DEFERRED, FEED_OVERRIDE_OFF, SPINDLE_OVERRIDE_OFF, EventKind
from planner.gcode.interpreter import parse_program
from planner.geometry.resume import remaining_program
from tools.linuxcnc_oracle import RS274, motion_alike, refused_alike

BOTH = FEED_OVERRIDE_OFF | SPINDLE_OVERRIDE_OFF
TAP = BOTH | FEED_HOLD_DEFERRED      # a tap's moves: the operator's feed hold waits for its end
NEEDS_RS274 = pytest.mark.skipif(RS274 is None,
                                 reason="LinuxCNC's rs274 is not installed (make test installs it as root)")


def locks(text: str) -> list[int]:
    got = parse_program(text).override_locks
    assert got is not None
    return [int(b) for b in got]


def test_m49_m50_m51_and_m48_switch_the_overrides_of_the_moves_that_follow() -> None:
    text = ("G21 F600\nG1 X1\nM49\nG1 X2\nM50\nG1 X3\nM48\nM51 P0\nG1 X4\nM51 P1 G1 X5\nM50 P0\n"
            "G1 X6\nM48\nG1 X7\nM2\n")
    assert locks(text) == [0, BOTH, SPINDLE_OVERRIDE_OFF, SPINDLE_OVERRIDE_OFF, 0, FEED_OVERRIDE_OFF, 0]


def test_the_panel_sees_the_overrides_off_in_the_modes() -> None:
    p = parse_program("G21 F600\nM49\nG1 X1\nM50\nG1 X2\nM51\nM50 P0\nG1 X3\nM48\nG1 X4\nM2\n")
    assert [p.modal_at_move(i).split(" G64")[1] for i in range(4)] == [" M49", " M51 P0", " M50 P0", ""]


def test_tapping_turns_both_overrides_off_for_its_feed_moves_only() -> None:
    p = parse_program("G21 G90 G0 X0 Y0 Z10\nS500 M3\nG84 X10 Z-12 R2 F625 L1\nX20\nG80\n"
                      "G33.1 Z-8 K1.25\nG0 Z10\nM2\n")
    got = p.override_locks
    assert got is not None
    feeds_in_taps = [i for i, m in enumerate(p.moves) if m.kind.name == "LINE"]
    assert [i for i, b in enumerate(got) if b] == feeds_in_taps
    assert all(int(got[i]) == TAP for i in feeds_in_taps)


def test_after_a_tap_the_program_state_comes_back() -> None:
    # M50 P0 before the cycle: after the tap the feed override stays off, the spindle's comes back
    got = locks("G21 G90 G0 X0 Y0 Z10\nS500 M3\nM50 P0\nG84 X10 Z-12 R2 F625\nG80\nG1 X30\nM2\n")
    assert got == [0, FEED_OVERRIDE_OFF, FEED_OVERRIDE_OFF, TAP, TAP, FEED_OVERRIDE_OFF]


def test_m72_restores_the_overrides_saved_by_m70() -> None:
    assert locks("G21 F600\nM70\nM49\nG1 X1\nM72\nG1 X2\nM2\n") == [BOTH, 0]


def test_a_restart_inside_a_tap_keeps_the_overrides_off() -> None:
    p = parse_program("G21 G90 G0 X0 Y0 Z10\nS500 M3\nG84 X10 Z-12 R2 F625\nG80\nG1 X30 F900\nM2\n")
    tap_in = next(i for i, m in enumerate(p.moves) if m.kind.name == "LINE")
    rest = remaining_program(p, tap_in, 3.0)
    got = rest.override_locks
    assert got is not None
    assert [int(b) for b in got] == [TAP, TAP, 0]


@pytest.mark.parametrize(("text", "word", "why"), [
    # deliberately: LinuxCNC reads it (its adaptive feed input unconnected is 1), but a program
    # asking for adaptive feed (a torch height control, a load feedback) expects it to act
    ("M52 P1", "M52", "adaptive feed"),
    ("M52", "M52", "adaptive feed"),
    ("M48 M49", "M49", "same modal group"),
    ("G41.1 D2 G1 X5 Y5\nM49", "M49", "cannot disable overrides with cutter radius compensation on"),
    ("G41.1 D2 G1 X5 Y5\nM50 P1", "M50", "cannot enable overrides with cutter radius compensation on"),
])
def test_refusals(text: str, word: str, why: str) -> None:
    with pytest.raises(ProgramError) as info:
        parse_program("G21 F600\n" + text + "\nM2\n")
    err = info.value.errors[0]
    line = ("G21 F600\n" + text).splitlines()[err.line - 1]
    assert line[err.col - 1:].startswith(word)
    assert why in err.message


def test_m52_p0_and_m53_change_nothing_here() -> None:
    # adaptive feed is off already; M53 is the feed stop switch, which this machine does not
    # have (the panel's feed hold always works: it is LinuxCNC's pause, which M53 leaves alone)
    p = parse_program("G21 F600\nM52 P0\nM53 P0\nG1 X1\nM53 P1\nG1 X2\nM2\n")
    assert p.override_locks is None
    assert [e.kind for e in p.events if e.kind is EventKind.OVERRIDES] == []


@NEEDS_RS274
@pytest.mark.parametrize("text", [
    "G21 F600\nM49\nG1 X2\nM50\nG1 X3\nM48\nM51 P0\nG1 X4 Y1\nM51 P1 G1 X5\nM50 P0\nG1 X6\nM48\n"
    "M52 P0\nM53 P1\nG1 X7\nM53 P0\nG0 Z3\nM2\n",
    "G21 G90 G0 X0 Y0 Z10\nS500 M3\nM49\nG84 X10 Z-12 R2 F625\nG80\nM48\nG33.1 Z-8 K1.25\nG0 Z10\nM2\n",
])
def test_linuxcnc_reads_these_alike(text: str) -> None:
    motion_alike(text)


@NEEDS_RS274
@pytest.mark.parametrize("text", [
    "G21 F600\nG41.1 D2 G1 X5 Y5\nX10\nM48\nG40 G1 X0\nM2\n",
    "G21 F600\nG41.1 D2 G1 X5 Y5\nX10\nM51 P0\nG40 G1 X0\nM2\n",
])
def test_linuxcnc_refuses_these_at_the_same_block(text: str) -> None:
    theirs, ours = refused_alike(text)
    assert theirs == ours
