"""Where each line of a program's text starts: the index a view over the text reads lines by.

A program of 10,000,000 lines is a 250 MB text. Put into a text widget it takes gigabytes
and tens of seconds; a view that finds line k as ``text[index[k]:index[k + 1]]`` needs only
this index next to the text the loader holds anyway (``LineIndex``: every 64th line start, the
others found from there). Made with NumPy over the UTF-8 bytes, a piece at a time (the
temporaries stay a few megabytes); no Qt.
"""

from __future__ import annotations

import numpy as np

__all__ = ["LineIndex", "line_text"]

_PIECE = 1 << 22  # characters examined at a time


def _piece_starts(text: str, lo: int) -> np.ndarray:
    """Offsets (in characters) of the lines that start after a newline in ``text[lo:lo +
    _PIECE]``, int64."""
    piece = text[lo: lo + _PIECE]
    data = piece.encode("utf-8", "surrogatepass")
    buf = np.frombuffer(data, dtype=np.uint8)
    ends = np.flatnonzero(buf == 10)
    if len(data) != len(piece):  # not ASCII: bytes that start no character do not count
        ends -= np.cumsum((buf & 0xC0) == 0x80)[ends]
    return ends + (lo + 1)


class LineIndex:
    """Where each line of a text starts (lines end at "\n", a "\r" before it staying in the
    line; a text ending with "\n" has an empty last line), kept every ``STRIDE``-th line: the
    lines between are found by looking for their newlines from there (a few dozen short
    searches; the lines painted one after another each take one). 10,000,000 lines in 1.3 MB
    instead of 40. Read like an array: ``len`` is the lines + 1, ``index[k]`` where line k
    (0-based) starts."""

    STRIDE = 64

    def __init__(self, text: str) -> None:
        self._text = text
        stride = self.STRIDE
        marks = [np.zeros(1, np.int64)]
        count = 1                   # lines found so far (the first starts at 0)
        widest, prev = 0, 0         # the longest line (with its newline), the last start seen
        for lo in range(0, len(text), _PIECE):
            starts = _piece_starts(text, lo)
            if len(starts):
                widest = max(widest, int(starts[0] - prev), int(np.diff(starts).max(initial=0)))
                prev = int(starts[-1])
                # line k starts at starts[k - count]: keep the lines k that are multiples of stride
                first = -count % stride
                marks.append(starts[first::stride])
                count += len(starts)
        self._marks = np.concatenate(marks)
        self._lines = count
        self.widest = max(widest, len(text) - prev)  # characters of the longest line
        self._last = (0, 0)          # the last line looked up and where it starts

    def __len__(self) -> int:
        return self._lines + 1

    def __getitem__(self, k: int) -> int:
        """Where line ``k`` starts (0 <= k <= lines; ``k == lines``: the text's end)."""
        k = int(k)
        if not 0 <= k <= self._lines:
            raise IndexError(f"line {k} of {self._lines}")
        if k == self._lines:
            return len(self._text)
        last_k, pos = self._last
        if not (k >= last_k and k // self.STRIDE == last_k // self.STRIDE):
            last_k, pos = k - k % self.STRIDE, int(self._marks[k // self.STRIDE])
        find = self._text.find
        for _ in range(k - last_k):
            pos = find("\n", pos) + 1
        self._last = (k, pos)
        return pos

    def line_number(self, offset: int) -> int:
        """The 1-based line holding character ``offset``."""
        j = int(np.searchsorted(self._marks, offset, side="right")) - 1
        return j * self.STRIDE + self._text.count("\n", int(self._marks[j]), offset) + 1


def line_text(text: str, starts: np.ndarray | LineIndex, index: int) -> str:
    """Line ``index`` (0-based) without its end of line."""
    line = text[int(starts[index]): int(starts[index + 1])]
    if line.endswith("\n"):
        line = line[:-1]
    return line[:-1] if line.endswith("\r") else line
