"""G05 (cubic), G05.1 (quadratic), G05.2/G05.3 (NURBS) curves, run as the arcs and lines
LinuxCNC's motion layer makes of them (``planner.geometry.splines``).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from planner.core.errors import BlockError
from planner.core.program import (
    Curve,
    _make_arc,
    spiral_length_mm,
)
from planner.gcode.codes import (
    G,
    gname,
)
from planner.gcode.motion import MotionCodes
from planner.gcode.state import (
    ARC,
    LINE,
    ZERO_FEED,
    ZERO_LEN,
)
from planner.geometry.arcs import (
    sweep_angle,
)
from planner.geometry.splines import nurbs_pieces

#: a curve's arcs above this radius (1 km: LinuxCNC's biarc where the curve hardly bends) are
#: fed as the lines they nearly are: a stretch of 10 mm departs from such an arc by at most
#: 12.5 nm (100 mm: 1.25 um), and a centre that far away leaves the arc's own measure of its
#: contour error (a distance from the centre) rounding above a nanometre
CURVE_MAX_RADIUS_MM = 1e6


class CurveCodes(MotionCodes):
    def spline(self, motion: int, previous_motion: int | None, vals: dict[str, float], axis_words: list[str],
               line_no: int) -> None:
        """G05 (cubic: I J the first control point from the start, P Q the second from the end),
        G05.1 (quadratic: I J the middle control point) and G05.2 (one NURBS control point, weight
        P, order L) as LinuxCNC 2.9 reads them; the curve is run as LinuxCNC runs it
        (``planner.geometry.splines``). Control points in program units and coordinates."""
        name = gname(motion)
        if self.comp.radius > 0.0:
            # LinuxCNC refuses G05/G05.1 so and runs a G05.2 NURBS uncompensated
            raise BlockError(f"cannot run a curve ({name}) with cutter radius compensation on: program G40 "
                             "first", name)
        if self.modal.feed_mode == G.G93:
            raise BlockError(f"{name} in inverse time feed mode (G93): program G94 or G95 for curves", name)
        if self.modal.plane != G.G17:
            raise BlockError(f"{name}: curves only in the XY plane (G17)", name)
        for letter in axis_words:
            if letter not in "XY":
                raise BlockError(f"{name}: a curve moves in X and Y only, not {letter}", letter)
        if self.modal.feed_mm_s <= 0.0:
            raise BlockError(ZERO_FEED, name)
        px, py = self.prog_xy(self.pos)
        x0, y0 = px / self.modal.scale, py / self.modal.scale

        def end(letter: str, here: float) -> float:
            if letter not in vals:
                return here
            return vals[letter] if self.modal.absolute else here + vals[letter]

        if motion == G.G5_2:
            self.nurbs_point(previous_motion, vals, x0, y0, end, line_no)
            return
        x3, y3 = end("X", x0), end("Y", y0)
        if motion == G.G5_1:
            if "I" not in vals or "J" not in vals:
                raise BlockError("G05.1 needs both I and J (the middle control point, from the start)",
                                 "I" if "I" in vals else "J" if "J" in vals else "G5.1")
            points = [(x0, y0, 1.0), (x0 + vals["I"], y0 + vals["J"], 1.0), (x3, y3, 1.0)]
            self.nurbs_feed(points, 3, line_no)
            return
        if ("I" in vals) != ("J" in vals):
            raise BlockError("G05 needs both I and J, or neither (then the first control point mirrors the "
                             "last G05's P and Q)", "I" if "I" in vals else "J")
        i, j = (vals["I"], vals["J"]) if "I" in vals else self.curve.spline_ij
        if "P" not in vals or "Q" not in vals:
            raise BlockError("G05 needs both P and Q (the second control point, from the end point)",
                             "P" if "P" in vals else "Q" if "Q" in vals else "G5")
        p, q = vals["P"], vals["Q"]
        points = [(x0, y0, 1.0), (x0 + i, y0 + j, 1.0), (x3 + p, y3 + q, 1.0), (x3, y3, 1.0)]
        self.nurbs_feed(points, 4, line_no)
        self.curve.spline_ij = (-p, -q)

    def nurbs_point(self, previous_motion: int | None, vals: dict[str, float], x0: float, y0: float,
                    end: Callable[[str, float], float], line_no: int) -> None:
        """A G05.2 block: the first one opens the NURBS at the current point (weight P when the
        block has no X and Y, else 1); X and Y add a control point of weight P. In G91 every
        point counts from where the curve begins: the tool does not move until G05.3."""
        has_x, has_y = "X" in vals, "Y" in vals
        if has_x != has_y:
            raise BlockError("G05.2 needs both X and Y for a control point", "Y" if has_x else "X")
        weight = vals.get("P")
        if self.curve.nurbs is None or previous_motion != G.G5_2:
            self.curve.nurbs = [(x0, y0,
                                 weight if weight is not None and weight > 0.0 and not has_x else 1.0)]
            self.curve.order = 3
            self.curve.line = line_no
        elif not has_x and weight is not None:
            raise BlockError("a weight P without X and Y only on the block that begins the NURBS", "P")
        if "L" in vals:
            order = vals["L"]
            if order != int(order):
                raise BlockError(f"L (the NURBS order) must be a whole number, got L{order:g}", "L")
            if order > 3:                       # LinuxCNC: L3 or less leaves the order at 3
                self.curve.order = int(order)
        if has_x:
            if weight is None or weight <= 0.0:
                # LinuxCNC takes a missing P on the first control point as weight -1
                raise BlockError("every NURBS control point needs a positive weight P",
                                 "P" if weight is not None else "X")
            self.curve.nurbs.append((end("X", x0), end("Y", y0), weight))
        self.motion = G.G5_2

    def nurbs_end(self, g1: int | None, previous_motion: int | None, line_no: int) -> None:
        """G05.3: run the NURBS of the G05.2 blocks before it."""
        if g1 not in (None, G.G5_2):
            raise BlockError(f"{gname(g1)} beside G05.3: between G05.2 and G05.3 only G05.2 blocks",
                             gname(g1))
        if self.curve.nurbs is None or previous_motion != G.G5_2:
            raise BlockError("G05.3 without G05.2 before it: there is no NURBS to end", "G5.3")
        points, order = self.curve.nurbs, self.curve.order
        if len(points) < order:
            raise BlockError(f"a NURBS of order L = {order} needs at least {order} control points, the "
                             f"start included; it has {len(points)}", "G5.3")
        if self.comp.radius > 0.0:
            raise BlockError("cannot run a NURBS with cutter radius compensation on: program G40 first",
                             "G5.3")
        if self.modal.feed_mm_s <= 0.0:
            raise BlockError(ZERO_FEED, "G5.3")
        self.curve.nurbs = None
        self.motion = None if g1 is None else G.G5_2   # LinuxCNC: no motion mode after G05.3
        self.nurbs_feed(points, order, line_no)

    def nurbs_feed(self, points: list[tuple[float, float, float]], order: int, line_no: int) -> None:
        """The arcs and lines LinuxCNC's motion layer makes of the curve, in machine coordinates."""
        pname, fa, sa, na, *_ = self.plane_axes()
        scale = self.modal.scale
        feed = self.modal.feed_mm_s
        first = len(self.rec.out)
        pieces = nurbs_pieces(np.array(points, dtype=float), order)
        last_x, last_y = points[-1][0], points[-1][1]
        for k, piece in enumerate(pieces):
            ex, ey = piece.end
            if k == len(pieces) - 1 and math.hypot(ex - last_x, ey - last_y) <= 1e-9 * max(1.0, abs(last_x),
                                                                                           abs(last_y)):
                ex, ey = last_x, last_y            # the curve ends on its last control point
            target = list(self.pos)
            target[fa], target[sa] = self.machine_xy(ex * scale, ey * scale)
            length = self.path_length(self.pos, target)
            if length <= ZERO_LEN:
                continue
            if piece.center is None:
                self.emit(target, LINE, feed, length, None, line_no)
                continue
            cx, cy = self.machine_xy(piece.center[0] * scale, piece.center[1] * scale)
            x0, y0 = self.pos[fa], self.pos[sa]
            r0 = math.hypot(x0 - cx, y0 - cy)
            if r0 > CURVE_MAX_RADIUS_MM:
                # where the curve hardly bends, LinuxCNC's biarc is an arc of kilometres: the
                # line it nearly is
                self.emit(target, LINE, feed, length, None, line_no)
                continue
            r1 = math.hypot(target[fa] - cx, target[sa] - cy)
            if abs(r1 - r0) <= 1e-9 * r0:
                r1 = r0
            a0, sweep = sweep_angle(x0, y0, target[fa], target[sa], cx, cy, not piece.ccw, 1)
            arc = _make_arc(pname, fa, sa, na, (cx, cy), r0, r1, a0, sweep, 0.0, 1)
            length = r0 * abs(sweep) if r0 == r1 else spiral_length_mm(r0, r1, sweep, 0.0)
            self.emit(target, ARC, feed, length, arc, line_no)
        in_mm = tuple((x * scale, y * scale, w) for x, y, w in points)
        self.rec.splines.append(Curve(first, len(self.rec.out), in_mm, order))
