"""Curvature-continuous transitions at the joints of arcs under G64 P.

Where an arc meets a line or another arc, the curvature steps: from 0 to 1/R, or from 1/R1 to
1/R2, and often the tangent has a small kink too (CAM's fitted arcs). The planner crosses a
curvature step at no more than sqrt(J Ts / |dkappa|) (the normal acceleration may change by
J Ts in one sample): 4.5 mm/s into a 2 mm arc at 10,000 mm/s^3. Such a joint is replaced by a
transition: the last stretch d of the incoming move and the first stretch d of the outgoing
one give way to a plane curve whose curvature is a cubic in its arc length,

    kappa(s) = c0 + c1 s + c2 s^2 + c3 s^3,   c0 = kappa_A,

solved (length L and c1..c3, Newton on two unknowns, the other two linear) so that it ends at
B with B's heading and curvature: position, tangent and curvature are continuous at both
ends, so the jerk limit holds through the joint. The transition keeps within P of the
programmed moves (checked on samples; d shrinks until it does) and takes at most half of each
move. Its largest curvature and curvature rate (exact, ``blend.poly_bounds``) set its speed.
Made only where its speed beats the speed the sharp plan crosses the joint at.

Joints handled: line-arc, arc-line and arc-arc (not line-line: ``planner.geometry.blend``'s corners),
both moves in one machine plane (the arc's; no helix), no rotary motion, G64 P on both, no
exact stop or event at the joint, and at most 150 degrees of kink. A joint kinked by more than
30 degrees is all but a stop when sharp, and its transition is tight (it turns within P): it is
made only where it also takes less time than the sharp plan over the two moves (the sharp one
leaves the joint at full acceleration; at J = 1e4 mm/s^3 a 40 degree joint into a 5 mm arc is
quicker sharp, at 1e6 eased).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from planner.core.curves import Blend, poly_heading
from planner.core.limits import LimitSet
from planner.core.machine import MachineSpec
from planner.core.program import Move, MoveKind, Program
from planner.geometry.blend import (
    MIN_LINE_MM,
    JointSpeeds,
    SpeedOracle,
    arc_distance,
    blend_speed,
    joint_context,
    line_limits,
    remap_program,
    segment_distance,
    window_quicker,
)
from planner.geometry.resume import head_move, split_move

__all__ = ["ease_joints", "solve_transition"]

_GX, _GW = np.polynomial.legendre.leggauss(24)
_GX = (_GX + 1.0) * 0.5
_GW = _GW * 0.5

#: kinks up to this are eased where the transition beats the sharp joint's own speed; larger
#: ones where it also takes less time over the two moves (``window_quicker``)
SMALL_KINK_RAD = math.radians(30.0)
#: kinks larger than this are left sharp (near a reversal no transition keeps within P)
MAX_KINK_RAD = math.radians(150.0)
#: a joint turning more than this strays from its moves in proportion to the stretch taken
#: (less: as its square, the curvature step's share)
KINKED_RAD = math.radians(1.0)


def _coeffs(length: float, c3: float, k0: float, k1: float, dpsi: float) -> tuple[float, float, float, float]:
    """c1, c2 (given c3) so that kappa(L) = k1 and the heading turns by dpsi over L."""
    # [[L, L^2], [L^2 / 2, L^3 / 3]] (c1, c2) = (b1, b2), by Cramer's rule (determinant -L^4 / 6)
    l2 = length * length
    b1 = k1 - k0 - c3 * l2 * length
    b2 = dpsi - k0 * length - c3 * l2 * l2 / 4.0
    det = -l2 * l2 / 6.0
    c1 = (b1 * l2 * length / 3.0 - l2 * b2) / det
    c2 = (length * b2 - 0.5 * l2 * b1) / det
    return (k0, c1, c2, c3)


def _end(c: tuple[float, float, float, float], length: float) -> np.ndarray:
    ps = poly_heading(np.array([c]), np.array([length * _GX]))[0]
    return length * np.array([np.cos(ps) @ _GW, np.sin(ps) @ _GW])


def solve_transition(k0: float, k1: float, dpsi: float, bx: float, by: float
                     ) -> tuple[float, tuple[float, float, float, float]] | None:
    """(L, coefficients) of the cubic-curvature curve from (0, 0) heading 0 with curvature k0
    to (bx, by) with heading dpsi and curvature k1; None when Newton does not find it."""
    chord = math.hypot(bx, by)
    if chord <= 0.0:
        return None
    length, c3 = chord, 0.0
    target = np.array([bx, by])

    def residual(length: float, c3: float) -> np.ndarray:
        return _end(_coeffs(length, c3, k0, k1, dpsi), length) - target

    f = residual(length, c3)
    for _ in range(30):
        if np.abs(f).max() <= 1e-13 * (1.0 + chord):
            return length, _coeffs(length, c3, k0, k1, dpsi)
        h1 = 1e-7 * length
        h2 = 1e-7 * (abs(c3) + 1.0 / length ** 3)
        j1 = (residual(length + h1, c3) - f) / h1
        j2 = (residual(length, c3 + h2) - f) / h2
        det = j1[0] * j2[1] - j2[0] * j1[1]
        if det == 0.0 or not math.isfinite(det):
            return None
        step = ((-f[0] * j2[1] + j2[0] * f[1]) / det, (-j1[0] * f[1] + f[0] * j1[1]) / det)
        scale = 1.0
        while scale > 1e-4:
            l2, c32 = length + scale * step[0], c3 + scale * step[1]
            if l2 > 0.0:
                f2 = residual(l2, c32)
                if np.abs(f2).max() < np.abs(f).max():
                    length, c3, f = l2, c32, f2
                    break
            scale *= 0.5
        else:
            return None
    return None


def _plane(a: Move, b: Move, n_axes: int) -> tuple[int, int] | None:
    """The machine plane (first, second axis) both moves lie in, from their arcs."""
    planes = {(m.arc.first_axis, m.arc.second_axis) for m in (a, b) if m.arc is not None}
    if len(planes) != 1 or any(m.arc is not None and m.arc.xy_turn_rad != 0.0 for m in (a, b)):
        return None                 # an arc in a turned frame lies in no machine plane
    f, s = planes.pop()
    other = np.ones(n_axes, dtype=bool)
    other[[f, s]] = False
    for m in (a, b):
        if np.any((m.end - m.start)[other] != 0.0):     # a helix, or a line leaving the plane
            return None
    return f, s


def _signed(m: Move, kappa: float) -> float:
    """Curvature ``kappa`` of ``m`` signed: positive turning left in the (first, second) frame."""
    if m.arc is None:
        return 0.0
    return kappa * (1.0 if m.arc.sweep_rad > 0.0 else -1.0)


def _distance_to(q: np.ndarray, m: Move) -> np.ndarray:
    if m.arc is None:
        return segment_distance(q, m.start[None, :], m.end[None, :])
    return arc_distance(q, m)


def _make(a: Move, b: Move, f: int, s: int, d: float, tol: float
          ) -> tuple[tuple[Move, Move, Move] | None, float]:
    """((a's head, transition, b's tail) with d taken from each, or None if none fits in tol;
    the transition's distance from the moves, NaN where there is no transition to measure)."""
    n_axes = a.start.shape[0]
    u_a = a.length_mm - d
    pa, ta, ka = a.evaluate(np.array([u_a]))
    pb, tb, kb = b.evaluate(np.array([d]))
    pa, ta, pb, tb = pa[0], ta[0], pb[0], tb[0]
    u1 = np.zeros(n_axes)
    u1[[f, s]] = ta[[f, s]] / math.hypot(ta[f], ta[s])
    n1 = np.zeros(n_axes)
    n1[f], n1[s] = -u1[s], u1[f]                         # left of u1 in the plane
    cos_t = float(np.clip(tb @ u1, -1.0, 1.0))
    dpsi = math.atan2(float(tb @ n1), cos_t)
    rel = pb - pa
    sol = solve_transition(_signed(a, float(ka[0])), _signed(b, float(kb[0])), dpsi, float(rel @ u1),
                           float(rel @ n1))
    if sol is None:
        return None, math.nan
    length, c = sol
    if not 0.5 * math.hypot(*rel[[f, s]]) < length < 3.0 * math.hypot(*rel[[f, s]]):
        return None, math.nan                             # a loop or a detour, not a transition
    bl = Blend(origin=pa.copy(), u1=u1, n1=n1, half_mm=0.5 * length, turn_rad=max(abs(dpsi), 1e-12),
               corner=a.end.copy(), poly=c)
    mv = Move(index=0, line=a.line, kind=MoveKind.BLEND, start=pa.copy(), end=pb.copy(),
              feed_mm_s=min(a.feed_mm_s, b.feed_mm_s), length_mm=length, arc=None, exact_stop=False, blend=bl)
    q = mv.evaluate(np.linspace(0.0, length, 49))[0]
    if np.linalg.norm(q[-1] - pb) > 1e-9 * (1.0 + np.abs(pb).max()):
        return None, math.nan
    dev = float(np.minimum(_distance_to(q, a), _distance_to(q, b)).max())
    if dev > tol:
        return None, dev
    mv = replace(mv, blend=replace(bl, measured_deviation_mm=dev))
    head = _head(a, u_a, pa)
    tail = split_move(b, d)
    if head is None or tail.length_mm <= MIN_LINE_MM:
        return None, math.nan
    return (head, mv, tail), dev


def _head(m: Move, u: float, end: np.ndarray) -> Move | None:
    if u <= MIN_LINE_MM:
        return None
    if m.arc is None:
        return replace(m, end=end.copy(), length_mm=float(np.linalg.norm(end - m.start)))
    return head_move(m, u)


def ease_joints(program: Program, machine: MachineSpec, speeds: SpeedOracle | None = None) -> Program:
    """The program with its line-arc, arc-line and arc-arc joints under G64 P eased (see the
    module's text; with ``speeds``, only where the transition is quicker than the sharp
    joint's plan); ``program`` itself when none is."""
    moves = program.moves
    n = len(moves)
    if n < 2 or not any(v > 0 for _, v in program.blend_tolerance):
        return program
    tol, rotary, event_after = joint_context(program)
    made: dict[int, tuple[Move, Move, Move]] = {}
    kinks: dict[int, tuple[float, float]] = {}
    tangents: dict[int, np.ndarray] = {}

    def end_tangents(i: int) -> np.ndarray:
        """The unit tangents at the start and the end of move i (each move evaluated once)."""
        if i not in tangents:
            tangents[i] = moves[i].evaluate(np.array([0.0, moves[i].length_mm]))[1]
        return tangents[i]

    for j in range(n - 1):
        a, b = moves[j], moves[j + 1]
        p_tol = min(tol[j], tol[j + 1])
        curve = (MoveKind.LINE, MoveKind.ARC)
        if (p_tol <= 0.0 or a.kind not in curve or b.kind not in curve
                or (a.arc is None and b.arc is None) or a.blend is not None or b.blend is not None
                or a.exact_stop or event_after[j]
                or any(np.any((m.end - m.start)[rotary] != 0.0) for m in (a, b))
                or np.abs(a.end - b.start).max() > 1e-9 * (1.0 + np.abs(a.end).max())):
            continue
        if any(m.arc is not None and abs(m.arc.sweep_rad) > 2.0 * math.pi for m in (a, b)):
            continue
        plane = _plane(a, b, len(program.axes))
        if plane is None:
            continue
        f, s = plane
        ta = end_tangents(j)[1]
        tb = end_tangents(j + 1)[0]
        kink = math.acos(float(np.clip(ta @ tb, -1.0, 1.0)))
        if kink > MAX_KINK_RAD:
            continue
        room = min(0.45 * a.length_mm, 0.45 * b.length_mm)   # the rest is for the other ends
        d = min(room, 50.0 * p_tol)
        trio = None
        # the stretch shrinks until the transition keeps within 0.9 P: by 0.6 a try, or at once
        # to where its deviation would fit (about d for a kink, d^2 for a curvature step alone)
        power = 1.0 if kink > KINKED_RAD else 0.5
        for _ in range(10):
            if d <= 1e-9 * (1.0 + abs(a.end).max()):
                break
            trio, dev = _make(a, b, f, s, d, 0.9 * p_tol)
            if trio is not None:
                break
            d *= min(0.6, 0.95 * (0.9 * p_tol / dev) ** power) if dev > 0.0 else 0.6
        if trio is None:
            continue
        made[j] = trio
        kinks[j] = (kink, d)
    if not made:
        return program
    if speeds is not None:
        made = _quicker(program, speeds(program), machine, made, kinks)
        if not made:
            return program
    return _apply(program, made)


def _quicker(program: Program, plan: JointSpeeds, machine: MachineSpec,
             made: dict[int, tuple[Move, Move, Move]], kinks: dict[int, tuple[float, float]]
             ) -> dict[int, tuple[Move, Move, Move]]:
    """The transitions whose speed beats the speed the sharp plan crosses their joint at and,
    for kinks over ``SMALL_KINK_RAD``, that take less time over the two moves than the sharp
    plan (``window_quicker``; ``kinks``: the kink and the stretch d taken from each move, per
    joint). Small kinks are not asked the second: the shared CAM programs run slower with it."""
    ve = np.asarray(plan.ve)
    lim = LimitSet.from_machine(machine)
    speed = {j: blend_speed(trio[1], lim) for j, trio in made.items()}
    big = np.array([j for j in made if kinks[j][0] > SMALL_KINK_RAD and speed[j] > ve[j]], dtype=np.int64)
    timed: set[int] = set()
    if big.size:
        v = np.array([speed[int(j)] for j in big])
        stretch = np.array([kinks[int(j)][1] for j in big])
        half = np.array([0.5 * made[int(j)][1].length_mm for j in big])
        a_in, j_in = np.array([_tangential_limits(program.moves[int(i)], lim) for i in big]).T
        a_out, j_out = np.array([_tangential_limits(program.moves[int(i)], lim) for i in big + 1]).T
        quick = window_quicker(program, plan, big, v, stretch, half, (a_in, a_out), (j_in, j_out))
        timed = {int(j) for j in big[quick]}
    return {j: trio for j, trio in made.items()
            if speed[j] > ve[j] and (kinks[j][0] <= SMALL_KINK_RAD or j in timed)}


def _tangential_limits(move: Move, lim: LimitSet) -> tuple[float, float]:
    """(acceleration, jerk) along a line or an arc: the path's, and each axis' over its share
    of the tangent (a line's direction; an arc's tangent turns through its plane, so at worst
    along the weaker of the plane's two axes)."""
    if move.arc is None:
        a, j = line_limits(((move.end - move.start) / max(move.length_mm, 1e-300))[None, :], lim)
        return float(a[0]), float(j[0])
    plane = [move.arc.first_axis, move.arc.second_axis]
    return (min(lim.a_path, float(lim.a_axis[plane].min())), min(lim.j_path, float(lim.j_axis[plane].min())))


def _apply(program: Program, made: dict[int, tuple[Move, Move, Move]]) -> Program:
    """Replace each eased joint's moves by head, transition, tail (a move between two eased
    joints loses both ends)."""
    moves = program.moves
    new: list[Move] = []
    spans: list[tuple[int, int]] = []
    tail_of: dict[int, Move] = {}
    for i, m in enumerate(moves):
        cur = tail_of.get(i, m)
        if i in made:
            head, mv, tail = made[i]
            if i in tail_of:                    # both ends eased: cut the tail at this head's end
                cur_head = _head(cur, cur.length_mm - (m.length_mm - head.length_mm), head.end)
                if cur_head is None:
                    continue
                head = cur_head
            new.append(head)
            spans.append((i, i))
            new.append(mv)
            spans.append((i, i))
            tail_of[i + 1] = tail
            continue
        new.append(cur)
        spans.append((i, i))
    return remap_program(program, new, spans)
