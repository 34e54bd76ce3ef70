"""M66 as the interpreter reads it (LinuxCNC 2.9's rules): the motion stopped, #5399 the
awaited value until the machine's is known, -1 after a timeout, and the refusals."""

from __future__ import annotations

import pytest

from planner.core.errors import ProgramError
from planner.core.program import EventKind, TableRef
from planner.gcode.interpreter import parse_program
from tools.linuxcnc_oracle import RS274, refused_alike, run_linuxcnc


def _debug(program) -> list[str]:
    return [e.message.strip() for e in program.events if e.kind is EventKind.MESSAGE]


def _with_inputs(*numbers: int):
    from dataclasses import replace

    from planner.core.machine import MachineSpec

    return replace(MachineSpec.default(), input_bits={n: (0, 16 + n, f"in{n}") for n in numbers})


WAITS = "G21 G90 F600\nG1 X10\nM66 P1 L3 Q5\n(DEBUG,#5399)\nG1 X[10 + #5399]\nM66 P0 L0\n(DEBUG,#5399)\nM2\n"


def test_m66_stops_the_motion_and_5399_reads_the_awaited_value_until_known() -> None:
    p = parse_program(WAITS, machine=_with_inputs(0, 1))
    assert [(q.line, q.number, q.mode.name, q.timeout_s, q.known) for q in p.inputs] == [
        (3, 1, "HIGH", 5.0, False), (6, 0, "IMMEDIATE", 0.0, False)]
    waits = [e for e in p.events if e.kind is EventKind.INPUT]
    assert [(e.after_move, e.payload) for e in waits] == [(0, TableRef(0)), (1, TableRef(1))]
    assert all(e.stops for e in waits)
    assert _debug(p) == ["1.000000", "0.000000"]
    assert p.moves[1].end[0] == 11.0


def test_m66_with_the_machine_s_values_and_a_timeout() -> None:
    p = parse_program(WAITS, machine=_with_inputs(0, 1), input_results=[-1.0, 1.0])
    assert _debug(p) == ["-1.000000", "1.000000"]
    assert p.moves[1].end[0] == 9.0
    assert [q.known for q in p.inputs] == [True, True]


@pytest.mark.parametrize(("text", "col_word", "reason"), [
    ("M66 P1 L3\n", "L3", "zero timeout with a wait mode other than immediate"),
    ("M66 L0\n", "M66", "needs a P word"),
    ("M66 P7 L0\n", "P7", "no such digital input on this machine (P0, P1)"),
    ("M66 P1 L5 Q1\n", "L5", "the wait mode is 0 (now), 1 (rise), 2 (fall), 3 (high) or 4 (low)"),
    ("M66 E0 L0\n", "E0", "no analog inputs"),
    ("G1 F100 G41.1 D2 X10\nM66 P0 L0\n", "M66", "cutter radius compensation on"),
    ("M62 P1 L0\n", "L0", "L word with no canned cycle, G05.2, G10, G76 or M66"),
])
def test_m66_refusals_name_the_place(text: str, col_word: str, reason: str) -> None:
    with pytest.raises(ProgramError) as info:
        parse_program(text + "M2\n", machine=_with_inputs(0, 1), name="w.ngc")
    err = info.value.errors[0]
    line = text.splitlines()[err.line - 1]
    assert line[err.col - 1:].upper().startswith(col_word), (line, err.col)
    assert reason in err.message


@pytest.mark.skipif(RS274 is None, reason="LinuxCNC's rs274 is not installed (make test installs it as root)")
@pytest.mark.parametrize("text", [
    "M66 P0 L3\nM2\n",
    "M66 L0\nM2\n",
    "G1 F100 G41.1 D2 X10\nM66 P0 L0\nM2\n",
])
def test_linuxcnc_refuses_the_same_m66_blocks(text: str) -> None:
    theirs, ours = refused_alike(text, machine=_with_inputs(0, 1))
    assert ours == theirs


@pytest.mark.skipif(RS274 is None, reason="LinuxCNC's rs274 is not installed (make test installs it as root)")
def test_an_immediate_read_reads_as_linuxcnc_s_stand_alone_interpreter() -> None:
    text = "G21 F600\nM66 P0 L0\n(DEBUG,#5399)\nG1 X[5 + #5399]\nM2\n"
    theirs = run_linuxcnc(text)
    assert not theirs.error
    ours = parse_program(text, machine=_with_inputs(0))
    assert [m.end[0] for m in ours.moves] == [c[1][0] for c in theirs.motion] == [5.0]

