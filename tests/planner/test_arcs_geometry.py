"""Property tests of the exact arc / helix / spiral geometry (hypothesis).

Random start, end, radius, direction, plane, R sign, turns and helix rise; checked:
exact end points (1e-9 mm), every evaluated point on the radius, the direction of travel,
u = arc length (unit tangent, length by integration), R form and I/J/K form give the same
arc, helix axis linear in the angle, spiral radius linear in the angle.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from planner.core.program import (
    Arc,
    Move,
    MoveKind,
    _spiral_s,
    arc_length_mm,
    arc_param_at_length,
    spiral_length_mm,
)
from planner.gcode.interpreter import parse_program

PLANES = {  # G code: (first, second, normal) axis letters and their centre-offset letters
    "G17": (("X", "Y", "Z"), ("I", "J")),
    "G18": (("Z", "X", "Y"), ("K", "I")),
    "G19": (("Y", "Z", "X"), ("J", "K")),
}
COLUMN = {"X": 0, "Y": 1, "Z": 2}

coord = st.floats(-300.0, 300.0, allow_nan=False, allow_infinity=False)
radius = st.floats(0.05, 400.0)
angle = st.floats(-math.pi, math.pi)
plane = st.sampled_from(sorted(PLANES))
gdir = st.sampled_from([2, 3])
rise = st.one_of(st.just(0.0), st.floats(-50.0, 50.0))
TOL = 1e-9


def num(x: float) -> str:
    """Shortest round-tripping decimal without an exponent (G-code has none)."""
    return np.format_float_positional(x, unique=True, trim="-")


def program_for(plane_g, start3, words):
    (f, s, n), _ = PLANES[plane_g]
    x, y, z = (start3[COLUMN[a]] for a in "XYZ")
    return f"G0 X{num(x)} Y{num(y)} Z{num(z)}\n{plane_g} G1 F600\n{words}\n"


def endpoint_words(plane_g, p1f, p1s, n1):
    (f, s, n), _ = PLANES[plane_g]
    return f"{f}{num(p1f)} {s}{num(p1s)} {n}{num(n1)}"


def check_exact_geometry(move: Move) -> None:
    arc = move.arc
    assert arc is not None and move.kind is MoveKind.ARC
    f, s, n = arc.first_axis, arc.second_axis, arc.normal_axis
    u = np.linspace(0.0, move.length_mm, 41)
    pos, tan, curv = move.evaluate(u)
    assert np.all(np.isfinite(pos)) and np.all(np.isfinite(tan)) and np.all(np.isfinite(curv))
    # Exact ends: u = 0 is the start, u = length is the programmed end (bit-exact), and the
    # analytic end of the arc (centre + radius at start angle + sweep) is within 1e-9 mm.
    np.testing.assert_allclose(pos[0], move.start, atol=TOL, rtol=0)
    np.testing.assert_array_equal(pos[-1], move.end)
    a_end = arc.start_angle_rad + arc.sweep_rad
    analytic_end = (
        arc.center[0] + arc.radius_end_mm * math.cos(a_end),
        arc.center[1] + arc.radius_end_mm * math.sin(a_end),
    )
    tol_end = TOL * max(1.0, arc.radius_end_mm * abs(arc.sweep_rad) / 100.0)
    assert abs(analytic_end[0] - move.end[f]) <= tol_end
    assert abs(analytic_end[1] - move.end[s]) <= tol_end
    # Points on the radius (linear in the angle for spirals); helix axis linear in the angle.
    t = arc_param_at_length(arc, u, move.length_mm)
    r_expected = arc.radius_start_mm + (arc.radius_end_mm - arc.radius_start_mm) * t
    r = np.hypot(pos[:, f] - arc.center[0], pos[:, s] - arc.center[1])
    np.testing.assert_allclose(
        r[:-1], r_expected[:-1], atol=TOL * max(1.0, arc.radius_start_mm / 100), rtol=0
    )
    if n >= 0:
        np.testing.assert_allclose(pos[:-1, n], move.start[n] + arc.rise_mm * t[:-1], atol=TOL, rtol=0)
    # Unit tangent over the linear axes.
    np.testing.assert_allclose(np.linalg.norm(tan, axis=1), 1.0, atol=1e-12)
    # Direction: (radius vector x tangent) has the sign of the sweep (+ = counter-clockwise).
    cross = (pos[:, f] - arc.center[0]) * tan[:, s] - (pos[:, s] - arc.center[1]) * tan[:, f]
    assert np.all(np.sign(cross) == np.sign(arc.sweep_rad))
    # u is arc length: a fine polyline has the same length.
    # Chords fall short of the arc by at most L (dtheta)^2 / 24 (dtheta: angle per chord).
    n_chords = 2000
    uu = np.linspace(0.0, move.length_mm, n_chords + 1)
    pp = move.evaluate(uu)[0]
    poly = np.sum(np.linalg.norm(np.diff(pp, axis=0), axis=1))
    dtheta = (
        abs(arc.sweep_rad)
        / n_chords
        * max(1.0, arc.radius_end_mm / arc.radius_start_mm, arc.radius_start_mm / arc.radius_end_mm)
    )
    shortfall = move.length_mm - poly
    assert -1e-9 * move.length_mm <= shortfall <= move.length_mm * (dtheta**2 / 24 * 1.05 + 1e-9)


@settings(max_examples=50)
@given(
    plane=plane,
    c1=coord,
    c2=coord,
    n0=coord,
    r=radius,
    a0=angle,
    a1=angle,
    g=gdir,
    sign=st.sampled_from([1, -1]),
    h=rise,
)
def test_r_form(plane, c1, c2, n0, r, a0, a1, g, sign, h):
    chord = 2 * r * abs(math.sin((a1 - a0) / 2))
    assume(chord > 1e-3 * r and chord > 1e-6)
    assume(chord < 2 * r * (1 - 1e-9))  # not the snapped half circle (own test)
    p0 = (c1 + r * math.cos(a0), c2 + r * math.sin(a0))
    p1 = (c1 + r * math.cos(a1), c2 + r * math.sin(a1))
    (f, s, n), _ = PLANES[plane]
    start = {f: p0[0], s: p0[1], n: n0}
    text = program_for(
        plane,
        (start["X"], start["Y"], start["Z"]),
        f"G{g} {endpoint_words(plane, p1[0], p1[1], n0 + h)} R{num(sign * r)}",
    )
    move = parse_program(text).moves[-1]
    arc = move.arc
    check_exact_geometry(move)
    # G02 clockwise, G03 counter-clockwise; R > 0 at most 180 deg, R < 0 at least 180 deg
    assert (arc.sweep_rad < 0) == (g == 2)
    if sign > 0:
        assert abs(arc.sweep_rad) <= math.pi + 1e-9
    else:
        assert abs(arc.sweep_rad) >= math.pi - 1e-9
    assert arc.radius_start_mm == pytest.approx(r, rel=1e-9, abs=1e-9)
    assert arc.rise_mm == pytest.approx(h, abs=1e-9)
    # Centre side: G02 short arc (or G03 long arc) has its centre right of the chord.
    cross = (p1[0] - p0[0]) * (arc.center[1] - p0[1]) - (p1[1] - p0[1]) * (arc.center[0] - p0[0])
    right = (g == 2) == (sign > 0)
    assert (cross < 0) == right or abs(cross) < 1e-9 * r * r

    # The same arc in the I/J/K form (centre from the R form): same centre, sweep, length.
    _, (ci, cj) = PLANES[plane]
    ijk = program_for(
        plane,
        (start["X"], start["Y"], start["Z"]),
        f"G{g} {endpoint_words(plane, p1[0], p1[1], n0 + h)} "
        f"{ci}{num(arc.center[0] - p0[0])} {cj}{num(arc.center[1] - p0[1])}",
    )
    m2 = parse_program(ijk).moves[-1]
    assert m2.arc.center == pytest.approx(arc.center, abs=1e-9)
    assert m2.arc.sweep_rad == pytest.approx(arc.sweep_rad, abs=1e-9)
    assert m2.length_mm == pytest.approx(move.length_mm, abs=1e-9 * max(1.0, move.length_mm))


def ijk_arc_text(plane, c1, c2, n0, r, a0, a1, g, turns, h, full=False) -> str:
    """A program to the start of an I/J/K arc about (c1, c2) of radius r from angle a0 to a1 (a
    whole circle with ``full``), its normal from n0 rising by h, in ``turns`` turns, and the arc."""
    p0 = (c1 + r * math.cos(a0), c2 + r * math.sin(a0))
    p1 = p0 if full else (c1 + r * math.cos(a1), c2 + r * math.sin(a1))
    assume(full or math.hypot(p1[0] - p0[0], p1[1] - p0[1]) > 1e-6)
    (f, s, n), (ci, cj) = PLANES[plane]
    start = {f: p0[0], s: p0[1], n: n0}
    return program_for(
        plane,
        (start["X"], start["Y"], start["Z"]),
        f"G{g} {endpoint_words(plane, p1[0], p1[1], n0 + h)} "
        f"{ci}{num(c1 - p0[0])} {cj}{num(c2 - p0[1])} P{turns}",
    )


# an I/J/K arc's centre, start and end angles, direction, normal and rise, as ijk_arc_text takes them
IJK_ARC = {"c1": coord, "c2": coord, "n0": coord, "r": radius, "a0": angle, "a1": angle, "g": gdir, "h": rise}


@settings(max_examples=40)
@given(plane=plane, turns=st.integers(1, 4), full=st.booleans(), **IJK_ARC)
def test_ijk_form_turns_and_full_circles(plane, c1, c2, n0, r, a0, a1, g, turns, h, full):
    p0 = (c1 + r * math.cos(a0), c2 + r * math.sin(a0))
    p1 = p0 if full else (c1 + r * math.cos(a1), c2 + r * math.sin(a1))
    move = parse_program(ijk_arc_text(plane, c1, c2, n0, r, a0, a1, g, turns, h, full)).moves[-1]
    arc = move.arc
    check_exact_geometry(move)
    assert arc.turns == turns
    assert (arc.sweep_rad < 0) == (g == 2)
    # principal angle in (0, 2 pi] plus whole turns
    principal = abs(arc.sweep_rad) - 2 * math.pi * (turns - 1)
    assert 0 < principal <= 2 * math.pi + 1e-12
    if full:
        assert principal == pytest.approx(2 * math.pi)
    expected = math.atan2(p1[1] - c2, p1[0] - c1) - math.atan2(p0[1] - c2, p0[0] - c1)
    if not full:
        # same end angle modulo 2 pi
        d = (arc.sweep_rad - expected) / (2 * math.pi)
        assert abs(d - round(d)) < 1e-9 * max(1.0, 1.0 / r)
    if arc.radius_start_mm == arc.radius_end_mm:
        c = arc.rise_mm / arc.sweep_rad
        k_expected = arc.radius_start_mm / (arc.radius_start_mm**2 + c * c)
        np.testing.assert_allclose(
            move.evaluate(np.array([0.0, move.length_mm / 3]))[2], k_expected, rtol=1e-9
        )


@settings(max_examples=40)
@given(
    c1=coord,
    c2=coord,
    r=st.floats(1.0, 400.0),
    a0=angle,
    a1=angle,
    g=gdir,
    frac=st.floats(-0.95, 0.95),
    h=rise,
)
def test_spirals_inside_tolerance(c1, c2, r, a0, a1, g, frac, h):
    # end radius differs by at most the tolerance: LinuxCNC runs it as a spiral
    tol = max(0.02828, min(0.001 * r, 2.828))
    r1 = r + frac * tol
    p0 = (c1 + r * math.cos(a0), c2 + r * math.sin(a0))
    p1 = (c1 + r1 * math.cos(a1), c2 + r1 * math.sin(a1))
    assume(math.hypot(p1[0] - p0[0], p1[1] - p0[1]) > 1e-6)
    # the same angle at both ends would be a radial move with no sweep: not an arc to test
    assume(abs(math.remainder(a1 - a0, 2 * math.pi)) > 1e-6)
    text = (
        f"G0 X{num(p0[0])} Y{num(p0[1])}\nG1 F600\n"
        f"G{g} X{num(p1[0])} Y{num(p1[1])} Z{num(h)} I{num(c1 - p0[0])} J{num(c2 - p0[1])}\n"
    )
    move = parse_program(text).moves[-1]
    assert move.arc.radius_end_mm == pytest.approx(r1, abs=1e-9)
    check_exact_geometry(move)


def test_r_form_half_circle_snap_is_exact():
    move = parse_program("G1 F60\nG2 X10.0025 R5").moves[0]
    assert move.arc.center == (5.00125, 0.0)
    check_exact_geometry(move)


def test_evaluate_line_and_vectorisation():
    m = parse_program("G1 X3 Y4 Z12 F60").moves[0]
    assert m.length_mm == 13.0
    u = np.array([0.0, 6.5, 13.0, 20.0, -1.0])
    pos, tan, curv = m.evaluate(u)
    assert pos.shape == (5, 3) and tan.shape == (5, 3) and curv.shape == (5,)
    np.testing.assert_allclose(pos[1], [1.5, 2, 6])
    np.testing.assert_array_equal(pos[2], m.end)
    np.testing.assert_array_equal(pos[3], m.end)  # clipped
    np.testing.assert_array_equal(pos[4], m.start)
    np.testing.assert_allclose(tan, np.tile([3 / 13, 4 / 13, 12 / 13], (5, 1)))
    assert not curv.any()
    p, _, _ = m.evaluate(6.5)  # scalar u
    assert p.shape == (1, 3)


def test_evaluate_tangent_matches_finite_difference_on_spiral_helix():
    a = Arc("XY", 0, 1, 2, (0.0, 0.0), 5.0, 5.5, 0.3, 2.5, 2.0)
    length = arc_length_mm(a)
    a_end = 0.3 + 2.5
    start = np.array([5 * math.cos(0.3), 5 * math.sin(0.3), 0.0])
    end = np.array([5.5 * math.cos(a_end), 5.5 * math.sin(a_end), 2.0])
    m = Move(0, 1, MoveKind.ARC, start, end, 1.0, length, a, False)
    u = np.linspace(0.1, length - 0.1, 7)
    eps = 1e-6
    p_hi, _, _ = m.evaluate(u + eps)
    p_lo, _, _ = m.evaluate(u - eps)
    _, tan, curv = m.evaluate(u)
    np.testing.assert_allclose((p_hi - p_lo) / (2 * eps), tan, atol=1e-7)
    # curvature from the second difference of the positions
    p0, _, _ = m.evaluate(u)
    h = 1e-3
    p_h, _, _ = m.evaluate(u + h)
    p_l, _, _ = m.evaluate(u - h)
    k_num = np.linalg.norm((p_h - 2 * p0 + p_l) / h**2, axis=1)
    np.testing.assert_allclose(curv, k_num, rtol=1e-4)


@pytest.mark.parametrize("dr_rel", [1e-12, 1e-6, 9.99e-4, 1.001e-3, 0.05, -0.5])
@pytest.mark.parametrize("rise_mm", [0.0, 3.0])
def test_spiral_length_closed_form_and_quadrature(dr_rel, rise_mm):
    """Both branches of the exact spiral length agree with a fine Simpson integration."""
    r0, sweep = 7.0, -4.0
    r1 = r0 * (1 + dr_rel)
    t = np.linspace(0.0, 1.0, 200_001)
    f = np.sqrt((r1 - r0) ** 2 + ((r0 + (r1 - r0) * t) * sweep) ** 2 + rise_mm**2)
    simpson = (f[0] + f[-1] + 4 * f[1:-1:2].sum() + 2 * f[2:-1:2].sum()) / (3 * (len(t) - 1))
    assert spiral_length_mm(r0, r1, sweep, rise_mm) == pytest.approx(simpson, rel=1e-13)
    arc = Arc("XY", 0, 1, 2, (0.0, 0.0), r0, r1, 0.0, sweep, rise_mm)
    # the vectorised length used by evaluate() agrees with the scalar one
    length = spiral_length_mm(r0, r1, sweep, rise_mm)
    assert float(_spiral_s(arc, np.array([1.0]))[0]) == pytest.approx(length, rel=1e-13)
    assert arc_param_at_length(arc, np.array([length]), length)[0] == 1.0


@settings(max_examples=60, deadline=None)
@given(rotation=st.floats(-179.0, 179.0).filter(lambda r: abs(r) > 0.01),
       plane=st.sampled_from(["G18", "G19"]), turns=st.integers(1, 3), **IJK_ARC)
# a small arc away from the origin: the curvature's second difference is bounded by rounding
@example(rotation=1.0, plane="G18", turns=1, c1=0.0, c2=0.0, n0=4.0, r=0.0625, a0=0.0, a1=-0.03125, g=2,
         h=0.0)
def test_arcs_in_a_rotated_system_lie_in_their_turned_plane(rotation, plane, c1, c2, n0, r, a0, a1, g,
                                                            turns, h):
    """A G18/G19 arc while the XY plane is rotated (G10 L2 R) lies in the plane of Z and the
    turned X (or Y): turned back by the rotation, every point is on the programmed circle, the
    normal linear in the angle, the ends exact; the vectorised table gives the
    same points, tangents and ends as the move itself."""
    from planner.geometry.movetable import MoveTable, contour_error

    (f, s, n), _ = PLANES[plane]
    program = parse_program(f"G10 L2 P1 R{num(rotation)}\n"
                            + ijk_arc_text(plane, c1, c2, n0, r, a0, a1, g, turns, h))
    move = program.moves[-1]
    arc = move.arc
    assert arc is not None and arc.xy_turn_rad == pytest.approx(math.radians(rotation))
    u = np.linspace(0.0, move.length_mm, 57)
    pos, tan, curv = move.evaluate(u)
    np.testing.assert_allclose(pos[0], move.start, atol=TOL * max(1.0, r), rtol=0)
    np.testing.assert_array_equal(pos[-1], move.end)
    # program coordinates (no offsets here): machine X, Y turned back by the rotation
    c, sn = math.cos(math.radians(rotation)), math.sin(math.radians(rotation))
    prog = pos.copy()
    prog[:, 0], prog[:, 1] = c * pos[:, 0] + sn * pos[:, 1], -sn * pos[:, 0] + c * pos[:, 1]
    fc, sc, nc = COLUMN[f], COLUMN[s], COLUMN[n]
    tol = 1e-9 * max(1.0, r, abs(c1), abs(c2), abs(n0))
    np.testing.assert_allclose(np.hypot(prog[:, fc] - c1, prog[:, sc] - c2), r, atol=tol * 10, rtol=1e-9)
    # the normal rises linearly in the angle, and so in u on a circle
    np.testing.assert_allclose(prog[:, nc], n0 + h * u / move.length_mm, atol=tol * 10, rtol=1e-9)
    # unit tangent = dq/du (central differences), curvature of a helix about a circle
    np.testing.assert_allclose(np.linalg.norm(tan, axis=1), 1.0, rtol=1e-9)
    du = 1e-6 * move.length_mm
    mid = u[1:-1]
    fd = (move.evaluate(mid + du)[0] - move.evaluate(mid - du)[0]) / (2 * du)
    scale = max(1.0, r, abs(c1), abs(c2), abs(n0))       # the largest coordinate's size
    np.testing.assert_allclose(fd, tan[1:-1], atol=1e-5 + 16 * np.finfo(float).eps * scale / du)
    pitch = arc.rise_mm / arc.sweep_rad
    np.testing.assert_allclose(curv, r / (r * r + pitch * pitch), rtol=1e-6)
    # the vectorised table: positions, end tangents and curvature vectors, distance to the path
    table = MoveTable.from_moves([move], len(program.axes))
    rows = np.zeros(u.size, dtype=np.int64)
    np.testing.assert_allclose(table.positions(rows, u), pos, atol=tol * 10, rtol=0)
    t_start, t_end = table.end_tangents()
    np.testing.assert_allclose(t_start[0], tan[0], atol=1e-9)
    np.testing.assert_allclose(t_end[0], tan[-1], atol=1e-9)
    c_start, _ = table.end_curvature_vectors()
    h2 = 1e-4 * min(move.length_mm, r)          # small against the radius, large against rounding
    fd2 = (move.evaluate(np.array([2 * h2]))[0] - 2 * move.evaluate(np.array([h2]))[0]
           + move.evaluate(np.array([0.0]))[0]) / (h2 * h2)
    # the differences divide the positions' rounding (a few ulp of the largest coordinate) by
    # du, or h2 squared: far from the origin that, not the method, bounds their accuracy
    rounding = 64 * np.finfo(float).eps * scale / (h2 * h2)
    np.testing.assert_allclose(c_start[0], fd2[0], atol=1e-3 * max(1.0, 1.0 / r) + rounding, rtol=1e-3)
    assert float(contour_error(table, rows, pos, u).max()) <= tol * 10


@pytest.mark.parametrize("rotation", [17.0, 45.0, -120.0, 90.0])
@pytest.mark.parametrize("arc", ["G18 G2 X40 Z0 I20 K0", "G19 G3 Y40 Z0 J20 K0 X5",
                                 "G18 G3 X0 Z0 I20 K0 Y-30 P2", "G19 G2 Y6 Z0 J3 K0.5 X-9"])
def test_the_travel_an_arc_in_a_rotated_system_covers_is_its_own(rotation, arc):
    """The soft limits read a move's bounds: for a G18/G19 arc in a rotated system, whose plane
    swings X, Y and Z at once, the bounds are those of its points (its extremes, not its ends);
    along a helix there the extremes of X and Y are off the quarter turns."""
    from planner.geometry.softlimits import move_bounds

    program = parse_program(f"G21 G90 F600\nG10 L2 P1 R{rotation}\nG0 X0 Y0 Z0\n{arc}\nM2\n")
    move = program.moves[-1]
    assert move.arc is not None and move.arc.xy_turn_rad != 0.0
    lo, hi, _ = move_bounds(move)
    pts = move.evaluate(np.linspace(0.0, move.length_mm, 200_001))[0]
    # every point inside the bounds, and the bounds reached (to the sampling's 1e-6 mm)
    assert np.all(pts.min(axis=0) >= lo - 1e-9) and np.all(pts.max(axis=0) <= hi + 1e-9)
    np.testing.assert_allclose(lo, pts.min(axis=0), atol=1e-6)
    np.testing.assert_allclose(hi, pts.max(axis=0), atol=1e-6)


@pytest.mark.parametrize("arc", ["G18 G2 X40 Z0 I20 K0 Y-7", "G19 G3 Y40 Z0 J20 K0 P2"])
def test_a_stop_inside_an_arc_in_a_rotated_system_resumes_on_it(arc):
    """A run stopped part way along a G18/G19 arc in a rotated system resumes from there on the
    same path (the tail and the head of the move keep the turned frame), to the same end."""
    from planner.geometry.resume import head_move, split_move

    move = parse_program(f"G21 G90 F600\nG10 L2 P1 X3 Y-2 R-35\nG0 X0 Y0 Z0\n{arc}\nM2\n").moves[-1]
    u = 0.37 * move.length_mm
    tail, head = split_move(move, u), head_move(move, u)
    assert tail.arc.xy_turn_rad == head.arc.xy_turn_rad == move.arc.xy_turn_rad != 0.0
    np.testing.assert_array_equal(tail.end, move.end)
    assert tail.length_mm == pytest.approx(move.length_mm - u, rel=1e-12)
    w = np.linspace(0.0, tail.length_mm, 101)
    np.testing.assert_allclose(tail.evaluate(w)[0], move.evaluate(u + w)[0], atol=1e-9)
    w = np.linspace(0.0, u, 101)
    np.testing.assert_allclose(head.evaluate(w)[0], move.evaluate(w)[0], atol=1e-9)
