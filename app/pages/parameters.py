"""Parameters (service level): path limits, Ts, corner tolerance, planner mode and interpolation,
homing, bus, service password. Changes are checked, confirmed and applied atomically by the controller."""

from __future__ import annotations

from PySide6.QtWidgets import (
    QButtonGroup,
    QFormLayout,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QScrollArea,
    QVBoxLayout,
    QWidget,
)

from app.config_edit import validate, with_bus, with_homing, with_limits, with_planner
from app.context import PanelContext
from app.i18n import N_, I18n, tr
from app.machine.config import MachineConfig
from app.service_access import MIN_LENGTH
from app.widgets.apply_bar import ApplyBar
from app.widgets.numeric_field import NumericField
from app.widgets.touch import enable_kinetic_scrolling
from planner.core.machine import INTERPOLATIONS, PLANNER_MODES

LIMIT_FIELDS = (  # (attribute, label, unit, minimum, maximum, decimals)
    ("v_max_mm_s", N_("Path speed Vmax"), "mm/s", 0.001, 10000.0, 3),
    ("a_max_mm_s2", N_("Path acceleration Amax"), "mm/s²", 0.001, 1e6, 1),
    ("j_max_mm_s3", N_("Path jerk Jmax"), "mm/s³", 0.001, 1e8, 1),
    ("rapid_mm_s", N_("Rapid speed"), "mm/s", 0.001, 10000.0, 3),
)


# what the planner's settings are called on the buttons (the configuration keeps its own words)
CHOICE_NAMES: dict[str, str] = {
    "lookahead": N_("Look-ahead"), "paper": N_("Paper (per block)"),
    "exact": N_("Exact"), "taylor": N_("Taylor"), "classic": N_("Classic"),
    "sim": N_("Simulated"), "soem": N_("EtherCAT (SOEM)"),
}


def _choice_row(values: tuple[str, ...], i18n: I18n) -> tuple[QWidget, QButtonGroup, dict[str, QPushButton]]:
    box = QWidget()
    row = QHBoxLayout(box)
    row.setContentsMargins(0, 0, 0, 0)
    group = QButtonGroup(box)
    buttons = {}
    for v in values:
        b = QPushButton()
        i18n.bind(b, CHOICE_NAMES.get(v, v))
        b.setCheckable(True)
        group.addButton(b)
        row.addWidget(b)
        buttons[v] = b
    row.addStretch(1)
    return box, group, buttons


class ParametersPage(QWidget):
    def __init__(self, context: PanelContext, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("parametersPage")
        self.ctx = context
        c = context.controller
        i18n = context.i18n
        outer = QVBoxLayout(self)
        scroll = QScrollArea()
        scroll.setWidgetResizable(True)
        enable_kinetic_scrolling(scroll)
        outer.addWidget(scroll, 1)
        body = QWidget()
        scroll.setWidget(body)
        form = QFormLayout(body)
        self.fields: dict[str, NumericField] = {}
        self.pending: MachineConfig = context.controller.config   # what Apply writes

        def label(text: str) -> QLabel:
            lab = QLabel()
            i18n.bind(lab, text)
            return lab

        for attr, text, unit, lo, hi, decimals in LIMIT_FIELDS:
            field = NumericField(tr(text), 0.0, lo, hi, decimals, unit, ask=context.dialogs.ask_number)
            field.valueChanged.connect(lambda v, a=attr: self._set(with_limits(self.pending, **{a: v})))
            form.addRow(label(text), field)
            self.fields[attr] = field
        self.ts_field = NumericField(tr("Cycle time Ts"), 1.0, 0.01, 100.0, 3, "ms",
                                     ask=context.dialogs.ask_number)
        self.ts_field.valueChanged.connect(lambda v: self._set(with_planner(self.pending, ts_s=v / 1000.0)))
        form.addRow(label(N_("Cycle time Ts")), self.ts_field)
        # G64 without P: how far a corner blend may leave the programmed corner (0: exact path)
        self.blend_field = NumericField(tr("Corner tolerance (G64)"), 0.0, 0.0, 10.0, 3, "mm",
                                        ask=context.dialogs.ask_number)
        self.blend_field.valueChanged.connect(
            lambda v: self._set(with_planner(self.pending, blend_tolerance_mm=v)))
        form.addRow(label(N_("Corner tolerance (G64)")), self.blend_field)
        # a velocity step allowed at joints that are not blended (0: within the jerk limit)
        self.corner_step_field = NumericField(tr("Corner velocity step"), 0.0, 0.0, 1000.0, 3, "mm/s",
                                              ask=context.dialogs.ask_number)
        self.corner_step_field.valueChanged.connect(
            lambda v: self._set(with_planner(self.pending, corner_velocity_step_mm_s=v)))
        form.addRow(label(N_("Corner velocity step")), self.corner_step_field)
        box, _g, self.mode_buttons = _choice_row(PLANNER_MODES, i18n)
        for mode, b in self.mode_buttons.items():
            b.clicked.connect(lambda _=False, m=mode: self._set(with_planner(self.pending, mode=m)))
        form.addRow(label(N_("Planner mode")), box)
        box, _g, self.interp_buttons = _choice_row(INTERPOLATIONS, i18n)
        for interp, b in self.interp_buttons.items():
            b.clicked.connect(lambda _=False, m=interp: self._set(
                with_planner(self.pending, interpolation=m)))
        form.addRow(label(N_("Interpolation")), box)
        self.homing_required = QPushButton()
        self.homing_required.setCheckable(True)
        i18n.bind(self.homing_required, N_("Homing required before a program"))
        self.homing_required.clicked.connect(lambda on: self._set(with_homing(self.pending, required=on)))
        form.addRow(label(N_("Homing")), self.homing_required)
        box, _g, self.bus_buttons = _choice_row(("sim", "soem"), i18n)
        for kind, b in self.bus_buttons.items():
            b.clicked.connect(lambda _=False, k=kind: self._set(with_bus(self.pending, kind=k)))
        form.addRow(label(N_("Bus")), box)
        self.adapter = QPushButton()  # tap: type it with the on-screen keyboard
        self.adapter.clicked.connect(self.edit_adapter)
        form.addRow(label(N_("Network adapter")), self.adapter)
        row = QHBoxLayout()
        self.password_button = QPushButton()
        i18n.bind(self.password_button, N_("Change service password"))
        self.password_button.clicked.connect(self.change_password)
        self.lock_button = QPushButton()
        i18n.bind(self.lock_button, N_("Lock service level"))
        self.lock_button.clicked.connect(self.lock)
        row.addWidget(self.password_button)
        row.addWidget(self.lock_button)
        form.addRow(label(N_("Service")), row)

        self.apply_bar = ApplyBar(i18n)
        self.apply_bar.apply_button.clicked.connect(self.apply)
        self.apply_bar.revert_button.clicked.connect(self.revert)
        outer.addWidget(self.apply_bar)
        self.pending = c.config
        c.configChanged.connect(lambda _cfg: self.revert())
        self.revert()

    def _set(self, config: MachineConfig) -> None:
        self.pending = config
        self.refresh()

    def revert(self) -> None:
        self.pending = self.ctx.controller.config
        self.refresh()

    def refresh(self) -> None:
        m = self.pending.machine
        for attr, field in self.fields.items():
            field.setValue(getattr(m.limits, attr))
        self.ts_field.setValue(m.planner.ts_s * 1000.0)
        self.blend_field.setValue(m.planner.blend_tolerance_mm)
        self.corner_step_field.setValue(m.planner.corner_velocity_step_mm_s)
        for mode, b in self.mode_buttons.items():
            b.setChecked(mode == m.planner.mode)
        for interp, b in self.interp_buttons.items():
            b.setChecked(interp == m.planner.interpolation)
        self.homing_required.setChecked(self.pending.homing.required)
        for kind, b in self.bus_buttons.items():
            b.setChecked(kind == self.pending.bus.kind)
        self.adapter.setText(self.pending.bus.adapter or "—")
        dirty = self.pending is not self.ctx.controller.config
        self.apply_bar.set_state(dirty, validate(self.pending) if dirty else "")

    def apply(self) -> bool:
        error = validate(self.pending)
        if error:
            self.apply_bar.set_state(True, error)
            return False
        running = str(getattr(self.ctx.controller.state, "value", "")) in ("running", "hold", "homing")
        text = tr("Apply the changed parameters?")
        if running:
            text += "\n" + tr("The machine is moving.")
        if not self.ctx.dialogs.confirm(self, tr("Apply parameters"), text):
            return False
        result = self.ctx.controller.update_config(self.pending)
        if not result:
            self.apply_bar.set_state(True, tr("Refused: {0}").format(result.reason))
            return False
        return True

    def edit_adapter(self) -> None:
        text = self.ctx.dialogs.ask_text(self, tr("Network adapter"),
                                         tr("Network interface of the EtherCAT bus:"),
                                         text=self.pending.bus.adapter)
        if text is not None:
            self._set(with_bus(self.pending, adapter=text.strip()))

    def change_password(self) -> None:
        d = self.ctx.dialogs
        access = self.ctx.access
        assert access is not None
        old = d.ask_text(self, tr("Service password"), tr("Current service password:"), password=True)
        if old is None:
            return
        prompt = tr("New service password (at least {0} characters):").format(MIN_LENGTH)
        new = d.ask_text(self, tr("Service password"), prompt, password=True)
        if new is None:
            return
        again = d.ask_text(self, tr("Service password"), tr("Repeat the new password:"), password=True)
        if again is None:
            return
        outcome = access.change_password(old, new, again)
        if outcome:
            d.inform(self, tr("Service password"), tr("The service password was changed."))
        else:
            d.inform(self, tr("Service password"), tr("Nothing changed: {0}").format(outcome.reason))

    def lock(self) -> None:
        if self.ctx.access is not None:
            self.ctx.access.lock()
        window = self.window()
        lock = getattr(window, "lock_service", None)
        if lock is not None:
            lock()


def create_page(context: PanelContext) -> QWidget:
    return ParametersPage(context)
