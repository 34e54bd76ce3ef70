"""G05, G05.1 and G05.2/G05.3 curves as LinuxCNC 2.9 runs them: a NURBS made into arcs.

LinuxCNC's interpreter turns a cubic spline (G05), a quadratic one (G05.1) and a NURBS (G05.2
control points, G05.3 to end) into one NURBS of control points (x, y, weight) and an order k;
its motion layer (emccanon.cc ``NURBS_FEED``) evaluates the curve at 4 points per control
point, equally spaced in the parameter, and joins each pair by a biarc: two tangent arcs that
leave along the curve's tangent at the first point and arrive along it at the second. The
machine runs those arcs. This module does the same arithmetic (knot vector, basis functions
with LinuxCNC's closed intervals, the tangent as a central difference of 1e-5 in the
parameter, the biarc with equal tangent lengths) in program units, where LinuxCNC's thresholds
apply, so that the path is LinuxCNC's.

Where LinuxCNC's biarc has no solution (parallel end tangents, no real root, or both roots
positive) it moves nowhere for that stretch and starts the next one from where it would have
been, a jump; this feeds a straight line to the stretch's end instead. The same where LinuxCNC's
biarc leaves the box of the control points: a curve of positive weights lies inside them, but
at a cusp (the curve turning back on itself) the two arcs can swing out tens of millimetres
around a curve a tenth of a millimetre long.

Plain floats and small NumPy arrays: a curve has a few dozen control points.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

__all__ = ["SplinePiece", "knot_vector", "nurbs_points", "nurbs_tangents", "nurbs_pieces",
           "biarc", "SAMPLES_PER_POINT"]

#: LinuxCNC evaluates the curve at this many points per control point (emccanon.cc)
SAMPLES_PER_POINT = 4
_DU = 1e-5           # the parameter step of the tangent's central difference (LinuxCNC's DU)
_ARC_SMALL = 1e-6    # below this 2 (chord x tangent), LinuxCNC feeds a line, not an arc


@dataclass(frozen=True)
class SplinePiece:
    """One move of the curve in program units: to ``end``; an arc about ``center`` (turning
    counter-clockwise when ``ccw``) or, with ``center`` None, a straight line."""

    end: tuple[float, float]
    center: tuple[float, float] | None = None
    ccw: bool = True


def knot_vector(n: int, k: int) -> np.ndarray:
    """LinuxCNC's clamped uniform knots for control points 0..n and order k."""
    return np.array([0 if i < k else (i - k + 1 if i <= n else n - k + 2) for i in range(n + k + 1)],
                    dtype=float)


def _basis(u: np.ndarray, k: int, knots: np.ndarray, count: int) -> list[np.ndarray]:
    """N(i, k, u) for i < count, for every u at once, by LinuxCNC's recursion (``Nmix``): the
    order-1 functions are 1 on closed intervals, and a term over a zero-width knot span is 0."""
    span = len(knots) - 1
    prev = [((u >= knots[i]) & (u <= knots[i + 1])).astype(float) for i in range(span)]
    for kk in range(2, k + 1):
        cur = []
        for i in range(span - kk + 1):
            d1 = knots[i + kk - 1] - knots[i]
            d2 = knots[i + kk] - knots[i + 1]
            if d1 == 0.0 and d2 != 0.0:
                cur.append(((knots[i + kk] - u) * prev[i + 1]) / d2)
            elif d2 == 0.0 and d1 != 0.0:
                cur.append(((u - knots[i]) * prev[i]) / d1)
            elif d1 == 0.0 and d2 == 0.0:
                cur.append(np.zeros_like(u))
            else:
                cur.append(((u - knots[i]) * prev[i]) / d1 + ((knots[i + kk] - u) * prev[i + 1]) / d2)
        prev = cur
    return prev[:count]


#: parameters evaluated at a time: the basis functions of a piece of the curve, not of all of it
#: at every parameter (5,000 control points took 1.6 GB that way)
NURBS_CHUNK = 512


def nurbs_points(points: np.ndarray, k: int, u: np.ndarray) -> np.ndarray:
    """The curve of control points ``points`` (rows x, y, weight) and order k at parameters
    ``u`` (0 to n - k + 2), as LinuxCNC's ``nurbs_point``: rows (x, y).

    The parameters a chunk at a time, in increasing order, each with only the basis functions
    that are not zero somewhere in its range (function i lives on knots[i] to knots[i + k]):
    the recursion is local, so each is the value the whole recursion gives, and the functions
    left out add exact zeros: the same sums, in the same order, bit for bit."""
    n = len(points) - 1
    knots = knot_vector(n, k)
    u = np.asarray(u, dtype=float)
    out = np.empty((len(u), 2))
    order = np.argsort(u, kind="stable")
    first, last = knots[: n + 1], knots[k: n + 1 + k]
    for start in range(0, len(u), NURBS_CHUNK):
        rows = order[start: start + NURBS_CHUNK]
        uc = u[rows]
        live = np.flatnonzero((first <= uc.max()) & (last >= uc.min()))
        if live.size == 0:
            out[rows] = np.nan              # outside every function: 0 / 0, as the whole sum gives
            continue
        i0, i1 = int(live[0]), int(live[-1]) + 1
        basis = _basis(uc, k, knots[i0: i1 + k], i1 - i0)
        den = np.zeros(len(uc))
        for b, w in zip(basis, points[i0:i1, 2]):
            den = den + b * w
        x = np.zeros(len(uc))
        y = np.zeros(len(uc))
        for b, (px, py, w) in zip(basis, points[i0:i1]):
            x = x + px * b * w / den
            y = y + py * b * w / den
        out[rows, 0], out[rows, 1] = x, y
    return out


def nurbs_tangents(points: np.ndarray, k: int, u: np.ndarray) -> np.ndarray:
    """Unit tangents at ``u`` as LinuxCNC's ``nurbs_tangent``: a central difference of the
    curve over 1e-5 in the parameter (one-sided at the ends), normalised."""
    umax = float(len(points) - 1 - k + 2)
    u = np.asarray(u, dtype=float)
    lo = np.maximum(0.0, u - _DU)
    hi = np.minimum(umax, u + _DU)
    d = (nurbs_points(points, k, hi) - nurbs_points(points, k, lo)) / (hi - lo)[:, None]
    h = np.hypot(d[:, 0], d[:, 1])
    h = np.where(h != 0.0, h, 1.0)
    return d / h[:, None]


def _arc(x0: float, y0: float, x1: float, y1: float, dx: float, dy: float) -> SplinePiece:
    """The arc from (x0, y0) leaving along (dx, dy) to (x1, y1), as LinuxCNC's ``arc``: a line
    when the chord is (nearly) along the tangent."""
    x, y = x1 - x0, y1 - y0
    den = 2.0 * (y * dx - x * dy)
    if abs(den) > _ARC_SMALL:
        r = -(x * x + y * y) / den
        return SplinePiece((x1, y1), (x0 + dy * r, y0 - dx * r), r < 0.0)
    return SplinePiece((x1, y1))


def _unit(x: float, y: float) -> tuple[float, float]:
    h = math.hypot(x, y)
    return (x / h, y / h) if h != 0.0 else (x, y)


def biarc(p0: Sequence[float], ts: Sequence[float], p4: Sequence[float],
          te: Sequence[float]) -> list[SplinePiece] | None:
    """The two tangent arcs from p0 (leaving along ts) to p4 (arriving along te), with equal
    tangent lengths, as LinuxCNC's ``biarc``; None where LinuxCNC finds none."""
    tsx, tsy = _unit(float(ts[0]), float(ts[1]))
    tex, tey = _unit(float(te[0]), float(te[1]))
    p0x, p0y = float(p0[0]), float(p0[1])
    p4x, p4y = float(p4[0]), float(p4[1])
    vx, vy = p0x - p4x, p0y - p4y
    c = vx * vx + vy * vy
    b = 2.0 * (vx * (tsx + tex) + vy * (tsy + tey))
    a = 2.0 * (tsx * tex + tsy * tey - 1.0)
    discr = b * b - 4.0 * a * c
    if discr < 0.0 or a == 0.0:
        return None
    disq = math.sqrt(discr)
    beta1 = (-b - disq) / 2.0 / a
    beta2 = (-b + disq) / 2.0 / a
    if beta1 > 0.0 and beta2 > 0.0:
        return None
    beta = beta2 if beta1 < beta2 else beta1
    alpha = beta
    ab = alpha + beta
    if ab == 0.0 or not math.isfinite(ab):
        return None
    p1x, p1y = p0x + alpha * tsx, p0y + alpha * tsy
    p3x, p3y = p4x - beta * tex, p4y - beta * tey
    p2x = (p1x * beta + p3x * alpha) / ab
    p2y = (p1y * beta + p3y * alpha) / ab
    tmx, tmy = _unit(p3x - p2x, p3y - p2y)
    return [_arc(p0x, p0y, p2x, p2y, tsx, tsy), _arc(p2x, p2y, p4x, p4y, tmx, tmy)]


def _arc_extremes(start: tuple[float, float], piece: SplinePiece) -> list[tuple[float, float]]:
    """The points of an arc piece that bound it: its ends and where it crosses the axes'
    directions from its centre."""
    assert piece.center is not None
    cx, cy = piece.center
    r = math.hypot(start[0] - cx, start[1] - cy)
    a0 = math.atan2(start[1] - cy, start[0] - cx)
    a1 = math.atan2(piece.end[1] - cy, piece.end[0] - cx)
    sweep = (a1 - a0) % (2.0 * math.pi) if piece.ccw else -((a0 - a1) % (2.0 * math.pi))
    out = [start, piece.end]
    for q in range(-4, 5):
        angle = q * math.pi / 2.0
        rel = (angle - a0) if piece.ccw else (a0 - angle)
        if 0.0 < rel % (2.0 * math.pi) < abs(sweep):
            out.append((cx + r * math.cos(angle), cy + r * math.sin(angle)))
    return out


def _inside(pieces: list[SplinePiece], start: tuple[float, float], lo: np.ndarray, hi: np.ndarray) -> bool:
    here = start
    for piece in pieces:
        pts = _arc_extremes(here, piece) if piece.center is not None else [piece.end]
        if any(not (lo[0] <= x <= hi[0] and lo[1] <= y <= hi[1]) for x, y in pts):
            return False
        here = piece.end
    return True


def nurbs_pieces(points: np.ndarray, k: int) -> list[SplinePiece]:
    """The moves LinuxCNC's ``NURBS_FEED`` makes of the curve (control points ``points``, rows
    x, y, weight, in program units; order k): a biarc between each pair of 4 (n + 1) equally
    spaced samples; a line where there is no biarc or where it leaves the control points' box."""
    lo = points[:, :2].min(axis=0)
    hi = points[:, :2].max(axis=0)
    margin = 1e-6 * max(1.0, float(np.max(np.abs(points[:, :2]))))    # rounding, in program units
    lo, hi = lo - margin, hi + margin
    n = len(points) - 1
    umax = float(n - k + 2)
    div = (n + 1) * SAMPLES_PER_POINT
    u = np.array([0.0] + [umax * i / div for i in range(1, div + 1)])
    pts = nurbs_points(points, k, u)
    tan = nurbs_tangents(points, k, u)
    out: list[SplinePiece] = []
    for i in range(1, div + 1):
        pieces = biarc(pts[i - 1], tan[i - 1], pts[i], tan[i])
        start = (float(pts[i - 1, 0]), float(pts[i - 1, 1]))
        if pieces is None or not _inside(pieces, start, lo, hi):
            out.append(SplinePiece((float(pts[i, 0]), float(pts[i, 1]))))
        else:
            out.extend(pieces)
    return out
