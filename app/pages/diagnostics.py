"""Diagnostics: v/a/j of the loaded program against time (Fig. 14), reference vs actual per
axis with RMSE/MSE (Fig. 17, Table 4), EtherCAT slaves and states, cycle-timing histogram, the
production log, and the machine's signals live with where each is wired."""

from __future__ import annotations

import functools

from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QLabel, QPushButton, QTabWidget, QVBoxLayout, QWidget

from app.background import Background
from app.context import PanelContext
from app.dialogs import connect_or_disconnect
from app.format import format_duration
from app.i18n import N_, tr
from app.path_profile import PathProfile, path_profile
from app.widgets.bus_view import BusView
from app.widgets.production_view import ProductionView
from app.widgets.profile_plots import ProfilePlots
from app.widgets.signals_view import SignalsView
from app.widgets.spindle_view import SpindleView
from app.widgets.tracking_view import TrackingView, load_trace

REDRAW_MS = 33  # 30 Hz


class DiagnosticsPage(QWidget):

    def __init__(self, context: PanelContext, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("diagnosticsPage")
        self.ctx = context
        c = context.controller
        i18n = context.i18n
        layout = QVBoxLayout(self)
        self.tabs = QTabWidget()
        layout.addWidget(self.tabs)
        profile_tab = QWidget()
        pl = QVBoxLayout(profile_tab)
        self.profile_label = QLabel()
        pl.addWidget(self.profile_label)
        self.profile_plots = ProfilePlots()
        pl.addWidget(self.profile_plots, 1)
        self.tracking = TrackingView(c.axes, i18n)
        self.bus = BusView(i18n)
        # Connect / Disconnect as a button of its own (the header's bus status does the same)
        self.connect_button = QPushButton()
        self.connect_button.setObjectName("connectButton")
        self.connect_button.setMinimumHeight(56)
        self.connect_button.clicked.connect(
            lambda: connect_or_disconnect(self, self.ctx.dialogs, self.ctx.controller,
                                          bool(self.ctx.controller.bus_status.connected)))
        bus_layout = self.bus.layout()
        assert isinstance(bus_layout, QVBoxLayout)
        bus_layout.insertWidget(0, self.connect_button)
        # the OPC UA server: where a shop's clients find the machine, or why they cannot
        self.opcua_label = QLabel()
        self.opcua_label.setObjectName("opcuaLabel")
        self.opcua_label.setWordWrap(True)
        bus_layout.insertWidget(1, self.opcua_label)
        self.tabs.addTab(profile_tab, "")
        self.tabs.addTab(self.tracking, "")
        self.tabs.addTab(self.bus, "")
        self.production = ProductionView(context)
        self.tabs.addTab(self.production, "")
        self.signals = SignalsView(i18n)
        self.tabs.addTab(self.signals, "")
        self.spindle = SpindleView(i18n, c.config.spindle, c.config.controller.spindle_max_rpm)
        self.tabs.addTab(self.spindle, "")
        for index, text in enumerate((N_("Path v / a / j"), N_("Tracking"), N_("EtherCAT"),
                                      N_("Production"), N_("Signals"), N_("Spindle"))):
            i18n.bind(self.tabs, text, functools.partial(self.tabs.setTabText, index))

        self.profile: PathProfile | None = None
        self._planning = Background("diag-plan", self._on_profile, self)
        self._profile_state = N_("No program loaded.")
        self._profile_stale = False   # the program changed while the page was not shown
        context.program.changed.connect(self.compute_profile)
        c.trackingSample.connect(self.tracking.add_sample)
        c.spindleSample.connect(self.spindle.add_sample)
        c.configChanged.connect(
            lambda cfg: self.spindle.set_settings(cfg.spindle, cfg.controller.spindle_max_rpm))
        c.spindleChanged.connect(self.spindle.set_spindle)
        c.trackingUpdated.connect(self.tracking.set_report)
        c.programFinished.connect(self._on_finished)
        c.busStateChanged.connect(lambda bus: self.bus.set_state(bus, c.config))
        c.busStateChanged.connect(lambda _bus: self._show_connect())
        i18n.languageChanged.connect(lambda _l: self._show_connect())
        i18n.languageChanged.connect(lambda _l: self._show_opcua())
        c.statusChanged.connect(lambda _snap: self._show_opcua())
        i18n.languageChanged.connect(lambda _l: self._show_profile_state())
        i18n.languageChanged.connect(lambda _l: self.profile_plots.retranslate())
        self.bus.set_state(c.bus_status, c.config)
        self._show_connect()
        self._show_opcua()
        self.tracking.set_report(c.tracking)
        self.timer = QTimer(self)
        self.timer.setInterval(REDRAW_MS)
        self.timer.timeout.connect(self.tracking.redraw)
        self.timer.timeout.connect(self.spindle.redraw)
        self.timer.timeout.connect(self._show_signals)
        self.compute_profile()

    def _show_signals(self) -> None:
        if self.tabs.currentWidget() is self.signals:
            self.signals.show_readings(self.ctx.controller.signal_readings())

    def _show_connect(self) -> None:
        connected = bool(self.ctx.controller.bus_status.connected)
        self.connect_button.setText(tr("Disconnect the drives") if connected else tr("Connect to the drives"))

    def _show_opcua(self) -> None:
        c = self.ctx.controller
        status, settings = c.opcua_status, c.opcua_settings
        warn = False
        if status is None:
            text = tr("OPC UA server: off ([opcua] enabled = false)")
        elif status.error:
            text, warn = tr("OPC UA server: not serving: {0}").format(status.error), True
        elif not status.running:
            text = tr("OPC UA server: starting at {0}").format(status.endpoint)
        elif settings.insecure:
            text = tr("OPC UA server: serving {0} with security None: anyone who reaches the port "
                      "reads the machine").format(status.endpoint)
            warn = True
        else:
            text = tr("OPC UA server: serving {0} ({1}), certificate SHA-1 {2}").format(
                status.endpoint, ", ".join(m.value for m in settings.security), status.thumbprint)
        if text != self.opcua_label.text():
            self.opcua_label.setText(text)
            self.opcua_label.setProperty("warning", warn)
            self.opcua_label.style().polish(self.opcua_label)

    def showEvent(self, event) -> None:  # noqa: N802 - Qt override
        self.timer.start()
        super().showEvent(event)
        if self._profile_stale:
            self.compute_profile()

    def hideEvent(self, event) -> None:  # noqa: N802 - Qt override
        self.timer.stop()
        super().hideEvent(event)

    # --- path profile (computed off the GUI thread) ---------------------------------------
    def compute_profile(self) -> None:
        program = self.ctx.program.program
        self._planning.cancel()
        if program is None:
            self.profile = None
            self.profile_plots.set_profile(None)
            self._profile_state = N_("No program loaded.")
            self._show_profile_state()
            return
        if not self.isVisible():
            # planned when the page is shown: a program of millions of moves was planned
            # for this page while its preview's copies were made, 120 MB more at once
            self._profile_stale = True
            self.profile = None
            self.profile_plots.set_profile(None)
            self._profile_state = N_("Planned when this page is shown.")
            self._show_profile_state()
            return
        self._profile_stale = False
        machine = self.ctx.controller.config.machine
        plan = getattr(self.ctx.program.info, "plan", None)
        planned_s = float(getattr(self.ctx.program.info, "plan_end_s", float("nan")))
        self._profile_state = N_("Planning…")
        self._show_profile_state()
        self._planning.submit(lambda: path_profile(program, machine, plan=plan, cycle_time_s=planned_s))

    def _on_profile(self, result: object) -> None:
        if isinstance(result, Exception):  # shown on the page, never kills the panel
            result = f"{type(result).__name__}: {result}"
        if isinstance(result, PathProfile):
            self.profile = result
            self.profile_plots.set_profile(result)
            self._profile_state = ""
        else:
            self._profile_state = str(result)
        self._show_profile_state()

    def _show_profile_state(self) -> None:
        p = self.profile
        if self._profile_state:
            self.profile_label.setText(tr(self._profile_state))
        elif p is not None:
            vmax, amax, jmax = p.limits
            text = tr("Cycle time {0}; limits Vmax {1:g} mm/s, Amax {2:g} mm/s², Jmax {3:g} mm/s³"
                      ).format(format_duration(p.cycle_time_s), vmax, amax, jmax)
            if p.truncated:
                text += tr(" (first {0:.0f} s shown)").format(p.t[-1] if len(p.t) else 0.0)
            self.profile_label.setText(text)

    def _on_finished(self, summary: object) -> None:
        report = getattr(summary, "tracking", None)
        if report is not None:
            self.tracking.set_report(report)
            trace = load_trace(str(getattr(report, "trace_path", "") or ""))
            if trace is not None:
                self.tracking.show_trace(trace)


def create_page(context: PanelContext) -> QWidget:
    return DiagnosticsPage(context)
