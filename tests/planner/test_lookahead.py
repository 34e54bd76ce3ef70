"""Joint speeds: Table 3 (paper mode), geometric caps (lookahead mode), passes, windows."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.core.limits import KINK_JERK_FLOOR
from planner.core.machine import AxisSpec
from planner.gcode.interpreter import parse_program
from planner.motion.lookahead import (
    ACCEL_NORMAL_SHARE,
    JERK_NORMAL_SHARE,
    LimitSet,
    plan_blocks,
    plan_whole,
)
from planner.motion.plan import plan_program
from planner.motion.profile import reachable_speed, reachable_speed_lower_bound, transition_length
from tests.planner.motion_programs import machine_with_axes, paper_machine, parse, random_program


def speeds(text: str, mode: str = "lookahead", machine=None):
    machine = machine or paper_machine()
    plan = plan_program(parse(text, machine), machine, mode=mode)
    return plan


def blocks_speeds(program, machine, mode, window):
    lim = LimitSet.from_machine(machine)
    vs, ve = [], []
    for b in plan_blocks(program, lim, mode, window):
        vs.append(b.vs)
        ve.append(b.ve)
    return np.concatenate(vs), np.concatenate(ve)


# -- passes and windows ----------------------------------------------------------------------
@pytest.mark.parametrize("mode", ["lookahead", "paper"])
@pytest.mark.parametrize("seed", range(12))
def test_windowed_plan_equals_whole_program_plan(seed, mode):
    m = paper_machine()
    prog = parse(random_program(seed, n_blocks=60), m)
    v_whole, _ = plan_whole(prog, LimitSet.from_machine(m), mode)
    for window in (2, 3, 7, 64):
        vs, ve = blocks_speeds(prog, m, mode, window)
        np.testing.assert_array_equal(vs, v_whole[:-1])
        np.testing.assert_array_equal(ve, v_whole[1:])


@pytest.mark.parametrize("mode", ["lookahead", "paper"])
@pytest.mark.parametrize("seed", range(12))
def test_every_move_reaches_its_end_speed_within_its_length(seed, mode):
    m = paper_machine()
    prog = parse(random_program(100 + seed, n_blocks=60), m)
    v, ml = plan_whole(prog, LimitSet.from_machine(m), mode)
    length = np.array([mv.length_mm for mv in prog.moves])
    need = transition_length(v[:-1], v[1:], ml.a_t, ml.j_t)
    assert np.all(need <= length * (1 + 1e-9) + 1e-12)
    assert v[0] == 0.0 and v[-1] == 0.0
    assert np.all(v[:-1] <= ml.vc * (1 + 1e-12)) and np.all(v[1:] <= ml.vc * (1 + 1e-12))


def test_reach_is_not_monotone_and_the_lower_bound_holds():
    # From rest a short move reaches more than from a small start speed (why 'final' needs care).
    L, A, J = 0.025, 1000.0, 10000.0
    v0 = np.linspace(0.0, 40.0, 4001)
    r = reachable_speed(v0, L, A, J)
    assert r[0] > r[60]  # v0 = 0.6 mm/s reaches less than v0 = 0
    assert np.all(r >= reachable_speed_lower_bound(L, A, J))
    assert r.min() == pytest.approx(float(reachable_speed_lower_bound(L, A, J)), rel=1e-4)
    for L2, A2 in ((5.0, 100.0), (50.0, 300.0)):  # 7-phase branch
        r = reachable_speed(np.linspace(0, 200, 20001), L2, A2, J)
        assert np.all(r >= reachable_speed_lower_bound(L2, A2, J))


def test_full_stops_at_events_g61_and_end():
    text = """G21 G90 G17 F1800
G01 X10
G01 X20
G04 P0.5
G01 X30
M00
G01 X40
M01
G01 X50
S3000 M03
G01 X60
M06 T2
G01 X70
G61
G01 X80
G01 X90
G64
G01 X100
G01 X110
M30
"""
    plan = speeds(text)
    ve = plan.ve
    # Moves: 0 X10, 1 X20 | G04, 2 X30 | M00, 3 X40 | M01, 4 X50 | S M03, 5 X60 | M06,
    # 6 X70, 7 X80 (G61), 8 X90 (G61), 9 X100 (G64), 10 X110 | end.
    for i in (0, 6, 9):
        assert ve[i] == pytest.approx(30.0), i  # collinear joints run through
    for i in (1, 2, 3, 4, 5, 7, 8, 10):
        assert ve[i] == 0.0, i
    # The dwell adds its time after the move.
    assert plan.t0[2] - plan.t1[1] == pytest.approx(0.5)


# -- lookahead caps ---------------------------------------------------------------------------
def test_tangent_break_with_a_velocity_step_keeps_axis_acceleration_within_one_sample():
    """A configured corner velocity step: the one-sample direction change within the axes'
    acceleration (and the step)."""
    base = paper_machine()
    m = replace(base, planner=replace(base.planner, corner_velocity_step_mm_s=5.0))
    plan = speeds("G21 G90 F1800\nG01 X10\nG01 Y10\nM30\n", machine=m)
    # 90 degree corner: |dt_k| = 1 on X and Y: v = (A - 2 Ts J) Ts / 1.
    assert plan.ve[0] == pytest.approx((1000.0 - 2 * 0.001 * 10000.0) * 0.001)
    plan = speeds("G21 G90 F1800\nG01 X10\nG01 X20 Y0.1745\nM30\n", machine=m)  # about 1 degree
    dt = np.abs(np.array([20 - 10, 0.1745]) / math.hypot(10, 0.1745) - np.array([1.0, 0.0]))
    assert plan.ve[0] == pytest.approx(min(30.0, 980.0 * 0.001 / dt.max()), rel=1e-9)
    # a smaller step binds before the acceleration: v |dt_k| <= 0.2 mm/s
    m = replace(base, planner=replace(base.planner, corner_velocity_step_mm_s=0.2))
    plan = speeds("G21 G90 F1800\nG01 X10\nG01 X20 Y0.1745\nM30\n", machine=m)
    assert plan.ve[0] == pytest.approx(0.2 / dt.max(), rel=1e-9)


def test_without_a_step_the_direction_change_keeps_axis_jerk_within_limits():
    """The default (no velocity step): v |dt_k| / Ts^2 within what the moves' own jerk leaves
    of the axis' limit; a right angle along the axes leaves nothing: all but a stop; a corner
    between diagonals leaves J (1 - 1/sqrt(2))."""
    plan = speeds("G21 G90 F1800\nG01 X10\nG01 Y10\nM30\n")
    assert plan.ve[0] == pytest.approx(KINK_JERK_FLOOR * 10_000.0 * 1e-6)
    plan = speeds("G21 G90 F1800\nG01 X10 Y10\nG01 X20 Y0\nM30\n")
    room = 10_000.0 * (1.0 - 1.0 / math.sqrt(2.0)) * 1e-6       # J_k - j_t |t_k|, times Ts^2
    dt = math.sqrt(2.0)                                           # |dt_y| = 2 / sqrt(2)
    assert plan.ve[0] == pytest.approx(room / dt, rel=1e-9)
    # and the samples say so
    text = "G21 G90 F1800\nG01 X10 Y10\nG01 X20 Y0\nG01 X30 Y0.2\nG01 Y20\nM30\n"
    machine = paper_machine()
    rep = plan_program(parse_program(text, "k.ngc", machine), machine).limit_report()
    assert rep.ok
    assert max(a["j_joint"] for a in rep.axes.values()) <= 10_000.0 * (1 + 1e-4)


def test_arc_joints_with_a_kink_and_a_curvature_jump_hold_every_axis_jerk():
    """CAM's fitted arcs (grbl's SO2_helloworld.nc, inch): each joint turns a little and steps
    the curvature; both land in the same samples, so they share what the arcs' own jerk leaves
    of the limit (each within it alone made 1.19 times the X jerk limit across a joint)."""
    text = """G20 G90 G17 G61.1 F40
G0 X7.6986 Y1.1452
G1 Z-0.01
G2 X7.7368 Y1.1441 I0 J-0.6209
G2 X7.7698 Y1.1408 I-0.0288 J-0.4669
G2 X7.8025 Y1.1351 I-0.0537 J-0.4022
G2 X7.8304 Y1.1276 I-0.0656 J-0.3011
G2 X7.8576 Y1.1176 I-0.0975 J-0.3061
G2 X7.8808 Y1.1064 I-0.0996 J-0.2366
G2 X7.9028 Y1.0929 I-0.1113 J-0.2042
G2 X7.9215 Y1.078 I-0.1143 J-0.1635
G2 X7.9383 Y1.0611 I-0.1312 J-0.1467
G2 X7.9526 Y1.0425 I-0.1419 J-0.1243
G2 X7.9645 Y1.0224 I-0.1576 J-0.1068
G2 X7.9743 Y1.0002 I-0.1832 J-0.0937
G2 X7.9816 Y0.9769 I-0.2296 J-0.085
G2 X7.987 Y0.9513 I-0.2735 J-0.0712
G2 X7.9901 Y0.9253 I-0.3042 J-0.0498
G2 X7.9912 Y0.8965 I-0.3724 J-0.0288
M2
"""
    base = paper_machine()
    axes = tuple(replace(a, v_max=100.0, a_max=1000.0, j_max=10_000.0) for a in base.axes)
    machine = replace(base, axes=axes).with_limits(v_max_mm_s=100.0, a_max_mm_s2=1000.0,
                                                   j_max_mm_s3=10_000.0, rapid_mm_s=100.0)
    rep = plan_program(parse_program(text, "so2.ngc", machine), machine).limit_report()
    assert rep.ok
    assert rep.joint_jerk["count"] == 0, rep.joint_jerk
    assert max(a["j_joint"] for a in rep.axes.values()) <= 10_000.0 * (1 + 1e-4)


def test_arc_centripetal_acceleration_and_jerk_caps():
    # R = 1 mm full circle at F3000 (50 mm/s): jerk cap v^3/R^2 <= J/2 binds, then a_n <= 0.866 A.
    m = paper_machine(vmax=100.0)
    plan = speeds("G21 G90 G17 F6000\nG00 X1 Y0\nG03 X1 Y0 I-1 J0\nM30\n", machine=m)
    r = 1.0
    expected = min(50.0 * 2, math.sqrt(ACCEL_NORMAL_SHARE * 1000.0 * r),
                   (JERK_NORMAL_SHARE * 10000.0 * r * r) ** (1 / 3))
    assert plan.vpeak[1] <= expected * (1 + 1e-12)
    assert plan.vpeak[1] == pytest.approx(expected, rel=1e-6)


def test_curvature_jump_at_a_tangent_joint_is_limited():
    # Line into a tangent arc of R = 5: the normal acceleration jumps from 0 to v^2/R.
    plan = speeds("G21 G90 G17 F1800\nG01 X10 Y0\nG03 X15 Y5 I0 J5\nM30\n")
    v = plan.ve[0]
    assert v == pytest.approx(math.sqrt(10000.0 * 0.001 * 5.0), rel=1e-9)


def test_per_axis_velocity_limit_including_rotary():
    axes = [AxisSpec("X", v_max=30, a_max=1000, j_max=10000),
            AxisSpec("Y", drive_position=1, v_max=30, a_max=1000, j_max=10000),
            AxisSpec("Z", drive_position=2, v_max=5, a_max=1000, j_max=10000),
            AxisSpec("A", rotary=True, drive_position=3, v_max=90, a_max=1800, j_max=36000,
                     min_pos=-1e5, max_pos=1e5)]
    m = machine_with_axes(axes)
    # X 10 mm with A 180 deg: tangent A = 18 deg/mm -> v <= 90 / 18 = 5 mm/s.
    plan = speeds("G21 G90 F1800\nG01 X10 A180\nG01 X20 Z10\nM30\n", machine=m)
    assert plan.vpeak[0] == pytest.approx(5.0)
    # Z at 45 degrees: Z component 0.707 -> v <= 5 / 0.707.
    assert plan.vpeak[1] == pytest.approx(5.0 / math.sqrt(0.5))


def test_rotary_only_move_runs_in_degrees():
    axes = [AxisSpec("X"), AxisSpec("Y", drive_position=1), AxisSpec("Z", drive_position=2),
            AxisSpec("C", rotary=True, drive_position=3, v_max=20, a_max=1000, j_max=10000,
                     min_pos=-1e5, max_pos=1e5)]
    m = machine_with_axes(axes)
    plan = speeds("G21 G90 F1800\nG01 C90\nM30\n", machine=m)
    assert plan.vpeak[0] == pytest.approx(20.0)
    assert plan.limit_report().ok


# -- paper mode: Table 3 ------------------------------------------------------------------------
def test_paper_table3_fig7_and_g01_joints():
    plan = speeds((__import__("pathlib").Path(__file__).resolve().parents[2]
                   / "resources/programs/fig7_circle.nc").read_text(), mode="paper")
    # Five G02 arcs then a G01: joints G02->G02 here fall in "Norm1, beta >= 90" -> Vmax / 2,
    # G02 -> G01 -> 0 (Fig. 7).
    np.testing.assert_allclose(plan.ve, [15.0, 15.0, 15.0, 15.0, 0.0, 0.0])


@pytest.mark.parametrize(
    "text, expected, case",
    [
        # G03 -> G03 consecutive half circles (Fig. 9): beta = 0 < 90, Norm1 -> Vmax.
        ("G03 X20 Y0 R10\nG03 X0 Y0 R10", 30.0, "G03->G03 Norm1 beta<90"),
        # G03 then G02 continuing straight on (an S): beta = 180 >= 90 -> Vmax.
        ("G03 X20 Y0 R10\nG02 X40 Y0 R10", 30.0, "G03->G02 beta>=90"),
        # G02 -> G02 turning left (against the arc's sense): Norm-1, beta >= 90 -> Vmax/2.
        ("G02 X20 Y0 R10\nG02 X30 Y10 R10", 15.0, "G02->G02 Norm-1 beta>=90"),
        # G02 -> G02 turning right sharply: Norm1, beta < 90 -> Vmax.
        ("G02 X20 Y0 R10\nG02 X5 Y-5 R10", 30.0, "G02->G02 Norm1 beta<90"),
        # G02 -> G03 with a sharp turn: beta < 90 -> 0.
        ("G02 X20 Y0 R10\nG03 X5 Y-5 R10", 0.0, "G02->G03 beta<90"),
        ("G01 X20 Y0\nG03 X40 Y0 R10", 0.0, "G01->G03"),
    ],
)
def test_paper_table3_cases(text, expected, case):
    plan = speeds(f"G21 G90 G17 F1800\n{text}\nM30\n", mode="paper")
    assert plan.ve[0] == pytest.approx(expected), case


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.integers(-1, 30), st.sampled_from(["dwell", "pause", "coolant"]),
                          st.floats(0.0, 2.0)), max_size=12),
       st.integers(0, 30), st.integers(0, 30))
def test_the_stops_and_dwells_of_a_window_are_the_programs(events, a, b):
    # kept as the few rows they are; any window of moves reads them as one flag and one dwell
    # a move, as the look-ahead wants them
    from planner.core.program import Coolant, CoolantSwitch, Dwell, Event, EventKind
    from planner.motion.lookahead import stops_and_dwells

    a, b = min(a, b), max(a, b)
    kinds = {"dwell": EventKind.DWELL, "pause": EventKind.PAUSE, "coolant": EventKind.COOLANT}
    prog = parse_program("G1 F600\n" + "".join(f"X{i + 1}\n" for i in range(30)))
    payloads = {"dwell": Dwell, "pause": lambda _v: None,
                "coolant": lambda _v: CoolantSwitch(Coolant.FLOOD_ON)}
    evs = tuple(Event(kinds[k], 1, i, payloads[k](v), "") for i, k, v in events)
    prog = replace(prog, events=evs)
    stop = np.zeros(30, bool)
    dwell = np.zeros(30)
    before = 0.0
    for ev in evs:                          # one after the last move (30) acts nowhere
        if ev.kind is EventKind.DWELL:
            if ev.after_move < 0:
                before += ev.payload_as(Dwell).seconds
            elif ev.after_move < 30:
                dwell[ev.after_move] += ev.payload_as(Dwell).seconds
        if ev.stops and 0 <= ev.after_move < 30:
            stop[ev.after_move] = True
    stop[-1] = True
    sd = stops_and_dwells(prog)
    np.testing.assert_array_equal(sd.stops(a, b), stop[a:b])
    np.testing.assert_array_equal(sd.dwells(a, b), dwell[a:b])
    assert sd.before_s == before


def test_the_corner_step_key_is_read_checked_and_reported(tmp_path) -> None:
    """``[planner] corner_velocity_step_mm_s``: read, refused out of its range with the key and
    line; what it allows shows in ``cnc-plan --json``'s ``corner_steps`` (none by default)."""
    import json
    import subprocess
    import sys

    from planner.core.errors import PlannerError
    from planner.core.machine import load_machine

    base = ("[[axes]]\nname = \"X\"\ndrive_position = 0\nmin = -100.0\nmax = 100.0\nv_max = 30.0\n"
            "a_max = 1000.0\nj_max = 10000.0\n[[axes]]\nname = \"Y\"\ndrive_position = 1\nmin = -100.0\n"
            "max = 100.0\nv_max = 30.0\na_max = 1000.0\nj_max = 10000.0\n[planner]\n")
    path = tmp_path / "m.toml"
    path.write_text(base + "corner_velocity_step_mm_s = 0.5\n", encoding="utf-8")
    assert load_machine(path).planner.corner_velocity_step_mm_s == 0.5
    path.write_text(base + "corner_velocity_step_mm_s = -1\n", encoding="utf-8")
    with pytest.raises(PlannerError, match=r"m.toml:18: planner.corner_velocity_step_mm_s: must be within"):
        load_machine(path)
    program = tmp_path / "square.ngc"
    program.write_text("G21 G90 G61.1 F1200\nG1 X10\nY10\nX0\nY0\nM2\n", encoding="utf-8")
    found = {}
    for step in (0.0, 0.5):
        path.write_text(base + f"corner_velocity_step_mm_s = {step}\n", encoding="utf-8")
        out = subprocess.run([sys.executable, "-m", "cli.plan", str(program), "--config", str(path),
                              "--json"], capture_output=True, text=True, check=True)
        found[step] = json.loads(out.stdout)
    assert found[0.0]["corner_steps"] == {"count": 0, "largest_mm_s": 0.0, "lines": []}
    assert found[0.0]["joint_jerk"]["count"] == 0
    assert found[0.5]["corner_steps"]["count"] == 3
    assert found[0.5]["corner_steps"]["lines"] == [3, 4, 5]
    assert found[0.5]["corner_steps"]["largest_mm_s"] == pytest.approx(0.5, rel=1e-6)
    assert found[0.5]["joint_jerk"]["worst_ratio"] > 10.0
    assert found[0.5]["cycle_time_s"] < found[0.0]["cycle_time_s"]
