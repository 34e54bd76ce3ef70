"""The moves of a program as columns: about 50 bytes a move instead of a Python object each.

A CAM finishing program has millions of short G01 lines; one ``Move`` object per line costs
about 700 bytes and a microsecond to make. ``MoveStore`` keeps the joint positions as one
(n + 1, d) array (move i runs from row i to row i + 1, as a path does) and line, kind, feed,
length and exact stop as one column each; the few arcs and corner blends sit in dictionaries
by move index. It is a read-only ``Sequence[Move]``: indexing and iteration make ``Move``
objects on demand (equal, field for field, to the ones the interpreter makes), and a
slice is a view that keeps the moves' own indices, as a slice of a tuple of moves does.
Code that needs speed reads the columns (``columns``) instead.

``MoveBuffer`` is where the interpreter writes them: one move at a time into short lists,
or a block of moves at a time as arrays (the vectorised reading of plain coordinate lines),
packed into array chunks as it goes so that its memory is the columns' too.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any, overload

import numpy as np

from planner.core.heap import trim_heap
from planner.core.packed import (
    ColumnPacker,
    DenseColumn,
    DerivedLength,
    FloatColumn,
    RunColumn,
    length_exceptions,
)
from planner.core.program import Arc, Move, MoveKind, _make_move

__all__ = ["MoveBuffer", "MoveColumns", "MoveStore"]

_KINDS = tuple(MoveKind)


@dataclass(frozen=True, slots=True, eq=False)
class MoveColumns:
    """Rows ``index[0] ..`` of a store as arrays (read-only views, no copies)."""

    first: int  # global index of row 0
    start: np.ndarray  # (n, d)
    end: np.ndarray  # (n, d)
    line: np.ndarray  # (n,) int32
    kind: np.ndarray  # (n,) int8
    feed_column: FloatColumn  # mm/s, inf for rapids (packed: ``feed`` makes the array)
    length_column: FloatColumn  # mm (packed: ``length`` makes the array)
    exact_stop: np.ndarray  # (n,) bool
    arc_rows: np.ndarray  # local rows that are arcs, ascending
    arcs: tuple[Arc, ...]  # their arcs
    blend_rows: np.ndarray  # local rows that are corner blends, ascending
    blends: tuple[Any, ...]  # their planner.core.curves.Blend

    @property
    def feed(self) -> np.ndarray:
        """(n,) mm/s, inf for rapids: a new array at each call."""
        return self.feed_column.array()

    @property
    def length(self) -> np.ndarray:
        """(n,) mm: a new array at each call."""
        return self.length_column.array()


def _readonly(a: np.ndarray) -> np.ndarray:
    a.setflags(write=False)
    return a


class MoveStore(Sequence[Move]):
    """Moves ``base .. base + n - 1`` over shared columns (see the module docstring)."""

    __slots__ = ("_pos", "_line", "_kind", "_feed", "_length", "_stop", "_arcs", "_arc_keys",
                 "_blends", "_blend_keys", "_base", "_n")

    def __init__(self, positions: np.ndarray, line: np.ndarray, kind: np.ndarray,
                 feed: np.ndarray | FloatColumn, length: np.ndarray | FloatColumn, exact_stop: np.ndarray,
                 arcs: dict[int, Arc] | None = None,
                 blends: dict[int, Any] | None = None, base: int = 0) -> None:
        n = int(line.shape[0])
        if positions.shape[0] != n + 1:
            raise ValueError(f"{n} moves need {n + 1} positions, got {positions.shape[0]}")
        self._pos = _readonly(positions)
        self._line = _readonly(line)
        self._kind = _readonly(kind)
        self._feed = DenseColumn(_readonly(feed)) if isinstance(feed, np.ndarray) else feed
        self._length = DenseColumn(_readonly(length)) if isinstance(length, np.ndarray) else length
        self._stop = _readonly(exact_stop)
        self._arcs = arcs or {}
        self._arc_keys = np.array(sorted(self._arcs), dtype=np.int64)
        self._blends = blends or {}
        self._blend_keys = np.array(sorted(self._blends), dtype=np.int64)
        self._base = base
        self._n = n

    @staticmethod
    def from_moves(moves: Sequence[Move], start_position: np.ndarray) -> MoveStore:
        """A store of moves made one by one (each move starting where the one before ends)."""
        n = len(moves)
        d = int(np.asarray(start_position).shape[0])
        pos = np.empty((n + 1, d))
        pos[0] = moves[0].start if n else start_position
        if n:
            pos[1:] = [m.end for m in moves]
        return MoveStore(
            pos,
            np.fromiter((m.line for m in moves), np.int32, n),
            np.fromiter((int(m.kind) for m in moves), np.int8, n),
            np.fromiter((m.feed_mm_s for m in moves), float, n),
            np.fromiter((m.length_mm for m in moves), float, n),
            np.fromiter((m.exact_stop for m in moves), bool, n),
            {i: m.arc for i, m in enumerate(moves) if m.arc is not None},
            {i: m.blend for i, m in enumerate(moves) if m.blend is not None},
        )

    def __len__(self) -> int:
        return self._n

    def _view(self, a: int, b: int) -> MoveStore:
        view = object.__new__(MoveStore)
        view._pos = self._pos[a:b + 1]
        view._line = self._line[a:b]
        view._kind = self._kind[a:b]
        view._feed = self._feed.slice(a, b)
        view._length = self._length.slice(a, b)
        view._stop = self._stop[a:b]
        view._arcs, view._arc_keys = self._arcs, self._arc_keys
        view._blends, view._blend_keys = self._blends, self._blend_keys
        view._base = self._base + a
        view._n = max(0, b - a)
        return view

    @overload
    def __getitem__(self, i: int) -> Move: ...

    @overload
    def __getitem__(self, i: slice) -> MoveStore: ...

    def __getitem__(self, i: int | slice) -> Move | MoveStore:
        if isinstance(i, slice):
            a, b, step = i.indices(self._n)
            if step != 1:
                raise ValueError("a slice of moves takes every move (step 1)")
            return self._view(a, max(a, b))
        n = self._n
        if i < 0:
            i += n
        if not 0 <= i < n:
            raise IndexError("move index out of range")
        return self._make(i)

    def _make(self, i: int) -> Move:
        return self._move(i, int(self._line[i]), int(self._kind[i]), self._feed.at(i),
                          self._length.at(i), bool(self._stop[i]))

    def _move(self, i: int, line: int, kind: int, feed: float, length: float, stop: bool) -> Move:
        """Move ``i`` of this store from its column values (Python scalars)."""
        g = self._base + i
        m = _make_move(g, line, _KINDS[kind], self._pos[i], self._pos[i + 1], feed, length, self._arcs.get(g),
                       stop)
        if self._blends:
            blend = self._blends.get(g)
            if blend is not None:
                object.__setattr__(m, "blend", blend)
        return m

    def __iter__(self) -> Iterator[Move]:
        move = self._move
        for lo in range(0, self._n, _ITER_ROWS):  # the packed columns made a piece at a time
            hi = min(self._n, lo + _ITER_ROWS)
            rows = zip(self._line[lo:hi].tolist(), self._kind[lo:hi].tolist(),
                       self._feed.slice(lo, hi).array().tolist(),
                       self._length.slice(lo, hi).array().tolist(), self._stop[lo:hi].tolist())
            for i, values in enumerate(rows, lo):
                yield move(i, *values)

    def __repr__(self) -> str:
        return f"MoveStore({self._n} moves from {self._base})"

    def numbered_from_zero(self) -> MoveStore:
        """These moves as a store of their own, its moves numbered from 0 (a piece of a program
        that runs as a program: what follows a probe). The columns are shared, the arcs and
        blends renumbered; no Move object is made."""
        lo, hi = self._base, self._base + self._n
        store = self._view(0, self._n)
        store._arcs = {k - lo: v for k, v in self._arcs.items() if lo <= k < hi}
        store._arc_keys = np.array(sorted(store._arcs), dtype=np.int64)
        store._blends = {k - lo: v for k, v in self._blends.items() if lo <= k < hi}
        store._blend_keys = np.array(sorted(store._blends), dtype=np.int64)
        store._base = 0
        return store

    def with_exact_stops(self) -> MoveStore:
        """The same moves, each ending at rest (single block's plan), over the same columns
        but that one."""
        store = self._view(0, self._n)
        store._stop = _readonly(np.ones(self._n, bool))
        return store

    @property
    def nbytes(self) -> int:
        """Bytes of the columns this store reads (a slice: those of the whole it views)."""
        arrays = (self._pos, self._line, self._kind, self._stop)
        return sum(int((a.base if a.base is not None else a).nbytes) for a in arrays) + \
            self._feed.nbytes + self._length.nbytes

    @property
    def positions(self) -> np.ndarray:
        """(n + 1, d): where each move starts, then where the last one ends."""
        return self._pos

    def columns(self) -> MoveColumns:
        """This store's rows as arrays (no Move objects)."""
        lo, hi = self._base, self._base + self._n
        ka = self._arc_keys[np.searchsorted(self._arc_keys, lo):np.searchsorted(self._arc_keys, hi)]
        kb = self._blend_keys[np.searchsorted(self._blend_keys, lo):np.searchsorted(self._blend_keys, hi)]
        return MoveColumns(lo, self._pos[:-1], self._pos[1:], self._line, self._kind, self._feed,
                           self._length, self._stop, ka - lo, tuple(self._arcs[k] for k in ka.tolist()),
                           kb - lo, tuple(self._blends[k] for k in kb.tolist()))


_ITER_ROWS = 1 << 14   # moves whose column values are made at once when iterating
_TRIM_MOVES = 1 << 20   # moves copied into the columns between two trims of the heap


@dataclass(frozen=True, slots=True, eq=False)
class _Sparse:
    """A chunk's lengths kept as the rows where a length is not the distance between the ends
    (arcs, helices, rotary moves) and their values, as the store's column keeps them
    (``DerivedLength``); the feeds are kept as runs (``RunColumn``). A CAM raster's chunks then
    hold a few bytes for both instead of 16 a move: 160 MB less while a 10,000,000-line program
    is read."""

    rows: np.ndarray
    values: np.ndarray


# packing a chunk's lengths pays while a kept row (16 bytes) stands for 4 rows (32 bytes)
_SPARSE_SHARE = 0.25


def _sparse_feed(feed: np.ndarray) -> RunColumn | np.ndarray:
    packer = ColumnPacker(int(feed.shape[0]))    # runs as the store keeps them, bit for bit
    packer.add(feed)
    runs = packer.column()
    return runs if isinstance(runs, RunColumn) else feed


def _dense_feed(feed: RunColumn | np.ndarray) -> np.ndarray:
    return feed.array() if isinstance(feed, RunColumn) else feed


def _sparse_length(length: np.ndarray, ends: np.ndarray, before: np.ndarray) -> _Sparse | np.ndarray:
    rows = length_exceptions(np.vstack((before, ends)), length)
    return _Sparse(rows, length[rows]) if len(rows) <= _SPARSE_SHARE * length.shape[0] else length


def _dense_length(length: _Sparse | np.ndarray, ends: np.ndarray, before: np.ndarray) -> np.ndarray:
    if isinstance(length, np.ndarray):
        return length
    m = int(ends.shape[0])
    return DerivedLength(np.vstack((before, ends)), length.rows, length.values, 0, m).array()


class MoveBuffer:
    """Moves as the interpreter makes them, packed into array chunks as it goes.

    A chunk is (ends, line, kind, feed, length, stop, before): ``before`` is where its first
    move starts (a copy: compensation may move the end of the chunk before it later, and the
    lengths kept are those the moves were made with). Every chunk but the last keeps its feeds
    as runs (``RunColumn``) and its lengths as exceptions (``_Sparse``) where that pays; the last
    stays plain, as compensation changes the moves it has just made."""

    CHUNK = 4096  # moves kept as Python lists before they are packed

    def __init__(self, start: Sequence[float]) -> None:
        self.start = [float(v) for v in start]
        self._chunks: list[tuple[Any, ...]] = []
        self._packed = 0
        self._ends: list[list[float]] = []
        self._recs: list[tuple[int, int, float, float, bool]] = []
        self.arcs: dict[int, Arc] = {}

    def __len__(self) -> int:
        return self._packed + len(self._ends)

    def append(self, target: list[float], line: int, kind: int, feed: float, length: float,
               arc: Arc | None, exact_stop: bool) -> None:
        ends = self._ends
        if arc is not None:
            self.arcs[self._packed + len(ends)] = arc
        ends.append(target)
        self._recs.append((line, kind, feed, length, exact_stop))
        if len(ends) >= self.CHUNK:
            self._pack()

    def extend(self, ends: np.ndarray, line: np.ndarray, kind: np.ndarray, feed: np.ndarray,
               length: np.ndarray, exact_stop: bool) -> None:
        """A block of straight moves (rapids and lines, no arcs) at once."""
        self._pack()
        k = int(ends.shape[0])
        if k:
            self._add_chunk((np.asarray(ends, float), line.astype(np.int32, copy=False),
                             kind.astype(np.int8, copy=False), np.asarray(feed, float),
                             np.asarray(length, float), np.full(k, exact_stop, bool)))

    def _pack(self) -> None:
        if not self._ends:
            return
        line, kind, feed, length, stop = zip(*self._recs)
        self._add_chunk((np.array(self._ends, float).reshape(len(self._ends), len(self.start)),
                         np.array(line, np.int32), np.array(kind, np.int8), np.array(feed, float),
                         np.array(length, float), np.array(stop, bool)))
        self._ends, self._recs = [], []

    def _add_chunk(self, chunk: tuple[np.ndarray, ...]) -> None:
        before = self._chunks[-1][0][-1].copy() if self._chunks else np.array(self.start, float)
        if self._chunks:   # the last chunk so far is done with: its feed and length made sparse
            ends, line, kind, feed, length, stop, first = self._chunks[-1]
            self._chunks[-1] = (ends, line, kind, _sparse_feed(feed), _sparse_length(length, ends, first),
                                stop, first)
        self._chunks.append((*chunk, before))
        self._packed += int(chunk[1].shape[0])

    def _plain(self, k: int) -> tuple[Any, ...]:
        """Chunk ``k`` with its feed and length as arrays (kept so: it is being changed or read
        row by row, which only compensation does, on the moves it has just made)."""
        ends, line, kind, feed, length, stop, before = self._chunks[k]
        if isinstance(feed, RunColumn) or isinstance(length, _Sparse):
            self._chunks[k] = (ends, line, kind, _dense_feed(feed), _dense_length(length, ends, before),
                               stop, before)
        return self._chunks[k]

    def _locate(self, i: int) -> tuple[tuple[Any, ...], int]:
        """The packed chunk holding move ``i`` (< the packed count), plain, and its row there."""
        first = 0
        for k, chunk in enumerate(self._chunks):
            m = chunk[1].shape[0]
            if i < first + m:
                return self._plain(k), i - first
            first += m
        raise IndexError(i)

    def end(self, i: int) -> list[float]:
        """Where move ``i`` ends."""
        if i >= self._packed:
            return self._ends[i - self._packed]
        chunk, row = self._locate(i)
        return chunk[0][row].tolist()

    def record(self, i: int) -> tuple[int, MoveKind, float, float, Arc | None, bool]:
        """(line, kind, feed, length, arc, exact stop) of move ``i``."""
        if i >= self._packed:
            line, kind, feed, length, stop = self._recs[i - self._packed]
        else:
            chunk, row = self._locate(i)
            line, kind, feed, length, stop = (c[row].item() for c in chunk[1:6])
        return line, _KINDS[kind], feed, length, self.arcs.get(i), stop

    def replace(self, i: int, end: list[float], length: float, arc: Arc | None) -> None:
        """Move ``i`` ends elsewhere (cutter compensation moved its end point)."""
        if arc is None:
            self.arcs.pop(i, None)
        else:
            self.arcs[i] = arc
        if i >= self._packed:
            k = i - self._packed
            self._ends[k] = end
            line, kind, feed, _, stop = self._recs[k]
            self._recs[k] = (line, kind, feed, length, stop)
        else:
            chunk, row = self._locate(i)
            chunk[0][row] = end
            chunk[4][row] = length

    def last_end(self) -> list[float]:
        """Where the last move ends (the start when there is none)."""
        if self._ends:
            return self._ends[-1]
        if self._chunks:
            return self._chunks[-1][0][-1].tolist()
        return list(self.start)

    def delete(self, i: int) -> None:
        """Remove move ``i``; the moves after it move down one."""
        if i >= self._packed:
            del self._ends[i - self._packed]
            del self._recs[i - self._packed]
        else:
            cols = self._columns()
            self._packed -= 1
            # no chunk of no moves: where the last move ends is then the start
            self._chunks = [(*(np.delete(c, i, axis=0) for c in cols), np.array(self.start, float))
                            ] if self._packed else []
        self.arcs = {(k - 1 if k > i else k): a for k, a in self.arcs.items() if k != i}

    def _columns(self) -> tuple[np.ndarray, ...]:
        self._pack()
        d = len(self.start)
        if not self._chunks:
            return (np.zeros((0, d)), np.zeros(0, np.int32), np.zeros(0, np.int8), np.zeros(0),
                    np.zeros(0), np.zeros(0, bool))
        plain = [self._plain(k)[:6] for k in range(len(self._chunks))]
        if len(plain) == 1:
            return plain[0]
        return tuple(np.concatenate(parts) for parts in zip(*plain))

    def store(self) -> MoveStore:
        """The moves as a store (the buffer is emptied). Each chunk is copied into the
        columns and let go at once, so that the moves are never held twice."""
        self._pack()
        chunks, self._chunks = self._chunks, []
        chunks.reverse()  # popped from the end, first chunk first
        n = sum(c[1].shape[0] for c in chunks)
        pos = np.empty((n + 1, len(self.start)))
        pos[0] = self.start
        line, kind, stop = np.empty(n, np.int32), np.empty(n, np.int8), np.empty(n, bool)
        # feeds come in runs and lengths are the distance between the ends but for arcs: kept
        # packed (planner.core.packed), 160 MB less at 10,000,000 moves
        feed, length = ColumnPacker(n), ColumnPacker(n, pos)
        k = 0
        trimmed_at = 0
        while chunks:
            ends, c_line, c_kind, c_feed, c_length, c_stop, before = chunks.pop()
            m = c_line.shape[0]
            pos[1 + k:1 + k + m] = ends
            line[k:k + m] = c_line
            kind[k:k + m] = c_kind
            stop[k:k + m] = c_stop
            feed.add(_dense_feed(c_feed))
            length.add(_dense_length(c_length, ends, before))
            k += m
            del ends, c_line, c_kind, c_feed, c_length, c_stop, before
            if k - trimmed_at > _TRIM_MOVES:
                # the chunks copied are freed into the heap, where they stay beside the columns
                # made (300 MB twice at 10,000,000 moves): handed back as the copy goes
                trim_heap()
                trimmed_at = k
        self._packed = 0
        arcs, self.arcs = self.arcs, {}
        return MoveStore(pos, line, kind, feed.column(), length.column(), stop, arcs)
