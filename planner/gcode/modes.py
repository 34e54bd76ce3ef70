"""Modes, messages and parameters: the modal text the panel shows, M48-M53 overrides, G64
tolerances, G96/G97, M66 inputs, M62-M65 outputs, M70-M73 modal memory, (MSG,) comments and
parameter assignments.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import fields, replace

from planner.core.errors import BlockError
from planner.core.program import (
    FEED_OVERRIDE_OFF,
    SPINDLE_OVERRIDE_OFF,
    Coolant,
    CoolantSwitch,
    Event,
    EventKind,
    OutputLevel,
    OverrideLocks,
    SpindleSpeed,
)
from planner.gcode.codes import PLANE_NAMES, SYSTEMS, G, M, gname
from planner.gcode.state import (
    P_SYSTEM,
    InterpBase,
    Modal,
    SavedModal,
)

MESSAGE_RE = re.compile(r"\(\s*(MSG|DEBUG|PRINT|ABORT)\s*,([^)]*)\)", re.IGNORECASE)
PARAM_TEXT_RE = re.compile(r"#<([^>]*)>|#(\d+)")

#: what an (ABORT,text) comment's error says before its text
ABORT_MARK = "(ABORT comment): "


class ModeCodes(InterpBase):
    def modal_text(self) -> str:
        """The modal codes as LinuxCNC's panels list them (motion mode aside); G7 and the
        overrides turned off are shown when in force, as they change what X and the knobs do."""
        m = self.modal
        return " ".join((
            PLANE_NAMES[m.plane], "G20" if m.inch else "G21", "G90" if m.absolute else "G91",
            gname(m.feed_mode),
            gname(m.work_code), gname(m.comp_code), gname(m.tlo_code),
            "G61" if m.exact_stop else ("G61.1" if m.exact_path else self.g64_text()),
        )) + (" G7" if m.diameter else "") + self.override_text()

    def override_text(self) -> str:
        if self.modal.feed_override_on and self.modal.spindle_override_on:
            return ""
        if not (self.modal.feed_override_on or self.modal.spindle_override_on):
            return " M49"
        return " M50 P0" if not self.modal.feed_override_on else " M51 P0"

    def overrides_event(self, line_no: int, after: int, text: str, lock: int = 0,
                        kind: EventKind = EventKind.OVERRIDES) -> None:
        """The OVERRIDES bits for the moves from ``after`` + 1 on: the program's M48-M51 state,
        and ``lock`` (tapping: both off for its moves; ``kind`` TAPPING, where the path stands)."""
        bits = ((0 if self.modal.feed_override_on else FEED_OVERRIDE_OFF)
                | (0 if self.modal.spindle_override_on else SPINDLE_OVERRIDE_OFF) | lock)
        if bits != self.rec.override_bits:
            self.rec.override_bits = bits
            self.rec.events.append(Event(kind, line_no, after, OverrideLocks(bits), text))

    def override_codes(self, code: int, vals: dict[str, float], line_no: int, after: int) -> None:
        """M48-M53 as LinuxCNC 2.9 reads them (refused with compensation on, as there)."""
        on = vals.get("P", 1.0) != 0.0
        if self.comp.side != 0:
            verb = "enable" if code == M.M48 or (code != M.M49 and on) else "disable"
            raise BlockError(f"cannot {verb} overrides with cutter radius compensation on "
                             f"({gname(self.modal.comp_code)}): program G40 first", f"M{code}")
        if code == M.M52 and on:
            raise BlockError("M52 (adaptive feed) scales the feed by an input this machine does not have",
                             "M52")
        if code in (M.M48, M.M49):
            self.modal.feed_override_on = self.modal.spindle_override_on = code == M.M48
        elif code == M.M50:
            self.modal.feed_override_on = on
        elif code == M.M51:
            self.modal.spindle_override_on = on
        elif code == M.M53:
            self.modal.feed_hold_on = on
        # M52 P0: adaptive feed off, as it is; M53: the feed stop switch, which this machine
        # does not have (the panel's feed hold is LinuxCNC's pause, which M53 leaves alone)
        what: dict[int, str] = {
            M.M48: "overrides on", M.M49: "overrides off: the program's own feed and speed",
            M.M50: f"feed override {'on' if on else 'off'}",
            M.M51: f"spindle override {'on' if on else 'off'}"}
        self.overrides_event(line_no, after, f"M{code}: {what.get(code, '')}")
        self.note_modal()

    def g64_text(self) -> str:
        """G64 with the tolerances in force, in the program's units (as the operator wrote them)."""
        if self.modal.blend_tol_mm <= 0.0 and self.modal.naive_cam_mm <= 0.0:
            return "G64"
        text = f"G64 P{self.modal.blend_tol_mm / self.modal.scale:g}"
        if self.modal.naive_cam_mm != self.modal.blend_tol_mm:
            text += f" Q{self.modal.naive_cam_mm / self.modal.scale:g}"
        return text

    def note_modal(self) -> None:
        text = self.modal_text()
        first = len(self.rec.out)
        if self.rec.modal_changes[-1][1] == text:
            return
        if self.rec.modal_changes[-1][0] == first:
            self.rec.modal_changes[-1] = (first, text)
        else:
            self.rec.modal_changes.append((first, text))

    def spindle_mode(self, code: int, vals: dict[str, float], line_no: int, after: int,
                     switched: bool) -> None:
        """G96 D S: constant surface speed, S the cutting speed (m/min, ft/min in G20) and D the
        highest speed (rpm); G97: S in rpm again. LinuxCNC on a mill sets the speed from the X
        radius; this spindle is switched by digital outputs and has no speed output, so G96 is
        kept as the mode LinuxCNC reads (the motion is the same) and the operator is told that
        its speed does not follow X. The speed shown and counted (spin-up) is what LinuxCNC
        commands near X0: D, else the spindle's highest speed."""
        if code == G.G97:
            self.css_max_rpm = None
            return
        d = vals.get("D")
        self.css_max_rpm = min(abs(d), self.setup.spindle_max_rpm) if d else self.setup.spindle_max_rpm
        if self.css_max_rpm != self.modal.spindle_rpm:
            self.modal.spindle_rpm = self.css_max_rpm
            if self.modal.spindle_dir != 0 and not switched:   # an M3/M4/M5 here tells it
                speed = SpindleSpeed(self.modal.spindle_dir, self.modal.spindle_rpm)
                self.rec.events.append(Event(EventKind.SPINDLE, line_no, after, speed))
        unit = "ft/min" if self.modal.inch else "m/min"
        limit = f" up to {abs(d):g} rpm" if d else ""
        self.rec.events.append(Event(EventKind.MESSAGE, line_no, after, None,
                                     f"G96 constant surface speed S{vals['S']:g} {unit}{limit}: this spindle "
                                     "has no speed output to follow X; counted at "
                                     f"{self.modal.spindle_rpm:g} rpm"))

    def note_blend_tolerance(self) -> None:
        first = len(self.rec.out)
        for changes, value in ((self.rec.blend_changes, self.modal.blend_tol_mm),
                               (self.rec.naive_changes, self.modal.naive_cam_mm)):
            if changes[-1][1] == value:
                continue
            if changes[-1][0] == first:
                changes[-1] = (first, value)
            else:
                changes.append((first, value))

    def modal_memory(self, code: int, line_no: int) -> None:
        """M70 save the modal state at this call level, M71 forget it, M72 restore it, M73 save it
        to be restored when the subroutine returns (LinuxCNC 2.9; the motion mode is not part)."""
        level = self.calls.level
        if code in (M.M70, M.M73):
            if code == M.M73 and level == 0:
                raise BlockError("M73 saves the state for the return of a subroutine: use M70 in the "
                                 "main program", "M73")
            o = self.offsets
            self.calls.saved_modal[level] = ((replace(self.modal), o.work, o.tlo, o.rotation), code == M.M73)
        elif code == M.M71:
            self.calls.saved_modal.pop(level, None)
        else:
            saved = self.calls.saved_modal.get(level)
            if saved is None:
                raise BlockError("M72: no modal state saved at this level (M70 or M73 first)", "M72")
            self.restore_modal(saved[0], line_no)

    def restore_modal(self, state: SavedModal, line_no: int) -> None:
        """The modal state and offsets as M70/M73 saved them (kept for another M72), and the
        spindle, coolant and overrides switched to match."""
        spindle_before = (self.modal.spindle_dir, self.modal.spindle_rpm)
        coolant_before = self.modal.coolant
        saved, work, tlo, rotation = state
        for f in fields(Modal):
            setattr(self.modal, f.name, getattr(saved, f.name))
        self.set_offset(work=work, tlo=tlo, rotation=rotation)
        self.note_blend_tolerance()
        self.params.numbered[P_SYSTEM] = float(SYSTEMS.index(self.modal.work_code) + 1)
        after = len(self.rec.out) - 1
        if (self.modal.spindle_dir, self.modal.spindle_rpm) != spindle_before:
            self.rec.events.append(Event(EventKind.SPINDLE, line_no, after,
                                         SpindleSpeed(self.modal.spindle_dir, self.modal.spindle_rpm),
                                         "M72: spindle as saved"))
        if self.modal.coolant != coolant_before:
            if coolant_before & ~self.modal.coolant:    # something to switch off: all off, then back on
                self.rec.events.append(Event(EventKind.COOLANT, line_no, after,
                                             CoolantSwitch(Coolant.ALL_OFF), "M72: coolant as saved"))
                coolant_before = 0
            for bit, on in ((1, Coolant.MIST_ON), (2, Coolant.FLOOD_ON)):
                if self.modal.coolant & bit and not coolant_before & bit:
                    self.rec.events.append(Event(EventKind.COOLANT, line_no, after, CoolantSwitch(on),
                                                 "M72: coolant as saved"))
        self.overrides_event(line_no, after, "M72: overrides as saved")
        self.note_modal()

    def output_event(self, number: int, on: bool, line_no: int, after: int, text: str) -> None:
        """An OUTPUT event: output ``number`` switched on or off."""
        self.rec.events.append(Event(EventKind.OUTPUT, line_no, after, OutputLevel(number, on),
                                     f"{text}: output {number} {'on' if on else 'off'}"))

    def messages(self, raw: str, line_no: int) -> None:
        """(MSG,text), (DEBUG,text) and (PRINT,text) comments as MESSAGE events; DEBUG and PRINT
        show parameter values (#123, #<name>) as LinuxCNC does, with six decimals. (ABORT,text)
        ends the program there with its text as the error, as in LinuxCNC 2.9."""
        for m in MESSAGE_RE.finditer(raw):
            kind, text = m.group(1).upper(), m.group(2)
            if kind != "MSG":
                text = PARAM_TEXT_RE.sub(self.param_text, text)
            if kind == "ABORT":
                raise BlockError(f"the program aborts here (ABORT comment): {text.strip()}", col=1)
            self.rec.events.append(Event(EventKind.MESSAGE, line_no, len(self.rec.out) - 1, None, text.strip()
                                     if kind == "MSG" else text))

    def param_text(self, m: re.Match[str]) -> str:
        if m.group(1) is not None:
            v = self.params.get_named(m.group(1).upper())
        else:
            n = int(m.group(2))
            v = self.params.get_numbered(n) if 1 <= n <= 5602 else None
        if v is not None and abs(v) < 5e-7:
            v = 0.0                        # round-off of a rotation must not print as -0.000000
        return "######" if v is None else f"{v:f}"

    def assign(self, assigns: Sequence[tuple[object, float]]) -> None:
        for key, value in assigns:
            if isinstance(key, str):
                self.params.set_named(key, value)
            else:
                self.params.numbered[key] = value  # type: ignore[index]
