"""G38.2-G38.5 straight probing as the interpreter reads it (LinuxCNC 2.9's rules): the probe
armed at rest before its move and read at rest after it, #5061-#5070, the move ending where
the machine stopped when the result is known, and the refusals with their place."""

from __future__ import annotations

import pytest

from planner.core.errors import ProgramError
from planner.core.program import EventKind, ProbeResult, TableRef
from planner.gcode.interpreter import parse_program
from tools.linuxcnc_oracle import RS274, refused_alike


def _debug(program) -> list[str]:
    return [e.message.strip() for e in program.events if e.kind is EventKind.MESSAGE]


PROGRAM = """G21 G90 G54
G0 X10 Y5 Z10
G38.2 Z-20 F100
(DEBUG,#5061 #5062 #5063 #5070)
G0 Z[#5063 + 2]
M2
"""


def test_an_unknown_result_is_read_as_linuxcncs_preview_reads_it() -> None:
    """Before the machine has probed, the move runs to its programmed end point, #5061-#5063
    hold that point and #5070 is 0, as LinuxCNC's own preview (and rs274) read a probe."""
    p = parse_program(PROGRAM)
    probe = p.probes[0]
    assert (probe.code, probe.line, probe.known, probe.name) == (382, 3, False, "G38.2")
    assert probe.move_index == 1 and p.moves[1].end.tolist() == [10.0, 5.0, -20.0]
    assert p.moves[1].feed_mm_s == pytest.approx(100 / 60)
    assert _debug(p) == ["10.000000 5.000000 -20.000000 0.000000"]
    assert p.moves[2].end.tolist() == [10.0, 5.0, -18.0]


def test_a_loop_probing_while_it_touches_ends_when_read_before_the_run() -> None:
    """LinuxCNC's grid probing sample (nc_files/smartprobe.ngc) goes round ``while [#5070 NE 0]``
    probing away and across until nothing is in the way; read before any result (check,
    preview) it must end after one pass, as it does in LinuxCNC, not run forever."""
    text = ("G20 F20\n#5070=1\no4 while [#5070 NE 0]\nG38.5 Z1.1\nG38.3 X0.5\no4 endwhile\n"
            "G38.2 Z-0.1\nM2\n")
    p = parse_program(text)
    assert [q.name for q in p.probes] == ["G38.5", "G38.3", "G38.2"]


def test_the_probe_stops_the_motion_before_and_after_its_move() -> None:
    p = parse_program(PROGRAM)
    probing = (EventKind.PROBE_START, EventKind.PROBE)
    kinds = [(e.kind, e.after_move, e.payload) for e in p.events if e.kind in probing]
    assert kinds == [(EventKind.PROBE_START, 0, TableRef(0)), (EventKind.PROBE, 1, TableRef(0))]
    assert all(e.stops for e in p.events if e.kind in (EventKind.PROBE_START, EventKind.PROBE))


def test_a_known_result_sets_the_parameters_and_ends_the_move_where_the_machine_stopped() -> None:
    result = ProbeResult(True, (10.0, 5.0, -4.2), (10.0, 5.0, -4.25))
    p = parse_program(PROGRAM, probe_results=[result])
    assert p.probes[0].known
    assert p.moves[1].end.tolist() == [10.0, 5.0, -4.25]
    assert p.moves[1].length_mm == pytest.approx(14.25)
    assert _debug(p) == ["10.000000 5.000000 -4.200000 1.000000"]
    assert p.moves[2].start.tolist() == [10.0, 5.0, -4.25]
    assert p.moves[2].end.tolist() == pytest.approx([10.0, 5.0, -2.2])


def test_no_contact_is_5070_zero_and_the_next_probe_is_assumed_again() -> None:
    text = "G21 G90\nG0 Z10\nG38.3 Z0 F60\n(DEBUG,#5070)\nG38.3 Z-5\n(DEBUG,#5070)\nM2\n"
    p = parse_program(text, probe_results=[ProbeResult(False, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0))])
    assert _debug(p) == ["0.000000", "0.000000"]
    assert [q.known for q in p.probes] == [True, False]


def test_probe_positions_are_in_the_coordinates_in_use() -> None:
    """#5061-#5063 take off the work offset, G92 and the tool length offset, and undo an XY
    rotation of the coordinate system, as LinuxCNC's canon gives them to the interpreter."""
    text = ("G21 G90\nG10 L2 P1 X100 Y50 Z-20 R90\nG54\nG43.1 Z3\nG0 X0 Y0 Z10\n"
            "G38.2 X10 F100\n(DEBUG,#5061 #5062 #5063)\nM2\n")
    p = parse_program(text)
    # no result: read as run to the programmed point, at machine (100, 60, -7)
    assert _debug(p) == ["10.000000 0.000000 10.000000"]
    assert p.moves[p.probes[0].move_index].end.tolist() == pytest.approx([100.0, 60.0, -7.0])
    # the machine touched at (100, 55, -8): 5 mm from the origin along the turned X axis, and
    # Z -8 less the offset -20 and the tool's 3
    p = parse_program(text, probe_results=[ProbeResult(True, (100.0, 55.0, -8.0), (100.0, 54.9, -8.0))])
    assert [float(v) for v in _debug(p)[0].split()] == pytest.approx([5.0, 0.0, 9.0], abs=1e-9)


def test_g38_is_modal_an_axis_word_alone_probes_again() -> None:
    p = parse_program("G21 G90 F100\nG38.3 Z-5\nZ-10\nM2\n")
    assert [q.line for q in p.probes] == [2, 3]


def test_inch_programs_report_in_inches() -> None:
    p = parse_program("G20 G90 F10\nG38.2 Z-1\n(DEBUG,#5063)\nM2\n",
                      probe_results=[ProbeResult(True, (0.0, 0.0, -12.7), (0.0, 0.0, -12.8))])
    assert _debug(p) == ["-0.500000"]


@pytest.mark.parametrize(("text", "line_no", "col_word", "reason"), [
    ("G21 F100 G91\nG38.2 Z0\nM2\n", 2, "G38.2", "start point too close to probe point"),
    ("G21\nG38.2 Z-5\nM2\n", 2, "G38.2", "zero feed rate"),
    ("G21 F100\nG41.1 D4\nG1 X10\nG38.2 Z-5\nM2\n", 4, "G38.2", "cutter radius compensation"),
    ("G21 S1000 M3\nG95 F0.1\nG38.2 Z-5\nM2\n", 3, "G38.2", "feed per revolution"),
    ("G21\nG93 G38.2 Z-5 F10\nM2\n", 2, "G38.2", "inverse time"),
    ("G21 F100\nG53 G38.2 Z-5\nM2\n", 2, "G53", "G00 or G01"),
])
def test_refusals_name_the_place_and_the_reason(text: str, line_no: int, col_word: str, reason: str) -> None:
    with pytest.raises(ProgramError) as info:
        parse_program(text, name="probe.ngc")
    err = info.value.errors[0]
    assert (err.file, err.line) == ("probe.ngc", line_no)
    assert text.splitlines()[line_no - 1][err.col - 1:].upper().startswith(col_word)
    assert reason in err.message


def test_g38_3_to_where_the_tool_is_moves_nothing_but_still_reads_the_probe() -> None:
    p = parse_program("G21 F100\nG0 X1\nG38.3 X1\n(DEBUG,#5070)\nM2\n")
    assert len(p.moves) == 1 and p.probes[0].move_index == -1
    assert [e.after_move for e in p.events if e.kind in (EventKind.PROBE_START, EventKind.PROBE)] == [0, 0]


@pytest.mark.skipif(RS274 is None, reason="LinuxCNC's rs274 is not installed (make test installs it as root)")
@pytest.mark.parametrize("text", [
    "G21 F100 G91\nG38.2 Z0\nM2\n",
    "G21\nG38.2 Z-5\nM2\n",
    "G21 F100\nG41.1 D4\nG1 X10\nG38.2 Z-5\nM2\n",
    "G21 S1000 M3\nG95 F0.1\nG38.2 Z-5\nM2\n",
])
def test_linuxcnc_refuses_the_same_blocks(text: str) -> None:
    theirs, ours = refused_alike(text)
    assert ours == theirs

