"""The lathe cycles G70 (finishing) and G71/G72 (roughing along Z and along X; .1 without the
pockets, .2 the pockets only) as the interpreter reads them: LinuxCNC 2.9's geometry
(``planner.gcode.g7x``, from ``interp_g7x.cc``) on a profile subroutine, checked move for move
against rs274, its refusals with their place, and the roughing never cutting into the
finishing allowance."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.core.errors import ProgramError
from planner.core.program import MoveKind
from planner.gcode.interpreter import parse_program
from tools.linuxcnc_oracle import RS274, motion_alike

# a turned part: a cone, a round over a shoulder (G2 R), a cove (G3 R), a fillet (A) and a
# chamfer (C) at corners, the X and Z of its blocks falling as it runs
PROFILE = ("O100 SUB\nG0 X0 Z3\nG1 X2 Z0\nG2 X4 Z-2 R2\nG1 Z-5\nG3 X6 Z-7 R2\nG1 Z-10 A0.5\n"
           "G1 X9 C0.3\nG1 Z-14\nG0 X12\nO100 ENDSUB\n")
HEAD = "G21 G18 G90 F300\n"
STEP = "O7 SUB\nG1 X2 Z0\nG1 Z-5\nG1 X6\nG1 Z-10\nG1 X9\nO7 ENDSUB\n"


needs_rs274 = pytest.mark.skipif(RS274 is None, reason="LinuxCNC's rs274 is not installed (make test "
                                                       "installs it as root)")


@needs_rs274
@pytest.mark.parametrize("text", [
    HEAD + PROFILE + "G71 Q100 X12 Z3 D0.3 I0.7 R0.3\nM2\n",
    HEAD + PROFILE + "G71.1 Q100 X12 Z3 D0.3 I0.7\nM2\n",
    HEAD + PROFILE + "G71.2 Q100 X12 Z3 D0.3 I0.5 R0.2\nM2\n",
    HEAD + PROFILE + "G72 Q100 X12 Z3 D0.3 I0.6 R0.3\nM2\n",
    HEAD + PROFILE + "G70 Q100 X12 Z3 D0.6 E0.1 P3\nM2\n",
    # roughing then finishing, and the motion mode after them
    HEAD + PROFILE + "G71 Q100 X12 Z3 D0.5 I1\nG70 Q100 X12 Z3 P1\nG0 X20\nG1 Z5\nM2\n",
    # a bore (X rising), in diameter mode, in inches, in another coordinate system
    HEAD + "O6 SUB\nG1 X10 Z0\nG1 X8 Z-4\nG1 Z-10\nG1 X5 Z-12\nO6 ENDSUB\nG71 Q6 X3 Z2 D0.2 I0.5 R0.3\nM2\n",
    "G21 G18 G7 G90 F200\nO9 SUB\nG1 X8 Z0\nG1 X10 Z-5 A1\nG1 Z-10\nG1 X14 Z-15\nO9 ENDSUB\n"
    "G71 Q9 X20 Z2 D0.2 I0.6 R0.4\nG8\nM2\n",
    "G20 G18 G90 F10\nO5 SUB\nG1 X0.2 Z0\nG1 X0.4 Z-0.5\nG1 Z-1\nG1 X0.6 Z-1.5\nO5 ENDSUB\n"
    "G71 Q5 X0.8 Z0.1 D0.01 I0.05 R0.02\nM2\n",
    "G21 G18 G90 F200\nG10 L2 P2 X5 Z-3\nG55\nO4 SUB\nG1 X2 Z0\nG1 X4 Z-3\nG1 Z-6\nO4 ENDSUB\n"
    "G71 Q4 X6 Z1 D0.1 I0.3 R0.2\nG54\nM2\n",
    # U W incremental in the profile and relative arc centres (LinuxCNC drops a segment here)
    "G21 G18 G90 G91.1 F200\nO8 SUB\nG1 X4 Z0\nG1 U1 W-3\nG3 X6 Z-6 I0 K-1.5\nG1 W-4\nO8 ENDSUB\n"
    "G71 Q8 X8 Z1 D0.1 I0.4\nM2\n",
    # a profile with a loop, reading where it has got to (#<_x>, #<_z>)
    "G21 G54 G18\nF400\nO100 SUB\nG0 X0 Z-10\nO101 REPEAT [3]\nG1 X[#<_x>+5] Z[#<_z>+3]\nG1 X[#<_x>+5]\n"
    "O101 ENDREPEAT\nO100 ENDSUB\nG72 Q100 X1 Z1 D0.5 I1 R0.3\nG70 Q100 X1 Z1 D0.5 P2\nM2\n",
])
def test_lathe_cycles_are_the_moves_linuxcnc_makes(text: str) -> None:
    motion_alike(text)


def _profile_x(z: float) -> float:
    """The STEP profile's X at Z (the smaller at a step: its corner)."""
    return 2.0 if z >= -5.0 - 1e-9 else 6.0 if z >= -10.0 - 1e-9 else 9.0


@pytest.mark.parametrize("allowance", [0.0, 0.25])
def test_roughing_stays_outside_the_finishing_allowance(allowance: float) -> None:
    p = parse_program(HEAD + STEP + f"G71 Q7 X10 Z2 D{allowance} I0.8 R0.3\nM2\n")
    feeds = [m for m in p.moves if m.kind is not MoveKind.RAPID]
    assert len(feeds) > 10
    for m in p.moves:
        for x, _y, z in (m.start, m.end):
            if -10.0 + 1e-9 < z < 0.0 - 1e-9:
                assert x >= _profile_x(z) + allowance - 1e-9, (m, allowance)
    # the passes step down I at a time, and the last one follows the profile at the allowance
    depths = sorted({round(float(m.end[0]), 9) for m in feeds if m.end[0] > _profile_x(float(m.end[2]))})
    assert depths[-1] <= 10.0
    finish = [m for m in feeds if abs(m.end[0] - (6.0 + allowance)) < 1e-9]
    assert finish, "no pass along the shoulder at the allowance"


def test_finishing_passes_close_in_from_d_to_e() -> None:
    p = parse_program(HEAD + STEP + "G70 Q7 X10 Z2 D0.6 E0 P3\nM2\n")
    along_shoulder = sorted({round(float(m.end[0]), 9) for m in p.moves
                             if m.kind is MoveKind.LINE and abs(m.end[2] - m.start[2]) > 1.0
                             and 5.0 < m.end[0] < 8.0})
    assert along_shoulder == pytest.approx([6.0, 6.2, 6.4])


@pytest.mark.parametrize(("text", "line", "reason"), [
    (HEAD + STEP + "G71 X10 Z2 I1\n", 9, "requires a Q word"),
    ("G21 G17 F300\n" + STEP + "G71 Q7 X10 Z2 I1\n", 9, "can only be used in the XZ plane (G18)"),
    (HEAD + STEP + "G71 Q8 X10 Z2 I1\n", 9, "no o8 sub in this program"),
    (HEAD + STEP + "G71 Q7 X10 Z2 I0\n", 9, "I (the depth of cut) must be greater than zero"),
    (HEAD + STEP + "G71 Q7 X10 Z2 U0.2\n", 9, "axis U is not on this machine"),
    (HEAD + "G41.1 D1 G1 X12 Z3\n" + STEP + "G71 Q7 X10 Z2\n", 10, "cutter compensation"),
    (HEAD + "O7 SUB\nG1 X2 Z0\nG1 Z-5 A0.2 C0.2\nG1 X6\nO7 ENDSUB\nG71 Q7 X10 Z2\n", 7, "both A and C"),
    (HEAD + "O7 SUB\nG1 X2 Z0\nO8 CALL\nO7 ENDSUB\nG71 Q7 X10 Z2\n", 6,
     "o8 call (line 4, in the profile) is not supported"),
    # a profile LinuxCNC 2.9 roughs for ever (its own test of it is marked as failing)
    (HEAD + "O200 SUB\nG01 X10 Z0\nG01 X10 Z-14\nG01 X3\nG01 X7 Z-22\nO200 ENDSUB\n"
     "G71.2 Q200 X15.0 Z0 D0.04 I0.5 R1\n", 8, "the cycle does not progress"),
])
def test_refusals_name_the_cycle_s_line_and_the_reason(text: str, line: int, reason: str) -> None:
    with pytest.raises(ProgramError) as info:
        parse_program(text + "M2\n")
    err = info.value.errors[0]
    assert err.line == line and reason in err.message, err


def test_a_profile_shorter_than_a_segment_cuts_nothing() -> None:
    p = parse_program(HEAD + "O3 SUB\nG1 X2 Z0\nO3 ENDSUB\nG71 Q3 X10 Z2 I1\nM2\n")
    assert np.array_equal([m.end for m in p.moves], [[10.0, 0.0, 2.0]])   # the rapid to X Z only


@st.composite
def lathe_programs(draw) -> str:
    """A random profile of lines, arcs by R, rounds and chamfers, cut by a random cycle, its
    lengths times a random scale (a thousandth of the part to a thousand times it)."""
    size = draw(st.sampled_from([0.001, 1.0, 1000.0]))

    def n(lo: float, hi: float) -> str:
        return f"{draw(st.integers(int(lo * 10), int(hi * 10))) / 10.0 * size:.6f}"

    body = [f"G1 X{n(0, 4)} Z{n(-1, 1)}"]
    for _ in range(draw(st.integers(1, 6))):
        kind = draw(st.sampled_from(["G1", "G2", "G3"]))
        words = f"{kind} X{n(0, 12)} Z{n(-20, 0)}"
        if kind != "G1":
            words += f" R{n(1, 15)}"
        words += draw(st.sampled_from(["", f" A{n(0.1, 1)}", f" C{n(0.1, 1)}"]))
        body.append(words)
    cycle = draw(st.sampled_from(["G71", "G71.1", "G71.2", "G72", "G72.1", "G72.2", "G70"]))
    words = f"{cycle} Q1 X{n(12, 16)} Z{n(1, 4)} D{n(0, 0.5)}"
    words += f" P{draw(st.integers(1, 3))}" if cycle == "G70" else f" I{n(0.2, 2)} R{n(0.1, 0.5)}"
    return "G21 G18 G90 F300\nO1 SUB\n" + "\n".join(body) + "\nO1 ENDSUB\n" + words + "\nM2\n"


@settings(max_examples=150, deadline=None)
@given(lathe_programs())
def test_any_profile_is_cut_or_refused_with_its_line(text: str) -> None:
    try:
        p = parse_program(text)
    except ProgramError as exc:
        assert all(e.line >= 1 and e.message for e in exc.errors)
        return
    assert all(np.isfinite(m.end).all() for m in p.moves)


@pytest.mark.parametrize("value", ["10**300", "10**308*10", "[0-10**300]"])
def test_a_profile_coordinate_out_of_range_is_refused_at_its_cycle(value: str) -> None:
    from planner.core.errors import ProgramError

    text = (HEAD + f"O100 SUB\nG0 X0 Z3\nG1 X2 Z0\nG1 X[{value}] Z-5\nG1 Z-10\nG0 X12\nO100 ENDSUB\n"
            "G71 Q100 X12 Z3 D0.3 I0.7 R0.3\nM2\n")
    with pytest.raises(ProgramError) as info:
        parse_program(text)
    err = info.value.errors[0]
    assert err.line == 9 and "out of range (|value| < 1e9) (line 5, in the profile)" in err.message
