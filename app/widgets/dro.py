"""Digital read-out: machine and work coordinates per axis in large digits, homed marks."""

from __future__ import annotations

import math
from collections.abc import Sequence

from PySide6.QtCore import QEvent, QObject, Qt
from PySide6.QtWidgets import QGridLayout, QLabel, QWidget

from app.i18n import N_, I18n, tr
from planner.core.frames import Frame


def format_position(value: float, rotary: bool = False, wrapped: bool = False) -> str:
    """Signed, fixed width: mm with 3 decimals (no unit: the DRO's linear axes all read mm),
    degrees with 3 and their sign (rotary: "+12.345°", never read as mm); a wrapped rotary axis
    (turning without end) reads modulo 360, in [0, 360)."""
    if not math.isfinite(value):
        return "---.---"
    if wrapped:
        value = value % 360.0
        if value >= 359.9995:       # shown to 3 decimals: 359.9999 reads as 0.000, not 360.000
            value = 0.0
    text = f"{value:+.3f}"
    text = "+0.000" if text == "-0.000" else text
    return text + "°" if rotary else text


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
        head_work = QLabel()
        head_work.setObjectName("droHeader")
        if i18n is not None:
            i18n.bind(head_work, N_("Work"))
        else:
            head_work.setText(N_("Work"))
        grid.addWidget(head_work, 1, 0)
        # the second row: Machine (G53) or the distance to go of the move being run; a tap on
        # the row (its title or any of its values) switches, and the header keeps its height
        self.second_button = QLabel()
        self.second_button.setObjectName("droHeader")
        self.second_button.installEventFilter(self)
        grid.addWidget(self.second_button, 2, 0)
        self._i18n = i18n
        self.show_to_go = False
        self._machine: tuple[float, ...] = (0.0,) * len(self.axes)
        self._to_go: tuple[float, ...] = ()
        if i18n is not None:
            i18n.languageChanged.connect(lambda _l: self._second_title())
            i18n.languageChanged.connect(lambda _l: self.set_frame(self._frame))   # said anew
        self._second_title()
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
            machine.installEventFilter(self)
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

    def _second_title(self) -> None:
        text = N_("To go") if self.show_to_go else N_("Machine")
        self.second_button.setText(tr(text))

    def eventFilter(self, obj: QObject, event: QEvent) -> bool:  # noqa: N802 - Qt override
        if event.type() == QEvent.Type.MouseButtonRelease and (
                obj is self.second_button or obj in self.machine_labels):
            self.toggle_second_row()
            return True
        return super().eventFilter(obj, event)

    def toggle_second_row(self) -> None:
        """Machine (G53) <-> distance to go, on the second row."""
        self.show_to_go = not self.show_to_go
        self._second_title()
        self._show_second()

    def set_distance_to_go(self, left: Sequence[float]) -> None:
        """What is left of the move being run per axis (empty at rest: shown as zero)."""
        self._to_go = tuple(float(v) for v in left)
        if self.show_to_go:
            self._show_second()

    def _show_second(self) -> None:
        values = self._machine if not self.show_to_go else (self._to_go or (0.0,) * len(self.axes))
        for i, (rot, wrap) in enumerate(zip(self.rotary, self.wrapped)):
            # distance to go is a difference: never read modulo 360
            text = format_position(float(values[i]), rot, wrap and not self.show_to_go)
            if self.machine_labels[i].text() != text:
                self.machine_labels[i].setText(text)

    def set_positions(self, machine: Sequence[float], work: Sequence[float]) -> None:
        self._machine = tuple(float(v) for v in machine)
        for i, (rot, wrap) in enumerate(zip(self.rotary, self.wrapped)):
            w = format_position(float(work[i]), rot, wrap)
            if self.work_labels[i].text() != w:
                self.work_labels[i].setText(w)
        self._show_second()

    def set_homed(self, homed: Sequence[bool]) -> None:
        for label, name, ok in zip(self.axis_labels, self.axes, homed):
            label.setText(f"{name} ✓" if ok else f"{name} ?")
            label.setProperty("homed", bool(ok))
            label.setToolTip("")

    def work_text(self, axis: str) -> str:
        return self.work_labels[self.axes.index(axis)].text()

    def machine_text(self, axis: str) -> str:
        return self.machine_labels[self.axes.index(axis)].text()
