"""Preview: the tool path drawn (arcs turquoise, lines green, rapids dashed) in work
coordinates with the work zero and the machine's travel, plane views and a 3-D view (turned by
touch buttons), fit, live tool position and executed part (Clear empties it), tap to pick a line."""

from __future__ import annotations

import numpy as np
from PySide6.QtWidgets import QHBoxLayout, QLabel, QPushButton, QVBoxLayout, QWidget

from app.context import PanelContext
from app.i18n import N_, tr
from app.widgets.preview_plot import PLANES, VIEW_3D, PreviewPlot, usable_planes
from app.widgets.touch import exclusive_buttons


class PreviewPage(QWidget):
    plot: PreviewPlot

    def __init__(self, context: PanelContext, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("previewPage")
        self.ctx = context
        i18n = context.i18n
        layout = QVBoxLayout(self)
        bar = QHBoxLayout()
        self.plane_group, self.plane_buttons = exclusive_buttons(
            self, bar, ((plane, QPushButton(plane)) for plane in (*PLANES, VIEW_3D)), self.set_plane)
        self.view3d_button = self.plane_buttons[VIEW_3D]
        self.turn_button = QPushButton("⟳ 45°")       # turn the 3-D view about Z
        self.turn_button.clicked.connect(lambda: self.plot.rotate(45.0))
        self.tilt_button = QPushButton("⤒ 15°")       # look from higher up (to the top view)
        self.tilt_button.clicked.connect(lambda: self.plot.rotate(0.0, 15.0 if self.plot.elevation_deg < 90
                                                                  else -90.0))
        bar.addWidget(self.turn_button)
        bar.addWidget(self.tilt_button)
        self.fit_button = QPushButton()
        i18n.bind(self.fit_button, N_("Fit"))
        bar.addWidget(self.fit_button)
        self.show_line_button = QPushButton()
        i18n.bind(self.show_line_button, N_("Show in program"))
        self.show_line_button.setEnabled(False)
        bar.addWidget(self.show_line_button)
        self.clear_button = QPushButton()
        i18n.bind(self.clear_button, N_("Clear"))
        bar.addWidget(self.clear_button)
        bar.addStretch(1)
        layout.addLayout(bar)
        self.note = QLabel()
        self.note.setObjectName("previewNote")
        self.note.setWordWrap(True)
        layout.addWidget(self.note)
        self.plot = PreviewPlot()
        layout.addWidget(self.plot, 1)
        self.line_label = QLabel()
        self.line_label.setObjectName("pickedLine")
        layout.addWidget(self.line_label)

        self._picked_line = 0
        self.fit_button.clicked.connect(self.plot.fit)
        self.clear_button.clicked.connect(self.plot.clear_backplot)
        self.show_line_button.clicked.connect(
            lambda: context.program.lineRequested.emit(self._picked_line))
        self.plot.moveTapped.connect(self._on_tapped)
        context.program.changed.connect(self._on_program)
        context.controller.positionChanged.connect(self._on_position)
        context.controller.offsetsChanged.connect(lambda *_: self._update_frame())
        context.controller.lineChanged.connect(self._on_line)
        context.controller.programFinished.connect(self._on_finished)
        usable = usable_planes(context.controller.axes)
        for plane, button in self.plane_buttons.items():
            button.setEnabled(plane in usable or not usable or plane == VIEW_3D)
        i18n.languageChanged.connect(lambda _l: self._update_frame())
        self.set_plane(usable[0] if usable else "XY")  # e.g. YZ on the paper's Y-Z-C-A machine
        self._on_program()

    def set_plane(self, plane: str) -> None:
        self.plane_buttons[plane].setChecked(True)
        self.plot.set_plane(plane)
        self.turn_button.setEnabled(plane == VIEW_3D)
        self.tilt_button.setEnabled(plane == VIEW_3D)

    def _on_position(self, _machine: object, work: object) -> None:
        """The tool where the DRO reads it: the machine position through the offsets in force
        (``Frame``: while a program runs, its frame at the move being run, through which that
        move is drawn), so the tool sits on the path it is cutting."""
        pos = self.ctx.controller.work_position if work is None else work
        self.plot.set_tool_position(np.asarray(pos, float))

    def _update_frame(self) -> None:
        """The machine's travel in the active work coordinates, and the note saying so."""
        c = self.ctx.controller
        axes = c.config.machine.axes
        offset = np.asarray(c.work_offsets.get(c.active_offset, (0.0,) * len(axes)), float)
        lo = np.array([a.min_pos for a in axes]) - offset
        hi = np.array([a.max_pos for a in axes]) - offset
        self.plot.set_envelope(lo, hi)
        self.note.setText(tr("Work coordinates ({0}): the cross is the work zero, the dashed box the "
                             "machine's travel.").format(c.active_offset))

    def _on_program(self) -> None:
        self.plot.set_toolpath(self.ctx.program.toolpath)
        self._update_frame()
        self._on_position(None, None)
        self.line_label.setText("")
        self.show_line_button.setEnabled(False)

    def _on_line(self, line: int) -> None:
        if line > 0:
            self.plot.set_executed(self.ctx.program.move_at_line(line), self.ctx.controller.run_first_move)

    def _on_finished(self, summary: object) -> None:
        if getattr(summary, "completed", False) and self.plot.path is not None:
            self.plot.set_executed(len(self.plot.path.move_lines), self.ctx.controller.run_first_move)

    def _on_tapped(self, _index: int, line: int) -> None:
        self._picked_line = line
        text = self.ctx.program.line(line).strip()
        self.line_label.setText(tr("Line {0}: {1}").format(line, text))
        self.show_line_button.setEnabled(True)


def create_page(context: PanelContext) -> QWidget:
    return PreviewPage(context)
