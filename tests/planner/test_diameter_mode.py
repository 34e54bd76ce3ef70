"""G7 (X words are diameters) and G8 (radii, the default) as LinuxCNC 2.9 reads them: the X
word is halved as it is read, whatever uses it (motion, G92, G10, cycles), in the mode the
block leaves; I and K are not."""

from __future__ import annotations

import pytest

from planner.core.errors import ProgramError
from planner.core.program import EventKind
from planner.gcode.interpreter import parse_program
from tools.linuxcnc_oracle import RS274, motion_alike


def x_ends(text: str) -> list[float]:
    return [float(m.end[0]) for m in parse_program(text).moves]


def test_g7_halves_x_words_and_g8_in_the_same_block_undoes_it() -> None:
    assert x_ends("G21 F600\nG7\nG1 X20 Y5\nG8 X20 Y6\nG7 G1 X30 Y7\nY8 X10\nM2\n") == [10.0, 20.0, 15.0, 5.0]


def test_g7_leaves_y_z_and_the_arc_centre_words_as_written() -> None:
    p = parse_program("G21 F600\nG7 G18\nG1 X20 Z0\nG2 X20 Z-10 K-5\nM2\n")
    line, arc = p.moves
    assert line.end.tolist() == [10.0, 0.0, 0.0]
    assert arc.end.tolist() == [10.0, 0.0, -10.0]
    assert arc.length_mm == pytest.approx(5.0 * 3.141592653589793)   # a half circle of radius 5 (K)


def test_g7_applies_to_every_use_of_x_offsets_included() -> None:
    p = parse_program("G21 F600\nG7\nG10 L2 P1 X8\nG1 X4\nG92 X10\nG1 X12\nG91 G1 X2\nM2\n")
    # G54 X4 (the 8 halved); X4 there is machine 6; G92 makes that point X5; X12 is X6: machine
    # 7; then X2 incremental is one more
    assert [float(m.end[0]) for m in p.moves] == [6.0, 7.0, 8.0]


def test_g7_is_modal_shown_saved_and_restored_by_m70_m72_and_read_by_its_parameters() -> None:
    text = ("G21 F600\nM70\nG7\n(debug,#<_lathe_diameter_mode> #<_lathe_radius_mode>)\nG1 X10\n"
            "M72\n(debug,#<_lathe_diameter_mode> #<_lathe_radius_mode>)\nG1 X10\nM2\n")
    p = parse_program(text)
    assert [float(m.end[0]) for m in p.moves] == [5.0, 10.0]
    messages = [e.message.split() for e in p.events if e.kind is EventKind.MESSAGE]
    assert [[float(v) for v in m] for m in messages] == [[1.0, 0.0], [0.0, 1.0]]
    assert p.modal_at_move(0).endswith(" G7")
    assert not p.modal_at_move(1).endswith(" G7")


def test_g7_rasters_are_read_line_by_line_not_by_the_fast_reader() -> None:
    # thousands of plain G01 lines go to the bulk reader; in G7 every X must still be halved
    lines = "".join(f"X{i % 50 + 10} Y{i * 0.01:.2f}\n" for i in range(3000))
    p = parse_program("G21 G90 F900\nG7\nG1 X10 Y0\n" + lines + "M2\n")
    xs = [float(m.end[0]) for m in p.moves]
    assert max(xs) == 29.5 and min(xs) == 5.0


def test_g7_and_g8_are_one_modal_group() -> None:
    with pytest.raises(ProgramError) as info:
        parse_program("G7 G8\nM2\n")
    assert "same modal group" in info.value.errors[0].message


@pytest.mark.skipif(RS274 is None, reason="LinuxCNC's rs274 is not installed (make test installs it as root)")
@pytest.mark.parametrize("text", [
    "G21 F600\nG7\nG1 X20 Y5\nG8 X20 Y6\nG7 G1 X30 Y7\nG91 X4\nG90 G8 X1\nM2\n",
    "G21 F600 G18\nG7 G0 X40 Z2\nG1 Z-10\nG2 X50 Z-15 K-5\nG3 X40 Z-20 I-5\nG0 X60\nM2\n",
    "G20 F20\nG7\nG10 L20 P1 X2\nG1 X1 Y1\nG92 X3\nG1 X4\nG92.1\nG8 G1 X0.5\nM2\n",
    "G21 F300\nG7 G0 X20 Z5\nG81 X30 Y4 Z-3 R1\nX40\nG80\nG28 X8\nM2\n",
])
def test_diameter_mode_reads_as_linuxcnc_reads_it(text: str) -> None:
    motion_alike(text)
