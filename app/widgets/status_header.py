"""Always visible: DRO, machine state, bus state, E-stop state and button, active alarm banner."""

from __future__ import annotations

from PySide6.QtCore import Qt, QTimer
from PySide6.QtGui import QFont, QFontMetrics, QResizeEvent
from PySide6.QtWidgets import QHBoxLayout, QLabel, QPushButton, QSizePolicy, QVBoxLayout, QWidget

from app.context import PanelContext
from app.controller_text import localize, source_text
from app.dialogs import connect_or_disconnect
from app.format import tool_text
from app.i18n import N_, tr
from app.machine.model import Alarm, BusStatus, MachineState
from app.widgets.dro import DroWidget
from planner.core.tools import ToolTable

STATE_TEXT = {  # MachineState.value -> label (translated when shown)
    "disconnected": N_("Disconnected"), "idle": N_("Idle"), "homing": N_("Homing"),
    "running": N_("Running"), "hold": N_("Feed hold"), "alarm": N_("Alarm"), "estop": N_("E-stop"),
}
HOLD_TEXT = {  # HoldKind.value -> label: a stop named for what it is
    "feed_hold": N_("Feed hold"), "single_block": N_("Single block"), "program_stop": N_("Program stop (M0)"),
    "optional_stop": N_("Optional stop (M1)"), "tool_change": N_("Tool change"), "stopping": N_("Stopping"),
}
STATE_COLOR = {
    "disconnected": "#6b7783", "idle": "#2f6f9f", "homing": "#8f5fbf", "running": "#1b7f3a",
    "hold": "#a86b00", "alarm": "#b00020", "estop": "#b00020",
}


#: the reasons that only repeat the activity: the state reads "Running" with them
_ACTIVITIES = frozenset({"program", "mdi", "jog", "approach", "homing", "none"})


#: the alarm banner's least width: "ALARM: <source>: <the start of its cause>" stays readable
BANNER_MIN_PX = 320


class AlarmBanner(QPushButton):
    """The newest alarm in the status bar: its whole text in the tooltip, shown cut with "…" to
    the width it gets (never clipped mid-letter, never squeezed below ``BANNER_MIN_PX``)."""

    def __init__(self) -> None:
        super().__init__()
        self.full_text = ""
        self.setMinimumWidth(BANNER_MIN_PX)
        self.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Preferred)

    def set_full_text(self, text: str) -> None:
        self.full_text = text
        self.setToolTip(text)
        self._fit()

    def resizeEvent(self, event: QResizeEvent) -> None:  # noqa: N802 - Qt override
        super().resizeEvent(event)
        self._fit()

    def _fit(self) -> None:
        room = max(self.contentsRect().width() - 24, 0)          # the button's own padding
        self.setText(self.fontMetrics().elidedText(self.full_text, Qt.TextElideMode.ElideRight, room))


class StatusHeader(QWidget):
    def __init__(self, context: PanelContext, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("statusHeader")
        self.ctx = context
        c = context.controller
        outer = QVBoxLayout(self)
        outer.setContentsMargins(0, 0, 0, 0)
        outer.setSpacing(2)
        row = QHBoxLayout()
        self.dro = DroWidget(c.axes, c.config.machine.rotary, context.i18n,
                             wrapped=tuple(a.wrapped for a in c.config.machine.axes))
        row.addWidget(self.dro, 1)
        status = QVBoxLayout()
        self.state_label = QLabel()
        self.state_label.setObjectName("machineState")
        self.state_label.setAlignment(Qt.AlignmentFlag.AlignCenter)
        self.state_label.setFixedWidth(240)     # as the tool's: a long state never moves the header
        # and as high as its larger font's line: a long state (in 16 px) never shrinks the header
        big = QFont(self.state_label.font())
        big.setPixelSize(22)
        big.setWeight(QFont.Weight.ExtraBold)
        self.state_label.setFixedHeight(QFontMetrics(big).height() + 12)      # the 6 px padding
        self.bus_label = QPushButton()  # tap: connect / disconnect the drives (confirmed)
        self.bus_label.setObjectName("busState")
        self.bus_label.clicked.connect(self._bus_clicked)
        self.tool_label = QLabel()               # the tool in the spindle, always in sight
        self.tool_label.setObjectName("toolLabel")
        self.tool_label.setAlignment(Qt.AlignmentFlag.AlignCenter)
        self.tool_label.setFixedWidth(240)      # a long description never widens the header
        status.addWidget(self.state_label)
        status.addWidget(self.bus_label)
        status.addWidget(self.tool_label)
        row.addLayout(status)
        self.estop_button = QPushButton()
        self.estop_button.setObjectName("estopButton")
        self.estop_button.setCheckable(False)
        self.estop_button.setMinimumSize(96, 80)
        self.estop_button.clicked.connect(self._estop_clicked)
        row.addWidget(self.estop_button)
        outer.addLayout(row)
        # the window puts the banner in its status bar (fixed height): an alarm appearing never
        # moves a control, so a tap lands where the operator aimed
        self.alarm_banner = AlarmBanner()
        self.alarm_banner.setObjectName("alarmBanner")
        self.alarm_banner.setVisible(False)

        self._state = c.state
        self._bus = c.bus_status
        self._alarms = c.active_alarms
        c.stateChanged.connect(self._on_state)
        self._feed_pct = float(c.feed_override_pct)
        c.overridesChanged.connect(self._on_overrides)
        c.positionChanged.connect(self._on_position)
        c.statusChanged.connect(lambda snap: self.dro.set_frame(snap.frame))
        c.homedChanged.connect(self.dro.set_homed)
        c.busStateChanged.connect(self._on_bus)
        c.alarmsChanged.connect(self._on_alarms)
        self._tools, self._tool = c.tool_table, c.tool_in_spindle
        c.toolsChanged.connect(self._on_tools)
        context.i18n.languageChanged.connect(lambda _lang: self.refresh())
        # the machine's E-stop chain and door, where they are wired (read 5 times a second): a
        # second line of the bus button, red when one is open
        self._safety: tuple[bool | None, bool | None] = (None, None)
        self.safety_text = ""
        self._safety_bad = False
        self._safety_timer = QTimer(self)
        self._safety_timer.setInterval(200)
        self._safety_timer.timeout.connect(self._poll_safety)
        self._safety_timer.start()
        self.dro.set_positions(c.machine_position, c.work_position)
        self.dro.set_homed(c.homed)
        self.dro.set_frame(c.snapshot().frame)
        self.refresh()

    # --- controller signals --------------------------------------------------------------
    def _on_state(self, state: MachineState, reason: str) -> None:
        self._state = state
        self._reason = str(reason)
        self.refresh()

    def _on_position(self, machine: tuple[float, ...], work: tuple[float, ...]) -> None:
        self.dro.set_positions(machine, work)
        self.dro.set_distance_to_go(self.ctx.controller.distance_to_go)

    def _on_overrides(self, feed: float, _rapid: float) -> None:
        self._feed_pct = float(feed)
        self.refresh()

    def _on_bus(self, bus: BusStatus) -> None:
        self._bus = bus
        self.refresh()

    def _on_alarms(self, alarms: tuple[Alarm, ...]) -> None:
        self._alarms = tuple(a for a in alarms if a.active)
        self.refresh()

    def _bus_clicked(self) -> None:
        connected = bool(getattr(self._bus, "connected", False))
        connect_or_disconnect(self, self.ctx.dialogs, self.ctx.controller, connected)

    def _estop_clicked(self) -> None:
        if self._state_value() == "estop":
            if self.ctx.dialogs.confirm(self, tr("Release E-stop"),
                                        tr("Release the emergency stop and enable the drives?")):
                self.ctx.controller.estop_release()
        else:
            self.ctx.controller.estop("operator")

    def _on_tools(self, table: ToolTable, in_spindle: int) -> None:
        self._tools, self._tool = table, int(in_spindle)
        self.refresh()

    def _poll_safety(self) -> None:
        values = {r.key: r.value for r in self.ctx.controller.signal_readings()
                  if r.key in ("estop_chain_ok", "door_closed")}
        now = (values.get("estop_chain_ok"), values.get("door_closed"))
        if now != self._safety:
            self._safety = now
            self.refresh()

    def _show_safety(self) -> None:
        chain, door = self._safety
        # short enough for the button's 240 px: what is open, in capitals, or all closed
        if chain is False and door is False:
            opened = tr("CHAIN & DOOR OPEN")
        else:
            opened = tr("E-STOP CHAIN OPEN") if chain is False else tr("DOOR OPEN") if door is False else ""
        if opened:
            self.safety_text, self._safety_bad = opened, True
            return
        closed = {(True, True): tr("chain and door closed"), (True, None): tr("E-stop chain closed"),
                  (None, True): tr("door closed")}
        self.safety_text, self._safety_bad = closed.get((chain, door), ""), False

    # --- display -------------------------------------------------------------------------
    def _state_font_px(self, text: str) -> int:
        """The largest of the state label's font sizes that shows ``text`` whole in one line of
        its 240 px (its padding aside): "Held by feed override 0 %" needs 16 px, in Turkish 14."""
        font = QFont(self.state_label.font())
        font.setWeight(QFont.Weight.ExtraBold)
        room = self.state_label.width() - 12
        for px in (22, 18, 16, 15, 14, 13, 12):
            font.setPixelSize(px)
            if QFontMetrics(font).horizontalAdvance(text) <= room:
                return px
        return 11

    def _state_value(self) -> str:
        return str(getattr(self._state, "value", self._state))

    def refresh(self) -> None:
        self._show_safety()
        value = self._state_value()
        text = STATE_TEXT.get(value, value)
        if value == "hold":
            hold = str(getattr(getattr(self.ctx.controller, "hold_kind", None), "value", ""))
            text = HOLD_TEXT.get(hold, text)
        elif value == "running" and self._feed_pct == 0.0:
            text = N_("Held by feed override 0 %")   # running, and nothing moves until it is raised
        text = tr(text)
        reason = getattr(self, "_reason", "")
        if value == "running" and self._feed_pct != 0.0 and reason and reason not in _ACTIVITIES:
            said = localize(reason)                 # what runs, named: "Measuring tool T1"
            text = said[:1].upper() + said[1:]
        self.state_label.setText(text)
        size = self._state_font_px(text)
        self.state_label.setStyleSheet(
            f"background: {STATE_COLOR.get(value, '#26303b')}; color: white; font-size: {size}px;"
            "font-weight: 800; padding: 6px; border-radius: 6px;")
        bus = self._bus
        kind = str(getattr(bus, "kind", "")).upper()
        connected = bool(getattr(bus, "connected", False))
        bus_text = tr("Bus {0}: {1}").format(kind, tr("connected") if connected else tr("not connected"))
        self.bus_label.setText(bus_text + ("\n" + self.safety_text if self.safety_text else ""))
        ok = connected and not self._safety_bad
        self.bus_label.setProperty("ok", ok)
        self.bus_label.setStyleSheet("color: %s; font-weight: 700; background: transparent; border: 0;"
                                     % ("#7fe0a0" if ok else "#ff9080"))
        self.estop_button.setText(tr("RELEASE\nE-STOP") if value == "estop" else tr("E-STOP"))
        # as wide as the wider of its two texts in this language: pressing it never moves the header
        fm = self.estop_button.fontMetrics()
        widest = max(fm.horizontalAdvance(line) for text in (tr("RELEASE\nE-STOP"), tr("E-STOP"))
                     for line in text.split("\n"))
        self.estop_button.setFixedWidth(max(96, widest + 32))
        text = tr("Tool: {0}").format(tool_text(self._tools, self._tool))
        self.tool_label.setToolTip(text)
        metrics = self.tool_label.fontMetrics()
        self.tool_label.setText(metrics.elidedText(text, Qt.TextElideMode.ElideRight, 236))
        alarms = self._alarms
        if alarms:
            last = alarms[-1]
            more = tr(" (+{0} more)").format(len(alarms) - 1) if len(alarms) > 1 else ""
            said = tr("ALARM: {0}: {1}").format(source_text(last.source), localize(last.cause))
            self.alarm_banner.set_full_text(said + more)
        self.alarm_banner.setVisible(bool(alarms))
