"""G05, G05.1 and G05.2/G05.3 curves, as LinuxCNC 2.9 reads and runs them.

The curve is LinuxCNC's: its points equal those LinuxCNC's own preview module computes (the
stand-alone rs274 prints only how many control points a curve has). It is run as LinuxCNC's
motion layer runs it: tangent arcs through the curve at four points a control point. Offsets,
rotation and inch units move it as they move any XY path; every refusal names its line and
column and why."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.core.errors import ProgramError
from planner.core.program import Curve
from planner.gcode.interpreter import parse_program
from planner.geometry.splines import SAMPLES_PER_POINT, biarc, nurbs_points
from tools.against_linuxcnc import preview_points
from tools.linuxcnc_oracle import RS274, preview_available, refused_alike, run_linuxcnc_preview

Point = tuple[float, float, float]


def _n(v: float) -> str:
    return f"{v:.1f}"


@st.composite
def curves(draw) -> tuple[str, list[Point], int]:
    """A program of one curve from a rapid start: (text, its control points as LinuxCNC makes
    them from the words (x, y, weight), order)."""
    val = st.integers(-400, 400).map(lambda k: k / 10.0)
    x0, y0 = draw(val), draw(val)
    head = f"G21 G17 G90 G94 F600\nG0 X{_n(x0)} Y{_n(y0)}\n"
    form = draw(st.sampled_from(["G5", "G5.1", "G5.2"]))
    if form == "G5":
        x, y, i, j, p, q = (draw(val) for _ in range(6))
        body = f"G5 X{_n(x)} Y{_n(y)} I{_n(i)} J{_n(j)} P{_n(p)} Q{_n(q)}"
        points = [(x0, y0, 1.0), (x0 + i, y0 + j, 1.0), (x + p, y + q, 1.0), (x, y, 1.0)]
        order = 4
    elif form == "G5.1":
        x, y, i, j = (draw(val) for _ in range(4))
        body = f"G5.1 X{_n(x)} Y{_n(y)} I{_n(i)} J{_n(j)}"
        points = [(x0, y0, 1.0), (x0 + i, y0 + j, 1.0), (x, y, 1.0)]
        order = 3
    else:
        order = draw(st.integers(3, 5))
        more = [(draw(val), draw(val), float(draw(st.sampled_from([0.5, 1, 2, 3]))))
                for _ in range(draw(st.integers(order - 1, 7)))]
        body = f"G5.2 L{order}\n" + "\n".join(f"X{_n(px)} Y{_n(py)} P{w:g}" for px, py, w in more) + "\nG5.3"
        points = [(x0, y0, 1.0), *more]
    return head + body + "\nM2\n", points, order


def _arc_tangents(move, start: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit tangents of an arc move at its start and at its end."""
    arc = move.arc
    sign = 1.0 if arc.sweep_rad > 0 else -1.0
    a0 = math.atan2(start[1] - arc.center[1], start[0] - arc.center[0])
    a1 = a0 + arc.sweep_rad
    return (sign * np.array([-math.sin(a0), math.cos(a0)]), sign * np.array([-math.sin(a1), math.cos(a1)]))


@pytest.mark.skipif(not preview_available(), reason="LinuxCNC's preview module (gcode, Debian's "
                    "linuxcnc-uspace, which make test installs as root) is not available")
@settings(max_examples=30, deadline=None)
@given(curves())
def test_the_curve_is_the_one_linuxcnc_computes(curve: tuple[str, list[Point], int]) -> None:
    """LinuxCNC's preview draws the curve through 15 points a control point, from its own NURBS
    code: those points are this module's curve at the same parameters."""
    text, points, order = curve
    drawn = np.array([args[:2] for call, args in run_linuxcnc_preview(text) if call == "straight_feed"])
    ours = preview_points(Curve(0, 0, tuple(points), order))      # the preview's own parameters
    assert drawn.shape == ours.shape, text
    assert np.max(np.abs(drawn - ours)) < 1e-6, text


@settings(max_examples=80, deadline=None)
@given(curves())
def test_the_moves_are_tangent_arcs_through_the_curve(curve: tuple[str, list[Point], int]) -> None:
    """The moves end on the curve at every one of its 4 (n + 1) samples, in order, and at the
    last control point exactly; one arc leaves along the direction the one before arrives
    (within 0.001 rad: the tangents are LinuxCNC's central differences, rough at a cusp)."""
    text, points, order = curve
    program = parse_program(text, "c.ngc")
    assert len(program.splines) == 1
    curve = program.splines[0]
    first, end = curve.first, curve.end
    assert curve.points == tuple(points) and curve.order == order
    moves = list(program.moves)[first:end]
    starts = [np.asarray(program.moves[first - 1].end[:2] if first else program.start_position[:2])]
    starts += [np.asarray(m.end[:2]) for m in moves[:-1]]
    ends = np.array([m.end[:2] for m in moves])
    n = len(points) - 1
    div = (n + 1) * SAMPLES_PER_POINT
    samples = nurbs_points(np.array(points), order, (n - order + 2) * np.arange(1, div + 1) / div)
    # where the tool is before each move and after the last (a sample where the curve stands
    # still is where the move before it ended, or the start)
    where = np.vstack([starts[0][None, :], ends.reshape(-1, 2)])
    at = 0
    for p in samples:
        hits = np.flatnonzero(np.max(np.abs(where[at:] - p), axis=1) < 1e-9)
        assert len(hits), (p, text)
        at += int(hits[0])
    assert tuple(where[-1]) == points[-1][:2]
    # a curve of positive weights lies inside its control points, and so does every move
    lo = np.min(np.array(points)[:, :2], axis=0) - 1e-6
    hi = np.max(np.array(points)[:, :2], axis=0) + 1e-6
    for move, start in zip(moves, starts):
        if move.arc is not None:
            a0 = math.atan2(start[1] - move.arc.center[1], start[0] - move.arc.center[0])
            angles = a0 + move.arc.sweep_rad * np.linspace(0.0, 1.0, 33)
            drawn = np.column_stack([move.arc.center[0] + move.arc.radius_start_mm * np.cos(angles),
                                     move.arc.center[1] + move.arc.radius_start_mm * np.sin(angles)])
            assert np.all((drawn >= lo) & (drawn <= hi)), text
    for a, b, start_a, start_b in zip(moves, moves[1:], starts, starts[1:]):
        if a.arc is not None and b.arc is not None:
            _, out = _arc_tangents(a, start_a)
            into, _ = _arc_tangents(b, start_b)
            assert float(np.dot(out, into)) > math.cos(1e-3), text


def test_at_a_cusp_the_moves_stay_by_the_curve() -> None:
    """A curve that turns back on itself (its tangent reverses): LinuxCNC's biarc there swings
    out 80 mm around a curve 0.2 mm long; here lines go from sample to sample."""
    program = parse_program("G21 F600\nG0 X0 Y0.1\nG5.1 X-0.1 Y0 I0.1 J0.1\nM2\n", "c.ngc")
    ends = np.array([m.end[:2] for m in program.moves])
    assert np.all(np.abs(ends) <= 0.2 + 1e-9)
    assert all(m.arc is None or m.arc.radius_start_mm < 0.1 for m in program.moves)


def test_a_curve_moves_with_the_coordinate_system_and_the_units() -> None:
    """Rotated and shifted by G10 L2 R, or written in inches, the curve is the same curve moved
    or scaled: its control points are program coordinates, in program units."""
    body = ("G5 X20 Y10 I8 J12 P-6 Q9\nG5.1 X30 Y0 I4 J-9\nG5.2 L4\nX35 Y5 P1\nX40 Y-5 P2\nX45 Y5 P1\n"
            "X50 Y0 P1\nG5.3\n")
    plain = parse_program("G21 G17 F600\n" + body + "M2\n", "p.ngc")
    turned = parse_program("G21 G17 F600\nG10 L2 P1 X5 Y7 R30\nG0 X0 Y0\n" + body + "M2\n", "t.ngc")
    inches = parse_program("G20 G17 F60\n" + body + "M2\n", "i.ngc")
    a = np.array([m.end[:2] for m in plain.moves])
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    moved = a @ np.array([[c, s], [-s, c]]) + np.array([5.0, 7.0])
    assert len(turned.moves) == len(plain.moves) + 1 == len(inches.moves) + 1 == 97
    assert np.max(np.abs(np.array([m.end[:2] for m in turned.moves[1:]]) - moved)) < 1e-9
    assert np.max(np.abs(np.array([m.end[:2] for m in inches.moves]) - 25.4 * a)) < 1e-9
    assert [(len(s.points), s.order) for s in plain.splines] == [(4, 4), (3, 3), (5, 4)]
    assert [s.points for s in inches.splines] == [tuple((25.4 * x, 25.4 * y, w) for x, y, w in s.points)
                                                  for s in plain.splines]


def test_where_linuxcnc_finds_no_biarc_a_line_is_fed() -> None:
    """Parallel end tangents (a straight stretch): LinuxCNC's biarc has no solution and leaves
    the stretch out; here it is a straight line to the stretch's end."""
    assert biarc((0.0, 0.0), (1.0, 0.0), (5.0, 0.0), (1.0, 0.0)) is None
    program = parse_program("G21 G17 F600\nG5.2 L3\nX10 Y0 P1\nX20 Y0 P1\nX30 Y0 P1\nG5.3\nM2\n", "s.ngc")
    assert all(m.arc is None for m in program.moves)
    assert program.moves[-1].end[:2].tolist() == [30.0, 0.0]
    ys = np.array([m.end[1] for m in program.moves])
    assert np.all(ys == 0.0) and np.all(np.diff([m.end[0] for m in program.moves]) > 0)


REFUSALS = [
    # (program, line, column, what the message says)
    ("G21 F100\nG5 X10 Y10 I1 J1\nM2\n", 2, 1, "G05 needs both P and Q"),
    ("G21 F100\nG5 X10 Y10 I1 P1 Q1\nM2\n", 2, 12, "G05 needs both I and J, or neither"),
    ("G21 F100\nG5.1 X10 Y10 I1\nM2\n", 2, 14, "G05.1 needs both I and J"),
    ("G21 F100\nG5 I1 J1 P1 Q1\nM2\n", 2, 1, "G5 needs X or Y"),
    ("G21 F100\nG18 G5 X10 Z1 I1 J1 P1 Q1\nM2\n", 2, 5, "curves only in the XY plane (G17)"),
    ("G21 F100\nG5 X10 Y10 Z3 I1 J1 P1 Q1\nM2\n", 2, 12, "moves in X and Y only, not Z"),
    ("G21\nG5 X10 Y10 I1 J1 P1 Q1\nM2\n", 2, 1, "feed rate is zero"),
    ("G21 F100\nG41.1 D2\nG1 X5\nG5 X10 Y10 I1 J1 P1 Q1\nM2\n", 4, 1, "cutter radius compensation on"),
    ("G21 G93\nG5 X10 Y10 I1 J1 P1 Q1 F2\nM2\n", 2, 1, "inverse time feed mode (G93)"),
    ("G21 F100\nG5.3\nM2\n", 2, 1, "G05.3 without G05.2"),
    ("G21 F100\nG5.2 L4\nX1 Y1 P1\nX2 Y0 P1\nG5.3\nM2\n", 5, 1, "order L = 4 needs at least 4"),
    ("G21 F100\nG5.2\nX1 Y1 P1\nX2 P1\nG5.3\nM2\n", 4, 1, "needs both X and Y"),
    ("G21 F100\nG5.2\nX1 Y1 P0\nG5.3\nM2\n", 3, 7, "positive weight P"),
    ("G21 F100\nG5.2\nX1 Y1\nG5.3\nM2\n", 3, 1, "positive weight P"),
    ("G21 F100\nG5.2\nX1 Y1 P1\nP2\nG5.3\nM2\n", 4, 1, "P word with no G code that uses it"),
    ("G21 F100\nG5.2\nX1 Y1 P1\nX2 Y2 P1\nG1 X5\nM2\n", 5, 1, "before the NURBS begun at line 2 is ended"),
    ("G21 F100\nG5.2\nX1 Y1 P1\nX2 Y2 P1\nM2\n", 5, 1, "program ends with the NURBS begun at line 2"),
    ("G21 F100\nG5.2\nX1 Y1 P1\nX2 Y2 P1\n", 2, 1, "program ends with this NURBS (G05.2) not ended"),
    ("G21 F100\nG5.2 L2.5\nX1 Y1 P1\nG5.3\nM2\n", 2, 6, "L (the NURBS order) must be a whole number"),
    ("G21 F100\nG1 X1 Q2\nM2\n", 2, 7, "Q word with no code that uses it (G05"),
]


@pytest.mark.parametrize(("text", "line", "col", "why"), REFUSALS)
def test_each_refusal_names_its_place_and_reason(text: str, line: int, col: int, why: str) -> None:
    with pytest.raises(ProgramError) as caught:
        parse_program(text, "bad.ngc")
    err = caught.value.errors[0]
    assert (err.line, err.col) == (line, col), str(caught.value)
    assert why in err.message, err.message


@pytest.mark.skipif(RS274 is None, reason="LinuxCNC's rs274 is not installed (make test installs Debian's "
                    "linuxcnc-uspace as root)")
@pytest.mark.parametrize("text", [
    "G21 F100\nG5 X10 Y10 I1 J1\nM2\n",                       # no P and Q
    "G21 F100\nG5.1 X10 Y10 I1\nM2\n",                        # no J
    "G21 F100\nG18 G5 X10 Z1 I1 J1 P1 Q1\nM2\n",              # not in XY
    "G21 F100\nG5 X10 Y10 Z3 I1 J1 P1 Q1\nM2\n",              # Z in a spline
    "G21\nG5 X10 Y10 I1 J1 P1 Q1\nM2\n",                      # no feed
    "G21 F100\nG41.1 D2\nG1 X5\nG5 X10 Y10 I1 J1 P1 Q1\nM2\n",  # compensation on
    "G21 F100\nG5.3\nM2\n",                                   # no G5.2 before
    "G21 F100\nG5.2 L4\nX1 Y1 P1\nX2 Y0 P1\nG5.3\nM2\n",      # fewer points than the order
    "G21 F100\nG5.2\nX1 Y1 P1\nX2 P1\nG5.3\nM2\n",            # X without Y
    "G21 F100\nG5.2\nX1 Y1 P0\nG5.3\nM2\n",                   # a weight of 0
])
def test_linuxcnc_refuses_the_same_block(text: str) -> None:
    theirs, ours = refused_alike(text)
    assert theirs == ours


def _nurbs_points_whole(points: np.ndarray, k: int, u: np.ndarray) -> np.ndarray:
    """The curve with every basis function at every parameter (LinuxCNC's sums, in its order)."""
    from planner.geometry.splines import _basis, knot_vector

    n = len(points) - 1
    basis = _basis(u, k, knot_vector(n, k), n + 1)
    den = np.zeros(len(u))
    for i in range(n + 1):
        den = den + basis[i] * points[i, 2]
    x, y = np.zeros(len(u)), np.zeros(len(u))
    for i in range(n + 1):
        x = x + points[i, 0] * basis[i] * points[i, 2] / den
        y = y + points[i, 1] * basis[i] * points[i, 2] / den
    return np.column_stack([x, y])


@settings(max_examples=60, deadline=None)
@given(st.integers(2, 5).flatmap(lambda k: st.tuples(
           st.just(k),
           st.lists(st.tuples(st.floats(-500, 500), st.floats(-500, 500), st.floats(0.1, 10)),
                    min_size=k, max_size=1400),
           st.integers(0, 10**6))))
def test_the_curve_a_piece_at_a_time_is_the_whole_recursion_bit_for_bit(case) -> None:
    """Only the basis functions alive in a chunk of parameters (a few, not thousands): the same
    values, to the last bit, at the knots (where LinuxCNC's closed intervals overlap) too."""
    from planner.geometry.splines import NURBS_CHUNK

    k, rows, seed = case
    points = np.array(rows, dtype=float)
    umax = len(points) - 1 - k + 2
    rng = np.random.default_rng(seed)
    u = np.concatenate([np.linspace(0.0, umax, 3 * NURBS_CHUNK + 7), np.arange(umax + 1.0),
                        rng.uniform(0.0, umax, 50)])
    np.testing.assert_array_equal(nurbs_points(points, k, u), _nurbs_points_whole(points, k, u))
