"""A drawn tool path as an image of the view (no Qt): the preview's far level of detail.

A program of millions of segments seen whole puts many segments on every pixel; drawing them
as vectors costs time in proportion to the segments, an image of the view costs time in
proportion to its pixels. ``rasterize`` walks every drawn segment in steps of at most a pixel
and sets the pixels it passes (two pixels wide, as the vector pens), layer over layer, in
NumPy.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

__all__ = ["Layer", "rasterize"]

STEPS_PER_PIXEL = 4  # pixel steps in one image at most, per pixel of the image


@dataclass(frozen=True, slots=True)
class Layer:
    """Polylines in view coordinates; ``connect[i]``: a segment from point i to point i + 1."""

    x: np.ndarray
    y: np.ndarray
    connect: np.ndarray
    rgba: tuple[int, int, int, int]


COVER_PIECE = 1 << 16  # segments stepped through at a time


def _cover(layer: Layer, x0: float, y0: float, pixel: float, width: int, height: int) -> np.ndarray:
    """(width, height) bool: the pixels the layer's segments pass, one pixel wide. Stepped a
    piece of the segments at a time, twice (their count of steps, then the steps): the steps
    of a view of millions of segments (up to STEPS_PER_PIXEL a pixel, 40 bytes each) took
    350 MB at once, the segments' own numbers 16 bytes each."""
    hit = np.zeros(width * height, bool)
    n = len(layer.x)
    if n < 2 or not layer.connect[:-1].any():
        return hit.reshape(width, height)

    def pieces() -> Iterator[tuple[np.ndarray, ...]]:
        """Each piece's segments: where they start and go, in pixels, and their steps (one a
        pixel along each: its end is the next segment's start)."""
        for lo in range(0, n - 1, COVER_PIECE):
            s = lo + np.flatnonzero(layer.connect[lo:min(lo + COVER_PIECE, n - 1)])
            ax, ay = (layer.x[s] - x0) / pixel, (layer.y[s] - y0) / pixel
            dx, dy = (layer.x[s + 1] - x0) / pixel - ax, (layer.y[s + 1] - y0) / pixel - ay
            steps = np.maximum(1, np.ceil(np.maximum(np.abs(dx), np.abs(dy)))).astype(np.int64)
            yield s, ax, ay, dx, dy, steps

    total = sum(int(piece[-1].sum()) for piece in pieces())
    budget = STEPS_PER_PIXEL * width * height
    last = 0
    for s, ax, ay, dx, dy, n_steps in pieces():
        if total > budget:  # far more segments than pixels: fewer steps along the long ones
            n_steps = np.maximum(1, (n_steps * (budget / total)).astype(np.int64))
        owner = np.repeat(np.arange(len(n_steps)), n_steps)
        t = np.arange(int(n_steps.sum()), dtype=np.float64)
        t -= np.repeat(np.cumsum(n_steps) - n_steps, n_steps)
        t /= np.repeat(n_steps, n_steps)
        i = (ax[owner] + t * dx[owner]).astype(np.int64)  # truncation: floor for the points inside
        j = (ay[owner] + t * dy[owner]).astype(np.int64)
        ok = (i >= 0) & (i < width) & (j >= 0) & (j < height)
        hit[i[ok] * height + j[ok]] = True
        if len(s):
            last = int(s[-1]) + 1
    # the very last point of the layer
    li, lj = int((layer.x[last] - x0) // pixel), int((layer.y[last] - y0) // pixel)
    if 0 <= li < width and 0 <= lj < height:
        hit[li * height + lj] = True
    return hit.reshape(width, height)


def rasterize(layers: list[Layer], x0: float, y0: float, pixel: float, width: int, height: int) -> np.ndarray:
    """An image (width, height, 4) uint8, column-major as pyqtgraph's ImageItem reads it:
    pixel (i, j) covers x0 + i * pixel .. + pixel, y0 + j * pixel .. + pixel. Transparent where
    no segment passes; a later layer covers an earlier one; lines two pixels wide."""
    image = np.zeros((width, height, 4), np.uint8)
    for layer in layers:
        hit = _cover(layer, x0, y0, pixel, width, height)
        wide = hit.copy()
        wide[1:, :] |= hit[:-1, :]
        wide[:, 1:] |= hit[:, :-1]
        image[wide] = layer.rgba
    return image
