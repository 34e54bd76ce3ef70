"""Production: the part counter and its target, the running program's expected end, and the
run log (newest first), exported where the operator saves programs."""

from __future__ import annotations

import time

from PySide6.QtWidgets import (
    QHBoxLayout,
    QLabel,
    QPushButton,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
    QWidget,
)

from app.context import PanelContext
from app.controller_text import localize
from app.format import format_duration
from app.i18n import N_, tr
from app.widgets.touch import touch_rows

COLUMNS = (N_("Start"), N_("Program"), N_("Result"), N_("Line"), N_("Cycle time"), N_("Part"), N_("Alarms"))


class ProductionView(QWidget):
    def __init__(self, context: PanelContext, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("productionView")
        self.ctx = context
        c = context.controller
        i18n = context.i18n
        layout = QVBoxLayout(self)
        top = QHBoxLayout()
        self.count_label = QLabel()
        self.count_label.setObjectName("partCount")
        self.count_label.setStyleSheet("font-size: 26px; font-weight: 800;")
        top.addWidget(self.count_label, 1)
        self.target_button = QPushButton()
        self.target_button.setMinimumHeight(56)
        i18n.bind(self.target_button, N_("Target…"))
        self.target_button.clicked.connect(self.ask_target)
        self.reset_button = QPushButton()
        self.reset_button.setMinimumHeight(56)
        i18n.bind(self.reset_button, N_("Reset counter"))
        self.reset_button.clicked.connect(self.reset_count)
        self.export_button = QPushButton()
        self.export_button.setMinimumHeight(56)
        i18n.bind(self.export_button, N_("Export log"))
        self.export_button.clicked.connect(self.export)
        for b in (self.target_button, self.reset_button, self.export_button):
            top.addWidget(b)
        layout.addLayout(top)
        self.end_label = QLabel()
        self.end_label.setObjectName("expectedEnd")
        layout.addWidget(self.end_label)
        self.table = QTableWidget(0, len(COLUMNS))
        self.table.setEditTriggers(QTableWidget.EditTrigger.NoEditTriggers)
        self.table.setSelectionBehavior(QTableWidget.SelectionBehavior.SelectRows)
        self.table.horizontalHeader().setStretchLastSection(True)
        touch_rows(self.table)
        layout.addWidget(self.table, 1)
        c.programFinished.connect(lambda _s: self.refresh())
        c.statusChanged.connect(self._on_status)
        i18n.languageChanged.connect(lambda _l: self.refresh())
        self.refresh()

    def _on_status(self, snap: object) -> None:
        remaining = float(getattr(snap, "remaining_s", 0.0))
        running = str(getattr(getattr(snap, "activity", None), "value", "")) == "program" and remaining > 0
        text = tr("This run ends about {0} ({1} from now)").format(
            time.strftime("%H:%M", time.localtime(time.time() + remaining)), format_duration(remaining)) \
            if running else ""
        if text != self.end_label.text():
            self.end_label.setText(text)

    def refresh(self) -> None:
        c = self.ctx.controller
        count, target = int(c.part_count), int(c.part_target)
        self.count_label.setText(tr("Parts: {0} of {1}").format(count, target) if target
                                 else tr("Parts: {0}").format(count))
        self.table.setHorizontalHeaderLabels([tr(col) for col in COLUMNS])
        runs = list(reversed(c.runs()))
        self.table.setRowCount(len(runs))
        for row, r in enumerate(runs):
            values = (time.strftime("%Y-%m-%d %H:%M", time.localtime(r.start_s)), r.program,
                      tr("completed") if r.completed else localize(r.result), str(r.last_line),
                      format_duration(r.cycle_time_s), str(r.part) if r.part else "",
                      "; ".join(localize(a) for a in r.alarms))
            for col, value in enumerate(values):
                item = QTableWidgetItem(value)
                item.setToolTip(value)
                self.table.setItem(row, col, item)

    def ask_target(self) -> None:
        c = self.ctx.controller
        value = self.ctx.dialogs.ask_number(self, tr("Parts to make (0: no target)"), float(c.part_target),
                                            0, 1_000_000, 0)
        if value is not None:
            c.set_part_target(int(value))
            self.refresh()

    def reset_count(self) -> None:
        counted = self.ctx.controller.part_count
        if self.ctx.dialogs.confirm(self, tr("Reset counter"),
                                    tr("Count parts from 0 again ({0} counted)?").format(counted)):
            self.ctx.controller.reset_part_count()
            self.refresh()

    def export(self) -> None:
        folders = self.ctx.folders
        if folders is None:
            return
        try:
            csv_path, json_path = self.ctx.controller.export_runs(folders.default)
        except OSError as exc:
            self.ctx.dialogs.inform(self, tr("Export failed"), str(exc))
            return
        self.ctx.dialogs.inform(self, tr("Run log exported"), tr("{0} and {1}").format(csv_path, json_path))
