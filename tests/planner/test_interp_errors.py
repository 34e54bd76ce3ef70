"""Every error the interpreter reports, with its line and column."""

from __future__ import annotations

import pytest

from planner.core.errors import ProgramError
from planner.core.machine import load_machine
from planner.gcode.interpreter import parse_program
from resources import shipped_machine


def errors_of(text: str, **kw):
    with pytest.raises(ProgramError) as ei:
        parse_program(text, "e.nc", **kw)
    return ei.value.errors


@pytest.mark.parametrize(
    "text,fragment,line,col",
    [
        # feed
        ("G1 X1", "feed rate is zero", 1, 1),
        # LinuxCNC checks the feed of a G01 before its length: "Cannot do g1 with zero feed rate"
        ("G1 (to where the tool is)", "feed rate is zero", 1, 1),
        ("G1 X0 Y0", "feed rate is zero", 1, 1),
        ("G2 X1 Y1 R1", "feed rate is zero", 1, 1),
        ("G1 X1 F-5", "negative feed", 1, 7),
        # R form
        ("G1 F60\nG2 X10 R4", "arc radius 4.000 mm too small to reach end point (half chord 5.000 mm)", 2, 8),
        ("G1 F60\nG2 X0 Y0 R4", "start point = end point", 2, 10),
        ("G1 F60\nG2 X1 R0", "zero-radius arc", 2, 7),
        ("G1 F60\nG2 X1 R1 I1", "mixed radius (R) and centre (I/J/K)", 2, 7),
        # centre form
        ("G1 F60\nG2 X10 I5.1", "radius to end of arc differs from radius to start", 2, 1),
        ("G1 F60\nG2 X10 I0.0001", "zero-radius arc", 2, 1),
        ("G1 F60\nG2 X1", "R, I, J and K words all missing", 2, 1),
        ("G1 F60\nG2 X1 K1", "K word given for arc in the XY plane (G17)", 2, 7),
        ("G1 F60\nG18 G2 Z1 J1", "J word given for arc in the ZX plane (G18)", 2, 11),
        ("G1 F60\nG19 G2 Y1 I1", "I word given for arc in the YZ plane (G19)", 2, 11),
        ("G1 F60\nG90.1 G2 X1 I1", "G90.1 (absolute arc centre) needs both I and J", 2, 1),
        # parameter numbers that are not numbers: NaN from inf - inf is refused, not rounded
        ("#[[10**300*10**300]-[10**300*10**300]]=5", "parameter number #nan out of range", 1, 39),
        ("#[1e400-1e400]=5", "expected ']'", 1, 4),                  # no exponents in G-code numbers
        ("#1e400=5", "parameter reference without a word letter", 1, 1),
        # turns
        ("G1 F60\nG2 X1 I0.5 P1.5", "whole number >= 1", 2, 12),
        ("G1 F60\nG2 X1 I0.5 P0", "whole number >= 1", 2, 12),
        ("G1 F60\nG2 X1 I0.5 P20000", "more than 10000 turns", 2, 12),
        # codes
        ("G5.4 X1", "unknown G code G5.4", 1, 1),
        ("G76 X1 Z-1", "G76 needs a P word (the thread pitch, length per turn)", 1, 1),
        ("M3 S100\nG76 X1 Z-1 P1 I-1 K1", "G76 needs I, J and K words (the thread's offset, first cut "
         "and depth): J missing", 2, 1),
        ("M3 S100\nG76 Z-1 P1 I-1 J0 K1", "G76: J (the first cut's depth) must be greater than 0", 2, 16),
        ("G1 X1 E2 F10", "E word with no G33, G33.1, G76, M67 or M68 to use it", 1, 7),
        ("G81 X1 Z-1 R1", "feed rate is zero", 1, 1),
        ("G91 F10\nG38.2 Z0", "G38.2: start point too close to probe point", 2, 1),
        ("G33 X1 K1", "spindle not turning in G33 (M3 or M4 first)", 1, 1),
        ("G41.1", "G41.1 needs a D word (the tool diameter)", 1, 1),
        ("G1.5 X1", "unknown G code G1.5", 1, 1),
        ("M98 P3", "M98 P3: no O3 in this program", 1, 1),
        ("M67 Q1", "M67 needs an E word, the analog output's number (0 or more)", 1, 1),
        ("M68 E-2 Q1", "M68 needs an E word, the analog output's number (0 or more)", 1, 5),
        ("M60", "M60 is not supported (M60 exchanges pallets and pauses; this machine has no pallet", 1, 1),
        ("G0 G18.1 X1", "G18.1 is not supported (G18.1 selects the WU plane, of U and W axes", 1, 4),
        ("M1.5", "unknown M code", 1, 1),
        ("M3 M5", "M3 and M5 are in the same modal group", 1, 4),
        ("M0 M2", "M0 and M2 are in the same modal group", 1, 4),
        ("M7 M8", "M7 and M8 are in the same modal group", 1, 4),   # as LinuxCNC 2.9, which refuses it
        # words
        ("G0 B5", "axis B is not on this machine (axes: X Y Z)", 1, 4),
        ("G0 U5", "axis U is not on this machine", 1, 4),
        ("G0 L5", "L word with no canned cycle, G05.2, G10, G76 or M66 to use it", 1, 4),
        ("X1", "axis words without a motion mode", 1, 1),
        ("G1 X1 F60 I1", "I word with no G02/G03, G05 or G05.1 to use it", 1, 11),
        ("G1 X1 F60 R1", "R word with no G02/G03 or canned cycle to use it", 1, 11),
        ("G1 X1 F60 P1", "P word with no G code that uses it", 1, 11),
        ("G1 X1 F60 D1", "D word with no G41, G41.1, G42, G42.1 or G96 to use it", 1, 11),
        ("G1 X1 F60 H1", "H word with no G43, G43.2 or G76 to use it", 1, 11),
        ("S-5", "negative spindle speed", 1, 1),
        ("T1.5", "whole number >= 0", 1, 1),
        ("G1 X1 Y1 X2 F60", "two X words in one block", 1, 4),
        # non-modal
        ("G0 G28 Z0", "cannot use two G codes that both use axis values", 1, 4),
        ("G53 G2 X1 R1 F60", "G53 needs G00 or G01", 1, 1),
        ("G91 G53 G0 X1", "G53 cannot be used in incremental mode", 1, 5),
        ("G53", "G53 needs G00 or G01 with axis words", 1, 1),
        ("G4", "G04 needs a P word", 1, 1),
        ("G4 P-1", "negative dwell time", 1, 4),
        ("G28 G4 P1", "same modal group", 1, 5),
        ("G80 X1", "cannot use axis values with G80", 1, 5),
    ],
)
def test_error(text, fragment, line, col):
    errs = errors_of(text)
    assert len(errs) == 1, errs
    e = errs[0]
    assert fragment in e.message, e
    assert (e.line, e.col) == (line, col), e
    assert str(e).startswith(f"e.nc:{line}:{col}: error: ")


def test_radius_mismatch_message_names_both_radii():
    (e,) = errors_of("G0 X20 Y-21\nG3 X21 Y-20 I20 J21 F100")
    assert "r1=29.0000 mm r2=27.5862 mm" in e.message


def test_inch_program_reports_inches():
    (e,) = errors_of("G20 G0 X0\nG2 X600 I[300 + [100 * [0.00101 * sqrt[2]]]] F1")
    assert "r1=300.1428 in r2=299.8572 in" in e.message


def test_axis_letters_follow_the_machine():
    m = load_machine(shipped_machine("paper_yzca"))
    (e,) = errors_of("G0 Y1 B2", machine=m)
    assert "axis B is not on this machine (axes: Y Z C A)" in e.message


def test_errors_do_not_stop_the_check_and_no_program_is_returned():
    errs = errors_of("G0 X1\nG2 X5 R1 F60\nG0 Y1\nM98\n")
    assert [(e.line, e.message.split()[0]) for e in errs] == [(2, "arc"), (4, "M98")]


def test_code_columns():
    (e,) = errors_of("G17 G90 G90.1 G91.1 G0 X1")
    assert e.col == 15 and "G90.1 and G91.1" in e.message
    (e,) = errors_of("G1 G17 G0 X1")
    assert e.col == 8


def test_error_after_program_end_not_reported():
    assert len(parse_program("G0 X1\nM2\nM99\n").moves) == 1
