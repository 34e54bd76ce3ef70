"""Jerk-limited velocity profile of one move in path length s (paper Eq. 14, generalised).

A move of length L goes from start speed vs to end speed ve with zero path acceleration at
both ends, cruising at most at vc, under the acceleration limit A and the jerk limit J.
The profile is the time-optimal constant-jerk profile (jerk in {+J, 0, -J}) of that
problem, which Ruckig also finds:

    phase   1     2     3     4       5     6     7
    jerk   +J     0    -J     0      -J     0    +J
           |--- speed-up ---|cruise|--- slow-down ---|

Speed-up and slow-down are each an S-curve between two speeds dv apart:
  * 5-phase form of the paper (Eq. 14): J * dv <= A^2, triangular acceleration, duration
    2 sqrt(dv / J), peak acceleration sqrt(J dv);
  * 7-phase form: J * dv > A^2, a constant-acceleration phase of dv / A - A / J between the
    two jerk phases (duration dv / A + A / J).
An S-curve is point-symmetric about its middle, so it covers (v0 + v1) / 2 * duration.
If the move is too short to cruise at vc, the peak speed vp in [max(vs, ve), vc] is the
root of the monotone length function D(vp) = L (the paper's Fig. 5 variants): solved in
closed form where both S-curves have a constant-acceleration phase (a quadratic), and by
bracketed Newton iteration to machine precision otherwise (Ruckig solves the same
polynomials). Phase durations and the evaluation s(t), v(t), a(t), j(t) are closed form
and vectorised over many moves and many samples.

``reachable_speed(v0, L, A, J)`` is the exact highest speed reachable from v0 (accelerating,
or, read backwards, the highest speed from which v0 is reachable decelerating) within a
length L: the real root of a cubic (5-phase) or a quadratic (7-phase). The look-ahead
passes use it.

Units: s, v, a, j in mm, mm/s, mm/s^2, mm/s^3 (or degrees for rotary-only moves); t in s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from planner.core.errors import PlannerError

__all__ = [
    "Profiles",
    "build_profiles",
    "reachable_speed",
    "reachable_speed_lower_bound",
    "reachable_speed_scalar",
    "transition_length",
    "transition_time",
]

# Jerk of each of the 7 phases in units of J.
_PHASE_JERK = np.array([1.0, 0.0, -1.0, 0.0, -1.0, 0.0, 1.0])


def transition_time(dv, a_max, j_max):
    """Duration of an S-curve changing the speed by |dv| (zero acceleration at both ends)."""
    dv = np.abs(np.asarray(dv, dtype=float))
    a_max = np.asarray(a_max, dtype=float)
    j_max = np.asarray(j_max, dtype=float)
    limited = dv * j_max > a_max * a_max
    return np.where(limited, dv / a_max + a_max / j_max, 2.0 * np.sqrt(dv / j_max))


def transition_length(v0, v1, a_max, j_max):
    """Path length of the S-curve from v0 to v1: (v0 + v1) / 2 times its duration."""
    v0 = np.asarray(v0, dtype=float)
    v1 = np.asarray(v1, dtype=float)
    return 0.5 * (v0 + v1) * transition_time(v1 - v0, a_max, j_max)


def reachable_speed(v0, length, a_max, j_max):
    """Highest v1 >= v0 with transition_length(v0, v1) <= length (vectorised, exact).

    5-phase branch: with x = sqrt(dv / J), (2 v0 + J x^2) x = L, i.e. the depressed cubic
    x^3 + p x - q = 0, p = 2 v0 / J, q = L / J, whose single real root is
    x = 2 sqrt(p/3) sinh(asinh(3q / (2p) sqrt(3/p)) / 3) (x = cbrt(q) for p = 0).
    7-phase branch (dv > A^2 / J): (2 v0 + dv)(dv + A^2 / J) = 2 A L, a quadratic in dv.
    """
    v0 = np.asarray(v0, dtype=float)
    length = np.maximum(np.asarray(length, dtype=float), 0.0)
    a_max = np.asarray(a_max, dtype=float)
    j_max = np.asarray(j_max, dtype=float)
    p = 2.0 * v0 / j_max
    q = length / j_max
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        arg = 1.5 * q / p * np.sqrt(3.0 / p)
        x_h = 2.0 * np.sqrt(p / 3.0) * np.sinh(np.arcsinh(arg) / 3.0)
    x = np.where((p > 1e-300) & np.isfinite(x_h), x_h, np.cbrt(q))
    # One Newton step polishes the rounding of the hyperbolic form.
    dfdx = 3.0 * x * x + p
    x = np.where(dfdx > 0.0, x - (x * x * x + p * x - q) / np.where(dfdx > 0.0, dfdx, 1.0), x)
    dv = j_max * x * x
    # 7-phase branch: dv^2 + b dv + c = 0, b = 2 v0 + A^2/J, c = 2 A (v0 A / J - L); c <= 0 here.
    b = 2.0 * v0 + a_max * a_max / j_max
    c = 2.0 * a_max * (v0 * a_max / j_max - length)
    dv_a = -2.0 * c / (b + np.sqrt(np.maximum(b * b - 4.0 * c, 0.0)))
    dv = np.where(dv * j_max > a_max * a_max, dv_a, dv)
    return v0 + np.maximum(dv, 0.0)


def reachable_speed_scalar(v0: float, length: float, a_max: float, j_max: float) -> float:
    """Scalar twin of :func:`reachable_speed` (same formulas, for the sequential passes)."""
    if length <= 0.0:
        return v0
    p = 2.0 * v0 / j_max
    q = length / j_max
    x = -1.0
    if p > 1e-300:
        arg = 1.5 * q / p * math.sqrt(3.0 / p)
        if arg < 1e300:
            x = 2.0 * math.sqrt(p / 3.0) * math.sinh(math.asinh(arg) / 3.0)
    if x < 0.0:
        x = q ** (1.0 / 3.0)
    dfdx = 3.0 * x * x + p
    if dfdx > 0.0:
        x -= (x * x * x + p * x - q) / dfdx
    dv = j_max * x * x
    if dv * j_max > a_max * a_max:
        b = 2.0 * v0 + a_max * a_max / j_max
        c = 2.0 * a_max * (v0 * a_max / j_max - length)
        dv = -2.0 * c / (b + math.sqrt(max(b * b - 4.0 * c, 0.0)))
    return v0 + max(dv, 0.0)


def reachable_speed_lower_bound(length, a_max, j_max):
    """min over v0 >= 0 of reachable_speed(v0, length): a bound that holds whatever v0 is.

    reachable_speed is NOT monotone in v0 (a faster start leaves less time to accelerate:
    from rest a short move may reach more than from a small v0). With x = sqrt(dv / J) the
    5-phase reach is L / (2x) + J x^2 / 2 (x <= A / J), least at x^3 = L / (2J) or at the
    branch end x = A / J; the 7-phase reach (dv >= A^2 / J) is A L / (dv + A^2/J) + dv / 2,
    least at dv = sqrt(2 A L) - A^2 / J or at its branch end. The minimum of the two.
    """
    length = np.maximum(np.asarray(length, dtype=float), 0.0)
    a_max = np.asarray(a_max, dtype=float)
    j_max = np.asarray(j_max, dtype=float)
    c = a_max * a_max / j_max
    with np.errstate(divide="ignore", invalid="ignore"):
        x5 = np.minimum(np.cbrt(length / (2.0 * j_max)), a_max / j_max)
        r5 = np.where(x5 > 0.0, length / (2.0 * x5) + 0.5 * j_max * x5 * x5, 0.0)
        dv7 = np.maximum(np.sqrt(2.0 * a_max * length) - c, c)
        r7 = a_max * length / (dv7 + c) + 0.5 * dv7
    has7 = reachable_speed(0.0, length, a_max, j_max) > c
    r = np.where(has7, np.minimum(r5, r7), r5)
    return np.maximum(r, 0.0) * (1.0 - 1e-12)


def _two_sided_length(x, d1, d2, vlo, a_max, j_max):
    """Length of speed-up and slow-down with peak vp = vlo + x, and d/dx.

    The two speed changes are x + d1 and x + d2 with d1, d2 = vlo - vs, vlo - ve >= 0 (one is
    0): working in x keeps tiny speed changes exact (vp - vs would cancel).
    """
    total = np.zeros_like(x)
    deriv = np.zeros_like(x)
    vp = vlo + x
    for d in (d1, d2):
        dv = x + d
        limited = dv * j_max > a_max * a_max
        root = np.sqrt(dv / j_max)
        t = np.where(limited, dv / a_max + a_max / j_max, 2.0 * root)
        with np.errstate(divide="ignore", invalid="ignore"):
            dt = np.where(limited, 1.0 / a_max, 1.0 / (j_max * np.maximum(root, 1e-300)))
        total += 0.5 * (2.0 * vp - dv) * t
        deriv += 0.5 * t + 0.5 * (2.0 * vp - dv) * dt
    return total, deriv


def _solve_peak(length, vs, ve, vc, a_max, j_max):
    """Peak speed vp in [max(vs, ve), vc] with two-sided length == length (D(vc) > length).

    Returns (vp, dv_up, dv_down) with the speed changes computed without cancellation.
    """
    vlo = np.maximum(vs, ve)
    d1 = vlo - vs
    d2 = vlo - ve
    lo = np.zeros_like(vlo)
    hi = vc - vlo
    # Closed form when both S-curves have a constant-acceleration phase:
    # vp^2 / A + (A / J) vp - (vs^2 + ve^2) / (2A) + A (vs + ve) / (2J) - L = 0.
    qa = 1.0 / a_max
    qb = a_max / j_max
    qc = -(vs * vs + ve * ve) / (2.0 * a_max) + a_max * (vs + ve) / (2.0 * j_max) - length
    vq = (-qb + np.sqrt(np.maximum(qb * qb - 4.0 * qa * qc, 0.0))) / (2.0 * qa)
    both = (vq - vs) * j_max > a_max * a_max
    both &= (vq - ve) * j_max > a_max * a_max
    both &= vq <= vc
    # Elsewhere Newton's method on y = sqrt(x): the length is convex in y (a cubic in y where
    # the S-curves are triangular), so from y = sqrt(hi), where the length is too long, every
    # step lands between the root and the last y, and it converges in a handful of steps
    # (in x the length is concave near 0 and Newton's step leaves the bracket, which made
    # bisection take 50 steps). The bracket stays as a guard against rounding.
    x = np.where(both, vq - vlo, hi)
    y = np.sqrt(x)
    ylo = np.sqrt(lo)
    yhi = y.copy()
    todo = ~both
    for _ in range(200):
        if not todo.any():
            break
        idx = np.nonzero(todo)[0]
        yi = y[idx]
        f, df = _two_sided_length(yi * yi, d1[idx], d2[idx], vlo[idx], a_max[idx], j_max[idx])
        f -= length[idx]
        df *= 2.0 * yi
        ylo[idx] = np.where(f < 0.0, yi, ylo[idx])
        yhi[idx] = np.where(f >= 0.0, yi, yhi[idx])
        with np.errstate(divide="ignore", invalid="ignore"):
            yn = yi - f / df
        inside = np.isfinite(yn) & (yn > ylo[idx]) & (yn < yhi[idx])
        yn = np.where(inside, yn, 0.5 * (ylo[idx] + yhi[idx]))
        yn = np.where(f == 0.0, yi, yn)
        done = (np.abs(yn - yi) <= 1e-15 * np.abs(yi)) | (yhi[idx] - ylo[idx] <= 1e-15 * yhi[idx])
        y[idx] = yn
        todo[idx[done]] = False
    x = np.where(both, x, y * y)
    return vlo + x, x + d1, x + d2


def _phase_durations(tj1, ta1, tj2, ta2, t_cruise):
    """(k, 7) durations of the seven phases: jerk up, constant acceleration, jerk down, cruise,
    and the same to slow down."""
    return np.stack([tj1, ta1, tj1, t_cruise, tj2, ta2, tj2], axis=1)


def _boundaries(length, vs, ve, vp, j_max, times):
    """Time, length, speed and acceleration (each (k, 8)) at the phase boundaries of moves
    whose phase durations are ``times`` (k, 5): tj1, ta1, tj2, ta2, t_cruise. Elementwise, so
    rows made for any subset are bit for bit the rows made for all."""
    k = length.shape[0]
    tj1, ta1, tj2, ta2, t_cruise = times.T
    durations = _phase_durations(tj1, ta1, tj2, ta2, t_cruise)
    d_up = 0.5 * (vs + vp) * (2.0 * tj1 + ta1)
    jerk = _PHASE_JERK[None, :] * j_max[:, None]
    t_b = np.zeros((k, 8))
    s_b = np.zeros((k, 8))
    v_b = np.zeros((k, 8))
    a_b = np.zeros((k, 8))
    v_b[:, 0] = vs
    t_b[:, 1:] = np.cumsum(durations, axis=1)
    for ph in range(7):
        d = durations[:, ph]
        j = jerk[:, ph]
        s0, v0, a0 = s_b[:, ph], v_b[:, ph], a_b[:, ph]
        s_b[:, ph + 1] = s0 + d * (v0 + d * (0.5 * a0 + d * j / 6.0))
        v_b[:, ph + 1] = v0 + d * (a0 + 0.5 * j * d)
        a_b[:, ph + 1] = a0 + j * d
        if ph == 2:  # end of the speed-up: exactly (d_up, vp, 0)
            s_b[:, 3], v_b[:, 3], a_b[:, 3] = d_up, vp, 0.0
        elif ph == 3:
            s_b[:, 4] = d_up + vp * t_cruise
        elif ph == 6:  # end of the move: exactly (L, ve, 0)
            s_b[:, 7], v_b[:, 7], a_b[:, 7] = length, ve, 0.0
    return t_b, s_b, v_b, a_b


@dataclass(frozen=True, slots=True, eq=False)
class Profiles:
    """Closed-form jerk-limited profiles of n moves (arrays of shape (n,), ``times`` (n, 5)).

    ``times``: the phase durations tj1, ta1, tj2, ta2 and the cruise (the seven phases are
    tj1, ta1, tj1, cruise, tj2, ta2, tj2). The state at the 8 phase boundaries (``tables``:
    time, length, speed, acceleration; t_b[:, 0] = 0, t_b[:, 7] = duration) is made from them
    for the rows asked, when asked: kept for every move it was 256 bytes a move, the most of
    a plan of millions of moves. ``jerk``: (n, 7) jerk of each phase, also made on demand.
    """

    length_mm: np.ndarray
    vs: np.ndarray
    ve: np.ndarray
    vc: np.ndarray
    vp: np.ndarray  # reached peak (cruise) speed
    a_max: np.ndarray
    j_max: np.ndarray
    times: np.ndarray
    duration: np.ndarray  # (n,) = t_b[:, 7]

    def __len__(self) -> int:
        return int(self.length_mm.shape[0])

    def tables(self, rows=None) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(t_b, s_b, v_b, a_b), each (k, 8), of moves ``rows`` (an index array or slice;
        None: all)."""
        sel = slice(None) if rows is None else rows
        return _boundaries(self.length_mm[sel], self.vs[sel], self.ve[sel], self.vp[sel], self.j_max[sel],
                           self.times[sel])

    @property
    def t_b(self) -> np.ndarray:
        return self.tables()[0]

    @property
    def s_b(self) -> np.ndarray:
        return self.tables()[1]

    @property
    def v_b(self) -> np.ndarray:
        return self.tables()[2]

    @property
    def a_b(self) -> np.ndarray:
        return self.tables()[3]

    @property
    def jerk(self) -> np.ndarray:
        """(n, 7) jerk of each phase (made on demand: it is +-J or 0 by phase, 56 bytes a move)."""
        return _PHASE_JERK[None, :] * self.j_max[:, None]

    def phase_jerk(self, move: np.ndarray, phase: np.ndarray) -> np.ndarray:
        """Jerk of phase ``phase[k]`` of move ``move[k]``."""
        return _PHASE_JERK[phase] * self.j_max[move]

    @property
    def accel_peak(self) -> np.ndarray:
        """Largest |path acceleration| of each move (closed form)."""
        return np.max(np.abs(self.a_b), axis=1) if len(self) else np.zeros(0)

    @property
    def jerk_peak(self) -> np.ndarray:
        """Largest |path jerk| over the phases that actually last (closed form)."""
        if not len(self):
            return np.zeros(0)
        lasting = np.diff(self.t_b, axis=1) > 0.0
        return np.max(np.where(lasting, np.abs(self.jerk), 0.0), axis=1)

    def take(self, sel) -> Profiles:
        return Profiles(*(getattr(self, f)[sel] for f in self.__slots__))

    def evaluate(self, move: np.ndarray, tau: np.ndarray):
        """(s, v, a, j) of move ``move[k]`` at local time ``tau[k]`` (clamped to [0, duration])."""
        tb, sb, vb, ab = self.tables(move)
        tau = np.clip(tau, 0.0, tb[:, 7])
        phase = np.minimum((tau[:, None] >= tb[:, 1:7]).sum(axis=1), 6)
        rows = np.arange(move.shape[0])
        dt = tau - tb[rows, phase]
        s0 = sb[rows, phase]
        v0 = vb[rows, phase]
        a0 = ab[rows, phase]
        j = self.phase_jerk(move, phase)
        s = s0 + dt * (v0 + dt * (0.5 * a0 + dt * (j / 6.0)))
        v = v0 + dt * (a0 + 0.5 * j * dt)
        a = a0 + j * dt
        end = tau >= tb[:, 7]
        length = self.length_mm[move]
        s = np.where(end, length, np.clip(s, 0.0, length))
        return s, v, a, np.where(end, 0.0, j)

    def evaluate_s(self, move: np.ndarray, tau: np.ndarray) -> np.ndarray:
        """Only s."""
        return self.evaluate(move, tau)[0]


def _s_curve_times(dv, a_max, j_max):
    """(jerk time, constant-acceleration time) of an S-curve changing speed by dv >= 0."""
    limited = dv * j_max > a_max * a_max
    tj = np.where(limited, a_max / j_max, np.sqrt(dv / j_max))
    ta = np.where(limited, dv / a_max - a_max / j_max, 0.0)
    return tj, ta


def build_profiles(length_mm, vs, ve, vc, a_max, j_max, tolerance: float = 1e-6) -> Profiles:
    """Minimum-time profiles for arrays of moves (length, vs, ve, vc, A, J).

    Requires 0 <= vs, ve <= vc, A, J > 0 and the move long enough for the direct S-curve
    from vs to ve (the look-ahead guarantees it; a shortfall up to ``tolerance`` relative
    plus 1e-9 mm, from rounding of tiny speed changes, is absorbed by clamping s to L;
    anything more is a PlannerError).
    """
    length = np.atleast_1d(np.asarray(length_mm, dtype=float))
    n = length.shape[0]

    def arr(x):
        return np.broadcast_to(np.asarray(x, dtype=float), (n,)).copy()

    vs, ve, vc, a_max, j_max = arr(vs), arr(ve), arr(vc), arr(a_max), arr(j_max)
    if n and (np.any(a_max <= 0) or np.any(j_max <= 0) or np.any(vc <= 0) or np.any(length <= 0)):
        raise PlannerError("profile needs length, vc, a_max and j_max > 0")
    if n and (np.any(vs < 0) or np.any(ve < 0)):
        raise PlannerError("profile needs vs, ve >= 0")
    if n and (np.any(vs > vc * (1 + 1e-12)) or np.any(ve > vc * (1 + 1e-12))):
        raise PlannerError("profile needs vs, ve <= vc")
    vs = np.minimum(vs, vc)
    ve = np.minimum(ve, vc)
    direct = transition_length(vs, ve, a_max, j_max)
    short = direct > length
    if np.any(direct > length * (1.0 + tolerance) + 1e-9):
        i = int(np.argmax(direct - length))
        raise PlannerError(
            f"move of {length[i]:.6g} mm cannot change speed from {vs[i]:.6g} to {ve[i]:.6g} mm/s "
            f"(needs {direct[i]:.6g} mm)")
    full = transition_length(vs, vc, a_max, j_max) + transition_length(ve, vc, a_max, j_max)
    cruise = full <= length
    vp = vc.copy()
    dv_up = vc - vs
    dv_dn = vc - ve
    need = ~cruise & ~short
    if need.any():
        vp[need], dv_up[need], dv_dn[need] = _solve_peak(
            length[need], vs[need], ve[need], vc[need], a_max[need], j_max[need])
    vp[short] = np.maximum(vs, ve)[short]
    dv_up[short] = (vp - vs)[short]
    dv_dn[short] = (vp - ve)[short]
    tj1, ta1 = _s_curve_times(dv_up, a_max, j_max)
    tj2, ta2 = _s_curve_times(dv_dn, a_max, j_max)
    d_up = 0.5 * (vs + vp) * (2.0 * tj1 + ta1)
    d_dn = 0.5 * (vp + ve) * (2.0 * tj2 + ta2)
    t_cruise = np.where(cruise, (length - d_up - d_dn) / vp, 0.0)
    t_cruise = np.maximum(t_cruise, 0.0)

    times = np.stack([tj1, ta1, tj2, ta2, t_cruise], axis=1)
    # the duration as the boundary times' last (the same sum in the same order)
    duration = np.cumsum(_phase_durations(tj1, ta1, tj2, ta2, t_cruise), axis=1)[:, -1]
    return Profiles(length, vs, ve, vc, vp, a_max, j_max, times, duration)
