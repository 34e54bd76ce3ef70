"""A numeric field for touch: read-only text that opens the numeric keypad when tapped."""

from __future__ import annotations

from collections.abc import Callable

from PySide6.QtCore import Signal
from PySide6.QtGui import QMouseEvent
from PySide6.QtWidgets import QLineEdit, QWidget

from app.widgets.keypad import ask_number

AskNumber = Callable[[QWidget | None, str, float, float, float, int], "float | None"]


class NumericField(QLineEdit):
    valueChanged = Signal(float)

    def __init__(self, title: str, value: float = 0.0, minimum: float = -1e9, maximum: float = 1e9,
                 decimals: int = 3, unit: str = "", ask: AskNumber | None = None,
                 parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("numericField")
        self.setReadOnly(True)
        self.setMinimumHeight(48)
        self.title, self.minimum, self.maximum, self.decimals, self.unit = (
            title, minimum, maximum, decimals, unit)
        self._ask = ask or ask_number
        self._value = value
        self._show()

    def value(self) -> float:
        return self._value

    def setValue(self, value: float, emit: bool = False) -> None:  # noqa: N802 - Qt naming
        self._value = float(value)
        self._show()
        if emit:
            self.valueChanged.emit(self._value)

    def _show(self) -> None:
        text = f"{self._value:.{self.decimals}f}" if self.decimals > 0 else f"{int(self._value)}"
        self.setText(f"{text} {self.unit}".rstrip())

    def open_keypad(self) -> None:
        value = self._ask(self, self.title, self._value, self.minimum, self.maximum, self.decimals)
        if value is not None:
            self.setValue(value, emit=True)

    def mouseReleaseEvent(self, event: QMouseEvent) -> None:  # noqa: N802 - Qt override
        super().mouseReleaseEvent(event)
        if self.isEnabled():
            self.open_keypad()
