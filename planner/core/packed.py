"""Float columns of a program's moves kept smaller than one float a move, exactly.

A CAM program of 10,000,000 lines keeps 80 MB for each float a move holds. Two of them need
far less:

- the feed changes at a few lines of a CAM program: ``RunColumn`` keeps where each run of
  equal values starts and its value;
- the length of a straight move is the distance between its end points: ``DerivedLength``
  keeps only the moves whose length is not that (arcs, helices, blends, rotary moves), by row.

Both give back the very values they were made from (a test compares them bit for bit), and
fall back to a plain array (``DenseColumn``) when packing would not pay. Each is a view: a
slice shares its data. A column is made a piece at a time (``ColumnPacker``), as the
interpreter's moves are copied out of their chunks, so that the whole column is never held as
an array on the way.
"""

from __future__ import annotations

import bisect
import math
from typing import Protocol

import numpy as np

__all__ = ["ColumnPacker", "DenseColumn", "DerivedLength", "FloatColumn", "RunColumn", "length_exceptions",
           "straight_lengths"]

_PIECE_ROWS = 1 << 16  # rows computed at a time: the temporaries stay a few megabytes


class FloatColumn(Protocol):
    """A column of ``len`` float values, as a view of shared data."""

    def __len__(self) -> int: ...

    def array(self) -> np.ndarray:
        """The values as a new float64 array."""
        ...

    def at(self, i: int) -> float:
        """Value ``i``."""
        ...

    def slice(self, a: int, b: int) -> FloatColumn:
        """Values ``a .. b - 1`` (0 <= a <= b <= len), sharing this column's data."""
        ...

    @property
    def nbytes(self) -> int:
        """Bytes of the data this column holds of its own (not the positions it reads)."""
        ...


class DenseColumn:
    """A plain array of values."""

    __slots__ = ("values",)

    def __init__(self, values: np.ndarray) -> None:
        self.values = values

    def __len__(self) -> int:
        return int(self.values.shape[0])

    def array(self) -> np.ndarray:
        return self.values.copy()

    def at(self, i: int) -> float:
        return float(self.values[i])

    def slice(self, a: int, b: int) -> DenseColumn:
        return DenseColumn(self.values[a:b])

    @property
    def nbytes(self) -> int:
        return int(self.values.nbytes)


class RunColumn:
    """Runs of equal values: ``starts[k]`` is the row where run k starts (``starts[0]`` is
    0), ``values[k]`` its value; rows ``off .. off + n - 1`` of it."""

    __slots__ = ("starts", "values", "off", "n")

    def __init__(self, starts: np.ndarray, values: np.ndarray, off: int, n: int) -> None:
        self.starts, self.values, self.off, self.n = starts, values, off, n

    def __len__(self) -> int:
        return self.n

    def array(self) -> np.ndarray:
        if self.n == 0:
            return np.zeros(0)
        lo, hi = self.off, self.off + self.n
        a = int(np.searchsorted(self.starts, lo, "right")) - 1
        b = int(np.searchsorted(self.starts, hi, "left"))
        edges = self.starts[a:b + 1].copy() if b < len(self.starts) else np.append(self.starts[a:b], hi)
        edges[0], edges[-1] = lo, hi
        return np.repeat(self.values[a:b], np.diff(edges))

    def at(self, i: int) -> float:
        return float(self.values[bisect.bisect_right(self.starts, self.off + i) - 1])

    def slice(self, a: int, b: int) -> RunColumn:
        return RunColumn(self.starts, self.values, self.off + a, b - a)

    @property
    def nbytes(self) -> int:
        return int(self.starts.nbytes + self.values.nbytes)


def straight_lengths(positions: np.ndarray) -> np.ndarray:
    """The distance between consecutive rows of ``positions`` ((m + 1, d) -> (m,)), every
    axis counted, each row alone (the same value whatever rows are computed with it)."""
    delta = positions[1:] - positions[:-1]
    total = delta[:, 0] * delta[:, 0]
    for k in range(1, delta.shape[1]):
        total += delta[:, k] * delta[:, k]
    return np.sqrt(total)


def length_exceptions(positions: np.ndarray, values: np.ndarray) -> np.ndarray:
    """The rows of ``values`` ((m,)) that are not the distance between consecutive rows of
    ``positions`` ((m + 1, d)): what a ``DerivedLength`` keeps."""
    return np.flatnonzero(straight_lengths(positions) != values)


class DerivedLength:
    """Lengths that are the distance between the end points (``straight_lengths`` of the
    positions) but at ``rows`` (ascending), where they are ``values``; rows ``off .. off + n
    - 1`` of it. ``positions`` are the store's own, row r + 1 the end of move r."""

    __slots__ = ("positions", "rows", "values", "off", "n")

    def __init__(self, positions: np.ndarray, rows: np.ndarray, values: np.ndarray, off: int,
                 n: int) -> None:
        self.positions, self.rows, self.values, self.off, self.n = positions, rows, values, off, n

    def __len__(self) -> int:
        return self.n

    def array(self) -> np.ndarray:
        lo, hi = self.off, self.off + self.n
        out = np.empty(self.n)
        for a in range(lo, hi, _PIECE_ROWS):
            b = min(hi, a + _PIECE_ROWS)
            out[a - lo:b - lo] = straight_lengths(self.positions[a:b + 1])
        i, j = np.searchsorted(self.rows, lo), np.searchsorted(self.rows, hi)
        out[self.rows[i:j] - lo] = self.values[i:j]
        return out

    def at(self, i: int) -> float:
        r = self.off + i
        k = bisect.bisect_left(self.rows, r) if len(self.rows) else 0
        if k < len(self.rows) and self.rows[k] == r:
            return float(self.values[k])
        # the same operations as ``straight_lengths`` in the same order, each rounded alike,
        # on Python floats: one move's length in a microsecond, not ten
        a, b = self.positions[r].tolist(), self.positions[r + 1].tolist()
        total = (b[0] - a[0]) * (b[0] - a[0])
        for k in range(1, len(a)):
            total += (b[k] - a[k]) * (b[k] - a[k])
        return math.sqrt(total)

    def slice(self, a: int, b: int) -> DerivedLength:
        return DerivedLength(self.positions, self.rows, self.values, self.off + a, b - a)

    @property
    def nbytes(self) -> int:
        return int(self.rows.nbytes + self.values.nbytes)


# packing pays while a run (16 bytes) stands for 4 rows (32 bytes as an array) and more
_MAX_RUN_SHARE = 0.25
_MAX_EXCEPTION_SHARE = 0.25


class ColumnPacker:
    """A column of ``n`` values given a piece at a time, in order (``add``), packed as runs
    (``positions`` None) or as lengths derived from ``positions`` ((n + 1, d), each row filled
    before the moves ending there are given). Falls back to an array as soon as the packing
    holds more than a quarter of the rows."""

    def __init__(self, n: int, positions: np.ndarray | None = None) -> None:
        if positions is not None and positions.shape[0] != n + 1:
            raise ValueError(f"{n} moves need {n + 1} positions, got {positions.shape[0]}")
        self.n, self.positions = n, positions
        self._rows: list[np.ndarray] = []
        self._values: list[np.ndarray] = []
        self._count = 0          # rows or runs kept so far
        self._dense: np.ndarray | None = None
        self._done = 0           # rows given
        self._last = 0           # the bits of the last row given (runs)

    def add(self, values: np.ndarray) -> None:
        """The next ``len(values)`` rows."""
        m = int(values.shape[0])
        lo = self._done
        self._done += m
        if self._dense is not None:
            self._dense[lo:lo + m] = values
            return
        if m == 0:
            return
        if self.positions is None:
            # runs of the same bits (-0.0 is not 0.0, a NaN is one value)
            bits = np.ascontiguousarray(values, np.float64).view(np.int64)
            change = np.flatnonzero(bits[1:] != bits[:-1]) + 1
            first = lo == 0 or int(bits[0]) != self._last
            rows = np.concatenate(([0], change)) if first else change
            self._last = int(bits[-1])
        else:
            assert self.positions is not None
            rows = length_exceptions(self.positions[lo:lo + m + 1], values)
        self._rows.append(rows + lo)
        self._values.append(values[rows])
        self._count += len(rows)
        if self._count > self._limit():
            self._to_dense(lo + m)

    def _limit(self) -> float:
        share = _MAX_RUN_SHARE if self.positions is None else _MAX_EXCEPTION_SHARE
        return max(64.0, share * self.n)

    def _to_dense(self, upto: int) -> None:
        dense = np.empty(self.n)
        dense[:upto] = self._column().slice(0, upto).array()
        self._dense, self._rows, self._values = dense, [], []

    def _column(self) -> FloatColumn:
        rows = np.concatenate(self._rows) if self._rows else np.zeros(0, np.int64)
        values = np.concatenate(self._values) if self._values else np.zeros(0)
        if self.positions is None:
            return RunColumn(rows, values, 0, self._done)
        return DerivedLength(self.positions, rows, values, 0, self._done)

    def column(self) -> FloatColumn:
        """The column once every row is given."""
        if self._done != self.n:
            raise ValueError(f"{self._done} of {self.n} rows given")
        if self._dense is not None:
            return DenseColumn(self._dense)
        return self._column()
