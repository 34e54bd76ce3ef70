"""Tool path arrays for drawing: counts per kind, arcs on their exact geometry, picking."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.toolpath import build_toolpath, nearest_projected
from planner.core.program import MoveKind
from planner.gcode.interpreter import parse_program

PROGRAM = """G21 G17 G90
G00 X0 Y0 Z5
G01 Z0 F300
G01 X10 Y0
G02 X20 Y0 R5
G03 X30 Y0 Z-1 I5 J0
G01 X30 Y10
G19 G02 Y20 Z-1 R5
G00 Z5
"""


@pytest.fixture(scope="module")
def path():
    return build_toolpath(parse_program(PROGRAM, name="t.nc"))


def test_counts_per_kind(path) -> None:
    assert path.kinds[MoveKind.RAPID].count == 2
    assert path.kinds[MoveKind.LINE].count == 3
    assert path.kinds[MoveKind.ARC].count == 3
    assert path.all.count == 8
    # lines are point pairs; each polyline ends with a break
    line = path.kinds[MoveKind.LINE]
    assert len(line.points) == 6 and line.connect.tolist() == [True, False] * 3


def test_arc_points_lie_on_the_exact_geometry(path) -> None:
    program = parse_program(PROGRAM, name="t.nc")
    arcs = path.kinds[MoveKind.ARC]
    for move in (m for m in program.moves if m.arc is not None):
        pts = arcs.points[arcs.move_index == move.index]
        np.testing.assert_allclose(pts[0], move.start, atol=1e-9)
        np.testing.assert_allclose(pts[-1], move.end, atol=1e-12)
        a = move.arc
        f, s = pts[:, a.first_axis], pts[:, a.second_axis]
        r = np.hypot(f - a.center[0], s - a.center[1])
        np.testing.assert_allclose(r, a.radius_start_mm, atol=1e-9)
        # for a circle/helix the angle parameter is proportional to arc length: compare with evaluate
        u = np.linspace(0.0, move.length_mm, len(pts))
        exact, _, _ = move.evaluate(u)
        np.testing.assert_allclose(pts, exact, atol=1e-9)


@pytest.mark.parametrize("rotation", [30.0, -72.5, 90.0, 160.0])
def test_arcs_in_a_rotated_system_are_drawn_in_their_turned_plane(rotation: float) -> None:
    """G18/G19 arcs (a helix among them) while the XY plane is rotated (G10 L2 R) lie in planes
    turned about Z: the preview draws the move's own points in the program's coordinates (the
    rotation undone, as the DRO reads them), where they swing in the program's X (Y) and Z."""
    text = (f"G21 G17 G90 F600\nG10 L2 P1 R{rotation}\nG0 X5 Y3 Z2\n"
            "G18 G2 X15 Z2 I5 K0\nG19 G3 Y13 Z2 X7 J5 K0\nG17\nM2\n")
    program = parse_program(text, name="t.nc")
    drawn = build_toolpath(program).kinds[MoveKind.ARC]
    arcs = [m for m in program.moves if m.arc is not None]
    assert [m.arc.plane for m in arcs] == ["ZX", "YZ"]
    for move in arcs:
        assert move.arc.xy_turn_rad == pytest.approx(np.radians(rotation))
        pts = drawn.points[drawn.move_index == move.index]
        u = np.linspace(0.0, move.length_mm, len(pts))
        machine = move.evaluate(u)[0]
        c, s = np.cos(np.radians(rotation)), np.sin(np.radians(rotation))
        np.testing.assert_allclose(pts[:, 0], c * machine[:, 0] + s * machine[:, 1], atol=1e-9)
        np.testing.assert_allclose(pts[:, 1], -s * machine[:, 0] + c * machine[:, 1], atol=1e-9)
        np.testing.assert_allclose(pts[:, 2], machine[:, 2], atol=1e-9)
        # the points swing in the program's X (Y) and Z about the programmed centre
        px, py = pts[:, 0], pts[:, 1]
        swing = px if move.arc.plane == "ZX" else py
        np.testing.assert_allclose(np.hypot(swing - (10.0 if move.arc.plane == "ZX" else 8.0),
                                            pts[:, 2] - 2.0), 5.0, atol=1e-9)


def test_helix_descends_linearly(path) -> None:
    arcs = path.kinds[MoveKind.ARC]
    program = parse_program(PROGRAM, name="t.nc")
    helix = next(m for m in program.moves if m.arc is not None and m.arc.rise_mm != 0)
    z = arcs.points[arcs.move_index == helix.index, 2]
    assert np.all(np.diff(z) < 0) and z[-1] == pytest.approx(-1.0)


def test_pick_nearest_segment(path) -> None:
    px, py = path.all.points[:, 0], path.all.points[:, 1]            # the XY view
    index, dist = nearest_projected(path, px, py, 5.0, 0.2)   # middle of G01 X10 (line 4)
    assert int(path.move_lines[index]) == 4 and dist == pytest.approx(0.2)
    index, _ = nearest_projected(path, px, py, 15.0, 5.0)      # top of the G02 R5 arc (line 5)
    assert int(path.move_lines[index]) == 5


def test_empty_program() -> None:
    path = build_toolpath(parse_program("G21\n", name="e.nc"))
    assert path.all.count == 0 and len(path.all.points) == 0


def test_corner_blends_are_drawn_on_their_curve() -> None:
    """G64 P blends (planner.geometry.blend) are drawn with the curved moves, on their exact points,
    and the drawing stays continuous through them."""
    from planner.core.machine import MachineSpec
    from planner.motion.blending import blend_program

    machine = MachineSpec.default()
    text = "G21 G90 G64 P0.05\nG0 X1 Y1\nG1 F3000 X21\nX41 Y2\nX61 Y1\nM2\n"
    program = blend_program(parse_program(text, name="b.nc", machine=machine), machine,
                            only_where_quicker=False)
    blends = [i for i, m in enumerate(program.moves) if m.kind is MoveKind.BLEND]
    assert len(blends) == 2
    path = build_toolpath(program)
    curved = path.kinds[MoveKind.ARC]
    assert curved.count == 2
    for i in blends:
        pts = curved.points[curved.move_index == i]
        move = program.moves[i]
        exact = move.evaluate(np.linspace(0.0, move.length_mm, len(pts)))[0]
        np.testing.assert_allclose(pts, exact, atol=1e-12)
        np.testing.assert_allclose(pts[0], program.moves[i - 1].end, atol=1e-12)
        np.testing.assert_allclose(pts[-1], program.moves[i + 1].start, atol=1e-12)


def test_a_program_of_columns_draws_as_one_of_move_objects() -> None:
    """A program read from G-code keeps its moves as columns; drawn from them or from the
    Move objects they stand for, the tool path is the same, point for point."""
    from dataclasses import replace

    from planner.core.movestore import MoveStore

    text = "G21 G90 G0 X1 Y1 Z5\nG1 Z-1 F300\n" + "".join(
        f"G1 X{i % 9} Y{i % 4}\nG2 X{i % 9 + 2} Y{i % 4} I1 J0\nG0 Z{1 + i % 3}\n" for i in range(40))
    program = parse_program(text)
    assert isinstance(program.moves, MoveStore)
    a = build_toolpath(program)
    b = build_toolpath(replace(program, moves=tuple(program.moves)))
    for kind in (MoveKind.RAPID, MoveKind.LINE, MoveKind.ARC):
        np.testing.assert_array_equal(a.kinds[kind].points, b.kinds[kind].points)
        np.testing.assert_array_equal(a.kinds[kind].move_index, b.kinds[kind].move_index)
    np.testing.assert_array_equal(a.all.points, b.all.points)
    np.testing.assert_array_equal(a.move_lines, b.move_lines)
    assert a.kinds[MoveKind.ARC].count == 40


def test_a_chain_of_lines_and_arcs_is_one_run_once_joined():
    """An arc's drawn ends are the very end points of the moves beside it, so the chain is one
    polyline that thinning can thin (a start off by a rounding of cos/sin broke it in runs)."""
    from app.toolpath import joined_runs

    text = "G1 X1 Y0.3 F600\nG2 X7.1 Y3.3 R4\nG1 X9 Y-1.7\nG3 X13.2 Y0.11 R3.7\nG1 X20 Y1\n"
    program = parse_program("G21 G90 G17\n" + text, "chain.nc")
    path = build_toolpath(program)
    joined = joined_runs(path.all)
    assert int((~joined.connect).sum()) == 1 < len(joined.points)
    for i in (1, 3):  # the arcs' first points are their moves' start points, bit for bit
        first = path.all.points[path.move_points(i)[0]]
        np.testing.assert_array_equal(first, program.moves[i].start)


@pytest.mark.parametrize("with_arcs", [False, True])
def test_each_kind_is_its_moves_points_in_program_order(with_arcs):
    """A kind's polylines, taken from the one path, draw exactly the moves of that kind, move
    after move, each from its start to its end: with arcs (merged by move), and without (a
    raster: one point a move, the program's own joints, rapids and feeds sharing them)."""
    arc = "G2 X6 Y2 R3\n" if with_arcs else "G1 X6 Y2\n"
    text = "G21 G90 G17\nG0 X1 Y1\nG1 X2 Y1 F600\nG1 X3 Y2\n" + arc + "G0 Z5\nG0 X0 Y0\nG1 Z0\n"
    program = parse_program(text, "kinds.nc")
    path = build_toolpath(program)
    kinds = [m.kind for m in program.moves]
    drawn: list[int] = []
    for kind in (MoveKind.RAPID, MoveKind.LINE):
        pl = path.kind(kind)
        idx = [i for i, k in enumerate(kinds) if k == kind]
        seg = np.flatnonzero(pl.connect)              # segment j: point j to point j + 1
        assert pl.count == len(idx) and pl.move_index[seg].tolist() == idx
        np.testing.assert_array_equal(pl.points[seg], np.array([program.moves[i].start for i in idx]))
        np.testing.assert_array_equal(pl.points[seg + 1], np.array([program.moves[i].end for i in idx]))
        drawn += idx
    arcs = path.kind(MoveKind.ARC)
    assert arcs.count == int(with_arcs) and (len(arcs.points) > 4) == with_arcs
    drawn += sorted(set(arcs.move_index.tolist()))
    assert sorted(drawn) == list(range(len(kinds)))          # every move drawn once, by its kind
    # a raster is one point a move: the path holds no copy of the joints beside the program's
    assert (len(path.all.points) == len(kinds) + 1) == (not with_arcs)


@pytest.mark.parametrize("with_arcs", [False, True])
def test_each_move_starts_at_its_first_point_and_keeps_its_line(with_arcs: bool) -> None:
    # kept 4 bytes a move (the index of each move's first point), the lines the program's own
    text = "G21 G0 X0 Y0\nG1 X5 F600\nY5\n" + ("G2 X10 Y0 R6\n" if with_arcs else "") + "G0 X0\nG1 Y2\n"
    program = parse_program(text)
    path = build_toolpath(program)
    n = len(program.moves)
    assert path.move_count == n
    for k, move in enumerate(program.moves):  # each move drawn from its start to its end
        lo, hi = path.move_points(k)
        assert hi - lo >= 2 and np.all(path.all.move_index[lo:hi - 1] == k)
        np.testing.assert_array_equal(path.all.points[lo], move.start)
        np.testing.assert_array_equal(path.all.points[hi - 1], move.end)
        assert path.points_before(k) == (lo if with_arcs else lo + (k > 0))
    assert path.points_before(n) == len(path.all.points)
    if with_arcs:   # 4 bytes a move: the index of each move's first point
        assert path.move_first_point is not None and path.move_first_point.dtype == np.int32
    else:           # one point a move, move k from point k: no index kept
        assert path.move_first_point is None
    np.testing.assert_array_equal(path.move_lines, [m.line for m in program.moves])
    assert np.shares_memory(path.move_lines, program.moves.columns().line)


@settings(max_examples=100, deadline=None)
@given(st.integers(1, 50), st.data())
def test_the_moves_of_a_one_point_a_move_path_read_as_their_array(n: int, data) -> None:
    """A raster's path keeps no move index a point (40 MB at 10,000,000 moves): read by a
    number, a slice, indices or a mask, it gives what the array gives, and refuses the same."""
    from app.toolpath import JointMoves

    joint = JointMoves(n)
    want = np.minimum(np.arange(n + 1, dtype=np.int32), n - 1)
    np.testing.assert_array_equal(np.asarray(joint), want)
    assert len(joint) == len(want) and joint.dtype == want.dtype
    k = data.draw(st.integers(-(n + 1), n))
    assert joint[k] == want[k]
    a, b = sorted(data.draw(st.lists(st.integers(-(n + 2), n + 2), min_size=2, max_size=2)))
    np.testing.assert_array_equal(joint[a:b], want[a:b])
    idx = np.array(data.draw(st.lists(st.integers(-(n + 1), n), max_size=8)), dtype=np.int64)
    np.testing.assert_array_equal(joint[idx], want[idx])
    mask = np.array(data.draw(st.lists(st.booleans(), min_size=n + 1, max_size=n + 1)))
    np.testing.assert_array_equal(joint[mask], want[mask])
    with pytest.raises(IndexError):
        joint[n + 1]
    with pytest.raises(IndexError):
        joint[np.array([0, n + 1])]


def test_a_raster_path_keeps_no_index_a_point() -> None:
    from app.toolpath import JointMoves

    text = "G21 G90 G0 X0 Y0\nG1 F600\n" + "".join(f"X{i % 2 * 10} Y{i * 0.5}\n" for i in range(400))
    path = build_toolpath(parse_program(text))
    assert isinstance(path.all.move_index, JointMoves) and path.move_first_point is None
    line = path.kind(MoveKind.LINE)           # a kind taken from it: the moves of its points
    assert np.all(np.diff(line.move_index) >= 0) and line.move_index[-1] == len(path.move_lines) - 1
