"""Reading the files the project is given, bounded: a G-code program, a machine
configuration, a tool table, an operator's script. Whatever the name points at (a file, a
FIFO with no writer, /dev/zero), a read ends within a size and a time, and says why when it
refuses.
"""

from __future__ import annotations

import io
import os
import select
import stat
import tomllib
from dataclasses import dataclass
from typing import Any

from planner.core.errors import PlannerError

__all__ = ["CONFIGURATION", "PROGRAM", "SCRIPT", "SILENT_PIPE_S", "TOOL_TABLE", "Bounded", "FileKind",
           "parse_toml", "read_text"]

#: a pipe or device that delivers nothing for this long is given up (a FIFO with no writer)
SILENT_PIPE_S = 10.0


@dataclass(frozen=True, slots=True)
class FileKind:
    """What a file read is to the reader, for its messages: ``what`` ("a program"), where its
    size bound is set ("[planner] max_program_mb", or ""), and what binary data is not ("a
    G-code program"; ``what`` when empty)."""

    what: str
    where: str = ""
    text: str = ""

    @property
    def not_text(self) -> str:
        return self.text or self.what


# what each kind of file is called in a message (module constants, so that the panel's catalogue
# gathers and translates them inside the messages that carry them)
A_PROGRAM = "a program"
A_GCODE_PROGRAM = "a G-code program"
A_CONFIGURATION = "a machine configuration"
A_TOOL_TABLE = "a tool table"
A_SCRIPT = "a script of operator actions"

PROGRAM = FileKind(A_PROGRAM, "[planner] max_program_mb", A_GCODE_PROGRAM)


def _too_big(path: object, limit: int, kind: FileKind) -> PlannerError:
    where = f" ({kind.where})" if kind.where else ""
    return PlannerError(f"{path}: more than {limit / (1 << 20):g} MB, the most {kind.what} may have{where}")


class Bounded(io.RawIOBase):
    """A file as a stream that ends at ``limit`` bytes (refused beyond) and, for a pipe or a
    device, after ``SILENT_PIPE_S`` without data (refused), whatever the file is: a regular
    file's size is looked at before it is read, /dev/zero ends at the limit, a FIFO with no
    writer ends at the timeout, and a NUL byte from a pipe or device is refused at once."""

    def __init__(self, path: str | os.PathLike[str], limit: int, kind: FileKind = PROGRAM) -> None:
        self.path, self.limit, self.read_bytes, self.kind = path, limit, 0, kind
        try:
            # without O_NONBLOCK, opening a FIFO waits for a writer, for ever
            self.fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
        except OSError as exc:
            raise PlannerError(f"{path}: cannot read: {exc.strerror or exc}") from None
        try:
            st = os.fstat(self.fd)
            if stat.S_ISDIR(st.st_mode):
                raise PlannerError(f"{path}: is a folder, not {kind.what}")
            self.regular = stat.S_ISREG(st.st_mode)
            if self.regular:
                if st.st_size > limit:
                    raise _too_big(path, limit, kind)
                os.set_blocking(self.fd, True)
        except BaseException:
            os.close(self.fd)
            raise

    def readable(self) -> bool:
        return True

    def seekable(self) -> bool:
        return self.regular

    def readall(self) -> bytes:
        """A regular file at once (its size is known and within the limit): one read, no
        pieces to join (a 250 MB program read in pieces took three times as long)."""
        if not self.regular:
            return super().readall() or b""
        parts: list[bytes] = []
        while True:
            # what is left of it, and a byte more to see its end: never a buffer of the limit
            left = os.fstat(self.fd).st_size - os.lseek(self.fd, 0, os.SEEK_CUR)
            block = os.read(self.fd, min(max(left, 0), self.limit) + 1)
            if not block:
                return b"".join(parts) if len(parts) != 1 else parts[0]
            self.read_bytes += len(block)
            if self.read_bytes > self.limit:       # it grew since it was opened
                raise _too_big(self.path, self.limit, self.kind)
            parts.append(block)

    def readinto(self, buffer: Any) -> int:
        view = memoryview(buffer).cast("B")
        want = min(len(view), self.limit + 1 - self.read_bytes)
        if want <= 0:
            raise _too_big(self.path, self.limit, self.kind)
        while True:
            if not self.regular:
                ready, _, _ = select.select([self.fd], [], [], SILENT_PIPE_S)
                if not ready:
                    raise PlannerError(f"{self.path}: nothing came for {SILENT_PIPE_S:g} s (a pipe with no "
                                       "writer?)")
            try:
                n = os.readv(self.fd, [view[:want]])
            except BlockingIOError:
                continue
            except OSError as exc:
                raise PlannerError(f"{self.path}: cannot read: {exc.strerror or exc}") from None
            self.read_bytes += n
            if self.read_bytes > self.limit:
                raise _too_big(self.path, self.limit, self.kind)
            if not self.regular and view[:n].tobytes().find(b"\0") >= 0:
                # a device of bytes (/dev/zero, /dev/urandom) is no program: said at once
                raise PlannerError(f"{self.path}: binary data (a NUL byte), not {self.kind.not_text}")
            return n

    def seek(self, offset: int, whence: int = 0) -> int:
        if not self.regular:
            raise PlannerError(f"{self.path}: a pipe is read once: what it gave is not UTF-8")
        self.read_bytes = 0 if whence == 0 else self.read_bytes
        return os.lseek(self.fd, offset, whence)

    def close(self) -> None:
        if not self.closed:
            os.close(self.fd)
        super().close()




CONFIGURATION = FileKind(A_CONFIGURATION)
TOOL_TABLE = FileKind(A_TOOL_TABLE)
SCRIPT = FileKind(A_SCRIPT)
#: the largest configuration, tool table or script read: far above any real one (a tool table
#: of 99,999 tools is 5 MB), far below what a device that goes on would fill
MAX_TEXT_BYTES = 16 << 20


def read_text(path: str | os.PathLike[str], kind: FileKind, limit: int = MAX_TEXT_BYTES) -> str:
    """A UTF-8 text file, at most ``limit`` bytes, refused at its first NUL byte (a text has
    none: a binary file or a device of bytes was named). Raises PlannerError naming the file
    and why."""
    with io.BufferedReader(Bounded(path, limit, kind)) as f:
        data = f.read()
    nul = data.find(b"\0")
    if nul >= 0:
        line = data.count(b"\n", 0, nul) + 1
        raise PlannerError(f"{path}:{line}: binary data (a NUL byte), not {kind.not_text}")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise PlannerError(f"{path}:{line}: not UTF-8 text ({kind.what} is)") from None


def parse_toml(text: str, where: str) -> dict[str, Any]:
    """``tomllib.loads``, with a table or array nested deeper than the parser's recursion can
    follow refused by name (the TOML error itself is the caller's to word)."""
    try:
        return tomllib.loads(text)
    except RecursionError:
        raise PlannerError(f"{where}: tables or arrays nested too deeply to read (a damaged file?)") from None
