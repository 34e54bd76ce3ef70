"""One test (at least) per supported G/M code and word, against hand-computed results."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from planner.core.errors import ProgramError
from planner.core.machine import MachineSpec, load_machine
from planner.core.program import Coolant, CoolantSwitch, Dwell, EventKind, MoveKind, SpindleSpeed, ToolNumber
from planner.gcode.interpreter import parse_program
from resources import shipped_machine

P = parse_program


def test_default_setup_and_g00_g01():
    p = P("G0 X10 Y5\nG1 Z-1 F600\n")
    assert p.axes == ("X", "Y", "Z") and p.rotary == (False, False, False)
    r, l = p.moves
    assert r.kind is MoveKind.RAPID and math.isinf(r.feed_mm_s) and r.arc is None
    assert l.kind is MoveKind.LINE and l.feed_mm_s == pytest.approx(10.0)  # 600 mm/min
    np.testing.assert_array_equal(r.start, [0, 0, 0])
    np.testing.assert_array_equal(r.end, l.start)
    assert r.length_mm == pytest.approx(math.hypot(10, 5)) and l.length_mm == pytest.approx(1.0)
    assert [m.index for m in p.moves] == [0, 1] and [m.line for m in p.moves] == [1, 2]


def test_modal_motion_and_feed_carry_over():
    p = P("G1 X1 F120\nX2\nY1\nG0 X0\nX5\n")
    assert [m.kind for m in p.moves] == [MoveKind.LINE] * 3 + [MoveKind.RAPID] * 2
    assert all(m.feed_mm_s == pytest.approx(2.0) for m in p.moves[:3])


def test_g02_g03_xy_direction_centre_and_sweep():
    # quarter circle from (10,0) around the origin
    ccw = P("G0 X10\nG3 X0 Y10 I-10 J0 F60").moves[1].arc
    cw = P("G0 X10\nG2 X0 Y10 I-10 J0 F60").moves[1].arc
    assert ccw.center == pytest.approx((0, 0)) and cw.center == pytest.approx((0, 0))
    assert ccw.sweep_rad == pytest.approx(math.pi / 2) and cw.sweep_rad == pytest.approx(-1.5 * math.pi)
    assert ccw.plane == "XY" and (ccw.first_axis, ccw.second_axis, ccw.normal_axis) == (0, 1, 2)
    assert ccw.start_angle_rad == pytest.approx(0.0)


def test_r_form_short_and_long_arc():
    short = P("G1 F60\nG2 X10 Y0 R10").moves[0]
    long_ = P("G1 F60\nG2 X10 Y0 R-10").moves[0]
    # G02 short arc: centre right of the chord (below), sweep 60 deg clockwise
    assert short.arc.center == pytest.approx((5, -math.sqrt(75)))
    assert short.arc.sweep_rad == pytest.approx(-math.pi / 3)
    assert long_.arc.center == pytest.approx((5, math.sqrt(75)))
    assert long_.arc.sweep_rad == pytest.approx(-5 * math.pi / 3)
    assert long_.length_mm == pytest.approx(10 * 5 * math.pi / 3)


def test_r_form_half_circle_snap():
    # half chord 5.001 > R = 5 by 0.001 mm < 0.00127 mm: snapped to a half circle
    a = P("G1 F60\nG3 X10.002 Y0 R5").moves[0].arc
    assert a.center == pytest.approx((5.001, 0.0), abs=1e-12)
    assert a.radius_start_mm == pytest.approx(5.001) and a.sweep_rad == pytest.approx(math.pi)


def test_full_circle_turns_and_helix():
    p = P("G0 X10\nG3 X10 Y0 I-10 J0 F60\nG3 X10 Y0 Z3 I-10 P3\n")
    full, helix = p.moves[1].arc, p.moves[2].arc
    assert full.sweep_rad == pytest.approx(2 * math.pi) and full.turns == 1
    assert helix.sweep_rad == pytest.approx(6 * math.pi) and helix.turns == 3 and helix.rise_mm == 3
    assert p.moves[2].length_mm == pytest.approx(math.hypot(60 * math.pi, 3))
    # quarter arc with 2 turns: 2 pi + pi / 2
    q = P("G0 X10\nG2 X0 Y-10 I-10 P2 F60").moves[1].arc
    assert q.sweep_rad == pytest.approx(-(2 * math.pi + math.pi / 2))


@pytest.mark.parametrize(
    "plane,start,words,centre,sweep,normal_rise",
    [
        # G17: first X, second Y, seen from +Z
        ("G17", "X10 Y0 Z0", "G3 X0 Y10 Z2 I-10", (0.0, 0.0), math.pi / 2, 2.0),
        # G18: first Z, second X, seen from +Y: from Z=10 to X=10 is counter-clockwise
        ("G18", "X0 Y0 Z10", "G3 X10 Z0 K-10 Y2", (0.0, 0.0), math.pi / 2, 2.0),
        ("G18", "X0 Y0 Z10", "G2 X10 Z0 K-10", (0.0, 0.0), -1.5 * math.pi, 0.0),
        # G19: first Y, second Z, seen from +X
        ("G19", "X0 Y10 Z0", "G3 Y0 Z10 J-10 X2", (0.0, 0.0), math.pi / 2, 2.0),
    ],
)
def test_planes(plane, start, words, centre, sweep, normal_rise):
    p = P(f"G0 {start}\n{plane} F60 {words}\n")
    arc = p.moves[1].arc
    assert arc.center == pytest.approx(centre, abs=1e-12)
    assert arc.sweep_rad == pytest.approx(sweep)
    assert arc.rise_mm == pytest.approx(normal_rise)
    name = {"G17": "XY", "G18": "ZX", "G19": "YZ"}[plane]
    first, second, normal = {"XY": (0, 1, 2), "ZX": (2, 0, 1), "YZ": (1, 2, 0)}[name]
    assert (arc.plane, arc.first_axis, arc.second_axis, arc.normal_axis) == (name, first, second, normal)


def test_g18_g02_is_clockwise_seen_from_plus_y():
    # From X=+10 (Z=0) around the origin, G02 in G18: clockwise seen from +Y means the
    # tool goes from +X towards -Z... check by evaluating the midpoint of a half circle.
    m = P("G0 X10\nG18 G2 X-10 Z0 I-10 K0 F60").moves[1]
    mid, tangent, _ = m.evaluate(np.array([m.length_mm / 2]))
    # Seen from +Y (x to the right? no: looking down -Y the axes are Z right, X up); the
    # right-handed frame (Z, X, Y): clockwise from X=+10 passes Z=+10.
    np.testing.assert_allclose(mid[0], [0, 0, 10], atol=1e-12)
    m3 = P("G0 X10\nG18 G3 X-10 Z0 I-10 K0 F60").moves[1]
    np.testing.assert_allclose(m3.evaluate(np.array([m3.length_mm / 2]))[0][0], [0, 0, -10], atol=1e-12)


def test_g20_inches_converted_to_mm():
    p = P("G20 G0 X1 Y2\nG1 X2 F10\nG2 X3 Y3 I0 J1\nG2 X4 Y2 R1\nG21 G0 X0\n")
    m = p.moves
    np.testing.assert_allclose(m[0].end, [25.4, 50.8, 0])
    assert m[1].feed_mm_s == pytest.approx(254 / 60)
    assert m[2].arc.center == pytest.approx((50.8, 76.2))
    assert m[3].arc.radius_start_mm == pytest.approx(25.4)
    np.testing.assert_allclose(m[4].end, [0, 50.8, 0])


def test_g90_g91_incremental():
    p = P("G0 X1 Y1\nG91 G0 X1 Y-1\nX1\nG90 X0\n")
    np.testing.assert_allclose([m.end for m in p.moves], [[1, 1, 0], [2, 0, 0], [3, 0, 0], [0, 0, 0]])


def test_incremental_r_helix_like_thread_milling():
    p = P("G91 G1 Z-1 F60\nG3 X1 Y1 Z0.5 R1\n")
    arc = p.moves[1].arc
    assert arc.center == pytest.approx((0.0, 1.0)) and arc.rise_mm == pytest.approx(0.5)
    np.testing.assert_allclose(p.moves[1].end, [1, 1, -0.5])


def test_g90_1_absolute_and_g91_1_incremental_centres():
    inc = P("G0 X10 Y10\nG3 X0 Y20 I-10 J0 F60").moves[1].arc
    ab = P("G0 X10 Y10\nG90.1 G3 X0 Y20 I0 J10 F60").moves[1].arc
    assert inc.center == pytest.approx((0, 10)) and ab.center == pytest.approx((0, 10))
    back = P("G90.1\nG91.1\nG0 X10 Y10\nG3 X0 Y20 I-10 J0 F60").moves[1].arc
    assert back.center == pytest.approx((0, 10))


def test_g94_and_g93_accepted_g87_rejected():
    assert len(P("G94 G1 X1 F10").moves) == 1
    assert len(P("G93 G1 X1 F10").moves) == 1
    with pytest.raises(ProgramError, match="G87 is not supported"):
        P("G87 X1 Z-1 R1 I1 J1 K1 F10")


def _machine_with_offsets() -> MachineSpec:
    m = MachineSpec.default()
    offs = dict(m.work_offsets)
    offs["G54"] = (100.0, 50.0, -20.0)
    offs["G55"] = (-5.0, 0.0, 1.0)
    return replace(m, work_offsets=offs)


def test_work_offsets_g54_g59_and_g53():
    m = _machine_with_offsets()
    p = P("G0 X1 Y1 Z1\nG55 G0 X1\nG53 G0 X0 Y0 Z0\nG0 X2\nG59 G0 X3\n", machine=m)
    e = [mv.end.tolist() for mv in p.moves]
    assert e[0] == [101, 51, -19]
    assert e[1] == [-4, 51, -19]
    assert e[2] == [0, 0, 0]  # machine coordinates for one block
    assert e[3] == [-3, 0, 0]  # back to G55 (modal): X2 + (-5), Y/Z stay
    assert e[4] == [3, 0, 0]  # G59 offsets are zero in the default machine
    np.testing.assert_array_equal(p.frame_at(0).to_machine([0, 0, 0]), [100, 50, -20])
    np.testing.assert_array_equal(p.frame_at(1).to_machine([0, 0, 0]), [-5, 0, 1])
    assert (p.frame_at(0).system_name, p.frame_at(1).system_name) == ("G54", "G55")


def test_one_offset_throughout_is_one_frame_for_every_move():
    """A program that never changes its offsets keeps one frame for all its moves; one that
    changes them keeps a frame per change, and each move names the one it runs in."""
    m = _machine_with_offsets()
    one = P("G0 X1 Y1 Z1\nG1 X2 F100\nG1 X3\n", machine=m)
    assert len(one.frames) == 1 and one.move_frames.tolist() == [0, 0, 0]
    assert one.frames[0].frame.g5x == (100, 50, -20)
    two = P("G0 X1 Y1 Z1\nG55 G0 X1\nG1 X3 F100\n", machine=m)
    assert [c.frame.g5x for c in two.frames] == [(100, 50, -20), (-5, 0, 1)]
    assert two.move_frames.tolist() == [0, 1, 1] and two.frames[1].line == 2


def test_g90_1_centre_uses_work_offset():
    m = _machine_with_offsets()
    arc = P("G0 X10 Y0\nG90.1 G3 X0 Y10 I0 J0 F60", machine=m).moves[1].arc
    assert arc.center == pytest.approx((100, 50))


def test_g61_g64_exact_stop():
    p = P("G1 X1 F60\nG61 X2\nX3\nG64 P0.01 Q0.01 X4\n")
    assert [m.exact_stop for m in p.moves] == [False, True, True, False]


def test_g64_tolerances_are_kept_and_shown():
    p = P("G20 G1 X1 F60\nG64 P0.001 X2\nG64 P0.002 Q0.0005 X3\nG61.1 X4\n")
    assert p.blend_tolerance == ((0, 0.0), (1, pytest.approx(0.0254)), (2, pytest.approx(0.0508)), (3, 0.0))
    assert p.naive_cam_tolerance == ((0, 0.0), (1, pytest.approx(0.0254)), (2, pytest.approx(0.0127)),
                                     (3, 0.0))
    assert [p.modal_at_move(i).split(" G49 ")[1] for i in range(4)] == [
        "G64", "G64 P0.001", "G64 P0.002 Q0.0005", "G61.1"]


def test_g04_dwell_event():
    p = P("G1 X1 F60\nG4 P0.5\nG1 X2\n")
    (ev,) = p.events
    assert ev.kind is EventKind.DWELL and ev.payload == Dwell(0.5) and ev.after_move == 0 and ev.line == 2
    assert ev.stops


def test_spindle_events():
    p = P("S1000 M3\nG1 X1 F60\nS2000\nM4\nM5\nS500\n")
    sp = [(e.payload_as(SpindleSpeed).signed_rpm, e.after_move, e.line) for e in p.events
          if e.kind is EventKind.SPINDLE]
    assert sp == [(1000, -1, 1), (2000, 0, 3), (-2000, 0, 4), (0, 0, 5)]  # S500 while off: no event


def test_program_stops_and_end():
    p = P("G1 X1 F60 M0\nG1 X2 M1\nM2\nG0 X100\n")
    kinds = [(e.kind, e.after_move) for e in p.events]
    assert kinds == [(EventKind.PAUSE, 0), (EventKind.OPTIONAL_PAUSE, 1), (EventKind.END, 1)]
    assert len(p.moves) == 2  # nothing runs after M02
    assert P("M30").events[0].kind is EventKind.END


def test_tool_and_m06_tool_change():
    p = P("T3 M6\nG0 X1\nT4\n")
    t, tc, t4 = p.events
    assert t.kind is EventKind.TOOL and t.payload == ToolNumber(3)
    assert tc.kind is EventKind.TOOL_CHANGE and tc.payload == ToolNumber(3)
    assert tc.stops
    assert "by hand" in tc.message and "T3" in tc.message
    assert t4.after_move == 0 and not t4.stops


def test_coolant_events():
    p = P("M8\nM9\nM7\nM8\n")
    assert [(e.kind, e.payload) for e in p.events] == [
        (EventKind.COOLANT, CoolantSwitch(Coolant.FLOOD_ON)),
        (EventKind.COOLANT, CoolantSwitch(Coolant.ALL_OFF)),
        (EventKind.COOLANT, CoolantSwitch(Coolant.MIST_ON)),
        (EventKind.COOLANT, CoolantSwitch(Coolant.FLOOD_ON)),
    ]
    assert not p.events[0].stops


def test_cutter_comp_and_tool_length_with_zero_tool_table():
    # No tool table: G41/G42 radius 0 and G43 length 0 leave the programmed path unchanged,
    # as LinuxCNC does with the reference run's zero tool table.
    a = P("G0 X1 Y1\nG1 X5 F60\nG2 X9 Y1 R2\n")
    b = P("G43 H1 G0 X1 Y1\nG42 D8\nG1 X5 F60\nG2 X9 Y1 R2\nG40 G49\n")
    for ma, mb in zip(a.moves, b.moves, strict=True):
        np.testing.assert_array_equal(ma.end, mb.end)
    assert len(P("G41 G1 X1 F60\nG40\n").moves) == 1


def test_g80_cancels_motion_mode():
    with pytest.raises(ProgramError, match="cannot use axis values with G80"):
        P("G1 X1 F60\nG80 X2")
    with pytest.raises(ProgramError, match="without a motion mode"):
        P("G1 X1 F60\nG80\nX2")


def test_g28_returns_to_machine_zero():
    p = P("G0 X10 Y10 Z10\nG91 G28 Z0\nG90\nG28 X5\nG28\n")
    e = [m.end.tolist() for m in p.moves]
    # Z to machine zero (the intermediate point is the current one: dropped)
    assert e[1] == [10, 10, 0]
    # G28 X5: via X=5, then X to zero
    assert e[2] == [5, 10, 0] and e[3] == [0, 10, 0]
    assert e[4] == [0, 0, 0]
    assert all(m.kind is MoveKind.RAPID for m in p.moves)


def test_zero_length_moves_dropped():
    p = P("G0 X1\nG0 X1\nG1 X1 F60\nG91 G1 X0\nG90 G2 X1.0000000001 R5\n")
    assert len(p.moves) == 1


def test_near_equal_centre_form_end_is_a_full_circle():
    arc = P("G0 X10\nG3 X10.0000000001 Y0 I-10 F60").moves[1].arc
    assert arc.sweep_rad == pytest.approx(2 * math.pi)


def test_paper_machine_axes_yzca():
    m = load_machine(shipped_machine("paper_yzca"))
    p = P("G0 Y10 Z5 C90 A-30\nG1 C180 F600\nG19 G2 Y0 Z-5 R10 C270\n", machine=m)
    assert p.axes == ("Y", "Z", "C", "A") and p.rotary == (False, False, True, True)
    np.testing.assert_array_equal(p.moves[0].end, [10, 5, 90, -30])
    # rotary-only move: length in degrees, feed in deg/s (LinuxCNC's rule)
    assert p.moves[1].length_mm == pytest.approx(90) and p.moves[1].feed_mm_s == pytest.approx(10)
    arc = p.moves[2].arc
    assert arc.normal_axis == -1 and (arc.first_axis, arc.second_axis) == (0, 1)
    # C rides along the arc linearly; length only over Y, Z
    assert p.moves[2].length_mm == pytest.approx(abs(arc.sweep_rad) * 10)
    q, _, _ = p.moves[2].evaluate(np.array([p.moves[2].length_mm / 2]))
    assert q[0, 2] == pytest.approx(225)
    with pytest.raises(ProgramError, match="axis X is not on this machine"):
        P("G0 X1", machine=m)
    with pytest.raises(ProgramError, match="needs axes X and Y"):
        P("G17 G2 Y1 R1 F60", machine=m)


def test_mixed_linear_rotary_length_is_linear_length():
    m = load_machine(shipped_machine("paper_yzca"))
    mv = P("G1 Y3 Z4 C90 F60", machine=m).moves[0]
    assert mv.length_mm == pytest.approx(5.0)
    assert mv.evaluate(np.array([2.5]))[0][0].tolist() == pytest.approx([1.5, 2, 45, 0])


def test_start_position():
    p = P("G91 G0 X1", start_position=[5, 6, 7])
    np.testing.assert_array_equal(p.start_position, [5, 6, 7])
    np.testing.assert_array_equal(p.moves[0].start, [5, 6, 7])
    np.testing.assert_array_equal(p.moves[0].end, [6, 6, 7])


def test_spiral_within_tolerance():
    # radius 10 at the start, 10.02 at the end (abs 0.02 mm < 0.02828): a spiral
    mv = P("G0 X10\nG3 X-10.02 Y0 I-10 J0 F60").moves[1]
    assert mv.arc.radius_start_mm == pytest.approx(10) and mv.arc.radius_end_mm == pytest.approx(10.02)
    pos, _, _ = mv.evaluate(np.array([0.0, mv.length_mm]))
    np.testing.assert_array_equal(pos[1], mv.end)


def test_moves_are_contiguous_and_read_only():
    p = P("G0 X1 Y2\nG1 X3 F60\nG2 X5 Y2 R1\n")
    for a, b in zip(p.moves, p.moves[1:]):
        assert a.end is not None and np.array_equal(a.end, b.start)
    with pytest.raises(ValueError):
        p.moves[0].end[0] = 5.0


@pytest.mark.parametrize("k", range(6))
def test_each_work_offset(k):
    m = MachineSpec.default()
    offs = {f"G5{4 + i}": (float(i), 10.0 * i, -1.0 * i) for i in range(6)}
    m = replace(m, work_offsets=offs)
    p = P(f"G5{4 + k} G0 X1 Y1 Z1", machine=m)
    np.testing.assert_array_equal(p.moves[0].end, [1 + k, 1 + 10 * k, 1 - k])


def test_polar_coordinates_as_linuxcnc_documents_them():
    """@ distance and ^ angle from the XY zero; in G91 both are added to the current ones
    (LinuxCNC's manual: '@.5 ^90' then 'G91 ^90' three times makes a square)."""
    assert P("G21 F100\nG1 @1 ^90\n").moves[0].end.tolist() == pytest.approx([0, 1, 0])
    square = P("G21 F100 G1 @.5 ^90\nG91 ^90\n^90\n^90\n^90\n")
    np.testing.assert_allclose([m.end[:2] for m in square.moves],
                               [[0, 0.5], [-0.5, 0], [0, -0.5], [0.5, 0], [0, 0.5]], atol=1e-12)
    spiral = P("G21 F100 G1 @.5 ^90\nG91 @.5 ^90\n@.5 ^90\n")
    np.testing.assert_allclose([np.hypot(*m.end[:2]) for m in spiral.moves], [0.5, 1.0, 1.5])
    offset = P("G21 F100\nG92 X-10\nG1 @2 ^0\n")                       # from the program's zero
    np.testing.assert_allclose(offset.moves[0].end[:2], [12, 0])
    for text, words in (("G21 F100\nG1 X1 @2\n", "with X or Y"), ("G21 F100 G91\nG1 ^30\n", "at the origin"),
                        ("G21 F100 G18\nG1 @1 ^30\n", "only in the XY plane")):
        with pytest.raises(ProgramError, match=words):
            P(text)


def test_polar_steps_of_a_repeated_cycle_turn_about_the_origin_at_every_hole():
    """In G91 a cycle's @ and ^ step the radius and the angle at each L repeat, about the
    program's zero, as LinuxCNC's bolt-circle sample (nc_files/hole-circle.ngc) uses them:
    six holes 60 degrees apart on the circle through the start, not six steps of one chord."""
    holes = P("G20 G17 G90\nG0 X1.5 Y0 Z0\nG91 G81 R.1 Z-.5 ^60 L6 F10\nM2\n")
    bottoms = [m.end[:2] for m in holes.moves if m.kind is MoveKind.LINE]
    angles = [math.radians(60 * k) for k in range(1, 7)]
    want = [[38.1 * math.cos(a), 38.1 * math.sin(a)] for a in angles]
    np.testing.assert_allclose(bottoms, want, atol=1e-9)
    row = P("G20 G90\nG0 X0 Y0 Z0\nG81 @1 ^33 R.1 Z-.5 F60\nG91 G81 @1 R.1 Z-.5 L3\nM2\n")
    bottoms = [m.end[:2] for m in row.moves if m.kind is MoveKind.LINE]
    np.testing.assert_allclose([np.hypot(*b) / 25.4 for b in bottoms], [1, 2, 3, 4], atol=1e-12)
    np.testing.assert_allclose([math.degrees(math.atan2(b[1], b[0])) for b in bottoms], [33] * 4, atol=1e-9)
    with pytest.raises(ProgramError, match="indeterminate at the origin"):
        P("G21 F100\nG0 X0 Y0 Z0\nG91 G81 R1 Z-1 ^30 L2\n")
    assert P("G21 F100\nG0 X0 Y0 Z0\nG91 G81 R1 Z-1 ^0 L2\n").moves     # no step: no question
