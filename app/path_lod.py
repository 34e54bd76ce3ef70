"""Level of detail of a drawn tool path (no Qt): what the preview draws for a view.

A kind of move with more than ``LOD_MIN_POINTS`` points keeps thinned copies of itself
(``app.toolpath.thin``), finest first, each cube 4 times the one before; a copy is kept only
where it has at most half the points of the finer one kept before it (near-copies of the path
cost its memory and draw no faster). For a view, each such kind is taken from the coarsest copy
whose cubes stay within half a pixel (the kind's own points when zoomed in closer) and cut to
the view with a margin. The copies of a path are made once for all the plots that draw it.
When the view then still holds more than ``VECTOR_POINTS`` points, the path is drawn as one
image of the view (``app.path_raster``), which costs what its pixels cost whatever the
segments; else as vectors. Everything here runs in any thread: the preview computes a new view
off the GUI thread while the old one is shown.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from app.path_raster import Layer, rasterize
from app.toolpath import (
    PointRows,
    Polylines,
    ToolPath,
    joined_rows,
    nonzero_indices,
    rows_of,
    take_points,
    thin_copies,
)
from planner.core.heap import trim_heap
from planner.core.program import MoveKind

__all__ = ["ALL_MOVES", "Detail", "LodLevels", "ViewSpec", "build_levels", "detail", "forget_levels",
           "needs_levels"]

LOD_MIN_POINTS = 200_000
BASE_CELLS = 65_536  # the finest copy: the path's extent in this many cubes
LEVELS = 7  # each level's cube 4 times the one before (the coarsest: extent / 16)
MARGIN = 0.25  # of the view's size, drawn beyond each side (a pan shows no gap at once)
VECTOR_POINTS = 250_000  # more points in view: the path is drawn as an image of the view
# the part run, drawn over the path at every line reached: a coarser copy above this many
# points in view (250,000 points of vectors took 140 ms a frame)
EXECUTED_POINTS = 50_000
KINDS = (MoveKind.RAPID, MoveKind.LINE, MoveKind.ARC)  # drawing order (later on top)
# the copies of every move in program order, for the part already run (drawn over the path:
# at millions of points drawn whole it took 150 ms a frame at each line reached)
ALL_MOVES = "all"

Projection = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]
LodLevels = dict[MoveKind | str, list[tuple[float, Polylines]]]


@dataclass(frozen=True, slots=True)
class ViewSpec:
    """What is seen: the projection of the view and its range, a pixel's size in view units."""

    project: Projection
    x0: float
    x1: float
    y0: float
    y1: float
    pixel: float
    colours: dict[MoveKind, tuple[int, int, int, int]]


@dataclass(frozen=True, slots=True)
class Detail:
    """Vectors per kind (x, y, connect) or, for a dense view, one image and where it goes."""

    vectors: dict[MoveKind, tuple[np.ndarray, np.ndarray, np.ndarray]]
    image: np.ndarray | None = None  # (width, height, 4) uint8, column-major
    rect: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)  # x, y, width, height
    # every move in program order for this view, at most EXECUTED_POINTS points: (x, y, connect,
    # move index); the part run so far is a prefix of it (None: draw it from the whole path)
    executed: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None = None


def needs_levels(path: ToolPath | None) -> bool:
    """Whether ``path`` has a kind of move big enough for thinned copies."""
    return path is not None and len(path.all.points) > LOD_MIN_POINTS


# the copies of the last path asked for: the preview and the Auto page's backplot draw the same
# path, and each made its own copies (twice the memory, twice the work)
_made_lock = threading.Lock()
_made: tuple[ToolPath, threading.Event, list[LodLevels]] | None = None


def build_levels(path: ToolPath | None) -> LodLevels:
    """Thinned copies of every kind with many points (none for a small path); made once for the
    last path asked for, whatever thread asks (a second asker waits for the first's)."""
    global _made
    if path is None:
        return {}
    with _made_lock:
        entry = _made
        mine = entry is None or entry[0] is not path
        if mine:
            entry = _made = (path, threading.Event(), [])
    assert entry is not None
    if not mine:
        entry[1].wait()
        if entry[2]:
            return entry[2][0]
        return _make_levels(path)  # the first asker failed: its error is its own
    try:
        levels = _make_levels(path)
        entry[2].append(levels)
        return levels
    finally:
        entry[1].set()


def forget_levels(shown: ToolPath | None) -> None:
    """A widget now shows ``shown``: the copies of another path are let go (they held the
    path they were made of, hundreds of megabytes at 10,000,000 moves, after its program had
    gone). A build under way keeps its own until it ends."""
    global _made
    with _made_lock:
        if _made is not None and _made[0] is not shown:
            _made = None


def _make_levels(path: ToolPath) -> LodLevels:
    levels: LodLevels = {}
    lo, hi = path.bounds
    extent = float(np.max(np.asarray(hi, float) - np.asarray(lo, float))) if len(lo) else 0.0
    if not extent > 0.0:
        return levels

    origin = np.asarray(lo, float)

    def copies_of(pr: PointRows) -> list[tuple[float, Polylines]]:
        """The thinned copies of ``pr`` worth keeping, each as ``thin`` of the one before it
        makes it; only those kept are made (``thin_copies``), as 4-byte floats from the path's
        corner (``Polylines.origin``)."""
        cell, kept = extent / BASE_CELLS, len(pr)
        joined = joined_rows(pr)
        if len(joined) < 3:
            every = np.ones(len(joined), bool)
            return [(cell, take_points(joined, every, origin))] if 2 * len(joined) <= kept else []

        def worth_keeping(counts: list[int]) -> list[int]:
            """A copy with at most half the points of the finer one kept before it."""
            chosen, before = [], kept
            for level, count in enumerate(counts):
                if 2 * count <= before:
                    chosen.append(level)
                    before = count
            return chosen

        made = thin_copies(joined, cell, LEVELS, worth_keeping, origin)
        copies = [(cell * 4.0 ** level, made[level]) for level in sorted(made)]
        return copies

    for kind in KINDS:  # one kind's polylines at a time, let go once thinned
        points = int(np.count_nonzero(path.point_kind == kind))
        if not points:
            continue
        # a kind with few points is kept whole (cube 0: taken at every scale), so that the view's
        # detail never takes it from the whole path again
        if points > LOD_MIN_POINTS:
            levels[kind] = copies_of(path.kind_rows(kind))
        else:
            levels[kind] = [(0.0, path.kind(kind))]
    if len(path.all.points) > LOD_MIN_POINTS:
        levels[ALL_MOVES] = copies_of(rows_of(path.all))
    # the thinning's temporaries (rows of each kind, cube numbers per axis) lie freed in the
    # heap between the copies kept: handed back
    trim_heap()
    return levels


CUT_PIECE = 1 << 18  # points looked at a time when cutting a path to a view


def _projected(view: ViewSpec, points: np.ndarray,
               origin: np.ndarray | None) -> tuple[np.ndarray, np.ndarray]:
    """View coordinates of ``points`` (from ``origin`` when given: the projection is linear)."""
    x, y = view.project(points)
    if origin is None:
        return x, y
    ox, oy = view.project(origin[None, :])
    return np.add(x, ox[0], dtype=np.float64), np.add(y, oy[0], dtype=np.float64)


def _in_view(pl: Polylines | PointRows, view: ViewSpec) -> np.ndarray:
    """Which points of ``pl`` are drawn for the view (with a margin): those in it and the other
    end of every segment with one end in it. Looked at a piece at a time: the whole path seen
    close did not make its view coordinates at once (160 MB of 10,000,000 points), nor a copy
    of a kind's points (290 MB)."""
    pr = rows_of(pl) if isinstance(pl, Polylines) else pl
    origin = pl.origin if isinstance(pl, Polylines) else None
    n = len(pr)
    mx, my = MARGIN * (view.x1 - view.x0), MARGIN * (view.y1 - view.y0)
    inside = np.empty(n, bool)
    for lo in range(0, n, CUT_PIECE):
        x, y = _projected(view, pr.points(lo, lo + CUT_PIECE), origin)
        inside[lo:lo + CUT_PIECE] = ((x >= view.x0 - mx) & (x <= view.x1 + mx)
                                     & (y >= view.y0 - my) & (y <= view.y1 + my))
    keep = inside.copy()  # and the other end of every segment that has one end inside
    keep[1:] |= inside[:-1] & pr.connect[:-1]
    keep[:-1] |= inside[1:] & pr.connect[:-1]
    return keep


def _gather(pl: Polylines | PointRows, keep: np.ndarray, view: ViewSpec,
            relative: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The points of ``pl`` where ``keep``, with no line across what is left out: (x, y,
    connect, their moves), a piece at a time; ``relative``: x and y as 4-byte floats from
    the view's corner (x0, y0), for an image of it (half the memory of millions of points)."""
    pr = rows_of(pl) if isinstance(pl, Polylines) else pl
    origin = pl.origin if isinstance(pl, Polylines) else None
    idx = nonzero_indices(keep)
    k = len(idx)
    x, y = (np.empty(k, np.float32 if relative else np.float64) for _ in range(2))
    moves = np.empty(k, pr.source.move_index.dtype)
    for lo in range(0, k, CUT_PIECE):
        points, moves[lo:lo + CUT_PIECE] = pr.take(idx[lo:lo + CUT_PIECE])
        px, py = _projected(view, points, origin)
        if relative:
            px, py = px - view.x0, py - view.y0
        x[lo:lo + CUT_PIECE], y[lo:lo + CUT_PIECE] = px, py
    connect = pr.connect[idx]
    for lo in range(0, k - 1, CUT_PIECE):   # no line across what is left out
        hi = min(k - 1, lo + CUT_PIECE)
        connect[lo:hi] &= idx[lo + 1:hi + 1] - idx[lo:hi] == 1
    if k:
        connect[-1] = False
    return x, y, connect, moves


def _cut(pl: Polylines | PointRows, view: ViewSpec,
         most: int | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None:
    """The points of ``pl`` drawn for the view (``_in_view``) as (x, y, connect, their moves);
    None when there are more than ``most``."""
    keep = _in_view(pl, view)
    if most is not None and np.count_nonzero(keep) > most:
        return None
    return _gather(pl, keep, view)


def _source(path: ToolPath, kind: MoveKind, copies: list[tuple[float, Polylines]],
            view: ViewSpec) -> Polylines | PointRows:
    """The coarsest copy whose cubes stay within half a pixel; zoomed in closer than the
    finest copy, the kind's own points (rows of the path)."""
    pl: Polylines | PointRows | None = None
    for cell, part in copies:
        if cell <= 0.5 * view.pixel:  # a cube's diagonal within a pixel
            pl = part
    return pl if pl is not None else path.kind_rows(kind)


def _executed(path: ToolPath, copies: list[tuple[float, Polylines]],
              view: ViewSpec) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Every move in program order for the view: the finest copy within half a pixel, or a
    coarser one while more than EXECUTED_POINTS points would be in view (an overlay may be
    coarser than the path under it; vectors of millions of points are not drawn in time)."""
    candidates: list[Polylines | PointRows] = [rows_of(path.all)] + [part for _cell, part in copies]
    first = 0
    for k, (cell, _part) in enumerate(copies, start=1):
        if cell <= 0.5 * view.pixel:
            first = k
    for pl in candidates[first:]:
        cut = _cut(pl, view, None if pl is candidates[-1] else EXECUTED_POINTS)
        if cut is not None:
            return cut
    raise AssertionError("unreachable: the last copy is always taken")


# views of a big path made off the GUI thread are made one at a time: each holds some 100 MB
# of a 10,000,000-move path on the way, and the preview and the Auto page's backplot make
# theirs at once after every load (the GUI thread never waits for this lock)
_detail_lock = threading.Lock()


def detail(path: ToolPath, levels: LodLevels, view: ViewSpec) -> Detail:
    """What to draw of ``path`` for ``view``."""
    if not levels or threading.current_thread() is threading.main_thread():
        return _detail(path, levels, view)
    with _detail_lock:
        return _detail(path, levels, view)


def _detail(path: ToolPath, levels: LodLevels, view: ViewSpec) -> Detail:
    if not levels:  # a small path: drawn whole
        shown = {}
        for kind in KINDS:
            if path.kind_counts.get(kind, 0):
                pl = path.kind(kind)
                x, y = view.project(pl.points)
                shown[kind] = (x, y, pl.connect)
        return Detail(shown)
    sources = {kind: _source(path, kind, levels[kind], view) for kind in KINDS if kind in levels}
    keeps = {kind: _in_view(pl, view) for kind, pl in sources.items()}
    copies = levels.get(ALL_MOVES)
    executed = _executed(path, copies, view) if copies else None
    if sum(int(np.count_nonzero(keep)) for keep in keeps.values()) <= VECTOR_POINTS:
        shown = {kind: _gather(pl, keeps[kind], view)[:3] for kind, pl in sources.items()}
        return Detail(shown, executed=executed)
    w, h = view.x1 - view.x0, view.y1 - view.y0
    x0, y0 = view.x0 - MARGIN * w, view.y0 - MARGIN * h
    width = max(1, math.ceil((1 + 2 * MARGIN) * w / view.pixel))
    height = max(1, math.ceil((1 + 2 * MARGIN) * h / view.pixel))
    layers = []
    for kind in KINDS:       # from the view's corner: what is drawn is the pixels it passes
        if kind in sources:
            x, y, connect, _moves = _gather(sources[kind], keeps[kind], view, relative=True)
            layers.append(Layer(x, y, connect, view.colours[kind]))
            del x, y, connect, _moves
    del sources, keeps
    image = rasterize(layers, x0 - view.x0, y0 - view.y0, view.pixel, width, height)
    del layers
    # the view's points (millions, seen whole) were freed into the heap of the thread that
    # made them, where they stayed: 200 MB of a 10,000,000-move path after two views
    trim_heap()
    return Detail({}, image, (x0, y0, width * view.pixel, height * view.pixel), executed)
