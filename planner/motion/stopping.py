r"""Time-optimal jerk-limited stop along the path from the current state (s, v, a).

A feed hold by time scaling (``app.machine.timescale``) brakes with worst-case bounds and
stops in about twice the distance of the best stop. Here the path speed itself is braked:

**1-D profile** (``stop_profile``). From v0 >= 0 and |a0| <= A, the time-optimal way to rest
(v = 0 and a = 0 together) with |a| <= A, |j| <= J is bang-bang in jerk: -J until the
acceleration reaches a_p, a_p held, then +J back to zero (the velocity-control case of
Kroeger's on-line trajectory generation, as in Ruckig). Without the hold phase the three
velocity changes sum to zero when

    a_p = -sqrt(J v0 + a0^2 / 2)                                  (1)

and if |a_p| > A, a_p = -A with the hold time t2 = (v0 + a0^2 / (2 J) - A^2 / J) / A.
It exists without a velocity reversal iff v0 >= a0^2 / (2 J) when a0 < 0 (else ramping
the acceleration back to zero already overshoots rest): ``None`` then.

**Limits along the path** (``plan_path_stop``). Position q(s(t)) on the planned geometry:

    q'   = q_s v
    q''  = q_s a + q_ss v^2
    q''' = q_s j + 3 q_ss v a + q_sss v^3

With g1, g2, g3 the maxima of |q_s|, |q_ss|, |q_sss| per axis over the stopping window
(finite differences of the exact geometry) and v <= v0, the stop keeps every axis limit if

    g1 v0 <= V_i,   A_t <= (A_i - g2 v0^2) / g1,   J_t <= (J_i - 3 g2 v0 A_t - g3 v0^3) / g1

besides the path's own A and J; the window is enlarged until it covers the stopping
distance. The stop is refused (``None``: the caller keeps its time-scaling ramp) when the
window holds a tangent break (corner) or a planned full stop before the stop ends, when the
plan itself is slower than the stop anywhere on the way (the plan's speed there is a limit),
or when a0 is out of reach. The caller checks the samples numerically as well.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from planner.core.machine import MachineSpec
from planner.motion.plan import Plan
from planner.motion.window import PlanWindow

__all__ = ["PathStop", "StopProfile", "plan_path_stop", "stop_profile"]

SAFETY = 0.98  # share of each limit the stop may use (finite-difference bounds, sampling)


@dataclass(frozen=True, slots=True)
class StopProfile:
    """Piecewise-cubic path motion to rest: phase k lasts ``t[k+1] - t[k]`` with jerk ``j[k]``."""

    t: np.ndarray  # (4,) phase boundaries, t[0] = 0, t[3] = duration
    j: np.ndarray  # (3,) jerk per phase
    s: np.ndarray  # (4,) distance at the boundaries
    v: np.ndarray  # (4,) speed at the boundaries
    a: np.ndarray  # (4,) acceleration at the boundaries

    @property
    def duration_s(self) -> float:
        return float(self.t[3])

    @property
    def distance(self) -> float:
        return float(self.s[3])

    def evaluate(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(s, v, a) at times t (clamped to [0, duration]); exactly at rest from the end on."""
        t = np.clip(np.asarray(t, dtype=float), 0.0, self.t[3])
        k = np.clip(np.searchsorted(self.t, t, side="right") - 1, 0, 2)
        dt = t - self.t[k]
        j = self.j[k]
        a0, v0, s0 = self.a[k], self.v[k], self.s[k]
        s = s0 + dt * (v0 + dt * (0.5 * a0 + dt * j / 6.0))
        v = v0 + dt * (a0 + 0.5 * j * dt)
        a = a0 + j * dt
        end = t >= self.t[3]
        return np.where(end, self.s[3], s), np.where(end, 0.0, v), np.where(end, 0.0, a)


def stop_profile(v0: float, a0: float, a_max: float, j_max: float) -> StopProfile | None:
    """Time-optimal stop from speed v0 >= 0 and acceleration a0 to rest, Eq. (1).
    None when |a0| > a_max or rest is out of reach without reversing."""
    if not (v0 >= 0.0 and a_max > 0.0 and j_max > 0.0) or abs(a0) > a_max * (1.0 + 1e-12):
        return None
    a0 = min(max(a0, -a_max), a_max)
    big_j = j_max
    if a0 < 0.0 and v0 < a0 * a0 / (2.0 * big_j):
        return None
    a_p = -math.sqrt(big_j * v0 + 0.5 * a0 * a0)
    t2 = 0.0
    if a_p < -a_max:
        a_p = -a_max
        t2 = max((v0 + a0 * a0 / (2.0 * big_j) - a_max * a_max / big_j) / a_max, 0.0)
    t1 = max((a0 - a_p) / big_j, 0.0)
    t3 = -a_p / big_j
    t = np.array([0.0, t1, t1 + t2, t1 + t2 + t3])
    j = np.array([-big_j, 0.0, big_j])
    s = np.zeros(4)
    v = np.zeros(4)
    a = np.zeros(4)
    s[0], v[0], a[0] = 0.0, v0, a0
    for k in range(3):
        d = t[k + 1] - t[k]
        s[k + 1] = s[k] + d * (v[k] + d * (0.5 * a[k] + d * j[k] / 6.0))
        v[k + 1] = v[k] + d * (a[k] + 0.5 * j[k] * d)
        a[k + 1] = a[k] + j[k] * d
    v[3] = 0.0  # exact rest (rounding)
    a[3] = 0.0
    return StopProfile(t, j, s, v, a)


@dataclass(frozen=True, slots=True, eq=False)
class PathStop:
    """Set-points of a stop along a plan: positions, planned times (tau), cumulative path
    length, move index and line per sample (every ``ts``; the last one at rest)."""

    q: np.ndarray
    tau: np.ndarray
    s_mm: np.ndarray
    move: np.ndarray
    line: np.ndarray
    speed: np.ndarray
    profile: StopProfile


def _geometry_bounds(plan: Plan | PlanWindow, s_from: float, s_to: float) -> tuple[np.ndarray, bool]:
    """Per-axis maxima of |dq/ds|, |d2q/ds2|, |d3q/ds3| over [s_from, s_to] (rows g1, g2, g3)
    and whether a tangent break (corner) lies inside."""
    seg = plan.segment
    tab = seg.table
    n = len(tab)
    m0 = int(np.clip(np.searchsorted(seg.s0, s_from, side="right") - 1, 0, n - 1))
    m1 = int(np.clip(np.searchsorted(seg.s0, s_to, side="right") - 1, 0, n - 1))
    g = np.zeros((3, tab.n_axes))
    corner = False
    prev_tangent: np.ndarray | None = None
    for m in range(m0, m1 + 1):
        length = float(tab.length[m])
        if length <= 0.0:
            continue
        u_a = max(s_from - float(seg.s0[m]), 0.0)
        u_b = min(s_to - float(seg.s0[m]), length)
        h = min(0.05, length / 8.0)
        # uniform stencils over [u_a - h, u_b + h] within the move (curvature at both ends)
        lo, hi = max(u_a - h, 0.0), min(u_b + h, length)
        if hi - lo < 3.0 * h:
            lo = max(hi - 3.0 * h, 0.0)
            hi = min(lo + 3.0 * h, length)
        k = int(math.floor((hi - lo) / h + 1e-9)) + 1
        u = np.minimum(lo + h * np.arange(k), length)
        q = tab.positions(np.full(k, m), u)
        g[0] = np.maximum(g[0], np.abs(np.diff(q, axis=0)).max(axis=0) / h)
        if k >= 4:
            g[1] = np.maximum(g[1], np.abs(np.diff(q, 2, axis=0)).max(axis=0) / h**2)
            g[2] = np.maximum(g[2], np.abs(np.diff(q, 3, axis=0)).max(axis=0) / h**3)
        t_start = (tab.positions(np.array([m, m]), np.array([0.0, h]))[1]
                   - tab.positions(np.array([m]), np.array([0.0]))[0]) / h
        if prev_tangent is not None and np.linalg.norm(t_start - prev_tangent) > 1e-6:
            corner = True
        end2 = tab.positions(np.array([m, m]), np.array([length - h, length]))
        prev_tangent = (end2[1] - end2[0]) / h
    return g, corner


def plan_path_stop(plan: Plan | PlanWindow, machine: MachineSpec, tau0: float, sigma: float, sigma_dot: float,
                   tau_limit: float) -> PathStop | None:
    """The time-optimal jerk-limited stop along ``plan`` from planned time ``tau0`` run at
    time scale ``sigma`` (d tau / dt) changing at ``sigma_dot``, to be at rest before planned
    time ``tau_limit`` (the next planned full stop). Samples every ``plan.ts_s`` from one
    period after now. None when no such stop keeps every limit (see the module docstring)."""
    seg = plan.segment
    tab = seg.table
    if len(tab) == 0 or sigma < 0.0:
        return None
    ts = plan.ts_s
    row, s_loc, v_p, a_p = seg.state(np.array([tau0]), need_va=True)
    m0 = int(row[0])
    s_start = float(seg.s0[m0] + s_loc[0])
    v0 = float(v_p[0]) * sigma
    a0 = float(a_p[0]) * sigma * sigma + float(v_p[0]) * sigma_dot
    if v0 <= 0.0:
        return None
    lim = machine.limits
    v_ax = np.array([a.v_motion for a in machine.axes])
    a_ax = np.array([a.a_motion for a in machine.axes])
    j_ax = np.array([a.j_motion for a in machine.axes])
    a_t, j_t = lim.a_max_mm_s2 * SAFETY, lim.j_max_mm_s3 * SAFETY
    prof = stop_profile(v0, a0, a_t, j_t)
    window = (prof.distance if prof is not None else v0 * (v0 / a_t + 2 * a_t / j_t)) * 1.25 + 1e-6
    for _ in range(6):
        g, corner = _geometry_bounds(plan, s_start, s_start + window)
        if corner:
            return None
        g1 = np.maximum(g[0], 1e-12)
        if np.any(g[0] * v0 > v_ax * SAFETY):
            return None
        a_ax_t = (a_ax * SAFETY - g[1] * v0 * v0) / g1
        a_t = min(lim.a_max_mm_s2 * SAFETY, float(a_ax_t.min()))
        if a_t <= 0.0:
            return None
        j_ax_t = (j_ax * SAFETY - 3.0 * g[1] * v0 * a_t - g[2] * v0**3) / g1
        j_t = min(lim.j_max_mm_s3 * SAFETY, float(j_ax_t.min()))
        if j_t <= 0.0:
            return None
        prof = stop_profile(v0, a0, a_t, j_t)
        if prof is None:
            return None
        if prof.distance <= window:
            break
        window = prof.distance * 1.25
    else:
        return None
    assert prof is not None
    n = max(int(math.ceil(prof.duration_s / ts - 1e-9)), 1)
    t = ts * np.arange(1, n + 1)
    s_rel, v, _ = prof.evaluate(t)
    s = s_start + s_rel
    # planned times of the samples: s(tau) = s_k by bisection on [tau0, tau_limit]
    lo = np.full(n, tau0)
    hi = np.full(n, tau_limit)
    r_hi, s_hi = seg.state(np.array([tau_limit]))
    if float(seg.s0[int(r_hi[0])] + s_hi[0]) < s[-1]:
        return None  # the plan stops (pause point, end) before the stop would
    for _ in range(64):
        mid = 0.5 * (lo + hi)
        r, sl = seg.state(mid)
        below = seg.s0[r] + sl < s
        lo = np.where(below, mid, lo)
        hi = np.where(below, hi, mid)
    tau = hi
    r, _, v_plan, _ = seg.state(tau, need_va=True)
    if np.any(v > np.maximum(v_plan, 0.0) * max(sigma, 1.0) + 1e-9):
        return None  # the plan is slower somewhere on the way: its speed there is a limit
    move = np.clip(np.searchsorted(seg.s0, s, side="right") - 1, 0, len(tab) - 1)
    q = tab.positions(move, s - seg.s0[move])
    return PathStop(q, tau, s, tab.index[move].astype(np.int64), tab.line[move].astype(np.int64), v, prof)
