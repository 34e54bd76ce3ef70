"""A one-line label for names of any length (a program's file name): whole when there is room,
otherwise cut with "…" to its width, the whole text in its tooltip. It asks for the room of its
whole text but takes less without complaint, so a long name never widens a page or squeezes
the buttons beside it."""

from __future__ import annotations

from PySide6.QtCore import QSize, Qt
from PySide6.QtGui import QResizeEvent
from PySide6.QtWidgets import QLabel, QSizePolicy, QWidget

__all__ = ["ElidedLabel"]


class ElidedLabel(QLabel):
    def __init__(self, parent: QWidget | None = None, min_chars: int = 8,
                 mode: Qt.TextElideMode = Qt.TextElideMode.ElideMiddle) -> None:
        """``min_chars``: the least width it takes, in widths of "M"; ``mode``: where the cut
        falls (the middle keeps a file name's start and its extension)."""
        super().__init__(parent)
        self._full = ""
        self._min_chars = min_chars
        self._mode = mode
        self.setSizePolicy(QSizePolicy.Policy.Preferred, QSizePolicy.Policy.Preferred)

    def text(self) -> str:  # noqa: D102 - Qt override
        """The whole text, whatever part of it is shown (``shown_text``)."""
        return self._full

    def shown_text(self) -> str:
        return QLabel.text(self)

    def setText(self, text: str) -> None:  # noqa: N802 - Qt override
        """The whole text: shown cut to the label's width when it does not fit."""
        self._full = str(text)
        self.setToolTip(self._full)
        self._fit()
        self.updateGeometry()

    def sizeHint(self) -> QSize:  # noqa: N802 - Qt override
        hint = super().sizeHint()
        m = self.contentsMargins()
        wide = self.fontMetrics().horizontalAdvance(self._full) + m.left() + m.right() + 2
        return QSize(wide, hint.height())

    def minimumSizeHint(self) -> QSize:  # noqa: N802 - Qt override
        hint = super().minimumSizeHint()
        least = self.fontMetrics().horizontalAdvance("M" * self._min_chars)
        return QSize(min(least, self.sizeHint().width()), hint.height())

    def resizeEvent(self, event: QResizeEvent) -> None:  # noqa: N802 - Qt override
        super().resizeEvent(event)
        self._fit()

    def _fit(self) -> None:
        room = max(self.contentsRect().width(), 0)
        shown = self.fontMetrics().elidedText(self._full, self._mode, room)
        QLabel.setText(self, shown)
