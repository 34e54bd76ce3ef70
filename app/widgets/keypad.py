"""On-screen numeric keypad: a modal dialog with 64 px keys for every numeric field."""

from __future__ import annotations

import math

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QDialog, QGridLayout, QLabel, QLineEdit, QPushButton, QVBoxLayout, QWidget

from app.i18n import N_, tr

KEYS: tuple[tuple[str, ...], ...] = (
    ("7", "8", "9", "⌫"),
    ("4", "5", "6", "C"),
    ("1", "2", "3", "±"),
    ("0", ".", "Cancel", "OK"),
)
_LABELS = (N_("Cancel"), N_("OK"))


def parse_number(text: str) -> float | None:
    try:
        value = float(text.replace(",", "."))
    except ValueError:
        return None
    return value if math.isfinite(value) else None


class NumericKeypad(QDialog):
    """Enter one number within [minimum, maximum]; ``value()`` after ``exec()`` == Accepted."""

    def __init__(self, title: str, value: float = 0.0, minimum: float = -1e9, maximum: float = 1e9,
                 decimals: int = 3, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("numericKeypad")
        self.setWindowTitle(title)
        self.setModal(True)
        self.minimum, self.maximum, self.decimals = minimum, maximum, decimals
        layout = QVBoxLayout(self)
        heading = QLabel(title)
        heading.setObjectName("keypadTitle")
        self.display = QLineEdit(f"{value:.{decimals}f}" if decimals > 0 else f"{int(value)}")
        self.display.setObjectName("keypadDisplay")
        self.display.setAlignment(Qt.AlignmentFlag.AlignRight)
        self.display.setMinimumHeight(56)
        self.display.selectAll()
        self._fresh = True  # the first key replaces the old value
        self.message = QLabel(tr("Range: {0} to {1}").format(self._fmt(minimum), self._fmt(maximum)))
        self.message.setObjectName("keypadMessage")
        layout.addWidget(heading)
        layout.addWidget(self.display)
        layout.addWidget(self.message)
        grid = QGridLayout()
        self.buttons: dict[str, QPushButton] = {}
        for r, row in enumerate(KEYS):
            for c, key in enumerate(row):
                button = QPushButton(tr(key) if key in ("Cancel", "OK") else key)
                button.setMinimumSize(80, 64)
                button.setFocusPolicy(Qt.FocusPolicy.NoFocus)
                button.clicked.connect(lambda _=False, k=key: self.press(k))
                grid.addWidget(button, r, c)
                self.buttons[key] = button
        self.buttons["OK"].setDefault(True)
        layout.addLayout(grid)

    def _fmt(self, v: float) -> str:
        return f"{v:g}"

    def press(self, key: str) -> None:
        text = self.display.text()
        if key == "OK":
            self.try_accept()
            return
        if key == "Cancel":
            self.reject()
            return
        if key == "⌫":
            text = text[:-1]
        elif key == "C":
            text = ""
        elif key == "±":
            text = text[1:] if text.startswith("-") else "-" + text
        elif self._fresh:
            text = key
        elif key != "." or "." not in text:
            text += key
        self._fresh = False
        self.display.setText(text)

    def value(self) -> float | None:
        return parse_number(self.display.text())

    def try_accept(self) -> bool:
        value = self.value()
        if value is None:
            self.message.setText(tr("Not a number"))
            return False
        if not self.minimum <= value <= self.maximum:
            self.message.setText(tr("Out of range: {0} to {1}").format(
                self._fmt(self.minimum), self._fmt(self.maximum)))
            return False
        if self.decimals == 0 and value != int(value):
            # a count (parts, a tool number): taken as typed, never cut to a whole number unsaid
            self.message.setText(tr("A whole number: {0} has a fraction").format(self.display.text()))
            return False
        self.accept()
        return True


def ask_number(parent: QWidget | None, title: str, value: float, minimum: float = -1e9,
               maximum: float = 1e9, decimals: int = 3) -> float | None:
    dialog = NumericKeypad(title, value, minimum, maximum, decimals, parent)
    if dialog.exec() == QDialog.DialogCode.Accepted:
        return dialog.value()
    return None
