"""The top of every command (``cnc-plan``, ``cnc-run``): whatever escapes its own handling
becomes one line naming the input, never a traceback, and a reader that stops reading its
standard output early (``| head``) ends it quietly."""

from __future__ import annotations

import contextlib
import os
import sys
from collections.abc import Callable, Sequence

__all__ = ["run_command"]

#: how much of an unexpected error's own text is shown
_SHOWN = 300


def _input_of(argv: Sequence[str]) -> str:
    """The first argument that is no option: the program the command was given."""
    return next((a for a in argv if a and not a.startswith("-")), "")


def run_command(prog: str, main: Callable[[list[str] | None], int], argv: list[str] | None = None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    try:
        return main(argv)
    except BrokenPipeError:
        # the reader went away: the rest is not wanted, and Python's own flush of standard
        # output at exit would fail again
        with contextlib.suppress(OSError, ValueError):
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, sys.stdout.fileno())
        print(f"{prog}: standard output was closed before the end", file=sys.stderr)
        return 1
    except Exception as exc:  # noqa: BLE001 - the last word: one line, not a traceback
        text = " ".join(str(exc).split())
        if len(text) > _SHOWN:
            text = text[:_SHOWN] + " ..."
        where = _input_of(args)
        print(f"{prog}: {where + ': ' if where else ''}internal error, {type(exc).__name__}: {text}",
              file=sys.stderr)
        return 2
