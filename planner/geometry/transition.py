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

from planner.core.curves import Blend, poly_heading, poly_positions
from planner.core.limits import LimitSet
from planner.core.machine import MachineSpec
from planner.core.program import Move, MoveKind, Program
from planner.geometry.blend import (
    MIN_LINE_MM,
    JointSpeeds,
    SpeedOracle,
    arc_distance_rows,
    blend_speed,
    joint_context,
    line_limits,
    remap_program,
    segment_distance,
    window_quicker,
)
from planner.geometry.movetable import MoveTable
from planner.geometry.resume import head_move, split_move

__all__ = ["ease_joints", "solve_transition"]

_GX, _GW = np.polynomial.legendre.leggauss(24)
_GX = (_GX + 1.0) * 0.5
_GW = _GW * 0.5
#: points along a transition at which its distance from the two moves is measured
_SAMPLES = 49
#: joints solved together (bounds the memory their samples take)
_BATCH = 2048

#: kinks up to this are eased where the transition beats the sharp joint's own speed; larger
#: ones where it also takes less time over the two moves (``window_quicker``)
SMALL_KINK_RAD = math.radians(30.0)
#: kinks larger than this are left sharp (near a reversal no transition keeps within P)
MAX_KINK_RAD = math.radians(150.0)
#: a joint turning more than this strays from its moves in proportion to the stretch taken
#: (less: as its square, the curvature step's share)
KINKED_RAD = math.radians(1.0)


def _coeffs(length: np.ndarray, c3: np.ndarray, k0: np.ndarray, k1: np.ndarray, dpsi: np.ndarray
            ) -> np.ndarray:
    """Coefficients (n, 4): c1, c2 (given c3) so that kappa(L) = k1 and the heading turns by
    dpsi over L, row by row."""
    # [[L, L^2], [L^2 / 2, L^3 / 3]] (c1, c2) = (b1, b2), by Cramer's rule (determinant -L^4 / 6)
    l2 = length * length
    b1 = k1 - k0 - c3 * l2 * length
    b2 = dpsi - k0 * length - c3 * l2 * l2 / 4.0
    det = -l2 * l2 / 6.0
    c1 = (b1 * l2 * length / 3.0 - l2 * b2) / det
    c2 = (length * b2 - 0.5 * l2 * b1) / det
    return np.stack([k0, c1, c2, c3], axis=-1)


def _ends(c: np.ndarray, length: np.ndarray) -> np.ndarray:
    """End points (n, 2) of the curves of coefficients c (n, 4) over their lengths (n,)."""
    ps = poly_heading(c, length[:, None] * _GX)
    return length[:, None] * np.stack([np.cos(ps) @ _GW, np.sin(ps) @ _GW], axis=-1)


def solve_transitions(k0: np.ndarray, k1: np.ndarray, dpsi: np.ndarray, bx: np.ndarray, by: np.ndarray
                      ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Row by row: (L, coefficients (n, 4), found) of the cubic-curvature curve from (0, 0)
    heading 0 with curvature k0 to (bx, by) with heading dpsi and curvature k1. Newton on
    (L, c3), each step halved until the residual falls; not found where no step does, or
    where it has not converged after 30 steps."""
    k0, k1, dpsi, bx, by = (np.asarray(v, dtype=float) for v in (k0, k1, dpsi, bx, by))
    n = k0.shape[0]
    chord = np.hypot(bx, by)
    target = np.stack([bx, by], axis=-1)
    length = chord.copy()
    c3 = np.zeros(n)
    found = np.zeros(n, dtype=bool)
    live = chord > 0.0

    def residual(rows: np.ndarray, length: np.ndarray, c3: np.ndarray) -> np.ndarray:
        return _ends(_coeffs(length, c3, k0[rows], k1[rows], dpsi[rows]), length) - target[rows]

    f = np.zeros((n, 2))
    rows = np.flatnonzero(live)
    f[rows] = residual(rows, length[rows], c3[rows])
    for _ in range(30):
        rows = np.flatnonzero(live)
        conv = np.abs(f[rows]).max(axis=1) <= 1e-13 * (1.0 + chord[rows])
        found[rows[conv]] = True
        live[rows[conv]] = False
        rows = rows[~conv]
        if not rows.size:
            break
        ln, c, fr = length[rows], c3[rows], f[rows]
        h1 = 1e-7 * ln
        h2 = 1e-7 * (np.abs(c) + 1.0 / ln ** 3)
        j1 = (residual(rows, ln + h1, c) - fr) / h1[:, None]
        j2 = (residual(rows, ln, c + h2) - fr) / h2[:, None]
        det = j1[:, 0] * j2[:, 1] - j2[:, 0] * j1[:, 1]
        solvable = (det != 0.0) & np.isfinite(det)
        pending = solvable.copy()
        with np.errstate(divide="ignore", invalid="ignore"):
            step_l = (-fr[:, 0] * j2[:, 1] + j2[:, 0] * fr[:, 1]) / det
            step_c = (-j1[:, 0] * fr[:, 1] + fr[:, 0] * j1[:, 1]) / det
        err = np.abs(fr).max(axis=1)
        scale = 1.0
        while scale > 1e-4 and pending.any():
            k = np.flatnonzero(pending)
            l2, c2 = ln[k] + scale * step_l[k], c[k] + scale * step_c[k]
            ok = l2 > 0.0
            k, l2, c2 = k[ok], l2[ok], c2[ok]
            if k.size:
                f2 = residual(rows[k], l2, c2)
                better = np.abs(f2).max(axis=1) < err[k]
                kb = rows[k[better]]
                length[kb], c3[kb], f[kb] = l2[better], c2[better], f2[better]
                pending[k[better]] = False
            scale *= 0.5
        live[rows[pending | ~solvable]] = False      # no step lowers the residual: none found
    return length, _coeffs(length, c3, k0, k1, dpsi), found


def solve_transition(k0: float, k1: float, dpsi: float, bx: float, by: float
                     ) -> tuple[float, tuple[float, float, float, float]] | None:
    """(L, coefficients) of the cubic-curvature curve from (0, 0) heading 0 with curvature k0
    to (bx, by) with heading dpsi and curvature k1; None when Newton does not find it."""
    length, c, found = solve_transitions(*(np.array([v], dtype=float) for v in (k0, k1, dpsi, bx, by)))
    if not found[0]:
        return None
    return float(length[0]), (float(c[0, 0]), float(c[0, 1]), float(c[0, 2]), float(c[0, 3]))


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


def _distance_rows(q: np.ndarray, table: MoveTable, row: np.ndarray) -> np.ndarray:
    """Distance of points q (N, d) from moves ``row`` (N,) of the table, lines and plane arcs."""
    start, end = table.start[row], table.end[row]
    out = segment_distance(q, start, end)
    k = np.flatnonzero(table.is_arc[row])
    if k.size:
        r = row[k]
        out[k] = arc_distance_rows(q[k], table.first[r], table.second[r], table.cx[r], table.cy[r],
                                   table.theta0[r], table.sweep[r], table.r0[r], table.r1[r],
                                   start[k], end[k])
    return out


def _try(table: MoveTable, ja: np.ndarray, f: np.ndarray, s: np.ndarray, d: np.ndarray, tol: np.ndarray
         ) -> tuple[np.ndarray, ...]:
    """Transitions at joints ``ja`` (between moves ja and ja + 1 of the table, in the plane of
    axes f, s) taking d from each move: (made, deviation (NaN where none was made to measure),
    length, coefficients (n, 4), turn, the frames (start, u1, n1, end; (n, d) each) stacked
    (4, n, d), and where the transition leaves a and meets b as fractions of them (2, n))."""
    jb = ja + 1
    n, n_axes = ja.size, table.n_axes
    u_a = table.length[ja] - d
    pa, ta, ka, fa = table.plane_frames(ja, u_a)
    pb, tb, kb, fb = table.plane_frames(jb, d)
    i = np.arange(n)
    u1 = np.zeros((n, n_axes))
    norm = np.hypot(ta[i, f], ta[i, s])
    u1[i, f] = ta[i, f] / norm
    u1[i, s] = ta[i, s] / norm
    n1 = np.zeros((n, n_axes))
    n1[i, f], n1[i, s] = -u1[i, s], u1[i, f]             # left of u1 in the plane
    cos_t = np.clip((tb * u1).sum(axis=1), -1.0, 1.0)
    dpsi = np.arctan2((tb * n1).sum(axis=1), cos_t)
    rel = pb - pa
    length, coeffs, made = solve_transitions(ka, kb, dpsi, (rel * u1).sum(axis=1), (rel * n1).sum(axis=1))
    chord = np.hypot(rel[i, f], rel[i, s])
    made &= (0.5 * chord < length) & (length < 3.0 * chord)    # else a loop or a detour
    # what is left of each move must be a move
    made &= (u_a > MIN_LINE_MM) & (table.length[jb] - d > MIN_LINE_MM)
    dev = np.full(n, math.nan)
    k = np.flatnonzero(made)
    if k.size:
        m = _SAMPLES
        sk = np.linspace(0.0, length[k], m, axis=1).ravel()
        rep = np.repeat(k, m)
        q = poly_positions(pa[rep], u1[rep], n1[rep], coeffs[rep], sk).reshape(k.size, m, n_axes)
        q[:, -1] = pb[k]                                  # its end is b's point exactly
        flat = q.reshape(-1, n_axes)
        near = np.minimum(_distance_rows(flat, table, ja[rep]), _distance_rows(flat, table, jb[rep]))
        dev[k] = near.reshape(k.size, m).max(axis=1)
        made[k] = dev[k] <= tol[k]
    return made, dev, length, coeffs, dpsi, np.stack([pa, u1, n1, pb]), np.stack([fa, fb])


def _head(m: Move, u: float, end: np.ndarray, frac: float | None = None) -> Move | None:
    """``m`` up to path length u, ending at ``end`` (an arc: at angle fraction ``frac``, found
    again where not given); None where too short to be a move."""
    if u <= MIN_LINE_MM:
        return None
    if m.arc is None:
        return replace(m, end=end.copy(), length_mm=float(np.linalg.norm(end - m.start)))
    return head_move(m, u, (end, frac) if frac is not None else None)


def _candidates(program: Program, tol: np.ndarray, rotary: np.ndarray, event_after: np.ndarray
                ) -> list[tuple[int, int, int, float]]:
    """The joints a transition may ease but for their kink: (joint j, plane axes f, s, P there)."""
    moves = program.moves
    out = []
    curve = (MoveKind.LINE, MoveKind.ARC)
    for j in range(len(moves) - 1):
        a, b = moves[j], moves[j + 1]
        p_tol = min(tol[j], tol[j + 1])
        if (p_tol <= 0.0 or a.kind not in curve or b.kind not in curve
                or (a.arc is None and b.arc is None) or a.blend is not None or b.blend is not None
                or a.exact_stop or event_after[j]
                or any(np.any((m.end - m.start)[rotary] != 0.0) for m in (a, b))
                or np.abs(a.end - b.start).max() > 1e-9 * (1.0 + np.abs(a.end).max())):
            continue
        if any(m.arc is not None and abs(m.arc.sweep_rad) > 2.0 * math.pi for m in (a, b)):
            continue
        plane = _plane(a, b, len(program.axes))
        if plane is not None:
            out.append((j, plane[0], plane[1], p_tol))
    return out


def ease_joints(program: Program, machine: MachineSpec, speeds: SpeedOracle | None = None) -> Program:
    """The program with its line-arc, arc-line and arc-arc joints under G64 P eased (see the
    module's text; with ``speeds``, only where the transition is quicker than the sharp
    joint's plan); ``program`` itself when none is. The joints are solved together, a batch
    at a time, on a table of their moves alone."""
    moves = program.moves
    n = len(moves)
    if n < 2 or not any(v > 0 for _, v in program.blend_tolerance):
        return program
    tol, rotary, event_after = joint_context(program)
    cands = _candidates(program, tol, rotary, event_after)
    if not cands:
        return program
    joint = np.array([c[0] for c in cands], dtype=np.int64)
    rows = np.unique(np.concatenate([joint, joint + 1]))
    table = MoveTable.from_moves([moves[int(i)] for i in rows], len(program.axes))
    row_a = np.searchsorted(rows, joint)                  # the joint's first move; the next row its second
    t_start, t_end = table.end_tangents()
    kink_all = np.arccos(np.clip((t_end[row_a] * t_start[row_a + 1]).sum(axis=1), -1.0, 1.0))
    keep = np.flatnonzero(kink_all <= MAX_KINK_RAD)
    joint, row_a, kink_all = joint[keep], row_a[keep], kink_all[keep]
    plane_f = np.array([cands[i][1] for i in keep], dtype=np.int64)
    plane_s = np.array([cands[i][2] for i in keep], dtype=np.int64)
    tol_all = np.array([cands[i][3] for i in keep])
    made: dict[int, tuple[Move, Move, Move]] = {}
    kinks: dict[int, tuple[float, float]] = {}
    for lo in range(0, joint.size, _BATCH):
        part = slice(lo, lo + _BATCH)
        ja, ra, f, s = joint[part], row_a[part], plane_f[part], plane_s[part]
        p_tol, kink = tol_all[part], kink_all[part]
        room = 0.45 * np.minimum(table.length[ra], table.length[ra + 1])   # the rest is for the other ends
        d = np.minimum(room, 50.0 * p_tol)
        # the stretch shrinks until the transition keeps within 0.9 P: by 0.6 a try, or at once
        # to where its deviation would fit (about d for a kink, d^2 for a curvature step alone)
        power = np.where(kink > KINKED_RAD, 1.0, 0.5)
        small = 1e-9 * (1.0 + np.abs(table.end[ra]).max(axis=1))
        live = np.ones(ja.size, dtype=bool)
        for _ in range(10):
            live &= d > small
            k = np.flatnonzero(live)
            if not k.size:
                break
            ok, dev, length, coeffs, turn, frames, fracs = _try(table, ra[k], f[k], s[k], d[k],
                                                                0.9 * p_tol[k])
            for x in np.flatnonzero(ok):
                j = int(ja[k[x]])
                trio = _trio(moves[j], moves[j + 1], float(d[k[x]]), float(length[x]), coeffs[x],
                             float(turn[x]), frames[:, x], fracs[:, x], float(dev[x]))
                if trio is not None:
                    made[j] = trio
                    kinks[j] = (float(kink[k[x]]), float(d[k[x]]))
            live[k[ok]] = False
            fit = 0.9 * p_tol[k] / np.where(dev > 0.0, dev, 1.0)
            d[k] *= np.where(dev > 0.0, np.minimum(0.6, 0.95 * fit ** power[k]), 0.6)
    if not made:
        return program
    if speeds is not None:
        made = _quicker(program, speeds(program), machine, made, kinks)
        if not made:
            return program
    return _apply(program, made)


def _trio(a: Move, b: Move, d: float, length: float, coeffs: np.ndarray, turn: float, frames: np.ndarray,
          fracs: np.ndarray, dev: float) -> tuple[Move, Move, Move] | None:
    """(a's head, the transition, b's tail) of a joint solved by ``_try``."""
    pa, u1, n1, pb = (v.copy() for v in frames)
    c = (float(coeffs[0]), float(coeffs[1]), float(coeffs[2]), float(coeffs[3]))
    bl = Blend(origin=pa, u1=u1, n1=n1, half_mm=0.5 * length, turn_rad=max(abs(turn), 1e-12),
               corner=a.end.copy(), poly=c, measured_deviation_mm=dev)
    mv = Move(index=0, line=a.line, kind=MoveKind.BLEND, start=pa.copy(), end=pb,
              feed_mm_s=min(a.feed_mm_s, b.feed_mm_s), length_mm=length, arc=None, exact_stop=False, blend=bl)
    head = _head(a, a.length_mm - d, pa, float(fracs[0]))
    tail = split_move(b, d, (pb, float(fracs[1])))
    if head is None or tail.length_mm <= MIN_LINE_MM:
        return None
    return head, mv, tail


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
                frac = None
                if cur.arc is not None and head.arc is not None and m.arc is not None and cur.arc.sweep_rad:
                    # angle fractions: the tail is m from t_b on, the head m up to t_a
                    frac = (head.arc.sweep_rad - m.arc.sweep_rad + cur.arc.sweep_rad) / cur.arc.sweep_rad
                cur_head = _head(cur, cur.length_mm - (m.length_mm - head.length_mm), head.end, frac)
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
