"""Reference vs actual per axis (Fig. 17) and the RMSE / MSE table (Table 4, Eq. 18).

Live: actual positions arrive at <= 30 Hz into a preallocated ring buffer and are drawn on a
30 Hz timer. After a run, the controller's NPZ trace gives reference and actual per 1 ms.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QHBoxLayout, QLabel, QTableWidget, QTableWidgetItem, QVBoxLayout, QWidget

from app.format import format_value
from app.i18n import N_, I18n, tr
from app.live_buffer import RingBuffer

COLORS = ("#40e0d0", "#4cdf6a", "#ffb347", "#ff7fd0", "#8fb8ff", "#ffd27f")
LIVE_SECONDS = 120


def load_trace(path: str) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """(t, reference, actual) from the controller's NPZ trace, tolerant to key names."""
    if not path or not Path(path).exists():
        return None
    with np.load(path) as data:
        keys = set(data.files)
        ref_key = next((k for k in ("reference", "ref", "q_ref") if k in keys), None)
        act_key = next((k for k in ("actual", "act", "q_act") if k in keys), None)
        if ref_key is None or act_key is None:
            return None
        ref, act = np.asarray(data[ref_key]), np.asarray(data[act_key])
        t = np.asarray(data["t"]) if "t" in keys else np.arange(len(ref)) * 0.001
    return t, ref, act


class TrackingView(QWidget):
    def __init__(self, axes: Sequence[str], i18n: I18n, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.axes = tuple(axes)
        layout = QHBoxLayout(self)
        self.plot = pg.PlotWidget(background="#0a0d10")
        self.plot.getPlotItem().hideButtons()
        self.plot.showGrid(x=True, y=True, alpha=0.25)
        self.plot.addLegend(offset=(10, 10))
        self.plot.setLabel("bottom", "t", units="s")
        self.plot.setDownsampling(auto=True, mode="peak")
        self.plot.setClipToView(True)
        self.actual = [self.plot.plot(pen=pg.mkPen(COLORS[i % 6], width=2), name=f"{a}")
                       for i, a in enumerate(self.axes)]
        dash = Qt.PenStyle.DashLine
        self.reference = [self.plot.plot(pen=pg.mkPen(COLORS[i % 6], width=1, style=dash))
                          for i in range(len(self.axes))]
        layout.addWidget(self.plot, 3)
        side = QVBoxLayout()
        self.title = QLabel()
        i18n.bind(self.title, N_("Tracking (reference − actual), Eq. 18"))
        side.addWidget(self.title)
        self.table = QTableWidget(len(self.axes), 3)
        self.table.setVerticalHeaderLabels(list(self.axes))
        self.table.setEditTriggers(QTableWidget.EditTrigger.NoEditTriggers)
        side.addWidget(self.table)
        self.samples_label = QLabel()
        side.addWidget(self.samples_label)
        side.addStretch(1)
        layout.addLayout(side, 2)
        self.buffer = RingBuffer(LIVE_SECONDS * 30, 2 * len(self.axes))  # reference | actual
        self._dirty = False
        self._report: object | None = None
        i18n.languageChanged.connect(lambda _l: self.set_report(self._report))
        self.set_report(None)

    def add_sample(self, time_s: float, reference: Sequence[float], actual: Sequence[float]) -> None:
        """One live sample (<= 30 Hz, from the controller's trackingSample)."""
        n = len(self.axes)
        row = np.empty(2 * n)
        row[:n] = reference[:n]
        row[n:] = actual[:n]
        self.buffer.append(time_s, row)
        self._dirty = True

    def redraw(self) -> None:
        """Called by the page's 30 Hz timer: copy the buffer into the curves when it changed."""
        if not self._dirty:
            return
        self._dirty = False
        t, values = self.buffer.ordered()
        n = len(self.axes)
        for i in range(n):
            self.reference[i].setData(t, values[:, i])
            self.actual[i].setData(t, values[:, n + i])

    def show_trace(self, trace: tuple[np.ndarray, np.ndarray, np.ndarray]) -> None:
        t, ref, act = trace
        for i in range(min(len(self.axes), ref.shape[1])):
            self.reference[i].setData(t, ref[:, i])
            self.actual[i].setData(t, act[:, i])

    def set_report(self, report: object | None) -> None:
        self._report = report
        self.table.setHorizontalHeaderLabels([tr("RMSE"), tr("MSE"), tr("max |e|")])
        rmse = tuple(getattr(report, "rmse", ()) or ())
        mse = tuple(getattr(report, "mse", ()) or ())
        mx = tuple(getattr(report, "max_abs", ()) or ())
        for row in range(len(self.axes)):
            for col, values in enumerate((rmse, mse, mx)):
                text = format_value(values[row]) if row < len(values) else "---"
                self.table.setItem(row, col, QTableWidgetItem(text))
        self.samples_label.setText(tr("Samples: {0}").format(int(getattr(report, "samples", 0) or 0)))
