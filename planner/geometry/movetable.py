"""Moves packed into flat NumPy arrays, so geometry is evaluated for many moves at once.

One row per move (Klipper's "one flat record per move"): start, end, length, feed, line
and, for arcs, the plane's axis columns, centre, radii, start angle, sweep and rise.
``positions(row, u)`` is the exact geometry of ``Move.evaluate`` (lines: linear in u;
circles and helices: the angle is linear in u, since |dq/du| is constant), vectorised over
samples of many different moves. Spirals (I/J/K radius mismatch within tolerance) are rare
and fall back to the move's own exact ``evaluate``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from planner.core.curves import pair_frames, pair_positions
from planner.core.movestore import MoveStore
from planner.core.program import Arc, Move, MoveKind, turn_xy

try:  # the sample geometry in C (planner/geometry/_kernels.c), built by `pip install -e .`
    import planner.geometry._kernels as _kernels
except ImportError:  # no compiler where it was installed: the NumPy forms, the reference
    _kernels = None  # type: ignore[assignment]

__all__ = ["MoveTable", "RowJoin", "concat_tables", "contour_error", "join_rows", "take_rows"]

_GL8_X, _GL8_W = np.polynomial.legendre.leggauss(8)
_GL8_X = (_GL8_X + 1.0) * 0.5
_GL8_W = _GL8_W * 0.5


def _spiral_newton(r0, r1, sweep, rise, length, u) -> np.ndarray:
    """Angle parameter t in [0, 1] with s(t) = u on spirals, by Newton's method.

    s(t) = t * sum_i w_i |p'(t x_i)|: 8-point Gauss-Legendre, exact to rounding for these
    nearly circular integrands (|p'|^2 is a quadratic in t with a relative spread of about
    2 dr / r <= 0.1). Starting from t = u / L, Newton converges in 2-3 steps.
    """
    t = np.clip(u / length, 0.0, 1.0)
    active = np.arange(t.shape[0])
    for _ in range(8):
        dr = r1[active] - r0[active]
        w = sweep[active]
        c0 = dr * dr + rise[active] ** 2
        ra = r0[active]
        ta = t[active]
        rad = ra[:, None] + dr[:, None] * (ta[:, None] * _GL8_X[None, :])
        s_t = ta * (np.sqrt(c0[:, None] + (rad * w[:, None]) ** 2) @ _GL8_W)
        speed = np.sqrt(c0 + ((ra + dr * ta) * w) ** 2)
        step = (s_t - u[active]) / speed
        t[active] = np.clip(ta - step, 0.0, 1.0)
        active = active[np.abs(step) > 1e-15]
        if not active.size:
            break
    return t


# Degree-7 interpolation at Chebyshev nodes on [0, 1] (one fixed matrix for every spiral).
#: arcs above this radius are evaluated from their start point (``MoveTable._far_arc``); below
#: it centre + radius (cos, sin) rounds no worse than a line's start + fraction x delta
_FAR_RADIUS_MM = 1000.0
_CHEB_X = 0.5 - 0.5 * np.cos((2 * np.arange(8) + 1) * np.pi / 16)
_CHEB_INV = np.linalg.inv(np.vander(_CHEB_X, 8, increasing=True))
SPIRAL_POLY_MAX_RATIO = 1e-2  # |dr| / r up to which the polynomial is exact to rounding


@dataclass(frozen=True, slots=True, eq=False)
class MoveTable:
    index: np.ndarray  # (n,) int64 global move index
    line: np.ndarray  # (n,) int32
    kind: np.ndarray  # (n,) int8 MoveKind
    start: np.ndarray  # (n, d)
    end: np.ndarray  # (n, d)
    delta: np.ndarray  # (n, d) end - start
    length: np.ndarray  # (n,)
    feed: np.ndarray  # (n,) mm/s, inf for rapids
    exact_stop: np.ndarray  # (n,) bool
    is_arc: np.ndarray  # (n,) bool
    spiral: np.ndarray  # (n,) bool
    first: np.ndarray  # (n,) int64 (0 for lines)
    second: np.ndarray
    normal: np.ndarray  # -1 when none
    cx: np.ndarray
    cy: np.ndarray
    r0: np.ndarray
    r1: np.ndarray
    theta0: np.ndarray
    sweep: np.ndarray
    rise: np.ndarray
    # a G18/G19 arc in a rotated system (Arc.xy_turn_rad): the turn of its frame about Z and the
    # machine's X and Y columns (0 elsewhere: only rows with a turn read them)
    turn: np.ndarray
    turn_x: np.ndarray
    turn_y: np.ndarray
    spiral_poly: np.ndarray  # (n, 8) t(x) - x coefficients (x = u / L), spirals only
    spiral_poly_ok: np.ndarray  # (n,) bool: polynomial exact to rounding for this spiral
    # corner blends (planner.geometry.blend): pair start A, unit direction and inside normal (n, d),
    # half length, turn and where the move starts along the pair (n,)
    is_blend: np.ndarray
    bl_a: np.ndarray
    bl_u1: np.ndarray
    bl_n1: np.ndarray
    bl_half: np.ndarray
    bl_turn: np.ndarray
    bl_s0: np.ndarray
    bl_arc: np.ndarray  # length of a fillet's middle arc (0 for a clothoid pair)
    bl_poly: np.ndarray  # (n, 4) a transition's curvature polynomial (NaN for the others)
    bl_kmax: np.ndarray  # largest curvature of a blend (1/mm)
    bl_dk: np.ndarray  # largest |dkappa/ds| of a blend (1/mm^2)

    @staticmethod
    def from_store(moves: MoveStore, n_axes: int) -> MoveTable:
        """The table of a program's moves (or a slice of them), from its columns."""
        c = moves.columns()
        n = len(moves)
        return MoveTable._build(np.arange(c.first, c.first + n, dtype=np.int64), c.line, c.kind,
                                c.start, c.end, c.length, c.feed, c.exact_stop, c.arc_rows, c.arcs,
                                c.blend_rows, c.blends, n_axes)

    @staticmethod
    def from_moves(moves: Sequence[Move], n_axes: int) -> MoveTable:
        """The table of Move objects (a few picked out of a program, or made by hand)."""
        moves = tuple(moves)
        n = len(moves)
        if n:
            start = np.array([m.start for m in moves], dtype=float).reshape(n, n_axes)
            end = np.array([m.end for m in moves], dtype=float).reshape(n, n_axes)
        else:
            start = np.zeros((0, n_axes))
            end = np.zeros((0, n_axes))
        rows = [(m.index, m.line, int(m.kind), m.length_mm, m.feed_mm_s, m.exact_stop) for m in moves]
        cols = list(zip(*rows)) if rows else [()] * 6
        arc_rows = [i for i, m in enumerate(moves) if m.arc is not None]
        blend_rows = [i for i, m in enumerate(moves) if m.blend is not None]
        return MoveTable._build(np.asarray(cols[0], dtype=np.int64), np.asarray(cols[1], dtype=np.int32),
                                np.asarray(cols[2], dtype=np.int8), start, end,
                                np.asarray(cols[3], dtype=float), np.asarray(cols[4], dtype=float),
                                np.asarray(cols[5], dtype=bool), np.asarray(arc_rows, dtype=np.int64),
                                tuple(moves[i].arc for i in arc_rows), np.asarray(blend_rows, dtype=np.int64),
                                tuple(moves[i].blend for i in blend_rows), n_axes)

    @staticmethod
    def _build(index: np.ndarray, line: np.ndarray, kind: np.ndarray, start: np.ndarray, end: np.ndarray,
               length: np.ndarray, feed: np.ndarray, exact_stop: np.ndarray, arc_rows: np.ndarray,
               arcs: tuple[Arc | None, ...], blend_rows: np.ndarray, blends: tuple[Any, ...],
               n_axes: int) -> MoveTable:
        n = int(length.shape[0])
        is_arc = np.zeros(n, dtype=bool)
        if arc_rows.size:
            arc_vals = np.zeros((n, 13))
            is_arc[arc_rows] = True
            arc_vals[arc_rows] = [(a.first_axis, a.second_axis, a.normal_axis, a.center[0], a.center[1],
                                   a.radius_start_mm, a.radius_end_mm, a.start_angle_rad, a.sweep_rad,
                                   a.rise_mm, a.xy_turn_rad, *(a.turned_xy or (0, 0)))
                                  for a in arcs if a is not None]
            first = arc_vals[:, 0].astype(np.int64)
            second = arc_vals[:, 1].astype(np.int64)
            normal = np.where(is_arc, arc_vals[:, 2], -1).astype(np.int64)
            turn_x = arc_vals[:, 11].astype(np.int64)
            turn_y = arc_vals[:, 12].astype(np.int64)
        else:
            # no arc: the arc columns take no memory (one row repeated, stride 0), as below
            arc_vals = np.broadcast_to(np.zeros((1, 13)), (n, 13))
            first = second = turn_x = turn_y = np.broadcast_to(np.zeros(1, np.int64), (n,))
            normal = np.broadcast_to(np.full(1, -1, np.int64), (n,))
        r0, r1 = arc_vals[:, 5], arc_vals[:, 6]
        spiral = is_arc & (r0 != r1)
        k = np.nonzero(spiral)[0]
        if k.size:
            poly = np.zeros((n, 8))
            poly_ok = np.zeros(n, dtype=bool)
            ratio = np.abs(r1[k] - r0[k]) / np.minimum(r0[k], r1[k])
            poly_ok[k] = ratio <= SPIRAL_POLY_MAX_RATIO
            kk = np.repeat(k, 8)
            u = np.tile(_CHEB_X, k.size) * length[kk]
            t = _spiral_newton(r0[kk], r1[kk], arc_vals[kk, 8], arc_vals[kk, 9], length[kk], u)
            dev = (t - np.tile(_CHEB_X, k.size)).reshape(k.size, 8)
            poly[k] = dev @ _CHEB_INV.T
        else:
            poly = np.broadcast_to(np.zeros((1, 8)), (n, 8))
            poly_ok = np.broadcast_to(np.zeros(1, bool), (n,))
        is_blend = np.zeros(n, dtype=bool)
        if blend_rows.size:
            bl_vec = np.zeros((3, n, n_axes))
            bl_val = np.zeros((6, n))
            bl_poly = np.full((n, 4), np.nan)
            for i, b in zip(blend_rows.tolist(), blends):
                is_blend[i] = True
                bl_vec[0, i], bl_vec[1, i], bl_vec[2, i] = b.origin, b.u1, b.n1
                bl_val[:, i] = (b.half_mm, b.turn_rad, b.s0_mm, b.arc_mm, b.kappa_max, b.sharpness)
                if b.poly is not None:
                    bl_poly[i] = b.poly
        else:
            # no blend: the blend columns take no memory (read-only views of one row, stride 0;
            # 150 bytes a move otherwise, 300 MB on a 2-million-line program)
            bl_vec = np.broadcast_to(np.zeros((3, 1, n_axes)), (3, n, n_axes))
            bl_val = np.broadcast_to(np.zeros((6, 1)), (6, n))
            bl_poly = np.broadcast_to(np.full((1, 4), np.nan), (n, 4))
        return MoveTable(
            index=index, line=line, kind=kind,
            start=start, end=end, delta=end - start,
            length=length, feed=feed, exact_stop=exact_stop,
            is_arc=is_arc,
            spiral=spiral,
            first=first, second=second, normal=normal,
            cx=arc_vals[:, 3], cy=arc_vals[:, 4], r0=r0, r1=r1,
            theta0=arc_vals[:, 7], sweep=arc_vals[:, 8], rise=arc_vals[:, 9],
            turn=arc_vals[:, 10], turn_x=turn_x, turn_y=turn_y,
            spiral_poly=poly, spiral_poly_ok=poly_ok,
            is_blend=is_blend, bl_a=bl_vec[0], bl_u1=bl_vec[1], bl_n1=bl_vec[2],
            bl_half=bl_val[0], bl_turn=bl_val[1], bl_s0=bl_val[2], bl_arc=bl_val[3],
            bl_poly=bl_poly, bl_kmax=bl_val[4], bl_dk=bl_val[5],
        )

    def __len__(self) -> int:
        return int(self.length.shape[0])

    @property
    def n_axes(self) -> int:
        return int(self.start.shape[1])

    @property
    def is_rapid(self) -> np.ndarray:
        return self.kind == int(MoveKind.RAPID)

    # -- geometry -------------------------------------------------------------------------
    def positions(self, row: np.ndarray, u: np.ndarray) -> np.ndarray:
        """Exact positions (N, d) of move ``row[k]`` at path length ``u[k]``: lines and plain
        arcs in C where it is built (``_kernels.positions``), the other rows here."""
        if _kernels is None or not len(row):
            return self.positions_numpy(row, u)
        row = np.ascontiguousarray(row, dtype=np.int64)
        u = np.ascontiguousarray(u, dtype=float)
        out = np.empty((len(row), self.n_axes))
        left = _kernels.positions(self.start, self.delta, self.end, self.length, self.is_arc, self.is_blend,
                                  self.spiral, self.turn, self.first, self.second, self.cx, self.cy, self.r0,
                                  self.r1, self.theta0, self.sweep, _FAR_RADIUS_MM, row, u, out)
        if left:
            k = np.flatnonzero(np.isnan(out[:, 0]))
            out[k] = self.positions_numpy(row[k], u[k])
        return out

    def positions_numpy(self, row: np.ndarray, u: np.ndarray) -> np.ndarray:
        """``positions`` in NumPy, every kind of row (the reference of the compiled form)."""
        length = self.length[row]
        frac = np.clip(u / length, 0.0, 1.0)
        arc = self.is_arc[row]
        if arc.any():
            k = np.nonzero(arc)[0]
            r = row[k]
            sp = self.spiral[r]
            if sp.any():
                frac[k[sp]] = self.spiral_param(r[sp], u[k[sp]])
        q = self.delta[row]
        q *= frac[:, None]
        q += self.start[row]
        if arc.any():
            # arcs in a turned frame: the linear part (start + frac delta) into the frame first
            tw = np.nonzero(self.turn[r])[0]
            if tw.size:
                self._turn(q, k[tw], r[tw], -1.0)
            fk = frac[k]
            theta = self.theta0[r] + self.sweep[r] * fk
            r0 = self.r0[r]
            rad = r0 + (self.r1[r] - r0) * fk
            x = self.cx[r] + rad * np.cos(theta)
            y = self.cy[r] + rad * np.sin(theta)
            f, s = self.first[r], self.second[r]
            far = r0 > _FAR_RADIUS_MM
            if far.any():
                x[far], y[far] = self._far_arc(r[far], fk[far])
            if f.size and np.all(f == f[0]) and np.all(s == s[0]):  # one plane: plain columns
                q[k, f[0]] = x
                q[k, s[0]] = y
            else:
                q[k, f] = x
                q[k, s] = y
            if tw.size:
                self._turn(q, k[tw], r[tw], 1.0)
        bl = self.is_blend[row]
        if bl.any():
            k = np.nonzero(bl)[0]
            r = row[k]
            q[k] = pair_positions(self.bl_a[r], self.bl_u1[r], self.bl_n1[r], self.end[r], self.bl_half[r],
                                  self.bl_turn[r], self.bl_s0[r] + u[k], self.bl_arc[r], self.bl_poly[r])
        done = frac >= 1.0
        if done.any():
            q[done] = self.end[row[done]]
        return q

    def _far_arc(self, r: np.ndarray, fk: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(first, second) coordinates on arcs of a large radius, from the start point: centre +
        radius (cos, sin) loses the last digits to the radius (an arc of kilometres: noise the
        limit meter reads as jerk). The start's radius vector v turned by the angle so far,
        R v - v by the half-angle forms, is small where the turn is; a spiral scales R v."""
        f, s = self.first[r], self.second[r]
        start = self.start[r]
        tw = np.nonzero(self.turn[r])[0]
        if tw.size:                          # the start in the frame of a turned arc
            self._turn(start, tw, r[tw], -1.0)
        xs, ys = start[np.arange(r.size), f], start[np.arange(r.size), s]
        vx, vy = xs - self.cx[r], ys - self.cy[r]
        half = 0.5 * self.sweep[r] * fk
        sh, ch = np.sin(half), np.cos(half)
        c1 = -2.0 * sh * sh                  # cos(turn) - 1
        s1 = 2.0 * sh * ch                   # sin(turn)
        dx = c1 * vx - s1 * vy
        dy = s1 * vx + c1 * vy
        grow = (self.r1[r] - self.r0[r]) * fk / self.r0[r]
        return xs + dx + grow * (vx + dx), ys + dy + grow * (vy + dy)

    def _turn(self, q: np.ndarray, k: np.ndarray, r: np.ndarray, sign: float) -> None:
        """Turn rows ``k`` of ``q`` (moves ``r``, arcs in a turned frame) into their frame
        (``sign`` -1) or back to the machine's (+1)."""
        turn_xy(q, self.turn_x[r], self.turn_y[r], sign * self.turn[r], k)

    def _blend_frames(self, at_end: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(rows, unit tangents, curvature vectors) of the blends at their start or end."""
        k = np.nonzero(self.is_blend)[0]
        s = 2.0 * self.bl_half[k] + self.bl_arc[k] if at_end else self.bl_s0[k]
        t, c = pair_frames(self.bl_a[k], self.bl_u1[k], self.bl_n1[k], self.end[k], self.bl_half[k],
                           self.bl_turn[k], s, self.bl_arc[k], self.bl_poly[k])
        return k, t, c

    def spiral_param(self, r: np.ndarray, u: np.ndarray) -> np.ndarray:
        """Angle parameter t in [0, 1] at path length u on spirals.

        Nearly circular spirals (all CAM rounding cases): t = x + g(x), x = u / L, with g the
        degree-7 interpolant at Chebyshev nodes of the exact deviation (``spiral_poly``; its
        error is of order (dr / r)^8, below rounding). Others: Newton on the exact length.
        """
        length = self.length[r]
        u = np.clip(u, 0.0, length)
        x = u / length
        ok = self.spiral_poly_ok[r]
        t = np.empty_like(x)
        if ok.any():
            c = self.spiral_poly[r[ok]]
            xo = x[ok]
            g = c[:, 7]
            for k in range(6, -1, -1):
                g = g * xo + c[:, k]
            t[ok] = np.clip(xo + g, 0.0, 1.0)
        if not ok.all():
            rb = r[~ok]
            t[~ok] = _spiral_newton(self.r0[rb], self.r1[rb], self.sweep[rb], self.rise[rb],
                                    length[~ok], u[~ok])
        return np.where(u >= length, 1.0, t)  # the end point exactly

    def plane_frames(self, row: np.ndarray, u: np.ndarray
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Positions (N, d), unit tangents dq/du (N, d), curvature (N,) and the fraction of the
        move (N,; an arc's: of its angle) of lines and of arcs in a machine plane at path length
        u, as ``Move.evaluate`` gives them; an arc's curvature is signed, positive turning left
        in its (first, second) plane (0 on lines). Not for helices (the curvature is the
        plane's) nor arcs in a turned frame (their plane is no machine plane)."""
        pos = self.positions(row, u)
        length = self.length[row]
        tangent = self.delta[row] / length[:, None]
        kappa = np.zeros(len(row))
        frac = np.clip(u / length, 0.0, 1.0)
        k = np.flatnonzero(self.is_arc[row])
        if k.size:
            r = row[k]
            uk = np.clip(u[k], 0.0, length[k])
            t = np.where(self.spiral[r], 0.0, uk / length[k])
            sp = np.flatnonzero(self.spiral[r])
            if sp.size:
                t[sp] = self.spiral_param(r[sp], uk[sp])
            w = self.sweep[r]
            dr = self.r1[r] - self.r0[r]
            rad = self.r0[r] + dr * t
            theta = self.theta0[r] + w * t
            c, sn = np.cos(theta), np.sin(theta)
            d1f = dr * c - rad * w * sn
            d1s = dr * sn + rad * w * c
            d2f = -2.0 * dr * w * sn - rad * w * w * c
            d2s = 2.0 * dr * w * c - rad * w * w * sn
            rise = self.rise[r]
            speed = np.sqrt(d1f * d1f + d1s * d1s + rise * rise)
            tk = self.delta[r] / speed[:, None]
            i = np.arange(k.size)
            tk[i, self.first[r]] = d1f / speed
            tk[i, self.second[r]] = d1s / speed
            nrm = self.normal[r]
            has = nrm >= 0
            tk[i[has], nrm[has]] = rise[has] / speed[has]
            tangent[k] = tk
            kappa[k] = (d1f * d2s - d1s * d2f) / speed ** 3
            frac[k] = t
        return pos, tangent, kappa, frac

    def end_tangents(self) -> tuple[np.ndarray, np.ndarray]:
        """Unit tangents dq/du (n, d) at the start and at the end of every move."""
        n, d = len(self), self.n_axes
        with np.errstate(divide="ignore", invalid="ignore"):
            lin = (self.end - self.start) / self.length[:, None]
        t_start = lin.copy()
        t_end = lin.copy()
        k = np.nonzero(self.is_arc)[0]
        if k.size:
            w = self.sweep[k]
            for frac, out in ((0.0, t_start), (1.0, t_end)):
                theta = self.theta0[k] + w * frac
                rad = self.r0[k] + (self.r1[k] - self.r0[k]) * frac
                dr = self.r1[k] - self.r0[k]
                d1f = dr * np.cos(theta) - rad * w * np.sin(theta)
                d1s = dr * np.sin(theta) + rad * w * np.cos(theta)
                speed = np.sqrt(d1f * d1f + d1s * d1s + self.rise[k] ** 2)
                out[k] = (self.end[k] - self.start[k]) / speed[:, None]
                tw = np.nonzero(self.turn[k])[0]
                if tw.size:
                    self._turn(out, k[tw], k[tw], -1.0)
                out[k, self.first[k]] = d1f / speed
                out[k, self.second[k]] = d1s / speed
                if tw.size:
                    self._turn(out, k[tw], k[tw], 1.0)
        if self.is_blend.any():
            for at_end, out in ((False, t_start), (True, t_end)):
                k, t, _ = self._blend_frames(at_end)
                out[k] = t
        del n, d
        return t_start, t_end

    def end_curvature_vectors(self) -> tuple[np.ndarray, np.ndarray]:
        """Curvature vectors d2q/du2 (n, d) at the start and end (zero for lines)."""
        c_start = np.zeros_like(self.start)
        c_end = np.zeros_like(self.start)
        k = np.nonzero(self.is_arc)[0]
        if k.size:
            omega = self.sweep[k] / self.length[k]  # rad per mm of path
            for frac, out in ((0.0, c_start), (1.0, c_end)):
                theta = self.theta0[k] + self.sweep[k] * frac
                rad = self.r0[k] + (self.r1[k] - self.r0[k]) * frac
                out[k, self.first[k]] = -rad * omega * omega * np.cos(theta)
                out[k, self.second[k]] = -rad * omega * omega * np.sin(theta)
                tw = np.nonzero(self.turn[k])[0]
                if tw.size:                  # written in the frame, where the rest was 0
                    self._turn(out, k[tw], k[tw], 1.0)
        if self.is_blend.any():
            for at_end, out in ((False, c_start), (True, c_end)):
                k, _, c = self._blend_frames(at_end)
                out[k] = c
        return c_start, c_end

    def arc_terms(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """For arcs: (rho, kappa, |omega|): in-plane tangent norm, curvature, rad per mm.

        Circle/helix: rho = R |omega|, kappa = R omega^2 (= R / (R^2 + c^2) for a helix),
        in-plane jerk at constant speed v^3 kappa |omega| (= v^3 / R^2 for a circle).
        Spirals: the bounds of their small end (the curvature grows as the radius shrinks).
        """
        with np.errstate(divide="ignore", invalid="ignore"):
            omega = np.where(self.is_arc, np.abs(self.sweep) / self.length, 0.0)
        rmax = np.maximum(self.r0, self.r1)
        rho = np.where(self.is_arc, np.minimum(rmax * omega, 1.0), 0.0)
        kappa = np.where(self.is_arc, rmax * omega * omega, 0.0)
        sp = np.nonzero(self.spiral)[0]
        if sp.size:
            # r = r0 + c theta: the curvature (r^2 + 2 c^2) / (r^2 + c^2)^1.5 and the turn rate
            # 1 / sqrt(r^2 + c^2 + h^2) are largest at the small end (the rise h per radian only
            # lowers the curvature): bound both there, and the in-plane share by 1
            c, h, q = self._spiral_small_end(sp)
            kappa[sp] = np.maximum(kappa[sp], (q + c * c) / (q * np.sqrt(q)))
            omega[sp] = np.maximum(omega[sp], 1.0 / np.sqrt(q + h * h))
            rho[sp] = 1.0
        bl = np.nonzero(self.is_blend)[0]
        if bl.size:
            # a planar curve: the whole tangent is in its plane; the curvature peaks mid-pair
            kb = self.bl_kmax[bl]
            rho[bl], kappa[bl], omega[bl] = 1.0, kb, kb
        return rho, kappa, omega

    def _spiral_small_end(self, sp: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Spirals r = r0 + c theta (rise h per radian): (c, h, r^2 + c^2 at the small end)."""
        sweep = np.abs(self.sweep[sp])
        c = (self.r1[sp] - self.r0[sp]) / sweep
        r = np.minimum(self.r0[sp], self.r1[sp])
        return c, self.rise[sp] / sweep, r * r + c * c

    def curvature_rate(self) -> np.ndarray:
        """A bound of |d kappa / ds| (1/mm^2) on every move: 0 on lines and circles; on
        spirals r = r0 + c theta, |dkappa/dr| = r (r^2 + 4 c^2) / (r^2 + c^2)^2.5 <= 4 / (r^2 + c^2)
        at the small end, times |c| dtheta/ds <= |c| / sqrt(r^2 + c^2 + h^2). The jerk of the
        changing curvature, v^3 dkappa/ds, is what a circle does not have."""
        out = np.zeros(len(self))
        sp = np.nonzero(self.spiral)[0]
        if sp.size:
            c, h, q = self._spiral_small_end(sp)
            out[sp] = 4.0 * np.abs(c) / (q * np.sqrt(q + h * h))
        bl = np.nonzero(self.is_blend)[0]
        if bl.size:  # clothoids: 1 / (R_c L_c) = theta / (L_c (L_c + L_a)); transitions: their largest
            out[bl] = self.bl_dk[bl]
        return out


def concat_tables(tables: list[MoveTable]) -> MoveTable:
    """One table of the rows of several (consecutive) tables."""
    if len(tables) == 1:
        return tables[0]
    return MoveTable(**{name: join_rows([getattr(t, name) for t in tables]) for name in MoveTable.__slots__})


class RowJoin:
    """Rows of consecutive parts joined into one array made once at its full length, part by
    part (joining a list of parts needs the parts and the whole at once, and the parts' freed
    memory lies between the arrays kept, where the heap cannot give it back). A column whose
    parts all repeat one row (stride 0: the arc and blend columns of tables without them)
    stays one row repeated."""

    __slots__ = ("total", "out", "rep", "filled", "like")

    def __init__(self, total: int) -> None:
        self.total = total
        self.out: np.ndarray | None = None
        self.rep: np.ndarray | None = None
        self.filled = 0
        self.like: np.ndarray | None = None  # the first part's empty rows: shape and dtype

    def add(self, part: np.ndarray) -> None:
        if self.like is None:
            self.like = part[:0]
        k = part.shape[0]
        if k == 0:
            return
        if self.out is None:
            same = self.rep is None or np.array_equal(part[:1], self.rep, equal_nan=True)
            if part.strides[0] == 0 and same:
                self.rep = part[:1] if self.rep is None else self.rep
                self.filled += k
                return
            dtype = part.dtype if self.rep is None else np.result_type(self.rep, part)
            self.out = np.empty((self.total, *part.shape[1:]), dtype=dtype)
            if self.filled:
                self.out[: self.filled] = self.rep
        elif part.dtype != self.out.dtype:
            self.out = self.out.astype(np.result_type(self.out, part))
        self.out[self.filled: self.filled + k] = part
        self.filled += k

    def result(self) -> np.ndarray:
        if self.filled != self.total:
            raise ValueError(f"joined rows: {self.filled} of {self.total}")
        if self.out is not None:
            return self.out
        if self.rep is not None:
            return np.broadcast_to(self.rep, (self.total, *self.rep.shape[1:]))
        assert self.like is not None, "no part to join"
        return self.like.copy()


def join_rows(parts: list[np.ndarray]) -> np.ndarray:
    """Concatenated rows (``RowJoin``: one repeated row stays one)."""
    join = RowJoin(sum(p.shape[0] for p in parts))
    for part in parts:
        join.add(part)
    return join.result()


def take_rows(table: MoveTable, sl: slice) -> MoveTable:
    """Rows ``sl`` of a table."""
    return MoveTable(**{name: getattr(table, name)[sl] for name in MoveTable.__slots__})


def contour_error(table: MoveTable, row: np.ndarray, q: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Distance (N,) of the points q from the programmed geometry of move ``row[k]``: lines and
    arcs not in a turned frame in C where it is built (``_kernels.contour_error``), blends and
    turned arcs by ``contour_error_numpy``."""
    if _kernels is None or not len(row):
        return contour_error_numpy(table, row, q, u)
    row = np.ascontiguousarray(row, dtype=np.int64)
    q = np.ascontiguousarray(q, dtype=float)
    u = np.ascontiguousarray(u, dtype=float)
    out = np.empty(len(row))
    left = _kernels.contour_error(table.start, table.delta, table.length, table.is_arc, table.is_blend,
                                  table.turn, table.first, table.second, table.cx, table.cy, table.r0,
                                  table.r1, table.theta0, table.sweep, row, q, u, out)
    if left:
        k = np.flatnonzero(np.isnan(out))
        out[k] = contour_error_numpy(table, row[k], q[k], u[k])
    return out


def contour_error_numpy(table: MoveTable, row: np.ndarray, q: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Distance (N,) of the points q from the programmed geometry of move ``row[k]``.

    ``u`` (the samples' path parameter) only picks the turn of multi-turn arcs.

    Lines: distance from the segment's line. Arcs: radial error in the plane and the error of
    the other axes against their value at the point's actual angle (helix pitch included).
    """
    start = table.start[row]
    delta = table.end[row] - start
    rel = q - start
    with np.errstate(divide="ignore", invalid="ignore"):
        proj = np.clip((rel * delta).sum(axis=1) / (delta * delta).sum(axis=1), 0.0, 1.0)
    proj = np.nan_to_num(proj)
    err = rel - proj[:, None] * delta
    bl = table.is_blend[row]
    if bl.any():
        # distance from the pair: one Newton step along the tangent from the sample's own
        # parameter (second order in the along-path offset)
        k = np.nonzero(bl)[0]
        r = row[k]
        args = (table.bl_a[r], table.bl_u1[r], table.bl_n1[r], table.end[r], table.bl_half[r],
                table.bl_turn[r])
        arc_len, poly = table.bl_arc[r], table.bl_poly[r]
        s_k = table.bl_s0[r] + np.clip(u[k], 0.0, table.length[r])
        t_k, _ = pair_frames(*args, s_k, arc_len, poly)
        p_k = pair_positions(*args, s_k, arc_len, poly)
        s_k = np.clip(s_k + ((q[k] - p_k) * t_k).sum(axis=1), table.bl_s0[r],
                      2.0 * table.bl_half[r] + arc_len)
        err[k] = q[k] - pair_positions(*args, s_k, arc_len, poly)
    arc = table.is_arc[row]
    if arc.any():
        k = np.nonzero(arc)[0]
        r = row[k]
        f, s = table.first[r], table.second[r]
        qk, start_k, delta_k = q[k], start[k], delta[k]     # copies (fancy indexing)
        tw = np.nonzero(table.turn[r])[0]
        if tw.size:                          # arcs in a turned frame: all three into it
            for a in (qk, start_k, delta_k):
                table._turn(a, tw, r[tw], -1.0)
        px = qk[np.arange(k.size), f] - table.cx[r]
        py = qk[np.arange(k.size), s] - table.cy[r]
        ang = np.arctan2(py, px)
        # Unwrap the angle next to the nominal angle of the point's own path parameter.
        sweep = table.sweep[r]
        nominal = table.theta0[r] + sweep * np.clip(u[k] / table.length[r], 0.0, 1.0)
        ang = nominal + np.remainder(ang - nominal + np.pi, 2.0 * np.pi) - np.pi
        frac = np.clip((ang - table.theta0[r]) / sweep, 0.0, 1.0)
        # an arc that hardly turns (a helix step whose start is a hair off its full circle):
        # the angle cannot place a point along it (an angle's rounding over that sweep is a
        # visible length), the projection on its chord can
        flat = np.maximum(table.r0[r], table.r1[r]) * np.abs(sweep) < 1e-6 * table.length[r]
        frac = np.where(flat, proj[k], frac)
        radius = table.r0[r] + (table.r1[r] - table.r0[r]) * frac
        other = qk - (start_k + frac[:, None] * delta_k)
        other[np.arange(k.size), f] = 0.0
        other[np.arange(k.size), s] = 0.0
        radial = np.hypot(px, py) - radius
        err_k = np.sqrt(radial * radial + (other * other).sum(axis=1))
        out = np.sqrt((err * err).sum(axis=1))
        out[k] = err_k
        return out
    return np.sqrt((err * err).sum(axis=1))
