"""Digital read-out: machine and work coordinates per axis in large digits, homed marks."""

from __future__ import annotations

import math
from collections.abc import Sequence

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QGridLayout, QLabel, QWidget

from app.i18n import N_, I18n


def format_position(value: float, rotary: bool = False) -> str:
    """Signed, fixed width: mm with 3 decimals, degrees with 3 (rotary) and a unit-free look."""
    if not math.isfinite(value):
        return "---.---"
    text = f"{value:+.3f}"
    return "+0.000" if text == "-0.000" else text


class DroWidget(QWidget):
    def __init__(self, axes: Sequence[str], rotary: Sequence[bool] | None = None,
                 i18n: I18n | None = None, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("dro")
        self.axes = tuple(axes)
        self.rotary = tuple(rotary) if rotary is not None else (False,) * len(self.axes)
        grid = QGridLayout(self)
        grid.setContentsMargins(6, 2, 6, 2)
        grid.setHorizontalSpacing(10)
        grid.setVerticalSpacing(0)
        head_work, head_machine = QLabel(), QLabel()
        for row, (label, text) in enumerate(((head_work, N_("Work")), (head_machine, N_("Machine"))),
                                            start=1):
            label.setObjectName("droHeader")
            if i18n is not None:
                i18n.bind(label, text)
            else:
                label.setText(text)
            grid.addWidget(label, row, 0)
        self.work_labels: list[QLabel] = []
        self.machine_labels: list[QLabel] = []
        self.axis_labels: list[QLabel] = []
        for col, name in enumerate(self.axes, start=1):
            axis = QLabel(name)
            axis.setObjectName("droAxis")
            axis.setAlignment(Qt.AlignmentFlag.AlignCenter)
            work = QLabel()
            work.setObjectName("droValue")
            machine = QLabel()
            machine.setObjectName("droMachine")
            for lab in (work, machine):
                lab.setAlignment(Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter)
            work.setMinimumWidth(150)
            grid.addWidget(axis, 0, col)
            grid.addWidget(work, 1, col)
            grid.addWidget(machine, 2, col)
            self.axis_labels.append(axis)
            self.work_labels.append(work)
            self.machine_labels.append(machine)
        self.set_positions([0.0] * len(self.axes), [0.0] * len(self.axes))
        self.set_homed([False] * len(self.axes))

    def set_positions(self, machine: Sequence[float], work: Sequence[float]) -> None:
        for i, rot in enumerate(self.rotary):
            w, m = format_position(float(work[i]), rot), format_position(float(machine[i]), rot)
            if self.work_labels[i].text() != w:
                self.work_labels[i].setText(w)
            if self.machine_labels[i].text() != m:
                self.machine_labels[i].setText(m)

    def set_homed(self, homed: Sequence[bool]) -> None:
        for label, name, ok in zip(self.axis_labels, self.axes, homed):
            label.setText(f"{name} ✓" if ok else f"{name} ?")
            label.setProperty("homed", bool(ok))
            label.setToolTip("")

    def work_text(self, axis: str) -> str:
        return self.work_labels[self.axes.index(axis)].text()

    def machine_text(self, axis: str) -> str:
        return self.machine_labels[self.axes.index(axis)].text()
