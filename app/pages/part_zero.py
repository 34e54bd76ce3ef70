"""Part zero: the nine coordinate systems G54-G59.3 (machine coordinates of part zero, every
axis, and the XY rotation of G10 L2 R), select the active one, touch off per axis (the current
position becomes a chosen work coordinate), and the G92/G52 offset in force; on a machine with a
probe, the probing wizards in a second tab (``app.widgets.probing_panel``)."""

from __future__ import annotations

import functools

from PySide6.QtWidgets import (
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QPushButton,
    QTableWidget,
    QTableWidgetItem,
    QTabWidget,
    QVBoxLayout,
    QWidget,
)

from app.context import PanelContext
from app.i18n import N_, tr
from app.widgets.probing_panel import ProbingPanel
from app.widgets.touch import exclusive_buttons, touch_rows
from planner.core.machine import WORK_OFFSET_NAMES


class PartZeroPage(QWidget):
    def __init__(self, context: PanelContext, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("partZeroPage")
        self.ctx = context
        c = context.controller
        i18n = context.i18n
        self.axes = c.axes
        page = QVBoxLayout(self)
        page.setContentsMargins(0, 0, 0, 0)
        self.tabs = QTabWidget()
        page.addWidget(self.tabs)
        systems = QWidget()
        layout = QVBoxLayout(systems)
        self.tabs.addTab(systems, "")
        i18n.bind(self.tabs, N_("Coordinate systems"), functools.partial(self.tabs.setTabText, 0))
        self.probing: ProbingPanel | None = None
        if c.config.probe.drive is not None and {"X", "Y", "Z"} <= set(self.axes):
            self.probing = ProbingPanel(context)
            self.tabs.addTab(self.probing, "")
            i18n.bind(self.tabs, N_("Probe"), functools.partial(self.tabs.setTabText, 1))
        select = QHBoxLayout()
        active = QLabel()
        i18n.bind(active, N_("Active:"))
        select.addWidget(active)
        self.select_group, self.select_buttons = exclusive_buttons(
            self, select, ((name, QPushButton(name)) for name in WORK_OFFSET_NAMES),
            c.select_work_offset)
        layout.addLayout(select)
        # one column per axis, then the XY rotation (degrees) where the machine has X and Y
        self.rotation_col = len(self.axes) if {"X", "Y"} <= set(self.axes) else -1
        columns = len(self.axes) + (1 if self.rotation_col >= 0 else 0)
        self.table = QTableWidget(len(WORK_OFFSET_NAMES), columns)
        self.table.setVerticalHeaderLabels(list(WORK_OFFSET_NAMES))
        self._header_texts()
        i18n.languageChanged.connect(lambda *_: self._header_texts())
        self.table.horizontalHeader().setSectionResizeMode(QHeaderView.ResizeMode.Stretch)
        self.table.setEditTriggers(QTableWidget.EditTrigger.NoEditTriggers)
        touch_rows(self.table)
        self.table.cellClicked.connect(self.edit_cell)
        layout.addWidget(self.table, 1)
        hint = QLabel()
        hint.setWordWrap(True)
        i18n.bind(hint, N_("Tap a value to type it. Touch off: the current position becomes the "
                           "work coordinate you enter, in the selected offset."))
        layout.addWidget(hint)
        # what a program left on top of the table: the G92/G52 offset and the XY rotation
        extra = QHBoxLayout()
        self.extra_label = QLabel()
        self.extra_label.setWordWrap(True)
        extra.addWidget(self.extra_label, 1)
        self.clear_g92_button = QPushButton()
        i18n.bind(self.clear_g92_button, N_("Clear G92"))
        self.clear_g92_button.clicked.connect(lambda: self.ctx.controller.clear_g92())
        extra.addWidget(self.clear_g92_button)
        layout.addLayout(extra)
        i18n.languageChanged.connect(lambda *_: self._show_extra())
        touch = QHBoxLayout()
        self.touch_buttons: dict[str, QPushButton] = {}
        for axis in self.axes:
            button = QPushButton()
            i18n.bind(button, N_("Touch off {0}"), functools.partial(_set_axis_text, button, axis))
            button.clicked.connect(lambda _=False, a=axis: self.touch_off(a))
            touch.addWidget(button)
            self.touch_buttons[axis] = button
        layout.addLayout(touch)
        self._offsets: dict[str, tuple[float, ...]] = dict(c.work_offsets)
        self._active = c.active_offset
        c.offsetsChanged.connect(self._on_offsets)
        self._on_offsets(self._offsets, self._active)

    def _on_offsets(self, offsets: object, active: str) -> None:
        self._offsets = dict(offsets)  # type: ignore[call-overload]
        self._active = active
        c = self.ctx.controller
        for r, name in enumerate(WORK_OFFSET_NAMES):
            values = self._offsets.get(name, (0.0,) * len(self.axes))
            for col, value in enumerate(values[: len(self.axes)]):
                item = QTableWidgetItem(f"{value:+.3f}")
                self.table.setItem(r, col, item)
            if self.rotation_col >= 0:
                self.table.setItem(r, self.rotation_col, QTableWidgetItem(f"{c.work_rotation(name):+.3f}"))
        if active in self.select_buttons:
            self.select_buttons[active].setChecked(True)
            self.table.selectRow(WORK_OFFSET_NAMES.index(active))
        self._show_extra()

    def _show_extra(self) -> None:
        c = self.ctx.controller
        g92 = c.g92_offset
        if g92 is None:
            text = tr("G92 offset: off")
        else:
            values = " ".join(f"{a}{v:+.3f}" for a, v in zip(self.axes, g92))
            text = tr("G92 offset: {0} (on: every work position is shifted by it)").format(values)
        rotation = c.xy_rotation_deg
        if rotation:
            text += "\n" + tr("XY rotation of {0}: {1} degrees").format(self._active, f"{rotation:g}")
        self.extra_label.setText(text)
        self.clear_g92_button.setEnabled(g92 is not None)

    def _header_texts(self) -> None:
        labels = list(self.axes)
        if self.rotation_col >= 0:
            labels.append(tr("XY rotation (°)"))
        self.table.setHorizontalHeaderLabels(labels)

    def edit_cell(self, row: int, col: int) -> None:
        name = WORK_OFFSET_NAMES[row]
        if col == self.rotation_col:
            c = self.ctx.controller
            value = self.ctx.dialogs.ask_number(self,
                                                tr("{0} XY rotation (degrees, as G10 L2 R)").format(name),
                                                c.work_rotation(name), -360.0, 360.0)
            if value is not None:
                c.set_work_rotation(name, value)
            return
        values = list(self._offsets.get(name, (0.0,) * len(self.axes)))
        value = self.ctx.dialogs.ask_number(self, tr("{0} {1} (machine coordinate of part zero)")
                                            .format(name, self.axes[col]), values[col])
        if value is not None:
            values[col] = value
            self.ctx.controller.set_work_offset(name, tuple(values))

    def touch_off(self, axis: str) -> None:
        value = self.ctx.dialogs.ask_number(self, tr("Touch off {0}: work coordinate here").format(axis), 0.0)
        if value is not None:
            self.ctx.controller.touch_off(axis, value, self._active)


def create_page(context: PanelContext) -> QWidget:
    return PartZeroPage(context)


def _set_axis_text(button: QPushButton, axis: str, text: str) -> None:
    """A button's text from its translated template and its axis."""
    button.setText(text.format(axis))
