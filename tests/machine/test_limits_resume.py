"""Soft limits on the whole path (arcs by their exact extremes) and the resume helpers."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.machine.config import load_config
from planner.core.errors import PlannerError
from planner.core.program import MoveKind
from planner.gcode.interpreter import parse_program
from planner.geometry.resume import approach_moves, locate, modal_state_at, remaining_program, split_move
from planner.geometry.softlimits import check_and_bound, check_program, move_bounds_table, program_bounds
from resources import shipped_machine


@pytest.fixture(scope="module")
def machine():
    return load_config(shipped_machine("xyz_mill")).machine  # X -250..250, Y -200..200


def test_arc_crossing_the_limit_between_its_end_points_is_found(machine) -> None:
    # both end points inside (X 200), the arc bulges to X = 260 > 250 in its middle
    prog = parse_program("G0 X200 Y-60\nG3 X200 Y60 R60 F600\nG0 X0 Y0\n", machine=machine)
    v = check_program(prog, machine)
    assert len(v) == 1
    assert v[0].line == 2 and v[0].axis == "X"
    assert v[0].value == pytest.approx(260.0, abs=1e-9)
    assert v[0].where == "arc extreme"
    assert "line 2" in str(v[0]) and "axis X" in str(v[0])


def test_bounds_are_exact_for_arcs(machine) -> None:
    # clockwise from angle 0 to 180 degrees: through -90 degrees, the lower half (Y min -10)
    prog = parse_program("G0 X10 Y0\nG2 X-10 Y0 R10 F600\n", machine=machine)
    lo, hi = program_bounds(prog)
    assert lo[1] == pytest.approx(-10.0, abs=1e-12)
    assert hi[1] == pytest.approx(0.0, abs=1e-12)


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 10_000), st.sampled_from([1, 2, 5, 64]))
def test_a_program_checked_a_piece_at_a_time_is_checked_as_a_whole(machine, seed: int, piece: int) -> None:
    # a long program's moves are bounded a piece at a time (the whole table of 10,000,000
    # moves took 480 MB): the same violations, in the same order, and the same bounds
    rng = np.random.default_rng(seed)
    lines = ["G21 G90 G0 X0 Y0 Z0", "G1 F900"]
    for _ in range(40):
        x, y = rng.uniform(-300, 300), rng.uniform(-240, 240)
        if rng.random() < 0.3:
            lines.append(f"G2 I{rng.uniform(-150, 150):.3f} J{rng.uniform(-150, 150):.3f}")  # a full circle
        else:
            lines.append(f"G1 X{x:.3f} Y{y:.3f} Z{rng.uniform(-160, 110):.3f}")
    prog = parse_program("\n".join(lines) + "\n", machine=machine)
    whole = move_bounds_table(prog)
    got, lo, hi = check_and_bound(prog, machine, piece=piece)
    assert [str(v) for v in got] == [str(v) for v in check_program(prog, machine, table=whole)]
    assert got                                        # this travel is exceeded somewhere
    wlo, whi = program_bounds(prog, whole)
    np.testing.assert_array_equal(lo, wlo)
    np.testing.assert_array_equal(hi, whi)


def test_helix_and_lines_inside_pass(machine) -> None:
    prog = parse_program("G0 X0 Y0\nG2 X0 Y0 I50 J0 Z-10 F600\nG1 X240\n", machine=machine)
    assert check_program(prog, machine) == []


def test_split_move_keeps_the_geometry(machine) -> None:
    prog = parse_program("G0 X20 Y0\nG3 X0 Y20 Z-3 R20 F600\n", machine=machine)
    arc = prog.moves[1]
    u = 0.37 * arc.length_mm
    tail = split_move(arc, u)
    assert tail.length_mm == pytest.approx(arc.length_mm - u, rel=1e-12)
    np.testing.assert_array_equal(tail.end, arc.end)
    w = np.linspace(0.0, tail.length_mm, 50)
    np.testing.assert_allclose(tail.evaluate(w)[0], arc.evaluate(u + w)[0], atol=1e-12)


def test_remaining_program_and_modal_state(machine) -> None:
    text = "G0 X0 Y0\nM3 S1200\nG1 X10 F600\nM5\nG1 Y10\nM4 S800\nG1 X0\nM30\n"
    prog = parse_program(text, machine=machine)
    i = locate(prog, 5)
    rest = remaining_program(prog, i, 2.5)
    assert rest.moves[0].line == 5
    np.testing.assert_allclose(rest.start_position, [10.0, 2.5, 0.0], atol=1e-12)
    np.testing.assert_array_equal(rest.end_position, prog.end_position)
    assert modal_state_at(prog, 3).spindle.signed_rpm == 1200.0
    assert modal_state_at(prog, 5).spindle.signed_rpm == 0.0
    assert modal_state_at(prog, 7).spindle.signed_rpm == -800.0


def test_approach_goes_up_to_the_clearance_across_then_down_at_feed(machine) -> None:
    a = approach_moves(np.array([0.0, 0.0, -5.0]), np.array([50.0, 20.0, -2.0]), ("X", "Y", "Z"),
                       (False, False, False), clearance=80.0, feed_mm_s=10.0, safe_height=5.0)
    assert [tuple(m.end) for m in a.moves] == [(0.0, 0.0, 80.0), (50.0, 20.0, 80.0), (50.0, 20.0, 5.0),
                                               (50.0, 20.0, -2.0)]
    assert [m.kind for m in a.moves] == [MoveKind.RAPID] * 3 + [MoveKind.LINE]
    assert a.moves[-1].feed_mm_s == 10.0
    assert a.spindle_after == 1      # the spindle starts before the tool goes below the clearance


_coord = st.floats(-100.0, 100.0, allow_nan=False)


@settings(max_examples=300, deadline=None)
@given(cur=st.tuples(_coord, _coord, _coord), tgt=st.tuples(_coord, _coord, _coord),
       clearance=_coord, safe=st.one_of(st.none(), _coord))
def test_an_approach_never_moves_sideways_below_the_clearance(machine, cur, tgt, clearance, safe) -> None:
    a = approach_moves(np.array(cur), np.array(tgt), ("X", "Y", "Z"), (False, False, False),
                       clearance=clearance, feed_mm_s=5.0, safe_height=safe)
    high = max(cur[2], tgt[2], clearance)
    pts = [np.array(cur)] + [m.end for m in a.moves]
    for m, p0 in zip(a.moves, pts):
        np.testing.assert_array_equal(m.start, p0)                  # continuous
        if np.abs(m.start[:2] - m.end[:2]).max() > 1e-12:  # sideways only at the top
            assert m.start[2] == pytest.approx(high, abs=1e-12) and m.end[2] == high
            assert m.kind is MoveKind.RAPID
    np.testing.assert_allclose(pts[-1], tgt, atol=1e-12, rtol=0)   # legs under 1e-12 mm are left out
    for i, m in enumerate(a.moves):                                 # below the top: spindle on
        if min(m.start[2], m.end[2]) < high:
            assert i > a.spindle_after or m.end[2] > m.start[2]
    rapid_floor = safe if safe is not None and tgt[2] < safe < high else high
    for m in a.moves:                                               # below the program's own
        if m.end[2] < rapid_floor - 1e-12:                          # retract plane: at feed
            assert m.kind is MoveKind.LINE


@settings(max_examples=60, deadline=None)
@given(st.lists(st.sampled_from(["G1 X{v} F600", "G0 Y{v}", "M3 S1000", "(note)", "G4 P0.1",
                                 "G1 Z-{v} F300"]), min_size=1, max_size=40),
       st.integers(min_value=-2, max_value=60))
def test_a_line_is_found_as_the_first_move_at_or_after_it(machine, blocks: list[str], line: int) -> None:
    """``locate`` (the line column) against reading the moves one by one: the same move, or
    the same refusal past the last motion."""
    text = "\n".join(b.format(v=(k % 7) * 5) for k, b in enumerate(blocks)) + "\n"
    prog = parse_program(text, machine=machine)
    expected = next((m.index for m in prog.moves if m.line >= line), None)
    if expected is None:
        with pytest.raises(PlannerError, match=f"no motion at or after line {line}"):
            locate(prog, line)
    else:
        assert locate(prog, line) == expected
