"""Manual: jog per axis (hold / increments), the handwheel's axis and step, spindle on/off and
speed, coolant and work light, MDI with history."""

from __future__ import annotations

from PySide6.QtGui import QGuiApplication
from PySide6.QtWidgets import (
    QApplication,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QListWidget,
    QPushButton,
    QVBoxLayout,
    QWidget,
)

from app.context import PanelContext
from app.i18n import N_, tr
from app.widgets.handwheel_box import HandwheelBox
from app.widgets.jog_panel import JogPanel
from app.widgets.keyboard import OnScreenKeyboard
from app.widgets.numeric_field import NumericField
from app.widgets.touch import touch_rows

MDI_HISTORY = 50


class ManualPage(QWidget):
    def __init__(self, context: PanelContext, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("manualPage")
        self.ctx = context
        c = context.controller
        i18n = context.i18n
        layout = QHBoxLayout(self)
        jog_box = QGroupBox()
        i18n.bind(jog_box, N_("Jog"), jog_box.setTitle)
        jog_layout = QVBoxLayout(jog_box)
        self.jog = JogPanel(c.axes, i18n, rotary=[a.rotary for a in c.config.machine.axes])
        jog_layout.addWidget(self.jog)
        self.jog.jogStart.connect(lambda axis, d: c.jog_start(axis, d, self.jog.speed_fraction))
        self.jog.jogStop.connect(lambda axis: c.jog_stop(axis or None))
        self.jog.jogStep.connect(lambda axis, step, d: c.jog_increment(axis, step, d))
        self.jog_box = jog_box
        self.handwheel = HandwheelBox(c, i18n)
        left = QVBoxLayout()
        left.addWidget(jog_box, 1)
        left.addWidget(self.handwheel)
        layout.addLayout(left, 1)

        right = QVBoxLayout()
        spindle_box = QGroupBox()
        i18n.bind(spindle_box, N_("Spindle"), spindle_box.setTitle)
        sp = QVBoxLayout(spindle_box)
        row = QHBoxLayout()
        self.spindle_buttons: dict[str, QPushButton] = {}
        for key, label in (("cw", N_("CW (M03)")), ("ccw", N_("CCW (M04)")), ("off", N_("Off (M05)"))):
            button = QPushButton()
            i18n.bind(button, label)
            row.addWidget(button)
            self.spindle_buttons[key] = button
        sp.addLayout(row)
        max_rpm = float(c.config.controller.spindle_max_rpm)
        self.rpm = NumericField(tr("Spindle speed"), c.spindle.rpm or 1000.0, 0.0, max_rpm, 0, tr("rpm"),
                                ask=context.dialogs.ask_number)
        sp.addWidget(self.rpm)
        self.spindle_label = QLabel()
        sp.addWidget(self.spindle_label)
        self.spindle_buttons["cw"].clicked.connect(lambda: c.spindle_on(True, self.rpm.value()))
        self.spindle_buttons["ccw"].clicked.connect(lambda: c.spindle_on(False, self.rpm.value()))
        self.spindle_buttons["off"].clicked.connect(lambda: c.spindle_off())
        self.rpm.valueChanged.connect(lambda rpm: c.spindle_speed(rpm))
        right.addWidget(spindle_box)

        # coolant (as M8 / M7; both off as M9) and the work light, where the machine has them
        self.coolant_box = QGroupBox()
        i18n.bind(self.coolant_box, N_("Coolant"), self.coolant_box.setTitle)
        cool = QHBoxLayout(self.coolant_box)
        wiring = c.config.wiring
        self.coolant_buttons: dict[str, QPushButton] = {}
        for key, label, signal in (("flood", N_("Flood (M08)"), "coolant_flood"),
                                   ("mist", N_("Mist (M07)"), "coolant_mist"),
                                   ("light", N_("Work light"), "work_light")):
            button = QPushButton()
            button.setCheckable(True)
            button.setMinimumHeight(48)
            i18n.bind(button, label)
            button.setVisible(wiring.has(signal))
            cool.addWidget(button)
            self.coolant_buttons[key] = button
        self.coolant_buttons["flood"].clicked.connect(lambda on: c.set_coolant(flood=on))
        self.coolant_buttons["mist"].clicked.connect(lambda on: c.set_coolant(mist=on))
        self.coolant_buttons["light"].clicked.connect(lambda on: c.set_work_light(on))
        self._coolant_wired = any(wiring.has(k) for k in ("coolant_flood", "coolant_mist", "work_light"))
        self.coolant_box.setVisible(self._coolant_wired)
        right.addWidget(self.coolant_box)
        c.statusChanged.connect(lambda _snap: self._on_coolant())

        mdi_box = QGroupBox()
        i18n.bind(mdi_box, N_("MDI"), mdi_box.setTitle)
        mdi = QVBoxLayout(mdi_box)
        row = QHBoxLayout()
        self.mdi_line = QLineEdit()
        self.mdi_line.setMinimumHeight(48)
        i18n.bind(self.mdi_line, N_("G-code block, e.g. G01 X10 F600"), self.mdi_line.setPlaceholderText)
        self.mdi_send = QPushButton()
        i18n.bind(self.mdi_send, N_("Send"))
        self.keyboard_button = QPushButton()
        self.keyboard_button.setCheckable(True)
        i18n.bind(self.keyboard_button, N_("Keyboard"))
        row.addWidget(self.mdi_line, 1)
        row.addWidget(self.mdi_send)
        row.addWidget(self.keyboard_button)
        mdi.addLayout(row)
        self.history = QListWidget()
        touch_rows(self.history)
        self.history.addItems(list(context.settings.settings.mdi_history))
        mdi.addWidget(self.history, 1)
        self.keyboard = OnScreenKeyboard()
        self.keyboard.set_target(self.mdi_line)
        self.keyboard.hide()
        mdi.addWidget(self.keyboard)
        right.addWidget(mdi_box, 1)
        layout.addLayout(right, 1)

        self.mdi_send.clicked.connect(self.send_mdi)
        self.mdi_line.returnPressed.connect(self.send_mdi)
        self.history.itemClicked.connect(lambda item: self.mdi_line.setText(item.text()))
        self.keyboard_button.toggled.connect(self._show_keyboard)
        c.spindleChanged.connect(self._on_spindle)
        i18n.languageChanged.connect(lambda _l: self._on_spindle(c.spindle))
        self._on_spindle(c.spindle)
        app = QApplication.instance()
        if isinstance(app, QGuiApplication):  # safe release: the panel losing the screen stops jogging
            app.applicationStateChanged.connect(self._release_jog)

    def _release_jog(self, *_args: object) -> None:
        self.jog.release_all()

    def send_mdi(self) -> None:
        block = self.mdi_line.text().strip()
        if not block:
            return
        result = self.ctx.controller.mdi(block)
        if result:
            history = [h for h in self.ctx.settings.settings.mdi_history if h != block] + [block]
            history = history[-MDI_HISTORY:]
            self.ctx.settings.update(mdi_history=tuple(history))
            self.history.clear()
            self.history.addItems(history)
            self.mdi_line.clear()

    def _show_keyboard(self, on: bool) -> None:
        """The keyboard takes the jog panel's place while it is open (and the coolant buttons'):
        beside the jog panel it would not fit in 1280 px, and nobody jogs while typing a block."""
        self.jog_box.setVisible(not on)
        self.handwheel.allow(not on)
        self.coolant_box.setVisible(not on and self._coolant_wired)
        self.keyboard.setVisible(on)

    def _on_coolant(self) -> None:
        """The buttons as the outputs are switched now (a program's M8, E-stop switching off)."""
        flood, mist = self.ctx.controller.coolant
        for key, on in (("flood", flood), ("mist", mist)):
            button = self.coolant_buttons[key]
            if button.isChecked() != on:
                button.setChecked(on)

    def _on_spindle(self, spindle: object) -> None:
        direction = int(getattr(spindle, "direction", 0))
        rpm = float(getattr(spindle, "rpm", 0.0))
        state = {1: tr("CW"), -1: tr("CCW")}.get(direction, tr("off"))
        self.spindle_label.setText(tr("Spindle: {0}, {1:.0f} rpm").format(state, rpm))


def create_page(context: PanelContext) -> QWidget:
    return ManualPage(context)
