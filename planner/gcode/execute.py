"""A block read and checked (``planner.gcode.reader``) executed in RS274/NGC order, as LinuxCNC's
``interp_execute.cc`` runs it: modal memory, lathe mode and units first, then feed, speed, tool,
spindle, coolant, I/O, overrides, dwell, the modes, the offsets and stored positions, the
motion, and the program stop last. Each step is a ``convert_*`` method here or in the family
of codes it belongs to (``motion``, ``offsets``, ``tools``, ``cycles``, ``lathe``, ``curves``,
``modes``).
"""

from __future__ import annotations

import math

from planner.core.errors import BlockError
from planner.core.program import (
    AnalogOutput,
    Coolant,
    CoolantSwitch,
    Dwell,
    Event,
    EventKind,
    InputRequest,
    SpindleSpeed,
    TableRef,
    WaitMode,
)
from planner.gcode.codes import (
    CYCLES,
    LATHE_CYCLES,
    PROBES,
    SHOWN_GROUPS,
    STOP_EVENTS,
    SYNCHRONISED,
    G,
    Group,
    M,
    MGroup,
    gname,
)
from planner.gcode.curves import CurveCodes
from planner.gcode.cycles import CycleCodes
from planner.gcode.lathe import LatheCodes
from planner.gcode.offsets import OffsetCodes
from planner.gcode.reader import Block
from planner.gcode.state import P_G28, P_G30, P_INPUT
from planner.gcode.tools import ToolCodes
from planner.geometry.arcs import MM_PER_INCH

__all__ = ["Executor"]

_SPINDLE_DIRECTION: dict[int, int] = {M.M3: 1, M.M4: -1, M.M5: 0}
_COOLANT: dict[int, Coolant] = {M.M7: Coolant.MIST_ON, M.M8: Coolant.FLOOD_ON, M.M9: Coolant.ALL_OFF}


class Executor(OffsetCodes, ToolCodes, CurveCodes, CycleCodes, LatheCodes):
    """Runs one ``Block`` on the interpreter's state."""

    def execute(self, b: Block) -> None:
        """The block's codes in RS274/NGC order (LinuxCNC's ``execute_block``)."""
        after = len(self.rec.out) - 1          # the events before any move of this block
        self.convert_modal_memory(b)
        self.convert_lathe_mode(b)
        self.convert_units(b)
        self.convert_feed_mode(b)
        self.convert_feed(b)
        self.convert_speed(b, after)
        self.convert_tool_select(b, after)
        self.convert_tool_change(b, after)
        self.convert_spindle(b, after)
        self.convert_coolant(b, after)
        self.convert_io(b, after)
        self.convert_overrides(b, after)
        self.convert_user_mcode(b, after)
        self.convert_dwell(b, after)
        self.convert_plane(b)
        self.convert_cutter_comp(b)
        self.convert_tool_length(b)
        self.convert_coord_system(b)
        self.convert_path_control(b)
        self.convert_distance_modes(b)
        self.convert_retract_mode(b)
        previous_motion = self.motion      # a cycle's words are required when it was not the mode
        self.convert_motion_mode(b)
        self.convert_axis_offsets(b)
        self.convert_curve_end(b, previous_motion)
        if self.convert_motion(b, previous_motion):
            self.convert_stop(b)
        self.assign(b.assigns)

    # ------------------------------------------------------------------ before the modes
    def convert_modal_memory(self, b: Block) -> None:
        """M70-M73, before the block's own changes."""
        code = b.mgroups.get(MGroup.MODAL_STATE)
        if code is not None:
            self.modal_memory(code, b.line)

    def convert_lathe_mode(self, b: Block) -> None:
        """G7 (X words are diameters) / G8 (radii); X halved as it is read in G7."""
        vals, modal = b.vals, self.modal
        code = b.groups.get(Group.LATHE_MODE)
        if code is not None:
            diameter = code == G.G7
            if b.motion == G.G76 and diameter != modal.diameter:
                # LinuxCNC scales a G76's I J K as the mode changes in its block (and halves them
                # again in the cycle in G7): its arithmetic, kept so programs read the same
                for letter in "IJK":
                    vals[letter] *= 0.5 if diameter else 2.0
            modal.diameter = diameter
        if modal.diameter and "X" in vals:
            # LinuxCNC halves X as it reads it in G7 and undoes that for a G8 in the same
            # block: every use of the word (motion, G10, G92, G28, cycles) takes the radius
            vals["X"] *= 0.5

    def convert_units(self, b: Block) -> None:
        """G20/G21, before anything that reads a length."""
        code = b.groups.get(Group.UNITS)
        if code is not None:
            self.modal.inch = code == G.G20
            self.modal.scale = MM_PER_INCH if self.modal.inch else 1.0

    def convert_feed_mode(self, b: Block) -> None:
        """G93/G94/G95; LinuxCNC: G94 and G95 clear the feed rate, G93 does not."""
        code = b.groups.get(Group.FEED_MODE)
        if code is not None:
            modal = self.modal
            modal.feed_mode = code
            if code != G.G93:
                modal.feed_mm_s = modal.feed_per_rev = 0.0

    def convert_feed(self, b: Block) -> None:
        """F: units per minute (G94), the move's 1/F minutes (G93), units per turn (G95)."""
        if "F" not in b.vals:
            return
        f, modal = b.vals["F"], self.modal
        if f < 0.0:
            raise BlockError(f"negative feed F{f:g}", "F")
        if modal.feed_mode == G.G93:
            modal.inverse_f = f
            modal.feed_mm_s = 1.0 if f > 0.0 else 0.0   # the move's own feed comes in emit()
        elif modal.feed_mode == G.G95:
            modal.feed_per_rev = f * modal.scale
            modal.feed_mm_s = modal.feed_per_rev * modal.spindle_rpm / 60.0
        else:
            modal.feed_mm_s = f * modal.scale / 60.0

    def convert_speed(self, b: Block, after: int) -> None:
        """G96/G97, then S: a running spindle's new speed is a SPINDLE event (unless an M3/M4/M5
        in the block says it)."""
        vals, modal = b.vals, self.modal
        switched = b.mgroups.get(MGroup.SPINDLE) is not None
        code = b.groups.get(Group.SPINDLE_MODE)
        if code is not None:
            self.spindle_mode(code, vals, b.line, after, switched)
        if "S" not in vals:
            return
        s = vals["S"]
        if self.css_max_rpm is not None:
            # a cutting speed: nothing to keep, the spindle's speed does not follow it here
            if s < 0.0:
                raise BlockError(f"negative surface speed S{s:g}", "S")
            return
        if s < 0.0:
            raise BlockError(f"negative spindle speed S{s:g}", "S")
        changed = s != modal.spindle_rpm
        modal.spindle_rpm = s
        if modal.feed_mode == G.G95:
            modal.feed_mm_s = modal.feed_per_rev * s / 60.0
        if changed and modal.spindle_dir != 0 and not switched:
            self.rec.events.append(Event(EventKind.SPINDLE, b.line, after,
                                         SpindleSpeed(modal.spindle_dir, s)))

    def convert_spindle(self, b: Block, after: int) -> None:
        """M3/M4/M5."""
        code = b.mgroups.get(MGroup.SPINDLE)
        if code is None:
            return
        modal = self.modal
        modal.spindle_dir = _SPINDLE_DIRECTION[code]
        self.rec.events.append(Event(EventKind.SPINDLE, b.line, after,
                                     SpindleSpeed(modal.spindle_dir, modal.spindle_rpm), f"M0{code}"))

    def convert_coolant(self, b: Block, after: int) -> None:
        """M7 (mist) / M8 (flood) on, M9 both off."""
        code = b.mgroups.get(MGroup.COOLANT)
        if code is None:
            return
        self.rec.events.append(Event(EventKind.COOLANT, b.line, after, CoolantSwitch(_COOLANT[code]),
                                     f"M0{code}"))
        modal = self.modal
        modal.coolant = 0 if code == M.M9 else modal.coolant | (1 if code == M.M7 else 2)

    def convert_io(self, b: Block, after: int) -> None:
        """M66 waits for an input; M67/M68 set an analog output (E its number, Q its value,
        LinuxCNC: -1 without Q); M62/M64 switch a digital output on, M63/M65 off, at this
        point of the path."""
        code = b.mgroups.get(MGroup.IO)
        if code is None:
            return
        vals = b.vals
        if code == M.M66:
            self.wait_input(vals, b.line)
        elif code in (M.M67, M.M68):
            self.comp_refuses("set an analog output", f"M{code}")
            e = vals.get("E")
            if e is None or math.floor(e + 0.5) < 0:
                raise BlockError(f"M{code} needs an E word, the analog output's number (0 or more)",
                                 "E" if e is not None else f"M{code}")
            self.rec.analog_outputs.append(AnalogOutput(f"M{code}", b.line, math.floor(e + 0.5),
                                                        vals.get("Q", -1.0)))
        else:
            self.comp_refuses("set a digital output", f"M{code}")
            p = vals.get("P")
            outputs = self.setup.outputs
            if p is None or p != int(p) or int(p) not in outputs:
                known = ", ".join(f"P{k}" for k in sorted(outputs)) or "none: add [[outputs]]"
                raise BlockError(f"M{code} needs P with a configured output number ({known})",
                                 "P" if p is not None else f"M{code}")
            self.output_event(int(p), code in (M.M62, M.M64), b.line, after, f"M{code}")

    def wait_input(self, vals: dict[str, float], line_no: int) -> None:
        """M66 P L Q as LinuxCNC 2.9 reads it: the motion stops, digital input P is read now
        (L0) or waited for (L1 rise, L2 fall, L3 high, L4 low) for at most Q seconds, and #5399
        holds its value (-1 after the timeout). The machine's value is known for the first
        ``input_results``; for the others the awaited value is assumed."""
        p = vals.get("P")
        if p is None or round(p) < 0:
            raise BlockError("M66 needs a P word (the number of a digital input)", "M66")
        number = round(p)
        if number not in self.setup.inputs:
            known = ", ".join(f"P{k}" for k in sorted(self.setup.inputs)) or "none: add [[inputs]]"
            raise BlockError(f"M66 P{number}: no such digital input on this machine ({known})", "P")
        mode_n = round(vals.get("L", 0.0))
        if not 0 <= mode_n <= 4:
            raise BlockError(f"M66 L{mode_n}: the wait mode is 0 (now), 1 (rise), 2 (fall), 3 (high) or "
                             "4 (low)", "L")
        timeout = vals.get("Q", 0.0)
        if mode_n > 0 and timeout <= 0.0:
            raise BlockError("M66: zero timeout with a wait mode other than immediate (give Q, seconds)",
                             "Q" if "Q" in vals else "L")
        if self.comp.side != 0:
            raise BlockError("cannot wait for a digital input (M66) with cutter radius compensation on",
                             "M66")
        self.comp.stop(self)
        k = len(self.rec.inputs_read)
        value = self.setup.input_results[k] if k < len(self.setup.input_results) else None
        request = InputRequest(line_no, number, WaitMode(mode_n), timeout if mode_n else 0.0,
                               value is not None)
        self.rec.inputs_read.append(request)
        self.rec.events.append(Event(EventKind.INPUT, line_no, len(self.rec.out) - 1, TableRef(k),
                                     f"M66 P{number}"))
        self.params.numbered[P_INPUT] = float(request.assumed_value if value is None else value)

    def convert_overrides(self, b: Block, after: int) -> None:
        """M48-M53."""
        code = b.mgroups.get(MGroup.OVERRIDES)
        if code is not None:
            self.override_codes(code, b.vals, b.line, after)

    def convert_user_mcode(self, b: Block, after: int) -> None:
        """M100-M199 as the machine configuration defines them: a pause with a message, an
        output, or nothing."""
        user = b.mgroups.get(MGroup.USER)
        if user is None:
            return
        action, message, output, on = self.setup.mcodes[user]
        text = f"M{user}" + (f": {message}" if message else "")
        if action == "pause":
            self.rec.events.append(Event(EventKind.PAUSE, b.line, after, None, text))
        elif action == "output":
            self.output_event(output, on, b.line, after, text)
        else:
            self.rec.events.append(Event(EventKind.MESSAGE, b.line, after, None,
                                         f"{text} (does nothing on this machine)"))

    def convert_dwell(self, b: Block, after: int) -> None:
        """G4 P: seconds."""
        if b.non_modal != G.G4:
            return
        p = b.vals.get("P")
        if p is None:
            raise BlockError("G04 needs a P word (dwell time in seconds)", "G4")
        if p < 0.0:
            raise BlockError(f"negative dwell time P{p:g}", "P")
        self.rec.events.append(Event(EventKind.DWELL, b.line, after, Dwell(p), f"dwell {p:g} s"))

    # ------------------------------------------------------------------ the modes
    def convert_plane(self, b: Block) -> None:
        code = b.groups.get(Group.PLANE)
        if code is not None:
            if code != self.modal.plane:
                self.comp_refuses("change the plane", gname(code))
            self.modal.plane = code

    def convert_path_control(self, b: Block) -> None:
        """G61 (exact stop), G61.1 (exact path), G64 P Q (the blends' and the naive CAM
        tolerance; G64 alone: the machine's default; G64 P0: the programmed path)."""
        code = b.groups.get(Group.PATH_CONTROL)
        if code is None:
            return
        self.comp_refuses("change the path control mode", gname(code))
        modal, scale = self.modal, self.modal.scale
        modal.exact_stop = code == G.G61
        # G61.1 keeps the programmed path without stopping at the joints; so does G64 unless
        # a tolerance lets the planner blend corners or join lines (planner.geometry.blend)
        modal.exact_path = code == G.G61_1
        if code == G.G64:
            p_tol = b.vals.get("P")
            modal.blend_tol_mm = self.setup.blend_default_mm if p_tol is None else max(p_tol, 0.0) * scale
            q_tol = b.vals.get("Q")
            modal.naive_cam_mm = modal.blend_tol_mm if q_tol is None or q_tol < 0.0 else q_tol * scale
        else:
            modal.blend_tol_mm = 0.0
            modal.naive_cam_mm = 0.0
        self.note_blend_tolerance()

    def convert_distance_modes(self, b: Block) -> None:
        """G90/G91 for the axis words, G90.1/G91.1 for arc centres."""
        code = b.groups.get(Group.DISTANCE)
        if code is not None:
            self.modal.absolute = code == G.G90
        code = b.groups.get(Group.ARC_DISTANCE)
        if code is not None:
            self.modal.arc_absolute = code == G.G90_1

    def convert_retract_mode(self, b: Block) -> None:
        """G98 (back to the level the cycles started from) / G99 (to the R plane)."""
        code = b.groups.get(Group.RETURN_MODE)
        if code is not None:
            self.comp_refuses("change the canned cycle retract mode", gname(code))
            self.modal.retract_r_plane = code == G.G99

    def convert_motion_mode(self, b: Block) -> None:
        """The motion group's code becomes the mode (G80: none); the panel's modal text follows."""
        g1 = b.motion_code
        if g1 is not None:
            self.motion = None if g1 == G.G80 else g1
        if not b.groups.keys().isdisjoint(SHOWN_GROUPS):
            self.note_modal()

    # ------------------------------------------------------------------ offsets and stored positions
    def convert_axis_offsets(self, b: Block) -> None:
        """G10, G28.1/G30.1, G52, G92 and G92.1-G92.3 (RS274/NGC order: after the modes, before
        motion)."""
        g0 = b.non_modal
        if g0 in (G.G28_1, G.G30_1):
            self.comp_refuses("store the G28/G30 position", gname(g0))
        elif g0 in (G.G52, G.G92):
            self.comp_refuses("change the axis offsets (G52, G92)", gname(g0))
        elif g0 in (G.G28, G.G30):
            self.comp_refuses(f"use {gname(g0)}", gname(g0))
        if g0 in (G.G10, G.G28_1, G.G30_1, G.G52, G.G92):
            self.data_code(g0, b.vals, b.axis_words, self.modal.scale, b.line)
        g16 = b.groups.get(Group.AXIS_OFFSETS)
        if g16 is not None:
            self.comp_refuses("change the axis offsets (G52, G92)", gname(g16))
            self.data_code(g16, b.vals, [], self.modal.scale, b.line)

    def convert_curve_end(self, b: Block, previous_motion: int | None) -> None:
        """G5.3 runs the open NURBS; any other motion code while one is open is refused."""
        g1 = b.motion_code
        if b.non_modal == G.G5_3:
            self.nurbs_end(g1, previous_motion, b.line)
        elif self.curve.nurbs is not None and g1 is not None and g1 != G.G5_2:
            raise BlockError(f"{gname(g1)} before the NURBS begun at line {self.curve.line} is ended: "
                             "program G05.3 to run it first", gname(g1))

    # ------------------------------------------------------------------ motion
    def check_feed_mode(self, b: Block) -> None:
        """What the feed mode forbids the block's motion."""
        motion, modal, vals = b.motion, self.modal, b.vals
        if motion is None:
            return
        if motion in PROBES and modal.feed_mode != G.G94:
            mode = ("inverse time feed mode (G93)" if modal.feed_mode == G.G93
                    else "feed per revolution mode (G95)")
            raise BlockError(f"cannot probe ({gname(motion)}) in {mode}: program G94 first", gname(motion))
        if motion == G.G0 or motion in SYNCHRONISED or b.axis_data:
            return
        where = "G95" if Group.FEED_MODE in b.groups else "G"
        if modal.feed_mode == G.G93:
            if motion in CYCLES:
                raise BlockError("cannot use inverse time feed (G93) with canned cycles", "G93")
            if "F" not in vals:
                raise BlockError("G93 inverse time: every feed move needs its F word (1/F minutes)", "G")
        elif modal.feed_mode == G.G95 and self.css_max_rpm is not None:
            raise BlockError("G95 feed per revolution in G96: the speed would follow X, and this "
                             "spindle has no speed output to follow it; program G97 and S in rpm", where)
        elif modal.feed_mode == G.G95 and modal.spindle_rpm <= 0.0:
            raise BlockError("G95 feed per revolution needs a spindle speed: S is 0", where)

    def convert_motion(self, b: Block, previous_motion: int | None) -> bool:
        """G28/G30, a canned cycle, or the block's motion (G53: in machine coordinates); False
        when a curve (G5, G5.1, G5.2) took the block whole (a stop beside it is not read, as in
        LinuxCNC)."""
        self.check_feed_mode(b)
        g0, g1, motion, vals = b.non_modal, b.motion_code, b.motion, b.vals
        scale = self.modal.scale
        if g1 == G.G80 or (motion is not None and motion not in CYCLES):
            self.cycle.il = None            # a cycle sequence ends: G98's level is taken anew
        if g0 in (G.G28, G.G30):
            self.g28(vals, b.axis_words, scale, b.line, P_G28 if g0 == G.G28 else P_G30)
        elif motion in CYCLES:
            if g0 == G.G53:
                raise BlockError("G53 needs G00 or G01", "G53")
            turn = None
            if b.polar and self.modal.absolute:
                self.polar(vals)
            elif b.polar:                       # G91: the radius and angle step at every repeat
                if self.modal.plane != G.G17:
                    raise BlockError("polar coordinates (@ ^) only in the XY plane (G17)",
                                     "@" if "@" in vals else "^")
                turn = (vals.pop("@", 0.0) * scale, math.radians(vals.pop("^", 0.0)))
            self.canned_cycle(motion, previous_motion != motion, vals, b.axis_words, scale, b.line, turn)
        elif motion is not None:
            if g0 == G.G53:
                if motion not in (G.G0, G.G1):
                    raise BlockError("G53 needs G00 or G01", "G53")
                if self.comp.radius > 0.0:
                    raise BlockError("cannot use G53 with cutter compensation on: program G40 first", "G53")
                if not self.modal.absolute:
                    raise BlockError("G53 cannot be used in incremental mode (G91)", "G53")
            if b.polar:
                self.polar(vals)
            if motion in (G.G5, G.G5_1, G.G5_2):
                self.spline(motion, previous_motion, vals, b.axis_words, b.line)
                return False
            self.move(motion, self.target(vals, b.axis_words, scale, g0 == G.G53), vals, b.line)
        elif g0 == G.G53:
            raise BlockError("G53 needs G00 or G01 with axis words", "G53")
        return True

    def move(self, motion: int, target: list[float], vals: dict[str, float], line_no: int) -> None:
        """The motion of a block to ``target`` (machine coordinates)."""
        scale = self.modal.scale
        if motion in (G.G0, G.G1):
            self.straight(target, motion == G.G0, line_no)
        elif motion in (G.G2, G.G3):
            self.arc(target, vals, motion == G.G2, scale, line_no)
        elif motion in PROBES:
            self.probe(motion, target, line_no)
        elif motion == G.G33_1:
            self.rigid_tap(target, vals, scale, line_no)
        elif motion == G.G33:
            self.synchronised_feed(target, vals, scale, line_no)
        elif motion == G.G76:
            self.thread_cycle(target, vals, scale, line_no)
        elif motion in LATHE_CYCLES:
            self.lathe_cycle(motion, vals, scale, line_no)
        else:
            raise BlockError(f"{gname(motion)} is not a motion this interpreter runs", gname(motion))

    def convert_stop(self, b: Block) -> None:
        """M0, M1 (pauses), M2, M30 (the end): after the block's motion."""
        code = b.mgroups.get(MGroup.STOPPING)
        if code is None:
            return
        self.comp.stop(self)
        kind = STOP_EVENTS[code]
        self.rec.events.append(Event(kind, b.line, len(self.rec.out) - 1, None, f"M{code:02d}"))
        if kind is EventKind.END:
            if self.curve.nurbs is not None:
                raise BlockError(f"the program ends with the NURBS begun at line {self.curve.line} "
                                 "not ended: program G05.3 to run it", f"M{code}")
            self.ended = True

