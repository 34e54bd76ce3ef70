"""Tool path of a Program as flat polylines for drawing (no Qt): vectorised over all moves.

Lines and rapids become point pairs; arcs, helices and spirals are sampled at most
ARC_STEP_RAD apart (at least MIN_ARC_POINTS points) from their exact parametrisation, all
arcs at once. The path is one array of points in program order with a ``connect`` array (True:
draw to the next point) and the kind each point is drawn as; each kind's polylines are taken
from it when asked, so pyqtgraph draws a whole program with a few items.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np

from planner.core.frames import Frame
from planner.core.movestore import MoveColumns
from planner.core.program import MoveKind, Program, turn_xy

ARC_STEP_RAD = math.radians(6.0)
MIN_ARC_POINTS = 5
MAX_ARC_POINTS = 400


@dataclass(frozen=True, slots=True)
class Polylines:
    """Points (N, n_axes) of one move kind in program order; connect[i]: segment i -> i+1."""

    points: np.ndarray
    connect: np.ndarray  # bool (N,)
    move_index: np.ndarray  # int32 (N,), move of each point (or a JointMoves standing for it)
    count: int  # number of moves drawn
    # None: ``points`` are where the points are; else the points are ``points + origin``
    # (a thinned copy keeps 4-byte floats from the path's corner: a copy's cube is at least
    # 1/65,536 of the path's extent, a float's step 1/16,777,216 of it)
    origin: np.ndarray | None = None


class JointMoves:
    """The move of each point of a path drawn one point a move (point k starts move k, the
    last point ends the last move): ``min(k, n - 1)``, read as the int32 array it stands for
    (indexed by a number, a slice, indices or a mask; ``np.asarray`` makes it), without the
    array: 40 MB at 10,000,000 moves."""

    __slots__ = ("n",)
    dtype = np.dtype(np.int32)

    def __init__(self, n_moves: int) -> None:
        if n_moves < 1:
            raise ValueError("a path of one point a move has a move")
        self.n = n_moves

    def __len__(self) -> int:
        return self.n + 1

    @property
    def shape(self) -> tuple[int]:
        return (self.n + 1,)

    def __getitem__(self, i: Any) -> Any:
        if isinstance(i, (int, np.integer)):
            k = int(i) + (self.n + 1 if i < 0 else 0)
            if not 0 <= k <= self.n:
                raise IndexError(f"point {i} of {self.n + 1}")
            return np.int32(min(k, self.n - 1))
        if isinstance(i, slice):
            return np.minimum(np.arange(self.n + 1, dtype=np.int32)[i], self.n - 1)
        idx = np.asarray(i)
        if idx.dtype == bool:
            idx = np.flatnonzero(idx)
        idx = np.where(idx < 0, idx + self.n + 1, idx)
        if idx.size and (idx.min() < 0 or idx.max() > self.n):
            raise IndexError(f"points out of 0 .. {self.n}")
        return np.minimum(idx, self.n - 1).astype(np.int32)

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        out = np.minimum(np.arange(self.n + 1, dtype=np.int32), self.n - 1)
        return out if dtype is None else out.astype(dtype)


@dataclass(frozen=True, slots=True)
class PointRows:
    """Polylines made of some points of ``source``, in order, without a copy of them: point i
    is ``source.points[rows[i]]`` (``rows`` None: every point), with a ``connect`` of its own.
    A kind of move of a 10,000,000-point path taken as a copy held 290 MB; as rows, 40."""

    source: Polylines
    rows: np.ndarray | None
    connect: np.ndarray
    count: int

    def __len__(self) -> int:
        return int(self.connect.shape[0])

    def points(self, lo: int, hi: int) -> np.ndarray:
        """Points lo .. hi - 1 (a new array unless every point is taken)."""
        return self.source.points[lo:hi] if self.rows is None else self.source.points[self.rows[lo:hi]]

    def take(self, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The points at ``idx`` and their moves."""
        rows = idx if self.rows is None else self.rows[idx]
        return self.source.points[rows], self.source.move_index[rows]


def rows_of(pl: Polylines) -> PointRows:
    """Every point of ``pl`` as rows."""
    return PointRows(pl, None, pl.connect, pl.count)


def nonzero_indices(mask: np.ndarray) -> np.ndarray:
    """``np.flatnonzero(mask)`` as 4-byte indices where they fit, a piece at a time (8 bytes
    a point at once was 80 MB of a 10,000,000-point path)."""
    n = int(mask.shape[0])
    if n >= 2**31:
        return np.flatnonzero(mask)
    out = np.empty(int(np.count_nonzero(mask)), np.int32)
    k = 0
    for lo in range(0, n, THIN_PIECE):
        part = np.flatnonzero(mask[lo:lo + THIN_PIECE])
        out[k:k + len(part)] = part + lo
        k += len(part)
    return out


DRAWN_KINDS = (MoveKind.RAPID, MoveKind.LINE, MoveKind.ARC)  # blends are drawn with the arcs


@dataclass(frozen=True, slots=True)
class ToolPath:
    axes: tuple[str, ...]
    all: Polylines  # every move, program order
    # the kind each point of ``all`` is drawn as (blends as arcs), int8: each kind's polylines
    # are taken from ``all`` when asked (``kind``), not kept beside it (58 bytes a line move)
    point_kind: np.ndarray
    kind_counts: dict[MoveKind, int]  # moves drawn as each kind
    move_lines: np.ndarray  # int32 (n_moves,), source line per move
    # int32 (n_moves,), index of each move's first point in ``all``; None where the path is
    # one point a move (move k runs from point k to point k + 1: 40 MB less at 10,000,000)
    move_first_point: np.ndarray | None
    bounds: tuple[np.ndarray, np.ndarray]  # (min, max) per axis
    # the program's frames (``Program.frames``) and, per move, the one it is drawn through
    # from machine positions into the program's (work) coordinates, as the DRO shows them
    # (coordinate system, XY rotation, G92, tool length offset); none: machine coordinates
    frames: tuple[Frame, ...] = ()
    move_frames: np.ndarray | None = None

    def frame_of(self, k: int) -> Frame | None:
        """The frame move ``k`` is drawn through (None: none recorded, or no such move)."""
        if self.move_frames is None or not 0 <= k < len(self.move_frames):
            return None
        return self.frames[int(self.move_frames[k])]

    def column(self, name: str) -> int | None:
        return self.axes.index(name) if name in self.axes else None

    @property
    def move_count(self) -> int:
        return int(self.move_lines.shape[0])

    def move_points(self, k: int) -> tuple[int, int]:
        """Where move ``k`` (0 <= k < move_count) is drawn: ``all.points[lo:hi]``."""
        if self.move_first_point is None:
            return k, k + 2
        first = self.move_first_point
        return int(first[k]), int(first[k + 1]) if k + 1 < len(first) else len(self.all.points)

    def points_before(self, k: int) -> int:
        """How many points of ``all`` draw moves 0 .. k - 1 (those run before move k)."""
        if k <= 0:
            return 0
        if k >= self.move_count:
            return len(self.all.points)
        return self.move_points(k - 1)[1]

    def kind(self, kind: MoveKind) -> Polylines:
        """The polylines of one kind of move, as a copy (``kind_rows``: the same without)."""
        rows = self.kind_rows(kind)
        idx = np.arange(len(rows))
        points, move_index = rows.take(idx)
        return Polylines(points, rows.connect, move_index, rows.count)

    def kind_rows(self, kind: MoveKind) -> PointRows:
        """The polylines of one kind of move as rows of ``all``. A point's kind is that of the
        segment it starts; the point ending a segment of this kind comes along whatever kind
        starts there (a raster's path is one point a move, rapids and feeds sharing their
        joints)."""
        if not self.kind_counts.get(kind, 0):
            return rows_of(_empty(len(self.axes)))
        mine = self.point_kind == kind
        starts = mine & self.all.connect          # points that start a drawn segment of this kind
        mine[1:] |= starts[:-1]                   # ... and the points that end them
        rows = nonzero_indices(mine)
        return PointRows(self.all, rows, starts[rows], self.kind_counts[kind])

    @property
    def kinds(self) -> dict[MoveKind, Polylines]:
        """Every kind's polylines (made when asked)."""
        return {kind: self.kind(kind) for kind in DRAWN_KINDS}


def _empty(n_axes: int) -> Polylines:
    return Polylines(np.zeros((0, n_axes)), np.zeros(0, bool), np.zeros(0, np.int32), 0)


PIECE_MOVES = 1 << 18  # filled a piece at a time: each NumPy pass holds the GIL a few ms


def _straight(starts: np.ndarray, ends: np.ndarray, idx: np.ndarray) -> Polylines:
    n = len(idx)
    pts = np.empty((2 * n, starts.shape[1]))
    move_index = np.empty(2 * n, np.int32)
    for lo in range(0, n, PIECE_MOVES):  # 10,000,000 moves at once held the panel 0.35 s
        hi = min(n, lo + PIECE_MOVES)
        pts[2 * lo: 2 * hi: 2], pts[2 * lo + 1: 2 * hi: 2] = starts[lo:hi], ends[lo:hi]
        move_index[2 * lo: 2 * hi: 2] = move_index[2 * lo + 1: 2 * hi: 2] = idx[lo:hi]
    connect = np.zeros(2 * n, bool)
    connect[0::2] = True
    return Polylines(pts, connect, move_index, n)


def _arcs(program: Program, idx: np.ndarray, cols: MoveColumns) -> Polylines:
    """Sample every arc at once: per-arc point counts, then one vectorised evaluation."""
    moves = program.moves
    n_axes = len(program.axes)
    if len(idx) == 0:
        return _empty(n_axes)
    if np.array_equal(cols.arc_rows, idx):  # the program's columns
        arcs = list(cols.arcs)
        start, end = cols.start[idx], cols.end[idx]
    else:
        arcs = [moves[i].arc for i in idx]
        start = np.array([moves[i].start for i in idx])
        end = np.array([moves[i].end for i in idx])
    sweep = np.array([a.sweep_rad for a in arcs])
    a0 = np.array([a.start_angle_rad for a in arcs])
    r0 = np.array([a.radius_start_mm for a in arcs])
    r1 = np.array([a.radius_end_mm for a in arcs])
    cf = np.array([a.center[0] for a in arcs])
    cs = np.array([a.center[1] for a in arcs])
    rise = np.array([a.rise_mm for a in arcs])
    f_ax = np.array([a.first_axis for a in arcs])
    s_ax = np.array([a.second_axis for a in arcs])
    n_ax = np.array([a.normal_axis for a in arcs])

    counts = np.clip(np.ceil(np.abs(sweep) / ARC_STEP_RAD).astype(int) + 1, MIN_ARC_POINTS, MAX_ARC_POINTS)
    total = int(counts.sum())
    owner = np.repeat(np.arange(len(idx)), counts)
    first = np.cumsum(counts) - counts
    t = (np.arange(total) - first[owner]) / (counts[owner] - 1)

    pts = start[owner] + t[:, None] * (end - start)[owner]   # axes off the plane: linear in t
    theta = a0[owner] + sweep[owner] * t
    r = r0[owner] + (r1 - r0)[owner] * t
    rows = np.arange(total)
    # arcs in a turned frame (G18/G19 in a rotated system): the points are made in the frame,
    # where the linear part (start + t delta) is turned first, and turned back
    turn = np.array([a.xy_turn_rad for a in arcs])
    tr = np.nonzero(turn[owner] != 0.0)[0]
    if tr.size:
        xy = np.array([a.turned_xy or (0, 0) for a in arcs])[owner[tr]]
        turn_xy(pts, xy[:, 0], xy[:, 1], -turn[owner[tr]], tr)
    pts[rows, f_ax[owner]] = cf[owner] + r * np.cos(theta)
    pts[rows, s_ax[owner]] = cs[owner] + r * np.sin(theta)
    has_n = (n_ax[owner] >= 0) & (turn[owner] == 0.0)   # in a frame the normal is already there
    rn, on, nn = rows[has_n], owner[has_n], n_ax[owner][has_n]
    pts[rn, nn] = start[on, nn] + rise[on] * t[has_n]
    if tr.size:
        turn_xy(pts, xy[:, 0], xy[:, 1], turn[owner[tr]], tr)
    last = first + counts - 1
    # exact start and end points: an arc's ends are then the very points of the moves beside
    # it, so a chain of arcs and lines is one run (``joined_runs``), which thinning can thin
    pts[first] = start
    pts[last] = end
    connect = np.ones(total, bool)
    connect[last] = False
    return Polylines(pts, connect, idx[owner].astype(np.int32), len(idx))


BLEND_POINTS = 9
THIN_PIECE = 1 << 18  # points thinned at a time (their temporaries: some 12 MB)


def _blends(program: Program, idx: np.ndarray) -> Polylines:
    """Corner blends sampled at BLEND_POINTS points each from their exact geometry."""
    n_axes = len(program.axes)
    if not len(idx):
        return _empty(n_axes)
    pts = np.concatenate([program.moves[i].evaluate(np.linspace(0.0, program.moves[i].length_mm,
                                                                 BLEND_POINTS))[0] for i in idx])
    connect = np.tile(np.r_[np.ones(BLEND_POINTS - 1, bool), False], len(idx))
    return Polylines(pts, connect, np.repeat(idx, BLEND_POINTS).astype(np.int32), len(idx))


def _merge(parts: list[Polylines], n_axes: int,
           codes: list[int] | None = None) -> tuple[Polylines, np.ndarray]:
    """Concatenate polylines and reorder their points by move index (stable within a move);
    and the code of the part each point came from (``codes``, one per part)."""
    if not parts:
        return _empty(n_axes), np.zeros(0, np.int8)
    pts = np.concatenate([p.points for p in parts])
    con = np.concatenate([p.connect for p in parts])
    mi = np.concatenate([p.move_index for p in parts])
    order = np.argsort(mi, kind="stable")
    codes = codes or [0] * len(parts)
    code = np.concatenate([np.full(len(p.points), c, np.int8) for p, c in zip(parts, codes)])
    return Polylines(pts[order], con[order], mi[order], sum(p.count for p in parts)), code[order]


def build_toolpath(program: Program) -> ToolPath:
    n_axes = len(program.axes)
    moves = program.moves
    n = len(moves)
    # the program's moves are columns: no Move object is made here
    cols = moves.columns()
    kinds, lines = cols.kind, cols.line.astype(np.int32, copy=False)   # the program's own
    arc_idx = np.flatnonzero(kinds == MoveKind.ARC)
    blend_idx = np.flatnonzero(kinds == MoveKind.BLEND)
    counts = {MoveKind.RAPID: int(np.count_nonzero(kinds == MoveKind.RAPID)),
              MoveKind.LINE: int(np.count_nonzero(kinds == MoveKind.LINE)),
              MoveKind.ARC: len(arc_idx) + len(blend_idx)}

    def straight(idx: np.ndarray) -> Polylines:
        if len(idx) == n:                       # every move: the columns themselves, no copy
            return _straight(cols.start, cols.end, idx)
        return _straight(cols.start[idx], cols.end[idx], idx)

    own_points = True      # the points are this path's (not the program's, which stay as read)
    if not counts[MoveKind.ARC] and n:
        # lines and rapids only (a CAM raster): one point a move, the program's own joint
        # positions in program order (each move ends where the next starts), drawn as one run
        positions = moves.positions
        move_index: Any = JointMoves(n)
        connect = np.ones(n + 1, bool)
        connect[-1] = False
        everything = Polylines(positions, connect, move_index, n)
        point_kind = np.empty(n + 1, np.int8)
        point_kind[:-1] = kinds
        point_kind[-1] = kinds[-1]
        own_points = False
    elif not counts[MoveKind.ARC]:
        # lines and rapids given as Move objects: two points a move
        everything = straight(np.arange(n))
        point_kind = np.repeat(kinds.astype(np.int8), 2)
    else:
        # corner blends (G64 P) are drawn with the arcs: curved feed moves
        curved, _ = _merge([_arcs(program, arc_idx, cols), _blends(program, blend_idx)], n_axes)
        parts = [straight(np.flatnonzero(kinds == MoveKind.RAPID)),
                 straight(np.flatnonzero(kinds == MoveKind.LINE)), curved]
        everything, point_kind = _merge(parts, n_axes, [int(k) for k in DRAWN_KINDS])
        del parts, curved
    frames = tuple(c.frame for c in program.frames)
    move_frames = program.move_frames
    if move_frames is not None and n and len(everything.points):
        # drawn in work coordinates (what the program says, where the operator set part zero),
        # each move through its own frame as the DRO reads the machine there
        everything = _in_frames(everything, frames, move_frames, own_points)
    first_point: np.ndarray | None = None   # one point a move: move k starts at point k
    if own_points:
        first_point = np.searchsorted(everything.move_index, np.arange(n, dtype=np.int32))
        if len(everything.points) < 2**31:
            first_point = first_point.astype(np.int32)   # 4 bytes a move, not 8
    if len(everything.points):
        lo, hi = everything.points.min(axis=0), everything.points.max(axis=0)
    else:
        lo = hi = np.asarray(program.start_position, float)
    return ToolPath(tuple(program.axes), everything, point_kind, counts, lines, first_point, (lo, hi),
                    frames, move_frames)


def _in_frames(pl: Polylines, frames: tuple[Frame, ...], move_frames: np.ndarray, own: bool) -> Polylines:
    """``pl``'s machine points in the program's coordinates, each move's through its frame
    (in place where the points are ``own``; one frame throughout: one conversion). A point
    two moves share (one point a move) ends the move before it and is drawn through that
    move's frame: each move's end is where the DRO reads it, and the move after a change of
    frame (G92, G43, another system) is drawn from there to its own end."""
    present = np.flatnonzero(np.bincount(move_frames, minlength=len(frames))).tolist()   # O(n), no sort
    used = [f for f in present if not frames[f].is_identity]
    if not used:
        return pl
    drawn = pl.points if own else pl.points.astype(float, copy=True)
    if len({frames[f] for f in present}) == 1:          # one frame throughout (given again)
        frames[used[0]].to_program_in_place(drawn)
    else:
        if isinstance(pl.move_index, JointMoves):
            of_point = move_frames[np.maximum(np.arange(len(drawn)) - 1, 0)]
        else:
            of_point = move_frames[pl.move_index]
        for f in used:
            at = of_point == f
            part = drawn[at]
            frames[f].to_program_in_place(part)
            drawn[at] = part
    return pl if own else Polylines(drawn, pl.connect, pl.move_index, pl.count)


def joined_runs(pl: Polylines) -> Polylines:
    """Runs that start where the run before them ends, as one run (lines and rapids are drawn
    as point pairs: a chain of moves becomes one polyline, which ``thin`` can thin)."""
    joined = joined_rows(rows_of(pl))
    if joined.rows is None:
        return pl
    return take_points(joined, np.ones(len(joined), bool))


def joined_rows(pr: PointRows) -> PointRows:
    """``joined_runs`` of rows: the rows kept and their connect (``pr`` itself when no run
    joins another)."""
    n = len(pr)
    if n < 2:
        return pr
    again = np.empty(n - 1, bool)    # point i + 1 repeats point i, which ends a run
    for lo in range(0, n - 1, THIN_PIECE):
        hi = min(n - 1, lo + THIN_PIECE)
        pts = pr.points(lo, hi + 1)
        again[lo:hi] = ~pr.connect[lo:hi] & np.all(pts[1:] == pts[:-1], axis=1)
    if not again.any():
        return pr
    keep = np.ones(n, bool)
    keep[1:] = ~again
    connect = pr.connect.copy()
    connect[:-1] |= again  # the run's end now continues into the next run
    idx = nonzero_indices(keep)
    return PointRows(pr.source, idx if pr.rows is None else pr.rows[idx], connect[idx], pr.count)


def thin(pl: Polylines, cell_mm: float) -> Polylines:
    """The polylines at a level of detail: a point inside a drawn run (connected on both
    sides) that lies in the same cube of ``cell_mm`` as the point before it is left out, so
    the line drawn through the points kept never leaves the path by more than a cube's
    diagonal. The first and last point of every run stay. Drawn at a pixel per cube, it looks
    the same as the full path, with as many points as the path crosses cubes."""
    pl = joined_runs(pl)
    if len(pl.points) < 3 or not cell_mm > 0.0:
        return pl
    return take_points(pl, thin_masks(pl, cell_mm, 1)[0])


def thin_masks(pl: Polylines | PointRows, cell_mm: float, levels: int) -> list[np.ndarray]:
    """The points ``thin`` keeps of joined polylines ``pl`` (``joined_runs``) at cubes of
    ``cell_mm``, 4 ``cell_mm``, 16 ``cell_mm`` ... (``levels`` of them), as one mask a level
    (``thin_pieces``)."""
    pr = rows_of(pl) if isinstance(pl, Polylines) else pl
    keeps = [np.empty(len(pr), bool) for _ in range(levels)]
    for lo, hi, parts in thin_pieces(pr, cell_mm, levels):
        for keep, part in zip(keeps, parts):
            keep[lo:hi] = part
    return keeps


def thin_pieces(pr: PointRows, cell_mm: float,
                levels: int) -> Iterator[tuple[int, int, list[np.ndarray]]]:
    """``thin_masks`` a piece at a time: (lo, hi, the masks of points lo .. hi - 1 a level),
    pieces in order, every point once. Cubes of 4 c are made of whole cubes of c, so thinning
    the thinned copy at 4 c keeps what thinning the whole at 4 c keeps: each level is taken
    from the whole, none made to make the next; and no level's mask of the whole path is
    held (7 levels of 10,000,000 points were 70 MB, the cube numbers per axis 250 MB)."""
    connect = pr.connect
    n = len(pr)
    if n < 3:
        yield 0, n, [np.ones(n, bool) for _ in range(levels)]
        return
    yield 0, 1, [np.ones(1, bool) for _ in range(levels)]  # a run's ends stay
    for lo in range(1, n - 1, THIN_PIECE):
        hi = min(lo + THIN_PIECE, n - 1)          # points lo .. hi - 1, each with the one before
        inner = connect[lo - 1:hi - 1] & connect[lo:hi]
        pts = pr.points(lo - 1, hi)
        cubes = [np.floor(pts[:, k] / cell_mm) for k in range(pts.shape[1])]
        del pts
        parts = []
        for level in range(levels):
            same = inner.copy()               # point i lies in the cube of point i - 1
            for c in cubes:
                c = np.floor(c / 4.0 ** level) if level else c
                same &= c[1:] == c[:-1]
            parts.append(~same)
        yield lo, hi, parts
    yield n - 1, n, [np.ones(1, bool) for _ in range(levels)]


def thin_copies(pr: PointRows, cell_mm: float, levels: int, wanted: Callable[[list[int]], list[int]],
                origin: np.ndarray | None = None) -> dict[int, Polylines]:
    """The thinned copies of joined polylines ``pr`` at the levels ``wanted`` chooses from the
    count of points each level keeps, made in two passes a piece at a time (the count, then
    the copies): only the copies are held whole."""
    counts = [0] * levels
    for _lo, _hi, parts in thin_pieces(pr, cell_mm, levels):
        for level, part in enumerate(parts):
            counts[level] += int(np.count_nonzero(part))
    chosen = wanted(counts)
    if not chosen:
        return {}
    source = pr.source
    dtype = source.points.dtype if origin is None else np.float32
    outs = {level: (np.empty((counts[level], source.points.shape[1]), dtype), np.empty(counts[level], bool),
                    np.empty(counts[level], source.move_index.dtype)) for level in chosen}
    filled = dict.fromkeys(chosen, 0)
    for lo, _hi, parts in thin_pieces(pr, cell_mm, max(chosen) + 1):
        for level in chosen:
            idx = lo + np.flatnonzero(parts[level])
            k, m = filled[level], len(idx)
            pts, mi = pr.take(idx)
            out_pts, out_con, out_mi = outs[level]
            out_pts[k:k + m] = pts if origin is None else pts - origin
            out_con[k:k + m], out_mi[k:k + m] = pr.connect[idx], mi
            filled[level] = k + m
    kept_origin = None if origin is None else np.asarray(origin, float).copy()
    return {level: Polylines(*outs[level], pr.count, kept_origin) for level in chosen}


def take_points(pl: Polylines | PointRows, keep: np.ndarray,
                origin: np.ndarray | None = None) -> Polylines:
    """The points of ``pl`` where ``keep``, gathered a piece at a time; with ``origin``, as
    4-byte floats from there (``Polylines.origin``)."""
    pr = rows_of(pl) if isinstance(pl, Polylines) else pl
    kept = int(np.count_nonzero(keep))
    source = pr.source
    dtype = source.points.dtype if origin is None else np.float32
    out_pts = np.empty((kept, source.points.shape[1]), dtype)
    out_con = np.empty(kept, bool)
    out_mi = np.empty(kept, source.move_index.dtype)
    k = 0
    for lo in range(0, len(keep), THIN_PIECE):
        idx = lo + np.flatnonzero(keep[lo:lo + THIN_PIECE])
        m = len(idx)
        pts, out_mi[k:k + m] = pr.take(idx)
        out_pts[k:k + m] = pts if origin is None else pts - origin
        out_con[k:k + m] = pr.connect[idx]
        k += m
    return Polylines(out_pts, out_con, out_mi, pr.count,
                     None if origin is None else np.asarray(origin, float).copy())


def nearest_projected(path: ToolPath, px: np.ndarray, py: np.ndarray, x: float,
                      y: float) -> tuple[int, float]:
    """Move index nearest to (x, y) where ``px, py`` are the drawn coordinates of every point
    (any projection: a plane or the 3-D view), and its distance (-1 if none)."""
    pl = path.all
    return nearest_segment(px, py, pl.connect, pl.move_index, x, y)


def nearest_segment(px: np.ndarray, py: np.ndarray, connect: np.ndarray, move_index: np.ndarray, x: float,
                    y: float) -> tuple[int, float]:
    """Move index of the drawn segment (points ``px, py``, ``connect``, the move of each point)
    nearest to (x, y), and its distance (-1 if none)."""
    if len(px) < 2:
        return -1, math.inf
    seg = np.flatnonzero(connect[:-1])
    ax, ay, bx, by = px[seg], py[seg], px[seg + 1], py[seg + 1]
    dx, dy = bx - ax, by - ay
    den = dx * dx + dy * dy
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.where(den > 0, ((x - ax) * dx + (y - ay) * dy) / den, 0.0)
    t = np.clip(t, 0.0, 1.0)
    d2 = (ax + t * dx - x) ** 2 + (ay + t * dy - y) ** 2
    if len(d2) == 0:
        return -1, math.inf
    k = int(np.argmin(d2))
    return int(move_index[seg[k]]), float(math.sqrt(d2[k]))
