"""Where each line of a program's text starts: the index a view over the text reads lines by.

A program of 10,000,000 lines is a 250 MB text. Put into a text widget it takes gigabytes
and tens of seconds; a view that finds line k as ``text[starts[k]:starts[k + 1]]`` needs only
this index (4 bytes a line) next to the text the loader holds anyway. Made with NumPy over the
UTF-8 bytes, a piece at a time (the temporaries stay a few megabytes); no Qt.
"""

from __future__ import annotations

import numpy as np

__all__ = ["line_starts", "line_text"]

_PIECE = 1 << 22  # characters examined at a time


def line_starts(text: str) -> np.ndarray:
    """Offsets (in characters) where the lines of ``text`` start, then ``len(text)``: n + 1
    values for n lines. Lines end at "\\n" (a "\\r" before it stays in the line); a text that
    ends with "\\n" has an empty last line, as an editor shows it. Made a piece of the text at
    a time: each NumPy pass holds the GIL (and the panel) a few milliseconds."""
    dtype = np.uint32 if len(text) < 2**32 - 1 else np.int64
    parts = [np.zeros(1, dtype=dtype)]
    for lo in range(0, len(text), _PIECE):
        piece = text[lo: lo + _PIECE]
        data = piece.encode("utf-8", "surrogatepass")
        buf = np.frombuffer(data, dtype=np.uint8)
        ends = np.flatnonzero(buf == 10)
        if len(data) != len(piece):  # not ASCII: bytes that start no character do not count
            ends -= np.cumsum((buf & 0xC0) == 0x80)[ends]
        parts.append((ends + (lo + 1)).astype(dtype))
    parts.append(np.array([len(text)], dtype=dtype))
    return np.concatenate(parts)


def line_text(text: str, starts: np.ndarray, index: int) -> str:
    """Line ``index`` (0-based) without its end of line."""
    line = text[int(starts[index]): int(starts[index + 1])]
    if line.endswith("\n"):
        line = line[:-1]
    return line[:-1] if line.endswith("\r") else line
