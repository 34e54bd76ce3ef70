"""Tools: the tool table's numbers, G43/G43.1/G43.2/G49 tool length offsets, and G41/G42
(G41.1/G42.1) cutter compensation requests with the tool's radius.
"""

from __future__ import annotations

from planner.core.errors import BlockError
from planner.core.program import (
    Event,
    EventKind,
    SpindleSpeed,
    ToolNumber,
)
from planner.gcode.codes import (
    PLANE_NAMES,
    G,
    Group,
    M,
    MGroup,
    gname,
)
from planner.gcode.cutter_comp import LEFT, RIGHT
from planner.gcode.motion import MotionCodes
from planner.gcode.reader import Block


class ToolCodes(MotionCodes):
    def known_tool(self, number: int, letter: str) -> int:
        """``number`` if the tool table has it (T0, the empty spindle, always)."""
        if number and not self.any_tool and self.tools is not None and number not in self.tools:
            raise BlockError(f"tool T{number} is not in the tool table (add it on the Tools page)", letter)
        return number

    def tool_label(self, number: int) -> str:
        return self.tools.label(number) if self.tools is not None else f"T{number}"

    def tool_offsets(self, number: int) -> tuple[float, ...]:
        tool = self.tools.get(number) if self.tools is not None else None
        if tool is None:
            return (0.0,) * self.setup.n
        return tuple(tool.offset(a) for a in self.setup.axes)

    def tool_length(self, code: int, vals: dict[str, float], axis_words: list[str], scale: float) -> None:
        """G43 (the tool in the spindle, or H's), G43.1 (the axis words), G43.2 (add H's or the
        axis words), G49 (none), as LinuxCNC 2.9 applies them."""
        if code == G.G49:
            self.set_offset(tlo=(0.0,) * self.setup.n)
            return
        words = [0.0] * self.setup.n
        for letter in axis_words:
            i = self.setup.axis_index[letter]
            words[i] = vals[letter] if self.setup.rotary[i] else vals[letter] * scale
        h = vals.get("H")
        if h is not None and (h < 0 or h != int(h)):
            raise BlockError(f"tool number H{h:g} must be a whole number >= 0", "H")
        if code == G.G43:
            number = self.known_tool(int(h), "H") if h is not None else self.tool
            self.set_offset(tlo=self.tool_offsets(number))
        elif code == G.G43_1:
            self.set_offset(tlo=tuple(words))
        else:  # 432
            if h is None and not axis_words:
                raise BlockError("G43.2 needs an H word or axis words (the offset to add)", "G43.2")
            add = self.tool_offsets(self.known_tool(int(h), "H")) if h is not None else tuple(words)
            self.set_offset(tlo=tuple(t + a for t, a in zip(self.offsets.tlo, add)))

    def comp_request(self, code: int, vals: dict[str, float], scale: float) -> None:
        """G41/G42 (radius from the tool table: D's tool, or the tool in the spindle without D
        or with D0) and G41.1/G42.1 (D is the diameter), as LinuxCNC 2.9 reads them."""
        name = gname(code)
        if self.comp.side != 0:
            raise BlockError(f"cannot turn cutter compensation on with {name} while it is on "
                             f"({gname(self.modal.comp_code)}): program G40 first", name)
        if self.modal.plane not in (G.G17, G.G18):
            raise BlockError(f"cutter compensation works in the XY (G17) or XZ (G18) plane, not in "
                             f"{PLANE_NAMES[self.modal.plane]}", name)
        if self.modal.plane == G.G18 and self.offsets.rotation != 0.0:
            # LinuxCNC offsets in the plane of Z and the turned X; this engine offsets in machine
            # planes (G18 arcs in a rotated system are read, their compensation is not)
            raise BlockError("cutter compensation in G18 with the XY plane rotated (G10 L2 R) is not "
                             "supported: cancel the rotation (G10 L2 R0) or program the tool centre's path",
                             name)
        d = vals.get("D")
        if code in (G.G41_1, G.G42_1):
            if d is None:
                raise BlockError(f"{name} needs a D word (the tool diameter)", name)
            if "L" in vals and vals["L"] not in (0, 9):
                raise BlockError(f"{name} L{vals['L']:g}: lathe tool orientations are not supported on "
                                 "this machine (L0 or L9: the centre of the tool)", "L")
            radius = d * scale / 2.0
        else:
            if d is not None and (d < 0 or d != int(d)):
                raise BlockError(f"{name} needs D to be a tool number (a whole number >= 0), got D{d:g}",
                                 "D")
            number = int(d) if d else self.tool
            if d:
                self.known_tool(number, "D")
            tool = self.tools.get(number) if self.tools is not None else None
            radius = tool.diameter_mm / 2.0 if tool is not None else 0.0
            orientation = dict(tool.lathe).get("Q", 0.0) if tool is not None else 0.0
            if orientation not in (0.0, 9.0) and radius > 0.0:
                # a lathe tool's controlled point is not its centre (LinuxCNC moves the path by
                # the orientation); offsetting the centre would cut a radius off
                raise BlockError(f"{name} with the lathe tool {self.tool_label(number)} (orientation "
                                 f"Q{orientation:g}): lathe tool orientations are not supported on this "
                                 "machine", "D" if d else name)
        _pname, fa, sa, *_ = self.plane_axes()
        self.comp.turn_on(LEFT if code in (G.G41, G.G41_1) else RIGHT, radius, (fa, sa))

    def convert_tool_select(self, b: Block, after: int) -> None:
        """T: the tool prepared for the next M6."""
        if "T" not in b.vals:
            return
        t = b.vals["T"]
        if t < 0 or t != int(t):
            raise BlockError(f"tool number T{t:g} must be a whole number >= 0", "T")
        self.selected = self.known_tool(int(t), "T")
        self.rec.events.append(Event(EventKind.TOOL, b.line, after, ToolNumber(int(t)),
                                     f"tool T{int(t)} selected"))

    def convert_tool_change(self, b: Block, after: int) -> None:
        """M6: the spindle stops (LinuxCNC's STOP_SPINDLE_TURNING, then CHANGE_TOOL) and stays
        stopped until the program's own M3/M4, and the selected tool goes into the spindle by
        hand; M6 of the tool already in the spindle changes nothing. M61 Q: the tool in the
        spindle is Q, nothing moves."""
        code = b.mgroups.get(MGroup.TOOL_CHANGE)
        if code == M.M6:
            self.comp_refuses("change tools", "M6")
            if self.selected == self.tool:
                return
            if self.modal.spindle_dir != 0:
                self.modal.spindle_dir = 0
                self.rec.events.append(Event(EventKind.SPINDLE, b.line, after, SpindleSpeed(0, 0.0),
                                             "M06: the spindle stops for the tool change"))
            self.tool = self.selected
            self.calls.tool_changed = bool(self.setup.after_tool_change)
            self.rec.events.append(Event(
                EventKind.TOOL_CHANGE, b.line, after, ToolNumber(self.tool),
                f"M06: change to tool {self.tool_label(self.tool)} by hand, then press cycle start"))
        elif code == M.M61:
            q = b.vals.get("Q")
            if q is None:
                raise BlockError("M61 needs a Q word (the tool now in the spindle)", "M61")
            if q < 0 or q != int(q):
                raise BlockError(f"tool number Q{q:g} must be a whole number >= 0", "Q")
            self.tool = self.selected = self.known_tool(int(q), "Q")
            self.rec.events.append(Event(EventKind.TOOL_SET, b.line, after, ToolNumber(self.tool),
                                         f"M61: tool {self.tool_label(self.tool)} is in the spindle"))

    def convert_cutter_comp(self, b: Block) -> None:
        """G40 / G41 G42 G41.1 G42.1, before what compensation forbids to change."""
        code = b.groups.get(Group.CUTTER_COMP)
        if code is None:
            return
        if code == G.G40:
            self.comp.turn_off(self)
        else:
            self.comp_request(code, b.vals, self.modal.scale)
        self.modal.comp_code = code

    def convert_tool_length(self, b: Block) -> None:
        """G43 / G43.1 / G43.2 / G49."""
        code = b.groups.get(Group.TOOL_LENGTH)
        if code is None:
            return
        self.comp_refuses("change the tool length offset", gname(code))
        self.tool_length(code, b.vals, b.offset_words, self.modal.scale)
        self.modal.tlo_code = code
