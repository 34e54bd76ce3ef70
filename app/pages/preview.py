"""Preview: the tool path drawn (arcs turquoise, lines green, rapids dashed), plane views,
3-D where OpenGL is available, fit, live tool position and executed part, tap to pick a line."""

from __future__ import annotations

import importlib.util

from PySide6.QtWidgets import QHBoxLayout, QLabel, QPushButton, QVBoxLayout, QWidget

from app.context import PanelContext
from app.i18n import N_, tr
from app.widgets.preview_plot import PLANES, PreviewPlot
from app.widgets.touch import exclusive_buttons


def opengl_available() -> bool:
    """pyqtgraph's 3-D view needs PyOpenGL; without it the 3-D button says why it is off."""
    return importlib.util.find_spec("OpenGL") is not None


class PreviewPage(QWidget):
    def __init__(self, context: PanelContext, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("previewPage")
        self.ctx = context
        i18n = context.i18n
        layout = QVBoxLayout(self)
        bar = QHBoxLayout()
        self.plane_group, self.plane_buttons = exclusive_buttons(
            self, bar, ((plane, QPushButton(plane)) for plane in PLANES), self.set_plane)
        self.view3d_button = QPushButton("3-D")
        self.view3d_button.setEnabled(False)  # no 3-D without PyOpenGL (see note)
        bar.addWidget(self.view3d_button)
        self.fit_button = QPushButton()
        i18n.bind(self.fit_button, N_("Fit"))
        bar.addWidget(self.fit_button)
        self.show_line_button = QPushButton()
        i18n.bind(self.show_line_button, N_("Show in program"))
        self.show_line_button.setEnabled(False)
        bar.addWidget(self.show_line_button)
        bar.addStretch(1)
        layout.addLayout(bar)
        self.note = QLabel()
        self.note.setObjectName("previewNote")
        self.note.setWordWrap(True)
        if not opengl_available():
            i18n.bind(self.note, N_("3-D view off: PyOpenGL is not installed (pip install PyOpenGL)."))
        layout.addWidget(self.note)
        self.plot = PreviewPlot()
        layout.addWidget(self.plot, 1)
        self.line_label = QLabel()
        self.line_label.setObjectName("pickedLine")
        layout.addWidget(self.line_label)

        self._picked_line = 0
        self.fit_button.clicked.connect(self.plot.fit)
        self.show_line_button.clicked.connect(
            lambda: context.program.lineRequested.emit(self._picked_line))
        self.plot.moveTapped.connect(self._on_tapped)
        context.program.changed.connect(self._on_program)
        context.controller.positionChanged.connect(
            lambda machine, _work: self.plot.set_tool_position(machine))
        context.controller.lineChanged.connect(self._on_line)
        context.controller.programFinished.connect(self._on_finished)
        axes = set(context.controller.axes)
        usable = [p for p, (a, b) in PLANES.items() if a in axes and b in axes]
        for plane, button in self.plane_buttons.items():
            button.setEnabled(plane in usable or not usable)
        self.set_plane(usable[0] if usable else "XY")  # e.g. YZ on the paper's Y-Z-C-A machine
        self._on_program()

    def set_plane(self, plane: str) -> None:
        self.plane_buttons[plane].setChecked(True)
        self.plot.set_plane(plane)

    def _on_program(self) -> None:
        self.plot.set_toolpath(self.ctx.program.toolpath)
        self.plot.set_tool_position(self.ctx.controller.machine_position)
        self.line_label.setText("")
        self.show_line_button.setEnabled(False)

    def _on_line(self, line: int) -> None:
        if line > 0:
            self.plot.set_executed(self.ctx.program.move_at_line(line))

    def _on_finished(self, summary: object) -> None:
        if getattr(summary, "completed", False) and self.plot.path is not None:
            self.plot.set_executed(len(self.plot.path.move_lines))

    def _on_tapped(self, _index: int, line: int) -> None:
        self._picked_line = line
        lines = self.ctx.program.text.splitlines()
        text = lines[line - 1].strip() if 0 < line <= len(lines) else ""
        self.line_label.setText(tr("Line {0}: {1}").format(line, text))
        self.show_line_button.setEnabled(True)


def create_page(context: PanelContext) -> QWidget:
    return PreviewPage(context)
