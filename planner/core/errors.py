"""The planner's one error type and the collected-errors form used by the interpreter."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["PlannerError", "ProgramError", "SourceError"]


class PlannerError(ValueError):
    """Any error raised by the planner package (bad program, bad settings, bad request)."""


class BlockError(Exception):
    """A refusal inside one block of a program. The interpreter turns it into a SourceError
    with the file, the line and the column of ``letter``'s word (or ``col``); it never leaves
    the interpreter."""

    def __init__(self, message: str, letter: str | None = None, col: int | None = None):
        super().__init__(message)
        self.message = message
        self.letter = letter
        self.col = col


@dataclass(frozen=True, slots=True)
class SourceError:
    """One error located in a source file: rendered as ``file:line:col: error: message``."""

    file: str
    line: int  # 1-based
    col: int  # 1-based
    message: str

    def __post_init__(self) -> None:
        # a message quotes the program, which may hold any byte: a control character is named
        # (U+0000), never written raw to a terminal, a log or the panel
        if not self.message.isprintable():
            object.__setattr__(self, "message", printable(self.message))

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.col}: error: {self.message}"


def printable(text: str) -> str:
    """``text`` with each character that is not printable named as U+XXXX."""
    return "".join(c if c.isprintable() else f"U+{ord(c):04X}" for c in text)


class ProgramError(PlannerError):
    """A G-code program with one or more errors; ``errors`` holds all of them (up to a limit).

    ``str(exc)`` is one ``file:line:col: error: message`` per line, ready for stderr.
    ``line`` is the line of the first error (what an editor jumps to).
    """

    def __init__(self, errors: list[SourceError] | tuple[SourceError, ...], truncated: bool = False):
        self.errors: tuple[SourceError, ...] = tuple(errors)
        self.truncated = truncated
        text = "\n".join(str(e) for e in self.errors)
        if truncated:
            text += "\n(too many errors; stopped)"
        super().__init__(text)

    @property
    def line(self) -> int:
        return self.errors[0].line if self.errors else 0

    @property
    def lines(self) -> tuple[int, ...]:
        return tuple(e.line for e in self.errors)
