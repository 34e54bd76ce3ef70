"""Override 0-200 % for touch: a slider with a large handle plus -10 / 100 % / +10 buttons."""

from __future__ import annotations

from PySide6.QtCore import Qt, Signal
from PySide6.QtWidgets import QHBoxLayout, QLabel, QPushButton, QSlider, QVBoxLayout, QWidget


class OverrideControl(QWidget):
    changed = Signal(float)  # percent, emitted when the operator changes it

    def __init__(self, title: str, maximum: int = 200, parent: QWidget | None = None,
                 minimum: int = 0) -> None:
        super().__init__(parent)
        self.setObjectName("overrideControl")
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.setSpacing(0)
        top = QHBoxLayout()
        self.title = QLabel(title)
        self.value_label = QLabel("100 %")
        self.value_label.setObjectName("overrideValue")
        self.value_label.setAlignment(Qt.AlignmentFlag.AlignRight)
        for label in (self.title, self.value_label):   # a compact title: three fit the Auto page
            label.setFixedHeight(22)
        top.addWidget(self.title)
        top.addWidget(self.value_label)
        layout.addLayout(top)
        row = QHBoxLayout()
        self.slider = QSlider(Qt.Orientation.Horizontal)
        self.slider.setRange(minimum, maximum)
        self.slider.setValue(100)
        self.slider.setMinimumHeight(48)
        self.slider.setPageStep(10)
        self.slider.valueChanged.connect(self._on_slider)
        self.buttons: dict[str, QPushButton] = {}
        for text, delta in (("-10", -10), ("100%", 0), ("+10", 10)):
            button = QPushButton(text)
            button.setMinimumWidth(64)
            button.clicked.connect(lambda _=False, d=delta: self._step(d))
            self.buttons[text] = button
        row.addWidget(self.buttons["-10"])
        row.addWidget(self.slider, 1)
        row.addWidget(self.buttons["+10"])
        row.addWidget(self.buttons["100%"])
        layout.addLayout(row)
        self._quiet = False
        self._note = ""

    def _show(self, value: int) -> None:
        self.value_label.setText(f"{value} %" + (f" ({self._note})" if self._note else ""))

    def set_note(self, note: str) -> None:
        """What the override does here when not what it is set to ("runs 100 %: program");
        "" when it is."""
        self._note = note
        self._show(self.slider.value())

    def _step(self, delta: int) -> None:
        self.slider.setValue(100 if delta == 0 else self.slider.value() + delta)

    def _on_slider(self, value: int) -> None:
        self._show(value)
        if not self._quiet:
            self.changed.emit(float(value))

    def set_value(self, percent: float) -> None:
        """Show the controller's value without echoing it back."""
        self._quiet = True
        self.slider.setValue(round(percent))
        self._show(round(percent))
        self._quiet = False

    def value(self) -> float:
        return float(self.slider.value())
