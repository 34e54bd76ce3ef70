"""A G-code program's text: read from its file (UTF-8, falling back to Latin-1; Windows line
ends and a byte-order mark taken off), searched and counted a piece at a time so that no one
call holds the GIL (and the panel's GUI thread) long, and the '%' lines that delimit it.
"""

from __future__ import annotations

import codecs
import io
import os
from typing import Any

from planner.core.errors import PlannerError
from planner.core.reading import PROGRAM, SILENT_PIPE_S, Bounded
from planner.gcode.lexer import LexError, compact, original_column

__all__ = ["MAX_PROGRAM_BYTES", "SILENT_PIPE_S", "compact_or_none", "contains", "count_lines", "decode_utf8",
           "open_program", "percent_line", "read_program", "read_program_bytes", "statement_col",
           "through_closing_percent"]

# bytes decoded at a time: a piece's decoding (3 ms for 4 MB) holds the GIL, which the GUI
# thread waits for at each of its calls into Qt while a file is read
DECODE_PIECE = 1 << 20

#: the largest program read, by default ([planner] max_program_mb): four times the 252 MB of
#: the 10,000,000-line programs the panel runs; a file or a device that goes on is refused
MAX_PROGRAM_BYTES = 1024 << 20


def open_program(path: str | os.PathLike[str], limit: int = MAX_PROGRAM_BYTES) -> io.BufferedReader:
    """A program's file for reading, bounded (``Bounded``). Raises PlannerError naming the
    file and why."""
    return io.BufferedReader(Bounded(path, limit, PROGRAM), buffer_size=DECODE_PIECE)


def statement_col(raw: str, index: int) -> int:
    return original_column(raw, index) if index else 1


def compact_or_none(raw: str) -> str | None:
    try:
        return compact(raw)
    except LexError:
        return None


def percent_line(s: str) -> bool:
    """A stripped line that is a '%' alone (a comment beside it allowed)."""
    return s[0] == "%" and (s == "%" or compact_or_none(s) == "%")


def through_closing_percent(lines: list[str]) -> int:
    """How many lines the program has: up to and with its closing '%' (the first '%' line after
    content or after an opening '%'), else all: LinuxCNC ignores what follows it, subroutines
    defined there included."""
    started = False
    for i, raw in enumerate(lines):
        s = raw.strip()
        if not s:
            continue
        if percent_line(s):
            if started:
                return i + 1
            started = True
        elif not started and compact_or_none(s) != "":
            started = True
    return len(lines)


def read_program_bytes(path: str | os.PathLike[str], limit: int = MAX_PROGRAM_BYTES
                       ) -> tuple[str | None, bytes | None]:
    """A G-code file as ``parse_program(None, ..., utf8=)`` reads it: (None, its bytes) when
    they are UTF-8, else (its Latin-1 text, None); at most ``limit`` bytes (``open_program``).
    Raises PlannerError naming the file and why."""
    with open_program(path, limit) as f:
        data = f.read()
    if data.isascii() or is_utf8(data):
        return None, data
    return data.decode("latin-1"), None


def is_utf8(data: bytes) -> bool:
    """Whether ``data`` decodes as UTF-8, a piece (cut after a newline) at a time."""
    view = memoryview(data)
    lo = 0
    try:
        while lo < len(data):
            hi = data.find(b"\n", min(lo + DECODE_PIECE, len(data)))
            hi = len(data) if hi < 0 else hi + 1
            str(view[lo:hi], "utf-8")
            lo = hi
    except UnicodeDecodeError:
        return False
    return True


def read_program(path: str | os.PathLike[str], limit: int = MAX_PROGRAM_BYTES) -> str:
    """A G-code file's text (UTF-8 without a byte-order mark, falling back to Latin-1) with
    Windows line ends made "\n", read and decoded a piece at a time: the file's bytes are
    never held whole beside the text (250 MB each at 10,000,000 lines), nor the text twice to
    change its line ends or drop the mark (the reader did that to a whole text), and no one
    decode holds the GIL long. At most ``limit`` bytes (``open_program``). Raises PlannerError
    naming the file and why."""
    with open_program(path, limit) as f:
        try:
            # "utf-8-sig": a byte-order mark (Windows editors put one before the first
            # line) is no part of the text, and the text is not copied to drop it
            return decoded(f, codecs.getincrementaldecoder("utf-8-sig")())
        except UnicodeDecodeError:
            if not f.seekable():
                raise PlannerError(f"{path}: not UTF-8, and a pipe cannot be read again as Latin-1") from None
            f.seek(0)
            return decoded(f, codecs.getincrementaldecoder("latin-1")())


def decoded(f: Any, decoder: codecs.IncrementalDecoder) -> str:
    """The rest of file ``f`` through ``decoder``, "\r\n" made "\n", a piece at a time."""
    pieces = []
    carry = ""           # a piece's last "\r": its "\n" may start the next piece
    while True:
        block = f.read(DECODE_PIECE)
        piece = carry + decoder.decode(block, final=not block)
        carry = "\r" if block and piece.endswith("\r") else ""
        if carry:
            piece = piece[:-1]
        # the search for two characters takes 3 ms a 4 MB piece, the one for "\r" alone 0.05 ms:
        # most programs have no Windows line end, and the GUI thread waits out each hold
        pieces.append(piece.replace("\r\n", "\n") if "\r" in piece else piece)
        if not block:
            break
    text = "".join(pieces)
    del pieces
    return text


def contains(text: Any, needle: Any, piece: int = 1 << 22) -> bool:
    """``needle in text``, a piece at a time: one search through a 250 MB program held the GIL,
    and with it the panel's GUI thread, for 0.18 s. A piece is first looked through for the
    needle's first character alone (a ``memchr``, ten times faster than the search for two):
    "\r\n" in a program of "\n" line ends took 3 ms a 4 MB piece, and the GUI thread, painting
    meanwhile, waited that long for the GIL at each of its hundreds of calls into Qt (a
    quarter of a second as a 10,000,000-line program was checked again)."""
    first, n, k = needle[:1], len(text), len(needle)
    for lo in range(0, n, piece):
        hi = min(n, lo + piece)
        at = text.find(first, lo, hi)
        if at >= 0 and text.find(needle, at, min(n, hi + k - 1)) >= 0:
            return True
    return False


def count_lines(text: Any, piece: int = 1 << 22) -> int:
    """The lines of ``text`` (str or bytes; none when empty), as an editor numbers them: a line
    end closes a line, and a last line without one counts too ("a\nb\n" and "a\nb" are two).
    Counted a piece at a time: one count through a 250 MB program held the GIL, and the panel's
    GUI thread, for 60 ms."""
    newline = b"\n" if isinstance(text, bytes) else "\n"
    count = sum(text.count(newline, lo, lo + piece) for lo in range(0, len(text), piece))
    return count + (0 if text[-1:] == newline else 1) if text else 0


def decode_utf8(data: bytes) -> str:
    """``data`` as ``read_program`` reads a UTF-8 file: without a byte-order mark, Windows
    line ends made "\n", decoded a piece at a time (one decode of a 250 MB program held the
    GIL, and with it the panel's GUI thread, for 0.12 s; changing the line ends of the whole
    text, 0.6 s and a second text)."""
    return decoded(io.BytesIO(data), codecs.getincrementaldecoder("utf-8-sig")())
