"""Jog buttons per axis: press and hold for continuous jog (stops on release, on leaving the
page and on losing focus), or one increment per tap (0.001 / 0.01 / 0.1 / 1 mm or degrees)."""

from __future__ import annotations

from collections.abc import Sequence

from PySide6.QtCore import Signal
from PySide6.QtWidgets import (
    QGridLayout,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QVBoxLayout,
    QWidget,
)

from app.i18n import N_, I18n
from app.widgets.override_control import OverrideControl
from app.widgets.touch import exclusive_buttons

INCREMENTS: tuple[float, ...] = (0.001, 0.01, 0.1, 1.0)


class JogPanel(QWidget):
    jogStart = Signal(str, int)        # axis, direction
    jogStop = Signal(str)              # axis ("" = all)
    jogStep = Signal(str, float, int)  # axis, step, direction

    def __init__(self, axes: Sequence[str], i18n: I18n, parent: QWidget | None = None,
                 rotary: Sequence[bool] | None = None) -> None:
        """``rotary``: which axes turn (their steps are degrees; the buttons say mm, ° or both)."""
        super().__init__(parent)
        self.axes = tuple(axes)
        turns = tuple(rotary) if rotary is not None else (False,) * len(self.axes)
        unit = "mm/°" if any(turns) and not all(turns) else "°" if all(turns) and turns else "mm"
        layout = QVBoxLayout(self)
        modes = QHBoxLayout()
        cont = QPushButton()
        i18n.bind(cont, N_("Continuous"))
        self.mode_group, self.mode_buttons = exclusive_buttons(
            self, modes, [(0.0, cont)] + [(s, QPushButton(f"{s:g}")) for s in INCREMENTS])
        # the steps' unit once, after them: in each button it would not fit beside the jog panel
        self.unit_label = QLabel(unit)
        modes.addWidget(self.unit_label)
        for button in self.mode_buttons.values():
            button.setObjectName("jogStep")
        cont.setChecked(True)
        layout.addLayout(modes)
        grid = QGridLayout()
        self.buttons: dict[tuple[str, int], QPushButton] = {}
        for row, axis in enumerate(self.axes):
            label = QLabel(axis)
            label.setObjectName("droAxis")
            grid.addWidget(label, row, 1)
            for col, direction in ((0, -1), (2, 1)):
                button = QPushButton(f"{axis}{'−' if direction < 0 else '+'}")
                button.setObjectName("jogButton")
                button.pressed.connect(lambda a=axis, d=direction: self._pressed(a, d))
                button.released.connect(lambda a=axis: self._released(a))
                grid.addWidget(button, row, col)
                self.buttons[(axis, direction)] = button
        layout.addLayout(grid)
        self.speed = OverrideControl("", maximum=100)
        i18n.bind(self.speed.title, N_("Jog speed"))
        layout.addWidget(self.speed)
        layout.addStretch(1)
        self._held: set[str] = set()

    @property
    def speed_fraction(self) -> float:
        """Continuous jog speed as a fraction of the configured jog speed (0.01 .. 1)."""
        return max(self.speed.value(), 1.0) / 100.0

    @property
    def step(self) -> float:
        """0 for continuous jog, else the increment."""
        for value, button in self.mode_buttons.items():
            if button.isChecked():
                return value
        return 0.0

    def set_step(self, step: float) -> None:
        self.mode_buttons[step].setChecked(True)

    def _pressed(self, axis: str, direction: int) -> None:
        if self.step == 0.0:
            self._held.add(axis)
            self.jogStart.emit(axis, direction)
        else:
            self.jogStep.emit(axis, self.step, direction)

    def _released(self, axis: str) -> None:
        if axis in self._held:
            self._held.discard(axis)
            self.jogStop.emit(axis)

    def release_all(self) -> None:
        """Safe release: stop every continuous jog (page hidden, focus lost, window closed)."""
        if self._held:
            self._held.clear()
            self.jogStop.emit("")

    def hideEvent(self, event) -> None:  # noqa: N802 - Qt override
        self.release_all()
        super().hideEvent(event)
