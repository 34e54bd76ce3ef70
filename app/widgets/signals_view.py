"""The machine's signals (Diagnostics): every wired signal, where it is wired (the slave, its
channel or bit, normally closed or not), what it reads now and LinuxCNC's name for it. A signal
reading other than a healthy machine at rest shows (the door open, the chain open, a limit
switch closed) is marked, so a commissioning engineer sees a wiring fault at a glance."""

from __future__ import annotations

from PySide6.QtGui import QColor
from PySide6.QtWidgets import QLabel, QTableWidget, QTableWidgetItem, QVBoxLayout, QWidget

from app.controller_text import localize
from app.i18n import N_, I18n, tr
from app.machine.model import SignalReading

SIGNAL_COLUMNS = (N_("Signal"), N_("Direction"), N_("Wired to"), N_("Now"), N_("LinuxCNC"))
#: what a healthy machine at rest reads on these (the others read false then)
HEALTHY_TRUE = frozenset({"estop_chain_ok", "door_closed", "air_ok", "lube_ok"})
DIRECTION_TEXT = {"in": N_("input"), "out": N_("output")}


class SignalsView(QWidget):
    def __init__(self, i18n: I18n, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        layout = QVBoxLayout(self)
        self.note = QLabel()
        self.note.setWordWrap(True)
        layout.addWidget(self.note)
        self.table = QTableWidget(0, len(SIGNAL_COLUMNS))
        self.table.setObjectName("signalsTable")
        self.table.setEditTriggers(QTableWidget.EditTrigger.NoEditTriggers)
        self.table.horizontalHeader().setStretchLastSection(True)
        layout.addWidget(self.table, 1)
        self.readings: tuple[SignalReading, ...] = ()
        i18n.languageChanged.connect(lambda _l: self.show_readings(self.readings, force=True))
        self.show_readings((), force=True)

    def show_readings(self, readings: tuple[SignalReading, ...], force: bool = False) -> None:
        if readings == self.readings and not force:
            return
        self.readings = readings
        self.table.setHorizontalHeaderLabels([tr(c) for c in SIGNAL_COLUMNS])
        self.note.setText(tr("The machine's signals as the drives and terminals report them ([signals] in "
                             "the machine configuration). Marked: not what a machine at rest reads.")
                          if readings else tr("No signal is wired ([signals] in the machine configuration)."))
        self.table.setRowCount(len(readings))
        for row, r in enumerate(readings):
            now = tr("unknown") if r.value is None else tr("on") if r.value else tr("off")
            healthy = r.key in HEALTHY_TRUE
            odd = r.direction == "in" and r.value is not None and r.value != healthy
            values = (r.key, tr(DIRECTION_TEXT.get(r.direction, r.direction)), localize(r.where), now,
                      r.hal or "—")
            for col, text in enumerate(values):
                item = QTableWidgetItem(text)
                if odd:
                    item.setBackground(QColor("#7a3b1d"))
                item.setToolTip(localize(r.meaning))
                self.table.setItem(row, col, item)
        self.table.resizeColumnsToContents()
