"""Machine zero: per-axis homed state, home one or all (to the home switches, by the drive, or
"set here"), the homing step under way, set the current position as machine zero."""

from __future__ import annotations

from PySide6.QtWidgets import QGridLayout, QLabel, QPushButton, QVBoxLayout, QWidget

from app.context import PanelContext
from app.controller_text import localize
from app.i18n import N_, tr
from app.machine.model import MachineState
from app.widgets.dro import format_position


class MachineZeroPage(QWidget):
    def __init__(self, context: PanelContext, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("machineZeroPage")
        self.ctx = context
        c = context.controller
        i18n = context.i18n
        layout = QVBoxLayout(self)
        self.method_label = QLabel()
        self.method_label.setWordWrap(True)
        layout.addWidget(self.method_label)
        # which axes home and the step they are at (searching, latching ...), while homing
        self.step_label = QLabel()
        self.step_label.setObjectName("homingStep")
        self.step_label.setWordWrap(True)
        layout.addWidget(self.step_label)
        grid = QGridLayout()
        for col, text in enumerate((N_("Axis"), N_("Homed"), N_("Machine position"))):
            head = QLabel()
            i18n.bind(head, text)
            grid.addWidget(head, 0, col)
        self.homed_labels: list[QLabel] = []
        self.pos_labels: list[QLabel] = []
        self.home_buttons: dict[str, QPushButton] = {}
        self.zero_buttons: dict[str, QPushButton] = {}
        for row, axis in enumerate(c.axes, start=1):
            name = QLabel(axis)
            name.setObjectName("droAxis")
            homed, pos = QLabel(), QLabel()
            pos.setObjectName("droValue")
            home = QPushButton()
            i18n.bind(home, N_("Home"))
            zero = QPushButton()
            i18n.bind(zero, N_("Set here as zero"))
            home.clicked.connect(lambda _=False, a=axis: self.home(a))
            zero.clicked.connect(lambda _=False, a=axis: self.set_zero_here(a))
            for col, w in enumerate((name, homed, pos, home, zero)):
                grid.addWidget(w, row, col)
            self.homed_labels.append(homed)
            self.pos_labels.append(pos)
            self.home_buttons[axis] = home
            self.zero_buttons[axis] = zero
        layout.addLayout(grid)
        self.home_all_button = QPushButton()
        i18n.bind(self.home_all_button, N_("Home all axes"))
        self.home_all_button.setMinimumHeight(64)
        self.home_all_button.clicked.connect(self.home_all)
        layout.addWidget(self.home_all_button)
        layout.addStretch(1)
        self._homed = c.homed
        c.homedChanged.connect(self._on_homed)
        c.stateChanged.connect(self._on_state)
        for signal in (c.stateChanged, c.homedChanged, c.alarmsChanged):
            signal.connect(lambda *_: self._update_buttons())
        i18n.languageChanged.connect(lambda _l: self._update_buttons())
        c.positionChanged.connect(self._on_position)
        i18n.languageChanged.connect(lambda _l: self._on_homed(self._homed))
        self._on_homed(c.homed)
        self._on_position(c.machine_position, c.work_position)
        self._update_buttons()

    def _update_buttons(self) -> None:
        """Home enabled when the controller would take it (never in E-stop, never while the
        machine moves); disabled, it says why in its tooltip, before anyone is asked to confirm."""
        reason = self.ctx.controller.refusal("home")
        tip = tr("{0}: {1}").format(tr("Home"), localize(reason)) if reason else ""
        for button in (*self.home_buttons.values(), self.home_all_button):
            button.setEnabled(not reason)
            button.setToolTip(tip)

    def home(self, axis: str) -> None:
        if self.ctx.dialogs.confirm(self, tr("Home axis"),
                                    tr("Home axis {0}? The axis may move.").format(axis)):
            self.ctx.controller.home_axis(axis)

    def home_all(self) -> None:
        if self.ctx.dialogs.confirm(self, tr("Home all axes"), tr("Home all axes? The axes may move.")):
            self.ctx.controller.home_all()

    def set_zero_here(self, axis: str) -> None:
        if self.ctx.dialogs.confirm(self, tr("Set machine zero"),
                                    tr("Make the current position of {0} its machine zero?").format(axis)):
            self.ctx.controller.set_machine_zero_here(axis)

    def _on_homed(self, homed: object) -> None:
        self._homed = tuple(homed)  # type: ignore[arg-type]
        homing = self.ctx.controller.config.homing
        for label, ok in zip(self.homed_labels, self._homed):
            label.setText(tr("yes") if ok else tr("no"))
            label.setStyleSheet(f"color: {'#7fe0a0' if ok else '#ff9080'}; font-weight: 700;")
        method = {"drive": tr("drive homing method {0}").format(homing.drive_method),
                  "switches": tr("to the home switches, in the configured sequence")}.get(
            homing.method, tr("set current position as zero (no reference switches: after a power loss the "
                              "part zero must be touched off again)"))
        required = tr("required before a program may start") if homing.required else tr("optional")
        self.method_label.setText(tr("Homing: {0}; {1}.").format(method, required))

    def _on_state(self, state: MachineState, reason: str) -> None:
        homing = state is MachineState.HOMING or (state is MachineState.RUNNING
                                                   and reason.startswith("homing"))
        self.step_label.setText(localize(reason) if homing else "")

    def _on_position(self, machine: object, _work: object) -> None:
        for label, value in zip(self.pos_labels, machine):  # type: ignore[call-overload]
            label.setText(format_position(float(value)))


def create_page(context: PanelContext) -> QWidget:
    return MachineZeroPage(context)
