"""Corner blending under G64 P: a clothoid pair replaces each sharp joint between two lines.

Under ``G64 P<tol>`` a joint between two straight feed moves that turns by theta is not
crossed with a velocity step: the last part of the incoming line and the first part of the
outgoing one are replaced by a symmetric pair of clothoids (Euler spirals) in the plane of
the two lines. Along each half the curvature grows linearly with path length, from 0 at the
line to kappa_max = theta / L_s in the middle and back to 0, so position, tangent and
curvature are continuous everywhere: the normal acceleration v^2 kappa rises at a finite
rate and the jerk limit can be held through the corner (a circular blend would step the
curvature, and with it the acceleration, at both ends).

Geometry of a pair of half length L_s (arc length s from the pair's start A, sharpness
c = theta / L_s^2, heading phi(s) = c s^2 / 2 on the first half):

    p(s) = A + X(s) u1 + Y(s) n1                       0 <= s <= L_s
    p(s) = B - X(2 L_s - s) u2 + Y(2 L_s - s) n2         L_s <= s <= 2 L_s

with X, Y the Fresnel-type integrals of cos and sin of the heading (16-point Gauss-Legendre,
exact to rounding for headings up to pi / 2), u1, u2 the lines' unit directions, n1, n2 the
unit normals towards the inside of the turn, A and B the trim points on the two lines, both
at the tangent length T = X(L_s) + Y(L_s) tan(theta / 2) from the corner C. The pair's middle
lies on the corner's bisector at D = Y(L_s) / cos(theta / 2) from C: that is the deviation
from the programmed corner, and the distance from the programmed lines is Y(L_s) <= D.

Size and shape: between the pair (the turn made on the clothoids alone) and a circular arc
with short clothoids at its ends, the blend is the one of these whose speed is highest with
D <= P and T <= half of each line (LinuxCNC's rule for its blend arcs; the other half is left
for the blend at the line's other end): ``corner_sizes``. The pair keeps nearest the corner
for its largest curvature, an arc turns most for its tangent length; where the jerk allows
short clothoids, an arc between them is usually quicker (a 1 mm step over between two right
angles within 0.25 mm at J = 1e6 mm/s^3: 20.7 mm/s, the pair 15.3 mm/s).

A blend is only made where it is quicker: its speed (the planner's limits on kappa_max and on
the jerk of the changing curvature) must beat the sharp corner's tangent-break speed, and
either what the sharp corner's own plan reaches a tangent length away from it, or, over the
two lines, the time of the sharp plan (each line run from the joint's speed, or from the blend's
after it, at full jerk and acceleration up to its peak). Sharp corners held within a tight
tolerance are no quicker jerk-limited than by a one-sample velocity step (a 90 degree corner
within 0.01 mm at J = 10,000 mm/s^3: about 1 mm/s either way; no curve does much better, as
turning the velocity at speed v with jerk J takes about 2 sqrt(v / J) and strays about
v^1.5 / (2 sqrt(J)) from the corner, 0.01 mm at 1.6 mm/s), so those stay sharp; small turns
between long lines (a few degrees) gain most.

Blends are made between feed lines only (G01, not arcs or moves with rotary motion, and not
rapids: a blend is a feed move, so the operator's rapid override would no longer slow that
corner), where both lines are in G64 with a tolerance, the incoming one has no exact stop and
no event (dwell, output, message, spindle...) sits at the joint.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any, Protocol

import numpy as np

from planner.core.curves import Blend, fresnel
from planner.core.limits import (
    ACCEL_NORMAL_SHARE,
    BLEND_DK_SHARE,
    BLEND_NORMAL_SHARE,
    LimitSet,
    break_budget,
    joint_step_budget,
    kink_caps,
)
from planner.core.machine import MachineSpec
from planner.core.movestore import MoveStore
from planner.core.program import Move, MoveKind, Program

__all__ = ["BlendReport", "JointSpeeds", "SpeedOracle", "blend_corners", "blend_report", "corner_sizes",
           "line_limits", "merge_naive_cam", "ramp_speed", "round_fillets", "window_quicker"]

class JointSpeeds(Protocol):
    """A program's plan as blends are judged by it: per move, the speed at its start and end
    and the highest it reaches (a ``planner.motion.plan.Plan`` is one)."""

    @property
    def vs(self) -> np.ndarray: ...

    @property
    def ve(self) -> np.ndarray: ...

    @property
    def vpeak(self) -> np.ndarray: ...


#: the sharp program's plan, for keeping only the blends that are quicker than the sharp
#: corner (None: every blend the tolerance allows is made)
SpeedOracle = Callable[[Program], JointSpeeds]

#: joints turning less than this are tangent for the planner already (no break to remove)
MIN_TURN_RAD = 1e-7
#: joints turning more than this (nearly a reversal) are not blended: the pair would need a
#: tangent length far beyond its deviation
MAX_TURN_RAD = math.radians(175.0)
#: what is left of a line shorter than this after both its ends were blended is dropped
MIN_LINE_MM = 1e-9


def _blend_caps_k(kappa: np.ndarray, dk: np.ndarray, a_pl: np.ndarray, j_pl: np.ndarray) -> np.ndarray:
    """The speed a blend allows from its largest curvature and curvature rate (the planner's
    in-plane rules for blends in ``lookahead.move_limits``)."""
    v = np.sqrt(ACCEL_NORMAL_SHARE * a_pl / kappa)
    v = np.minimum(v, np.cbrt(BLEND_NORMAL_SHARE * j_pl / (kappa * kappa)))
    return np.minimum(v, np.cbrt(BLEND_DK_SHARE * j_pl / dk))


#: the share of a corner blend's turn made on its clothoids, tried from a clothoid pair (1) to
#: all but a circular arc: the best for the corner's speed is taken
CLOTHOID_SHARES = np.array([1.0, 0.8, 0.6, 0.45, 0.32, 0.22, 0.15, 0.1, 0.06, 0.035, 0.02, 0.01, 0.005])
#: golden-section steps refining the best share between its neighbours (to 1 % of the bracket)
REFINE_STEPS = 10


def corner_sizes(theta: np.ndarray, tol: np.ndarray, room: np.ndarray, a_pl: np.ndarray,
                 j_pl: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(clothoid length L_c, arc length L_a, tangent length T, corner deviation D, speed) of
    the quickest symmetric clothoid-arc-clothoid blend of corners turning theta: D <= ``tol``
    and T <= ``room``, its speed by the planner's rules for blends (``_blend_caps_k``).

    The blend of middle radius R with clothoids turning f theta in all (L_c = f theta R) scales
    with R: from the clothoid's end point (X, Y) at R = 1, the shift p = Y - (1 - cos(f theta / 2))
    and k = X - sin(f theta / 2) give T = R ((1 + p) tan(theta / 2) + k) and
    D = R ((1 + p) / cos(theta / 2) - 1). For each f in ``CLOTHOID_SHARES`` R is the largest
    the two bounds allow, the f of the highest speed is taken (the pair, f = 1, first where
    speeds tie) and refined between its neighbours: short clothoids bind the speed by the jerk
    of the changing curvature, long ones by the curvature they reach within the bounds."""
    th = theta[:, None]
    tol_c, room_c, a_c, j_c = tol[:, None], room[:, None], a_pl[:, None], j_pl[:, None]

    def shape(f: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(R, T at R = 1, D at R = 1, speed) for clothoid shares f (rows: the corners)."""
        vt = f * th                                    # L_c / R, each clothoid's length at R = 1
        x1, y1 = fresnel(vt, np.ones_like(vt))
        x1, y1 = x1 * vt, y1 * vt
        tau = 0.5 * vt
        shift = y1 - (1.0 - np.cos(tau))
        k = x1 - np.sin(tau)
        t_unit = (1.0 + shift) * np.tan(0.5 * th) + k
        d_unit = (1.0 + shift) / np.cos(0.5 * th) - 1.0
        # a hair inside both bounds, so that D and T computed back stay within them to rounding
        radius = np.minimum(tol_c / d_unit, room_c / t_unit) * (1.0 - 1e-12)
        v = _blend_caps_k(1.0 / radius, 1.0 / (radius * vt * radius), a_c, j_c)
        return radius, t_unit, d_unit, v

    r_g, t_g, d_g, v_g = shape(np.broadcast_to(CLOTHOID_SHARES[None, :], (len(theta), len(CLOTHOID_SHARES))))
    best = np.argmax(v_g, axis=1)
    # refined between the best share's neighbours (golden section on log f; the pair, f = 1,
    # stays where it is best of all)
    last = len(CLOTHOID_SHARES) - 1
    lo = np.log(CLOTHOID_SHARES[np.minimum(best + 1, last)])
    hi = np.log(CLOTHOID_SHARES[np.maximum(best - 1, 0)])
    g = (math.sqrt(5.0) - 1.0) / 2.0
    for _ in range(REFINE_STEPS):
        m1, m2 = hi - g * (hi - lo), lo + g * (hi - lo)
        v1 = shape(np.exp(m1)[:, None])[3][:, 0]
        v2 = shape(np.exp(m2)[:, None])[3][:, 0]
        lo = np.where(v1 < v2, m1, lo)
        hi = np.where(v1 < v2, hi, m2)
    share = np.exp(0.5 * (lo + hi))
    r_r, t_r, d_r, v_r = (x[:, 0] for x in shape(share[:, None]))
    rows = np.arange(len(theta))
    keep = v_r < v_g[rows, best]                       # the grid's best, where refining did not help
    share = np.where(keep, CLOTHOID_SHARES[best], share)
    r_b, t_b, d_b, v_b = (np.where(keep, g[rows, best], r) for g, r in ((r_g, r_r), (t_g, t_r), (d_g, d_r),
                                                                        (v_g, v_r)))
    lc_b = share * theta * r_b
    return lc_b, theta * r_b - lc_b, t_b * r_b, d_b * r_b, v_b


def _blend_not_slower(program: Program, plan: JointSpeeds, jj: np.ndarray, v_blend: np.ndarray,
                      tangent_len: np.ndarray, eligible: np.ndarray, v_sharp: np.ndarray,
                      half_len: np.ndarray, accel: tuple[np.ndarray, np.ndarray],
                      jerk: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """True where the blend cannot make the corner slower than the sharp corner's plan.

    The program is planned as it is; a blend holds about one speed over the lines' last and
    first T (its tangent length). Where that speed is at least what the sharp plan reaches T
    from the joint on both sides (bounded above: a ramp at full jerk from the joint's speed, as
    each move's profile starts with zero acceleration, up to the line's acceleration, and the
    lines' peak speeds), the blended corner is crossed at least as fast everywhere; or where
    over the two lines it takes less time (``window_quicker``). Either provided the corner is
    where the sharp plan is slowest, or where the plan crosses it at the sharp corner's own cap
    ``v_sharp`` (then the corner, not a joint beside it, holds the speed down). ``eligible``: the
    joints whose pair allows more than their sharp corner; ``accel``, ``jerk``: the tangential
    acceleration and jerk the incoming and the outgoing line allow."""
    v_joint = np.asarray(plan.ve)[jj]
    peak = np.asarray(plan.vpeak)
    # each side on its own: the incoming line may run far faster than the outgoing one
    quicker = ((v_blend >= np.minimum(ramp_speed(v_joint, tangent_len, jerk[0], accel[0]), peak[jj]))
               & (v_blend >= np.minimum(ramp_speed(v_joint, tangent_len, jerk[1], accel[1]), peak[jj + 1])))
    quicker |= window_quicker(program, plan, jj, v_blend, tangent_len, half_len, accel, jerk)
    # and only where the sharp corner is what slows the motion (its speed is the lowest of the
    # two lines'): a plan that brakes through the joint for something further on would have to
    # brake on the blend, whose tangential acceleration is small (its budget goes to the turn).
    # A slower joint next to it that is blended too does not slow it: along a run of kinks
    # (a CAM contour of short chords) each joint is taken where every slower joint it brakes
    # for, in either direction, is blended as well, down to the run's slowest.
    at_cap = v_joint >= v_sharp * (1.0 - 1e-6)
    slower_before = (np.asarray(plan.vs)[jj] < v_joint) & ~at_cap
    slower_after = (np.asarray(plan.ve)[jj + 1] < v_joint) & ~at_cap
    taken = quicker & eligible
    n_joints = max(len(np.asarray(plan.ve)) - 1, 0)
    return quicker & _through_blended(jj, slower_before, taken, n_joints) \
        & _through_blended(jj, slower_after, taken, n_joints, after=True)


def window_quicker(program: Program, plan: JointSpeeds, jj: np.ndarray, v_blend: np.ndarray,
                   tangent_len: np.ndarray, half_len: np.ndarray, accel: tuple[np.ndarray, np.ndarray],
                   jerk: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """True where crossing joint jj (between moves jj and jj + 1) by a blend takes less time
    than the sharp plan over the two moves: each from the joint to its other end, run from the
    joint's speed (sharp) or from the blend's (``half_len`` of the blend at its speed, then the
    rest of the move past the ``tangent_len`` the blend took from it) with a ramp at the move's
    full jerk up to its acceleration (``accel``, ``jerk``: incoming and outgoing move's), and
    no faster than the move's peak in the sharp plan."""
    ve, peak = np.asarray(plan.ve)[jj], np.asarray(plan.vpeak)
    lengths = np.fromiter((m.length_mm for m in program.moves), float, len(program.moves))
    total = np.zeros(len(jj))
    for side, a, j in ((jj, accel[0], jerk[0]), (jj + 1, accel[1], jerk[1])):
        length = lengths[side]
        cap = np.maximum(peak[side], 1e-9)
        rest = np.maximum(length - tangent_len, 0.0)
        sharp = _ramp_time(np.minimum(ve, cap), length, j, a, cap)
        blended = (half_len / np.maximum(v_blend, 1e-12)
                   + _ramp_time(np.minimum(v_blend, cap), rest, j, a, cap))
        total += blended - sharp
    return total < 0.0


def _ramp_time(v0: np.ndarray, dist: np.ndarray, j: float | np.ndarray, a: float | np.ndarray,
               cap: np.ndarray) -> np.ndarray:
    """Time to cover ``dist`` from speed v0 and no acceleration: jerk ``j`` up to acceleration
    ``a``, then ``a``, up to the speed ``cap`` and then at it (bisection on the time)."""
    v0, dist, cap = np.broadcast_arrays(np.asarray(v0, float), np.asarray(dist, float),
                                        np.asarray(cap, float))
    jj = np.broadcast_to(np.asarray(j, float), v0.shape)
    t_a = a / jj
    v_a = v0 + 0.5 * a * t_a
    # when the cap is reached, and the distance by then
    t_cap = np.where(v_a >= cap, np.sqrt(2.0 * np.maximum(cap - v0, 0.0) / jj), t_a + (cap - v_a) / a)

    def covered(t: np.ndarray) -> np.ndarray:
        tt = np.minimum(t, t_cap)
        ramp = np.where(tt <= t_a, v0 * tt + jj * tt**3 / 6.0,
                        v0 * t_a + jj * t_a**3 / 6.0 + v_a * (tt - t_a) + 0.5 * a * (tt - t_a) ** 2)
        return ramp + cap * np.maximum(t - t_cap, 0.0)

    lo = np.zeros_like(v0)
    hi = t_cap + dist / cap + 1e-9
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        far = covered(mid) >= dist
        hi = np.where(far, mid, hi)
        lo = np.where(far, lo, mid)
    return hi


def _through_blended(jj: np.ndarray, slower: np.ndarray, taken: np.ndarray, n_joints: int,
                     after: bool = False) -> np.ndarray:
    """Per joint jj[i]: not ``slower[i]`` (its neighbour joint on that side is not slower), or
    the neighbour is ``taken`` and holds the same, recursively: the joints from jj[i] towards
    the side, up to the first that is not slower than its own next, all taken."""
    free = np.ones(n_joints, dtype=bool)        # the joint's side needs nothing
    free[jj] = ~slower
    ok_joint = np.zeros(n_joints, dtype=bool)   # taken, and itself through on that side
    ok_joint[jj] = taken
    idx = np.arange(n_joints)
    if after:
        free, ok_joint = free[::-1], ok_joint[::-1]
    # through[k] = free[k] | (ok_joint[k-1] & through[k-1]): true where, going back from k, a
    # free joint comes before any joint that is not ok
    last_free = np.maximum.accumulate(np.where(free, idx, -1))
    last_bad = np.maximum.accumulate(np.where(ok_joint, -1, idx))
    prev_bad = np.concatenate([[-1], last_bad[:-1]])   # the last not-ok joint before k
    through = free | (last_free > prev_bad)
    if after:
        through = through[::-1]
    return through[jj]


def joint_context(program: Program) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(G64 P per move, the rotary axes, whether an event follows each move): what every
    pass here checks before it touches a joint."""
    n = len(program.moves)
    rotary = np.array(program.rotary, dtype=bool) if program.rotary else np.zeros(len(program.axes), bool)
    event_after = np.zeros(n, dtype=bool)
    for ev in program.events:
        if 0 <= ev.after_move < n:
            event_after[ev.after_move] = True
    return tolerance_per_move(program), rotary, event_after


def tolerance_per_move(program: Program) -> np.ndarray:
    """The G64 P tolerance (mm) in force for each move (0: no blending)."""
    n = len(program.moves)
    tol = np.zeros(n)
    changes = list(program.blend_tolerance) + [(n, 0.0)]
    for (first, value), (nxt, _) in zip(changes[:-1], changes[1:]):
        tol[first:nxt] = value
    return tol


def _settle(lc: np.ndarray, radius: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(R_c, p, c_x) for clothoids of length L_c onto a circle about the fillet's centre:
    R_c + p = R, p = Y(L_c) - R_c (1 - cos(L_c / 2 R_c)) (the fixed point converges by about
    p / R per step, so 12 steps reach rounding)."""
    rc = radius.copy()
    for _ in range(12):
        vt = lc / rc
        x1, y1 = fresnel(vt, np.ones_like(vt))
        rc = radius - (lc * y1 - rc * (1.0 - np.cos(0.5 * vt)))
    vt = lc / rc
    x1, y1 = fresnel(vt, np.ones_like(vt))
    p = lc * y1 - rc * (1.0 - np.cos(0.5 * vt))
    return rc, p, lc * x1 - rc * np.sin(0.5 * vt)


def _fillet_sizes(radius: np.ndarray, theta: np.ndarray, tol: np.ndarray, room: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Clothoid length L_c, middle radius R_c, arc length L_a, the distance c_x from where the
    blend leaves each line to the foot of the centre, and the radius reduction p, for fillets of
    radius R turning theta about the same centre: R_c + p = R (the clothoids ease onto a circle
    p inside the programmed one), p <= 0.9 P, L_c <= theta R_c (the arc keeps a sweep >= 0),
    c_x <= room (what the lines leave)."""
    lc = np.minimum(np.sqrt(24.0 * radius * 0.9 * tol),
                    np.minimum(2.0 * 0.95 * room, 0.999 * theta * radius))
    for _ in range(4):
        rc, p, cx = _settle(lc, radius)
        shrink = np.minimum.reduce([np.ones_like(lc), 0.98 * room / np.maximum(cx, 1e-300),
                                    np.sqrt(0.9 * tol / np.maximum(p, 1e-300)),
                                    0.999 * theta * rc / np.maximum(lc, 1e-300)])
        if np.all(shrink >= 1.0):
            break
        lc = lc * np.minimum(shrink, 1.0)
    rc, p, cx = _settle(lc, radius)
    return lc, rc, rc * theta - lc, cx, p


def arc_distance(q: np.ndarray, move: Move) -> np.ndarray:
    """Distance of points q from a circular arc move (its angular range, else its ends)."""
    arc = move.arc
    assert arc is not None
    n = q.shape[0]

    def rows(v: float) -> np.ndarray:
        return np.full(n, v)

    return arc_distance_rows(q, np.full(n, arc.first_axis), np.full(n, arc.second_axis), rows(arc.center[0]),
                             rows(arc.center[1]), rows(arc.start_angle_rad), rows(arc.sweep_rad),
                             rows(arc.radius_start_mm), rows(arc.radius_end_mm), move.start[None, :],
                             move.end[None, :])


def arc_distance_rows(q: np.ndarray, f: np.ndarray, s: np.ndarray, cx: np.ndarray, cy: np.ndarray,
                      theta0: np.ndarray, sweep: np.ndarray, r0: np.ndarray, r1: np.ndarray,
                      start: np.ndarray, end: np.ndarray) -> np.ndarray:
    """Distance of points q (N, d) from arcs, row by row: plane axes f, s, centre (cx, cy),
    start angle, sweep, radius at the start and end (a spiral's changes with the angle), start
    and end points (N, d) or (1, d). Within the arc's angular range the distance from it (in
    the plane and off it), elsewhere from the nearer end."""
    i = np.arange(q.shape[0])
    dx, dy = q[i, f] - cx, q[i, s] - cy
    rel = np.remainder((np.arctan2(dy, dx) - theta0) * np.sign(sweep), 2.0 * np.pi)
    inside = rel <= np.abs(sweep)
    frac = np.clip(rel / np.abs(sweep), 0.0, 1.0)
    r_at = r0 + (r1 - r0) * frac
    radial = np.abs(np.hypot(dx, dy) - r_at)
    off = q - start
    off[i, f] = 0.0
    off[i, s] = 0.0
    off_plane = np.sqrt((off * off).sum(axis=1))
    ends = np.minimum(np.sqrt(((q - start) ** 2).sum(axis=1)), np.sqrt(((q - end) ** 2).sum(axis=1)))
    return np.where(inside, np.hypot(radial, off_plane), ends)


def round_fillets(program: Program, machine: MachineSpec, speeds: SpeedOracle | None = None) -> Program:
    """Under G64 P, a fillet - a circular arc tangent to a line on each side, CAM's rounded
    corner - is run as clothoid, arc, clothoid: the curvature eases from 0 onto a circle about
    the same centre, p <= 0.9 P smaller in radius, and back, instead of stepping to 1/R where
    the arc meets each line (where the jerk limit allows only sqrt(J Ts R): 4.5 mm/s on a 2 mm
    fillet at 10,000 mm/s^3). The new path stays within P of the programmed one (checked on
    samples). With ``speeds``, made only where its speed is at least what the sharp plan
    reaches on the arc."""
    moves = program.moves
    n = len(moves)
    if n < 3 or not any(v > 0 for _, v in program.blend_tolerance):
        return program
    tol, rotary, event_after = joint_context(program)
    cands: list[tuple[Any, ...]] = []
    for k in range(1, n - 1):
        arc, l1, l2 = moves[k].arc, moves[k - 1], moves[k + 1]
        p_tol = min(tol[k - 1], tol[k], tol[k + 1])
        # a circle, or CAM's rounding of one (start and end radius a hair apart)
        if (arc is None or l1.kind != MoveKind.LINE or l2.kind != MoveKind.LINE or l1.blend is not None
                or l2.blend is not None or arc.rise_mm != 0.0 or p_tol <= 0.0
                or abs(arc.radius_end_mm - arc.radius_start_mm) > 0.25 * p_tol
                or abs(arc.sweep_rad) >= math.pi - 1e-6 or event_after[k - 1] or event_after[k]
                or l1.exact_stop or moves[k].exact_stop or arc.xy_turn_rad != 0.0):
            continue        # (an arc in a turned frame is no fillet of a machine plane)
        if any(np.any((m.end - m.start)[rotary] != 0.0) for m in (l1, moves[k], l2)):
            continue
        f, s = arc.first_axis, arc.second_axis
        plane = np.zeros(len(program.axes), dtype=bool)
        plane[[f, s]] = True
        if np.any((l1.end - l1.start)[~plane] != 0.0) or np.any((l2.end - l2.start)[~plane] != 0.0):
            continue
        u1 = (l1.end - l1.start) / l1.length_mm
        u2 = (l2.end - l2.start) / l2.length_mm
        cos_t = float(np.clip(u1 @ u2, -1.0, 1.0))
        turn = math.acos(cos_t)
        perp = u2 - cos_t * u1
        if turn < 1e-6 or np.linalg.norm(perp) == 0.0 or abs(abs(arc.sweep_rad) - turn) > 1e-3:
            continue
        n1 = perp / np.linalg.norm(perp)
        n2 = -math.sin(turn) * u1 + cos_t * n1
        # the circle of the arc's mean radius tangent to both lines (CAM's rounding moves the
        # programmed centre a hair off it): its centre C = P1 + a u1 + R n1 with (C - P2).n2 = R
        r = 0.5 * (arc.radius_start_mm + arc.radius_end_mm)
        a_u = (r * (1.0 - cos_t) - float((l1.end - l2.start) @ n2)) / -math.sin(turn)
        centre = l1.end + a_u * u1 + r * n1
        foot1 = l1.end + a_u * u1
        foot2 = centre - r * n2
        # tangent where the arc meets its lines, to CAM's rounding, and turning about that centre
        arc_centre = l1.end.copy()
        arc_centre[f], arc_centre[s] = arc.center
        if (np.linalg.norm(foot1 - l1.end) > 1e-3 or np.linalg.norm(foot2 - l2.start) > 1e-3
                or np.linalg.norm(centre - arc_centre) > 0.25 * p_tol
                or (arc.sweep_rad > 0.0) != (float(u1[f] * u2[s] - u1[s] * u2[f]) > 0.0)):
            continue
        cands.append((k, u1, n1, foot1, foot2, turn, r, p_tol))
    if not cands:
        return program
    ks = np.array([c[0] for c in cands])
    theta = np.array([c[5] for c in cands])
    radius = np.array([c[6] for c in cands])
    ptol = np.array([c[7] for c in cands])
    room = np.array([min(0.5 * moves[k - 1].length_mm, 0.5 * moves[k + 1].length_mm) for k in ks])
    lc, rc, la, cx, p = _fillet_sizes(radius, theta, ptol, room)
    ok = (lc > 0.0) & (la >= 0.0) & (cx <= room) & (p <= 0.9 * ptol * (1 + 1e-9)) & (cx > 0.0)
    blends: dict[int, Move] = {}
    for i in (int(x) for x in np.flatnonzero(ok)):
        k, u1, n1, foot1, foot2 = cands[i][0], cands[i][1], cands[i][2], cands[i][3], cands[i][4]
        a_pt = foot1 - cx[i] * u1
        cs_t, sn_t = math.cos(theta[i]), math.sin(theta[i])
        u2, n2 = cs_t * u1 + sn_t * n1, -sn_t * u1 + cs_t * n1
        # B along the forward path: first clothoid, arc, then back along the last clothoid
        x1, y1 = fresnel(np.array([lc[i] / rc[i]]), np.ones(1))
        x1, y1 = float(x1[0]) * lc[i], float(y1[0]) * lc[i]
        ph0 = 0.5 * lc[i] / rc[i]
        sweep = la[i] / rc[i]
        q1 = a_pt + x1 * u1 + y1 * n1
        q2 = q1 + rc[i] * ((math.sin(ph0 + sweep) - math.sin(ph0)) * u1
                           + (math.cos(ph0) - math.cos(ph0 + sweep)) * n1)
        b_pt = q2 + x1 * u2 - y1 * n2
        if np.linalg.norm(b_pt - (foot2 + cx[i] * u2)) > 1e-9 * (1.0 + np.abs(b_pt).max()):
            continue
        corner = moves[k - 1].end + 0.0
        # the lines' meeting point, for the soft-limit bound (the blend lies in the triangle A V B)
        w = float(u1 @ u2)
        den = 1.0 - w * w
        if den > 1e-12:
            rel = foot2 - foot1
            t1 = float((rel @ u1 - w * (rel @ u2)) / den)
            corner = foot1 + t1 * u1
        bl = Blend(origin=a_pt, u1=u1.copy(), n1=n1.copy(), half_mm=float(lc[i]), turn_rad=float(theta[i]),
                   corner=corner, arc_mm=float(la[i]))
        mv = Move(index=k, line=moves[k].line, kind=MoveKind.BLEND, start=a_pt.copy(), end=b_pt,
                  feed_mm_s=min(moves[k - 1].feed_mm_s, moves[k].feed_mm_s, moves[k + 1].feed_mm_s),
                  length_mm=bl.length_mm, arc=None, exact_stop=False, blend=bl)
        # within P of the programmed line, arc, line: checked on samples
        q = mv.evaluate(np.linspace(0.0, mv.length_mm, 65))[0]
        before, after = moves[k - 1], moves[k + 1]
        dist = np.minimum.reduce([arc_distance(q, moves[k]),
                                  segment_distance(q, before.start[None, :], before.end[None, :]),
                                  segment_distance(q, after.start[None, :], after.end[None, :])])
        dev = float(dist.max())
        if dev > ptol[i]:
            continue
        blends[k] = replace(mv, blend=replace(bl, measured_deviation_mm=dev))
    if not blends:
        return program
    if speeds is not None:
        blends = _fillets_not_slower(speeds(program), machine, blends)
        if not blends:
            return program
    # each fillet's lines were given at most half (room): two fillets never share a line's part
    new: list[Move] = []
    spans: list[tuple[int, int]] = []
    start_at: dict[int, np.ndarray] = {}
    for k, mv in blends.items():
        start_at[k + 1] = mv.end
    for i, m in enumerate(moves):
        if i + 1 in blends and m.kind == MoveKind.LINE:
            first_pt = start_at.get(i, m.start)
            en = blends[i + 1].start
            length = float(np.linalg.norm((en - first_pt)[~rotary]))
            if length > MIN_LINE_MM:
                new.append(replace(m, start=np.array(first_pt, dtype=float), end=np.array(en, dtype=float),
                                   length_mm=length))
                spans.append((i, i))
            continue
        if i in blends:
            new.append(blends[i])
            spans.append((i, i))
            continue
        if i in start_at:
            first_pt = start_at[i]
            length = float(np.linalg.norm((m.end - first_pt)[~rotary]))
            if length > MIN_LINE_MM:
                new.append(replace(m, start=np.array(first_pt, dtype=float), length_mm=length))
                spans.append((i, i))
            continue
        new.append(m)
        spans.append((i, i))
    return remap_program(program, new, spans)


def blend_speed(move: Move, lim: Any) -> float:
    """The speed a blend, fillet or transition allows (``lookahead.move_limits``' in-plane rules
    for blends, every axis of its plane counted), its feed and the path limit (a LimitSet)."""
    b = move.blend
    assert b is not None
    in_plane = (np.abs(b.u1) + np.abs(b.n1)) > 1e-12
    a_pl = min(float(lim.a_axis[in_plane].min()), lim.a_path)
    j_pl = min(float(lim.j_axis[in_plane].min()), lim.j_path)
    v_b = float(_blend_caps_k(np.array([max(b.kappa_max, 1e-12)]), np.array([max(b.sharpness, 1e-12)]),
                              np.array([a_pl]), np.array([j_pl]))[0])
    return min(v_b, move.feed_mm_s, lim.v_path)


def _fillets_not_slower(plan: JointSpeeds, machine: MachineSpec, blends: dict[int, Move]) -> dict[int, Move]:
    """The fillets whose speed is at least what the sharp plan reaches on their arc."""
    ve, vpeak = np.asarray(plan.ve), np.asarray(plan.vpeak)
    lim = LimitSet.from_machine(machine)
    # the sharp plan crosses a fillet's joints at no more than sqrt(J Ts R) (the curvature step)
    # and its arc at up to its peak; the blend holds one speed over the arc and the short
    # stretches c_x of the lines beside it: kept where that speed is at least the arc's peak
    return {k: mv for k, mv in blends.items() if blend_speed(mv, lim) >= max(vpeak[k], ve[k - 1], ve[k])}


def line_limits(direction: np.ndarray, limits: LimitSet) -> tuple[np.ndarray, np.ndarray]:
    """(acceleration, jerk) along lines of unit directions ``direction`` (rows): the path's, and
    each axis' over its share of the line's tangent."""
    share = np.abs(direction)
    with np.errstate(divide="ignore"):
        return (np.minimum(limits.a_path, np.min(limits.a_axis[None, :] / share, axis=1)),
                np.minimum(limits.j_path, np.min(limits.j_axis[None, :] / share, axis=1)))


def ramp_speed(v_joint: np.ndarray, dist: np.ndarray, j: float | np.ndarray,
                a: float | np.ndarray = math.inf) -> np.ndarray:
    """Upper bound of the speed a distance ``dist`` from a joint crossed at v_joint: each move's
    profile starts with zero acceleration, so at most a full-jerk ramp up to the tangential
    acceleration ``a``, then ``a`` held. The ramp: J t^3 / 6 + v t = dist (Newton from above
    converges monotonically on this convex cubic); where it would pass ``a`` (t > a / J), the
    ramp ends at t_a = a / J, v_a = v + a t_a / 2, and v^2 = v_a^2 + 2 a (dist - d_a) after it."""
    t = np.cbrt(6.0 * dist / j)
    for _ in range(30):
        f = j * t**3 / 6.0 + v_joint * t - dist
        t = t - f / (0.5 * j * t * t + v_joint)
    v_jerk = v_joint + 0.5 * j * t * t
    t_a = np.broadcast_to(np.asarray(a / j, dtype=float), np.shape(v_jerk))
    if not np.isfinite(t_a).any():
        return v_jerk
    d_a = v_joint * t_a + j * t_a**3 / 6.0
    v_a = v_joint + 0.5 * a * t_a
    with np.errstate(invalid="ignore"):
        v_held = np.sqrt(v_a * v_a + 2.0 * a * np.maximum(dist - d_a, 0.0))
    return np.where(t > t_a, v_held, v_jerk)


def blend_corners(program: Program, machine: MachineSpec, speeds: SpeedOracle | None = None) -> Program:
    """Sharp line-line joints under G64 P replaced by clothoid pairs (the module's text); with
    ``speeds``, only where the pair is quicker than the sharp corner's plan. ``program``
    itself when none is made."""
    moves = program.moves
    n = len(moves)
    if n < 2 or not program.blend_tolerance or not any(v > 0 for _, v in program.blend_tolerance):
        return program
    tol, rotary, event_after = joint_context(program)
    d = len(program.axes)
    start = np.array([m.start for m in moves], dtype=float).reshape(n, d)
    end = np.array([m.end for m in moves], dtype=float).reshape(n, d)
    kind = np.array([int(m.kind) for m in moves])
    stop = np.array([m.exact_stop for m in moves])
    delta = end - start
    lin_len = np.sqrt((delta[:, ~rotary] ** 2).sum(axis=1))
    line_ok = (kind == int(MoveKind.LINE)) & (lin_len > 0.0) & ~np.any(delta[:, rotary] != 0.0, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        direction = np.where(line_ok[:, None], delta / np.where(lin_len > 0, lin_len, 1.0)[:, None], 0.0)

    j = np.arange(n - 1)
    cand = line_ok[j] & line_ok[j + 1] & ~stop[j] & ~event_after[j]
    p_tol = np.minimum(tol[j], tol[j + 1])
    cand &= p_tol > 0.0
    # the joint must be one point (moves are continuous; guard against rounding of offsets)
    cand &= np.all(np.abs(end[j] - start[j + 1]) <= 1e-9 * (1.0 + np.abs(end[j])), axis=1)
    if not cand.any():
        return program
    jj = j[cand]
    u1 = direction[jj]
    u2 = direction[jj + 1]
    cos_t = np.clip((u1 * u2).sum(axis=1), -1.0, 1.0)
    theta = np.arccos(cos_t)
    keep = (theta > MIN_TURN_RAD) & (theta < MAX_TURN_RAD)
    jj, u1, u2, theta = jj[keep], u1[keep], u2[keep], theta[keep]
    if not jj.size:
        return program
    # inside normal: the part of u2 across u1, normalised
    perp = u2 - cos_t[keep][:, None] * u1
    n1 = perp / np.sqrt((perp * perp).sum(axis=1))[:, None]
    limits = LimitSet.from_machine(machine)
    lim_a, lim_j, ts = limits.a_axis, limits.j_axis, limits.ts_s
    in_plane = (np.abs(u1) + np.abs(n1)) > 1e-12
    a_pl = np.where(in_plane, lim_a[None, :], np.inf).min(axis=1)
    j_pl = np.where(in_plane, lim_j[None, :], np.inf).min(axis=1)
    room = np.minimum(0.5 * lin_len[jj], 0.5 * lin_len[jj + 1])
    half, arc, tangent_len, deviation, v_blend = corner_sizes(
        theta, p_tol[cand][keep], room, np.minimum(a_pl, machine.limits.a_max_mm_s2),
        np.minimum(j_pl, machine.limits.j_max_mm_s3))

    # Worth it only where the blend is faster than the sharp corner (tangent-break rule).
    # the sharp corner's cap, as the look-ahead gives it: acceleration and jerk of the
    # one-sample direction change (the lines' path jerk: ``joint_step_budget``)
    dt = np.abs(u2 - u1)
    with np.errstate(divide="ignore", invalid="ignore"):
        v_break = np.where(dt > 1e-12, break_budget(limits)[None, :] * ts / dt, np.inf).min(axis=1)
    a_line, j_line = line_limits(direction, limits)
    step = joint_step_budget(limits, j_line[jj], j_line[jj + 1], u1, u2)
    v_break = np.minimum(v_break, kink_caps(np.where(dt > 1e-12, dt, 0.0), step))
    good = v_blend > v_break if speeds is not None else np.ones(v_blend.shape, dtype=bool)
    if speeds is not None and good.any():
        # the pair is crossed at no more than the slower line's feed, over both halves
        feed = np.fromiter((m.feed_mm_s for m in moves), float, n)
        feeds = np.minimum(feed[jj], feed[jj + 1])
        v_cross = np.minimum(v_blend, np.minimum(feeds, machine.limits.v_max_mm_s))
        good &= _blend_not_slower(program, speeds(program), jj, v_cross, tangent_len, good.copy(), v_break,
                                  half + 0.5 * arc, (a_line[jj], a_line[jj + 1]),
                                  (j_line[jj], j_line[jj + 1]))
    jj, u1, n1, theta, half, arc = jj[good], u1[good], n1[good], theta[good], half[good], arc[good]
    tangent_len, deviation = tangent_len[good], deviation[good]
    if not jj.size:
        return program

    corner = end[jj]
    a_pts = corner - tangent_len[:, None] * u1
    b_pts = corner + tangent_len[:, None] * direction[jj + 1]
    return _rebuild(program, jj, a_pts, b_pts, u1, n1, half, theta, corner, arc, deviation)


def _rebuild(program: Program, joints: np.ndarray, a_pts: np.ndarray, b_pts: np.ndarray,
             u1: np.ndarray, n1: np.ndarray, half: np.ndarray, theta: np.ndarray,
             corner: np.ndarray, arc: np.ndarray, deviation: np.ndarray) -> Program:
    moves = program.moves
    at_joint = {int(k): i for i, k in enumerate(joints)}
    new: list[Move] = []
    origin: list[int] = []  # the old move each new move belongs to (a blend: its incoming move)
    prev_b: np.ndarray | None = None  # where the previous blend ended (the trimmed start)
    for i, m in enumerate(moves):
        b_i = at_joint.get(i)
        st = m.start if prev_b is None else prev_b
        en = m.end if b_i is None else a_pts[b_i]
        if prev_b is None and b_i is None:
            new.append(replace(m, index=len(new)))
            origin.append(i)
        else:
            rest = float(np.sqrt(((en - st) ** 2).sum()))
            if rest > MIN_LINE_MM:
                st_c = np.array(st, dtype=float)
                en_c = np.array(en, dtype=float) if b_i is not None else m.end
                new.append(replace(m, index=len(new), start=st_c, end=en_c, length_mm=rest))
                origin.append(i)
        if b_i is not None:
            bl = Blend(origin=np.array(a_pts[b_i]), u1=np.array(u1[b_i]), n1=np.array(n1[b_i]),
                       half_mm=float(half[b_i]), turn_rad=float(theta[b_i]), corner=np.array(corner[b_i]),
                       arc_mm=float(arc[b_i]),
                       measured_deviation_mm=float(deviation[b_i]) if arc[b_i] > 0.0 else math.nan)
            nxt = moves[i + 1]
            # where the motion is: the trimmed line's end, or the previous blend's end when the
            # line between was blended away whole (the same point to rounding)
            b_start = new[-1].end if new else np.array(a_pts[b_i])
            b_end = np.array(b_pts[b_i])
            new.append(Move(index=len(new), line=m.line, kind=MoveKind.BLEND, start=b_start, end=b_end,
                            feed_mm_s=min(m.feed_mm_s, nxt.feed_mm_s), length_mm=bl.length_mm,
                            arc=None, exact_stop=False, blend=bl))
            origin.append(i)
            prev_b = b_end
        else:
            prev_b = None
    return remap_program(program, new, [(o, o) for o in origin])


def remap_program(program: Program, new: list[Move], spans: list[tuple[int, int]]) -> Program:
    """The program with moves ``new``; ``spans[k]``: the old moves new move k comes from.

    Events after old move i go after the last new move of i; modal texts, frames and
    tolerances changing at old move i change at its first new move (each keeps its place)."""
    n = len(program.moves)
    first_new = np.full(n, len(new), dtype=np.int64)
    last_new = np.full(n, -1, dtype=np.int64)
    for k, (lo, hi) in enumerate(spans):
        first_new[lo:hi + 1] = np.minimum(first_new[lo:hi + 1], k)
        last_new[lo:hi + 1] = np.maximum(last_new[lo:hi + 1], k)

    def first(i: int) -> int:
        return int(first_new[i]) if i < n else len(new)

    events = tuple(replace(e, after_move=int(last_new[e.after_move])) if 0 <= e.after_move < n else e
                   for e in program.events)
    return replace(program, moves=MoveStore.from_moves(new, program.start_position), events=events,
                   modal=tuple((first(f), t) for f, t in program.modal),
                   frames=tuple(replace(c, first=first(c.first)) for c in program.frames),
                   blend_tolerance=tuple((first(f), v) for f, v in program.blend_tolerance),
                   naive_cam_tolerance=tuple((first(f), v) for f, v in program.naive_cam_tolerance))


#: LinuxCNC's chain limit: at most this many points are joined into one line
NAIVE_CAM_MAX_POINTS = 101


def _changes_at(program: Program) -> set[int]:
    """Moves where a modal text, the offsets or a tolerance changes (a chain stops there)."""
    out: set[int] = set()
    for seq in (program.modal, program.blend_tolerance, program.naive_cam_tolerance):
        out.update(int(item[0]) for item in seq[1:])
    out.update(c.first for c in program.frames[1:])
    return out


def merge_naive_cam(program: Program) -> Program:
    """G64 Q, as LinuxCNC's canon does it (``see_segment``/``linkable`` in emccanon.cc): consecutive
    feed lines are chained while every point of the chain lies within Q of the line from where
    the chain starts to its newest point, up to 101 points; the chain is run as that one line,
    with the line number of its last point. A chain stops at anything else: a rapid, an arc,
    motion of a rotary axis, a feed change, an event, a change of mode, offset or tolerance, an
    exact stop. Returns ``program`` itself when nothing is joined.

    One difference, on purpose: LinuxCNC also runs a G17 arc whose sagitta is below Q as two
    chords through its middle. That turns a tangent path into corners; measured here on the
    shared CAM programs it made them slower (ugs arc_rword_test 58.7 s to 73.2 s in inch Q), so
    arcs stay arcs.

    Speed: whether a chain's first point can take a second is decided for all moves at once;
    longer chains are grown in blocks (all candidate ends of a block checked in one array)."""
    moves = program.moves
    n = len(moves)
    if n < 2 or not any(v > 0 for _, v in program.naive_cam_tolerance):
        return program
    q_tol = np.zeros(n)
    changes = list(program.naive_cam_tolerance) + [(n, 0.0)]
    for (first, value), (nxt, _) in zip(changes[:-1], changes[1:]):
        q_tol[first:nxt] = value
    d = len(program.axes)
    rotary = np.array(program.rotary, dtype=bool) if program.rotary else np.zeros(d, bool)
    cols = moves.columns()                # no Move object for the moves that stay
    start, end, feed, exact_stop = cols.start, cols.end, cols.feed, cols.exact_stop
    chainable = cols.kind == int(MoveKind.LINE)
    chainable[cols.blend_rows] = False
    chainable &= (q_tol > 0.0) & ~np.any((end - start)[:, rotary] != 0.0, axis=1)
    # cont[i]: move i may continue a chain that holds move i - 1
    cont = np.zeros(n, dtype=bool)
    cont[1:] = chainable[1:] & chainable[:-1] & (feed[1:] == feed[:-1]) & (q_tol[1:] == q_tol[:-1])
    cont[1:] &= ~exact_stop[:-1]
    for ev in program.events:
        if 0 <= ev.after_move < n - 1:
            cont[ev.after_move + 1] = False
    for i in _changes_at(program):
        if 0 <= i < n:
            cont[i] = False
    lin = end[:, ~rotary]
    b_lin = start[:, ~rotary]
    # a chain whose first point is move i's end (it starts at move i's start) takes move i + 1's
    # end if move i's end lies within Q of the line from its start to that end
    pair_ok = np.zeros(n, dtype=bool)
    if n > 1:
        pair_ok[:-1] = cont[1:] & (segment_distance(lin[:-1], b_lin[:-1], lin[1:]) <= q_tol[:-1])
        pair_ok[:-1] &= np.any(lin[1:] != b_lin[:-1], axis=1)
    # run[i]: how many moves after i continue a chain holding i (cont run length)
    follows = np.append(cont[1:], False)  # follows[i]: move i + 1 continues
    stop_at = np.where(follows, n, np.arange(n))
    run = np.minimum.accumulate(stop_at[::-1])[::-1] - np.arange(n)
    new: list[Move] = []
    spans: list[tuple[int, int]] = []
    joined = False
    i = 0
    while i < n:
        if not pair_ok[i]:
            new.append(moves[i])
            spans.append((i, i))
            i += 1
            continue
        last = i + min(int(run[i]), NAIVE_CAM_MAX_POINTS - 1)
        k_end = _chain_end(lin, b_lin[i], i, last, q_tol[i])
        b = start[i]
        length = float(np.sqrt(((end[k_end] - b)[~rotary] ** 2).sum()))
        new.append(Move(index=len(new), line=moves[k_end].line, kind=MoveKind.LINE, start=b.copy(),
                        end=end[k_end].copy(), feed_mm_s=float(feed[i]), length_mm=length, arc=None,
                        exact_stop=bool(exact_stop[k_end])))
        spans.append((i, k_end))
        joined = True
        i = k_end + 1
    if not joined:
        return program
    return remap_program(program, new, spans)


def segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance of points p from segments a-b, row by row (LinuxCNC's clamped projection)."""
    m = b - a
    rel = p - a
    mm = (m * m).sum(axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.clip(np.where(mm > 0.0, (rel * m).sum(axis=-1) / np.where(mm > 0.0, mm, 1.0), 0.0), 0.0, 1.0)
    return np.sqrt(((rel - t[..., None] * m) ** 2).sum(axis=-1))


def _chain_end(lin: np.ndarray, b: np.ndarray, i: int, last: int, q: float) -> int:
    """The last move of the chain whose first point is lin[i] (starting at b), at most ``last``:
    the chain takes end k while every point i .. k-1 lies within q of the segment b - lin[k]."""
    hi_done = i + 1                        # pair_ok: the chain reaches i + 1
    for width in (8, 32, NAIVE_CAM_MAX_POINTS):
        hi = min(i + width - 1, last)
        if hi <= hi_done:
            if hi == last:
                return hi_done
            continue
        ends = lin[hi_done + 1:hi + 1]                 # candidate ends k = hi_done+1 .. hi
        pts = lin[i:hi]                                # chain points i .. hi-1
        k_idx = np.arange(hi_done + 1, hi + 1)
        dist = segment_distance(pts[None, :, :], b[None, None, :], ends[:, None, :])
        inside = (dist <= q) | (np.arange(i, hi)[None, :] >= k_idx[:, None])
        ok = inside.all(axis=1) & np.any(ends != b, axis=1)
        bad = np.flatnonzero(~ok)
        if bad.size:
            return int(k_idx[bad[0]]) - 1
        hi_done = hi
        if hi == last:
            return hi
    return hi_done


@dataclass(frozen=True, slots=True)
class BlendReport:
    """How far the blended path leaves the programmed one."""

    blends: int
    max_corner_deviation_mm: float  # largest distance of a blend from its programmed corner
    line: int  # where it is (0 when no blend)


def blend_report(program: Program) -> BlendReport:
    cols = program.moves.columns()     # only the blends are looked at
    found = [(b, int(cols.line[r])) for r, b in zip(cols.blend_rows.tolist(), cols.blends)]
    best, line = 0.0, 0
    for blend, at in found:
        if blend.deviation_mm > best:
            best, line = blend.deviation_mm, at
    return BlendReport(len(found), best, line)
