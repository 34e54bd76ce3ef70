"""EtherCAT slaves and their states, bus figures, and the cycle-timing histogram."""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PySide6.QtWidgets import QLabel, QTableWidget, QTableWidgetItem, QVBoxLayout, QWidget

from app.i18n import N_, I18n, tr

SLAVE_COLUMNS = (N_("Position"), N_("Axis"), N_("Vendor"), N_("Product"), N_("State"))
#: the worker's state as the panel says it (``BusStatus.state``: the state's name in lower case)
WORKER_STATE_TEXT = {"disconnected": N_("disconnected"), "stopped": N_("stopped"), "starting": N_("starting"),
                     "disabled": N_("disabled"), "enabling": N_("enabling"), "enabled": N_("enabled"),
                     "homing": N_("homing"), "quick_stop": N_("quick stop"), "fault": N_("fault"),
                     "fault_reset": N_("fault reset"), "error": N_("error")}


class BusView(QWidget):
    def __init__(self, i18n: I18n, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        layout = QVBoxLayout(self)
        self.summary = QLabel()
        self.summary.setWordWrap(True)
        layout.addWidget(self.summary)
        # the probe input as the drive reads it: wiring and level are checked here by touching
        # the stylus by hand
        self.probe = QLabel()
        self.probe.setObjectName("probeState")
        layout.addWidget(self.probe)
        self.table = QTableWidget(0, len(SLAVE_COLUMNS))
        self.table.setEditTriggers(QTableWidget.EditTrigger.NoEditTriggers)
        self.table.horizontalHeader().setStretchLastSection(True)
        layout.addWidget(self.table, 1)
        self.histogram_title = QLabel()
        i18n.bind(self.histogram_title, N_("Cycle timing: start jitter histogram (µs)"))
        layout.addWidget(self.histogram_title)
        self.histogram = pg.PlotWidget(background="#0a0d10")
        self.histogram.getPlotItem().hideButtons()
        self.bars = pg.BarGraphItem(x=[], height=[], width=1.0, brush="#40e0d0")
        self.histogram.addItem(self.bars)
        layout.addWidget(self.histogram, 1)
        self._bus: object | None = None
        self._config: object | None = None
        i18n.languageChanged.connect(lambda _l: self.refresh())
        self.refresh()

    def set_state(self, bus: object, config: object) -> None:
        self._bus, self._config = bus, config
        self.refresh()

    def refresh(self) -> None:
        bus, config = self._bus, self._config
        self.table.setHorizontalHeaderLabels([tr(c) for c in SLAVE_COLUMNS])
        self.histogram.setLabel("bottom", tr(N_("start jitter (µs)")))
        self.histogram.setLabel("left", tr(N_("cycles")))
        if bus is None or config is None:
            return
        # the loop's drives: the axes', then each gantry's second drive; their identities by position
        ids = {d.position: d for d in tuple(getattr(getattr(config, "bus", None), "drives", ()) or ())}
        drives = tuple(getattr(config, "drives", ()) or ())
        states = tuple(getattr(bus, "drive_states", ()) or ())
        n_axes = len(getattr(config, "axes", ()) or ())
        skews = tuple(getattr(bus, "gantry_skew", ()) or ())
        comp = tuple(getattr(bus, "compensation", ()) or ())
        compensated = {spec.axis for spec in getattr(config, "compensation", ()) or ()}
        n = max(len(drives), len(states))
        terminals = tuple(getattr(getattr(config, "wiring", None), "terminals", ()) or ())
        spindle = getattr(getattr(config, "spindle", None), "spec", None)    # its own drive, or None
        self.table.setRowCount(n + len(terminals) + (spindle is not None))
        for row in range(n):
            position, name = drives[row] if row < len(drives) else (row, "")
            d = ids.get(position)
            if n_axes <= row < len(skews):                   # a gantry's second side and its skew
                name = tr("{0} (gantry {1}, skew {2:+.4f})").format(name, name[:-1], skews[row])
            elif row < len(comp) and row in compensated:      # the leadscrew correction it is sent
                name = tr("{0} (compensation {1:+.4f})").format(name, comp[row])
            values = (
                str(position),
                name,
                f"0x{d.vendor_id:08X}" if d is not None else "",
                f"0x{d.product_code:08X}" if d is not None else "",
                states[row] if row < len(states) else tr("unknown"),
            )
            for col, text in enumerate(values):
                self.table.setItem(row, col, QTableWidgetItem(text))
        up = bool(getattr(bus, "connected", False))
        for k, t in enumerate(terminals):        # the terminals beside the drives
            tt = t.terminal_type
            values = (str(t.position), f"{t.name} ({tt.name})" if t.name else tt.name,
                      f"0x{tt.vendor_id:08X}", f"0x{tt.product_code:08X}", "OP" if up else tr("unknown"))
            for col, text in enumerate(values):
                self.table.setItem(n + k, col, QTableWidgetItem(text))
        if spindle is not None:                  # the spindle's own drive, after them
            state = str(getattr(bus, "spindle_state", "") or "") or tr("unknown")
            values = (str(spindle.position), tr("spindle"), f"0x{spindle.vendor_id:08X}",
                      f"0x{spindle.product_code:08X}", state)
            for col, text in enumerate(values):
                self.table.setItem(n + len(terminals), col, QTableWidgetItem(text))
        probe = str(getattr(bus, "probe", "") or "")
        self.probe.setText({"touching": tr("Probe input: touching"), "free": tr("Probe input: free")}.get(
            probe, tr("Probe input: none ([probe] drive in the machine configuration)")))
        connected = tr("connected") if getattr(bus, "connected", False) else tr("not connected")
        self.summary.setText(tr("Bus {0} ({1}): {2}. Buffer {3} set-points, late cycles {4}, "
                                "period p99 {5:.1f} µs, max jitter {7:.0f} µs. {6}").format(
            str(getattr(bus, "kind", "")).upper(), _worker_state(str(getattr(bus, "state", ""))), connected,
            getattr(bus, "buffer_level", 0), getattr(bus, "late_cycles", 0),
            float(getattr(bus, "period_p99_us", 0.0)), getattr(bus, "message", ""),
            float(getattr(bus, "jitter_max_us", 0.0))))
        width_us = float(getattr(bus, "jitter_hist_bin_us", 0.0) or 0.0)
        counts = np.asarray(getattr(bus, "jitter_hist_counts", ()) or (), float)
        if width_us > 0 and len(counts):  # bins from 0 us; the last one collects the overflow
            centres = (np.arange(len(counts)) + 0.5) * width_us
            self.bars.setOpts(x=centres, height=counts, width=width_us * 0.9)


def _worker_state(state: str) -> str:
    return tr(WORKER_STATE_TEXT[state]) if state in WORKER_STATE_TEXT else state
