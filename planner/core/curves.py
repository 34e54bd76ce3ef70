"""The exact geometry of corner blends, fillets and transitions: a clothoid pair (or a clothoid,
an arc and a clothoid; or a cubic-curvature transition) evaluated at any arc length: position,
unit tangent and curvature vector. ``Move.evaluate`` of a BLEND move is ``blend_eval``; how
blends are sized and placed is ``planner.geometry.blend``'s (and ``planner.geometry.transition``'s).

Geometry of a pair of half length L_s (arc length s from the pair's start A, sharpness
c = theta / L_s^2, heading phi(s) = c s^2 / 2 on the first half):

    p(s) = A + X(s) u1 + Y(s) n1                       0 <= s <= L_s
    p(s) = B - X(2 L_s - s) u2 + Y(2 L_s - s) n2         L_s <= s <= 2 L_s

with X, Y the Fresnel-type integrals of cos and sin of the heading (16-point Gauss-Legendre,
exact to rounding for headings up to pi / 2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from planner.core.program import Move

__all__ = ["Blend", "blend_eval", "fresnel", "pair_frames", "pair_positions", "poly_bounds", "poly_heading",
           "poly_positions", "unit_pair"]

_GX, _GW = np.polynomial.legendre.leggauss(16)
_GX = (_GX + 1.0) * 0.5
_GW = _GW * 0.5

@dataclass(frozen=True, slots=True, eq=False)
class Blend:
    """Exact geometry of one clothoid-pair blend (or of its tail from ``s0_mm`` on)."""

    origin: np.ndarray  # A: start of the pair on the incoming line (n_axes,), machine coords
    u1: np.ndarray  # unit direction of the incoming line (n_axes,)
    n1: np.ndarray  # unit normal in the corner's plane, towards the inside of the turn
    half_mm: float  # L_s, the length of each clothoid
    turn_rad: float  # theta, the direction change of the corner
    corner: np.ndarray  # C: the programmed corner (n_axes,); a fillet's: where its lines meet
    s0_mm: float = 0.0  # where this move starts along the blend (a resumed tail: > 0)
    arc_mm: float = 0.0  # length of the arc between the clothoids (a rounded fillet), 0 for a pair
    measured_deviation_mm: float = math.nan  # a fillet's or transition's distance from its path
    # a transition (planner.geometry.transition): signed curvature kappa(s) = c0 + c1 s + c2 s^2 + c3 s^3
    # towards n1, heading from u1, over the whole length 2 * half_mm; None for pairs and fillets
    poly: tuple[float, float, float, float] | None = None

    @property
    def radius_mm(self) -> float:
        """Radius in the middle (the smallest)."""
        if self.poly is not None:
            return 1.0 / self.kappa_max
        return (self.half_mm + self.arc_mm) / self.turn_rad

    @property
    def kappa_max(self) -> float:
        if self.poly is not None:
            return poly_bounds(self.poly, 2.0 * self.half_mm)[0]
        return 1.0 / self.radius_mm

    @property
    def sharpness(self) -> float:
        """|dkappa/ds| (1/mm^2) on the clothoids (a transition: its largest)."""
        if self.poly is not None:
            return poly_bounds(self.poly, 2.0 * self.half_mm)[1]
        return 1.0 / (self.radius_mm * self.half_mm)

    @property
    def length_mm(self) -> float:
        return 2.0 * self.half_mm + self.arc_mm

    @property
    def deviation_mm(self) -> float:
        """Largest distance from the programmed path: a pair's middle from its corner, or a
        fillet's, measured when it was made."""
        if not math.isnan(self.measured_deviation_mm):
            return self.measured_deviation_mm
        _, y1, _, d1 = unit_pair(np.array([self.turn_rad]))
        return float(d1[0] * self.half_mm)


def fresnel(theta: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """X, Y of the unit pair (L_s = 1, c = theta) at x in [0, 1], element-wise."""
    xs = x[..., None] * _GX
    phase = 0.5 * theta[..., None] * xs * xs
    return x * (np.cos(phase) @ _GW), x * (np.sin(phase) @ _GW)


def unit_pair(theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(X(1), Y(1), tangent length T, corner deviation D) of the pair of half length 1."""
    theta = np.asarray(theta, dtype=float)
    x1, y1 = fresnel(theta, np.ones_like(theta))
    half = 0.5 * theta
    return x1, y1, x1 + y1 * np.tan(half), y1 / np.cos(half)


_PX, _PW = np.polynomial.legendre.leggauss(24)
_PX = (_PX + 1.0) * 0.5
_PW = _PW * 0.5


def poly_bounds(c: tuple[float, float, float, float], length: float) -> tuple[float, float]:
    """(max |kappa|, max |dkappa/ds|) of kappa(s) = c0 + c1 s + c2 s^2 + c3 s^3 on [0, length],
    exactly: at the ends and where the derivative (a quadratic) and its derivative vanish."""
    c0, c1, c2, c3 = c
    cand = [0.0, length]
    disc = 4.0 * c2 * c2 - 12.0 * c3 * c1
    if c3 != 0.0 and disc >= 0.0:
        r = math.sqrt(disc)
        cand += [(-2.0 * c2 + r) / (6.0 * c3), (-2.0 * c2 - r) / (6.0 * c3)]
    elif c3 == 0.0 and c2 != 0.0:
        cand.append(-c1 / (2.0 * c2))
    if c3 != 0.0:
        cand.append(-c2 / (3.0 * c3))
    pts = np.clip(np.array(cand), 0.0, length)
    k = c0 + pts * (c1 + pts * (c2 + pts * c3))
    dk = c1 + pts * (2.0 * c2 + pts * 3.0 * c3)
    return float(np.abs(k).max()), float(np.abs(dk).max())


def poly_heading(c: np.ndarray, s: np.ndarray) -> np.ndarray:
    """Heading psi(s) = integral of kappa (row-wise coefficients c (N, 4), s (N,) or (N, m))."""
    if s.ndim == 2:
        c = c[:, None, :]
    return s * (c[..., 0] + s * (c[..., 1] / 2.0 + s * (c[..., 2] / 3.0 + s * c[..., 3] / 4.0)))


def _poly_eval(origin, u1, n1, c, s):
    """Positions, unit tangents and curvature vectors of transitions at arc length s (row-wise):
    p(s) = A + integral_0^s (cos psi u1 + sin psi n1), by 24-point Gauss-Legendre (psi is a
    polynomial of degree 4 turning a fraction of a radian: exact to rounding)."""
    sg = s[:, None] * _PX[None, :]
    ps = poly_heading(c, sg)
    x = s * (np.cos(ps) @ _PW)
    y = s * (np.sin(ps) @ _PW)
    pos = origin + x[:, None] * u1 + y[:, None] * n1
    psi = poly_heading(c, s)
    cp, sp = np.cos(psi)[:, None], np.sin(psi)[:, None]
    tangent = cp * u1 + sp * n1
    normal = -sp * u1 + cp * n1
    kappa = c[:, 0] + s * (c[:, 1] + s * (c[:, 2] + s * c[:, 3]))
    return pos, tangent, kappa[:, None] * normal


def poly_positions(origin, u1, n1, c, s) -> np.ndarray:
    """Positions of transitions (curvature polynomials c (N, 4) from origin along u1, turning
    towards n1) at arc length s, row-wise."""
    return _poly_eval(origin, u1, n1, c, s)[0]


def _pair_eval(origin, u1, n1, end, half, theta, s, arc=None, poly=None):
    """Positions, unit tangents and curvature vectors of blends at arc length s from A.

    A blend is a clothoid of length L_c (``half``) from A, an arc of length L_a (``arc``, 0 for
    a clothoid pair) and the mirror clothoid into B (``end``), turning by theta in all: the
    middle radius is R_c = (L_c + L_a) / theta, the clothoids' heading at x = s / L_c is
    (L_c / R_c) x^2 / 2. Row-wise arrays: origin, u1, n1, end (N, d); half, theta, s, arc (N,)."""
    if arc is None:
        arc = np.zeros_like(half)
    total = 2.0 * half + arc
    s = np.clip(s, 0.0, total)
    with np.errstate(divide="ignore", invalid="ignore"):
        rc = np.where(theta != 0.0, (half + arc) / np.where(theta != 0.0, theta, 1.0), np.inf)
    vt = half / rc
    first = s <= half
    third = s >= half + arc
    x = np.where(first, s, np.where(third, total - s, half)) / half
    xf, yf = fresnel(vt, x)
    xf = (xf * half)[:, None]
    yf = (yf * half)[:, None]
    ct, st = np.cos(theta)[:, None], np.sin(theta)[:, None]
    u2 = ct * u1 + st * n1
    n2 = -st * u1 + ct * n1
    f = first[:, None]
    pos = np.where(f, origin + xf * u1 + yf * n1, end - xf * u2 + yf * n2)
    phi = (0.5 * vt * x * x)[:, None]
    cp, sp = np.cos(phi), np.sin(phi)
    tangent = np.where(f, cp * u1 + sp * n1, cp * u2 - sp * n2)
    normal = np.where(f, -sp * u1 + cp * n1, sp * u2 + cp * n2)
    kappa = x / rc
    mid = ~(first | third)
    if mid.any():
        # the arc: from the first clothoid's end Q1 (heading vt / 2) about its centre
        k = np.nonzero(mid)[0]
        x1, y1 = fresnel(vt[k], np.ones(k.size))
        q1 = origin[k] + (x1 * half[k])[:, None] * u1[k] + (y1 * half[k])[:, None] * n1[k]
        ph0 = 0.5 * vt[k]
        psi = ph0 + (s[k] - half[k]) / rc[k]
        r = rc[k][:, None]
        pos[k] = q1 + r * ((np.sin(psi) - np.sin(ph0))[:, None] * u1[k]
                           + (np.cos(ph0) - np.cos(psi))[:, None] * n1[k])
        tangent[k] = np.cos(psi)[:, None] * u1[k] + np.sin(psi)[:, None] * n1[k]
        normal[k] = -np.sin(psi)[:, None] * u1[k] + np.cos(psi)[:, None] * n1[k]
        kappa[k] = 1.0 / rc[k]
    curv = kappa[:, None] * normal
    if poly is not None:
        is_poly = ~np.isnan(poly[:, 0])
        if is_poly.any():
            k = np.nonzero(is_poly)[0]
            pos[k], tangent[k], curv[k] = _poly_eval(origin[k], u1[k], n1[k], poly[k], s[k])
    return pos, tangent, curv


def blend_eval(move: Move, u_mm: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``Move.evaluate`` for a blend: position, unit tangent and curvature at u."""
    b = move.blend
    assert b is not None
    u = np.clip(np.atleast_1d(np.asarray(u_mm, dtype=float)).ravel(), 0.0, move.length_mm)
    n = u.shape[0]
    rep = (n, 1)
    poly = np.tile(np.array(b.poly if b.poly is not None else (math.nan,) * 4), rep)
    pos, tangent, curv = _pair_eval(np.tile(b.origin, rep), np.tile(b.u1, rep), np.tile(b.n1, rep),
                                    np.tile(move.end, rep), np.full(n, b.half_mm),
                                    np.full(n, b.turn_rad), b.s0_mm + u, np.full(n, b.arc_mm), poly)
    pos[u >= move.length_mm] = move.end
    return pos, tangent, np.sqrt((curv * curv).sum(axis=1))


def pair_positions(origin, u1, n1, end, half, theta, s, arc=None, poly=None) -> np.ndarray:
    """Positions only (row-wise arrays, see ``_pair_eval``)."""
    return _pair_eval(origin, u1, n1, end, half, theta, s, arc, poly)[0]


def pair_frames(origin, u1, n1, end, half, theta, s, arc=None, poly=None) -> tuple[np.ndarray, np.ndarray]:
    """(unit tangents, curvature vectors) at s (row-wise arrays)."""
    _, t, k = _pair_eval(origin, u1, n1, end, half, theta, s, arc, poly)
    return t, k


