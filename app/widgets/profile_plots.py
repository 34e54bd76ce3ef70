"""Three stacked plots sharing the time axis: path speed, acceleration and jerk (Fig. 14)."""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QVBoxLayout, QWidget

from app.i18n import N_, tr
from app.path_profile import PathProfile

RAPID = N_("rapid")
ROWS = (("v", "mm/s", "#40e0d0"), ("a", "mm/s²", "#4cdf6a"), ("j", "mm/s³", "#ffb347"))


class ProfilePlots(QWidget):
    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        self.view = pg.GraphicsLayoutWidget()
        self.view.setBackground("#0a0d10")
        layout.addWidget(self.view)
        self.plots: dict[str, pg.PlotItem] = {}
        self.curves: dict[str, pg.PlotDataItem] = {}
        self.limit_lines: dict[str, tuple[pg.InfiniteLine, pg.InfiniteLine]] = {}
        first = None
        for row, (key, unit, color) in enumerate(ROWS):
            plot = self.view.addPlot(row=row, col=0)
            plot.hideButtons()
            plot.showGrid(x=True, y=True, alpha=0.25)
            plot.setLabel("left", key, units=unit)
            plot.setDownsampling(auto=True, mode="peak")
            plot.setClipToView(True)
            if first is None:
                first = plot
            else:
                plot.setXLink(first)
            curve = plot.plot(pen=pg.mkPen(color, width=2))
            pen = pg.mkPen("#ff4060", width=1, style=Qt.PenStyle.DashLine)
            lo, hi = pg.InfiniteLine(angle=0, pen=pen), pg.InfiniteLine(angle=0, pen=pen)
            plot.addItem(lo)
            plot.addItem(hi)
            self.plots[key], self.curves[key], self.limit_lines[key] = plot, curve, (lo, hi)
        self.plots["j"].setLabel("bottom", "t", units="s")
        # Path speed is never negative: its lower line marks the rapid limit instead (G00 moves
        # may run above the feed limit Vmax, up to the rapid speed).
        self.limit_lines["v"][0].setPen(pg.mkPen("#ffd27f", width=1, style=Qt.PenStyle.DotLine))
        self.limit_lines["v"][0].label = pg.InfLineLabel(self.limit_lines["v"][0], tr(RAPID),
                                                         position=0.02, color="#ffd27f")
        self.limit_lines["v"][1].label = pg.InfLineLabel(self.limit_lines["v"][1], "Vmax",
                                                         position=0.02, color="#ff4060")

    def retranslate(self) -> None:
        """The rapid line's label in the panel's language."""
        self.limit_lines["v"][0].label.setFormat(tr(RAPID))

    def set_profile(self, profile: PathProfile | None) -> None:
        if profile is None:
            for curve in self.curves.values():
                curve.setData([], [])
            return
        for key, data, limit in zip(("v", "a", "j"), (profile.v, profile.a, profile.j), profile.limits):
            self.curves[key].setData(profile.t, np.asarray(data))
            lo, hi = self.limit_lines[key]
            lo.setValue(profile.rapid_mm_s if key == "v" else -limit)
            hi.setValue(limit)
        self.plots["v"].enableAutoRange()
