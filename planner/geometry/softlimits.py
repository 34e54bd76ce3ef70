"""Soft limits checked on the whole path, arcs by their exact extremes (not only end points).

A circle or helix reaches its extreme along a plane axis where the angle crosses a multiple
of pi/2 inside the swept range: those points are added to the end points. Spirals (radius
changing linearly with the angle) are checked on dense samples (every 1 degree) plus the
end points, with the radius bound as a safety margin only where the samples get close.
Other axes of an arc (helix axis, rotary axes) move linearly: their end points are extreme.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass

import numpy as np

from planner.core.machine import MachineSpec
from planner.core.program import Arc, Move, Program

__all__ = [
    "LimitViolation", "check_and_bound", "check_point", "check_program", "move_bounds", "move_bounds_pieces",
    "move_bounds_table", "program_bounds",
]

_EPS = 1e-9  # mm|deg: rounding allowance at a limit


@dataclass(frozen=True, slots=True)
class LimitViolation:
    line: int
    axis: str
    value: float  # the extreme reached (mm|deg)
    limit: float  # the limit it crosses
    where: str  # "end point", "arc extreme", "path"

    def __str__(self) -> str:
        side = "max" if self.value > self.limit else "min"
        return (f"line {self.line}: axis {self.axis} reaches {self.value:.4f} ({self.where}), "
                f"beyond its soft limit {side} {self.limit:g}")


def move_bounds(move: Move) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(min per axis, max per axis, points where they occur (2, n_axes) unused) of one move."""
    pts = [move.start, move.end]
    if move.blend is not None and move.blend.poly is None:
        # a blend turns less than half a circle, so it stays inside the triangle of its ends
        # and the programmed corner: the corner bounds it (the programmed path reached it)
        pts.append(move.blend.corner)
    elif move.blend is not None:
        # a transition: its points 1/64 of its length apart, widened by what the curve can
        # bulge between two of them (kappa h^2 / 8)
        h = move.length_mm / 64.0
        q = move.evaluate(np.linspace(0.0, move.length_mm, 65))[0]
        bulge = move.blend.kappa_max * h * h / 8.0
        pts.extend(q - bulge)
        pts.extend(q + bulge)
    arc = move.arc
    if arc is not None:
        if arc.radius_end_mm == arc.radius_start_mm:
            a0 = arc.start_angle_rad
            a1 = a0 + arc.sweep_rad
            lo, hi = min(a0, a1), max(a0, a1)
            k0 = math.ceil(lo / (math.pi / 2) - 1e-12)
            k1 = math.floor(hi / (math.pi / 2) + 1e-12)
            ang = np.arange(k0, k1 + 1) * (math.pi / 2) if k1 >= k0 else np.zeros(0)
            if arc.xy_turn_rad != 0.0:
                ang = np.concatenate([ang, _turned_extreme_angles(arc, lo, hi)])
            if ang.size:
                # Angle -> path length: u = L (ang - a0) / sweep (angle linear in u).
                u = move.length_mm * (ang - a0) / arc.sweep_rad if arc.sweep_rad else np.zeros_like(ang)
                p = move.evaluate(u)[0]
                # Exact plane coordinates at the extreme angles (no rounding from u); in a turned
                # frame u's rounding stays (the extremes of X and Y are no plane coordinates)
                if arc.xy_turn_rad == 0.0:
                    p[:, arc.first_axis] = arc.center[0] + arc.radius_start_mm * np.cos(ang)
                    p[:, arc.second_axis] = arc.center[1] + arc.radius_start_mm * np.sin(ang)
                pts.extend(p)
        else:
            n = max(int(abs(arc.sweep_rad) / math.radians(1.0)) + 2, 8)
            pts.extend(move.evaluate(np.linspace(0.0, move.length_mm, n))[0])
    arr = np.vstack(pts)
    return arr.min(axis=0), arr.max(axis=0), arr


def _turned_extreme_angles(arc: Arc, lo: float, hi: float) -> np.ndarray:
    """Angles in [lo, hi] where the machine's X or Y is extreme on a circle or helix in a turned
    frame (G18/G19 in a rotated system). There each of X and Y is a cos(t) + b sin(t) + g t +
    const: the frame's in-plane axes and its normal each carry part of it, so a helix's extremes
    are off the quarter turns: where -a sin(t) + b cos(t) + g = 0."""
    c, s = math.cos(arc.xy_turn_rad), math.sin(arc.xy_turn_rad)
    turned = (c, s)                       # the frame's X in machine X, Y
    normal = (-s, c)                      # the frame's Y
    # (X, Y) parts of the plane's first axis, its second, and its normal, per unit
    if arc.plane == "ZX":                 # first Z, second the frame's X, normal its Y
        first, second, along = (0.0, 0.0), turned, normal
    else:                                 # "YZ": first the frame's Y, second Z, normal its X
        first, second, along = normal, (0.0, 0.0), turned
    r = arc.radius_start_mm
    k = arc.rise_mm / arc.sweep_rad if arc.sweep_rad else 0.0
    out = []
    for axis in (0, 1):
        a, b, g = r * first[axis], r * second[axis], k * along[axis]
        amp = math.hypot(a, b)
        if amp == 0.0 or abs(g) > amp:
            continue
        delta = math.atan2(a, b)          # -a sin t + b cos t = amp cos(t + delta)
        psi = math.acos(-g / amp)
        for base in (-delta + psi, -delta - psi):
            m0 = math.ceil((lo - base) / (2 * math.pi))
            m1 = math.floor((hi - base) / (2 * math.pi))
            out += [base + 2 * math.pi * m for m in range(m0, m1 + 1)]
    return np.array(out)


#: moves whose bounds are made at once: a piece's tables are a few megabytes (the whole
#: table of 10,000,000 moves took 480 MB for as long as the load held it)
PIECE_MOVES = 1 << 18


def move_bounds_pieces(program: Program,
                       piece: int = PIECE_MOVES) -> Iterator[tuple[int, np.ndarray, np.ndarray]]:
    """Per-move bounds a piece of moves at a time: (first move, lo (m, n_axes), hi (m, n_axes)),
    arcs exact: NumPy over lines and rapids (their end points), ``move_bounds`` for arcs and
    blends. Made a piece at a time so that a load in a worker thread never holds the GIL for
    long."""
    moves = program.moves
    # straight moves by their end points at once, only arcs and blends one by one
    pos = moves.positions
    cols = moves.columns()
    special = np.union1d(cols.arc_rows, cols.blend_rows)
    for a in range(0, len(moves), piece):
        b = min(a + piece, len(moves))
        lo = np.minimum(pos[a:b], pos[a + 1:b + 1])
        hi = np.maximum(pos[a:b], pos[a + 1:b + 1])
        for k in special[np.searchsorted(special, a):np.searchsorted(special, b)].tolist():
            lo[k - a], hi[k - a], _ = move_bounds(moves[k])
        yield a, lo, hi


def move_bounds_table(program: Program) -> tuple[np.ndarray, np.ndarray]:
    """Per-move bounds of the whole program (lo (M, n_axes), hi (M, n_axes)), arcs exact."""
    n = len(program.axes) if program.axes else len(program.start_position)
    pieces = list(move_bounds_pieces(program))
    if not pieces:
        return np.empty((0, n)), np.empty((0, n))
    return np.concatenate([p[1] for p in pieces]), np.concatenate([p[2] for p in pieces])


def _pieces(program: Program, table: tuple[np.ndarray, np.ndarray] | None, piece: int = PIECE_MOVES
            ) -> Iterable[tuple[int, np.ndarray, np.ndarray]]:
    return [(0, *table)] if table is not None else move_bounds_pieces(program, piece)


def program_bounds(program: Program, table: tuple[np.ndarray, np.ndarray] | None = None
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Axis-aligned bounding box of the whole path (machine coordinates), arcs exact.
    ``table``: a ``move_bounds_table`` of the program, if already built."""
    lo = np.asarray(program.start_position, dtype=float).copy()
    hi = lo.copy()
    for _, mlo, mhi in _pieces(program, table):
        if len(mlo):
            np.minimum(lo, mlo.min(axis=0), out=lo)
            np.maximum(hi, mhi.max(axis=0), out=hi)
    return lo, hi


def check_point(machine: MachineSpec, q: np.ndarray) -> list[tuple[str, float, float]]:
    """(axis, value, limit) for every axis of ``q`` outside its travel."""
    out = []
    for i, ax in enumerate(machine.axes):
        v = float(q[i])
        if ax.wrapped:                  # turns without end: no travel to leave
            continue
        if v > ax.max_pos + _EPS:
            out.append((ax.name, v, ax.max_pos))
        elif v < ax.min_pos - _EPS:
            out.append((ax.name, v, ax.min_pos))
    return out


def check_program(program: Program, machine: MachineSpec, max_reports: int = 50,
                  table: tuple[np.ndarray, np.ndarray] | None = None) -> list[LimitViolation]:
    """Every move whose path leaves an axis' travel, with its line and axis (first report per
    move and axis). Empty when the whole path is inside the soft limits. ``table``: a
    ``move_bounds_table`` of the program, if already built."""
    return check_and_bound(program, machine, max_reports, table)[0]


def check_and_bound(program: Program, machine: MachineSpec, max_reports: int = 50,
                    table: tuple[np.ndarray, np.ndarray] | None = None, piece: int = PIECE_MOVES
                    ) -> tuple[list[LimitViolation], np.ndarray, np.ndarray]:
    """``check_program`` and ``program_bounds`` in one pass over the moves, ``piece`` moves at
    a time (the bounds of every move are never held at once)."""
    lo_lim = np.array([-np.inf if a.wrapped else a.min_pos for a in machine.axes])
    hi_lim = np.array([np.inf if a.wrapped else a.max_pos for a in machine.axes])
    names = machine.axis_names
    out: list[LimitViolation] = []
    lo = np.asarray(program.start_position, dtype=float).copy()
    hi = lo.copy()
    for first, mlo, mhi in _pieces(program, table, piece):
        if not len(mlo):
            continue
        np.minimum(lo, mlo.min(axis=0), out=lo)
        np.maximum(hi, mhi.max(axis=0), out=hi)
        if len(out) >= max_reports:
            continue
        bad_hi_all = mhi > hi_lim + _EPS
        bad_lo_all = mlo < lo_lim - _EPS
        for j in np.flatnonzero((bad_hi_all | bad_lo_all).any(axis=1)):
            m = program.moves[first + int(j)]
            a, b = mlo[j], mhi[j]
            bad_hi, bad_lo = bad_hi_all[j], bad_lo_all[j]
            ends = np.vstack([m.start, m.end])
            for i in np.nonzero(bad_hi | bad_lo)[0]:
                if bad_hi[i]:
                    value, limit = float(b[i]), float(hi_lim[i])
                    at_end = ends[:, i].max() > hi_lim[i] + _EPS
                else:
                    value, limit = float(a[i]), float(lo_lim[i])
                    at_end = ends[:, i].min() < lo_lim[i] - _EPS
                where = "end point" if at_end else ("arc extreme" if m.arc is not None else "path")
                out.append(LimitViolation(m.line, names[i], value, limit, where))
                if len(out) >= max_reports:
                    break
            if len(out) >= max_reports:
                break
    return out, lo, hi
