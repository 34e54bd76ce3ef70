"""Cutter radius compensation (G41, G42, G41.1, G42.1, G40) computed as LinuxCNC 2.9 does it.

The tool centre runs one tool radius to the left (G41) or right (G42) of the programmed path
in the XY (G17) or XZ (G18) plane:

- the first move after G41/G42 is the entry: a line ends perpendicular to its own direction,
  an arc ends on the offset of its end point with a new centre;
- a convex corner is driven round on an arc about the programmed corner (a rapid goes
  straight to the arc's end instead);
- at a concave corner the move before is cut back to where the tool touches both sides, so
  each move stays queued until the next one shows the corner. A corner the tool cannot fit
  (the cut-back would reverse a move, or an arc cannot be reached) is refused as a gouge;
- G40 ends it: the next move must be a straight line, from the offset point to the
  programmed point.

The geometry follows LinuxCNC's convert_straight_comp1/2, convert_arc_comp1/2 and its move
queue (interp_convert.cc, interp_queue.cc), including its tolerances: corners within 0.05 rad
of straight need no arc, and an arc whose end moves more than 0.0254 rad (0.001 in inch programs)
beyond its programmed sweep gouges. Two choices differ on purpose: the corner arc carries no motion of
axes outside the plane (the next move carries it all, so a rotary axis moves on a straight
line), and a compensated arc that would turn a full circle more than the programmed one is
refused instead of cut.

Positions here are machine coordinates. The offsets that may apply (work offset, G92, tool
length) are translations and the XY rotation is a rotation, so the offset path is the same
shape as LinuxCNC computes in program coordinates; offsets cannot change while compensation
is on (LinuxCNC refuses it too).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

from planner.core.errors import BlockError
from planner.core.movestore import MoveBuffer
from planner.core.program import Arc, MoveKind, _make_arc, spiral_length_mm
from planner.gcode.codes import G
from planner.geometry.arcs import FULL_CIRCLE_MM

__all__ = ["CutterComp", "CompHost", "LEFT", "RIGHT", "find_turn"]

LEFT, RIGHT = 1, -1
_SMALL = 0.05          # rad: LinuxCNC's TOLERANCE_CONCAVE_CORNER
_EQUAL = 1e-6          # LinuxCNC's TOLERANCE_EQUAL
_ARC_BACK_MM = 0.0254  # rad: how far an arc's end may move past its programmed sweep
_HALF_PI = 0.5 * math.pi
_TWO_PI = 2.0 * math.pi



class _Moves(Protocol):
    @property
    def out(self) -> MoveBuffer: ...


class _Units(Protocol):
    @property
    def inch(self) -> bool: ...

    @property
    def scale(self) -> float: ...

    @property
    def feed_mode(self) -> int: ...

    @property
    def feed_mm_s(self) -> float: ...

    @property
    def inverse_f(self) -> float: ...


class _Fixed(Protocol):
    @property
    def start(self) -> tuple[float, ...]: ...

    @property
    def zero_length(self) -> float: ...


class CompHost(Protocol):
    """What compensation uses of the interpreter: where the tool is, the moves made (to cut
    back a queued one), the units and feed, and the interpreter's own move and arc rules."""

    pos: list[float]

    @property
    def rec(self) -> _Moves: ...

    @property
    def modal(self) -> _Units: ...

    @property
    def setup(self) -> _Fixed: ...

    def emit(self, target: list[float], kind: MoveKind, feed: float, length: float, arc: Arc | None,
             line_no: int, fixed_feed: bool = False) -> None: ...

    def drop_move(self, i: int) -> None: ...

    def path_length(self, a: Sequence[float], b: Sequence[float]) -> float: ...

    def plane_axes(self) -> tuple: ...

    def arc_center(self, x0: float, y0: float, x1: float, y1: float, vals: dict[str, float], cw: bool,
                   scale: float) -> tuple[float, float, float, float]: ...


def find_turn(x1: float, y1: float, cx: float, cy: float, turn: int, x2: float, y2: float) -> float:
    """Signed sweep (rad, + counter-clockwise) of the arc about (cx, cy) from (x1, y1) to
    (x2, y2) turning ``turn`` times (+ counter-clockwise); start = end is a whole turn."""
    if turn == 0:
        return 0.0
    alpha = math.atan2(y1 - cy, x1 - cx)
    beta = math.atan2(y2 - cy, x2 - cx)
    if turn > 0:
        if beta <= alpha:
            beta += _TWO_PI
        return beta - alpha + (turn - 1) * _TWO_PI
    if alpha <= beta:
        alpha += _TWO_PI
    return beta - alpha + (turn + 1) * _TWO_PI


def _inside(side: int, turn: int) -> bool:
    """The tool runs inside the arc (towards its centre)."""
    return (side == LEFT and turn > 0) or (side == RIGHT and turn < 0)


@dataclass(slots=True)
class _Queued:
    """A move whose end may still move to a concave corner."""

    index: int
    dx: float                                  # a line's programmed direction in the plane
    dy: float
    center: tuple[float, float] | None = None  # an arc's centre, turn and programmed sweep
    turn: int = 0
    sweep0: float = 0.0                         # 0: the end may move without a gouge check


class CutterComp:
    """The compensation state of one program run and its queue of movable moves."""

    def __init__(self) -> None:
        self.side = 0                  # LEFT, RIGHT, 0: off
        self.radius = 0.0              # mm; 0 with compensation on runs the programmed path
        self.first = True              # the next move is the entry move
        self.axes = (0, 1)             # the plane's first and second axis (columns)
        # the programmed point (first, second) while compensating, and after G40 until the
        # exit move: incremental moves and missing words count from it, not from the tool
        self.programmed: tuple[float, float] | None = None
        self.queue: list[_Queued] = []
        self.endpoint: tuple[float, float] | None = None   # start of the queued moves, if known
        self.arc_banned = False        # G40 was given: the next move must be straight
        self.busy = False              # any of the above: the interpreter's fast paths stay off

    def _update(self) -> None:
        self.busy = self.side != 0 or self.programmed is not None or self.arc_banned

    # ------------------------------------------------------------------ on and off
    def turn_on(self, side: int, radius_mm: float, axes: tuple[int, int]) -> None:
        if radius_mm < 0.0:            # a negative radius swaps the side (LinuxCNC)
            radius_mm = -radius_mm
            side = -side
        self.side = side
        self.radius = radius_mm
        self.first = True
        self.axes = axes
        self._update()

    def turn_off(self, host: CompHost) -> None:
        if self.side != 0 and self.radius > 0.0 and not self.first:
            fa, sa = self.axes
            self.move_endpoint_and_flush(host, host.pos[fa], host.pos[sa])
            self.dequeue()
            self.arc_banned = True
            # self.programmed stays: the exit move goes from the tool to the programmed point
        else:
            self.programmed = None
        self.side = 0
        self.radius = 0.0
        self.first = True
        self._update()

    def straight_done(self) -> None:
        """A straight move without compensation: the tool is at the programmed point again."""
        self.programmed = None
        self.arc_banned = False
        self._update()

    def stop(self, host: CompHost) -> None:
        """M0, M1, M2, M30: the queued moves are final (LinuxCNC's convert_stop)."""
        if self.queue:
            fa, sa = self.axes
            self.move_endpoint_and_flush(host, host.pos[fa], host.pos[sa])
        self.dequeue()

    def base(self, pos: list[float]) -> list[float]:
        """The position incremental words and missing axis words count from."""
        if self.programmed is None:
            return pos
        base = pos.copy()
        fa, sa = self.axes
        base[fa], base[sa] = self.programmed
        return base

    # ------------------------------------------------------------------ the queue
    def dequeue(self) -> None:
        self.queue.clear()
        self.endpoint = None

    def move_endpoint_and_flush(self, host: CompHost, x: float, y: float) -> None:
        """Move the end of every queued move to (x, y) in the plane, then make them final."""
        if not self.queue:
            return
        try:
            self._check_moved_ends(host, x, y)
        except BlockError:
            self.dequeue()       # the queued moves stay as they are; no second error from them
            raise
        fa, sa = self.axes
        out = host.rec.out
        for q in self.queue:
            moved = out.end(q.index).copy()
            moved[fa], moved[sa] = x, y
            out.replace(q.index, moved, out.record(q.index)[3], out.arcs.get(q.index))
        for q in self.queue:
            self._rebuild(host, q)
        host.pos = out.last_end()
        for q in reversed(self.queue):
            if out.record(q.index)[3] <= host.setup.zero_length:
                host.drop_move(q.index)
        self.queue.clear()
        self.endpoint = (x, y)

    def _check_moved_ends(self, host: CompHost, x: float, y: float) -> None:
        """LinuxCNC's gouge checks: a line must not turn back, an arc must not grow."""
        fa, sa = self.axes
        ep = self.endpoint
        # LinuxCNC adds this to the sweep (rad) as it is: 0.0254 in mm programs, 0.001 in inch
        tol = 0.001 if host.modal.inch else _ARC_BACK_MM
        for q in self.queue:
            end = host.rec.out.end(q.index)
            if q.center is not None:
                cx, cy = q.center
                r1 = math.hypot(end[fa] - cx, end[sa] - cy)
                r2 = math.hypot(x - cx, y - cy)
                if abs(r1 - r2) > 0.01 * host.modal.scale:
                    raise BlockError(f"cutter compensation made an arc whose radius changes from {r1:.4f} "
                                     f"to {r2:.4f} mm (an error of this control: please report the "
                                     "program)", "G")
                if q.sweep0 != 0.0 and ep is not None:
                    l2 = find_turn(ep[0], ep[1], cx, cy, q.turn, x, y)
                    if abs(l2) > abs(q.sweep0) + tol:
                        raise BlockError("arc move in a concave corner cannot be reached by the tool "
                                         "without gouging (the tool is too big for this corner)", "G")
            elif ep is not None and q.dx * (x - ep[0]) + q.dy * (y - ep[1]) < 0.0:
                what = "rapid" if host.rec.out.record(q.index)[1] is MoveKind.RAPID else "straight feed"
                raise BlockError(f"{what} in a concave corner cannot be reached by the tool without "
                                 "gouging (the corner's sides are shorter than the tool needs)", "G")

    def _rebuild(self, host: CompHost, q: _Queued) -> None:
        i = q.index
        out = host.rec.out
        start = out.end(i - 1) if i else list(host.setup.start)
        end = out.end(i)
        if q.center is None:
            out.replace(i, end, host.path_length(start, end), None)
        else:
            arc, length = self._arc_record(host, start, end, q.center, q.turn, q.sweep0)
            out.replace(i, end, length, arc)

    def _arc_record(self, host: CompHost, start: list[float], end: list[float],
                    center: tuple[float, float], turn: int, sweep0: float = 0.0) -> tuple:
        """The arc and its length; ``sweep0`` the programmed sweep, which decides whether an
        arc that ends where it starts (to rounding) is a whole turn or nothing."""
        pname, fa, sa, na, *_ = host.plane_axes()
        x0, y0, x1, y1 = start[fa], start[sa], end[fa], end[sa]
        cx, cy = center
        if abs(x1 - x0) <= FULL_CIRCLE_MM and abs(y1 - y0) <= FULL_CIRCLE_MM:
            # rounding must not turn a programmed full circle into nothing, nor the reverse
            whole = abs(turn) if abs(sweep0) > math.pi else abs(turn) - 1
            sweep = math.copysign(whole * _TWO_PI, turn)
        else:
            sweep = find_turn(x0, y0, cx, cy, turn, x1, y1)
        r0 = math.hypot(x0 - cx, y0 - cy)
        r1 = math.hypot(x1 - cx, y1 - cy)
        if abs(r1 - r0) <= 1e-9 * max(1.0, r0):
            r1 = r0
        rise = end[na] - start[na] if na >= 0 else 0.0
        arc = _make_arc(pname, fa, sa, na, (cx, cy), r0, r1, math.atan2(y0 - cy, x0 - cx), sweep, rise,
                        abs(turn))
        length = math.hypot(r0 * sweep, rise) if r0 == r1 else spiral_length_mm(r0, r1, sweep, rise)
        return arc, length

    # ------------------------------------------------------------------ emitting
    def _line(self, host: CompHost, end: list[float], rapid: bool, feed: float, line_no: int,
              dx: float, dy: float, queued: bool = True) -> None:
        length = host.path_length(host.pos, end)
        if length <= host.setup.zero_length:
            return
        host.emit(end, MoveKind.RAPID if rapid else MoveKind.LINE, math.inf if rapid else feed, length,
                  None, line_no, fixed_feed=True)
        if queued:
            self.queue.append(_Queued(len(host.rec.out) - 1, dx, dy))

    def _arc(self, host: CompHost, end: list[float], center: tuple[float, float], turn: int,
             feed: float, line_no: int, sweep0: float, queued: bool = True) -> None:
        arc, length = self._arc_record(host, host.pos, end, center, turn, sweep0)
        if sweep0 != 0.0 and abs(arc.sweep_rad) > abs(sweep0) + math.pi:
            raise BlockError("with cutter compensation this arc would turn a whole circle more than "
                             "programmed: the arc is too short for the tool's radius", "G")
        if length <= host.setup.zero_length:
            return
        host.emit(end, MoveKind.ARC, feed, length, arc, line_no, fixed_feed=True)
        if queued:
            self.queue.append(_Queued(len(host.rec.out) - 1, 0.0, 0.0, center, turn, sweep0))

    def _feed(self, host: CompHost, rapid: bool, programmed_mm: float) -> float:
        if rapid:
            return math.inf
        if host.modal.feed_mode == G.G93:    # the block's time over its programmed length
            return programmed_mm * host.modal.inverse_f / 60.0
        return host.modal.feed_mm_s

    # ------------------------------------------------------------------ straight moves
    def straight(self, host: CompHost, target: list[float], rapid: bool, line_no: int) -> None:
        fa, sa = self.axes
        pos = host.pos
        base = self.base(pos)
        feed = self._feed(host, rapid, host.path_length(base, target))
        px, py = target[fa], target[sa]
        cx, cy = pos[fa], pos[sa]
        r = self.radius
        side = self.side
        if self.first:
            cx, cy = base[fa], base[sa]     # after G40 and G41 at once: the programmed point
            distance = math.hypot(px - cx, py - cy)
            if distance <= r:
                raise BlockError(f"the cutter compensation entry move ({distance:.4f} mm in the plane) is "
                                 f"not longer than the tool radius ({r:.4f} mm)", "G")
            alpha = math.atan2(py - cy, px - cx) + (_HALF_PI if side == LEFT else -_HALF_PI)
            end = target.copy()
            end[fa], end[sa] = px + r * math.cos(alpha), py + r * math.sin(alpha)
            self.dequeue()
            self.endpoint = (cx, cy)
            self._line(host, end, rapid, feed, line_no, math.cos(alpha), math.sin(alpha))
            self.first = False
            self.programmed = (px, py)
            self._update()
            return
        assert self.programmed is not None
        opx, opy = self.programmed
        if px == opx and py == opy:    # no motion in the plane: the tool stays where it is
            end = target.copy()
            end[fa], end[sa] = cx, cy
            self._line(host, end, rapid, feed, line_no, 0.0, 0.0)
            return
        theta = math.atan2(cy - opy, cx - opx)
        alpha = math.atan2(py - opy, px - opx)
        if side == LEFT:
            if theta < alpha:
                theta += _TWO_PI
            beta = theta - alpha - _HALF_PI
            gamma = _HALF_PI
        else:
            if alpha < theta:
                alpha += _TWO_PI
            beta = alpha - theta - _HALF_PI
            gamma = -_HALF_PI
        end = target.copy()
        end[fa] = px + r * math.cos(alpha + gamma)
        end[sa] = py + r * math.sin(alpha + gamma)
        mid_x = opx + r * math.cos(alpha + gamma)
        mid_y = opy + r * math.sin(alpha + gamma)
        front = self.queue[0] if self.queue else None
        if beta < -_SMALL or beta > math.pi + _SMALL:
            concave = True
        else:
            # an "h" shape: over the round top, then down beside the stem; stay outside
            concave = (beta > math.pi - _SMALL and front is not None and front.center is not None
                       and ((side == RIGHT and front.turn > 0) or (side == LEFT and front.turn < 0)))
        if not concave and beta > _SMALL:          # convex corner: round it
            self.move_endpoint_and_flush(host, cx, cy)
            corner = pos.copy()
            corner[fa], corner[sa] = mid_x, mid_y
            if rapid:      # no arc at rapid: straight to the arc's end, parallel to the path after
                self._line(host, corner, True, feed, line_no, 0.0, 0.0, queued=False)
            else:
                self._arc(host, corner, (opx, opy), -1 if side == LEFT else 1, feed, line_no, 0.0,
                          queued=False)
            self.dequeue()
            self.endpoint = (mid_x, mid_y)
        elif concave:
            if front is None or front.center is None:     # line to line: cut the last one back
                halfcorner = (beta + math.pi) / 2.0
                if halfcorner == 0.0:
                    raise BlockError("a zero-degree inside corner cannot be cut with cutter compensation",
                                     "G")
                retreat = r / math.tan(halfcorner)
                self.move_endpoint_and_flush(host, cx + retreat * math.cos(theta + gamma),
                                             cy + retreat * math.sin(theta + gamma))
            else:                                          # arc to line
                pcx, pcy = front.center
                oldrad = math.hypot(pcx - cx, pcy - cy)
                base_dir = math.atan2(py - opy, px - opx)
                th = base_dir + _HALF_PI if front.turn > 0 else base_dir - _HALF_PI
                phi = math.atan2(pcy - opy, pcx - opx)
                inside = _inside(side, front.turn)
                oldrad_uncomp = oldrad + r if inside else oldrad - r
                d = oldrad_uncomp * math.cos(th - phi)
                d2 = d - r if inside else d + r
                ratio = d2 / oldrad if oldrad else math.inf
                if not -1.0 <= ratio <= 1.0:
                    raise BlockError("arc to straight motion makes a corner the compensated tool cannot fit "
                                     "in without gouging", "G")
                if inside == (front.turn > 0):
                    angle = -math.acos(ratio) + th + math.pi
                else:
                    angle = math.acos(ratio) + th + math.pi
                self.move_endpoint_and_flush(host, pcx + oldrad * math.cos(angle),
                                             pcy + oldrad * math.sin(angle))
        else:                                              # straight on, or tangent
            self.dequeue()
            self.endpoint = (cx, cy)
        self._line(host, end, rapid, feed, line_no, px - opx, py - opy)
        self.programmed = (px, py)

    # ------------------------------------------------------------------ arcs
    def arc(self, host: CompHost, target: list[float], vals: dict[str, float], cw: bool, turns: int,
            scale: float, line_no: int) -> None:
        fa, sa = self.axes
        pos = host.pos
        side = self.side
        r = self.radius
        turn = -turns if cw else turns
        ex, ey = target[fa], target[sa]
        cx, cy = pos[fa], pos[sa]
        inside = _inside(side, turn)
        _pname, _f, _s, na, *_ = host.plane_axes()
        rise = target[na] - pos[na] if na >= 0 else 0.0
        if self.first:
            if math.hypot(ex - cx, ey - cy) <= r:
                raise BlockError("the radius of the cutter compensation entry arc is not greater than the "
                                 f"tool radius ({r:.4f} mm)", "G")
            if "R" in vals and abs(vals["R"] * scale) <= r and inside:
                raise BlockError(f"tool radius ({r:.4f} mm) not less than the arc radius with cutter "
                                 "compensation", "R")
            ccx, ccy, r0, _r1 = host.arc_center(cx, cy, ex, ey, vals, cw, scale)
            if inside and r0 <= r:
                raise BlockError(f"tool radius ({r:.4f} mm) not less than the arc radius ({r0:.4f} mm) "
                                 "with cutter compensation", "G")
            sweep0 = find_turn(cx, cy, ccx, ccy, turn, ex, ey)
            feed = self._feed(host, False, math.hypot(r0 * sweep0, rise))
            if inside:
                gamma = math.atan2(ccy - ey, ccx - ex)
            else:
                gamma = math.atan2(ey - ccy, ex - ccx)
            nx, ny = ex + r * math.cos(gamma), ey + r * math.sin(gamma)
            # the new centre: on the line from the new end towards the old centre, as far from
            # the start as from the new end
            b_len = math.hypot(cy - ny, cx - nx) / 2.0
            ab_ang = math.atan2(ccy - ny, ccx - nx)
            a_ang = math.atan2(cy - ny, cx - nx) - ab_ang
            if abs(math.cos(a_ang)) < _EQUAL:
                raise BlockError("tool radius not less than the arc radius with cutter compensation", "G")
            c_len = b_len / math.cos(a_ang)
            ncx, ncy = nx + c_len * math.cos(ab_ang), ny + c_len * math.sin(ab_ang)
            end = target.copy()
            end[fa], end[sa] = nx, ny
            self.dequeue()
            self._arc(host, end, (ncx, ncy), turn, feed, line_no, find_turn(cx, cy, ncx, ncy, turn, nx, ny))
            self.first = False
            self.programmed = (ex, ey)
            self._update()
            return
        assert self.programmed is not None
        opx, opy = self.programmed
        ccx, ccy, _r0, _r1 = host.arc_center(opx, opy, ex, ey, vals, cw, scale)
        sweep0 = find_turn(opx, opy, ccx, ccy, turn, ex, ey)
        arc_radius = math.hypot(ccx - ex, ccy - ey)
        feed = self._feed(host, False, math.hypot(arc_radius * sweep0, rise))
        theta = math.atan2(cy - opy, cx - opx)
        theta = theta - _HALF_PI if side == LEFT else theta + _HALF_PI
        delta = math.atan2(ccy - opy, ccx - opx)
        alpha = delta - _HALF_PI if not cw else delta + _HALF_PI
        beta = theta - alpha if side == LEFT else alpha - theta
        if beta > 1.5 * math.pi:
            beta -= _TWO_PI
        elif beta < -_HALF_PI:
            beta += _TWO_PI
        if inside:
            gamma = math.atan2(ccy - ey, ccx - ex)
            if arc_radius <= r:
                raise BlockError(f"tool radius ({r:.4f} mm) not less than the arc radius "
                                 f"({arc_radius:.4f} mm) with cutter compensation", "G")
        else:
            gamma = math.atan2(ey - ccy, ex - ccx)
            delta += math.pi
        nx, ny = ex + r * math.cos(gamma), ey + r * math.sin(gamma)
        end = target.copy()
        end[fa], end[sa] = nx, ny
        front = self.queue[0] if self.queue else None
        if (beta < -_SMALL or beta > math.pi + _SMALL
                or (abs(beta - math.pi) < _SMALL and not inside)):
            # concave (or the top of an "m" or an "h"): cut the move before back
            if front is None or front.center is None:      # line to arc
                cyy = arc_radius * math.sin(beta - _HALF_PI)
                if inside:
                    dist = arc_radius - r
                    ratio = (cyy + r) / dist
                else:
                    dist = arc_radius + r
                    ratio = (cyy - r) / dist
                if not -1.0 <= ratio <= 1.0:
                    raise BlockError("arc move in a concave corner cannot be reached by the tool without "
                                     "gouging", "G")
                if inside:
                    angle = theta + math.asin(ratio) if turn > 0 else theta - math.asin(ratio)
                else:
                    angle = (theta + math.pi - math.asin(ratio) if turn > 0
                             else theta + math.pi + math.asin(ratio))
                self.move_endpoint_and_flush(host, ccx + dist * math.cos(angle), ccy + dist * math.sin(angle))
            else:                                            # arc to arc
                pcx, pcy = front.center
                oldrad = math.hypot(pcx - cx, pcy - cy)
                newrad = arc_radius - r if inside else arc_radius + r
                arc_cc = math.hypot(pcx - ccx, pcy - ccy)
                if oldrad == 0.0 or arc_cc == 0.0:
                    raise BlockError("arc to arc motion is invalid because the arcs have the same centre",
                                     "G")
                a = (oldrad * oldrad + arc_cc * arc_cc - newrad * newrad) / (2.0 * oldrad * arc_cc)
                if not -1.0 <= a <= 1.0:
                    raise BlockError("arc to arc motion makes a corner the compensated tool cannot fit in "
                                     "without gouging", "G")
                pullback = math.acos(a)
                cc_dir = math.atan2(ccy - pcy, ccx - pcx)
                if _inside(side, front.turn) == (turn > 0):
                    direction = cc_dir + pullback
                else:
                    direction = cc_dir - pullback
                self.move_endpoint_and_flush(host, pcx + oldrad * math.cos(direction),
                                             pcy + oldrad * math.sin(direction))
        elif beta > _SMALL:                                  # convex: round the corner first
            mid_x, mid_y = opx + r * math.cos(delta), opy + r * math.sin(delta)
            self.dequeue()
            corner = pos.copy()
            corner[fa], corner[sa] = mid_x, mid_y
            self._arc(host, corner, (opx, opy), -1 if side == LEFT else 1, feed, line_no, 0.0, queued=False)
            self.endpoint = (mid_x, mid_y)
        else:                                                # tangent
            self.dequeue()
            self.endpoint = (cx, cy)
        self._arc(host, end, (ccx, ccy), turn, feed, line_no, sweep0)
        self.programmed = (ex, ey)
