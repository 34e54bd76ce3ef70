"""Tool path plot (pyqtgraph): arcs turquoise, lines green (paper Fig. 13a), rapids dashed.

One PlotDataItem per move kind with a ``connect`` array, so a 35,000-line program is a few
items. Drawn in work coordinates (the program's), with the work zero marked and the machine's
travel dashed. Plane views XY / XZ / YZ and a 3-D view (an orthographic projection turned by
azimuth and elevation: no OpenGL needed); pinch and drag to zoom and pan; tap a segment to
pick its program line; the live tool position and the executed part drawn on top (Clear
empties the executed part).
"""

from __future__ import annotations

import math
from collections.abc import Iterable

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import QEvent, QPointF, QRectF, Qt, QTimer, Signal
from PySide6.QtGui import QColor, QPen
from PySide6.QtWidgets import QGestureEvent, QPinchGesture, QWidget

from app.background import Background
from app.path_lod import (
    LOD_MIN_POINTS,
    Detail,
    LodLevels,
    ViewSpec,
    build_levels,
    detail,
    forget_levels,
    needs_levels,
)
from app.toolpath import ToolPath, nearest_projected, nearest_segment
from planner.core.program import MoveKind

ARC_COLOR = QColor(64, 224, 208)     # turquoise
LINE_COLOR = QColor(0, 200, 70)      # green
RAPID_COLOR = QColor(255, 170, 60)   # orange, dashed
DONE_COLOR = QColor(255, 240, 90)    # executed part
TOOL_COLOR = QColor(255, 60, 90)

PLANES: dict[str, tuple[str, str]] = {"XY": ("X", "Y"), "XZ": ("X", "Z"), "YZ": ("Y", "Z")}
VIEW_3D = "3-D"
ENVELOPE_COLOR = QColor(140, 150, 165)
ZERO_COLOR = QColor(255, 255, 255)
PICK_RADIUS_PX = 24.0
LOD_REDRAW_MS = 40  # the view settles this long before the detail follows it (app.path_lod)


def usable_planes(axes: Iterable[str]) -> list[str]:
    """The view planes whose two axes the machine has, XY first (YZ alone on the paper's
    Y-Z-C-A machine)."""
    have = set(axes)
    return [p for p, (a, b) in PLANES.items() if a in have and b in have]


def kind_pen(kind: MoveKind) -> QPen:
    if kind is MoveKind.ARC:
        return pg.mkPen(ARC_COLOR, width=2)
    if kind is MoveKind.LINE:
        return pg.mkPen(LINE_COLOR, width=2)
    return pg.mkPen(RAPID_COLOR, width=2, style=Qt.PenStyle.DashLine)


def _project(points: np.ndarray, plane: str, cols: tuple[int | None, int | None],
             axis_cols: tuple[int | None, int | None, int | None], az: float,
             el: float) -> tuple[np.ndarray, np.ndarray]:
    """View coordinates of points: a plane's two axes, or the 3-D view turned by the azimuth
    ``az`` about Z and seen from the elevation ``el`` (rad) above the XY plane."""
    n = len(points)
    if plane != VIEW_3D:
        c0, c1 = cols
        return (points[:, c0] if c0 is not None else np.zeros(n),
                points[:, c1] if c1 is not None else np.zeros(n))
    x, y, z = (points[:, c] if c is not None and c < points.shape[1] else np.zeros(n) for c in axis_cols)
    u = x * math.cos(az) - y * math.sin(az)
    depth = x * math.sin(az) + y * math.cos(az)
    return u, depth * math.sin(el) + z * math.cos(el)


class PreviewPlot(pg.PlotWidget):
    moveTapped = Signal(int, int)  # move index, source line

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent, background="#0a0d10")
        self.setObjectName("previewPlot")
        self.plane = "XY"
        self.path: ToolPath | None = None
        self.showGrid(x=True, y=True, alpha=0.25)
        self.setAspectLocked(True)
        self.getPlotItem().hideButtons()  # no hover-only controls
        self.items: dict[MoveKind, pg.PlotDataItem] = {}
        # a big path's thinned copies (app.path_lod); a new view's detail is made off the GUI
        # thread once the view settles, the old one shown meanwhile
        self._lod: LodLevels = {}
        # (x, y, connect, move index) of every move for the view, when the path is big
        self._executed: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None = None
        self._first_move = 0    # where the run began (run from line): nothing before it ran
        self._lod_timer = QTimer(self)
        self._lod_timer.setSingleShot(True)
        self._lod_timer.setInterval(LOD_REDRAW_MS)
        self._lod_timer.timeout.connect(lambda: self._draw_paths(wait=False))
        self._detail_work = Background("preview-detail", self._show_detail, self)
        self._levels_work = Background("preview-levels", self._levels_made, self)
        self._levels_pending = False
        self.getViewBox().sigRangeChanged.connect(self._on_range)
        for kind in (MoveKind.RAPID, MoveKind.LINE, MoveKind.ARC):
            item = pg.PlotDataItem(pen=kind_pen(kind), antialias=False, skipFiniteCheck=True)
            item.setZValue(int(kind))
            self.addItem(item)
            self.items[kind] = item
        # the far level of detail: the whole path as an image of the view (app.path_raster)
        self.raster_item = pg.ImageItem()
        self.raster_item.setZValue(3)
        self.raster_item.setVisible(False)
        self.addItem(self.raster_item)
        self.done_item = pg.PlotDataItem(pen=pg.mkPen(DONE_COLOR, width=4), skipFiniteCheck=True)
        self.done_item.setZValue(5)
        self.addItem(self.done_item)
        self.tool_item = pg.ScatterPlotItem(size=18, brush=pg.mkBrush(TOOL_COLOR),
                                            pen=pg.mkPen("w", width=2), symbol="o")
        self.tool_item.setZValue(10)
        self.addItem(self.tool_item)
        self.current_item = pg.PlotDataItem(pen=pg.mkPen(DONE_COLOR, width=4), skipFiniteCheck=True)
        self.current_item.setZValue(5)
        self.addItem(self.current_item)
        self.selected_item = pg.PlotDataItem(pen=pg.mkPen("#ffffff", width=5), skipFiniteCheck=True)
        self.selected_item.setZValue(6)
        self.addItem(self.selected_item)
        dashed = pg.mkPen(ENVELOPE_COLOR, width=1, style=Qt.PenStyle.DashLine)
        self.envelope_item = pg.PlotDataItem(pen=dashed, skipFiniteCheck=True)
        self.envelope_item.setZValue(-1)
        self.addItem(self.envelope_item)
        self.zero_item = pg.PlotDataItem(pen=pg.mkPen(ZERO_COLOR, width=2), skipFiniteCheck=True)
        self.zero_item.setZValue(4)
        self.addItem(self.zero_item)
        # the way a run from a line would take (shown before the operator confirms it)
        self.approach_item = pg.PlotDataItem(pen=pg.mkPen(TOOL_COLOR, width=3, style=Qt.PenStyle.DotLine),
                                             symbol="o", symbolSize=8, symbolBrush=pg.mkBrush(TOOL_COLOR),
                                             skipFiniteCheck=True)
        self.approach_item.setZValue(8)
        self.addItem(self.approach_item)
        self._approach: np.ndarray | None = None
        self._done_move = -1
        self._tool = np.zeros(0)
        self._envelope: tuple[np.ndarray, np.ndarray] | None = None   # (lo, hi) in work coordinates
        self.azimuth_deg, self.elevation_deg = -60.0, 30.0
        self.grabGesture(Qt.GestureType.PinchGesture)
        self.scene().sigMouseClicked.connect(self._on_click)

    # --- data ----------------------------------------------------------------------------
    def _cols(self) -> tuple[int | None, int | None]:
        if self.path is None or self.plane == VIEW_3D:
            return None, None
        a, b = PLANES[self.plane]
        return self.path.column(a), self.path.column(b)

    def _axis_cols(self) -> tuple[int | None, int | None, int | None]:
        if self.path is None:
            return None, None, None
        return self.path.column("X"), self.path.column("Y"), self.path.column("Z")

    def _xy(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return _project(points, self.plane, self._cols(), self._axis_cols(), math.radians(self.azimuth_deg),
                        math.radians(self.elevation_deg))

    def project(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The 3-D view: turned by the azimuth about Z, seen from the elevation above the XY
        plane (90 degrees: from the top; 0: from the side)."""
        return _project(points, VIEW_3D, (None, None), self._axis_cols(), math.radians(self.azimuth_deg),
                        math.radians(self.elevation_deg))

    def rotate(self, d_azimuth_deg: float = 0.0, d_elevation_deg: float = 0.0) -> None:
        """Turn the 3-D view (elevation kept within 0..90 degrees)."""
        self.azimuth_deg = (self.azimuth_deg + d_azimuth_deg + 180.0) % 360.0 - 180.0
        self.elevation_deg = min(max(self.elevation_deg + d_elevation_deg, 0.0), 90.0)
        if self.plane == VIEW_3D:
            self._refresh_view()

    def set_toolpath(self, path: ToolPath | None) -> None:
        self.path = path
        self._done_move = -1
        self.done_item.setData([], [])
        self.current_item.setData([], [])
        self.selected_item.setData([], [])
        self._lod = {}
        self._executed = None
        self.fit()  # first: what is drawn depends on the view (level of detail)
        self._levels_work.cancel()
        forget_levels(path)
        self._levels_pending = needs_levels(path)
        if self._levels_pending:
            # a big path: its thinned copies are made off the GUI thread (seconds for
            # millions of segments); it is drawn once they are there
            self._levels_work.submit(lambda: build_levels(path))
        self._redraw()

    def _levels_made(self, levels: object) -> None:
        self._levels_pending = False
        # an exception of the work leaves no copies: the path is then drawn whole, at once
        self._lod = levels if isinstance(levels, dict) else {}
        self._draw_paths(wait=not self._lod)

    def set_plane(self, plane: str) -> None:
        if plane not in PLANES and plane != VIEW_3D:
            raise ValueError(f"unknown plane {plane!r}")
        self.plane = plane
        a, b = PLANES.get(plane, ("", ""))
        self.setLabel("bottom", a, units="mm" if a else None)
        self.setLabel("left", b, units="mm" if b else None)
        self.fit()
        self._refresh_view()

    def _refresh_view(self) -> None:
        self._redraw()
        done, self._done_move = self._done_move, -1
        self.set_executed(done, self._first_move)
        selected = getattr(self, "_selected", -1)
        self.highlight_move(selected)
        self._draw_envelope()
        self.set_approach(self._approach)

    def set_envelope(self, lo: np.ndarray | None, hi: np.ndarray | None) -> None:
        """The machine's travel in work coordinates (per axis of the tool path), dashed."""
        self._envelope = None if lo is None or hi is None else (np.asarray(lo, float), np.asarray(hi, float))
        self._draw_envelope()

    def _draw_envelope(self) -> None:
        n = len(self.path.axes) if self.path is not None else 0
        if self._envelope is None or n == 0:
            self.envelope_item.setData([], [])
            self.zero_item.setData([], [])
            return
        lo, hi = self._envelope[0][:n], self._envelope[1][:n]
        # the 12 edges of the travel box (rotary axes at 0), as pairs of points
        box = []
        cols = [c for c in self._axis_cols() if c is not None]
        for corner in range(1 << len(cols)):
            for bit in range(len(cols)):
                if corner & (1 << bit):
                    continue
                a, b = np.zeros(n), np.zeros(n)
                for k, c in enumerate(cols):
                    a[c] = b[c] = hi[c] if corner & (1 << k) else lo[c]
                b[cols[bit]] = hi[cols[bit]]
                box += [a, b]
        self._draw_segments(self.envelope_item, box, n)
        # work zero: a short cross of the axes through 0 (a tenth of the path's size)
        span = self.path.bounds[1] - self.path.bounds[0] if self.path is not None else np.ones(n)
        size = 0.1 * float(max(np.max(span), 1.0))
        marks = []
        for c in cols:
            a, b = np.zeros(n), np.zeros(n)
            a[c], b[c] = -size, size
            marks += [a, b]
        self._draw_segments(self.zero_item, marks, n)

    def _draw_segments(self, item: pg.PlotDataItem, ends: list[np.ndarray], n: int) -> None:
        """Separate segments, given as consecutive (start, end) points, in the current view."""
        pts = np.array(ends) if ends else np.zeros((0, n))
        x, y = self._xy(pts)
        connect = np.zeros(len(pts), bool)
        connect[0::2] = True
        item.setData(x, y, connect=connect)

    def set_approach(self, points: np.ndarray | None) -> None:
        """Draw (or, with None, remove) the way to a restart point, in work coordinates."""
        self._approach = None if points is None else np.asarray(points, float)
        if self._approach is None or not len(self._approach):
            self.approach_item.setData([], [])
            return
        x, y = self._xy(self._approach)
        self.approach_item.setData(x, y)

    def clear_backplot(self) -> None:
        """Forget the executed part drawn so far (the next line reached draws it again)."""
        self._done_move = -1
        self.done_item.setData([], [])
        self.current_item.setData([], [])

    def _redraw(self) -> None:
        self._draw_paths()
        if len(self._tool):
            self.set_tool_position(self._tool)

    def _view_spec(self) -> ViewSpec:
        """The view as it is now (the projection's settings copied: the detail may be made in
        another thread while the operator turns the view)."""
        plane, cols, axis_cols = self.plane, self._cols(), self._axis_cols()
        az, el = math.radians(self.azimuth_deg), math.radians(self.elevation_deg)

        def project(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            return _project(points, plane, cols, axis_cols, az, el)

        vb = self.getViewBox()
        (x0, x1), (y0, y1) = vb.viewRange()
        pixel = float(np.max(np.abs(np.asarray(vb.viewPixelSize(), float))))
        colours: dict[MoveKind, tuple[int, int, int, int]] = {}
        for kind in self.items:
            c = kind_pen(kind).color()
            colours[kind] = (c.red(), c.green(), c.blue(), c.alpha())
        return ViewSpec(project, float(x0), float(x1), float(y0), float(y1), pixel, colours)

    def _draw_paths(self, wait: bool = True) -> None:
        """The path for the view: at once, or for a big path after a view change off the GUI
        thread (``wait=False``)."""
        if self.path is None or self._levels_pending:  # nothing yet while a big path is prepared
            self._detail_work.cancel()
            self._show_detail(Detail({}))
            return
        path, levels, view = self.path, self._lod, self._view_spec()
        if wait or not levels:
            self._detail_work.cancel()
            self._show_detail(detail(path, levels, view))
        else:
            self._detail_work.submit(lambda: detail(path, levels, view))

    @property
    def detail_pending(self) -> bool:
        """A view's detail is being made off the GUI thread."""
        return self._levels_pending or self._detail_work.busy or self._lod_timer.isActive()

    def _show_detail(self, drawn: object) -> None:
        if not isinstance(drawn, Detail):  # an exception of the work: keep what is shown
            return
        self._executed = drawn.executed
        done, self._done_move = self._done_move, -1
        self.set_executed(done, self._first_move)  # the part run so far, for this view
        for kind, item in self.items.items():
            if kind in drawn.vectors:
                x, y, connect = drawn.vectors[kind]
                item.setData(x, y, connect=connect)
            else:
                item.setData([], [])
        self.raster_item.setVisible(drawn.image is not None)
        if drawn.image is not None:
            self.raster_item.setImage(drawn.image, autoLevels=False)
            self.raster_item.setRect(QRectF(*drawn.rect))

    def _on_range(self, *_args: object) -> None:
        if self._lod:
            self._lod_timer.start()  # the detail follows once the view settles

    def drawn_points(self) -> int:
        """How many points the path's vector items hold now (0 while it is drawn as an image)."""
        return sum(len(item.xData) if item.xData is not None else 0 for item in self.items.values())

    def fit(self) -> None:
        if self.path is None or len(self.path.all.points) == 0:
            self.getViewBox().setRange(xRange=(-10, 10), yRange=(-10, 10))
            return
        if len(self.path.all.points) > LOD_MIN_POINTS:
            # a big path: its bounding box's corners (projecting every point held the GUI
            # thread 0.2 s at 10,000,000 moves in 3-D); the view may be a little looser
            lo, hi = (np.asarray(b, float) for b in self.path.bounds)
            corners = np.array([[hi[c] if (k >> c) & 1 else lo[c] for c in range(len(lo))]
                                for k in range(1 << len(lo))])
            x, y = self._xy(corners)
        else:
            x, y = self._xy(self.path.all.points)
        pad = 0.05 * max(float(np.ptp(x)), float(np.ptp(y)), 1.0)
        self.getViewBox().setRange(xRange=(x.min() - pad, x.max() + pad),
                                   yRange=(y.min() - pad, y.max() + pad), padding=0)

    # --- live ----------------------------------------------------------------------------
    def set_tool_position(self, work_pos: np.ndarray) -> None:
        """The tool, in the same (work) coordinates as the path."""
        self._tool = np.asarray(work_pos, float)
        if self.path is None:
            self.tool_item.setData([], [])
            return
        x, y = self._xy(self._tool[None, : len(self.path.axes)])
        self.tool_item.setData(x, y)
        self._update_current()

    def _update_current(self) -> None:
        """The part of the move being executed up to the tool (nearest sampled point)."""
        path, k = self.path, self._done_move
        if path is None or k < 0 or k >= path.move_count or not len(self._tool):
            self.current_item.setData([], [])
            return
        lo, hi = path.move_points(k)
        pts = path.all.points[lo:hi]
        if len(pts) < 2:
            self.current_item.setData([], [])
            return
        n = min(pts.shape[1], len(self._tool))
        near = 0 if len(pts) == 2 else int(np.argmin(np.sum((pts[:, :n] - self._tool[:n]) ** 2, axis=1)))
        part = np.vstack([pts[: near + 1], self._tool[None, : pts.shape[1]]]) if n == pts.shape[1] \
            else pts[: near + 1]
        x, y = self._xy(part)
        self.current_item.setData(x, y)

    def set_executed(self, move_index: int, first: int = 0) -> None:
        """Highlight moves ``first`` .. move_index - 1 (those finished in this run: a run from
        a line never cut what lies before it) as executed."""
        if self.path is None or (move_index, first) == (self._done_move, self._first_move):
            return
        self._done_move, self._first_move = move_index, first
        self._update_current()
        if move_index <= first:
            self.done_item.setData([], [])
            return
        if self._executed is not None:  # a big path: a stretch of the view's own copy
            x, y, connect, moves = self._executed
            lo = int(np.searchsorted(moves, first, side="left"))
            end = int(np.searchsorted(moves, move_index, side="left"))
        else:
            lo, end = self.path.points_before(first), self.path.points_before(move_index)
            pl = self.path.all
            x, y = self._xy(pl.points[:end])
            connect = pl.connect
        if first > 0 and lo > 0:
            lo -= 1             # a move's points follow its start, the point before them
        connect = connect[lo:end].copy()
        if end > lo:
            connect[-1] = False
        self.done_item.setData(x[lo:end], y[lo:end], connect=connect)

    def highlight_move(self, move_index: int) -> None:
        self._selected = move_index
        if self.path is None or move_index < 0:
            self.selected_item.setData([], [])
            return
        if move_index >= self.path.move_count:
            self.selected_item.setData([], [])
            return
        lo, hi = self.path.move_points(move_index)  # a move's points are one stretch of the path's
        x, y = self._xy(self.path.all.points[lo:hi])
        self.selected_item.setData(x, y)

    # --- touch ---------------------------------------------------------------------------
    def pick(self, x: float, y: float, radius: float) -> int:
        """Move index within ``radius`` (data units) of (x, y), else -1."""
        if self.path is None:
            return -1
        if self._executed is not None:  # a big path: among the points drawn for this view
            px, py, connect, moves = self._executed
            index, dist = nearest_segment(px, py, connect, moves, x, y)
        else:
            px, py = self._xy(self.path.all.points)
            index, dist = nearest_projected(self.path, px, py, x, y)
        return index if dist <= radius else -1

    def _on_click(self, event) -> None:  # pyqtgraph MouseClickEvent
        if self.path is None or event.button() != Qt.MouseButton.LeftButton:
            return
        vb = self.getViewBox()
        p = vb.mapSceneToView(event.scenePos())
        px = vb.viewPixelSize()[0]
        index = self.pick(p.x(), p.y(), PICK_RADIUS_PX * px)
        if index >= 0:
            self.highlight_move(index)
            self.moveTapped.emit(index, int(self.path.move_lines[index]))

    def event(self, ev: QEvent) -> bool:
        if ev.type() == QEvent.Type.Gesture and isinstance(ev, QGestureEvent):
            pinch = ev.gesture(Qt.GestureType.PinchGesture)
            if isinstance(pinch, QPinchGesture):
                factor = pinch.scaleFactor()
                if factor > 0:
                    local = self.mapFromGlobal(pinch.centerPoint().toPoint())  # screen -> widget
                    centre = self.getViewBox().mapSceneToView(QPointF(self.mapToScene(local)))
                    self.getViewBox().scaleBy((1 / factor, 1 / factor), center=centre)
                ev.accept()
                return True
        return super().event(ev)
