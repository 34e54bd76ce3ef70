"""Digital read-out: machine and work coordinates per axis in large digits, homed marks."""

from __future__ import annotations

import math
from collections.abc import Sequence

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QGridLayout, QLabel, QWidget

from app.i18n import N_, I18n, tr
from planner.core.frames import Frame


def format_position(value: float, rotary: bool = False, wrapped: bool = False) -> str:
    """Signed, fixed width: mm with 3 decimals, degrees with 3 (rotary) and a unit-free look; a
    wrapped rotary axis (turning without end) reads modulo 360, in [0, 360)."""
    if not math.isfinite(value):
        return "---.---"
    if wrapped:
        value = value % 360.0
        if value >= 359.9995:       # shown to 3 decimals: 359.9999 reads as 0.000, not 360.000
            value = 0.0
    text = f"{value:+.3f}"
    return "+0.000" if text == "-0.000" else text


def frame_text(frame: Frame) -> str:
    """What the Work DRO includes, in the operator's words: "Work = G54 · G92 · XY turned 30° ·
    tool T2 length -12.500 mm"."""
    parts = [frame.system_name]
    if frame.has_g92:
        parts.append("G92")
    if frame.rotation_deg:
        parts.append(tr("XY turned {0:g}°").format(frame.rotation_deg))
    if frame.has_tool_offset:
        z = frame.tool[frame.axes.index("Z")] if "Z" in frame.axes else 0.0
        tool = f"T{frame.tool_number} " if frame.tool_number else ""
        parts.append(tr("tool {0}length {1} mm").format(tool, format_position(z)))
    else:
        parts.append(tr("no tool length offset"))
    return tr("Work = tool tip in {0}").format(" · ".join(parts))


class DroWidget(QWidget):
    def __init__(self, axes: Sequence[str], rotary: Sequence[bool] | None = None,
                 i18n: I18n | None = None, parent: QWidget | None = None,
                 wrapped: Sequence[bool] | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("dro")
        self.axes = tuple(axes)
        self.rotary = tuple(rotary) if rotary is not None else (False,) * len(self.axes)
        self.wrapped = tuple(wrapped) if wrapped is not None else (False,) * len(self.axes)
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
        # what the Work row includes (system, G92, rotation, tool length offset): one line of
        # its own, its height fixed, so that a change never moves the digits
        self.frame_label = QLabel()
        self.frame_label.setObjectName("droFrame")
        self.frame_label.setFixedHeight(self.frame_label.fontMetrics().height() + 4)
        grid.addWidget(self.frame_label, 3, 0, 1, len(self.axes) + 1)
        self._frame: Frame | None = None
        self.set_positions([0.0] * len(self.axes), [0.0] * len(self.axes))
        self.set_homed([False] * len(self.axes))

    def set_frame(self, frame: Frame | None) -> None:
        """The offsets the Work row reads the tool tip in."""
        self._frame = frame
        self.frame_label.setText(frame_text(frame) if frame is not None else "")

    def set_positions(self, machine: Sequence[float], work: Sequence[float]) -> None:
        for i, (rot, wrap) in enumerate(zip(self.rotary, self.wrapped)):
            w = format_position(float(work[i]), rot, wrap)
            m = format_position(float(machine[i]), rot, wrap)
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
