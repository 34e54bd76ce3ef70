"""Velocity / acceleration / jerk against time as a PNG, like the paper's Fig. 14.

pyqtgraph's ImageExporter on an offscreen scene (no matplotlib, no window), for
``cnc-plan --plot``.
"""

from __future__ import annotations

import os

import numpy as np

__all__ = ["export_vaj_png", "peak_decimate"]

# the default of peak_decimate; a PNG draws a min and a max per pixel column (2 x its width),
# all it can show: more points only cost drawing time (20,000 points of a dense saw-tooth took
# 4.5 s to antialias, 2,400 take 0.4 s)
MAX_POINTS = 20_000


def peak_decimate(t: np.ndarray, y: np.ndarray,
                  max_points: int = MAX_POINTS) -> tuple[np.ndarray, np.ndarray]:
    """Keep the min and the max of each bin, so that short spikes stay visible."""
    n = t.shape[0]
    if n <= max_points:
        return t, y
    bins = max_points // 2
    edges = np.linspace(0, n, bins + 1).astype(np.int64)
    lo = np.minimum.reduceat(y, edges[:-1])
    hi = np.maximum.reduceat(y, edges[:-1])
    tt = np.repeat(t[edges[:-1]], 2)
    yy = np.empty(2 * bins)
    yy[0::2] = lo
    yy[1::2] = hi
    return tt, yy


def export_vaj_png(path: str, t: np.ndarray, v: np.ndarray, a: np.ndarray, j: np.ndarray, *,
                   title: str = "", limits: tuple[float, float, float] | None = None,
                   width: int = 1200, height: int = 900) -> None:
    """Write three stacked plots (v mm/s, a mm/s^2, j mm/s^3 against t s) to a PNG file."""
    if not os.environ.get("DISPLAY") and not os.environ.get("WAYLAND_DISPLAY"):
        os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    import pyqtgraph as pg
    import pyqtgraph.exporters  # noqa: F401  (registers ImageExporter)

    app = pg.mkQApp("cnc-plan")
    pg.setConfigOptions(antialias=True, background="w", foreground="k")
    win = pg.GraphicsLayoutWidget()
    win.resize(width, height)
    if title:
        win.addLabel(title, row=0, col=0)
    specs = (("velocity", "mm/s", v, "#1f77b4"), ("acceleration", "mm/s²", a, "#2ca02c"),
             ("jerk", "mm/s³", j, "#d62728"))
    plots = []
    for k, (name, unit, y, colour) in enumerate(specs):
        p = win.addPlot(row=k + 1, col=0)
        p.showGrid(x=True, y=True, alpha=0.3)
        p.setLabel("left", f"{name} [{unit}]")
        p.getAxis("left").enableAutoSIPrefix(False)
        p.getAxis("left").setWidth(80)
        tt, yy = peak_decimate(np.asarray(t, float), np.asarray(y, float), max_points=2 * width)
        p.plot(tt, yy, pen=pg.mkPen(colour, width=1.5))
        if limits is not None:
            lim = limits[k]
            for sign in ((1.0,) if k == 0 else (1.0, -1.0)):
                dash = pg.QtCore.Qt.PenStyle.DashLine
                p.addLine(y=sign * lim, pen=pg.mkPen("#888888", width=1, style=dash))
        if tt.size:
            p.setXRange(float(tt[0]), float(tt[-1]), padding=0.01)
        plots.append(p)
    plots[-1].setLabel("bottom", "time [s]")
    win.show()  # offscreen: lays the plots out at the requested size
    app.processEvents()
    exporter = pg.exporters.ImageExporter(win.scene())
    exporter.parameters()["width"] = width
    # PNG whatever the name ends with: a device or a pipe (/dev/null, -) has no suffix to go by
    image = exporter.export(toBytes=True)
    if not image.save(path, "PNG"):
        raise OSError(f"cannot write the plot to {path}")
    win.close()
    win.deleteLater()
