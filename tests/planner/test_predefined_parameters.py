"""LinuxCNC 2.9's predefined named parameters (``#<_spindle_on>``, ``#<_coord_system>`` ...)
read as rs274 reads them: after random sequences of the codes that set them, each parameter's
value moves an axis, and the motion is compared with LinuxCNC's own interpreter."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.gcode.interpreter import parse_program
from tools.linuxcnc_oracle import RS274, motion_alike

#: every predefined parameter compared with rs274 (the pockets are left out: rs274 alone, with
#: no tool table of a machine, reads pocket 1 for the empty spindle)
NAMES = ("_vmajor", "_vminor", "_ccomp", "_inverse_time", "_units_per_minute", "_units_per_rev",
         "_coord_system", "_tool_offset", "_spindle_rpm_mode", "_spindle_css_mode", "_ijk_absolute_mode",
         "_spindle_on", "_spindle_cw", "_mist", "_flood", "_speed_override", "_feed_override",
         "_adaptive_feed", "_feed_hold", "_call_level", "_remap_level", "_metric", "_imperial",
         "_absolute", "_incremental", "_plane", "_motion_mode", "_retract_r_plane", "_retract_old_z")
#: codes that set them
SETTERS = ("M3 S1000", "M4 S500", "M5", "M7", "M8", "M9", "G93", "G94", "G95", "G90.1", "G91.1",
           "G43.1 Z1", "G49", "G55", "G54", "G59.3", "M48", "M49", "M50 P0", "M50", "M51 P0", "M51 P1",
           "M53 P0", "M53 P1", "G18", "G19", "G17", "G98", "G99")


def _reading(setters: list[str], names: tuple[str, ...] = NAMES, in_sub: bool = False) -> str:
    """A program that runs ``setters``, then moves X, Y, Z by three parameters at a time."""
    lines = ["G21 G90", *setters]
    moves = []
    for k in range(0, len(names), 3):
        words = " ".join(f"{axis}[#<{name}>*10+1]" for axis, name in zip("XYZ", names[k:k + 3]))
        moves.append(f"G90 G0 {words}")
    if in_sub:
        lines += ["o100 sub", *moves, "o100 endsub", "o100 call"]
    else:
        lines += moves
    return "\n".join([*lines, "M2"]) + "\n"


def test_every_predefined_parameter_has_a_value() -> None:
    names = (*NAMES, "_current_pocket", "_selected_pocket")
    text = "G21\n" + "".join(f"#1 = #<{name}>\n" for name in names) + "M2\n"
    parse_program(text)                    # an unknown name is refused: none is


def test_the_pockets_read_the_tool_table() -> None:
    from planner.core.tools import Tool, ToolTable

    table = ToolTable({5: Tool(5, 12, (), 0.0, ""), 7: Tool(7, 3, (), 0.0, "")})
    text = "G21 G90\nM61 Q5\nT7\nG0 X[#<_current_pocket>] Y[#<_selected_pocket>]\nM2\n"
    program = parse_program(text, tools=table)
    assert tuple(program.moves.positions[-1][:2]) == (12.0, 3.0)


needs_rs274 = pytest.mark.skipif(RS274 is None, reason="LinuxCNC's rs274 is not installed (make test "
                                                       "installs it as root)")


@needs_rs274
@pytest.mark.parametrize("setter", SETTERS)
def test_each_code_sets_the_parameters_as_linuxcnc_does(setter: str) -> None:
    motion_alike(_reading([setter]))


@needs_rs274
def test_the_call_level_inside_a_subroutine_is_linuxcnc_s() -> None:
    motion_alike(_reading(["M8"], ("_call_level", "_flood", "_remap_level"), in_sub=True))


@needs_rs274
@settings(max_examples=40, deadline=None)
@given(st.lists(st.sampled_from(SETTERS), min_size=1, max_size=6))
def test_random_sequences_set_the_parameters_as_linuxcnc_does(setters: list[str]) -> None:
    motion_alike(_reading(setters))
