"""Alarms: active alarms and the history, acknowledge one or all, reset the machine."""

from __future__ import annotations

import time

from PySide6.QtCore import Qt
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
from app.controller_text import localize, source_text
from app.i18n import N_, tr
from app.widgets.touch import touch_rows

COLUMNS = (N_("Time"), N_("Source"), N_("Cause"), N_("Severity"), N_("State"))
#: the alarm log's words, shown in the operator's language
SEVERITY_TEXT = {"INFO": N_("info"), "WARNING": N_("warning"), "STOP": N_("stop"),
                 "QUICK_STOP": N_("quick stop"), "ESTOP": N_("E-stop")}


class AlarmsPage(QWidget):
    def __init__(self, context: PanelContext, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("alarmsPage")
        self.ctx = context
        c = context.controller
        i18n = context.i18n
        layout = QVBoxLayout(self)
        bar = QHBoxLayout()
        self.show_history = QPushButton()
        self.show_history.setCheckable(True)
        i18n.bind(self.show_history, N_("Show history"))
        self.ack_button = QPushButton()
        i18n.bind(self.ack_button, N_("Acknowledge"))
        self.ack_all_button = QPushButton()
        i18n.bind(self.ack_all_button, N_("Acknowledge all"))
        self.reset_button = QPushButton()
        i18n.bind(self.reset_button, N_("Reset"))
        for b in (self.show_history, self.ack_button, self.ack_all_button, self.reset_button):
            bar.addWidget(b)
        bar.addStretch(1)
        layout.addLayout(bar)
        self.table = QTableWidget(0, len(COLUMNS))
        self.table.setEditTriggers(QTableWidget.EditTrigger.NoEditTriggers)
        self.table.setSelectionBehavior(QTableWidget.SelectionBehavior.SelectRows)
        self.table.horizontalHeader().setStretchLastSection(False)
        self.table.setColumnWidth(0, 120)
        self.table.setColumnWidth(1, 140)
        self.table.setColumnWidth(2, 460)
        self.table.setColumnWidth(3, 130)
        touch_rows(self.table)
        layout.addWidget(self.table, 1)
        # the tapped alarm in full: a long cause is cut in its column, never here
        self.detail = QLabel()
        self.detail.setObjectName("alarmDetail")
        self.detail.setWordWrap(True)
        self.detail.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        layout.addWidget(self.detail)
        self.table.currentCellChanged.connect(lambda row, *_: self.show_detail(row))
        self.table.cellClicked.connect(lambda row, _col: self.show_detail(row))
        self._alarms: tuple = tuple(c.alarms)
        self.show_history.toggled.connect(lambda _on: self.refresh())
        self.ack_button.clicked.connect(self.acknowledge_selected)
        self.ack_all_button.clicked.connect(lambda: c.acknowledge_alarm(None))
        self.reset_button.clicked.connect(lambda: c.reset())
        c.alarmsChanged.connect(self._on_alarms)
        i18n.languageChanged.connect(lambda _l: self.refresh())
        self.refresh()

    def _on_alarms(self, alarms: object) -> None:
        self._alarms = tuple(alarms)  # type: ignore[arg-type]
        self.refresh()

    def shown_alarms(self) -> list:
        alarms = [a for a in self._alarms if a.active or self.show_history.isChecked()]
        return sorted(alarms, key=lambda a: a.time_s, reverse=True)

    def refresh(self) -> None:
        self.table.setHorizontalHeaderLabels([tr(c) for c in COLUMNS])
        alarms = self.shown_alarms()
        self.table.setRowCount(len(alarms))
        for row, a in enumerate(alarms):
            when = time.strftime("%H:%M:%S", time.localtime(a.time_s)) if a.time_s else "--:--:--"
            state = tr("active") if a.active else tr("acknowledged")
            severity = tr(SEVERITY_TEXT.get(a.severity.name, a.severity.name.lower()))
            values = (when, source_text(a.source), localize(a.cause), severity, state)
            for col, value in enumerate(values):
                item = QTableWidgetItem(str(value))
                item.setData(256, a.id)  # Qt.UserRole
                item.setToolTip(str(value))
                self.table.setItem(row, col, item)
        self.show_detail(self.table.currentRow())

    def show_detail(self, row: int) -> None:
        """The alarm of ``row`` in full below the table ("" when none is chosen)."""
        items = [self.table.item(row, col) for col in range(len(COLUMNS))] if row >= 0 else []
        if not items or any(i is None for i in items):
            self.detail.setText("")
            return
        when, source, cause, severity, state = (i.text() for i in items if i is not None)
        self.detail.setText(tr("{0} {1} ({2}, {3}): {4}").format(when, source, severity, state, cause))

    def acknowledge_selected(self) -> None:
        row = self.table.currentRow()
        if row < 0:
            return
        item = self.table.item(row, 0)
        if item is not None:
            self.ctx.controller.acknowledge_alarm(int(item.data(256)))


def create_page(context: PanelContext) -> QWidget:
    return AlarmsPage(context)
