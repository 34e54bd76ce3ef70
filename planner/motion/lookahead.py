"""Speeds at the joints between moves (paper section 3.2), and the look-ahead passes.

Units as in Klipper's toolhead: ``_v`` mm/s, ``_a`` mm/s^2, ``_j`` mm/s^3, lengths mm.
Rotary axes: per-axis limits in deg/s, deg/s^2, deg/s^3, tangent components in deg/mm.

Two modes (``planner.mode``):

* ``"paper"`` - Table 3 of the paper, literally. Reading (documented in METHOD.md section 4):
  chords d10 = P1 - P0 of the current move and d21 = P2 - P1 to the end of the next move,
  both projected on the current arc's plane (first, second axes); beta' = acos of their
  normalised dot product, beta = 180 - beta' (degrees); Norm1 when the turn d10 x d21 has
  the sense of the current arc (left for G03, right for G02; a zero cross product counts as
  Norm1). Same direction (G02->G02, G03->G03): Norm1 beta<90: Vmax, beta>=90: Vmax/2;
  Norm-1 beta<90: 0, beta>=90: Vmax/2. Opposite direction: beta<90: 0, beta>=90: Vmax.
  Any joint to or from G00/G01, or with a zero chord (full circles), or between arcs in
  different planes: 0. Cruise at min(F, Vmax) (rapids: the rapid speed); tangential A and J
  are the path limits; no per-axis or centripetal limit (the limit report shows the result).

* ``"lookahead"`` (default) - caps from the real geometry:
  - cruise speed of a move: min(F, Vmax) (rapids: rapid speed), every axis' velocity limit
    through its tangent component (rotary included); on arcs the centripetal acceleration
    kappa v^2 <= cos(30 deg) A_plane and the centripetal jerk kappa |omega| v^3
    (= v^3 / R^2 on a circle) <= J_plane / 2.
  - tangential acceleration and jerk of a move: the path limits, every axis' limit through
    its tangent component, and on arcs what the in-plane budget leaves. The acceleration
    split follows LinuxCNC's trajectory planner (normal <= cos 30 = 0.866, tangential gets
    at least sin 30 = 0.5 of the budget): the in-plane acceleration vector
    sqrt((rho a_t)^2 + (kappa v^2)^2) stays <= A_plane, so each in-plane axis does. The
    in-plane jerk vector is rho (j_t - kappa |omega| v^3 / rho) e_theta - 3 kappa v a_t e_r:
    the cross term 3 kappa v a_t gets <= 0.6 J_plane (a_t is lowered if needed), the
    centripetal jerk <= 0.5 J_plane, and j_t gets the rest (>= 0.3 J_plane), so
    |jerk vector| <= J_plane. A_plane, J_plane: the smaller limit of the two plane axes.
    Spirals take the curvature and turn rate of their small end, and the jerk of their
    changing curvature, v^3 |dkappa/ds|, shares the cross term's part (at most half of it).
    Corner blends (``planner.geometry.blend``, clothoid pairs in the plane of their two lines, every
    axis of that plane counted) take kappa and dkappa/ds of the pair and other shares: the
    changing curvature up to 0.8 J_plane and the cross term the rest of 0.9 J_plane, the
    centripetal jerk up to 0.3 J_plane, j_t the rest of sqrt(1 - 0.9^2) J_plane.
  - tangent break at a joint: the velocity change v |t2 - t1| happens within one sample Ts;
    for every axis k: v |dt_k| / Ts + kappa v^2 + 2 Ts J_k <= A_k (the arcs' centripetal
    acceleration and the jerk-limited tangential acceleration one sample either side share
    the budget) - solved exactly as a quadratic in v. Joints closer together than two
    samples' travel (2 v Ts) fall in the same or neighbouring samples, where their velocity
    changes add up: each run of up to GROUP_JOINTS + 1 joints either keeps that distance or
    holds the rule for the sum of its direction changes.
  - curvature jump at a joint: the normal acceleration v^2 |d(kappa n)_k| changes within one
    sample: v^2 |d(kappa n)_k| <= J_k Ts for every axis.
  - full stop at stopping events (M00 M01 M02 M30 G04 M06 M03/M04/M05/S), under G61, at the
    end of the program.

Both modes then run a backward and a forward pass with the exact reachable speed of the
jerk-limited profile (``profile.reachable_speed_scalar``), so every move goes from its
start speed to its end speed within its length. Planning runs in windows of moves: the
backward pass from an assumed stop at the window's end is final up to the last joint whose
cap holds whatever the rest of the program allows, the forward pass is causal, so the
windowed plan equals the whole-program plan (tested). "Final" needs care: the reachable
speed is not monotone in the start speed (a faster start leaves less time to accelerate),
so a joint is final only where its cap is below the least speed reachable over the next
move from any start speed; stops always are.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, replace

import numpy as np

from planner.core.errors import PlannerError
from planner.core.limits import (
    ACCEL_NORMAL_SHARE,
    BLEND_CROSS_SHARE,
    BLEND_DK_SHARE,
    BLEND_NORMAL_SHARE,
    JERK_CROSS_SHARE,
    JERK_NORMAL_SHARE,
    LimitSet,
    break_budget,
    joint_step_budget,
    kink_caps,
)
from planner.core.program import Dwell, EventKind, Program
from planner.geometry.movetable import MoveTable, take_rows
from planner.motion.profile import reachable_speed_lower_bound, reachable_speed_scalar

try:  # the passes in C (planner/_passes.c), built by `pip install -e .`; the Python ones else
    import planner._passes as _passes
    COMPILED = True  # tests compare both ways
except ImportError:  # pragma: no cover - a machine without a compiler
    COMPILED = False

__all__ = [
    "ACCEL_NORMAL_SHARE",
    "JERK_CROSS_SHARE",
    "JERK_NORMAL_SHARE",
    "LimitSet",
    "MoveLimits",
    "PlannedBlock",
    "backward_pass",
    "forward_pass",
    "joint_caps",
    "move_limits",
    "plan_blocks",
    "plan_whole",
    "StopsAndDwells",
    "stops_and_dwells",
]

MODES = ("lookahead", "paper")


@dataclass(frozen=True, slots=True)
class MoveLimits:
    """Per-move cruise speed cap and tangential limits (arrays of shape (n,))."""

    vc: np.ndarray  # cruise speed cap
    a_t: np.ndarray  # tangential acceleration limit of the profile
    j_t: np.ndarray  # tangential jerk limit of the profile
    v_prog: np.ndarray  # programmed speed limit min(F, Vmax) (rapids: rapid speed)


def _safe_div(num, den):
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(den > 0.0, num / np.where(den > 0.0, den, 1.0), np.inf)


def move_limits(table: MoveTable, lim: LimitSet, mode: str) -> MoveLimits:
    rapid = table.is_rapid
    # moves of rotary axes alone run F along the rotary distance (deg/s) within their own
    # path limits, rapids up to each axis's limit (LinuxCNC 2.9's rule)
    v_path, a_path, j_path, rapid_v = lim.path(lim.rotary_only(table.start, table.end))
    v_prog = np.where(rapid, rapid_v, np.minimum(table.feed, v_path))
    if mode == "paper":
        cap = np.isfinite(v_prog)       # the paper's ramps need a finite cap: the slowest axis's
        if not cap.all():
            v_prog = np.where(cap, v_prog, np.min(lim.v_axis))
        return MoveLimits(v_prog.copy(), np.where(np.isfinite(a_path), a_path, np.min(lim.a_axis)),
                          np.where(np.isfinite(j_path), j_path, np.min(lim.j_axis)), v_prog)
    if mode != "lookahead":
        raise PlannerError(f"planner mode must be one of {MODES}, got {mode!r}")
    arc = table.is_arc
    # Axes whose tangent component is constant along the move (all for lines; on arcs all but
    # the plane's two): a_k = t_k a_t, j_k = t_k j_t, v_k = t_k v.
    with np.errstate(divide="ignore", invalid="ignore"):
        tc = np.abs(table.end - table.start) / table.length[:, None]
    k = np.nonzero(arc)[0]
    sp = np.nonzero(table.spiral)[0]
    if sp.size:  # spirals: those axes move linearly in the angle, |dq/du| peaks where ds/dt is least
        dr = table.r1[sp] - table.r0[sp]
        r_min = np.minimum(table.r0[sp], table.r1[sp])
        speed_min = np.sqrt(dr * dr + (r_min * table.sweep[sp]) ** 2 + table.rise[sp] ** 2)
        tc[sp] = np.abs(table.end[sp] - table.start[sp]) / speed_min[:, None]
    tc[k, table.first[k]] = 0.0
    tc[k, table.second[k]] = 0.0
    # an arc in a turned frame (G18/G19 in a rotated system): the machine's X and Y each carry
    # part of the plane's turned axis and part of the normal, so X, Y and Z are all counted as
    # the plane's, with the whole tangent in it (rho 1, as a blend's): |a component| <= |the vector|
    kt = k[table.turn[k] != 0.0]
    tc[kt, table.turn_x[kt]] = 0.0
    tc[kt, table.turn_y[kt]] = 0.0
    bl = np.nonzero(table.is_blend)[0]
    # a blend turns in the plane of its two lines: every axis of that plane changes speed
    bl_plane = (np.abs(table.bl_u1[bl]) + np.abs(table.bl_n1[bl])) > 1e-12
    tc[bl] = 0.0
    vc = np.minimum(v_prog, np.min(_safe_div(lim.v_axis[None, :], tc), axis=1))
    a_t = np.minimum(a_path, np.min(_safe_div(lim.a_axis[None, :], tc), axis=1))
    j_t = np.minimum(j_path, np.min(_safe_div(lim.j_axis[None, :], tc), axis=1))
    if bl.size:
        vc[bl] = np.minimum(vc[bl], np.where(bl_plane, lim.v_axis[None, :], np.inf).min(axis=1))
    if k.size or bl.size:
        rho, kappa, omega = table.arc_terms()
        rho[kt] = 1.0
        f, s = table.first[k], table.second[k]
        # the turned frame's X and Y (f and s elsewhere: no change there)
        turned = table.turn[k] != 0.0
        tx, ty = np.where(turned, table.turn_x[k], f), np.where(turned, table.turn_y[k], s)

        def plane_min(limit: np.ndarray) -> np.ndarray:
            arcs = np.minimum(np.minimum(limit[f], limit[s]), np.minimum(limit[tx], limit[ty]))
            return np.concatenate([arcs, np.where(bl_plane, limit[None, :], np.inf).min(axis=1)])

        v_pl, a_pl, j_pl = plane_min(lim.v_axis), plane_min(lim.a_axis), plane_min(lim.j_axis)
        # shares of the in-plane jerk (see the module docstring): arcs keep most of the cross
        # budget for the tangential acceleration they need along their length; a blend is short
        # and crossed at about one speed, so its changing curvature takes most of it
        is_bl = np.concatenate([np.zeros(k.size, dtype=bool), np.ones(bl.size, dtype=bool)])
        cross_share = np.where(is_bl, BLEND_CROSS_SHARE, JERK_CROSS_SHARE)
        dk_share = np.where(is_bl, BLEND_DK_SHARE, 0.5 * JERK_CROSS_SHARE)
        normal_share = np.where(is_bl, BLEND_NORMAL_SHARE, JERK_NORMAL_SHARE)
        k = np.concatenate([k, bl])
        rho, kappa, omega = rho[k], kappa[k], omega[k]
        v = np.minimum(vc[k], _safe_div(v_pl, rho))
        v = np.minimum(v, np.sqrt(ACCEL_NORMAL_SHARE * a_pl / kappa))
        v = np.minimum(v, np.cbrt(normal_share * j_pl / (kappa * omega)))
        # spirals and blends: the changing curvature adds v^3 dkappa/ds along the normal, where
        # the cross term is
        dk = table.curvature_rate()[k]
        v = np.minimum(v, _safe_div(1.0, np.cbrt(_safe_div(dk, dk_share * j_pl))))
        j_dk = dk * v**3
        a_n = kappa * v * v
        at = np.minimum(a_t[k], _safe_div(np.sqrt(np.maximum(a_pl * a_pl - a_n * a_n, 0.0)), rho))
        at = np.minimum(at, _safe_div(cross_share * j_pl - j_dk, 3.0 * kappa * v))
        j_n = kappa * omega * v**3
        cross = 3.0 * kappa * v * at + j_dk
        jt = np.minimum(j_t[k], _safe_div(np.sqrt(np.maximum(j_pl * j_pl - cross * cross, 0.0)) - j_n, rho))
        vc[k], a_t[k], j_t[k] = v, at, jt
    if np.any(~(vc > 0)) or np.any(~(a_t > 0)) or np.any(~(j_t > 0)):
        i = int(np.argmax(~((vc > 0) & (a_t > 0) & (j_t > 0))))
        raise PlannerError(f"line {int(table.line[i])}: no positive speed/acceleration/jerk limit "
                           f"(v {vc[i]:.4g}, a {a_t[i]:.4g}, j {j_t[i]:.4g})")
    return MoveLimits(vc, a_t, j_t, v_prog)


def _paper_joint_caps(table: MoveTable, vc: np.ndarray, lim: LimitSet) -> np.ndarray:
    """Table 3 at the n-1 joints between consecutive moves of ``table``."""
    n = len(table)
    if n < 2:
        return np.zeros(0)
    cur = np.arange(n - 1)
    nxt = cur + 1
    both_arcs = table.is_arc[cur] & table.is_arc[nxt]
    f, s = table.first[cur], table.second[cur]
    p0, p1, p2 = table.start[cur], table.end[cur], table.end[nxt]
    d10 = np.stack([p1[cur, f] - p0[cur, f], p1[cur, s] - p0[cur, s]], axis=1)
    d21 = np.stack([p2[cur, f] - p1[cur, f], p2[cur, s] - p1[cur, s]], axis=1)
    n10 = np.hypot(d10[:, 0], d10[:, 1])
    n21 = np.hypot(d21[:, 0], d21[:, 1])
    ok = both_arcs & (n10 > 1e-9) & (n21 > 1e-9)
    ok &= (table.first[nxt] == f) & (table.second[nxt] == s)
    # Table 3 reads the arcs' chords in a machine plane: arcs in a turned frame stop at their joints
    ok &= (table.turn[cur] == 0.0) & (table.turn[nxt] == 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        cosb = np.clip((d10 * d21).sum(axis=1) / (n10 * n21), -1.0, 1.0)
    beta = 180.0 - np.degrees(np.arccos(cosb))
    cross = d10[:, 0] * d21[:, 1] - d10[:, 1] * d21[:, 0]
    ccw = table.sweep[cur] > 0.0
    norm1 = np.where(ccw, cross >= 0.0, cross <= 0.0)
    same_dir = (table.sweep[cur] > 0.0) == (table.sweep[nxt] > 0.0)
    acute = beta < 90.0
    vmax = lim.v_path
    same = np.where(norm1, np.where(acute, vmax, vmax / 2), np.where(acute, 0.0, vmax / 2))
    opposite = np.where(acute, 0.0, vmax)
    cap = np.where(same_dir, same, opposite)
    cap = np.where(ok, cap, 0.0)
    return np.minimum(cap, np.minimum(vc[cur], vc[nxt]))


#: joints closer together than two samples' travel share the tangent-break budget: up to this
#: many following joints are added to each joint's group
GROUP_JOINTS = 6


def _grouped_breaks(cap: np.ndarray, dt: np.ndarray, length: np.ndarray, kappa: np.ndarray,
                    c: np.ndarray, ts: float, step: np.ndarray) -> np.ndarray:
    """Breaks at joints less than 2 v Ts apart land in the same or neighbouring samples, where
    their velocity changes add up (a quarter-micrometre move between two corners is one corner
    of twice the turn at any useful speed). For each run of joints j..j+k (k <= GROUP_JOINTS)
    with D the path between the first and the last: either v <= D / (2 Ts) (the breaks are two
    samples apart or more, each joint's own cap holds) or v obeys the tangent-break rule and
    the jerk rule (the smallest one-sample step of the run's joints, ``step``) for the sum of
    their per-axis direction changes. Every joint of the run gets the larger of the two as a
    cap."""
    m = dt.shape[0]
    if m < 2:
        return cap
    cap = cap.copy()
    inner = length[1:m]                      # the move between joint j and joint j + 1
    total = dt.copy()
    budget = step.copy()
    dist = np.zeros(m)
    kap = np.maximum(kappa[:m], kappa[1:m + 1])
    for k in range(1, min(GROUP_JOINTS, m - 1) + 1):
        rows = m - k
        total = total[:rows] + dt[k:k + rows]
        budget = np.minimum(budget[:rows], step[k:k + rows])
        dist = dist[:rows] + inner[k - 1:k - 1 + rows]
        kap = np.maximum(kap[:rows], kappa[k + 1:k + 1 + rows])
        b = total / ts
        kk = kap[:, None]
        with np.errstate(divide="ignore", invalid="ignore"):
            v_g = np.where(b > 0.0, 2.0 * c / (b + np.sqrt(b * b + 4.0 * kk * c)), np.inf).min(axis=1)
        v_g = np.minimum(v_g, kink_caps(total, budget))
        group_cap = np.maximum(dist / (2.0 * ts), v_g)
        if np.all(group_cap >= cap.max()):
            continue
        for i in range(k + 1):              # every joint of the run
            np.minimum(cap[i:i + rows], group_cap, out=cap[i:i + rows])
    return cap


def joint_caps(table: MoveTable, ml: MoveLimits, lim: LimitSet, mode: str) -> np.ndarray:
    """Speed caps at the n-1 joints between consecutive moves of ``table`` (no stops)."""
    n = len(table)
    if n < 2:
        return np.zeros(0)
    if mode == "paper":
        return _paper_joint_caps(table, ml.vc, lim)
    cur = slice(0, n - 1)
    nxt = slice(1, n)
    cap = np.minimum(ml.vc[cur], ml.vc[nxt])
    t_start, t_end, dt = tangent_changes(table)
    c_start, c_end = table.end_curvature_vectors()
    _, kappa, _ = table.arc_terms()
    ts = lim.ts_s
    # Tangent break: kappa v^2 + (|dt_k| / Ts) v <= A_k - 2 Ts J_k, per axis (acceleration),
    # and v |dt_k| within the joint's one-sample step (jerk: ``joint_step_budget``).
    b = dt / ts
    c = break_budget(lim)[None, :]
    kap = np.maximum(kappa[cur], kappa[nxt])[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        v_break = np.where(b > 0.0, 2.0 * c / (b + np.sqrt(b * b + 4.0 * kap * c)), np.inf)
    cap = np.minimum(cap, v_break.min(axis=1))
    step = joint_step_budget(lim, ml.j_t[cur], ml.j_t[nxt], t_end[cur], t_start[nxt])
    cap = np.minimum(cap, kink_caps(dt, step))
    cap = _grouped_breaks(cap, dt, table.length, kappa, c, ts, step)
    # Curvature jump: v^2 |d(kappa n)_k| in one sample. With a configured corner step, within
    # J_k Ts on its own; without, the direction change and the curvature jump land in the same
    # stencils: together within what the moves' own jerk leaves of J_k,
    # v |dt_k| / Ts^2 + v^2 |d(kappa n)_k| / Ts <= room_k (= step_k / Ts^2).
    dk = np.abs(c_start[nxt] - c_end[cur])
    dk = np.where(dk > 1e-12, dk, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        if lim.corner_step_mm_s:
            v_curv = np.where(dk > 0.0, np.sqrt(lim.j_axis[None, :] * ts / dk), np.inf)
        else:
            qa, qb, room = dk / ts, dt / (ts * ts), step / (ts * ts)
            v_curv = np.where(qa + qb > 0.0, 2.0 * room / (qb + np.sqrt(qb * qb + 4.0 * qa * room)), np.inf)
    return np.minimum(cap, v_curv.min(axis=1))


def tangent_changes(table: MoveTable) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(unit tangents at each move's start, at its end, and |change| per axis at each of the
    n - 1 joints, rounding below 1e-12 taken as none)."""
    t_start, t_end = table.end_tangents()
    dt = np.abs(t_start[1:] - t_end[:-1])
    return t_start, t_end, np.where(dt > 1e-12, dt, 0.0)


def corner_steps(table: MoveTable, v_joint: np.ndarray, j_t: np.ndarray, lim: LimitSet) -> np.ndarray:
    """Per joint of ``table`` (n - 1), crossed at ``v_joint`` by moves of path jerk ``j_t``: the
    largest one-sample velocity step of an axis beyond what its jerk limit allows there (mm/s;
    0 where within: without a configured corner velocity step, every joint)."""
    if len(table) < 2:
        return np.zeros(0)
    t_start, t_end, dt = tangent_changes(table)
    room = joint_step_budget(replace(lim, corner_step_mm_s=0.0), j_t[:-1], j_t[1:], t_end[:-1], t_start[1:])
    step = v_joint[:, None] * dt
    over = step > room * (1.0 + 1e-9)          # the cap itself, rounded, is no step
    return np.where(over, step - room, 0.0).max(axis=1)


@dataclass(frozen=True)
class StopsAndDwells:
    """Where a program's path stands: the moves after which it stops (stopping events and the
    last move) and the dwells after moves, kept as the few rows they are (arrays over every
    move of 10,000,000 took 90 MB and, made at each cycle start, 0.2 s), and the dwell
    before the first move."""

    stop_rows: np.ndarray     # sorted move indices
    dwell_rows: np.ndarray    # sorted move indices, each once
    dwell_s: np.ndarray       # the dwell after each of them
    before_s: float

    def stops(self, a: int, b: int) -> np.ndarray:
        """Per move a .. b - 1: whether the path stops after it."""
        out = np.zeros(b - a, dtype=bool)
        rows = self.stop_rows[np.searchsorted(self.stop_rows, a):np.searchsorted(self.stop_rows, b)]
        out[rows - a] = True
        return out

    def dwells(self, a: int, b: int) -> np.ndarray:
        """Per move a .. b - 1: the dwell after it (s)."""
        out = np.zeros(b - a)
        lo, hi = np.searchsorted(self.dwell_rows, a), np.searchsorted(self.dwell_rows, b)
        out[self.dwell_rows[lo:hi] - a] = self.dwell_s[lo:hi]
        return out


def stops_and_dwells(program: Program) -> StopsAndDwells:
    """The stops and dwells of ``program`` (``StopsAndDwells``)."""
    n = len(program.moves)
    stops: set[int] = set()
    dwell: dict[int, float] = {}
    before = 0.0
    for ev in program.events:
        i = ev.after_move
        if ev.kind == EventKind.DWELL:
            seconds = max(ev.payload_as(Dwell).seconds, 0.0)
            if i < 0:
                before += seconds
            elif i < n:
                dwell[i] = dwell.get(i, 0.0) + seconds
        if ev.stops and 0 <= i < n:
            stops.add(i)
    if n:
        stops.add(n - 1)
    rows = sorted(dwell)
    return StopsAndDwells(np.array(sorted(stops), dtype=np.int64), np.array(rows, dtype=np.int64),
                          np.array([dwell[r] for r in rows], dtype=float), before)


# -- passes ---------------------------------------------------------------------------------
def backward_pass(v: list[float], cap: list[float], length, a_t, j_t, r0, lo: int = 0) -> None:
    """v[j] = min(cap[j], reach(v[j+1], L_j)) for j = len-2 .. lo+1 (v[lo] is fixed, in place).

    ``r0[j]`` is a lower bound of reach(v, L_j) for every v (``reachable_speed_lower_bound``;
    reach is not monotone in v): where cap[j] <= r0[j] the cap holds without solving.
    """
    for j in range(len(v) - 2, lo, -1):
        cj = cap[j]
        nxt = v[j + 1]
        if cj <= nxt or cj <= r0[j]:
            v[j] = cj
        else:
            r = reachable_speed_scalar(nxt, length[j], a_t[j], j_t[j])
            v[j] = cj if cj <= r else r


def forward_pass(v: list[float], length, a_t, j_t, r0, lo: int = 0, hi: int | None = None) -> None:
    """v[j+1] = min(v[j+1], reach(v[j], L_j)) for j = lo .. hi-1 (in place)."""
    hi = len(v) - 1 if hi is None else hi
    for j in range(lo, hi):
        nxt = v[j + 1]
        if nxt <= v[j] or nxt <= r0[j]:
            continue
        r = reachable_speed_scalar(v[j], length[j], a_t[j], j_t[j])
        if r < nxt:
            v[j + 1] = r


def _passes_on(caps: np.ndarray, v_start: float, length: np.ndarray, a_t: np.ndarray, j_t: np.ndarray,
               r0: np.ndarray, k: int) -> np.ndarray:
    """The joint speeds 0 .. k of a window: the backward pass over all of it from its caps,
    then the forward pass from ``v_start`` up to joint k (compiled where built)."""
    if COMPILED:
        v = np.array(caps, dtype=float)
        v[0] = v_start
        f64 = np.ascontiguousarray
        length, a_t, j_t, r0 = f64(length, float), f64(a_t, float), f64(j_t, float), f64(r0, float)
        _passes.backward_pass(v, f64(caps, float), length, a_t, j_t, r0, 0)
        _passes.forward_pass(v, length, a_t, j_t, r0, 0, k)
        return v[: k + 1]
    vl = caps.tolist()
    vl[0] = v_start
    ll, al, jl, rl = length.tolist(), a_t.tolist(), j_t.tolist(), r0.tolist()
    backward_pass(vl, caps.tolist(), ll, al, jl, rl)
    forward_pass(vl, ll, al, jl, rl, 0, k)
    return np.asarray(vl[: k + 1])


@dataclass(frozen=True, slots=True, eq=False)
class PlannedBlock:
    """Consecutive moves with final speeds: ``table`` rows are moves first..first+n-1."""

    first: int
    table: MoveTable
    limits: MoveLimits
    vs: np.ndarray
    ve: np.ndarray
    dwell_after: np.ndarray


def _window(program: Program, lim: LimitSet, mode: str, a: int, b: int, stop: np.ndarray):
    """The moves a .. b - 1 with their limits, joint caps and reach bounds; ``stop``: whether
    the path stops after each of them."""
    caps = np.empty(b - a + 1)
    if mode == "paper" or b - a < 2:
        table = MoveTable.from_store(program.moves[a:b], len(program.axes))
        ml = move_limits(table, lim, mode)
        caps[1:-1] = joint_caps(table, ml, lim, mode)
    else:
        # the joints' groups reach GROUP_JOINTS moves either side: compute them with that
        # context, so that a window's caps are the whole program's
        lo, hi = max(0, a - GROUP_JOINTS), min(len(program.moves), b + GROUP_JOINTS)
        wide = MoveTable.from_store(program.moves[lo:hi], len(program.axes))
        wide_ml = move_limits(wide, lim, mode)
        caps[1:-1] = joint_caps(wide, wide_ml, lim, mode)[a - lo:a - lo + b - a - 1]
        rows = slice(a - lo, b - lo)
        table = wide if (lo, hi) == (a, b) else take_rows(wide, rows)
        ml = MoveLimits(wide_ml.vc[rows], wide_ml.a_t[rows], wide_ml.j_t[rows], wide_ml.v_prog[rows])
    caps[1:] = np.where(stop | table.exact_stop, 0.0, caps[1:])
    caps[-1] = 0.0  # assumed stop at the window's end (exact at the program's end)
    r0 = reachable_speed_lower_bound(table.length, ml.a_t, ml.j_t)
    return table, ml, caps, r0


def plan_blocks(program: Program, lim: LimitSet, mode: str = "lookahead",
                window: int = 256, first_window: int | None = None) -> Iterator[PlannedBlock]:
    """Plan ``program`` window by window; yields blocks whose speeds are final.

    ``first_window`` (default ``window``) may be smaller for a quick first block (streaming).
    """
    n = len(program.moves)
    sd = stops_and_dwells(program)
    a = 0
    v_a = 0.0
    w = max(int(first_window or window), 2)
    while a < n:
        b = min(n, a + w)
        table, ml, caps, r0 = _window(program, lim, mode, a, b, sd.stops(a, b))
        if b == n:
            k = b - a
        else:
            # Final: a joint whose cap holds whatever comes after it (cap <= the least speed
            # reachable over the move after it, from any speed).
            final = np.flatnonzero(caps[1:b - a] <= r0[1:b - a])
            k = int(final[-1]) + 1 if final.size else 0
            if k == 0:  # nothing final yet: look further ahead
                w *= 2
                continue
        va = _passes_on(caps, v_a, table.length, ml.a_t, ml.j_t, r0, k)
        sl = slice(0, k)
        sub = table if k == len(table) else take_rows(table, sl)
        yield PlannedBlock(a, sub, MoveLimits(ml.vc[sl], ml.a_t[sl], ml.j_t[sl], ml.v_prog[sl]),
                           va[:-1].copy(), va[1:].copy(), sd.dwells(a, a + k))
        a += k
        v_a = float(va[k])
        # the window that found a final joint is kept for the next one (a raster of tiny moves
        # has one every row: starting again small would plan each row's window three times)
        w = max(int(window), 2, w)


def plan_whole(program: Program, lim: LimitSet, mode: str = "lookahead") -> tuple[np.ndarray, MoveLimits]:
    """Reference: both passes over the whole program at once. Returns (v at n+1 joints, limits)."""
    n = len(program.moves)
    table, ml, caps, r0 = _window(program, lim, mode, 0, n, stops_and_dwells(program).stops(0, n))
    v = caps.tolist()
    v[0] = 0.0
    length, at, jt, r0l = table.length.tolist(), ml.a_t.tolist(), ml.j_t.tolist(), r0.tolist()
    backward_pass(v, caps.tolist(), length, at, jt, r0l)
    forward_pass(v, length, at, jt, r0l)
    return np.asarray(v), ml

