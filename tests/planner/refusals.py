"""What a table of refused programs checks: the refusal is an error at a line and column whose
text starts with the word it names, and says why."""

from __future__ import annotations

import pytest

from planner.core.errors import ProgramError, SourceError
from planner.gcode.interpreter import parse_program


def refused_at(text: str, col_word: str, reason: str) -> SourceError:
    """``text`` (with an M2 added) is refused: its first error points at ``col_word`` and its
    message holds ``reason``. Returns the error for further checks."""
    with pytest.raises(ProgramError) as info:
        parse_program(text + "M2\n")
    err = info.value.errors[0]
    assert text.splitlines()[err.line - 1][err.col - 1:].startswith(col_word), err
    assert reason in err.message, err
    return err
