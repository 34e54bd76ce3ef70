"""G-code editor: line numbers, current-line and error-line highlights, go to line, find.

Errors are set per line (1-based) with their message; the margin shows a red marker and the
line is tinted. The file handling (open/save/autosave) lives in program_document.py.
"""

from __future__ import annotations

from PySide6.QtCore import QRect, QSize, Qt, QTimer, Signal
from PySide6.QtGui import (
    QColor,
    QFont,
    QPainter,
    QPaintEvent,
    QResizeEvent,
    QTextCharFormat,
    QTextCursor,
    QTextDocument,
    QTextFormat,
)
from PySide6.QtWidgets import QPlainTextEdit, QTextEdit, QWidget

from app.format import error_column
from app.widgets.gcode_highlighter import GCodeHighlighter

HIGHLIGHT_MAX_LINES = 5000  # highlighting costs ~20 us a line in the GUI thread: off beyond this
CHUNK_LINES = 3000  # a big text goes in in pieces, one per event-loop turn (~30 ms each, measured)
ERROR_BG = QColor("#5a1020")
CURRENT_BG = QColor("#1c3550")
RUN_BG = QColor("#1b5f2a")
MARGIN_BG = QColor("#0f1318")  # the line numbers' margin
NUMBER_FG = QColor("#7a8796")
ERROR_MARK = QColor("#ff3050")  # the bar beside an error line's number, and its number
ERROR_NUMBER_FG = QColor("#ff8090")
RUN_NUMBER_FG = QColor("#9fffb0")


def code_font() -> QFont:
    """The monospaced font G-code is shown in (the editor and the read-only view alike)."""
    font = QFont("DejaVu Sans Mono")
    font.setStyleHint(QFont.StyleHint.Monospace)
    font.setPointSize(13)
    return font


def paint_line_number(painter: QPainter, number: int, top: int, width: int, height: int, error: bool,
                      running: bool) -> None:
    """One line's number in the margin: a red bar and red number for an error, green for the
    line being run."""
    if error:
        painter.fillRect(0, top, 8, height, ERROR_MARK)
        painter.setPen(ERROR_NUMBER_FG)
    else:
        painter.setPen(RUN_NUMBER_FG if running else NUMBER_FG)
    painter.drawText(0, top, width - 6, height, Qt.AlignmentFlag.AlignRight, str(number))


class _LineNumberArea(QWidget):
    def __init__(self, editor: CodeEditor) -> None:
        super().__init__(editor)
        self.editor = editor

    def sizeHint(self) -> QSize:  # noqa: N802 - Qt override
        return QSize(self.editor.line_number_width(), 0)

    def paintEvent(self, event: QPaintEvent) -> None:  # noqa: N802 - Qt override
        self.editor.paint_line_numbers(event)


class CodeEditor(QPlainTextEdit):
    lineActivated = Signal(int)  # 1-based line the cursor moved to
    textLoaded = Signal()  # the last piece of a ``load_text`` is in

    def __init__(self, parent: QWidget | None = None, read_only: bool = False) -> None:
        super().__init__(parent)
        self.setObjectName("codeEditor")
        self.setFont(code_font())
        self.setLineWrapMode(QPlainTextEdit.LineWrapMode.NoWrap)
        self.setReadOnly(read_only)
        self._errors: dict[int, str] = {}
        self._run_line = 0
        self._load_generation = 0
        self._loading_text = False
        self._read_only_before = read_only
        self.highlighter = GCodeHighlighter(self.document())
        self._numbers = _LineNumberArea(self)
        self.blockCountChanged.connect(self._update_margin)
        self.updateRequest.connect(self._scroll_margin)
        self.cursorPositionChanged.connect(self._on_cursor)
        self._update_margin()

    def load_text(self, text: str, chunked: bool = False) -> None:
        """Replace the text; syntax highlighting only for programs up to HIGHLIGHT_MAX_LINES.

        ``chunked``: a text over CHUNK_LINES lines goes in CHUNK_LINES at a time, one piece per
        event-loop turn (35,000 lines at once hold the GUI thread ~0.15-0.2 s); ``loading``
        is True and ``textChanged`` fires per piece until ``textLoaded``."""
        self._load_generation += 1
        big = text.count("\n") > HIGHLIGHT_MAX_LINES
        self.highlighter.setDocument(None if big else self.document())
        if self._loading_text:  # a chunked load in progress: stopped above, undo it
            self._loading_text = False
            self.setReadOnly(self._read_only_before)
            self.document().setUndoRedoEnabled(True)
        if not chunked or text.count("\n") <= CHUNK_LINES:
            self.setPlainText(text)
            self.textLoaded.emit()
            return
        generation = self._load_generation
        self._loading_text = True
        was_read_only = self._read_only_before = self.isReadOnly()
        self.setReadOnly(True)  # no typing into a half-loaded text
        self.document().setUndoRedoEnabled(False)

        def piece_end(start: int) -> int:
            """Where the piece of CHUNK_LINES lines from ``start`` ends (no list of the lines:
            2,000,000 of them took 0.1 s and 150 MB at once)."""
            end = start
            for _ in range(CHUNK_LINES):
                end = text.find("\n", end) + 1
                if end == 0:
                    return len(text)
            return end

        first = piece_end(0)
        self.setPlainText(text[:first])

        def more(start: int) -> None:
            if generation != self._load_generation:
                return  # a newer text replaced this one
            try:
                cursor = QTextCursor(self.document())
            except RuntimeError:  # the widget was deleted meanwhile
                return
            end = piece_end(start)
            cursor.movePosition(QTextCursor.MoveOperation.End)
            cursor.insertText(text[start:end])
            if end < len(text):
                QTimer.singleShot(0, lambda: more(end))
                return
            self._loading_text = False
            self.setReadOnly(was_read_only)
            self.document().setUndoRedoEnabled(True)
            self._refresh_selections()
            self.textLoaded.emit()

        QTimer.singleShot(0, lambda: more(first))

    @property
    def loading(self) -> bool:
        """True while a chunked ``load_text`` is still putting its text in."""
        return self._loading_text

    @property
    def highlighting(self) -> bool:
        return self.highlighter.document() is not None

    # --- line numbers -------------------------------------------------------------------
    def line_number_width(self) -> int:
        digits = max(3, len(str(self.blockCount())))
        return 22 + self.fontMetrics().horizontalAdvance("9") * digits

    def _update_margin(self, _count: int = 0) -> None:
        self.setViewportMargins(self.line_number_width(), 0, 0, 0)

    def _scroll_margin(self, rect: QRect, dy: int) -> None:
        if dy:
            self._numbers.scroll(0, dy)
        else:
            self._numbers.update(0, rect.y(), self._numbers.width(), rect.height())

    def resizeEvent(self, event: QResizeEvent) -> None:  # noqa: N802 - Qt override
        super().resizeEvent(event)
        cr = self.contentsRect()
        self._numbers.setGeometry(QRect(cr.left(), cr.top(), self.line_number_width(), cr.height()))

    def paint_line_numbers(self, event: QPaintEvent) -> None:
        painter = QPainter(self._numbers)
        painter.fillRect(event.rect(), MARGIN_BG)
        block = self.firstVisibleBlock()
        number = block.blockNumber() + 1
        top = round(self.blockBoundingGeometry(block).translated(self.contentOffset()).top())
        height = round(self.blockBoundingRect(block).height())
        width = self._numbers.width()
        while block.isValid() and top <= event.rect().bottom():
            if block.isVisible() and top + height >= event.rect().top():
                paint_line_number(painter, number, top, width, height, number in self._errors,
                                  number == self._run_line)
            block = block.next()
            top += height
            height = round(self.blockBoundingRect(block).height())
            number += 1
        painter.end()

    # --- highlights ----------------------------------------------------------------------
    def set_errors(self, errors: dict[int, str]) -> None:
        """Mark these 1-based lines as erroneous (message per line); empty clears."""
        self._errors = dict(errors)
        self._refresh_selections()
        self._numbers.update()

    @property
    def errors(self) -> dict[int, str]:
        return dict(self._errors)

    def set_run_line(self, line: int, keep_visible: bool = True) -> None:
        """Highlight the line being executed (0: none) and scroll it into view."""
        if line == self._run_line:
            return
        self._run_line = line
        self._refresh_selections()
        self._numbers.update()
        if keep_visible and line > 0:
            block = self.document().findBlockByNumber(line - 1)
            if block.isValid():
                cursor = QTextCursor(block)
                self.setTextCursor(cursor)
                self.centerCursor()

    @property
    def run_line(self) -> int:
        return self._run_line

    def _selection(self, line: int, color: QColor) -> QTextEdit.ExtraSelection | None:
        block = self.document().findBlockByNumber(line - 1)
        if not block.isValid():
            return None
        sel = QTextEdit.ExtraSelection()
        sel.format.setBackground(color)
        sel.format.setProperty(QTextFormat.Property.FullWidthSelection, True)
        sel.cursor = QTextCursor(block)
        return sel

    def _column_mark(self, line: int) -> QTextEdit.ExtraSelection | None:
        """The error's column underlined, from there to the end of its word."""
        col = error_column(self._errors.get(line, ""))
        block = self.document().findBlockByNumber(line - 1)
        if col <= 0 or not block.isValid() or col > len(block.text()):
            return None
        text = block.text()
        end = col
        while end < len(text) and not text[end].isspace():
            end += 1
        sel = QTextEdit.ExtraSelection()
        sel.format.setUnderlineStyle(QTextCharFormat.UnderlineStyle.WaveUnderline)
        sel.format.setUnderlineColor(QColor("#ff5050"))
        cursor = QTextCursor(block)
        cursor.setPosition(block.position() + col - 1)
        cursor.setPosition(block.position() + end, QTextCursor.MoveMode.KeepAnchor)
        sel.cursor = cursor
        return sel

    def _refresh_selections(self) -> None:
        selections = []
        current = self.textCursor().blockNumber() + 1
        for line, color in [(current, CURRENT_BG)] + [(n, ERROR_BG) for n in sorted(self._errors)] + [
                (self._run_line, RUN_BG)]:
            if line > 0:
                sel = self._selection(line, color)
                if sel is not None:
                    selections.append(sel)
        for line in sorted(self._errors):
            mark = self._column_mark(line)
            if mark is not None:
                selections.append(mark)
        self.setExtraSelections(selections)

    def _on_cursor(self) -> None:
        self._refresh_selections()
        self.lineActivated.emit(self.current_line())

    # --- navigation ----------------------------------------------------------------------
    def current_line(self) -> int:
        return self.textCursor().blockNumber() + 1

    def go_to_line(self, line: int) -> bool:
        block = self.document().findBlockByNumber(max(0, line - 1))
        if not block.isValid():
            return False
        self.setTextCursor(QTextCursor(block))
        self.centerCursor()
        return True

    def find_text(self, text: str, backward: bool = False) -> bool:
        """Find the next occurrence (wrapping around); case-insensitive."""
        if not text:
            return False
        flags = QTextDocument.FindFlag.FindBackward if backward else QTextDocument.FindFlag(0)
        if self.find(text, flags):
            return True
        cursor = self.textCursor()
        cursor.movePosition(QTextCursor.MoveOperation.End if backward else QTextCursor.MoveOperation.Start)
        self.setTextCursor(cursor)
        return self.find(text, flags)

