"""Level of detail of the preview: thinned copies stay within a cube of the path, an image of
the view shows the pixels the path passes, and the preview draws a big program as an image
when seen whole and as its exact vectors when zoomed in."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.path_lod import ViewSpec, build_levels, detail
from app.path_raster import Layer, rasterize
from app.toolpath import Polylines, build_toolpath, thin
from planner.core.program import MoveKind
from planner.gcode.interpreter import parse_program


def _polyline(steps: list[tuple[float, float]], breaks: list[bool]) -> Polylines:
    pts = np.cumsum(np.array([(0.0, 0.0)] + steps), axis=0)
    pts = np.column_stack([pts, np.zeros(len(pts))])
    connect = np.ones(len(pts), bool)
    for i, b in enumerate(breaks[: len(pts)]):
        connect[i] = not b
    connect[-1] = False
    return Polylines(pts, connect, np.arange(len(pts), dtype=np.int32), len(pts))


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(st.floats(-3, 3), st.floats(-3, 3)), min_size=2, max_size=80),
       st.lists(st.booleans(), max_size=80), st.sampled_from([0.01, 0.5, 2.0]))
def test_thinning_keeps_run_ends_and_every_dropped_point_near_the_one_before(steps, breaks, cell):
    pl = _polyline(steps, [b and i % 7 == 0 for i, b in enumerate(breaks)])
    out = thin(pl, cell)
    assert len(out.points) <= len(pl.points)
    # every run's first and last point is drawn, the runs joined where one starts at the point
    # the one before ends (that point is then inside the joined run, and may be thinned)
    from app.toolpath import joined_runs

    joined = joined_runs(pl)
    starts = np.flatnonzero(np.r_[True, ~joined.connect[:-1]])
    ends = np.flatnonzero(~joined.connect)
    kept = {tuple(p) for p in out.points}
    for i in np.r_[starts, ends]:
        assert tuple(joined.points[i]) in kept
    # a dropped point lies within a cube's diagonal of a kept point of its own run before it
    diag = cell * np.sqrt(3.0) * (1 + 1e-12)
    for i, p in enumerate(pl.points):
        if tuple(p) not in kept:
            before = [q for q in pl.points[:i] if tuple(q) in kept]
            assert before and min(np.linalg.norm(before - p, axis=1)) <= diag


def _thin_whole(pl: Polylines, cell: float) -> Polylines:
    """The thinning of every point at once (the rule, written plainly)."""
    from app.toolpath import joined_runs

    pl = joined_runs(pl)
    pts, n = pl.points, len(pl.points)
    if n < 3:
        return pl
    same = np.ones(n - 1, bool)
    for k in range(pts.shape[1]):
        c = np.floor(pts[:, k] / cell)
        same &= c[1:] == c[:-1]
    keep = np.ones(n, bool)
    keep[1:-1] = ~(same[:-1] & pl.connect[:-2] & pl.connect[1:-1])
    idx = np.flatnonzero(keep)
    return Polylines(pts[idx], pl.connect[idx], pl.move_index[idx], pl.count)


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(st.floats(-3, 3), st.floats(-3, 3)), min_size=2, max_size=80),
       st.lists(st.booleans(), max_size=80), st.sampled_from([0.01, 0.5, 2.0]),
       st.sampled_from([1, 2, 7, 64]))
def test_thinning_a_piece_at_a_time_is_thinning_at_once(steps, breaks, cell, piece):
    # millions of points are thinned a piece at a time (their cube numbers took 250 MB at once)
    import app.toolpath as toolpath

    pl = _polyline(steps, [b and i % 5 == 0 for i, b in enumerate(breaks)])
    old = toolpath.THIN_PIECE
    toolpath.THIN_PIECE = piece
    try:
        got = thin(pl, cell)
    finally:
        toolpath.THIN_PIECE = old
    want = _thin_whole(pl, cell)
    for name in ("points", "connect", "move_index"):
        np.testing.assert_array_equal(getattr(got, name), getattr(want, name), err_msg=name)


# no subnormal steps (1e-320 mm): there floor(floor(x / c) / 4) and floor(x / 4 c) part, as
# dividing a subnormal rounds to zero; a machine's coordinates are never that small
_STEP = st.floats(-3, 3, allow_subnormal=False)


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(_STEP, _STEP), min_size=2, max_size=120),
       st.lists(st.booleans(), max_size=120), st.sampled_from([0.003, 0.01, 0.13]),
       st.sampled_from([3, 64]))
def test_each_level_taken_from_the_whole_is_the_level_thinned_from_the_one_before(steps, breaks, cell, piece):
    # cubes of 4 c are made of whole cubes of c: the copies are made from the path at once,
    # none made only to make the next, and are the chain of thinnings to the point
    import app.toolpath as toolpath
    from app.toolpath import joined_runs, take_points, thin_masks

    pl = _polyline(steps, [b and i % 6 == 0 for i, b in enumerate(breaks)])
    old = toolpath.THIN_PIECE
    toolpath.THIN_PIECE = piece
    try:
        joined = joined_runs(pl)
        masks = thin_masks(joined, cell, 5) if len(joined.points) >= 3 else []
        part = pl
        for level, keep in enumerate(masks):
            part = _thin_whole(part, cell * 4.0 ** level)
            got = take_points(joined, keep)
            for name in ("points", "connect", "move_index"):
                np.testing.assert_array_equal(getattr(got, name), getattr(part, name),
                                              err_msg=f"{level} {name}")
    finally:
        toolpath.THIN_PIECE = old


def test_a_raster_image_shows_the_pixels_a_segment_passes():
    layer = Layer(np.array([0.5, 9.5]), np.array([2.5, 2.5]), np.array([True, False]), (0, 255, 0, 255))
    img = rasterize([layer], 0.0, 0.0, 1.0, 12, 6)
    assert img.shape == (12, 6, 4)
    lit = img[:, :, 3] > 0
    assert lit[0:11, 2].all() and lit[0:10, 3].all()  # two pixels wide
    assert not lit[:, 0:2].any() and not lit[11, 2] and not lit[:, 4:].any()
    top = Layer(np.array([4.5, 4.5]), np.array([0.5, 5.5]), np.array([True, False]), (255, 0, 0, 255))
    both = rasterize([layer, top], 0.0, 0.0, 1.0, 12, 6)
    assert tuple(both[4, 2]) == (255, 0, 0, 255)  # the later layer covers the earlier one


@pytest.fixture(scope="module")
def big_path():
    rows = []
    for r in range(200):
        xs = np.arange(0, 2001) * 0.05
        rows.append("\n".join(f"X{x:.2f} Y{r * 0.5:.1f}" for x in (xs if r % 2 == 0 else xs[::-1])))
    text = "G1 F600\n" + "\n".join(rows) + "\n"
    path = build_toolpath(parse_program(text, "raster.ngc"))
    assert len(path.kinds[MoveKind.LINE].points) > 400_000
    return path


def _view(x0, x1, y0, y1, pixel):
    return ViewSpec(lambda p: (p[:, 0], p[:, 1]), x0, x1, y0, y1, pixel,
                    {k: (0, 255, 0, 255) for k in MoveKind})


def test_a_big_path_seen_whole_is_an_image_and_zoomed_in_its_own_points(big_path):
    levels = build_levels(big_path)
    assert MoveKind.LINE in levels and MoveKind.RAPID not in levels
    whole = detail(big_path, levels, _view(-5, 105, -5, 100, 0.1))
    assert whole.image is not None and not whole.vectors
    assert (whole.image[:, :, 3] > 0).mean() > 0.05
    near = detail(big_path, levels, _view(10, 12, 10, 12, 0.002))
    assert near.image is None
    x, y, connect = near.vectors[MoveKind.LINE]
    assert 0 < len(x) < 10_000
    pts = big_path.kinds[MoveKind.LINE].points
    inside = (pts[:, 0] >= 10) & (pts[:, 0] <= 12) & (pts[:, 1] >= 10) & (pts[:, 1] <= 12)
    drawn = set(zip(x.tolist(), y.tolist()))
    assert all((px, py) in drawn for px, py in pts[inside, :2].tolist())  # every point in view


def test_the_preview_draws_a_big_path_as_an_image_then_zoomed_in_as_vectors(qtbot, big_path):
    from app.widgets.preview_plot import PreviewPlot

    plot = PreviewPlot()
    qtbot.addWidget(plot)
    plot.resize(900, 600)
    plot.show()
    plot.set_toolpath(big_path)  # its thinned copies are made off the GUI thread
    assert plot.detail_pending
    qtbot.waitUntil(lambda: not plot.detail_pending, timeout=10_000)
    assert plot.raster_item.isVisible() and plot.drawn_points() == 0
    plot.getViewBox().setRange(xRange=(10, 12), yRange=(10, 12), padding=0)
    qtbot.waitUntil(lambda: not plot.detail_pending, timeout=10_000)
    assert not plot.raster_item.isVisible()
    assert 0 < plot.drawn_points() < 10_000


def test_the_part_run_of_a_big_path_is_a_prefix_of_a_thinned_copy_in_view(big_path):
    """Seen whole, the run part of 400,000 points is drawn from a copy of at most
    EXECUTED_POINTS points; zoomed in, every point of the path in view that was run is drawn."""
    from app.path_lod import ALL_MOVES, EXECUTED_POINTS

    levels = build_levels(big_path)
    assert ALL_MOVES in levels
    whole = detail(big_path, levels, _view(-5, 105, -5, 100, 0.1))
    x, y, connect, moves = whole.executed
    assert 0 < len(x) <= EXECUTED_POINTS < len(big_path.all.points)
    assert np.all(np.diff(moves) >= 0)
    near = detail(big_path, levels, _view(10, 12, 10, 12, 0.002))
    x, y, connect, moves = near.executed
    pts, mi = big_path.all.points, np.asarray(big_path.all.move_index)
    inside = (pts[:, 0] >= 10) & (pts[:, 0] <= 12) & (pts[:, 1] >= 10) & (pts[:, 1] <= 12)
    drawn = set(zip(x.tolist(), y.tolist(), moves.tolist()))
    assert all((px, py, m) in drawn for (px, py), m in zip(pts[inside, :2].tolist(), mi[inside].tolist()))


def test_the_preview_draws_the_run_part_of_a_big_path_from_its_copy(qtbot, big_path):
    from app.path_lod import EXECUTED_POINTS
    from app.widgets.preview_plot import PreviewPlot

    plot = PreviewPlot()
    qtbot.addWidget(plot)
    plot.resize(900, 600)
    plot.show()
    plot.set_toolpath(big_path)
    qtbot.waitUntil(lambda: not plot.detail_pending, timeout=10_000)
    half = big_path.all.count // 2
    plot.set_executed(half)
    x = plot.done_item.xData
    ran = big_path.all.points[np.asarray(big_path.all.move_index) < half]
    assert 0 < len(x) <= EXECUTED_POINTS and len(x) < len(ran) / 2  # thinned, not the points run
    assert x.max() <= ran[:, 0].max() and plot.done_item.yData.max() <= ran[:, 1].max()
    assert plot.done_item.yData.max() >= ran[:, 1].max() - 0.5  # up to the row being cut
    plot.getViewBox().setRange(xRange=(10, 12), yRange=(10, 12), padding=0)  # the view's copy
    qtbot.waitUntil(lambda: not plot.detail_pending, timeout=10_000)
    assert 0 < len(plot.done_item.xData) < 10_000


def test_copies_are_made_once_per_path_and_each_halves_the_one_before(big_path):
    import threading

    from app.path_lod import ALL_MOVES

    got: list[object] = []
    threads = [threading.Thread(target=lambda: got.append(build_levels(big_path))) for _ in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(got) == 3 and got[0] is got[1] is got[2]  # the preview and the backplot share them
    levels = got[0]
    for key in (MoveKind.LINE, ALL_MOVES):
        source = big_path.all if key == ALL_MOVES else big_path.kind(key)
        sizes = [len(source.points)] + [len(part.points) for _cell, part in levels[key]]
        assert len(sizes) > 2 and all(2 * b <= a for a, b in zip(sizes, sizes[1:])), sizes
    other = build_toolpath(parse_program("G1 X1 Y1 F100\nG1 X2\n", "small.ngc"))
    assert build_levels(other) is not levels


def test_a_tap_on_a_big_path_picks_the_move_drawn_there(qtbot, big_path, monkeypatch):
    """Picked among the points drawn for the view (not every point of the path), the move under
    the finger; its highlight is that move's own points; the view fits the path's box."""
    import app.widgets.preview_plot as preview_plot
    from app.widgets.preview_plot import PreviewPlot

    def every_point(*_args):
        raise AssertionError("a big path is picked among the points drawn, not every point")

    monkeypatch.setattr(preview_plot, "nearest_projected", every_point)

    plot = PreviewPlot()
    qtbot.addWidget(plot)
    plot.resize(900, 600)
    plot.show()
    plot.set_toolpath(big_path)
    (x0, x1), (y0, y1) = plot.getViewBox().viewRange()
    assert x0 < 0.0 and x1 > 100.0 and y0 < 0.0 and y1 > 99.5  # the raster's 100 x 99.5 mm, padded
    qtbot.waitUntil(lambda: not plot.detail_pending, timeout=10_000)
    assert plot._executed is not None
    pts, mi = big_path.all.points, np.asarray(big_path.all.move_index)
    k = int(mi[np.flatnonzero((np.abs(pts[:, 1] - 50.0) < 1e-9) & (np.abs(pts[:, 0] - 33.3) < 0.03))[0]])
    picked = plot.pick(33.31, 50.0, radius=0.5)
    assert picked >= 0 and abs(picked - k) <= 20  # within a few of the 0.05 mm moves there
    assert np.all(np.abs(pts[mi == picked][:, 1] - 50.0) < 1e-9)  # on the row tapped
    plot.highlight_move(picked)
    # the move is drawn whole, from its start to its end: a 0.05 mm step along the row
    x, y = plot.selected_item.xData, plot.selected_item.yData
    assert len(x) == 2 and np.all(np.abs(y - 50.0) < 1e-9)
    assert abs(abs(x[1] - x[0]) - 0.05) < 1e-9
    assert plot.pick(50.0, 120.0, radius=0.5) == -1  # nothing there


def _mixed_path(seed: int, scale: float):
    """A path of rapids, lines and arcs (two points a line move: runs to join)."""
    rng = np.random.default_rng(seed)
    lines = ["G21 G90 F600"]
    for _ in range(60):
        x, y, z = (rng.uniform(-50, 50, 3) * scale).round(4)
        pick = rng.integers(0, 4)
        if pick == 0:
            lines.append(f"G0 X{x} Y{y} Z{z}")
        elif pick == 1:
            lines.append(f"G2 X{x} Y{y} R{abs(x) + abs(y) + 60 * scale:.4f}")
        else:
            lines.append(f"G1 X{x} Y{y} Z{z}")
    return build_toolpath(parse_program("\n".join(lines) + "\n", "mixed.ngc"))


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**31), st.sampled_from([0.001, 1.0, 1000.0]), st.sampled_from([1, 5, 64, 1 << 20]),
       st.sampled_from([0.01, 0.1, 1.0]))
def test_a_kind_thinned_as_rows_of_the_path_is_the_kind_thinned_as_a_copy(seed, scale, piece, cell):
    """The copies of a big path are made from rows of its points (no copy of a kind's points);
    a piece at a time; as 4-byte floats from the path's corner: the same points within a
    float's step of the extent, the same runs and moves."""
    import app.toolpath as toolpath
    from app.toolpath import joined_rows, joined_runs, take_points, thin_masks

    path = _mixed_path(seed, scale)
    lo, hi = path.bounds
    extent = float(np.max(hi - lo))
    old = toolpath.THIN_PIECE
    toolpath.THIN_PIECE = piece
    try:
        for kind in (MoveKind.RAPID, MoveKind.LINE, MoveKind.ARC):
            rows = joined_rows(path.kind_rows(kind))
            copy = joined_runs(path.kind(kind))
            assert len(rows) == len(copy.points)
            if len(copy.points) < 3:
                continue
            masks = zip(thin_masks(rows, cell * scale, 3), thin_masks(copy, cell * scale, 3))
            for keep_rows, keep_copy in masks:
                np.testing.assert_array_equal(keep_rows, keep_copy)
                want = take_points(copy, keep_copy)
                got = take_points(rows, keep_rows, np.asarray(lo))
                assert got.points.dtype == np.float32
                np.testing.assert_array_equal(got.connect, want.connect)
                np.testing.assert_array_equal(got.move_index, want.move_index)
                np.testing.assert_allclose(got.points + got.origin, want.points, rtol=0,
                                           atol=extent * 2.0**-22)
    finally:
        toolpath.THIN_PIECE = old


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**31), st.sampled_from([3, 64, 1 << 20]), st.floats(0.05, 0.9), st.floats(0.05, 0.9))
def test_a_path_cut_to_a_view_a_piece_at_a_time_is_cut_at_once(seed, piece, fx, fy):
    import app.path_lod as path_lod

    path = _mixed_path(seed, 1.0)
    lo, hi = path.bounds
    x0, y0 = lo[0] + fx * (hi[0] - lo[0]) * 0.5, lo[1] + fy * (hi[1] - lo[1]) * 0.5
    view = _view(x0, x0 + 30, y0, y0 + 30, 0.05)
    old = path_lod.CUT_PIECE
    path_lod.CUT_PIECE = piece
    try:
        got = path_lod._cut(path.kind_rows(MoveKind.LINE), view)
        assert got is not None
    finally:
        path_lod.CUT_PIECE = old
    # the rule, written plainly over a copy of the kind
    pl = path.kind(MoveKind.LINE)
    x, y = pl.points[:, 0], pl.points[:, 1]
    m = 0.25 * 30
    inside = (x >= view.x0 - m) & (x <= view.x1 + m) & (y >= view.y0 - m) & (y <= view.y1 + m)
    keep = inside.copy()
    keep[1:] |= inside[:-1] & pl.connect[:-1]
    keep[:-1] |= inside[1:] & pl.connect[:-1]
    idx = np.flatnonzero(keep)
    connect = pl.connect[idx] & np.r_[np.diff(idx) == 1, False]
    for a, b in zip(got, (x[idx], y[idx], connect, pl.move_index[idx])):
        np.testing.assert_array_equal(a, b)


def test_copies_of_a_big_path_hold_no_copy_of_its_points_on_the_way(big_path, monkeypatch):
    """Thinned copies are taken from rows of the path's points (a piece at a time), and kept
    as 4-byte floats: beyond the copies kept, making them holds less than half of what the
    path's points take (a copy of a kind's points took more than all of it)."""
    import tracemalloc

    import app.toolpath as toolpath
    from app.path_lod import ALL_MOVES, _make_levels

    monkeypatch.setattr(toolpath, "THIN_PIECE", 1 << 14)
    points_bytes = big_path.all.points.nbytes
    tracemalloc.start()
    try:
        levels = _make_levels(big_path)
        kept, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    copies = [part for key in (MoveKind.LINE, ALL_MOVES) for _c, part in levels[key]]
    assert len(copies) >= 2 and all(part.points.dtype == np.float32 for part in copies)
    assert kept < 1.2 * points_bytes and peak - kept < points_bytes / 2, (peak, kept, points_bytes)


@settings(max_examples=80, deadline=None)
@given(st.integers(0, 2**31), st.sampled_from([1, 3, 64]), st.sampled_from([0.05, 0.5, 5.0]))
def test_an_image_stepped_a_piece_of_the_segments_at_a_time_is_stepped_at_once(seed, piece, pixel):
    """Segments far more than pixels (their steps thinned to the image's budget) or fewer, in
    and out of the image: stepped a few segments at a time, the very same pixels."""
    import app.path_raster as path_raster

    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 400))
    x, y = np.cumsum(rng.normal(0, 3, (2, n)), axis=1)
    connect = rng.random(n) < 0.9
    layer = Layer(x, y, connect, (0, 255, 0, 255))
    old = path_raster.COVER_PIECE
    try:
        path_raster.COVER_PIECE = piece
        got = rasterize([layer], -10.0, -10.0, pixel, 40, 30)
        path_raster.COVER_PIECE = 1 << 20
        want = rasterize([layer], -10.0, -10.0, pixel, 40, 30)
    finally:
        path_raster.COVER_PIECE = old
    np.testing.assert_array_equal(got, want)


def test_an_image_of_a_big_path_is_the_image_of_its_points_in_view(big_path):
    """Seen whole, the path's image is made from 4-byte coordinates taken from the view's
    corner (half the memory of its points in view): the pixels of the exact points but for
    a few on the edges of lines."""
    from app.path_lod import MARGIN, _cut, _source

    levels = build_levels(big_path)
    view = _view(-5, 105, -5, 100, 0.1)
    whole = detail(big_path, levels, view)
    assert whole.image is not None
    layers = []
    for kind in (MoveKind.RAPID, MoveKind.LINE, MoveKind.ARC):
        if kind in levels:
            x, y, connect, _moves = _cut(_source(big_path, kind, levels[kind], view), view)
            layers.append(Layer(x, y, connect, view.colours[kind]))
    w, h = whole.image.shape[:2]
    want = rasterize(layers, -5 - MARGIN * 110, -5 - MARGIN * 105, 0.1, w, h)
    lit = want[:, :, 3] > 0
    assert lit.sum() > 10_000
    assert np.count_nonzero(whole.image[:, :, 3] != want[:, :, 3]) <= 0.001 * lit.sum()


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**31), st.sampled_from([3, 64, 1 << 18]), st.sampled_from([0.01, 0.1]))
def test_copies_made_in_two_passes_are_the_masks_taken(seed, piece, cell):
    """``thin_copies`` counts each level's points in one pass and gathers the chosen levels in
    a second, holding no mask: the very copies the masks of the whole give."""
    import app.toolpath as toolpath
    from app.toolpath import joined_rows, take_points, thin_copies, thin_masks

    path = _mixed_path(seed, 1.0)
    rows = joined_rows(path.kind_rows(MoveKind.LINE))
    origin = np.asarray(path.bounds[0])
    old = toolpath.THIN_PIECE
    toolpath.THIN_PIECE = piece
    try:
        made = thin_copies(rows, cell, 4, lambda counts: [0, 2, 3], origin)
        masks = thin_masks(rows, cell, 4)
    finally:
        toolpath.THIN_PIECE = old
    assert sorted(made) == [0, 2, 3]
    for level, copy in made.items():
        want = take_points(rows, masks[level], origin)
        for name in ("points", "connect", "move_index", "origin"):
            np.testing.assert_array_equal(getattr(copy, name), getattr(want, name), err_msg=f"{level} {name}")
