"""A drawn tool path as an image of the view (no Qt): the preview's far level of detail.

A program of millions of segments seen whole puts many segments on every pixel; drawing them
as vectors costs time in proportion to the segments, an image of the view costs time in
proportion to its pixels. ``rasterize`` walks every drawn segment in steps of at most a pixel
and sets the pixels it passes (two pixels wide, as the vector pens), layer over layer, in
NumPy.
"""

from __future__ import annotations

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
    piece of the segments at a time: the steps of a view of millions of segments (up to
    STEPS_PER_PIXEL a pixel, 40 bytes each) took 350 MB at once."""
    hit = np.zeros(width * height, bool)
    seg = np.flatnonzero(layer.connect[:-1]) if len(layer.x) > 1 else np.zeros(0, np.int64)
    if not len(seg):
        return hit.reshape(width, height)

    def pixels(s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        ax, ay = (layer.x[s] - x0) / pixel, (layer.y[s] - y0) / pixel
        return ax, ay, (layer.x[s + 1] - x0) / pixel - ax, (layer.y[s + 1] - y0) / pixel - ay

    # a step per pixel along each segment (its end is the next segment's start)
    steps = np.empty(len(seg), np.int64)
    for lo in range(0, len(seg), COVER_PIECE):
        _ax, _ay, dx, dy = pixels(seg[lo:lo + COVER_PIECE])
        steps[lo:lo + COVER_PIECE] = np.maximum(1, np.ceil(np.maximum(np.abs(dx), np.abs(dy))))
    total = int(steps.sum())
    budget = STEPS_PER_PIXEL * width * height
    if total > budget:  # far more segments than pixels: fewer steps along the long ones
        steps = np.maximum(1, (steps * (budget / total)).astype(np.int64))
    for lo in range(0, len(seg), COVER_PIECE):
        ax, ay, dx, dy = pixels(seg[lo:lo + COVER_PIECE])
        n_steps = steps[lo:lo + COVER_PIECE]
        owner = np.repeat(np.arange(len(n_steps)), n_steps)
        t = np.arange(int(n_steps.sum()), dtype=np.float64)
        t -= np.repeat(np.cumsum(n_steps) - n_steps, n_steps)
        t /= np.repeat(n_steps, n_steps)
        i = (ax[owner] + t * dx[owner]).astype(np.int64)  # truncation: floor for the points inside
        j = (ay[owner] + t * dy[owner]).astype(np.int64)
        ok = (i >= 0) & (i < width) & (j >= 0) & (j < height)
        hit[i[ok] * height + j[ok]] = True
    last = seg[-1] + 1  # the very last point of the layer
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
