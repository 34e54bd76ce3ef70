"""Corner blending under G64 P: clothoid pairs between lines, within the tolerance and every limit.

What is specified here: a blend leaves the programmed path by at most P (measured on the
samples, against the programmed polyline); position, tangent and curvature are continuous
where it meets its lines, so the per-axis jerk holds through the corner (closed form and
finite differences); it takes at most half of each line; the rest of the path is exact; the
default rule blends only where the corner gets quicker; G61, G61.1, G64 P0 and events at the
joint keep the corner sharp; events, modal texts and resume points keep their place.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from planner.core.curves import Blend, pair_frames, unit_pair
from planner.core.errors import PlannerError
from planner.core.machine import MachineSpec, load_machine
from planner.core.program import EventKind, MoveKind
from planner.gcode.interpreter import parse_program
from planner.geometry.blend import (
    blend_report,
    blend_speed,
    corner_sizes,
    merge_naive_cam,
    round_fillets,
)
from planner.geometry.resume import remaining_program, split_move
from planner.geometry.softlimits import check_program
from planner.motion.blending import blend_program
from planner.motion.lookahead import LimitSet
from planner.motion.plan import plan_program
from tests.planner.motion_programs import paper_machine


def planned(m: MachineSpec):  # noqa: ANN201 - planner.geometry.blend.SpeedOracle
    """The oracle the planner gives the geometry: the plan of the program as it stands."""
    return lambda p: plan_program(p, m)


def fast_machine() -> MachineSpec:
    """100 mm/s, 1000 mm/s^2, 10,000 mm/s^3 per axis and path (LinuxCNC comparison runs)."""
    base = paper_machine()
    axes = tuple(replace(a, v_max=100.0, a_max=1000.0, j_max=10_000.0) for a in base.axes)
    return replace(base, axes=axes).with_limits(v_max_mm_s=100.0, a_max_mm_s2=1000.0, j_max_mm_s3=10_000.0,
                                                rapid_mm_s=100.0)


def polyline_text(points, tol: float, feed: float = 6000.0, mode: str | None = None) -> str:
    # Q0: corners only (G64 Q, joining lines, is checked on its own below)
    head = mode if mode is not None else f"G64 P{tol:.12f} Q0"
    out = [f"G21 G90 {head}", f"G0 X{points[0][0]:.9f} Y{points[0][1]:.9f} Z{points[0][2]:.9f}",
           f"G1 F{feed:g}"]
    out += [f"X{p[0]:.9f} Y{p[1]:.9f} Z{p[2]:.9f}" for p in points[1:]]
    return "\n".join(out + ["M2"]) + "\n"


def corner(deg: float, leg: float = 10.0):
    a = math.radians(deg)
    x0, y0 = 1.0, 2.0  # away from the start position, so the rapid to it is a move
    return [(x0, y0, 0.0), (x0 + leg, y0, 0.0), (x0 + leg + leg * math.cos(a), y0 + leg * math.sin(a), 0.0)]


def distance_to_polyline(q: np.ndarray, pts: np.ndarray) -> np.ndarray:
    a, b = pts[:-1], pts[1:]
    d = b - a
    rel = q[:, None, :] - a[None, :, :]
    t = np.clip((rel * d).sum(axis=2) / np.maximum((d * d).sum(axis=1), 1e-300), 0.0, 1.0)
    return np.sqrt(((rel - t[..., None] * d) ** 2).sum(axis=2)).min(axis=1)


def blend_axis_derivatives(plan, n_per_move: int = 96):
    """Per-axis velocity, acceleration and jerk on the blends, in closed form: q' = T v,
    q'' = K v^2 + T a, q''' = K' v^3 + 3 K v a + T j with K = kappa N, K' = kappa' N - kappa^2 T."""
    seg = plan.segment
    tab, prof = seg.table, seg.profiles
    rows = np.nonzero(tab.is_blend)[0]
    move = np.repeat(rows, n_per_move)
    tau = np.tile(np.linspace(0.0, 1.0, n_per_move), rows.size) * prof.duration[move]
    s, v, a, j = prof.evaluate(move, tau)
    arc_s = tab.bl_s0[move] + s
    half, theta = tab.bl_half[move], tab.bl_turn[move]
    t_vec, k_vec = pair_frames(tab.bl_a[move], tab.bl_u1[move], tab.bl_n1[move], tab.end[move], half, theta,
                               arc_s, tab.bl_arc[move], tab.bl_poly[move])
    u1, n1 = tab.bl_u1[move], tab.bl_n1[move]
    cos_psi = (t_vec * u1).sum(axis=1)[:, None]
    sin_psi = (t_vec * n1).sum(axis=1)[:, None]
    normal = -sin_psi * u1 + cos_psi * n1
    kappa = np.sqrt((k_vec * k_vec).sum(axis=1))[:, None]
    arc_len = tab.bl_arc[move]
    # dkappa/ds: + 1 / (R_c L_c) on the first clothoid, 0 on a fillet's arc, - on the last one;
    # a transition's from its cubic (signed, as its curvature vector kappa N with N left of T)
    sign = np.where(arc_s <= half, 1.0, np.where(arc_s >= half + arc_len, -1.0, 0.0))
    dkappa = sign * theta / (half * (half + arc_len))
    poly = tab.bl_poly[move]
    is_poly = ~np.isnan(poly[:, 0])
    dkappa = np.where(is_poly, poly[:, 1] + arc_s * (2.0 * poly[:, 2] + 3.0 * arc_s * poly[:, 3]), dkappa)
    dkappa = dkappa[:, None]
    k_prime = dkappa * normal - kappa * kappa * t_vec
    vv, aa, jj = v[:, None], a[:, None], j[:, None]
    return t_vec * vv, k_vec * vv**2 + t_vec * aa, k_prime * vv**3 + 3.0 * k_vec * vv * aa + t_vec * jj


def test_unit_pair_matches_its_definition() -> None:
    """X, Y of the unit pair against a fine trapezoid sum; T and D from the symmetry."""
    for theta in (1e-6, 0.1, 1.0, math.pi / 2, 3.0):
        x = np.linspace(0.0, 1.0, 200_001)
        phase = 0.5 * theta * x * x
        xr = np.trapezoid(np.cos(phase), x)
        yr = np.trapezoid(np.sin(phase), x)
        x1, y1, t1, d1 = unit_pair(np.array([theta]))
        assert abs(x1[0] - xr) < 1e-10 and abs(y1[0] - yr) < 1e-10
        assert t1[0] == pytest.approx(xr + yr * math.tan(theta / 2), rel=1e-9)
        assert d1[0] == pytest.approx(yr / math.cos(theta / 2), rel=1e-9)


@pytest.mark.parametrize("deg", [0.5, 5.0, 30.0, 90.0, 150.0])
def test_a_blend_meets_its_lines_smoothly_and_stays_within_the_tolerance(deg: float) -> None:
    m = fast_machine()
    tol = 0.01
    pts = corner(deg)
    prog = blend_program(parse_program(polyline_text(pts, tol), "c.ngc", m), m, only_where_quicker=False)
    kinds = [mv.kind for mv in prog.moves]
    assert kinds == [MoveKind.RAPID, MoveKind.LINE, MoveKind.BLEND, MoveKind.LINE]
    line_in, bl, line_out = prog.moves[1:]
    # continuous position (exactly: the same points), tangent and curvature
    np.testing.assert_array_equal(line_in.end, bl.start)
    np.testing.assert_array_equal(bl.end, line_out.start)
    p, t, k = bl.evaluate(np.array([0.0, bl.length_mm]))
    np.testing.assert_allclose(p[0], line_in.end, atol=1e-12)
    np.testing.assert_allclose(p[1], line_out.start, atol=1e-12)
    np.testing.assert_allclose(t[0], (line_in.end - line_in.start) / line_in.length_mm, atol=1e-12)
    np.testing.assert_allclose(t[1], (line_out.end - line_out.start) / line_out.length_mm, atol=1e-12)
    assert np.all(k < 1e-9)
    # within P of the corner and of the programmed lines, at most half of each line
    u = np.linspace(0.0, bl.length_mm, 4001)
    q, tq, kq = bl.evaluate(u)
    corner_pt = np.array(pts[1])
    dist_corner = np.sqrt(((q - corner_pt) ** 2).sum(axis=1)).min()
    assert dist_corner <= tol * (1 + 1e-9)
    assert distance_to_polyline(q, np.array(pts)).max() <= tol * (1 + 1e-9)
    assert line_in.length_mm >= 5.0 - 1e-9 and line_out.length_mm >= 5.0 - 1e-9
    # the curve is parametrised by its length, its curvature peaks in the middle at 1 / R, the
    # clothoids and the arc between them turning theta: R = (L_c + L_a) / theta
    chord = np.sqrt((np.diff(q, axis=0) ** 2).sum(axis=1)).sum()
    assert chord == pytest.approx(bl.length_mm, rel=1e-6)
    np.testing.assert_allclose(np.sqrt((tq * tq).sum(axis=1)), 1.0, atol=1e-12)
    assert kq.max() == pytest.approx(math.radians(deg) / (bl.blend.half_mm + bl.blend.arc_mm), rel=1e-6)
    assert blend_report(prog).max_corner_deviation_mm == pytest.approx(dist_corner, rel=1e-6, abs=1e-12)


def test_every_blended_corner_holds_every_axis_limit_without_a_velocity_step() -> None:
    """A zigzag, all corners blended: per-axis v, a, j in closed form on the blends, the limit
    report on the samples, and no jerk at the joints beyond the limit (no velocity step)."""
    m = fast_machine()
    pts = [(i * 4.0, (i % 2) * 0.7, 0.1 * i) for i in range(12)]
    sharp = parse_program(polyline_text(pts, 0.02), "z.ngc", m)
    prog = blend_program(sharp, m, only_where_quicker=False)
    assert blend_report(prog).blends == 10
    plan = plan_program(prog, m)
    qv, qa, qj = blend_axis_derivatives(plan)
    lim = LimitSet.from_machine(m)
    assert np.all(np.abs(qv) <= lim.v_axis * (1 + 1e-9))
    assert np.all(np.abs(qa) <= lim.a_axis * (1 + 1e-9))
    assert np.all(np.abs(qj) <= lim.j_axis * (1 + 1e-9))
    rep = plan.limit_report()
    assert rep.violations == {}
    assert rep.joint_jerk["worst_ratio"] <= 1.0 + 1e-6
    assert rep.contour_error_mm < 1e-9
    # the sharp corners: crossed with a velocity step where one is configured (its jerk is
    # what the blends remove), nearly stopped at within the jerk limit by default
    stepping = replace(m, planner=replace(m.planner, corner_velocity_step_mm_s=1.0))
    assert plan_program(sharp, stepping).limit_report().joint_jerk["worst_ratio"] > 10.0
    sharp_plan = plan_program(sharp, m)
    assert max(a["j_joint"] for a in sharp_plan.limit_report().axes.values()) <= 10_000.0 * (1 + 1e-4)
    assert plan.cycle_time_s < sharp_plan.cycle_time_s


def test_small_turns_between_long_lines_get_quicker() -> None:
    """5 degree corners between 10 mm lines at 100 mm/s: the blend is crossed at about 35 mm/s
    where the sharp corner's one-sample velocity step allows 11 mm/s."""
    m = fast_machine()
    rise = 10.0 * math.tan(math.radians(2.5))  # segments at +-2.5 degrees: 5 degree turns
    pts = [(1.0 + 10.0 * i, rise * (i % 2), 0.0) for i in range(8)]
    sharp = parse_program(polyline_text(pts, 0.01), "s.ngc", m)
    blended = blend_program(sharp, m)
    # every corner, the last one too: it lies on the braking ramp to the program's end, but
    # the sharp plan crosses it at its own cap (the corner, not the end, holds the speed down;
    # leaving it sharp took 0.05 s more)
    assert blend_report(blended).blends == 6
    t_sharp = plan_program(sharp, m).cycle_time_s
    t_blend = plan_program(blended, m).cycle_time_s
    assert t_blend < 0.95 * t_sharp, (t_blend, t_sharp)


def test_a_run_of_short_kinked_chords_is_blended_throughout() -> None:
    """A CAM contour of 0.4 mm chords turning by 6, 16 and 10 degrees in turn at 20 mm/s: the
    sharp plan is slowest at the 16 degree joints and climbs a little towards the others; each
    joint is blended where every slower joint it brakes for is blended too, so the whole run is
    (taking only the slowest joint of each run leaves 27 of 39 sharp: 2.24 s)."""
    m = fast_machine()
    pts = [(5.0, 5.0, 0.0)]
    heading = 0.0
    for i in range(40):
        heading += math.radians((6.0, 16.0, 10.0)[i % 3])
        x, y, _ = pts[-1]
        pts.append((x + 0.4 * math.cos(heading), y + 0.4 * math.sin(heading), 0.0))
    sharp = parse_program(polyline_text(pts, 0.01, feed=1200.0), "chords.ngc", m)
    blended = blend_program(sharp, m)
    assert blend_report(blended).blends == 39
    assert blend_report(blended).max_corner_deviation_mm <= 0.01 * (1 + 1e-9)
    plan = plan_program(blended, m)
    assert plan.cycle_time_s < 0.8 * plan_program(sharp, m).cycle_time_s
    assert plan.limit_report().ok


def test_the_default_rule_keeps_a_tight_right_angle_sharp() -> None:
    """A 90 degree corner within 0.01 mm at J = 10,000 mm/s^3: the jerk-limited blend is about
    as slow as the velocity step (1 mm/s) and longer, so the quicker sharp corner stays."""
    m = fast_machine()
    sharp = parse_program(polyline_text(corner(90.0), 0.01, feed=1000.0), "r.ngc", m)
    assert blend_program(sharp, m) is sharp


@pytest.mark.parametrize("mode", ["G61", "G61.1", "G64 P0", "G64"])
def test_other_path_modes_keep_the_corner(mode: str) -> None:
    m = fast_machine()  # its default tolerance is 0: G64 alone keeps the path too
    prog = parse_program(polyline_text(corner(5.0), 0.01, mode=mode), "k.ngc", m)
    assert blend_program(prog, m, only_where_quicker=False) is prog


def test_g64_alone_takes_the_machine_default_and_m72_restores_the_tolerance() -> None:
    m = fast_machine().with_planner(blend_tolerance_mm=0.05)
    text = ("G21 G90 G64\nG0 X1 Y0\nG1 F6000 X10\nX20 Y1\nM70\nG64 P0.001\nX30 Y1\nX40 Y2\nM72\n"
            "X50 Y2\nX60 Y3\nG61.1\nX70 Y3\nX80 Y4\nM2\n")
    prog = parse_program(text, "d.ngc", m)
    assert prog.blend_tolerance == ((0, 0.05), (3, 0.001), (5, 0.05), (7, 0.0))
    bl = blend_program(prog, m, only_where_quicker=False)
    devs = [mv.blend.deviation_mm for mv in bl.moves if mv.blend is not None]
    # joints 1-2 (0.05), 2-3 (0.05 / 0.001: the smaller), 3-4 (0.001), 4-5 (0.001 / 0.05), 5-6 (0.05)
    assert len(devs) == 5
    assert devs[0] == pytest.approx(0.05, rel=1e-9) and devs[4] == pytest.approx(0.05, rel=1e-6)
    assert max(devs[1:4]) <= 0.001 * (1 + 1e-9)


def test_inch_tolerance_is_converted() -> None:
    m = fast_machine()
    prog = parse_program("G20 G90 G64 P0.001\nG0 X0 Y0\nG1 F100 X1\nX2 Y0.1\nM2\n", "i.ngc", m)
    assert prog.blend_tolerance[-1] == (0, pytest.approx(0.0254))


def test_events_at_a_joint_keep_it_sharp_and_keep_their_place() -> None:
    m = fast_machine()
    text = ("G21 G90 G64 P0.01\nG0 X1 Y0\nG1 F6000 X10\n(MSG, here)\nX20 Y0.9\nX30 Y0\nG91 X10 Y0.9\nG90\n"
            "X50 Y0\nM2\n")
    prog = parse_program(text, "e.ngc", m)
    bl = blend_program(prog, m, only_where_quicker=False)
    assert blend_report(bl).blends == 3  # not at the message
    msg = next(e for e in bl.events if e.kind is EventKind.MESSAGE)
    np.testing.assert_array_equal(bl.moves[msg.after_move].end, [10.0, 0.0, 0.0])
    # the modal change (G91 on line 7) starts at that line's move, after the blend into it
    first_g91 = next(first for first, modal in bl.modal if "G91" in modal)
    assert bl.moves[first_g91].line == 7 and bl.moves[first_g91].kind is MoveKind.LINE
    assert bl.moves[first_g91 - 1].kind is MoveKind.BLEND
    assert len(bl.move_frames) == len(bl.moves)


def assert_resume_follows(prog, m, fraction: float) -> None:
    """A stop at ``fraction`` of the program's first blend resumes on the same curve, within
    every limit."""
    i = next(k for k, mv in enumerate(prog.moves) if mv.kind is MoveKind.BLEND)
    bl = prog.moves[i]
    u = fraction * bl.length_mm
    tail = split_move(bl, u)
    w = np.linspace(0.0, tail.length_mm, 50)
    np.testing.assert_allclose(tail.evaluate(w)[0], bl.evaluate(u + w)[0], atol=1e-12)
    np.testing.assert_array_equal(tail.end, bl.end)
    rest = remaining_program(prog, i, u)
    np.testing.assert_allclose(rest.start_position, bl.evaluate(np.array([u]))[0][0], atol=1e-12)
    assert plan_program(rest, m).limit_report().violations == {}


def test_a_resume_inside_a_blend_follows_the_same_curve() -> None:
    m = fast_machine()
    prog = blend_program(parse_program(polyline_text(corner(30.0), 0.05), "r.ngc", m), m,
                         only_where_quicker=False)
    assert_resume_follows(prog, m, 0.37)


def test_soft_limits_still_see_the_programmed_corner() -> None:
    m = fast_machine()
    axes = tuple(replace(a, max_pos=10.0) if a.name == "X" else a for a in m.axes)
    m = replace(m, axes=axes)
    text = polyline_text([(0.0, 0.0, 0.0), (10.005, 0.0, 0.0), (0.0, 1.0, 0.0)], 0.01)
    prog = blend_program(parse_program(text, "l.ngc", m), m, only_where_quicker=False)
    assert blend_report(prog).blends == 1
    over = check_program(prog, m)
    assert over and over[0].axis == "X"


def test_the_configuration_key_is_checked(tmp_path) -> None:
    base = ("[[axes]]\nname = \"X\"\ndrive_position = 0\nmin = -10.0\nmax = 10.0\nv_max = 10.0\n"
            "a_max = 100.0\nj_max = 1000.0\n[planner]\n")
    path = tmp_path / "m.toml"
    path.write_text(base + "blend_tolerance_mm = 0.02\n", encoding="utf-8")
    assert load_machine(path).planner.blend_tolerance_mm == 0.02
    path.write_text(base + "blend_tolerance_mm = -1\n", encoding="utf-8")
    with pytest.raises(PlannerError, match="blend_tolerance_mm"):
        load_machine(path)


def test_cnc_plan_reports_the_largest_deviation(tmp_path) -> None:
    path = tmp_path / "p.ngc"
    rise = 10.0 * math.tan(math.radians(2.5))
    path.write_text(polyline_text([(1.0 + 10.0 * i, rise * (i % 2), 0.0) for i in range(6)], 0.01))
    out = subprocess.run([sys.executable, "-m", "cli.plan", str(path), "--json", "--vmax", "100"],
                         capture_output=True, text=True, check=True).stdout
    rep = json.loads(out)
    assert rep["blends"] >= 1
    assert 0.0 < rep["path_deviation_mm"] <= 0.01 * (1 + 1e-9)
    assert rep["path_deviation_line"] >= 4
    assert rep["ok"]


_coord = st.floats(-1.0, 1.0, allow_nan=False)


@settings(max_examples=40, deadline=None)
@given(pts=st.lists(st.tuples(_coord, _coord, _coord), min_size=3, max_size=9),
       tol=st.floats(0.001, 0.3), scale=st.sampled_from([0.001, 1.0, 1000.0]),
       feed=st.sampled_from([300.0, 3000.0, 6000.0]), every=st.booleans())
def test_random_polylines_blend_within_the_tolerance_and_the_limits(pts, tol, scale, feed, every) -> None:
    """Random 3-D polylines at 0.001x, 1x and 1000x: every sample within P of the programmed
    polyline, every limit held (finite differences of the samples), blends exact end points."""
    m = fast_machine()
    axes = tuple(replace(a, min_pos=-5000.0, max_pos=5000.0) for a in m.axes)
    m = replace(m, axes=axes)
    p = np.array(pts) * 10.0 * scale
    keep = [p[0]]
    for q in p[1:]:
        if np.abs(q - keep[-1]).max() > 1e-3 * scale:
            keep.append(q)
    if len(keep) < 3:
        return
    p = np.array(keep)
    # metre-long paths at full speed, so that a case stays a few seconds of samples
    text = polyline_text(p, tol * scale, feed=6000.0 if scale > 1.0 else feed)
    prog = blend_program(parse_program(text, "f.ngc", m), m, only_where_quicker=not every)
    plan = plan_program(prog, m)
    rep = plan.limit_report()
    assert rep.violations == {}, rep.violations
    assert rep.end_error_mm == 0.0
    # the programmed path: the rapid from the origin, then the polyline
    prog_pts = np.vstack([np.zeros((1, 3)), p])
    q = plan.collect().q
    # printed with 9 decimals: the programmed points are those of the text
    assert distance_to_polyline(q, prog_pts).max() <= tol * scale * (1 + 1e-6) + 1e-12
    for mv in prog.moves:
        if mv.blend is not None:
            assert mv.blend.deviation_mm <= tol * scale * (1 + 1e-9) + 1e-12  # P printed to 1e-12


# -- G64 Q: LinuxCNC's naive CAM tolerance -----------------------------------------------------
def lines_text(points, head: str, feed: float = 3000.0) -> str:
    out = [f"G21 G90 {head}", f"G0 X{points[0][0]:.6f} Y{points[0][1]:.6f}", f"G1 F{feed:g}"]
    out += [f"X{p[0]:.6f} Y{p[1]:.6f}" for p in points[1:]]
    return "\n".join(out + ["M2"]) + "\n"


def test_nearly_collinear_lines_within_q_run_as_one_line() -> None:
    m = fast_machine()
    pts = [(1.0 + i, 0.004 * (i % 2)) for i in range(11)]  # 10 segments, 4 um off a line
    prog = parse_program(lines_text(pts, "G64 P0 Q0.005"), "q.ngc", m)
    assert prog.naive_cam_tolerance[-1] == (0, 0.005)
    merged = merge_naive_cam(prog)
    lines = [mv for mv in merged.moves if mv.kind is MoveKind.LINE]
    assert len(lines) == 1
    np.testing.assert_array_equal(lines[0].start[:2], pts[0])
    np.testing.assert_array_equal(lines[0].end[:2], pts[-1])
    assert lines[0].line == 13 and lines[0].length_mm == pytest.approx(10.0)
    # a point that takes an earlier one further than Q from the chain's line ends the chain
    # before it: (3, 0) is 0.0067 from the line (1, 0)-(7, 0.02)
    pts[6] = (7.0, 0.02)
    split = merge_naive_cam(parse_program(lines_text(pts, "G64 P0 Q0.005"), "q.ngc", m))
    assert [mv.end[0] for mv in split.moves if mv.kind is MoveKind.LINE][0] == 6.0


def test_q_follows_linuxcnc_defaults_and_chain_limit() -> None:
    m = fast_machine()
    pts = [(1.0 + 0.1 * i, 0.0) for i in range(151)]  # 150 collinear segments
    for head, expected in (("G64 P0.01", 2), ("G64 P0.01 Q0", 150), ("G61.1", 150), ("G64", 150)):
        prog = merge_naive_cam(parse_program(lines_text(pts, head), "c.ngc", m))
        # at most 101 points per chain (LinuxCNC's limit): 101 + 49 segments; Q defaults to P
        assert sum(mv.kind is MoveKind.LINE for mv in prog.moves) == expected, head
    assert merge_naive_cam(parse_program(lines_text(pts, "G64 P0.01"), "c.ngc", m)).moves[1].end[0] == \
        pytest.approx(1.0 + 10.1)


@pytest.mark.parametrize("between", ["F1000", "(MSG, x)", "G0 X4 Y1\nX4 Y0\nG1", "M8", "G4 P0",
                                     "G91 X1\nG90"])
def test_a_chain_stops_at_a_feed_change_an_event_a_rapid_or_a_mode(between: str) -> None:
    m = fast_machine()
    text = "G21 G90 G64 P0.01\nG0 X1 Y0\nG1 F3000 X2\nX3\nX4\n" + between + "\nX6\nX7\nM2\n"
    prog = parse_program(text, "s.ngc", m)
    merged = merge_naive_cam(prog)
    ends = [round(float(mv.end[0]), 6) for mv in merged.moves if mv.kind is MoveKind.LINE]
    # the G91 block is its own move: the mode changes at it and again after it
    assert ends[0] == 4.0 and ends[-1] == 7.0 and len(ends) == (3 if "G91" in between else 2)
    for ev in merged.events:
        if ev.after_move >= 0 and ev.kind is not EventKind.END:
            assert merged.moves[ev.after_move].end[0] == 4.0


@settings(max_examples=40, deadline=None)
@given(noise=st.lists(st.floats(-1.0, 1.0), min_size=3, max_size=60), q=st.floats(0.001, 0.1),
       scale=st.sampled_from([0.001, 1.0, 1000.0]), step=st.floats(0.01, 2.0))
def test_merged_paths_pass_within_q_of_every_programmed_point(noise, q, scale, step) -> None:
    """Noisy straight runs at 0.001x, 1x and 1000x: the merged path goes through points of the
    program only, leaves no programmed point further than Q away, and plans within limits."""
    m = fast_machine()
    m = replace(m, axes=tuple(replace(a, min_pos=-1e6, max_pos=1e6) for a in m.axes))
    pts = [((1.0 + step * i) * scale, 0.8 * q * n * scale) for i, n in enumerate(noise)]
    prog = parse_program(lines_text(pts, f"G64 P0 Q{q * scale:.12f}", feed=6000.0), "n.ngc", m)
    merged = merge_naive_cam(prog)
    assert len(merged.moves) <= len(prog.moves)
    programmed = np.array([mv.end[:2] for mv in prog.moves])
    ends = np.array([mv.end[:2] for mv in merged.moves])
    assert all(np.any(np.all(programmed == e, axis=1)) for e in ends)  # a program point each
    path = np.vstack([np.zeros((1, 3)), np.array([mv.end for mv in merged.moves])])
    far = distance_to_polyline(np.column_stack([programmed, np.zeros(len(programmed))]), path)
    assert far.max() <= q * scale * (1 + 1e-9) + 1e-12
    assert plan_program(merged, m).limit_report().violations == {}
    # the program's moves as columns and as Move objects merge alike
    objects = merge_naive_cam(replace(prog, moves=tuple(prog.moves)))
    assert [(mv.line, mv.end.tolist(), mv.length_mm, mv.exact_stop) for mv in objects.moves] == \
        [(mv.line, mv.end.tolist(), mv.length_mm, mv.exact_stop) for mv in merged.moves]


# -- fillets: a tangent arc between two lines eased by clothoids ------------------------------
RECTANGLE = """G21 G90 G64 P{tol} Q0
G1 F{feed} X40
G3 X42 Y0 R2
G1 Y20
G3 X40 Y22 R2
G1 X0
G3 X-2 Y20 R2
G1 Y0
G3 X0 Y-2 R2
G1 X20
M2
"""


def rectangle(m, tol: float = 0.01, feed: float = 3000.0):
    return parse_program(RECTANGLE.format(tol=tol, feed=feed), "rect.ngc", m,
                         start_position=np.array([0.0, -2.0, 0.0]))


def distance_to_program(q: np.ndarray, program) -> np.ndarray:
    """Distance of points from the programmed path (lines as segments, arcs exactly)."""
    best = np.full(len(q), np.inf)
    for mv in program.moves:
        if mv.arc is None:
            best = np.minimum(best, distance_to_polyline(q, np.array([mv.start, mv.end])))
        else:
            a = mv.arc
            ang = np.arctan2(q[:, 1] - a.center[1], q[:, 0] - a.center[0])
            rel = np.remainder((ang - a.start_angle_rad) * np.sign(a.sweep_rad), 2 * np.pi)
            # a spiral (CAM's rounding) changes its radius in proportion to the angle
            r_at = a.radius_start_mm + (a.radius_end_mm - a.radius_start_mm) * np.clip(
                rel / abs(a.sweep_rad), 0.0, 1.0)
            radial = np.abs(np.hypot(q[:, 0] - a.center[0], q[:, 1] - a.center[1]) - r_at)
            ends = np.minimum(np.linalg.norm(q - mv.start, axis=1), np.linalg.norm(q - mv.end, axis=1))
            best = np.minimum(best, np.where(rel <= abs(a.sweep_rad), np.hypot(radial, q[:, 2] - mv.start[2]),
                                             ends))
    return best


def test_fillets_ease_onto_a_smaller_circle_within_the_tolerance() -> None:
    m = fast_machine()
    sharp = rectangle(m)
    prog = round_fillets(sharp, m)
    kinds = [mv.kind.name for mv in prog.moves]
    assert kinds == ["LINE", "BLEND"] * 4 + ["LINE"]
    for a, b in zip(prog.moves[:-1], prog.moves[1:]):
        np.testing.assert_array_equal(a.end, b.start)
        ta = a.evaluate(np.array([a.length_mm]))
        tb = b.evaluate(np.array([0.0]))
        np.testing.assert_allclose(ta[1], tb[1], atol=1e-9)      # tangent
        assert ta[2][0] < 1e-9 and tb[2][0] < 1e-9                 # curvature 0 where they meet
    for mv in prog.moves:
        if mv.blend is None:
            continue
        bl = mv.blend
        assert bl.turn_rad == pytest.approx(math.pi / 2, abs=1e-12)
        assert bl.arc_mm > 0.0 and 2.0 - 0.009 * (1 + 1e-9) <= bl.radius_mm < 2.0   # p <= 0.9 P
        u = np.linspace(0.0, mv.length_mm, 3001)
        q, t, k = mv.evaluate(u)
        assert k.max() == pytest.approx(1.0 / bl.radius_mm, rel=1e-9)
        dev = distance_to_program(q, sharp).max()
        assert dev <= 0.01 and dev == pytest.approx(bl.deviation_mm, rel=1e-3)
        chord = np.sqrt((np.diff(q, axis=0) ** 2).sum(axis=1)).sum()
        assert chord == pytest.approx(mv.length_mm, rel=1e-6)


def test_fillets_hold_every_limit_and_run_sooner() -> None:
    """The rectangle's corners step the curvature at 8 joints, crossed at sqrt(J Ts R) = 4.5 mm/s
    to keep the jerk of that step within J; eased, every joint is continuous in curvature and
    the plan is quicker."""
    m = fast_machine()
    sharp = rectangle(m)
    prog = round_fillets(sharp, m, planned(m))
    assert blend_report(prog).blends == 4
    plan = plan_program(prog, m)
    rep = plan.limit_report()
    assert rep.violations == {} and rep.joint_jerk["worst_ratio"] <= 1.0 + 1e-6
    qv, qa, qj = blend_axis_derivatives(plan)
    lim = LimitSet.from_machine(m)
    assert np.all(np.abs(qa) <= lim.a_axis * (1 + 1e-9)) and np.all(np.abs(qj) <= lim.j_axis * (1 + 1e-6))
    sharp_plan = plan_program(sharp, m)
    assert plan.cycle_time_s < 0.9 * sharp_plan.cycle_time_s


def test_an_arc_that_is_not_tangent_stays() -> None:
    m = fast_machine()
    text = "G21 G90 G64 P0.01 Q0\nG1 F3000 X40 Y0.5\nG3 X42 Y2 R2\nG1 Y20\nM2\n"
    prog = parse_program(text, "k.ngc", m)
    assert round_fillets(prog, m) is prog


@settings(max_examples=40, deadline=None)
@given(turn=st.floats(5.0, 175.0), radius=st.floats(0.05, 20.0), legs=st.tuples(st.floats(0.2, 50.0),
       st.floats(0.2, 50.0)), tol=st.floats(0.001, 0.1), scale=st.sampled_from([0.001, 1.0, 1000.0]),
       rounding=st.sampled_from([0.0, 0.1, -0.2]))
def test_random_fillets_stay_within_the_tolerance_and_the_limits(turn, radius, legs, tol, scale,
                                                                rounding) -> None:
    """Fillets of any turn, radius and scale, also with the end radius a little off as CAM's
    rounding leaves it (a spiral, the radius up to 0.0008 mm off): within P of the programmed
    path, every limit."""
    m = fast_machine()
    m = replace(m, axes=tuple(replace(a, min_pos=-1e6, max_pos=1e6) for a in m.axes))
    th = math.radians(turn)
    r, l1, l2 = radius * scale, legs[0] * scale, legs[1] * scale
    assume(r >= 0.01)             # the interpreter's smallest arc
    t1 = np.array([l1, 0.0])                                  # the arc from here, centre (l1, r)
    c = np.array([l1, r])
    r_end = r + rounding * min(tol * scale, 0.004)   # at most what CAM's 3-4 decimals leave
    t2 = c + r_end * np.array([math.sin(th), -math.cos(th)])
    end = t2 + l2 * np.array([math.cos(th), math.sin(th)])
    text = (f"G21 G90 G64 P{tol * scale:.12f} Q0\nG1 F6000 X{t1[0]:.12f} Y0\n"
            f"G3 X{t2[0]:.12f} Y{t2[1]:.12f} I0 J{r:.12f}\nG1 X{end[0]:.12f} Y{end[1]:.12f}\nM2\n")
    sharp = parse_program(text, "r.ngc", m)
    prog = round_fillets(sharp, m)
    plan = plan_program(prog, m)
    assume(plan.cycle_time_s < 30.0)   # the sample checks cost time in proportion
    assert plan.limit_report().violations == {}
    q = plan.collect().q
    assert distance_to_program(q, sharp).max() <= tol * scale * (1 + 1e-6) + 1e-12
    for mv in prog.moves:
        if mv.blend is not None:
            assert mv.blend.deviation_mm <= tol * scale * (1 + 1e-9) + 1e-12


@pytest.mark.parametrize("interp, tol", [("exact", 0.0), ("classic", 0.0), ("taylor", 1e-5)])
def test_a_blended_program_streams_as_it_plans(interp: str, tol: float) -> None:
    """Windows of the blended path (pairs, fillets, joined lines) give the whole plan's samples
    in every interpolation; the exact one keeps every limit on them (Taylor's Eq. 16 drifts and
    classic ignores the profile, by design, blended or not)."""
    from planner.motion.interpolate import SampleChunk
    from planner.motion.plan import stream_program

    m = fast_machine()
    rise = 10.0 * math.tan(math.radians(2.5))
    zig = "".join(f"X{41 + 10 * i} Y{rise * (i % 2):.6f}\n" for i in range(1, 8))
    text = RECTANGLE.format(tol=0.01, feed=6000.0).replace("G1 X20\nM2\n", "G1 X40\n" + zig + "M2\n")
    prog = blend_program(parse_program(text, "s.ngc", m, start_position=np.array([0.0, -2.0, 0.0])), m)
    assert blend_report(prog).blends >= 8
    plan = plan_program(prog, m, interpolation=interp)
    whole = plan.collect()
    chunks = list(stream_program(prog, m, interpolation=interp, chunk_samples=2000, window=3))
    got = SampleChunk.concat(chunks, 3)
    assert len(got) == len(whole)
    np.testing.assert_array_equal(got.t, whole.t)
    np.testing.assert_allclose(got.q, whole.q, rtol=0, atol=max(tol, 1e-12))
    if interp == "exact":
        assert plan.limit_report().violations == {}


# -- transitions at the joints of arcs -------------------------------------------------------
ARCS = "G21 G90 G64 P{tol} Q0\nG1 F3000 X10\nG3 X14 Y4 R4\nG1 Y10\nG2 X20 Y16 R6\nG3 X26 Y22 R6\nM2\n"


def test_the_transition_curve_meets_both_ends() -> None:
    """The cubic-curvature curve ends where asked with the heading and curvature asked."""
    from planner.geometry.transition import solve_transition

    for k0, k1, dpsi, bx, by in ((0.0, 0.5, 0.3, 0.59, 0.09), (0.25, -0.2, 0.02, 1.0, 0.01),
                                 (1.0, 1.0, 0.4, 0.39, 0.08), (0.0, 0.2, 0.0, 1.0, 0.033)):
        sol = solve_transition(k0, k1, dpsi, bx, by)
        assert sol is not None
        length, c = sol
        s = np.linspace(0.0, length, 200_001)
        kappa = c[0] + s * (c[1] + s * (c[2] + s * c[3]))
        psi = np.concatenate([[0.0], np.cumsum(0.5 * (kappa[1:] + kappa[:-1]) * np.diff(s))])
        x = np.trapezoid(np.cos(psi), s)
        y = np.trapezoid(np.sin(psi), s)
        assert abs(x - bx) < 1e-8 and abs(y - by) < 1e-8
        assert psi[-1] == pytest.approx(dpsi, abs=1e-9) and kappa[-1] == pytest.approx(k1, abs=1e-12)


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.floats(-1.0, 1.0), st.floats(-1.0, 1.0), st.floats(-0.6, 0.6),
                          st.floats(0.1, 10.0), st.floats(-0.3, 0.3)), min_size=1, max_size=12),
       st.sampled_from([0.001, 0.1, 1.0, 30.0, 1000.0]))
def test_transitions_solved_together_are_each_solved_alone(rows, scale) -> None:
    """The joints of a program are solved a batch at a time: each row's curve is the one it
    has alone (found or not alike), at every scale (lengths x scale, curvatures / scale)."""
    from planner.geometry.transition import solve_transition, solve_transitions

    k0 = np.array([r[0] for r in rows]) / scale
    k1 = np.array([r[1] for r in rows]) / scale
    dpsi = np.array([r[2] for r in rows])
    chord = np.array([r[3] for r in rows]) * scale
    aim = dpsi / 2.0 + np.array([r[4] for r in rows])
    bx, by = chord * np.cos(aim), chord * np.sin(aim)
    length, coeffs, found = solve_transitions(k0, k1, dpsi, bx, by)
    assert length.shape == found.shape == (len(rows),) and coeffs.shape == (len(rows), 4)
    for i in range(len(rows)):
        alone = solve_transition(k0[i], k1[i], dpsi[i], bx[i], by[i])
        assert (alone is not None) == bool(found[i])
        if alone is not None:
            assert length[i] == pytest.approx(alone[0], rel=1e-9)
            # the curvature each gives along the curve (not its coefficients one by one), alike
            # within what Newton's end tolerance (1e-13 mm, 1e-9 of a 0.1 um curve) leaves open
            s = np.linspace(0.0, length[i], 9)
            kb = np.polynomial.polynomial.polyval(s, coeffs[i])
            ka = np.polynomial.polynomial.polyval(s, alone[1])
            assert np.abs(kb - ka).max() * length[i] <= 1e-7 * (1.0 + np.abs(ka).max() * length[i])


def test_head_and_tail_given_their_point_are_the_moves_found_without_it() -> None:
    """The transitions hand the point and the angle fraction they found to the head and tail
    of the moves they ease: the same moves as when those are found again."""
    from planner.core.program import arc_param_at_length
    from planner.geometry.resume import head_move, split_move

    m = fast_machine()
    prog = parse_program("G21 G90\nG1 X10 F3000\nG3 X14 Y4 I0.0005 J4\nM2\n", "spiral.ngc", m)
    arc = prog.moves[1]
    assert arc.arc is not None and arc.arc.radius_end_mm != arc.arc.radius_start_mm   # a spiral
    for u in (0.01, 1.7, arc.length_mm - 0.02):
        point = arc.evaluate(np.array([u]))[0][0]
        t = float(arc_param_at_length(arc.arc, np.array([u]), arc.length_mm)[0])
        for cut in (head_move, split_move):
            mine, again = cut(arc, u, (point, t)), cut(arc, u)
            assert np.array_equal(mine.start, again.start) and np.array_equal(mine.end, again.end)
            assert mine.arc == again.arc and mine.length_mm == again.length_mm


def test_joints_of_arcs_get_curvature_continuous_transitions() -> None:
    from planner.geometry.transition import ease_joints

    m = fast_machine()
    sharp = parse_program(ARCS.format(tol=0.01), "arcs.ngc", m)
    prog = ease_joints(sharp, m)
    assert [mv.kind.name for mv in prog.moves] == ["LINE", "BLEND", "ARC", "BLEND", "LINE", "BLEND", "ARC",
                                                   "BLEND", "ARC"]
    for a, b in zip(prog.moves[:-1], prog.moves[1:]):
        np.testing.assert_array_equal(a.end, b.start)
        ea, eb = a.evaluate(np.array([a.length_mm])), b.evaluate(np.array([0.0]))
        np.testing.assert_allclose(ea[1], eb[1], atol=1e-7)                   # tangent
        assert ea[2][0] == pytest.approx(eb[2][0], rel=1e-6, abs=1e-9)        # curvature
    for mv in prog.moves:
        if mv.blend is not None:
            q = mv.evaluate(np.linspace(0.0, mv.length_mm, 2001))[0]
            dev = distance_to_program(q, sharp).max()
            assert dev <= 0.009 and dev == pytest.approx(mv.blend.deviation_mm, rel=1e-2, abs=1e-7)
    plan = plan_program(prog, m)
    rep = plan.limit_report()
    assert rep.violations == {}
    qv, qa, qj = blend_axis_derivatives(plan)
    lim = LimitSet.from_machine(m)
    assert np.all(np.abs(qa) <= lim.a_axis * (1 + 1e-9)) and np.all(np.abs(qj) <= lim.j_axis * (1 + 1e-6))
    assert plan.cycle_time_s < 0.85 * plan_program(sharp, m).cycle_time_s   # measured 1.40 s vs 1.75 s


def test_head_move_keeps_the_geometry() -> None:
    from planner.geometry.resume import head_move

    m = fast_machine()
    prog = parse_program("G21 G90\nG1 F600 X10\nG3 X14 Y4 R4.0005\nM2\n", "h.ngc", m)
    arc = prog.moves[1]
    u = 0.4 * arc.length_mm
    head = head_move(arc, u)
    np.testing.assert_array_equal(head.start, arc.start)
    w = np.linspace(0.0, u, 50)
    np.testing.assert_allclose(head.evaluate(w)[0], arc.evaluate(w)[0], atol=1e-12)
    assert head.length_mm == pytest.approx(u, rel=1e-12)


def test_soft_limits_bound_a_transition() -> None:
    from planner.geometry.softlimits import move_bounds
    from planner.geometry.transition import ease_joints

    m = fast_machine()
    prog = ease_joints(parse_program(ARCS.format(tol=0.05), "arcs.ngc", m), m)
    for mv in prog.moves:
        if mv.blend is not None:
            lo, hi, _ = move_bounds(mv)
            q = mv.evaluate(np.linspace(0.0, mv.length_mm, 5001))[0]
            assert np.all(q >= lo - 1e-12) and np.all(q <= hi + 1e-12)


@settings(max_examples=40, deadline=None)
@given(spec=st.lists(st.tuples(st.sampled_from(["line", "left", "right"]), st.floats(0.3, 8.0),
                               st.floats(0.05, 1.2), st.floats(-4.0, 4.0)), min_size=2, max_size=5),
       tol=st.floats(0.001, 0.05), scale=st.sampled_from([0.001, 1.0, 1000.0]), every=st.booleans())
def test_random_arc_chains_ease_within_the_tolerance_and_the_limits(spec, tol, scale, every) -> None:
    """Chains of lines and arcs, tangent or kinked up to 4 degrees, at 0.001x, 1x and 1000x:
    the eased path stays within P of the programmed one and every limit holds."""
    from planner.geometry.transition import ease_joints

    m = fast_machine()
    m = replace(m, axes=tuple(replace(a, min_pos=-1e7, max_pos=1e7) for a in m.axes))
    x, y, heading = 0.0, 0.0, 0.0
    lines = [f"G21 G90 G64 P{tol * scale:.12f} Q0", "G1 F6000"]
    for kind, size, sweep, kink in spec:
        heading += math.radians(kink)
        if kind == "line":
            x, y = x + size * scale * math.cos(heading), y + size * scale * math.sin(heading)
            lines.append(f"G1 X{x:.12f} Y{y:.12f}")
            continue
        side = 1.0 if kind == "left" else -1.0
        r = size * scale
        assume(r >= 0.01)                                   # the interpreter's smallest arc
        cx, cy = x - side * r * math.sin(heading), y + side * r * math.cos(heading)
        end = math.atan2(y - cy, x - cx) + side * sweep
        px, py = x, y
        x, y = cx + r * math.cos(end), cy + r * math.sin(end)
        heading += side * sweep
        lines.append(f"{'G3' if side > 0 else 'G2'} X{x:.12f} Y{y:.12f} I{cx - px:.12f} J{cy - py:.12f}")
    sharp = parse_program("\n".join(lines + ["M2"]) + "\n", "c.ngc", m)
    prog = ease_joints(sharp, m, None if every else planned(m))
    plan = plan_program(prog, m)
    assume(plan.cycle_time_s < 30.0)
    rep = plan.limit_report()
    assert rep.violations == {}, rep.violations
    assert rep.end_error_mm == 0.0
    q = plan.collect().q
    assert distance_to_program(q, sharp).max() <= tol * scale * (1 + 1e-6) + 1e-12
    for mv in prog.moves:
        if mv.blend is not None:
            assert mv.blend.deviation_mm <= 0.9 * tol * scale * (1 + 1e-9) + 1e-12


def test_a_resume_inside_a_transition_follows_the_same_curve() -> None:
    from planner.geometry.transition import ease_joints

    m = fast_machine()
    prog = ease_joints(parse_program(ARCS.format(tol=0.05), "arcs.ngc", m), m)
    assert prog.moves[1].blend is not None and prog.moves[1].blend.poly is not None
    assert_resume_follows(prog, m, 0.61)


def linuxcnc_dynamics() -> MachineSpec:
    """``fast_machine`` at J = 1e6 mm/s^3: LinuxCNC 2.9's dynamics (no jerk limit to speak of)."""
    m = fast_machine()
    axes = tuple(replace(a, j_max=1e6) for a in m.axes)
    return replace(m, axes=axes).with_limits(v_max_mm_s=100.0, a_max_mm_s2=1000.0, j_max_mm_s3=1e6,
                                             rapid_mm_s=100.0)


def raster_step_text(step_mm: float, tol: str) -> str:
    """A finishing raster's turn: along X, a short step over in Y, back along X (two right
    angles a step apart), as blur_torus.ngc of LinuxCNC's tests runs it (G20, P0.01 inch)."""
    return (f"G21 G90 G64 P{tol} Q0\nG0 X20 Y10\nG1 F6000 X0\nY{10.0 - step_mm:.4f}\nX20\nM2\n")


def test_a_short_step_between_right_angles_is_turned_on_an_arc(monkeypatch) -> None:
    """A 1.016 mm step within 0.254 mm: each right angle may take half the step, so the turn is
    bound by the room, not the tolerance; an arc with short clothoids turns more for its tangent
    length than a clothoid pair, and is crossed at 20.7 mm/s (the circle's own bound,
    sqrt(0.866 A R) with R = 0.508 mm, is 21.0) where the pair allows 15.3 mm/s."""
    m = linuxcnc_dynamics()
    sharp = parse_program(raster_step_text(1.016, "0.254"), "step.ngc", m)
    blended = blend_program(sharp, m)
    blends = [mv for mv in blended.moves if mv.kind is MoveKind.BLEND]
    assert len(blends) == 2
    lim = LimitSet.from_machine(m)
    speeds = [blend_speed(b, lim) for b in blends]
    assert min(speeds) > 20.0
    for b in blends:
        assert b.blend.arc_mm > 2.0 * b.blend.half_mm           # mostly arc
        q = b.evaluate(np.linspace(0.0, b.length_mm, 2001))[0]
        assert distance_to_program(q, sharp).max() <= 0.254 * (1 + 1e-9)
    assert blend_report(blended).max_corner_deviation_mm <= 0.254 * (1 + 1e-9)
    plan = plan_program(blended, m)
    assert plan.limit_report().ok
    assert plan.cycle_time_s < plan_program(sharp, m).cycle_time_s - 0.02
    # clothoid pairs only: at 15.3 mm/s they are no quicker than the sharp corners, none is made
    args = (np.array([math.pi / 2.0]), np.array([0.254]), np.array([0.508]), np.array([1000.0]),
            np.array([1e6]))
    assert 20.6 < corner_sizes(*args)[4][0] < 20.8
    monkeypatch.setattr("planner.geometry.blend.CLOTHOID_SHARES", np.array([1.0]))
    assert 15.2 < corner_sizes(*args)[4][0] < 15.4
    assert blend_program(sharp, m) is sharp


@settings(max_examples=200, deadline=None)
@given(st.floats(0.001, 3.0), st.floats(1e-4, 1.0), st.floats(1e-3, 10.0), st.sampled_from([1e-3, 1.0, 1e3]),
       st.sampled_from([1e3, 1e4, 1e6]))
def test_corner_sizes_are_within_bounds_and_never_slower_than_the_pair(theta, tol, room, scale, jerk) -> None:
    """Any turn, tolerance, room, at scales 0.001 to 1000: D <= P, T <= room, the turn made by
    the clothoids and the arc together, and a speed at least the clothoid pair's."""
    th, p, r = np.array([theta]), np.array([tol * scale]), np.array([room * scale])
    a, j = np.array([1000.0 * scale]), np.array([jerk * scale])
    lc, la, t, d, v = corner_sizes(th, p, r, a, j)
    assert d[0] <= p[0] and t[0] <= r[0]                                    # to the last bit
    assert max(d[0] / p[0], t[0] / r[0]) == pytest.approx(1.0, rel=1e-9)   # as large as allowed
    assert lc[0] > 0.0 and la[0] >= 0.0
    radius = (lc[0] + la[0]) / theta
    # the blend's own speed rule from its geometry, as blend_speed reads it from the Blend
    bl = Blend(origin=np.zeros(3), u1=np.array([1.0, 0.0, 0.0]), n1=np.array([0.0, 1.0, 0.0]),
               half_mm=float(lc[0]), turn_rad=theta, corner=np.zeros(3), arc_mm=float(la[0]))
    assert bl.radius_mm == pytest.approx(radius, rel=1e-12)
    _, _, t1, d1 = unit_pair(th)
    half = min(p[0] / d1[0], r[0] / t1[0])
    pair = Blend(origin=np.zeros(3), u1=np.array([1.0, 0.0, 0.0]), n1=np.array([0.0, 1.0, 0.0]),
                 half_mm=float(half), turn_rad=theta, corner=np.zeros(3))
    lim = SimpleNamespace(a_axis=np.full(3, a[0]), j_axis=np.full(3, j[0]), a_path=a[0], j_path=j[0],
                          v_path=math.inf)
    mv = SimpleNamespace(blend=pair, feed_mm_s=math.inf)
    assert v[0] >= blend_speed(mv, lim) * (1 - 1e-9)


def test_a_corner_is_blended_where_it_saves_time_over_its_lines() -> None:
    """12mmflat.ngc's climb out of a pass (LinuxCNC's tests): a 17 mm line, then 0.97 mm lines
    turning 22.5 and 45 degrees, within 0.01 mm. The 45 degree blend is crossed at 8.9 mm/s,
    less than the sharp plan reaches a tangent length from that corner (12 mm/s), but the
    corner is no longer a stop: over the two lines it is quicker, and it is made."""
    m = linuxcnc_dynamics()
    text = ("G21 G90 G64 P0.01 Q0\nG0 X176.571 Y37.868 Z0.497\nG1 F3500 X193.40333\n"
            "X194.30136 Z0.86884\nX194.67333 Z1.76686\nX194.67333 Z6\nM2\n")
    sharp = parse_program(text, "climb.ngc", m)
    blended = blend_program(sharp, m)
    turns = sorted(round(math.degrees(b.blend.turn_rad), 1)
                   for b in blended.moves if b.kind is MoveKind.BLEND)
    assert turns[:2] == [22.5, 22.5] and 45.0 in turns
    plan = plan_program(blended, m)
    assert plan.limit_report().ok
    assert plan.cycle_time_s < plan_program(sharp, m).cycle_time_s - 0.01


@pytest.mark.parametrize("radius_mm", [5.0, 20.0])
@pytest.mark.parametrize("kink_deg", [40.0, 60.0, 90.0])
def test_a_joint_kinked_beyond_30_degrees_is_eased_only_where_quicker(kink_deg: float,
                                                                      radius_mm: float) -> None:
    """A line into an arc at a 40-90 degree kink, within 0.01 mm: the transition is made where
    it takes less time than the sharp joint (a stop) - at 40 and 60 degrees with LinuxCNC's
    dynamics - and not where the sharp joint is quicker (every kink at J = 1e4, 90 degrees at
    1e6): either way the program is never slower than sharp."""
    from planner.geometry.transition import ease_joints

    k = math.radians(kink_deg)
    phi = k - math.pi / 2.0                          # the start's angle about the centre
    cx, cy = 10.0 - radius_mm * math.cos(phi), -radius_mm * math.sin(phi)
    ex, ey = cx + radius_mm * math.cos(phi + 1.0), cy + radius_mm * math.sin(phi + 1.0)
    text = (f"G21 G90 G64 P0.01 Q0\nG0 X0 Y0\nG1 F3000 X10\n"
            f"G3 X{ex:.9f} Y{ey:.9f} I{cx - 10.0:.9f} J{cy:.9f}\nM2\n")
    for m, expect in ((linuxcnc_dynamics(), kink_deg < 90.0), (fast_machine(), False)):
        sharp = parse_program(text, "kink.ngc", m)
        eased = ease_joints(sharp, m, planned(m))
        always = ease_joints(sharp, m)
        assert [mv.kind for mv in always.moves] == [MoveKind.LINE, MoveKind.BLEND, MoveKind.ARC]
        t_sharp, t_always = plan_program(sharp, m).cycle_time_s, plan_program(always, m).cycle_time_s
        made = any(mv.kind is MoveKind.BLEND for mv in eased.moves)
        assert made == expect and made == (t_always < t_sharp)
        assert plan_program(eased, m).cycle_time_s <= t_sharp + 1e-9


@pytest.mark.parametrize(("tol", "room", "jerk"), [(0.01, 100.0, 1e6), (0.01, 100.0, 1e4),
                                                   (0.254, 0.508, 1e6), (0.01, 0.1, 1e6), (0.01, 0.05, 1e4)])
def test_corner_sizes_find_the_quickest_shape(monkeypatch, tol: float, room: float, jerk: float) -> None:
    """The share of the turn on the clothoids is refined between the grid's best and its
    neighbours: the speed is within 0.1 % of the best over 300 shares from 1 to 0.005 (the grid
    alone falls short by up to 1.8 %)."""
    import planner.geometry.blend as blend_module

    theta = np.radians([5.0, 15.0, 22.5, 45.0, 70.0, 90.0, 120.0, 150.0])
    n = len(theta)
    args = (theta, np.full(n, tol), np.full(n, room), np.full(n, 1000.0), np.full(n, jerk))
    v = corner_sizes(*args)[4]
    monkeypatch.setattr(blend_module, "CLOTHOID_SHARES", np.geomspace(1.0, 0.005, 300))
    monkeypatch.setattr(blend_module, "REFINE_STEPS", 0)
    v_fine = corner_sizes(*args)[4]
    assert np.all(v >= v_fine * (1 - 1e-3))
