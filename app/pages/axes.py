"""Axes (service level): the axis definitions of the machine configuration, edited by touch
(keypad per value, tap to toggle kind and direction), validated, applied atomically."""

from __future__ import annotations

from PySide6.QtWidgets import QLabel, QTableWidget, QTableWidgetItem, QVBoxLayout, QWidget

from app.config_edit import AXIS_FIELDS, validate, with_axis
from app.context import PanelContext
from app.i18n import N_, tr
from app.widgets.apply_bar import ApplyBar
from app.widgets.touch import touch_rows

COLUMNS = (N_("Kind"), N_("Direction")) + tuple(f[1] for f in AXIS_FIELDS)
_ = (N_("Drive"), N_("Counts/unit"), N_("Min"), N_("Max"), N_("Vmax"), N_("Amax"), N_("Jmax"),
     N_("FE window"))


class AxesPage(QWidget):
    def __init__(self, context: PanelContext, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("axesPage")
        self.ctx = context
        c = context.controller
        i18n = context.i18n
        layout = QVBoxLayout(self)
        hint = QLabel()
        hint.setWordWrap(True)
        i18n.bind(hint, N_("Tap a value to change it. Units: mm for linear axes, degrees for rotary "
                           "axes. Changes take effect after Apply (written atomically)."))
        layout.addWidget(hint)
        self.table = QTableWidget(0, len(COLUMNS))
        self.table.setEditTriggers(QTableWidget.EditTrigger.NoEditTriggers)
        touch_rows(self.table)
        self.table.cellClicked.connect(self.edit_cell)
        layout.addWidget(self.table, 1)
        self.apply_bar = ApplyBar(i18n)
        self.apply_bar.apply_button.clicked.connect(self.apply)
        self.apply_bar.revert_button.clicked.connect(self.revert)
        layout.addWidget(self.apply_bar)
        self.pending = c.config
        c.configChanged.connect(lambda _cfg: self.revert())
        i18n.languageChanged.connect(lambda _l: self.refresh())
        self.revert()

    def revert(self) -> None:
        self.pending = self.ctx.controller.config
        self.refresh()

    def refresh(self) -> None:
        axes = self.pending.machine.axes
        self.table.setRowCount(len(axes))
        self.table.setVerticalHeaderLabels([a.name for a in axes])
        self.table.setHorizontalHeaderLabels([tr(c) for c in COLUMNS])
        for row, a in enumerate(axes):
            values = [tr("rotary") if a.rotary else tr("linear"), "+1" if a.direction > 0 else "-1"]
            for attr, _label, _unit, decimals, _lo, _hi in AXIS_FIELDS:
                v = getattr(a, attr)
                values.append(f"{v:.{decimals}f}" if decimals else str(int(v)))
            for col, text in enumerate(values):
                self.table.setItem(row, col, QTableWidgetItem(text))
        self.table.resizeColumnsToContents()
        dirty = self.pending is not self.ctx.controller.config
        self.apply_bar.set_state(dirty, validate(self.pending) if dirty else "")

    def edit_cell(self, row: int, col: int) -> None:
        axis = self.pending.machine.axes[row]
        if col == 0:
            self.pending = with_axis(self.pending, row, rotary=not axis.rotary)
        elif col == 1:
            self.pending = with_axis(self.pending, row, direction=-axis.direction)
        else:
            attr, label, unit, decimals, lo, hi = AXIS_FIELDS[col - 2]
            unit = unit.replace("unit", axis.unit)
            value = self.ctx.dialogs.ask_number(self, f"{axis.name} {tr(label)} {unit}".strip(),
                                                float(getattr(axis, attr)), lo, hi, decimals)
            if value is None:
                return
            self.pending = with_axis(self.pending, row, **{attr: int(value) if decimals == 0 else value})
        self.refresh()

    def apply(self) -> None:
        error = validate(self.pending)
        if error:
            self.apply_bar.set_state(True, error)
            return
        running = str(getattr(self.ctx.controller.state, "value", "")) in ("running", "hold", "homing")
        text = tr("Apply the changed axis definitions?")
        if running:
            text += "\n" + tr("The machine is moving.")
        if self.ctx.dialogs.confirm(self, tr("Apply axes"), text):
            result = self.ctx.controller.update_config(self.pending)
            if not result:
                self.apply_bar.set_state(True, tr("Refused: {0}").format(result.reason))


def create_page(context: PanelContext) -> QWidget:
    return AxesPage(context)
