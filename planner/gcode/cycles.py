"""Canned cycles G73, G74, G81-G86, G89 (LinuxCNC 2.9's interp_cycles.cc), G38.2-G38.5 probe
moves, G33.1 rigid tapping, G33 and the G76 threading cycle.
"""

from __future__ import annotations

import math

import numpy as np

from planner.core.errors import BlockError, PlannerError
from planner.core.program import (
    Dwell,
    Event,
    EventKind,
    EventPayload,
    ProbeRequest,
    SpindleSpeed,
    SynchronisedMotion,
    TableRef,
)
from planner.gcode.codes import (
    CYCLE_NEEDS_P,
    CYCLE_NEEDS_Q,
    CYCLE_TAKES_P,
    PLANE_NAMES,
    PLANES,
    G,
    gname,
)
from planner.gcode.motion import MotionCodes
from planner.gcode.state import (
    LINE,
    P_PROBE,
    P_PROBE_TRIPPED,
    PARAM_AXES,
    TAP_LOCK,
    ZERO_FEED,
    ZERO_LEN,
)

#: G73 backs off and G83 comes back down to this far above the last peck: LinuxCNC 2.9's
#: G83_RAPID_DELTA, 0.010 inch in every unit (later versions read it from their INI file)
PECK_CLEARANCE_MM = 0.254
#: pecks or repeats of one block above this are refused (a typo such as Q0.0001 on a deep
#: hole would otherwise make millions of moves)
MAX_CYCLE_MOVES = 100_000


class CycleCodes(MotionCodes):
    def canned_cycle(self, motion: int, first: bool, vals: dict[str, float], axis_words: list[str],
                     scale: float, line_no: int, turn: tuple[float, float] | None = None) -> None:
        """G73, G74, G81-G86, G89 as LinuxCNC 2.9 runs them (interp_cycles.cc): in the selected
        plane, the hole axis is the plane's normal; R, the bottom, P and Q are sticky while the
        same cycle stays the motion mode; L repeats (incremental G91 steps the position each
        time); G98 returns to the level the cycles started from (or R if that is higher), G99 to
        R. Every move of the cycle is an exact stop, as LinuxCNC's exact path mode. ``first``: the
        cycle was not the motion mode before this block, so R, the bottom, P and Q must be given.
        ``turn``: G91 polar words (radius step in mm, angle step in radians): each repeat's hole
        is the one before moved out by the radius and turned by the angle about the origin."""
        name = gname(motion)
        if self.modal.feed_mm_s <= 0.0:
            raise BlockError(ZERO_FEED, name)
        if self.modal.comp_code != G.G40:
            raise BlockError("cannot use canned cycles with cutter compensation on "
                             f"({gname(self.modal.comp_code)})", name)
        pname, fa, sa, na, *_ = self.plane_axes()
        plane_g = PLANE_NAMES[self.modal.plane]
        normal = PLANES[self.modal.plane][3]
        if na < 0:
            raise BlockError(f"{plane_g} canned cycle is not possible on a machine without {normal} axis",
                             name)
        first_l, second_l = PLANES[self.modal.plane][1], PLANES[self.modal.plane][2]
        if "R" in vals:
            self.cycle.r_word = vals["R"] * scale
        elif first:
            raise BlockError(f"{name} needs an R word (the retract plane) the first time", name)
        if normal in vals:
            self.cycle.z_word = vals[normal] * scale
        elif first:
            raise BlockError(f"{name} needs a {normal} word (the bottom of the hole) the first time "
                             f"in {plane_g}", name)
        repeats = vals.get("L", 1.0)
        if repeats != int(repeats) or repeats < 1:
            raise BlockError(f"L{repeats:g}: the repeats of a cycle are a whole number of 1 or more", "L")
        if repeats > MAX_CYCLE_MOVES:
            raise BlockError(f"L{repeats:g}: more than {MAX_CYCLE_MOVES} repeats in one block", "L")
        if motion in CYCLE_TAKES_P:
            if "P" in vals:
                if vals["P"] < 0.0:
                    raise BlockError(f"negative dwell time P{vals['P']:g}", "P")
                self.cycle.p = vals["P"]
            elif first and motion in CYCLE_NEEDS_P:
                raise BlockError(f"{name} needs a P word (the dwell at the bottom, s) the first time", name)
        if motion in CYCLE_NEEDS_Q:
            if "Q" in vals:
                self.cycle.q = vals["Q"] * scale
            elif first:
                raise BlockError(f"{name} needs a Q word (the peck depth) the first time", name)
            if self.cycle.q <= 0.0:
                raise BlockError(f"{name}: negative or zero Q (peck depth)", "Q")
        if motion in (G.G74, G.G84):
            want = -1 if motion == G.G74 else 1
            if self.modal.spindle_dir == 0:
                raise BlockError(f"spindle not turning in {name} (tapping needs M0{3 if want > 0 else 4})",
                                 name)
            if self.modal.spindle_dir != want:
                raise BlockError(f"spindle turning {'clockwise' if want < 0 else 'counterclockwise'} in "
                                 f"{name}", name)
        if motion == G.G86 and self.modal.spindle_dir == 0:
            raise BlockError("spindle not turning in G86", name)
        off = self.offsets.total
        pos = self.pos
        rotated = self.offsets.rotation != 0.0
        ix, iy = self.setup.axis_index.get("X", -1), self.setup.axis_index.get("Y", -1)
        # in G18/G19 of a rotated system the hole axis or the plane's second axis is a turned X or Y
        here_prog = self.program_position(pos)
        current_cc = here_prog[na]
        if self.cycle.il is None:
            self.cycle.il = current_cc
        old_cc = self.cycle.il
        if self.modal.absolute:
            aa_inc = bb_inc = 0.0
            r = self.cycle.r_word
            cc = self.cycle.z_word
            cur_a, cur_b = here_prog[fa], here_prog[sa]
            aa = vals[first_l] * scale if first_l in vals else cur_a
            bb = vals[second_l] * scale if second_l in vals else cur_b
        else:
            aa_inc = vals.get(first_l, 0.0) * scale
            bb_inc = vals.get(second_l, 0.0) * scale
            r = self.cycle.r_word + old_cc
            cc = r + self.cycle.z_word
            aa, bb = here_prog[fa], here_prog[sa]
        if r < cc:
            raise BlockError(f"R ({r / scale:g}) below the bottom {normal} ({cc / scale:g}) of the canned "
                             f"cycle in {plane_g}", "R" if "R" in vals else name)
        delta = self.cycle.q
        rapid_delta = PECK_CLEARANCE_MM
        if motion in CYCLE_NEEDS_Q and repeats * (r - cc) / delta > MAX_CYCLE_MOVES:
            raise BlockError(f"{name}: Q{delta / scale:g} over a depth of {(r - cc) / scale:g} makes more "
                             f"than {MAX_CYCLE_MOVES} pecks", "Q")

        def go(a: float, b: float, c: float, rapid: bool) -> None:
            target = self.pos.copy()
            if rotated:                      # the plane's point in program coordinates, then turned
                q = self.program_position(self.pos)
                q[fa], q[sa], q[na] = a, b, c
                target[ix], target[iy] = self.machine_xy(q[ix], q[iy])
                for i in (fa, sa, na):
                    if i not in (ix, iy):
                        target[i] = q[i] + off[i]
            else:
                target[fa] = a + off[fa]
                target[sa] = b + off[sa]
                target[na] = c + off[na]
            self.straight(target, rapid, line_no)

        def event(kind: EventKind, payload: EventPayload, text: str) -> None:
            self.rec.events.append(Event(kind, line_no, len(self.rec.out) - 1, payload, text))

        if old_cc < r:                         # below the R plane: straight up to it first
            go(here_prog[fa], here_prog[sa], r, True)
            old_cc = current_cc = r
        clear_cc = r if self.modal.retract_r_plane else old_cc
        saved_stop = self.modal.exact_stop
        self.modal.exact_stop = True
        direction, rpm = self.modal.spindle_dir, self.modal.spindle_rpm
        try:
            for k in range(int(repeats)):
                aa += aa_inc
                bb += bb_inc
                for step, letter in zip(turn or (), "@^"):
                    if not step:                # LinuxCNC: a zero step is no step
                        continue
                    if aa == 0.0 and bb == 0.0:
                        raise BlockError("incremental motion with polar coordinates is indeterminate at "
                                         "the origin", letter)
                    radius, theta = math.hypot(aa, bb), math.atan2(bb, aa)
                    radius, theta = (radius + step, theta) if letter == "@" else (radius, theta + step)
                    aa, bb = radius * math.cos(theta), radius * math.sin(theta)
                if k == 0 and current_cc > r:
                    go(aa, bb, current_cc, True)
                    go(aa, bb, r, True)
                else:
                    go(aa, bb, clear_cc, True)
                    if clear_cc > r:
                        go(aa, bb, r, True)
                if motion in (G.G73, G.G83):
                    if self.comp.busy or (rotated and na in (ix, iy)):   # pecks along a turned axis
                        depth = r - delta
                        while depth > cc:
                            go(aa, bb, depth, False)
                            if motion == G.G83:
                                go(aa, bb, r, True)
                            go(aa, bb, depth + rapid_delta, True)
                            depth -= delta
                    else:
                        self.pecks(na, off[na], r, cc, delta, rapid_delta, motion == G.G83, line_no)
                    go(aa, bb, cc, False)
                    go(aa, bb, clear_cc, True)
                elif motion in (G.G74, G.G84):
                    # LinuxCNC turns both overrides off for the tap: its feed is the pitch times
                    # the speed
                    self.overrides_event(line_no, len(self.rec.out) - 1,
                                         f"{name}: feed and spindle overrides "
                                         "off while tapping", TAP_LOCK,
                                         EventKind.TAPPING)
                    go(aa, bb, cc, False)
                    event(EventKind.SPINDLE, SpindleSpeed(-direction, rpm),
                          f"{name}: spindle reversed to back the tap out (tapping as feed moves at F, not "
                          "synchronised with the spindle: use a floating tap holder)")
                    if self.cycle.p > 0.0:
                        event(EventKind.DWELL, Dwell(self.cycle.p), f"dwell {self.cycle.p:g} s")
                    go(aa, bb, clear_cc, False)
                    event(EventKind.SPINDLE, SpindleSpeed(direction, rpm),
                          f"{name}: spindle turning forward again")
                    self.overrides_event(line_no, len(self.rec.out) - 1,
                                         f"{name}: overrides as before the tap",
                                         kind=EventKind.TAPPING)
                else:
                    go(aa, bb, cc, False)
                    if motion in (G.G82, G.G86, G.G89) and self.cycle.p > 0.0:
                        event(EventKind.DWELL, Dwell(self.cycle.p), f"dwell {self.cycle.p:g} s")
                    if motion == G.G85:
                        go(aa, bb, r, False)
                        go(aa, bb, clear_cc, True)
                    elif motion == G.G86:
                        event(EventKind.SPINDLE, SpindleSpeed(0, 0.0), "G86: spindle stopped to retract")
                        go(aa, bb, clear_cc, True)
                        event(EventKind.SPINDLE, SpindleSpeed(direction, rpm), "G86: spindle restarted")
                    elif motion == G.G89:
                        go(aa, bb, clear_cc, False)
                    else:                      # G81, G82
                        go(aa, bb, clear_cc, True)
        finally:
            self.modal.exact_stop = saved_stop

    def pecks(self, na: int, off_na: float, r: float, cc: float, delta: float, rapid_delta: float,
              out_to_r: bool, line_no: int) -> None:
        """The pecks of G73 / G83 (``out_to_r``) above the bottom ``cc``, from the R plane ``r``,
        all at once: feed down by ``delta`` each time, then back off (G73: ``rapid_delta`` up;
        G83: out to R and rapid back down to ``rapid_delta`` above the peck). The depths are
        LinuxCNC's, by the same repeated subtraction; moves of no length are left out, as
        ``straight`` leaves them out. Thousands of pecks (a small Q on a deep hole) take
        milliseconds instead of seconds."""
        n_est = int((r - cc) / delta) + 2
        depths = np.subtract.accumulate(np.concatenate(([r], np.full(n_est, delta))))[1:]
        depths = depths[depths > cc]
        if not len(depths):
            return
        if self.modal.feed_mm_s <= 0.0:
            raise BlockError(ZERO_FEED, "G")
        per = 3 if out_to_r else 2
        z = np.empty(len(depths) * per)
        z[0::per] = depths
        if out_to_r:
            z[1::per] = r
        z[per - 1::per] = depths + rapid_delta
        ends = np.repeat(np.asarray([self.pos], dtype=float), len(z), axis=0)
        ends[:, na] = z + off_na
        rapid = np.ones(len(z), dtype=bool)
        rapid[0::per] = False
        self.straight_runs(ends, rapid, np.full(len(z), line_no), np.full(len(z), self.modal.feed_mm_s))

    def probe(self, code: int, target: list[float], line_no: int) -> None:
        """G38.2-G38.5 as LinuxCNC 2.9 runs them: a straight move at the feed, the probe armed at
        rest before it; at rest after it, #5061-#5069 hold where the input changed (program
        coordinates) and #5070 whether it did, and the move ends where the machine stopped.
        What the machine did is known for the first ``probe_results``; the others are read as
        LinuxCNC's own preview and rs274 read them: the move goes to its programmed end point,
        #5061-#5069 hold that point and #5070 is 0 (a loop probing while #5070 says it touched
        ends; the run reads the rest again with the machine's result)."""
        name = gname(code)
        if self.comp.side != 0:
            raise BlockError(f"cannot probe ({name}) with cutter radius compensation on: program G40 "
                             "first", name)
        if self.modal.feed_mm_s <= 0.0:
            raise BlockError(f"cannot probe ({name}) with zero feed rate: program an F word", name)
        if self.comp.busy:
            self.comp.straight_done()
        if code in (G.G38_2, G.G38_4) and all(abs(t - p) <= ZERO_LEN for t, p in zip(target, self.pos)):
            raise BlockError(f"{name}: start point too close to probe point (the move has no length)", name)
        k = len(self.rec.probes)
        result = self.setup.probe_results[k] if k < len(self.setup.probe_results) else None
        known = result is not None
        if result is not None:
            if len(result.stop_position) != self.setup.n or len(result.trip_position) != self.setup.n:
                raise PlannerError(f"probe result {k} has positions for {len(result.stop_position)} axes, "
                                   f"the machine has {self.setup.n}")
            end, trip, tripped = list(result.stop_position), list(result.trip_position), result.tripped
        else:
            end, trip, tripped = list(target), list(target), False
        self.rec.events.append(Event(EventKind.PROBE_START, line_no, len(self.rec.out) - 1, TableRef(k),
                                     f"{name}: probe armed"))
        moved = self.straight_one(end, LINE, self.modal.feed_mm_s, line_no)
        self.rec.probes.append(ProbeRequest(code, line_no, len(self.rec.out) - 1 if moved else -1,
                                            tuple(float(v) for v in target), known))
        self.rec.events.append(Event(EventKind.PROBE, line_no, len(self.rec.out) - 1, TableRef(k),
                                     f"{name}: probe result"))
        # #5061-#5069 in the coordinates of the system in use, in the program's units (an axis the
        # machine does not have reads 0)
        at = self.program_position(trip)
        for p, letter in enumerate(PARAM_AXES):
            i = self.setup.axis_index.get(letter)
            value = 0.0 if i is None else at[i] if self.setup.rotary[i] else at[i] / self.modal.scale
            self.params.numbered[P_PROBE + p] = float(value)
        self.params.numbered[P_PROBE_TRIPPED] = 1.0 if tripped else 0.0

    def rigid_tap(self, target: list[float], vals: dict[str, float], scale: float, line_no: int) -> None:
        """G33.1 X Y Z K I, LinuxCNC's rigid tapping, as feed moves: this spindle has no encoder to
        synchronise with, so the tap goes in at the pitch K times the programmed speed, the
        spindle reverses (I times faster, I >= 1) and it comes out the same way to where it
        started, where the spindle turns forward again (a floating tap holder takes up the
        difference)."""
        if self.css_max_rpm is not None:
            raise BlockError("G33.1 in G96: the tap's pitch needs a known speed; program G97 and S in rpm",
                             "G33.1")
        if self.modal.spindle_dir == 0 or self.modal.spindle_rpm <= 0.0:
            raise BlockError("spindle not turning in G33.1 (rigid tapping needs M3 or M4 and S)", "G33.1")
        if self.comp.side != 0:
            raise BlockError("cannot tap (G33.1) with cutter radius compensation on: program G40 first",
                             "G33.1")
        if any(target[i] != self.pos[i] for i in self.setup.rotary_idx):
            raise BlockError("G33.1 moves the linear axes only", "G33.1")
        pitch = vals["K"] * scale
        if pitch <= 0.0:
            raise BlockError(f"G33.1: the pitch K{vals['K']:g} must be above 0", "K")
        speed_up = max(vals.get("I", 1.0), 1.0)          # LinuxCNC: below 1 counts as 1
        start = list(self.pos)
        length = self.path_length(start, target)
        if length <= ZERO_LEN:
            return
        if self.comp.busy:
            self.comp.straight_done()
        rpm = self.modal.spindle_rpm
        into = pitch * rpm / 60.0
        self.rec.taps.append(len(self.rec.out))
        saved_stop, self.modal.exact_stop = self.modal.exact_stop, True
        # the tap's feed follows the spindle: neither override may change one without the other
        self.overrides_event(line_no, len(self.rec.out) - 1,
                             "G33.1: feed and spindle overrides off while tapping",
                             TAP_LOCK, EventKind.TAPPING)
        try:
            self.emit(target, LINE, into, length, None, line_no, fixed_feed=True)
            self.rec.events.append(Event(EventKind.SPINDLE, line_no, len(self.rec.out) - 1,
                                         SpindleSpeed(-self.modal.spindle_dir, rpm * speed_up),
                                         "G33.1: spindle reversed to back the tap out (tapping as feed "
                                         "moves at the pitch, not synchronised with the spindle: use a "
                                         "floating tap holder)"))
            self.emit(start, LINE, into * speed_up, length, None, line_no, fixed_feed=True)
            self.rec.events.append(Event(EventKind.SPINDLE, line_no, len(self.rec.out) - 1,
                                         SpindleSpeed(self.modal.spindle_dir, rpm),
                                         "G33.1: spindle turning forward again"))
        finally:
            self.overrides_event(line_no, len(self.rec.out) - 1, "G33.1: overrides as before the tap",
                                 kind=EventKind.TAPPING)
            self.modal.exact_stop = saved_stop

    def synchronised_speed(self, name: str) -> float:
        """The spindle speed (rpm) a G33 or G76 moves at: the spindle must turn (LinuxCNC's
        rule), and at a speed, or the feed it gives would be 0."""
        if self.modal.spindle_dir == 0:
            raise BlockError(f"spindle not turning in {name} (M3 or M4 first)", name)
        if self.modal.spindle_rpm <= 0.0:
            raise BlockError(f"{name} with the spindle at S0: the feed, the pitch times the speed, "
                             "would be 0", name)
        return self.modal.spindle_rpm

    def synchronised_move(self, target: list[float], feed: float, line_no: int) -> None:
        """A feed move of G33 or G76 at ``feed`` (mm/s), whatever F and the feed mode say."""
        self.straight_one(target, LINE, feed, line_no, fixed_feed=True)

    def synchronised_feed(self, target: list[float], vals: dict[str, float], scale: float,
                          line_no: int) -> None:
        """G33 X Y Z K, LinuxCNC's spindle-synchronised motion: a straight move at the pitch K
        (length per turn) times the spindle speed. Recorded in ``synchronised``: the machine,
        whose spindle has no encoder, refuses to run it (a thread's passes would not meet)."""
        rpm = self.synchronised_speed("G33")
        if self.comp.side != 0:
            raise BlockError("cannot use G33 with cutter radius compensation on: program G40 first", "G33")
        pitch = vals["K"] * scale
        if pitch <= 0.0:
            raise BlockError(f"G33: the pitch K{vals['K']:g} must be above 0", "K")
        if self.comp.busy:
            self.comp.straight_done()
        self.rec.synchronised.append(SynchronisedMotion("G33", line_no))
        self.synchronised_move(target, pitch * rpm / 60.0, line_no)

    def thread_cycle(self, target: list[float], vals: dict[str, float], scale: float, line_no: int) -> None:
        """G76 P I J K [R Q H E L], LinuxCNC 2.9's threading cycle (interp_convert.cc), in X and
        Z from where the tool stands (the drive line): P the pitch; I the thread's offset from
        the drive line (negative: an outside thread, positive: boring); J the first cut's depth
        and K the thread's full depth; R the depth degression (the n-th pass cuts to
        J n^(1/R)); Q the compound slide angle (degrees); H spring passes at full depth; E the
        taper's length along Z, L which ends have it (1 entry, 2 exit, 3 both). Each pass goes
        back to the drive line, rapid in to its depth, feeds along Z at the pitch times the
        speed, and rapid out; the cycle ends with a rapid to the block's end point. In G7 I J K
        are diameters. Recorded in ``synchronised``: the machine refuses to run it."""
        rpm = self.synchronised_speed("G76")
        if any(target[i] != self.pos[i] for i in self.setup.rotary_idx):
            raise BlockError("cannot move rotary axes with G76", "G76")
        if "X" not in self.setup.axis_index or "Z" not in self.setup.axis_index:
            raise BlockError(f"G76 threads along Z and cuts in X: this machine has no "
                             f"{'X' if 'X' not in self.setup.axis_index else 'Z'} axis", "G76")
        if self.comp.side != 0:
            raise BlockError("cannot use the G76 threading cycle with cutter radius compensation on: "
                             "program G40 first", "G76")
        i_w, j_w, k_w = vals["I"], vals["J"], vals["K"]
        if i_w == 0.0:
            raise BlockError("G76: I (the thread's offset from the drive line) must not be 0", "I")
        if j_w <= 0.0:
            raise BlockError("G76: J (the first cut's depth) must be greater than 0", "J")
        if k_w <= j_w:
            raise BlockError("G76: K (the full thread depth) must be greater than J", "K")
        if vals["P"] <= 0.0:
            raise BlockError(f"G76: the pitch P{vals['P']:g} must be above 0", "P")
        spring = vals.get("H", 0.0)
        if spring != int(spring) or spring < 0.0:
            raise BlockError(f"G76: H{spring:g} (spring passes) must be a whole number of 0 or more", "H")
        flags = vals.get("L", 0.0)
        if flags != int(flags) or flags < 0.0:
            raise BlockError(f"G76: L{flags:g} (taper ends) must be a whole number of 0 or more", "L")
        half = 0.5 if self.modal.diameter else 1.0
        i_mm, j_mm, k_mm = i_w * scale * half, j_w * scale * half, k_w * scale * half
        ix, iz, iy = self.setup.axis_index["X"], self.setup.axis_index["Z"], self.setup.axis_index.get("Y")
        here, end = self.program_position(self.pos), self.program_position(target)
        safe_x, start_z = here[ix], here[iz]
        start_y = here[iy] if iy is not None else 0.0
        boring = i_mm > 0.0
        full_dia_depth = abs(i_mm)
        cut_increment = abs(j_mm)
        full_threadheight = abs(k_mm)
        end_depth = full_threadheight + full_dia_depth
        pitch = vals["P"] * scale
        angle = vals.get("Q", 0.0)
        angle = math.radians(0.0 if angle == -1.0 else angle)    # LinuxCNC reads Q-1 as no Q
        if end[iz] > start_z:
            angle = -angle
        degression = vals.get("R", 1.0)
        degression = max(degression, 1.0)
        taper_dist = max(vals.get("E", 0.0) * scale, 0.0)
        taper_pitch = (pitch * math.hypot(taper_dist, full_threadheight) / taper_dist if taper_dist > 0.0
                       else pitch)
        if end[iz] > start_z:
            taper_dist = -taper_dist
        entry_taper, exit_taper = int(flags) & 1, int(flags) & 2
        target_z = end[iz] + full_threadheight * math.tan(angle)
        # the passes' depths: J n^(1/R) below the first, then the full depth 1 + H times
        depths = []
        depth, n = full_dia_depth + cut_increment, 1
        while depth < end_depth:
            depths.append(depth)
            if len(depths) > MAX_CYCLE_MOVES // 6:
                raise BlockError(f"G76: J{j_w:g} to K{k_w:g} (R{degression:g}) makes more than "
                                 f"{MAX_CYCLE_MOVES // 6} passes", "J")
            n += 1
            depth = full_dia_depth + cut_increment * n ** (1.0 / degression)
        if len(depths) + spring + 1 > MAX_CYCLE_MOVES // 6:
            raise BlockError(f"G76: H{spring:g} makes more than {MAX_CYCLE_MOVES // 6} passes", "H")
        depths += [end_depth] * (int(spring) + 1)
        off = self.offsets.total
        rotated = self.offsets.rotation != 0.0

        def point(x: float, z: float) -> list[float]:
            q = self.program_position(self.pos)
            q[ix], q[iz] = x, z
            if iy is not None:
                q[iy] = start_y
            out = list(self.pos)
            if rotated and iy is not None:     # the XY rotation turns X (and Y) with the system
                out[ix], out[iy] = self.machine_xy(q[ix], q[iy])
            else:
                out[ix] = q[ix] + off[ix]
                if iy is not None:
                    out[iy] = q[iy] + off[iy]
            out[iz] = q[iz] + off[iz]
            return out

        sign = 1.0 if boring else -1.0
        feed = pitch * rpm / 60.0
        taper_feed = taper_pitch * rpm / 60.0
        self.rec.synchronised.append(SynchronisedMotion("G76", line_no))
        saved_stop, self.modal.exact_stop = self.modal.exact_stop, True
        try:
            for depth in depths:
                zoff = (depth - full_dia_depth) * math.tan(angle)
                at_depth = safe_x + sign * depth
                clear = safe_x + sign * (depth - end_depth)
                top = safe_x + sign * (depth - full_threadheight)
                self.straight(point(clear, start_z - zoff), True, line_no)            # back
                if taper_dist and entry_taper:
                    self.synchronised_move(point(top, start_z - zoff), taper_feed, line_no)       # in
                    self.synchronised_move(point(at_depth, start_z - zoff - taper_dist), taper_feed,
                                           line_no)                                          # angled in
                else:
                    self.straight(point(at_depth, start_z - zoff), True, line_no)     # in
                if taper_dist and exit_taper:
                    self.synchronised_move(point(at_depth, target_z - zoff + taper_dist), feed, line_no)
                    self.synchronised_move(point(top, target_z - zoff), taper_feed, line_no)  # angled out
                else:
                    self.synchronised_move(point(at_depth, target_z - zoff), feed, line_no)   # over
                self.straight(point(clear, target_z - zoff), True, line_no)          # out
            self.straight(target, True, line_no)
        finally:
            self.modal.exact_stop = saved_stop
