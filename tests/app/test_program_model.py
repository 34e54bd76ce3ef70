"""The loaded program's lines as the pages show them (a tapped segment's source line)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from app.program_lines import LineIndex
from app.program_model import ProgramModel

TEXT = "G21 G90\r\nG0 X1\n\nG1 X2 F100 ; cut\nM2"


@pytest.mark.parametrize("indexed", [True, False])
def test_a_line_is_its_text_without_its_end(qapp, indexed: bool) -> None:
    model = ProgramModel()
    info = SimpleNamespace(name="p.ngc", path="", text=TEXT,
                           line_starts=LineIndex(TEXT) if indexed else None)
    model.info, model.text = info, info.text
    assert [model.line(k) for k in range(0, 7)] == ["", "G21 G90", "G0 X1", "", "G1 X2 F100 ; cut", "M2", ""]


def test_a_loaded_program_is_read_through_its_line_index(qapp) -> None:
    # ten million lines are not split into ten million strings to show one: the index the
    # check made is what the line is read by
    model = ProgramModel()
    starts = np.array([0, 9, 15, 16, 33, 35], np.int64)   # where TEXT's lines start, then its end
    assert [LineIndex(TEXT)[k] for k in range(len(starts))] == starts.tolist()
    starts[1] += 3                                   # an index that says line 2 starts later
    info = SimpleNamespace(name="p.ngc", path="", text=TEXT, line_starts=starts)
    model.info, model.text = info, info.text
    assert model.line(2) == "X1"
