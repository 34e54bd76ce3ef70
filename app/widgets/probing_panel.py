"""The probing wizards at the panel (the Part zero page's Probe tab): pick what to find by its
picture, say where the part is from the probe and which coordinate system takes the result,
see the moves drawn as they will run, then run them.

The moves are the controller's: every change of an input asks it for the wizard's routine read
and checked (``preview_probing``) and draws that, or shows why it cannot run; Run starts the
same routine (``run_probing``), and what it found comes back with ``probingFinished``.
"""

from __future__ import annotations

import math

import numpy as np
from PySide6.QtCore import QPointF, QRectF, QSize, Qt
from PySide6.QtGui import QColor, QIcon, QPainter, QPainterPath, QPaintEvent, QPen, QPixmap, QShowEvent
from PySide6.QtWidgets import (
    QButtonGroup,
    QGridLayout,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QSizePolicy,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from app.context import PanelContext
from app.controller_text import localize
from app.i18n import N_, tr
from app.machine.model import (
    WIZARD,
    WIZARDS,
    CommandResult,
    ProbeWizard,
    ProbingRequest,
    ProbingResult,
    WizardAim,
)
from app.widgets.numeric_field import NumericField
from app.widgets.touch import exclusive_buttons
from planner.core.machine import WORK_OFFSET_NAMES
from planner.core.program import Program

__all__ = ["ProbingPanel", "RoutinePreview", "wizard_icon"]

# which way: an edge or a face as the direction the probe moves (axis, sign); a corner as where
# the part (outside) or the walls (inside) are from the probe (x sign, y sign)
MOVES = (("X", 1, "X+"), ("X", -1, "X-"), ("Y", 1, "Y+"), ("Y", -1, "Y-"))
CORNERS = ((1, 1, "X+ Y+"), (-1, 1, "X- Y+"), (1, -1, "X+ Y-"), (-1, -1, "X- Y-"))
REPORT_ONLY = ""
ICON_PX = 48


class ProbingPanel(QWidget):
    def __init__(self, context: PanelContext, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("probingPanel")
        self.ctx = context
        c = context.controller
        i18n = context.i18n
        probe = c.config.probe
        outer = QVBoxLayout(self)
        # what to find, by its picture
        row = QHBoxLayout()
        choices: list[tuple[ProbeWizard, QToolButton]] = []
        for spec in WIZARDS:
            wizard = spec.wizard
            b = QToolButton()
            b.setObjectName("wizardButton")
            b.setToolButtonStyle(Qt.ToolButtonStyle.ToolButtonTextUnderIcon)
            b.setIcon(QIcon(wizard_icon(wizard, ICON_PX)))
            b.setIconSize(QSize(ICON_PX, ICON_PX))
            b.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Preferred)
            i18n.bind(b, spec.title)
            choices.append((wizard, b))
        self.wizard_group, self.wizard_buttons = exclusive_buttons(self, row, choices, self._choose)
        outer.addLayout(row)
        body = QHBoxLayout()
        outer.addLayout(body, 1)
        left = QVBoxLayout()
        body.addLayout(left, 3)
        # which way
        self.direction_label = QLabel()
        left.addWidget(self.direction_label)
        way = QHBoxLayout()
        self.move_group, self.move_buttons = exclusive_buttons(
            self, way, ((k, QPushButton(k)) for _a, _s, k in MOVES), lambda _k: self.refresh())
        self.corner_group, self.corner_buttons = exclusive_buttons(
            self, way, ((k, QPushButton(k)) for _x, _y, k in CORNERS), lambda _k: self.refresh())
        self.move_buttons["X+"].setChecked(True)
        self.corner_buttons["X+ Y+"].setChecked(True)
        left.addLayout(way)
        # the numbers, with [probe]'s defaults, two to a row
        self.form = form = QGridLayout()
        form.setColumnStretch(1, 1)
        form.setColumnStretch(3, 1)
        left.addLayout(form)
        left.addStretch(1)
        self.result = QLabel()                   # what the last run found
        self.result.setWordWrap(True)
        self.result.setObjectName("probingResult")
        left.addWidget(self.result)
        ask = context.dialogs.ask_number
        self.fields: dict[str, NumericField] = {}
        self.labels: dict[str, QLabel] = {}
        specs = (
            ("diameter", N_("Diameter as expected"), 20.0, 0.1, 1000.0, "mm"),
            ("tolerance", N_("Diameter tolerance"), 0.5, 0.001, 100.0, "mm"),
            ("depth", N_("Depth below the start"), 5.0, 0.1, 500.0, "mm"),
            ("along", N_("Distance along the faces"), 10.0, 0.1, 1000.0, "mm"),
            ("search", N_("Search distance"), probe.search_mm, 0.1, 1000.0, "mm"),
            ("clearance", N_("Clearance"), probe.clearance_mm, 0.1, 1000.0, "mm"),
            ("fast", N_("Fast probe feed"), probe.fast_feed_mm_min, 1.0, probe.max_feed_mm_min, "mm/min"),
            ("slow", N_("Slow probe feed"), probe.slow_feed_mm_min, 0.1, probe.max_feed_mm_min, "mm/min"),
            ("x", N_("X reads after"), 0.0, -1e6, 1e6, "mm"),
            ("y", N_("Y reads after"), 0.0, -1e6, 1e6, "mm"),
            ("z", N_("Z reads after"), 0.0, -1e6, 1e6, "mm"),
        )
        for key, text, value, lo, hi, unit in specs:
            field = NumericField(tr(text), value, lo, hi, 3, unit, ask=ask, parent=self)
            field.valueChanged.connect(lambda _v: self.refresh())
            label = QLabel(self)
            label.setWordWrap(True)
            label.setMaximumWidth(150)
            i18n.bind(label, text)
            self.fields[key], self.labels[key] = field, label
        # which system takes the result
        # the moves as they will run, which system takes the result, why not, what was found
        right = QVBoxLayout()
        body.addLayout(right, 2)
        self.preview = RoutinePreview()
        right.addWidget(self.preview, 1)
        self.target_label = QLabel()
        i18n.bind(self.target_label, N_("Write the result to:"))
        right.addWidget(self.target_label)
        grid = QGridLayout()
        self.target_group = QButtonGroup(self)
        self.target_buttons: dict[str, QPushButton] = {}
        for k, name in enumerate((*WORK_OFFSET_NAMES, REPORT_ONLY)):
            target = QPushButton(name)
            if name == REPORT_ONLY:
                i18n.bind(target, N_("Only report"))
            target.setCheckable(True)
            self.target_group.addButton(target)
            target.clicked.connect(lambda _=False: self.refresh())
            grid.addWidget(target, k // 4, k % 4, 1, 2 if name == REPORT_ONLY else 1)
            self.target_buttons[name] = target
        right.addLayout(grid)
        active = c.active_offset
        self.target_buttons.get(active, self.target_buttons["G54"]).setChecked(True)
        self.status = QLabel()
        self.status.setWordWrap(True)
        self.status.setObjectName("probingStatus")
        # three lines, fixed: a shorter or longer reason never moves the buttons around it (the
        # whole text in the tooltip)
        self.status.ensurePolished()
        self.status.setFixedHeight(self.status.fontMetrics().lineSpacing() * 3 + 4)
        right.addWidget(self.status)
        self.run_button = QPushButton()
        self.run_button.setObjectName("probingRun")
        self.run_button.setMinimumHeight(56)
        i18n.bind(self.run_button, N_("Run the probing"))
        self.run_button.clicked.connect(self.run)
        right.addWidget(self.run_button)
        self._why = ""
        self.wizard_buttons[WIZARDS[0].wizard].setChecked(True)
        c.probingFinished.connect(self._finished)
        c.stateChanged.connect(lambda *_: self.refresh())
        c.toolsChanged.connect(lambda *_: self.refresh())
        c.offsetsChanged.connect(lambda *_: self.refresh())
        i18n.languageChanged.connect(lambda *_: self._show_texts())
        self._choose(WIZARDS[0].wizard)

    # ------------------------------------------------------------------ the request
    def wizard(self) -> ProbeWizard:
        return next(w for w, b in self.wizard_buttons.items() if b.isChecked())

    def request(self) -> ProbingRequest:
        wizard = self.wizard()
        f = {k: v.value() for k, v in self.fields.items()}
        move = next(m for m in MOVES if self.move_buttons[m[2]].isChecked())
        corner = next(m for m in CORNERS if self.corner_buttons[m[2]].isChecked())
        target = next(name for name, b in self.target_buttons.items() if b.isChecked())
        corners = WIZARD[wizard].aim is WizardAim.CORNER
        axis, sign = move[0], move[1]
        return ProbingRequest(
            wizard, system=target, axis=axis,
            x_dir=corner[0] if corners else sign, y_dir=corner[1] if corners else sign,
            diameter_mm=f["diameter"], tolerance_mm=f["tolerance"], depth_mm=f["depth"], along_mm=f["along"],
            value=(f["x"], f["y"], f["z"]), search_mm=f["search"], clearance_mm=f["clearance"],
            fast_feed_mm_min=f["fast"], slow_feed_mm_min=f["slow"])

    def _uses(self, wizard: ProbeWizard) -> set[str]:
        """The inputs ``wizard`` takes (one that reads one coordinate: the one of the axis it
        probes along)."""
        spec = WIZARD[wizard]
        uses = set(spec.inputs) | {"search", "clearance", "fast", "slow"}
        if spec.one_value:
            uses -= {"y"} if self._move()[0] == "X" else {"x"}
        return uses

    def _choose(self, wizard: ProbeWizard) -> None:
        """Show the inputs ``wizard`` takes."""
        uses = self._uses(wizard)
        self._place_fields(uses)
        moves = WIZARD[wizard].aim is WizardAim.ALONG_AXIS
        corners = WIZARD[wizard].aim is WizardAim.CORNER
        for b in self.move_buttons.values():
            b.setVisible(moves)
        for b in self.corner_buttons.values():
            b.setVisible(corners)
        self.direction_label.setVisible(moves or corners)
        self.target_buttons[REPORT_ONLY].setVisible(True)
        self._show_texts()
        self.refresh()

    def _place_fields(self, uses: set[str]) -> None:
        """The fields ``uses`` names, two to a row, each with its label before it; the rest hidden."""
        for key, field in self.fields.items():
            self.form.removeWidget(field)
            self.form.removeWidget(self.labels[key])
        for k, key in enumerate(key for key in self.fields if key in uses):
            self.form.addWidget(self.labels[key], k // 2, 2 * (k % 2))
            self.form.addWidget(self.fields[key], k // 2, 2 * (k % 2) + 1)
        for key, field in self.fields.items():  # after the layout took them: a parent shows them
            field.setVisible(key in uses)
            self.labels[key].setVisible(key in uses)

    def _move(self) -> tuple[str, int, str]:
        return next(m for m in MOVES if self.move_buttons[m[2]].isChecked())

    def _show_texts(self) -> None:
        spec = WIZARD[self.wizard()]
        self.direction_label.setText(tr(spec.prompt) if spec.prompt else "")
        self.fields["along"].title = tr(spec.along_title or N_("Distance along the faces"))
        self.labels["along"].setText(self.fields["along"].title)
        self._show_status()

    # ------------------------------------------------------------------ preview and run
    def showEvent(self, event: QShowEvent) -> None:  # noqa: N802 - Qt override
        super().showEvent(event)
        self.refresh()

    def refresh(self) -> None:
        """Ask the controller for the moves of what is set now and draw them (or say why not);
        hidden, nothing is read (the tab shown reads again)."""
        if not self.isVisible():
            return
        wizard = self.wizard()
        if WIZARD[wizard].one_value and self.fields["x"].isHidden() == (self._move()[0] == "X"):
            self._place_fields(self._uses(wizard))     # the axis it probes along changed
        req = self.request()
        c = self.ctx.controller
        if c.state.value != "idle":
            self._why = tr("Probing starts with the machine idle.")
            self.preview.set_program(None)
        else:
            got = c.preview_probing(req)
            if isinstance(got, CommandResult):
                self._why = localize(got.reason)
                self.preview.set_program(None)
            else:
                self._why = ""
                self.preview.set_program(got)
        self.run_button.setEnabled(not self._why)
        self._show_status()

    def _show_status(self) -> None:
        self._set_status(self._status_text())

    def _set_status(self, text: str) -> None:
        self.status.setText(text)
        self.status.setToolTip(text)

    def _status_text(self) -> str:
        if self._why:
            return tr("Cannot run: {0}").format(self._why)
        else:
            target = self.request().system
            if target:
                return tr("The moves drawn run when you press Run; the result goes to {0}.").format(target)
            return tr("The moves drawn run when you press Run; the result is only reported.")

    def run(self) -> None:
        req = self.request()
        self.result.setText("")
        res = self.ctx.controller.run_probing(req)
        if not res:
            self._why = localize(res.reason)
            self._show_status()

    def _finished(self, result: object) -> None:
        if not isinstance(result, ProbingResult):
            return
        said = result.said(tr("diameter"), tr("angle"))
        self.result.setText(tr("Found (machine): {0}; written to {1}").format(said, result.written)
                            if result.written else tr("Found (machine): {0} (only reported)").format(said))


class RoutinePreview(QWidget):
    """A probing routine's moves seen from above (XY) and from the front (XZ): positioning in
    blue, probe moves in yellow, the start as a dot."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("routinePreview")
        self.setMinimumSize(200, 80)          # it gives the status its three lines at 800 px
        self.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Expanding)
        self.points: np.ndarray = np.zeros((0, 3))
        self.probe_moves: set[int] = set()

    def set_program(self, program: Program | None) -> None:
        if program is None or not len(program.moves):
            self.points = np.zeros((0, 3))
            self.probe_moves = set()
        else:
            ends = [np.asarray(m.end[:3], dtype=float) for m in program.moves]
            self.points = np.vstack([np.asarray(program.start_position[:3], dtype=float), *ends])
            self.probe_moves = {p.move_index for p in program.probes if p.code == 382}
        self.update()

    def paintEvent(self, event: QPaintEvent) -> None:  # noqa: N802 - Qt override
        painter = QPainter(self)
        painter.setRenderHint(QPainter.RenderHint.Antialiasing)
        painter.fillRect(self.rect(), QColor("#0a0d10"))
        if len(self.points) < 2:
            painter.setPen(QColor("#7f8a94"))
            painter.drawText(self.rect(), Qt.AlignmentFlag.AlignCenter, tr("No moves to draw"))
            return
        split = self.height() * 0.68                # from above gets the most room
        for top, bottom, ia, ib, title in ((0.0, split, 0, 1, "XY"), (split, self.height(), 0, 2, "XZ")):
            self._view(painter, QRectF(8, top + 4, self.width() - 16, bottom - top - 8), ia, ib, title)

    def _view(self, painter: QPainter, box: QRectF, ia: int, ib: int, title: str) -> None:
        pts = self.points[:, [ia, ib]]
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        span = max(float(np.max(hi - lo)), 1.0)
        scale = min(box.width(), box.height() - 16) / span
        centre = (lo + hi) / 2.0

        def at(p: np.ndarray) -> QPointF:
            return QPointF(box.center().x() + (p[0] - centre[0]) * scale,
                           box.center().y() + 8 - (p[1] - centre[1]) * scale)

        painter.setPen(QColor("#7f8a94"))
        painter.drawText(box.topLeft() + QPointF(2, 12), title)
        for probes in (False, True):             # the probe moves over the positioning
            for i in range(1, len(pts)):
                if ((i - 1) in self.probe_moves) is probes:
                    painter.setPen(QPen(QColor("#ffd27f" if probes else "#40a0ff"), 3 if probes else 2))
                    painter.drawLine(at(pts[i - 1]), at(pts[i]))
        painter.setBrush(QColor("#4cdf6a"))
        painter.setPen(Qt.PenStyle.NoPen)
        painter.drawEllipse(at(pts[0]), 5, 5)


def wizard_icon(wizard: ProbeWizard, size: int) -> QPixmap:
    """A picture of what the wizard finds: the part in grey, the probe's moves as arrows."""
    pix = QPixmap(size, size)
    pix.fill(QColor(0, 0, 0, 0))
    p = QPainter(pix)
    p.setRenderHint(QPainter.RenderHint.Antialiasing)
    s = size / 48.0
    part, arrow = QColor("#8a949e"), QColor("#ffd27f")
    p.setPen(Qt.PenStyle.NoPen)
    p.setBrush(part)

    def arrow_to(x0: float, y0: float, x1: float, y1: float) -> None:
        p.setPen(QPen(arrow, 3 * s))
        p.drawLine(QPointF(x0 * s, y0 * s), QPointF(x1 * s, y1 * s))
        a = math.atan2(y1 - y0, x1 - x0)
        head = QPainterPath(QPointF(x1 * s, y1 * s))
        for da in (2.6, -2.6):
            head.lineTo(QPointF((x1 + 7 * math.cos(a + da)) * s, (y1 + 7 * math.sin(a + da)) * s))
        head.closeSubpath()
        p.setPen(Qt.PenStyle.NoPen)
        p.setBrush(arrow)
        p.drawPath(head)
        p.setBrush(part)

    if wizard is ProbeWizard.Z_SURFACE:
        p.drawRect(QRectF(6 * s, 30 * s, 36 * s, 14 * s))
        arrow_to(24, 4, 24, 27)
    elif wizard is ProbeWizard.EDGE:
        p.drawRect(QRectF(26 * s, 8 * s, 18 * s, 32 * s))
        arrow_to(3, 24, 23, 24)
    elif wizard is ProbeWizard.OUTSIDE_CORNER:
        p.drawRect(QRectF(20 * s, 4 * s, 24 * s, 24 * s))
        arrow_to(2, 12, 17, 12)
        arrow_to(32, 46, 32, 31)
    elif wizard is ProbeWizard.INSIDE_CORNER:
        path = QPainterPath()
        path.addRect(QRectF(2 * s, 2 * s, 44 * s, 44 * s))
        hole = QPainterPath()
        hole.addRect(QRectF(2 * s, 14 * s, 32 * s, 32 * s))
        p.drawPath(path.subtracted(hole))
        arrow_to(14, 34, 31, 34)
        arrow_to(14, 34, 14, 17)
    elif wizard is ProbeWizard.BORE:
        path = QPainterPath()
        path.addRect(QRectF(2 * s, 2 * s, 44 * s, 44 * s))
        hole = QPainterPath()
        hole.addEllipse(QPointF(24 * s, 24 * s), 17 * s, 17 * s)
        p.drawPath(path.subtracted(hole))
        for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            arrow_to(24 + 3 * dx, 24 + 3 * dy, 24 + 14 * dx, 24 + 14 * dy)
    elif wizard is ProbeWizard.BOSS:
        p.drawEllipse(QPointF(24 * s, 24 * s), 12 * s, 12 * s)
        for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            arrow_to(24 + 23 * dx, 24 + 23 * dy, 24 + 14 * dx, 24 + 14 * dy)
    else:
        path = QPainterPath(QPointF(4 * s, 30 * s))
        path.lineTo(QPointF(44 * s, 20 * s))
        path.lineTo(QPointF(44 * s, 46 * s))
        path.lineTo(QPointF(4 * s, 46 * s))
        path.closeSubpath()
        p.drawPath(path)
        arrow_to(12, 6, 12, 25)
        arrow_to(36, 4, 36, 19)
    p.end()
    return pix

