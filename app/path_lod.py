"""Level of detail of a drawn tool path (no Qt): what the preview draws for a view.

A kind of move with more than ``LOD_MIN_POINTS`` points keeps thinned copies of itself
(``app.toolpath.thin``), finest first, each cube 4 times the one before. For a view, each such
kind is taken from the coarsest copy whose cubes stay within half a pixel (the full path when
zoomed in closer) and cut to the view with a margin. When the view then still holds more
than ``VECTOR_POINTS`` points, the path is drawn as one image of the view
(``app.path_raster``), which costs what its pixels cost whatever the segments; else as
vectors. Everything here runs in any thread: the preview computes a new view off the GUI
thread while the old one is shown.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from app.path_raster import Layer, rasterize
from app.toolpath import Polylines, ToolPath, thin
from planner.program import MoveKind

__all__ = ["Detail", "LodLevels", "ViewSpec", "build_levels", "detail", "needs_levels"]

LOD_MIN_POINTS = 200_000
BASE_CELLS = 65_536  # the finest copy: the path's extent in this many cubes
LEVELS = 7  # each level's cube 4 times the one before (the coarsest: extent / 16)
MARGIN = 0.25  # of the view's size, drawn beyond each side (a pan shows no gap at once)
VECTOR_POINTS = 250_000  # more points in view: the path is drawn as an image of the view
KINDS = (MoveKind.RAPID, MoveKind.LINE, MoveKind.ARC)  # drawing order (later on top)

Projection = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]
LodLevels = dict[MoveKind, list[tuple[float, Polylines]]]


@dataclass(frozen=True, slots=True)
class ViewSpec:
    """What is seen: the projection of the view and its range, a pixel's size in view units."""

    project: Projection
    x0: float
    x1: float
    y0: float
    y1: float
    pixel: float
    colours: dict[MoveKind, tuple[int, int, int, int]]


@dataclass(frozen=True, slots=True)
class Detail:
    """Vectors per kind (x, y, connect) or, for a dense view, one image and where it goes."""

    vectors: dict[MoveKind, tuple[np.ndarray, np.ndarray, np.ndarray]]
    image: np.ndarray | None = None  # (width, height, 4) uint8, column-major
    rect: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)  # x, y, width, height


def needs_levels(path: ToolPath | None) -> bool:
    """Whether ``path`` has a kind of move big enough for thinned copies."""
    return path is not None and any(len(pl.points) > LOD_MIN_POINTS for pl in path.kinds.values())


def build_levels(path: ToolPath | None) -> LodLevels:
    """Thinned copies of every kind with many points (none for a small path)."""
    levels: LodLevels = {}
    if path is None:
        return levels
    lo, hi = path.bounds
    extent = float(np.max(np.asarray(hi, float) - np.asarray(lo, float))) if len(lo) else 0.0
    if not extent > 0.0:
        return levels
    for kind, pl in path.kinds.items():
        if len(pl.points) <= LOD_MIN_POINTS:
            continue
        copies, cell, part = [], extent / BASE_CELLS, pl
        for _ in range(LEVELS):
            part = thin(part, cell)
            copies.append((cell, part))
            cell *= 4.0
        levels[kind] = copies
    return levels


def _visible(pl: Polylines, copies: list[tuple[float, Polylines]] | None,
             view: ViewSpec) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    if not copies:
        x, y = view.project(pl.points)
        return x, y, pl.connect
    for cell, part in copies:
        if cell <= 0.5 * view.pixel:  # a cube's diagonal within a pixel
            pl = part
    x, y = view.project(pl.points)
    mx, my = MARGIN * (view.x1 - view.x0), MARGIN * (view.y1 - view.y0)
    inside = (x >= view.x0 - mx) & (x <= view.x1 + mx) & (y >= view.y0 - my) & (y <= view.y1 + my)
    keep = inside.copy()  # and the other end of every segment that has one end inside
    keep[1:] |= inside[:-1] & pl.connect[:-1]
    keep[:-1] |= inside[1:] & pl.connect[:-1]
    idx = np.flatnonzero(keep)
    connect = pl.connect[idx].copy()
    if len(idx):
        connect[:-1] &= np.diff(idx) == 1  # no line across what is left out
        connect[-1] = False
    return x[idx], y[idx], connect


def detail(path: ToolPath, levels: LodLevels, view: ViewSpec) -> Detail:
    """What to draw of ``path`` for ``view``."""
    shown = {kind: _visible(path.kinds[kind], levels.get(kind), view) for kind in KINDS
             if path.kinds[kind].count}
    if not levels or sum(len(v[0]) for v in shown.values()) <= VECTOR_POINTS:
        return Detail(shown)
    w, h = view.x1 - view.x0, view.y1 - view.y0
    x0, y0 = view.x0 - MARGIN * w, view.y0 - MARGIN * h
    width = max(1, math.ceil((1 + 2 * MARGIN) * w / view.pixel))
    height = max(1, math.ceil((1 + 2 * MARGIN) * h / view.pixel))
    layers = [Layer(*shown[kind], view.colours[kind]) for kind in KINDS if kind in shown]
    image = rasterize(layers, x0, y0, view.pixel, width, height)
    return Detail({}, image, (x0, y0, width * view.pixel, height * view.pixel))
