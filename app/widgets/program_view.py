"""A read-only view over a program's text: line numbers, the current line, the line being run
and error lines marked, go to line, find, flick to scroll.

It paints only the lines in sight, each cut from the text by its line index
(``app.program_lines``): a program of millions of lines shows at once and takes 4 bytes a line
next to the text the loader holds anyway, where a text widget needs gigabytes and tens of
seconds of the GUI thread. Same calls as the editor's where they mean the same
(``load_text``, ``set_errors``, ``set_run_line``, ``go_to_line``, ``find_text``,
``current_line``, ``lineActivated``), so a page can show either.
"""

from __future__ import annotations

import re

from PySide6.QtCore import QRect, QSize, Qt, Signal
from PySide6.QtGui import QColor, QMouseEvent, QPainter, QPaintEvent, QResizeEvent
from PySide6.QtWidgets import QAbstractScrollArea, QWidget

from app.program_lines import LineIndex, line_text
from app.widgets.code_editor import CURRENT_BG, ERROR_BG, MARGIN_BG, RUN_BG, code_font, paint_line_number

TEXT_FG = QColor("#d8dee6")
VIEW_BG = QColor("#141a21")
FIND_PIECE = 1 << 20  # characters searched backwards at a time


class _Margin(QWidget):
    """Line numbers, left of the lines."""

    def __init__(self, view: ProgramView) -> None:
        super().__init__(view)
        self.view = view

    def paintEvent(self, event: QPaintEvent) -> None:  # noqa: N802 - Qt override
        self.view.paint_margin(event)


class ProgramView(QAbstractScrollArea):
    lineActivated = Signal(int)  # 1-based line the operator touched or went to
    textLoaded = Signal()  # a new text is shown (at once: nothing is copied)

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("programView")
        self.setFont(code_font())
        self._text = ""
        self._starts = LineIndex("")
        self._widest = 0  # characters of the longest line
        self._current = 1
        self._run_line = 0
        self._errors: dict[int, str] = {}
        self._find_pos = 0  # where the next search starts (character offset)
        self._on_match = False  # ... and a match starts there (a search forward goes past it)
        self._margin = _Margin(self)
        self.viewport().setCursor(Qt.CursorShape.ArrowCursor)
        self._update_margin()
        self._update_scroll_range()

    # --- text ----------------------------------------------------------------------------
    def load_text(self, text: str, chunked: bool = False, starts: LineIndex | None = None) -> None:
        """Show ``text`` (its line index ``starts`` when known). ``chunked`` is accepted for
        the editor's sake; nothing here needs pieces."""
        del chunked
        self._text = text
        self._starts = LineIndex(text) if starts is None else starts
        self._widest = self._starts.widest
        self._current = 1
        self._find_pos, self._on_match = 0, False
        self._update_scroll_range()
        self.verticalScrollBar().setValue(0)
        self.horizontalScrollBar().setValue(0)
        self._update_margin()
        self.viewport().update()
        self.textLoaded.emit()

    def toPlainText(self) -> str:  # noqa: N802 - the editor's name for the same thing
        return self._text

    @property
    def loading(self) -> bool:
        return False

    @property
    def highlighting(self) -> bool:
        return False

    def isReadOnly(self) -> bool:  # noqa: N802 - the editor's name for the same thing
        return True

    def line_count(self) -> int:
        return len(self._starts) - 1

    def blockCount(self) -> int:  # noqa: N802 - the editor's name for the same thing
        return self.line_count()

    def line(self, number: int) -> str:
        """Text of 1-based line ``number``."""
        return line_text(self._text, self._starts, number - 1)

    # --- geometry ------------------------------------------------------------------------
    def line_height(self) -> int:
        return self.fontMetrics().lineSpacing()

    def line_number_width(self) -> int:
        digits = max(3, len(str(self.line_count())))
        return 22 + self.fontMetrics().horizontalAdvance("9") * digits

    def first_visible_line(self) -> int:
        """1-based line at the top of the view."""
        return self.verticalScrollBar().value() // self.line_height() + 1

    def visible_lines(self) -> int:
        return max(1, self.viewport().height() // self.line_height())

    def _update_margin(self) -> None:
        self.setViewportMargins(self.line_number_width(), 0, 0, 0)
        cr = self.contentsRect()
        self._margin.setGeometry(QRect(cr.left(), cr.top(), self.line_number_width(),
                                       self.viewport().height()))

    def _update_scroll_range(self) -> None:
        h = self.line_height()
        total = self.line_count() * h
        bar = self.verticalScrollBar()
        bar.setRange(0, max(0, total - self.viewport().height()))
        bar.setPageStep(self.viewport().height())
        bar.setSingleStep(h)
        char = self.fontMetrics().horizontalAdvance("9")
        hbar = self.horizontalScrollBar()
        hbar.setRange(0, max(0, (self._widest + 2) * char - self.viewport().width()))
        hbar.setPageStep(self.viewport().width())
        hbar.setSingleStep(char)

    def resizeEvent(self, event: QResizeEvent) -> None:  # noqa: N802 - Qt override
        super().resizeEvent(event)
        cr = self.contentsRect()
        self._margin.setGeometry(QRect(cr.left(), cr.top(), self.line_number_width(),
                                       self.viewport().height()))
        self._update_scroll_range()

    def sizeHint(self) -> QSize:  # noqa: N802 - Qt override
        return QSize(480, 320)

    def scrollContentsBy(self, dx: int, dy: int) -> None:  # noqa: N802 - Qt override
        self.viewport().update()
        self._margin.update()

    # --- painting ------------------------------------------------------------------------
    def paintEvent(self, event: QPaintEvent) -> None:  # noqa: N802 - Qt override
        painter = QPainter(self.viewport())
        painter.setFont(self.font())
        h = self.line_height()
        top_px = self.verticalScrollBar().value()
        x0 = 4 - self.horizontalScrollBar().value()
        width = self.viewport().width()
        painter.fillRect(event.rect(), VIEW_BG)
        first = top_px // h
        y = first * h - top_px
        ascent = self.fontMetrics().ascent()
        n = self.line_count()
        index = first
        while y < self.viewport().height() and index < n:
            number = index + 1
            bg = (RUN_BG if number == self._run_line else ERROR_BG if number in self._errors
                  else CURRENT_BG if number == self._current else None)
            if bg is not None:
                painter.fillRect(0, y, width, h, bg)
            painter.setPen(TEXT_FG)
            painter.drawText(x0, y + ascent, line_text(self._text, self._starts, index))
            y += h
            index += 1
        painter.end()

    def paint_margin(self, event: QPaintEvent) -> None:
        painter = QPainter(self._margin)
        painter.setFont(self.font())
        painter.fillRect(event.rect(), MARGIN_BG)
        h = self.line_height()
        top_px = self.verticalScrollBar().value()
        width = self._margin.width()
        first = top_px // h
        y = first * h - top_px
        n = self.line_count()
        index = first
        while y < self._margin.height() and index < n:
            number = index + 1
            paint_line_number(painter, number, y, width, h, number in self._errors, number == self._run_line)
            y += h
            index += 1
        painter.end()

    # --- marks ---------------------------------------------------------------------------
    def set_errors(self, errors: dict[int, str]) -> None:
        """Mark these 1-based lines as erroneous (message per line); empty clears."""
        self._errors = dict(errors)
        self.viewport().update()
        self._margin.update()

    @property
    def errors(self) -> dict[int, str]:
        return dict(self._errors)

    def set_run_line(self, line: int, keep_visible: bool = True) -> None:
        """Mark the line being run (0: none); ``keep_visible``: scroll it into the middle when it
        leaves the view."""
        if line == self._run_line:
            return
        self._run_line = line
        if keep_visible and line > 0 and not self._in_view(line):
            self._center(line)
        self.viewport().update()
        self._margin.update()

    @property
    def run_line(self) -> int:
        return self._run_line

    # --- navigation ----------------------------------------------------------------------
    def current_line(self) -> int:
        return self._current

    def _set_current(self, line: int) -> None:
        line = min(max(1, line), self.line_count())
        changed = line != self._current
        self._current = line
        self._find_pos, self._on_match = int(self._starts[line - 1]), False
        self.viewport().update()
        if changed:
            self.lineActivated.emit(line)

    def _in_view(self, line: int) -> bool:
        first = self.first_visible_line()
        return first <= line < first + self.visible_lines()

    def _center(self, line: int) -> None:
        h = self.line_height()
        self.verticalScrollBar().setValue((line - 1) * h - (self.viewport().height() - h) // 2)

    def go_to_line(self, line: int) -> bool:
        if not 1 <= line <= self.line_count():
            return False
        self._set_current(line)
        self._center(line)
        return True

    def line_at(self, y_px: int) -> int:
        """1-based line under viewport row ``y_px``."""
        return (self.verticalScrollBar().value() + y_px) // self.line_height() + 1

    def mousePressEvent(self, event: QMouseEvent) -> None:  # noqa: N802 - Qt override
        line = self.line_at(int(event.position().y()))
        if line <= self.line_count():
            self._set_current(line)
        super().mousePressEvent(event)

    def find_text(self, text: str, backward: bool = False) -> bool:
        """Go to the next line holding ``text`` (case-insensitive), wrapping around; backward:
        the last one before the line or the match the search stands on."""
        if not text:
            return False
        pattern = re.compile(re.escape(text), re.IGNORECASE)
        hit = self._find_back(pattern, len(text)) if backward else self._find_forward(pattern, len(text))
        if hit is None:
            return False
        line = self._starts.line_number(hit)
        self._set_current(line)
        self._find_pos, self._on_match = hit, True
        self._center(line)
        return True

    def _find_forward(self, pattern: re.Pattern[str], overlap: int) -> int | None:
        """Start of the first match from the search position (past the match it stands on),
        else the first one before it."""
        start = min(self._find_pos + int(self._on_match), len(self._text))
        found = pattern.search(self._text, start) or pattern.search(self._text, 0, start + overlap)
        return found.start() if found else None

    def _find_back(self, pattern: re.Pattern[str], overlap: int) -> int | None:
        """Start of the last match that starts before the search position, else the last one."""
        n = len(self._text)
        for lo_end, hi_end in ((0, self._find_pos), (self._find_pos, n)):  # match starts in here
            hi = hi_end
            while hi > lo_end:
                lo = max(lo_end, hi - FIND_PIECE)
                last = None
                # the piece reaches ``overlap`` past its end: a match across the cut is found
                for found in pattern.finditer(self._text, lo, min(hi + overlap, n)):
                    if found.start() >= hi:
                        break
                    last = found
                if last is not None:
                    return last.start()
                hi = lo
        return None
