"""No limit exceeded on random programs, lookahead mode: from the closed-form profiles and
geometry, and again from finite differences of the samples (the limit meter). Programs come
from fixed seeds and from hypothesis, block by block, at scales 0.001, 1 and 1000."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.motion.lookahead import LimitSet
from planner.motion.plan import plan_program
from tests.planner.motion_programs import paper_machine, parse, programs, random_program, xyza_machine


def closed_form_axis_derivatives(plan, n_per_move: int = 64):
    """Per-axis velocity, acceleration, jerk from the profile (s, v, a, j) and the exact
    derivatives of line / circle / helix geometry (no finite differences)."""
    seg = plan.segment
    tab = seg.table
    prof = seg.profiles
    n = len(tab)
    move = np.repeat(np.arange(n), n_per_move)
    tau = (np.tile(np.linspace(0.0, 1.0, n_per_move), n)) * prof.duration[move]
    s, v, a, j = prof.evaluate(move, tau)
    length = tab.length[move]
    lin = (tab.end[move] - tab.start[move]) / length[:, None]
    qv, qa, qj = lin * v[:, None], lin * a[:, None], lin * j[:, None]
    arc = tab.is_arc[move]
    k = np.nonzero(arc)[0]
    if k.size:
        r = move[k]
        # an arc in a turned frame (G18/G19 in a rotated system): its derivatives are those of
        # its frame, where the linear part is turned first, turned back to the machine's X and Y
        tw = np.nonzero(tab.turn[r])[0]
        for q in (qv, qa, qj):
            turn_rows(q, k[tw], tab.turn_x[r[tw]], tab.turn_y[r[tw]], -tab.turn[r[tw]])
        w = tab.sweep[r] / length[k]  # rad per mm
        th = tab.theta0[r] + w * s[k]
        rad = tab.r0[r]
        c, sn = np.cos(th), np.sin(th)
        vk, ak, jk = v[k], a[k], j[k]
        f, se = tab.first[r], tab.second[r]
        qv[k, f] = -rad * sn * w * vk
        qv[k, se] = rad * c * w * vk
        qa[k, f] = -rad * c * w**2 * vk**2 - rad * sn * w * ak
        qa[k, se] = -rad * sn * w**2 * vk**2 + rad * c * w * ak
        qj[k, f] = rad * sn * w**3 * vk**3 - 3 * rad * c * w**2 * vk * ak - rad * sn * w * jk
        qj[k, se] = -rad * c * w**3 * vk**3 - 3 * rad * sn * w**2 * vk * ak + rad * c * w * jk
        for q in (qv, qa, qj):
            turn_rows(q, k[tw], tab.turn_x[r[tw]], tab.turn_y[r[tw]], tab.turn[r[tw]])
    return move, v, a, j, qv, qa, qj


def turn_rows(q: np.ndarray, rows: np.ndarray, ix: np.ndarray, iy: np.ndarray, angle: np.ndarray) -> None:
    """Columns ix, iy of q's rows turned by angle about Z (one of each a row), written out by
    hand here rather than with the code under test."""
    x, y = q[rows, ix].copy(), q[rows, iy].copy()
    q[rows, ix] = np.cos(angle) * x - np.sin(angle) * y
    q[rows, iy] = np.sin(angle) * x + np.cos(angle) * y


def check_program(text: str, machine=None, mode: str = "lookahead") -> None:
    m = machine or paper_machine()
    prog = parse(text, m)
    plan = plan_program(prog, m, mode=mode)
    lim = LimitSet.from_machine(m)
    # Closed form: tangential v <= min(F, Vmax), |a| <= Amax, |j| <= Jmax; per axis v, a, j.
    move, v, a, j, qv, qa, qj = closed_form_axis_derivatives(plan)
    seg = plan.segment
    # moves of rotary axes alone are held to the angular path limits (the axes' own when the
    # machine names none), the others to the path's
    _v, a_path, j_path, _r = lim.path(lim.rotary_only(seg.table.start, seg.table.end))
    assert np.all(v <= seg.v_prog[move] * (1 + 1e-9))
    assert np.all(np.abs(a) <= a_path[move] * (1 + 1e-9))
    assert np.all(np.abs(j) <= j_path[move] * (1 + 1e-9))
    spiral = seg.table.spiral[move]  # tiny radius mismatch: circle formulas are approximate
    ok = ~spiral
    assert np.all(np.abs(qv[ok]) <= lim.v_axis * (1 + 1e-6))
    assert np.all(np.abs(qa[ok]) <= lim.a_axis * (1 + 1e-6))
    assert np.all(np.abs(qj[ok]) <= lim.j_axis * (1 + 1e-6))
    # Finite differences of the samples, contour, end points, NaN, time.
    rep = plan.limit_report()
    assert rep.violations == {}, rep.violations
    if mode == "lookahead":
        # no velocity step at any joint (no corner step configured): the jerk of stencils
        # across joints within every axis' limit too
        assert rep.joint_jerk["count"] == 0, rep.joint_jerk
        assert rep.corner_steps["count"] == 0, rep.corner_steps
    # exact geometry: 1 nm, or 1e-12 of the program's extent on metre-scale programs (the
    # rounding of float64 positions of several metres is ~1e-12 of them)
    extent = max(1.0, max(float(np.abs(m.end).max()) for m in prog.moves) if prog.moves else 1.0)
    assert rep.contour_error_mm <= max(1e-9, 1e-12 * extent)
    assert rep.end_error_mm == 0.0
    assert not rep.nan and rep.time_increasing
    assert rep.samples == plan.n_samples
    # Every move ends exactly at its programmed end (closed form s(t1) = L, exact geometry).
    tab = seg.table
    rows = np.arange(len(tab))
    end_q = tab.positions(rows, seg.profiles.evaluate_s(rows, seg.profiles.duration))
    np.testing.assert_array_equal(end_q, tab.end)


@pytest.mark.parametrize("seed", range(16))
def test_random_programs_hold_every_limit(seed):
    check_program(random_program(seed, n_blocks=35))


@pytest.mark.parametrize("seed", range(4))
def test_random_programs_with_low_axis_limits(seed):
    m = paper_machine()
    from dataclasses import replace

    axes = (replace(m.axes[0], a_max=300.0, j_max=3000.0), replace(m.axes[1], v_max=12.0),
            replace(m.axes[2], a_max=500.0, j_max=20000.0))
    check_program(random_program(50 + seed, n_blocks=30), replace(m, axes=axes))


@pytest.mark.parametrize("seed", range(6))
def test_random_programs_with_a_rotary_axis_moving_along(seed):
    check_program(random_program(300 + seed, n_blocks=30, rotary=True), xyza_machine())


@settings(max_examples=30, deadline=None)
@given(text=programs(max_blocks=12))
def test_drawn_programs_hold_every_limit(text):
    check_program(text)


def slow_y_machine():
    """Y much slower than X and Z: an arc whose plane is turned about Z moves Y as well."""
    from dataclasses import replace

    m = paper_machine()
    axes = (m.axes[0], replace(m.axes[1], v_max=8.0, a_max=200.0, j_max=2000.0), m.axes[2])
    return replace(m, axes=axes)


@settings(max_examples=30, deadline=None)
@given(text=programs(max_blocks=12, rotated=True), slow_y=st.booleans())
def test_drawn_programs_in_a_rotated_system_hold_every_limit(text, slow_y):
    """G18/G19 arcs in a rotated system (G10 L2 R) lie in planes turned about Z: X, Y and Z all
    swing along them, and every limit still holds, on a machine whose Y is slow too."""
    check_program(text, slow_y_machine() if slow_y else None)


@pytest.mark.parametrize("rotation", [30.0, 45.0, -60.0, 90.0, 135.0])
@pytest.mark.parametrize("arc", ["G18 G02 X20 Y0 Z0 I10 K0", "G19 G03 X0 Y20 Z0 J10 K0",
                                 "G18 G03 X20 Y-6 Z0 I10 K0 F3000"])
def test_a_half_circle_in_a_turned_plane_holds_the_slow_axis(rotation, arc):
    """The plane of a G18/G19 arc in a rotated system takes Y along as it turns: at 30 mm/s on a
    10 mm radius, the Y of a slow machine (8 mm/s, 200 mm/s^2) would be over its limits if the
    arc were planned with the limits of its named axes (Z and X, or Y and Z) alone."""
    check_program(f"G21 G90 G94 G17 F1800\nG10 L2 P1 R{rotation}\nG00 X0 Y0 Z0\n{arc}\nM30\n",
                  slow_y_machine())


@settings(max_examples=12, deadline=None)
@given(text=st.sampled_from([0.001, 1000.0]).flatmap(
    lambda scale: programs(max_blocks=5, scale=scale, rotated=True)))
def test_drawn_programs_in_a_rotated_system_hold_every_limit_at_any_scale(text):
    check_program(text)


@settings(max_examples=40, deadline=None, derandomize=True)
@given(text=programs(max_blocks=6, scale=0.001))
def test_drawn_micrometre_programs_hold_every_limit(text):
    """Derandomized: a known violation (below) is rare here, and a random search would make
    this test fail at random; the pinned program keeps the known case in view."""
    check_program(text)


@pytest.mark.parametrize("radius_mm", [3e6, 1e8])
def test_arcs_of_kilometres_hold_every_limit(radius_mm):
    """A nearly straight arc (a curve's biarc where it hardly bends, or R of kilometres): its
    points, taken about a centre that far away, would carry rounding noise the limit meter
    reads as jerk over the limit (1.0002 x at 3 km, before the arcs were taken from their
    start); from the start point they do not. (At 100 km the contour measure itself, a
    distance from the centre, rounds to 1e-8 mm: only the limits are checked there.)"""
    text = (f"G21 G90 G94 G17 F1800\nG0 X0 Y0\nG2 X1000 Y0 R{radius_mm:.0f}\nG1 X1200\n"
            f"G3 X0 Y0 R{radius_mm:.0f}\nM30\n")
    if radius_mm < 1e7:
        check_program(text)
    else:
        machine = paper_machine()
        assert plan_program(parse(text, machine), machine).limit_report().violations == {}


@pytest.mark.parametrize("feed", ["F1000000000", "F999999999999"])
def test_a_feed_of_a_billion_runs_at_the_machines_limits(feed):
    # programs write F1e9 for "as fast as the machine goes" (LinuxCNC's own tests do): read,
    # and held to every limit, in G94 and in inverse time
    check_program(f"G21 G90 G0 X0 Y0 Z0\n{feed}\nG1 X-1\nG2 X5 Y2 R4\nG93 G1 X6 {feed}\nG94 {feed} X1\nM2\n")


def test_micrometre_corner_between_tiny_lines():
    """The program hypothesis shrank a failure to: four lines of 1-19 um with a 90-degree
    corner; the X acceleration reached 1.075 Amax there, until joints closer than two samples'
    travel shared one tangent-break budget."""
    check_program("G21 G90 G94 G17 F1800\nG00 X0 Y0 Z0\nG01 X0.005 Y0 Z0 F1800\nG01 X-0.014 Y0 Z0\n"
                  "G01 X-0.014 Y0 Z0.000001\nG01 X-0.009 Y0 Z0.000001\nM30\n")


def test_half_micrometre_line_after_a_full_circle():
    """Found by a random (not derandomized) run of ``test_drawn_programs_hold_every_limit``: the
    X acceleration reached 1.034 Amax (two joints half a micrometre apart)."""
    check_program("G21 G90 G94 G17 F1800\nG00 X0 Y0 Z0\nG04 P0.05\n"
                  "G19 G03 X0 Y0 Z0 J0.416146837 K-0.909297427\nG01 X0.0005 Y0 Z0 F1800\n"
                  "G01 X0.0005 Y0 Z1 F1800\nM30\n")


def test_quarter_micrometre_rapid_before_a_corner():
    """Found by a stress run of cutter compensation at scale 0.001 (a rapid round a convex corner
    is a short straight to the corner arc's end), the same without compensation: the X
    acceleration reached 1.42 Amax (two corners a quarter micrometre apart)."""
    check_program("G21 G17 G90 F1200\nG1 X-0.0384592 Y-0.0231729\nG0 X-0.0383931 Y-0.0234205\n"
                  "X0.0177309 Y-0.0247405\nG1 X0.0177745 Y-0.0244798\nM2\n")


def test_five_line_program_of_the_motion_issue():
    """A fuzzed program that made the plan exceed the Z acceleration limit 1.8 times."""
    check_program("G21 G90 G17\nG1 X-0.042160 Y-0.024135 F1200\nG0 Z0.020000\n"
                  "G0 X-0.042181 Y-0.024197\nG1 Z-0.001949 F400\n")


@settings(max_examples=6, deadline=None)
@given(text=programs(max_blocks=4, scale=1000.0))
def test_drawn_metre_scale_programs_hold_every_limit(text):
    check_program(text)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(200, 260))
def test_many_random_programs_hold_every_limit(seed):
    check_program(random_program(seed, n_blocks=80))


@pytest.mark.parametrize("seed", range(4))
def test_paper_mode_produces_the_same_report_and_shows_breaks(seed):
    m = paper_machine()
    prog = parse(random_program(seed, n_blocks=40), m)
    rep = plan_program(prog, m, mode="paper").limit_report()
    assert rep.contour_error_mm <= 1e-9 and not rep.nan and rep.time_increasing
    assert set(rep.violations) <= {"axis_a", "axis_j", "axis_v"}
    assert "tangential_a" not in rep.violations
