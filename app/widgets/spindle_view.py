"""The spindle's own drive on the Diagnostics page: the speed commanded and the speed its drive
reads (rpm) against time, live at <= 30 Hz, and whether it is at speed. A spindle on a VFD's
analog input: the speed commanded and the volts sent on the analog output (nothing is read
back). Without either, the page says the spindle is switched by output bits and no speed is
read."""

from __future__ import annotations

import pyqtgraph as pg
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QLabel, QVBoxLayout, QWidget

from app.i18n import I18n, tr
from app.live_buffer import RingBuffer
from app.machine.model import SpindleState
from app.machine.spindle_settings import SpindleDriveSettings

__all__ = ["SpindleView"]

LIVE_SECONDS = 120


class SpindleView(QWidget):
    """``add_sample(t, commanded, read)`` from the controller's ``spindleSample``; ``redraw``
    on the page's timer."""

    def __init__(self, i18n: I18n, settings: SpindleDriveSettings, max_rpm: float,
                 parent: QWidget | None = None) -> None:
        super().__init__(parent)
        layout = QVBoxLayout(self)
        self.label = QLabel()
        self.label.setObjectName("spindleSpeedLabel")
        self.label.setWordWrap(True)
        layout.addWidget(self.label)
        self.plot = pg.PlotWidget(background="#0a0d10")
        self.plot.getPlotItem().hideButtons()
        self.plot.showGrid(x=True, y=True, alpha=0.25)
        self.plot.addLegend(offset=(10, 10))
        self.plot.setLabel("bottom", "t", units="s")
        self.plot.setLabel("left", "rpm")
        self.commanded = self.plot.plot(pen=pg.mkPen("#ffb347", width=1, style=Qt.PenStyle.DashLine),
                                        name=tr("commanded"))
        self.read = self.plot.plot(pen=pg.mkPen("#40e0d0", width=2), name=tr("read"))
        layout.addWidget(self.plot, 1)
        self.buffer = RingBuffer(LIVE_SECONDS * 30, 2)
        self.settings = settings
        self.max_rpm = max_rpm
        self._dirty = False
        self._last: tuple[float, float] | None = None
        self._spindle = SpindleState()
        i18n.languageChanged.connect(lambda _l: self._show())
        self._show()

    @property
    def drive(self) -> SpindleDriveSettings | None:
        """The spindle's own drive (None: none)."""
        return self.settings if self.settings.drive is not None else None

    def set_settings(self, settings: SpindleDriveSettings, max_rpm: float) -> None:
        """The spindle of the configuration in force; the plot starts anew."""
        self.settings = settings
        self.max_rpm = max_rpm
        self.buffer.clear()
        self._last = None
        self._dirty = True
        self._show()

    def add_sample(self, time_s: float, commanded_rpm: float, read_rpm: float) -> None:
        self.buffer.append(time_s, (commanded_rpm, read_rpm))
        changed = self._last is None or round(self._last[0]) != round(commanded_rpm) \
            or round(self._last[1]) != round(read_rpm)
        self._last = (commanded_rpm, read_rpm)
        self._dirty = True
        if changed:
            self._show()

    def set_spindle(self, spindle: object) -> None:
        """The spindle as the controller commands it (``spindleChanged``): what a VFD is sent."""
        if isinstance(spindle, SpindleState):
            self._spindle = spindle
            if self.drive is None:
                self._show()

    def redraw(self) -> None:
        if not self._dirty:
            return
        self._dirty = False
        t, values = self.buffer.ordered()
        self.commanded.setData(t, values[:, 0])
        self.read.setData(t, values[:, 1])

    @property
    def text(self) -> str:
        return self.label.text()

    def _show(self) -> None:
        if self.drive is None and self.settings.analog_out:
            sp = self._spindle
            volts = 10.0 * self.settings.analog_share(sp.commanded_rpm, sp.on, self.max_rpm)
            rpm = sp.commanded_rpm if sp.on else 0.0
            self.label.setText(tr("Spindle on a VFD (analog output {0}): {1} rpm commanded, {2} V sent; "
                                  "no speed is read").format(self.settings.analog_out, f"{rpm:.0f}",
                                                             f"{volts:.2f}"))
            return
        if self.drive is None:
            self.label.setText(tr("No spindle drive: the spindle is switched by output bits; "
                                  "no speed is read"))
            return
        if self._last is None:
            self.label.setText(tr("Spindle drive: no speed read yet"))
            return
        cmd, act = self._last
        if cmd == 0.0 and abs(act) < 1.0:
            state = tr("stopped")
        else:
            state = tr("at speed") if self.drive.at_speed(cmd, act) else tr("not at speed")
        self.label.setText(tr("Spindle drive: {0} rpm commanded, {1} rpm read: {2}").format(
            f"{cmd:.0f}", f"{act:.0f}", state))
