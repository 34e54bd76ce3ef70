"""Motion and arcs: G00/G01 straight moves, G02/G03 arcs in the three planes (R or centre words,
turns, the XY rotation), the target of a block's axis words, polar words; every move reaches the
program through ``emit``, straight moves through the recorder of straight runs
(``straight_runs``, and ``straight_one`` for a move at a time).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from planner.core.errors import BlockError
from planner.core.program import (
    Arc,
    MoveKind,
    _make_arc,
    spiral_length_mm,
)
from planner.gcode.codes import PLANE_NAMES, PLANES, G
from planner.gcode.modes import ModeCodes
from planner.gcode.state import (
    ARC,
    LINE,
    MAX_TURNS,
    RAPID,
    ZERO_FEED,
    ZERO_LEN,
    short_way,
)
from planner.geometry.arcs import (
    ArcError,
    center_from_radius,
    check_center_radii,
    sweep_angle,
)

_G93 = G.G93  # looked up once: an enum member's lookup costs 60 ns in CPython 3.11

class MotionCodes(ModeCodes):
    def target(self, vals: dict[str, float], axis_words: list[str], scale: float,
               machine: bool) -> list[float]:
        """The machine position a block's axis words go to (program units and coordinates;
        ``machine``: G53, machine coordinates), from where the tool is (or, under cutter
        compensation, from the programmed point)."""
        pos = self.comp.base(self.pos)
        tgt = pos.copy()
        setup = self.setup
        idx, rot = setup.axis_index, setup.rotary
        rotated = not machine and self.offsets.rotation != 0.0 and ("X" in axis_words or "Y" in axis_words)
        absolute = self.modal.absolute
        # a word's value (mm, deg) is added to the offsets (absolute), the position (incremental)
        # or nothing (G53)
        base = None if machine else self.offsets.total if absolute else pos
        for letter in axis_words:
            if rotated and letter in "XY":
                continue
            i = idx[letter]
            v = vals[letter] if rot[i] else vals[letter] * scale
            tgt[i] = v if base is None else v + base[i]
            if base is not pos and setup.wrapped[i]:        # absolute, on an axis without end
                tgt[i] = short_way(pos[i], tgt[i])
        if rotated:                      # X and Y in the rotated system, then to the machine
            px, py = self.prog_xy(pos)
            for letter in ("X", "Y"):
                if letter in axis_words:
                    v = vals[letter] * scale
                    if letter == "X":
                        px = v if absolute else px + v
                    else:
                        py = v if absolute else py + v
            tgt[idx["X"]], tgt[idx["Y"]] = self.machine_xy(px, py)
        return tgt

    def path_length(self, a: Sequence[float], b: Sequence[float]) -> float:
        if self.setup.all_linear:
            return math.dist(a, b)
        lin = self.setup.linear_idx
        length = math.sqrt(sum((b[i] - a[i]) ** 2 for i in lin)) if lin else 0.0
        if length > ZERO_LEN:
            return length
        rot = self.setup.rotary_idx
        rot_len = math.sqrt(sum((b[i] - a[i]) ** 2 for i in rot))
        return rot_len if rot_len > ZERO_LEN else length

    def straight(self, target: list[float], rapid: bool, line_no: int) -> None:
        """G00 (``rapid``) or G01 to ``target``: under cutter compensation, its offset path;
        else the straight-move recorder's rules for one move (``straight_runs``), in plain
        floats: a move shorter than ``ZERO_LEN`` is dropped (LinuxCNC refuses a G01 without a
        feed even then)."""
        comp = self.comp
        feed = math.inf if rapid else self.modal.feed_mm_s
        if comp.busy:
            if comp.radius > 0.0:
                if feed <= 0.0:
                    raise BlockError(ZERO_FEED, "G")
                comp.straight(self, target, rapid, line_no)
                return
            comp.straight_done()
        if feed <= 0.0:
            raise BlockError(ZERO_FEED, "G")
        self.straight_one(target, RAPID if rapid else LINE, feed, line_no)

    def straight_one(self, target: list[float], kind: MoveKind, feed: float, line_no: int,
                     fixed_feed: bool = False) -> bool:
        """One straight move to ``target`` by the rules of ``straight_runs``, in plain floats (the
        interpreter reads most lines one at a time: no array a move): left out when no longer
        than ``ZERO_LEN`` (the tool stays where it is), else recorded by ``emit``. Whether it
        was recorded."""
        length = math.dist(self.pos, target) if self.setup.all_linear else self.path_length(self.pos, target)
        if length <= ZERO_LEN:
            return False
        self.emit(target, kind, feed, length, None, line_no, fixed_feed)
        return True

    def emit(self, target: list[float], kind: MoveKind, feed: float, length: float, arc: Arc | None,
             line_no: int, fixed_feed: bool = False) -> None:
        """Every move the program makes one at a time: G93's feed from the move's length, the
        move recorded (stopping exactly where the modal G61 says), the tool there."""
        modal = self.modal
        if modal.feed_mode == _G93 and kind is not RAPID and not fixed_feed:
            feed = self.inverse_time_feed(length)
        self.rec.out.append(target, line_no, kind, feed, length, arc, modal.exact_stop)
        self.pos = target

    def inverse_time_feed(self, length: float | np.ndarray) -> Any:
        """G93: the feed (mm/s) of a feed move of ``length`` that takes 1/F minutes."""
        return length * self.modal.inverse_f / 60.0

    def path_lengths(self, starts: np.ndarray, ends: np.ndarray) -> np.ndarray:
        """``path_length`` of many moves (rows): over the linear axes, or over the rotary ones
        when the linear part is shorter than ``ZERO_LEN``."""
        d = ends - starts
        if self.setup.all_linear:
            return np.sqrt(np.einsum("ij,ij->i", d, d))
        lin, rot = list(self.setup.linear_idx), list(self.setup.rotary_idx)
        length = np.sqrt(np.einsum("ij,ij->i", d[:, lin], d[:, lin])) if lin else np.zeros(len(d))
        if rot:
            turned = np.sqrt(np.einsum("ij,ij->i", d[:, rot], d[:, rot]))
            length = np.where((length <= ZERO_LEN) & (turned > ZERO_LEN), turned, length)
        return length

    def straight_runs(self, ends: np.ndarray, rapid: np.ndarray, lines: np.ndarray, feed_mm_s: np.ndarray,
                      lengths: np.ndarray | None = None, fixed_feed: bool = False) -> int:
        """The recorder of straight runs: moves from where the tool is through each row of
        ``ends`` (machine coordinates) at ``feed_mm_s`` (inf for a rapid), all at once, with the
        rules ``straight`` follows for one: a move no longer than ``ZERO_LEN`` is left out and
        the tool stays where it was (the next one measured from there); a feed move in G93
        takes 1/F minutes (unless ``fixed_feed``); each stops exactly where the modal G61 says.
        ``lengths``: the moves' lengths as the caller measured them (``path_lengths``). Returns
        how many moves were recorded."""
        n = len(ends)
        if not n:
            return 0
        if lengths is None:
            lengths = self.path_lengths(np.vstack(([self.pos], ends[:-1])), ends)
        keep = lengths > ZERO_LEN
        if not keep.all():
            # a move left out leaves the tool where it was, and the next one starts there (rare:
            # a back-off landing within 1e-9 mm of where it started): measured one by one
            lengths = lengths.copy()
            at = list(self.pos)
            for i in range(n):
                lengths[i] = self.path_length(at, ends[i])
                keep[i] = lengths[i] > ZERO_LEN
                if keep[i]:
                    at = ends[i]
        if not keep.any():
            return 0
        feed = np.where(rapid, math.inf, feed_mm_s)
        if self.modal.feed_mode == _G93 and not fixed_feed:
            feed = np.where(rapid, math.inf, self.inverse_time_feed(lengths))
        kept = int(np.count_nonzero(keep))
        if kept == n:
            self.rec.out.extend(ends, lines, np.where(rapid, 0, 1), feed, lengths, self.modal.exact_stop)
        else:
            self.rec.out.extend(ends[keep], lines[keep], np.where(rapid[keep], 0, 1), feed[keep],
                                lengths[keep], self.modal.exact_stop)
        self.pos = ends[np.flatnonzero(keep)[-1]].tolist()
        return kept

    def drop_move(self, i: int) -> None:
        """Remove move ``i`` (cutter compensation cut it to nothing); what refers to later moves
        by index moves down one."""
        self.rec.out.delete(i)
        self.pos = self.rec.out.last_end()
        self.rec.events[:] = [replace(e, after_move=e.after_move - 1) if e.after_move >= i else e
                              for e in self.rec.events]
        self.rec.frames[:] = [replace(c, first=c.first - 1) if c.first > i else c for c in self.rec.frames]
        self.rec.modal_changes[:] = [(f - 1 if f > i else f, t) for f, t in self.rec.modal_changes]
        self.rec.taps[:] = [t - 1 if t > i else t for t in self.rec.taps]
        self.rec.probes[:] = [replace(p, move_index=p.move_index - 1) if p.move_index > i else p
                              for p in self.rec.probes]

    def plane_axes(self) -> tuple:
        """(name, first, second, normal column, centre letters, forbidden letter, axis letters) of the
        current plane, cached per plane; raises if the machine lacks one of the plane's axes."""
        info = self.plane_cache.get(self.modal.plane)
        if info is None:
            pname, fl, sl, nl, fc, sc, bad = PLANES[self.modal.plane]
            fa = self.setup.axis_index.get(fl)
            sa = self.setup.axis_index.get(sl)
            if fa is None or sa is None:
                raise BlockError(
                    f"arc in plane {PLANE_NAMES[self.modal.plane]} ({pname}) needs axes {fl} and {sl}; "
                    f"this machine has {' '.join(self.setup.axes)}",
                    "G",
                )
            info = (pname, fa, sa, self.setup.axis_index.get(nl, -1), fc, sc, bad, (fl, sl))
            self.plane_cache[self.modal.plane] = info
        return info

    def arc_turns(self, vals: dict[str, float]) -> int:
        """The P word of an arc: whole turns, 1 without it."""
        if "P" not in vals:
            return 1
        p = vals["P"]
        if p != int(p) or p < 1:
            raise BlockError(f"P (number of turns) must be a whole number >= 1, got P{p:g}", "P")
        if p > MAX_TURNS:
            raise BlockError(f"P{p:g}: more than {MAX_TURNS} turns", "P")
        return int(p)

    def arc_center(self, x0: float, y0: float, x1: float, y1: float, vals: dict[str, float], cw: bool,
                   scale: float) -> tuple[float, float, float, float]:
        """Centre and (start, end) radius of the arc from (x0, y0) to (x1, y1) in the plane's
        machine coordinates, from R or the centre words, checked as LinuxCNC checks them."""
        pname, fa, sa, na, fc, sc, bad, letters = self.plane_axes()
        try:
            r_val = vals.get("R")
            if r_val is not None:
                if "I" in vals or "J" in vals or "K" in vals:
                    raise BlockError("mixed radius (R) and centre (I/J/K) format for arc", "R")
                cx, cy = center_from_radius(x0, y0, x1, y1, r_val * scale, cw)
                r0 = r1 = math.hypot(x0 - cx, y0 - cy)
                return cx, cy, r0, r1
            if bad in vals:
                raise BlockError(
                    f"{bad} word given for arc in the {pname} plane ({PLANE_NAMES[self.modal.plane]})", bad
                )
            ci = vals.get(fc)
            cj = vals.get(sc)
            if ci is None and cj is None:
                raise BlockError("arc needs R or a centre: R, I, J and K words all missing", "G")
            turned = self.offsets.rotation != 0.0 and self.modal.plane != G.G17
            if self.modal.arc_absolute:
                if ci is None or cj is None:
                    raise BlockError(f"G90.1 (absolute arc centre) needs both {fc} and {sc}",
                                     fc if ci is None else sc)
                if turned:
                    cx, cy = self.frame_centre(fa, sa, ci * scale, cj * scale)
                elif self.offsets.rotation != 0.0:
                    cx, cy = self.machine_xy(ci * scale, cj * scale)
                else:
                    cx = ci * scale + self.offsets.total[fa]
                    cy = cj * scale + self.offsets.total[sa]
            else:
                di = ci * scale if ci is not None else 0.0
                dj = cj * scale if cj is not None else 0.0
                if self.offsets.rotation != 0.0 and not turned:   # the centre offset turns with the system
                    di, dj = self.frame.turn(di, dj)
                cx = x0 + di
                cy = y0 + dj
            r0, r1 = check_center_radii(x0, y0, x1, y1, cx, cy, self.modal.inch, letters)
            if abs(r1 - r0) <= 1e-12 * r0:
                r1 = r0
            return cx, cy, r0, r1
        except ArcError as e:
            raise BlockError(str(e), "R" if "R" in vals else "G") from None

    def frame_centre(self, fa: int, sa: int, first: float, second: float) -> tuple[float, float]:
        """An absolute arc centre (G90.1) of a G18/G19 arc in a rotated system, from program
        coordinates to the arc's frame (the machine's X and Y turned back by the rotation):
        there the plane's X or Y is the program's plus a constant, and Z the machine's."""
        ix, iy = self.setup.axis_index["X"], self.setup.axis_index["Y"]
        out = []
        for col, value in ((fa, first), (sa, second)):
            if col == ix:
                out.append(self.frame_xy(*self.machine_xy(value, 0.0))[0])
            elif col == iy:
                out.append(self.frame_xy(*self.machine_xy(0.0, value))[1])
            else:
                out.append(value + self.offsets.total[col])
        return out[0], out[1]

    def frame_xy(self, x: float, y: float) -> tuple[float, float]:
        """Machine X and Y turned back by the XY rotation: the frame of a G18/G19 arc there."""
        return self.frame.turn_back(x, y)

    def arc(self, target: list[float], vals: dict[str, float], cw: bool, scale: float, line_no: int) -> None:
        pname, fa, sa, na, fc, sc, bad, letters = self.plane_axes()
        feed = self.modal.feed_mm_s
        if feed <= 0.0:
            raise BlockError(ZERO_FEED, "G")
        turns = self.arc_turns(vals) if "P" in vals else 1
        if self.comp.arc_banned:
            raise BlockError("the move just after turning cutter compensation off (G40) must be a "
                             "straight line, not an arc", "G")
        if self.comp.radius > 0.0:
            self.comp.arc(self, target, vals, cw, turns, scale, line_no)
            return
        pos = self.pos
        turn = 0.0
        frame_pos, frame_target = pos, target
        if self.offsets.rotation != 0.0 and self.modal.plane != G.G17:
            # a G18/G19 arc in a rotated system: its plane holds Z and a turned X or Y, so it is
            # made in the frame turned with the system, where that plane is an axis plane
            turn = self.frame.rotation_rad
            ix, iy = self.setup.axis_index["X"], self.setup.axis_index["Y"]
            frame_pos, frame_target = list(pos), list(target)
            frame_pos[ix], frame_pos[iy] = self.frame_xy(pos[ix], pos[iy])
            frame_target[ix], frame_target[iy] = self.frame_xy(target[ix], target[iy])
        x0 = frame_pos[fa]
        y0 = frame_pos[sa]
        x1 = frame_target[fa]
        y1 = frame_target[sa]
        if "R" in vals and ("I" in vals or "J" in vals or "K" in vals):
            raise BlockError("mixed radius (R) and centre (I/J/K) format for arc", "R")
        if ("R" in vals and (x0 != x1 or y0 != y1) and vals["R"] > 0.0
                and self.path_length(pos, target) <= ZERO_LEN):
            return  # a short R arc between points within 1e-9 mm: a zero-length move
        cx, cy, r0, r1 = self.arc_center(x0, y0, x1, y1, vals, cw, scale)
        try:
            a0, sweep = sweep_angle(x0, y0, x1, y1, cx, cy, cw, turns)
        except ArcError as e:
            raise BlockError(str(e), "R" if "R" in vals else "G") from None
        rise = frame_target[na] - frame_pos[na] if na >= 0 else 0.0
        arc = _make_arc(pname, fa, sa, na, (cx, cy), r0, r1, a0, sweep, rise, turns, turn)
        length = math.hypot(r0 * sweep, rise) if r0 == r1 else spiral_length_mm(r0, r1, sweep, rise)
        self.emit(target, ARC, feed, length, arc, line_no)

    def polar(self, vals: dict[str, float]) -> None:
        """LinuxCNC's polar words: @ radius and ^ angle (degrees) about the origin of the
        program's coordinates in the XY plane, turned into X and Y here. A missing one keeps the
        current radius or angle; in G91 both are added to the current ones."""
        if self.modal.plane != G.G17:
            raise BlockError("polar coordinates (@ ^) only in the XY plane (G17)",
                             "@" if "@" in vals else "^")
        px, py = self.prog_xy(self.pos)
        x, y = px / self.modal.scale, py / self.modal.scale
        radius, theta = math.hypot(x, y), math.atan2(y, x)
        if self.modal.absolute:
            radius = vals.pop("@", radius)
            theta = math.radians(vals.pop("^")) if "^" in vals else theta
        else:
            if radius == 0.0:
                raise BlockError("incremental motion with polar coordinates is indeterminate at the origin",
                                 "@" if "@" in vals else "^")
            radius += vals.pop("@", 0.0)
            theta += math.radians(vals.pop("^", 0.0))
        px, py = radius * math.cos(theta), radius * math.sin(theta)
        vals["X"], vals["Y"] = (px, py) if self.modal.absolute else (px - x, py - y)
