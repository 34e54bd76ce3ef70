"""The read-only program view: any number of lines shown at once through their line index,
current, run and error lines marked, go to line, find both ways, touch a line to pick it."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from PySide6.QtCore import QPoint, Qt
from PySide6.QtGui import QColor

import app.program_lines as program_lines
from app.program_lines import LineIndex, line_text
from app.widgets.program_view import CURRENT_BG, ERROR_BG, RUN_BG, ProgramView

LINE_CHARS = st.text(alphabet=st.sampled_from("G01XYZ.-5 \r;(é°ü)İ"), max_size=12)


def _lines_of(text: str) -> list[str]:
    return [line[:-1] if line.endswith("\r") else line for line in text.split("\n")]


def line_starts(text: str) -> np.ndarray:
    """Where every line starts, then the text's end (the rule, written plainly)."""
    return np.array([0] + [i + 1 for i, c in enumerate(text) if c == "\n"] + [len(text)], np.int64)


@settings(max_examples=200, deadline=None)
@given(st.lists(LINE_CHARS, max_size=30).map("\n".join), st.sampled_from([3, 7, 1 << 24]))
def test_line_index_finds_every_line(text: str, piece: int) -> None:
    """Every line, as the text splits at "\\n", across pieces cut inside multi-byte characters."""
    old = program_lines._PIECE
    program_lines._PIECE = piece
    try:
        starts = LineIndex(text)
    finally:
        program_lines._PIECE = old
    want = _lines_of(text)
    assert len(starts) == len(want) + 1
    assert [line_text(text, starts, i) for i in range(len(want))] == want
    assert starts[len(want)] == len(text)


def test_a_final_newline_leaves_an_empty_last_line() -> None:
    starts = LineIndex("G0 X1\nG1 Y2\n")
    assert len(starts) - 1 == 3 and line_text("G0 X1\nG1 Y2\n", starts, 2) == ""


@pytest.fixture
def view(qtbot) -> ProgramView:
    widget = ProgramView()
    qtbot.addWidget(widget)
    widget.resize(500, 400)
    widget.show()
    qtbot.waitExposed(widget)
    return widget


BIG = "".join(f"N{i} G1 X{i % 100} Y{i // 100}\n" for i in range(1, 200_001))


def test_two_hundred_thousand_lines_show_at_once(view: ProgramView) -> None:
    view.load_text(BIG)
    assert view.line_count() == 200_001 and view.toPlainText() is BIG
    assert view.line(1) == "N1 G1 X1 Y0" and view.line(200_000) == "N200000 G1 X0 Y2000"
    assert view.go_to_line(150_000) and view.current_line() == 150_000
    first = view.first_visible_line()
    assert first < 150_000 < first + view.visible_lines()
    assert not view.go_to_line(200_002)


def _row_colour(view: ProgramView, line: int) -> QColor:
    image = view.viewport().grab().toImage()
    h = view.line_height()
    y = (line - 1) * h - view.verticalScrollBar().value() + h // 2
    return QColor(image.pixel(image.width() - 3, y))


def test_run_line_error_lines_and_current_line_are_painted(view: ProgramView, qtbot) -> None:
    view.load_text(BIG)
    view.set_errors({5: "radius"})
    view.set_run_line(3)
    assert view.first_visible_line() == 1  # already in sight: no scrolling
    assert _row_colour(view, 3) == RUN_BG
    assert _row_colour(view, 5) == ERROR_BG
    assert _row_colour(view, 1) == CURRENT_BG
    assert _row_colour(view, 2) != CURRENT_BG
    margin = view._margin.grab().toImage()
    h = view.line_height()
    from app.widgets.code_editor import ERROR_MARK, MARGIN_BG

    assert QColor(margin.pixel(2, 4 * h + h // 2)) == ERROR_MARK  # the bar beside line 5
    assert QColor(margin.pixel(2, 1 * h + h // 2)) == MARGIN_BG
    view.set_run_line(120_000)  # out of sight: brought to the middle
    assert view.first_visible_line() < 120_000 < view.first_visible_line() + view.visible_lines()
    assert _row_colour(view, 120_000) == RUN_BG
    assert view.errors == {5: "radius"} and view.run_line == 120_000


def test_touching_a_line_makes_it_current(view: ProgramView, qtbot) -> None:
    view.load_text(BIG)
    view.go_to_line(1000)
    seen: list[int] = []
    view.lineActivated.connect(seen.append)
    row, h = 2, view.line_height()
    y = row * h + h // 2 - view.verticalScrollBar().value() % h
    qtbot.mouseClick(view.viewport(), Qt.MouseButton.LeftButton, pos=QPoint(40, y))
    want = view.first_visible_line() + row
    assert view.current_line() == want and seen == [want]


def test_find_goes_forward_and_back_and_wraps(view: ProgramView) -> None:
    view.load_text(BIG)
    view.go_to_line(10)
    assert view.find_text("x99 y1999") and view.current_line() == 199_999
    assert view.find_text("X99 Y1999") and view.current_line() == 199_999  # the only one: wraps to it
    view.go_to_line(1)
    assert view.find_text("n3 ") and view.current_line() == 3
    assert view.find_text("n3 ", backward=True) and view.current_line() == 3
    assert view.find_text("n3 ", backward=True) and view.current_line() == 3  # the only one
    view.go_to_line(5)
    assert view.find_text("N200000 ", backward=True) and view.current_line() == 200_000  # wraps
    assert not view.find_text("G2 ")
    assert not view.find_text("")


@settings(max_examples=200, deadline=None)
@given(st.lists(LINE_CHARS, max_size=40).map("\n".join), st.sampled_from([3, 7, 1 << 24]),
       st.sampled_from([1, 2, 5, 64]), st.randoms(use_true_random=False))
def test_a_sparse_line_index_reads_as_the_whole_index(text: str, piece: int, stride: int, rnd) -> None:
    """Every stride-th line start kept (a 10,000,000-line program's index in 1.3 MB, not
    40): every line start, looked up in order or not, the line of every character and the
    longest line, as the whole index gives them."""
    old = program_lines._PIECE, LineIndex.STRIDE
    program_lines._PIECE, LineIndex.STRIDE = piece, stride
    try:
        index = LineIndex(text)
        starts = line_starts(text)
        assert len(index) == len(starts)
        order = list(range(len(starts)))
        assert [index[k] for k in order] == starts.tolist()
        rnd.shuffle(order)
        assert [index[k] for k in order] == [int(starts[k]) for k in order]
        assert [index.line_number(o) for o in range(len(text))] == \
            np.searchsorted(starts, np.arange(len(text)), side="right").tolist()
        assert index.widest == int(np.diff(starts).max())
        assert [line_text(text, index, i) for i in range(len(starts) - 1)] == _lines_of(text)
    finally:
        program_lines._PIECE, LineIndex.STRIDE = old
