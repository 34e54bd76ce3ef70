"""The handwheel on the Manual page: which axis it moves (Off, X, Y, Z ...), its step per detent
(x1, x10, x100 with the step in mm or degrees), and a lamp that is lit while turning the wheel
moves the axis, or says why it does not. With a pendant's selector wired, the buttons show
what the selector chooses and cannot be pressed."""

from __future__ import annotations

from PySide6.QtWidgets import QGroupBox, QHBoxLayout, QLabel, QPushButton, QVBoxLayout, QWidget

from app.controller_text import localize
from app.i18n import N_, I18n, tr
from app.machine.api import MachineApi
from app.machine.model import HANDWHEEL_SCALES, HandwheelStatus
from app.widgets.touch import exclusive_buttons

__all__ = ["HandwheelBox"]

#: the lamp's colours: live, and not live with an axis given
LIVE_COLOR, IDLE_COLOR = "#7fe0a0", "#ffb070"


class HandwheelBox(QGroupBox):
    """The handwheel's axis and step buttons and its lamp (hidden when the machine has none)."""

    def __init__(self, controller: MachineApi, i18n: I18n, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("handwheelBox")
        self._c = controller
        self._allowed = True
        i18n.bind(self, N_("Handwheel"), self.setTitle)
        layout = QVBoxLayout(self)
        row = QHBoxLayout()
        off = QPushButton()
        i18n.bind(off, N_("Off"))
        choices = [("", off)] + [(a, QPushButton(a)) for a in controller.axes]
        self.axis_group, self.axis_buttons = exclusive_buttons(self, row, choices,
                                                               lambda a: controller.select_handwheel(a))
        row.addSpacing(12)
        self.step_group, self.step_buttons = exclusive_buttons(
            self, row, [(k, QPushButton(x)) for k, x in enumerate(HANDWHEEL_SCALES)],
            lambda k: controller.set_handwheel_step(k))
        layout.addLayout(row)
        for button in (*self.axis_buttons.values(), *self.step_buttons.values()):
            button.setMinimumHeight(48)
        self.lamp = QLabel()
        self.lamp.setObjectName("handwheelLamp")
        self.lamp.setWordWrap(True)
        layout.addWidget(self.lamp)
        controller.handwheelChanged.connect(self.show_status)
        i18n.languageChanged.connect(lambda _lang: self.show_status(self._c.handwheel))
        self.show_status(controller.handwheel)

    def allow(self, on: bool) -> None:
        """Shown (when the machine has a handwheel) or kept hidden by the page (its keyboard)."""
        self._allowed = on
        self.setVisible(on and self._c.handwheel.configured)

    def show_status(self, status: HandwheelStatus) -> None:
        self.setVisible(status.configured and self._allowed)
        self.axis_buttons[status.axis if status.axis in self.axis_buttons else ""].setChecked(True)
        self.step_buttons[status.scale_index].setChecked(True)
        for button in (*self.axis_buttons.values(), *self.step_buttons.values()):
            button.setEnabled(not status.selector)
        step = f"{status.step:g}"
        if status.live:
            text, color = tr("Live: a detent moves {0} by {1}").format(status.axis, step), LIVE_COLOR
        elif status.axis:
            why = localize(status.why) if status.why else tr("waiting for the drives")
            text, color = tr("Not live: {0}").format(why), IDLE_COLOR
        else:
            text, color = tr("Off: choose an axis ({0} a detent)").format(step), ""
        if status.selector:
            text += "\n" + tr("The pendant's selector chooses the axis and the step.")
        self.lamp.setText(text)
        self.lamp.setStyleSheet(f"color: {color}; font-weight: 700;" if color else "")
