"""Offsets and coordinate systems: G10 L2/L20 (with R, the XY rotation), G10 L1/L10/L11 (tool
data), G28/G30 and their stored positions, G52, G92 and G92.1-G92.3, and the parameters that
read positions (#5420-, #5021-, #<_x> ...), as LinuxCNC 2.9 keeps them.
"""

from __future__ import annotations

from dataclasses import replace

from planner.core.errors import BlockError, PlannerError
from planner.core.program import (
    Event,
    EventKind,
    TableRef,
)
from planner.core.tools import Tool, ToolTable
from planner.gcode.codes import (
    SYSTEMS,
    G,
    Group,
    gname,
)
from planner.gcode.motion import MotionCodes
from planner.gcode.reader import Block
from planner.gcode.state import (
    P_G28,
    P_G30,
    P_G92,
    P_G92_ON,
    P_SYSTEM,
    PARAM_AXES,
    PERSISTENT_PARAMETERS,
    system_base,
)


class OffsetCodes(MotionCodes):
    def g28(self, vals: dict[str, float], axis_words: list[str], scale: float, line_no: int,
            base: int = P_G28) -> None:
        """G28 / G30: rapid to the programmed point (if any), then to the stored position of
        those axes (#5161- for G28, #5181- for G30, machine coordinates, set by G28.1 / G30.1;
        machine zero until then). No axis words: every axis goes there."""
        stored = [self.params.numbered.get(base + p, 0.0) for p in self.setup.axis_param]
        if axis_words:
            mid = self.target(vals, axis_words, scale, False)
            self.straight(mid, True, line_no)
            home = self.pos.copy()
            for letter in axis_words:
                i = self.setup.axis_index[letter]
                home[i] = stored[i]
            if self.offsets.rotation != 0.0 and ("X" in axis_words) != ("Y" in axis_words):
                # LinuxCNC keeps the other axis's program coordinate, which a rotated system
                # couples to both machine axes: X (or Y) of the stored point, the rest as it is
                sx, sy = self.prog_xy(stored)
                cx, cy = self.prog_xy(self.pos)
                px, py = (sx, cy) if "X" in axis_words else (cx, sy)
                ix, iy = self.setup.axis_index["X"], self.setup.axis_index["Y"]
                home[ix], home[iy] = self.machine_xy(px, py)
        else:
            home = stored
        self.straight(home, True, line_no)

    def data_code(self, code: int, vals: dict[str, float], axis_words: list[str], scale: float,
                  line_no: int) -> None:
        """G10 L2/L20 (coordinate system data), G28.1/G30.1 (store the position), G52 and G92
        (axis offsets), G92.1/.2/.3, as LinuxCNC 2.9 sets its parameters."""
        num = self.params.numbered

        def value(letter: str) -> float:
            i = self.setup.axis_index[letter]
            return vals[letter] if self.setup.rotary[i] else vals[letter] * scale

        if code == G.G10:
            l_word = vals.get("L")
            if l_word is None:
                raise BlockError("G10 needs an L word (L2 or L20: coordinate system; L1, L10, L11: tool "
                                 "table)", "G10")
            if l_word in (1, 10, 11):
                self.g10_tool(int(l_word), vals, axis_words, scale, line_no)
                return
            if l_word == 0:
                # LinuxCNC reloads its tool table file, which G10 L1/L10/L11 have already
                # written: here the table the program reads is the machine's, kept up to date
                # the same way, so there is nothing to reload; LinuxCNC's refusal is kept
                if self.tool > 0:
                    raise BlockError(f"G10 L0 (reload the tool table) with tool {self.tool} in the spindle: "
                                     "unload it first (M6 T0 or M61 Q0)", "L")
                return
            if l_word not in (2, 20):
                raise BlockError(f"G10 L{l_word:g} is not a G10 this control knows (L0, L1, L2, L10, L11, "
                                 "L20)", "L")
            p = vals.get("P")
            if p is None or p != int(p) or not 0 <= p <= 9:
                raise BlockError("G10 L2/L20 needs P0-P9 (0: the system in use, 1: G54 ... 9: G59.3)", "P")
            system = self.modal.work_code if p == 0 else SYSTEMS[int(p) - 1]
            base = system_base(system)
            if "R" in vals:
                if l_word == 20:
                    raise BlockError("R not allowed in G10 L20 (the rotation is set with G10 L2 R)", "R")
                if "X" not in self.setup.axis_index or "Y" not in self.setup.axis_index:
                    raise BlockError("G10 L2 R rotates the XY plane: this machine has no X and Y", "R")
                num[base + 9] = vals["R"]
            if self.modal.comp_code != G.G40 and system == self.modal.work_code:
                raise BlockError("cannot change the offsets of the coordinate system in use with cutter "
                                 "compensation on", "G10")
            theta = num.get(base + 9, 0.0)
            given = {self.setup.axis_index[letter]: value(letter) for letter in axis_words}
            if l_word == 2:
                new = list(self.offsets.systems[system])
                for i, v in given.items():
                    new[i] = v
            else:
                # L20: the current position reads the given values in that system (in a rotated
                # one, X and Y together)
                new = list(replace(self.frame, g5x=self.offsets.systems[system],
                                   rotation_deg=theta).origin_reading(self.pos, given))
            for i, p_index in enumerate(self.setup.axis_param):
                num[base + p_index] = new[i]
            self.offsets.systems[system] = tuple(new)
            if system == self.modal.work_code:
                self.set_offset(work=tuple(new), rotation=theta)
            self.parameters_changed(line_no, f"G10 L{l_word:g}: {gname(system)} offsets set")
        elif code in (G.G28_1, G.G30_1):
            base = P_G28 if code == G.G28_1 else P_G30
            for i, p in enumerate(self.setup.axis_param):
                num[base + p] = self.pos[i]
            self.parameters_changed(line_no, f"{gname(code)}: position stored for {gname(code - 1)}")
        elif code in (G.G52, G.G92):
            given = {self.setup.axis_index[letter]: value(letter) for letter in axis_words}
            if code == G.G52:             # G52: the offsets themselves
                g92 = list(self.offsets.g92)
                for i, v in given.items():
                    g92[i] = v
            else:                         # G92: the current position reads the given values
                g92 = list(self.frame.g92_reading(self.pos, given))
            self.set_g92(tuple(g92), True)
            self.parameters_changed(line_no, f"{gname(code)}: axis offsets set")
        elif code == G.G92_1:               # G92.1: offsets and their parameters to zero
            self.set_g92((0.0,) * self.setup.n, False)
            self.parameters_changed(line_no, "G92.1: axis offsets cleared")
        elif code == G.G92_2:               # G92.2: offsets off, parameters kept
            num[P_G92_ON] = 0.0
            self.set_offset(g92=(0.0,) * self.setup.n)
            self.parameters_changed(line_no, "G92.2: axis offsets suspended")
        else:                           # G92.3: back from the parameters
            num[P_G92_ON] = 1.0
            self.set_offset(g92=tuple(num.get(P_G92 + p, 0.0) for p in self.setup.axis_param))
            self.parameters_changed(line_no, "G92.3: axis offsets restored")

    def g10_tool(self, l_word: int, vals: dict[str, float], axis_words: list[str], scale: float,
                 line_no: int) -> None:
        """G10 L1 (tool data as given: offsets, R = radius), L10 (offsets so that the current
        position reads the given values with that tool), L11 (the same in G59.3, without G92),
        as LinuxCNC 2.9; later G43s use them, and the machine keeps them (TOOL_DATA events)."""
        p = vals.get("P")
        if p is None or p != int(p) or p < 1:
            raise BlockError(f"G10 L{l_word} needs P with the tool number (1 or more)", "P")
        number = int(p)
        if self.tools is None:
            self.tools = ToolTable()
        tool = self.tools.get(number)
        if tool is None and self.any_tool:            # no table given: every tool is known, at 0
            tool = Tool(number, number, (), 0.0, "")
        if tool is None:
            raise BlockError(f"G10 L{l_word} P{number}: tool T{number} is not in the tool table (add it "
                             "on the Tools page first)", "P")
        if l_word == 11:
            work, g92 = self.offsets.systems[593], (0.0,) * self.setup.n
            rotation = self.params.numbered.get(system_base(593) + 9, 0.0)
        else:
            work, g92 = self.offsets.work, self.offsets.g92
            rotation = self.offsets.rotation
        index = self.setup.axis_index
        given = {index[letter]: vals[letter] if self.setup.rotary[index[letter]] else vals[letter] * scale
                 for letter in axis_words}
        written = list(axis_words)
        if l_word == 1:
            values = [0.0] * self.setup.n
            for i, v in given.items():
                values[i] = v
        else:
            # L10/L11: the position in that system without any tool offset, minus the values;
            # X and Y as LinuxCNC's convert_setup_tool, in the (possibly rotated) system, both
            # written when one is given
            old = [tool.offset(a) for a in self.setup.axes]
            values = list(replace(self.frame, g5x=work, g92=g92, rotation_deg=rotation)
                          .tool_reading(self.pos, given, old))
            if ("X" in axis_words or "Y" in axis_words) and "X" in index and "Y" in index:
                written += [letter for letter in "XY" if letter not in written]
        for letter in written:
            tool = tool.with_offset(letter, values[index[letter]])
        if "R" in vals:
            if vals["R"] < 0:
                raise BlockError(f"G10 L{l_word} R{vals['R']:g}: the tool radius cannot be negative", "R")
            tool = replace(tool, diameter_mm=2.0 * vals["R"] * scale)
        try:
            self.tools = self.tools.with_tool(tool)
        except PlannerError as exc:
            raise BlockError(str(exc).split(": ", 1)[-1], "P") from None
        self.rec.tool_sets.append(tool)
        text = f"G10 L{l_word}: {tool.label()} offsets set"
        self.rec.events.append(Event(EventKind.TOOL_DATA, line_no, len(self.rec.out) - 1,
                                     TableRef(len(self.rec.tool_sets) - 1), text))

    def set_g92(self, g92: tuple[float, ...], on: bool) -> None:
        num = self.params.numbered
        for i, p in enumerate(self.setup.axis_param):
            num[P_G92 + p] = g92[i]
        num[P_G92_ON] = 1.0 if on else 0.0
        self.set_offset(g92=g92)

    def parameters_changed(self, line_no: int, text: str) -> None:
        """An OFFSETS event: the machine takes the persistent parameters as they are now when
        the program passes this point (LinuxCNC keeps them in its var file)."""
        num = self.params.numbered
        self.rec.parameter_sets.append({p: num.get(p, 0.0) for p in sorted(PERSISTENT_PARAMETERS)})
        self.rec.events.append(Event(EventKind.OFFSETS, line_no, len(self.rec.out) - 1,
                                     TableRef(len(self.rec.parameter_sets) - 1), text))

    def position_parameter(self, number: int) -> float | None:
        """#5420-#5428 the current position in program coordinates, #5021-#5029 the machine
        position (X Y Z A B C U V W), #5400 the tool in the spindle, #5401-#5409 its offsets in
        the tool table, #5410 its diameter; 0 for an axis the machine does not have."""
        if number >= 5420:
            return self.system_parameter("_" + PARAM_AXES[number - 5420])
        if number <= 5029:
            letter = PARAM_AXES[number - 5021]
            i = self.setup.axis_index.get(letter)
            if i is None:
                return 0.0
            return self.pos[i] if self.setup.rotary[i] else self.pos[i] / self.modal.scale
        if number == 5400:
            return float(self.tool)
        tool = self.tools.get(self.tool) if self.tools is not None else None
        if tool is None:
            return 0.0
        if number == 5410:
            return tool.diameter_mm / self.modal.scale
        letter = PARAM_AXES[number - 5401]
        value = tool.offset(letter)
        return value if letter in "ABC" else value / self.modal.scale

    def system_parameter(self, name: str) -> float | None:
        """LinuxCNC's predefined named parameters the interpreter knows."""
        axis = name[1:]
        if name.startswith("_ABS_") and len(name) == 6 and name[5] in PARAM_AXES:
            return self.position_parameter(5021 + PARAM_AXES.index(name[5]))   # machine position
        if axis not in self.setup.axis_index and len(axis) == 1 and axis in PARAM_AXES:
            return 0.0                     # an axis this machine does not have reads 0, as LinuxCNC's
        if axis in self.setup.axis_index:
            i = self.setup.axis_index[axis]
            value = self.program_position(self.pos)[i]
            return value if self.setup.rotary[i] else value / self.modal.scale
        modal = self.modal
        return {
            "_LINE": float(self.current_line),
            "_METRIC": 0.0 if self.modal.inch else 1.0,
            "_IMPERIAL": 1.0 if self.modal.inch else 0.0,
            "_ABSOLUTE": 1.0 if self.modal.absolute else 0.0,
            "_INCREMENTAL": 0.0 if self.modal.absolute else 1.0,
            "_FEED": self.modal.feed_mm_s * 60.0 / self.modal.scale,
            "_RPM": self.modal.spindle_rpm,
            "_CURRENT_TOOL": float(self.tool),
            "_SELECTED_TOOL": float(self.selected),
            "_MOTION_MODE": float(self.motion if self.motion is not None else G.G80),
            "_PLANE": float(self.modal.plane),
            "_RETRACT_R_PLANE": 1.0 if self.modal.retract_r_plane else 0.0,
            "_RETRACT_OLD_Z": 0.0 if self.modal.retract_r_plane else 1.0,
            "_LATHE_DIAMETER_MODE": 1.0 if self.modal.diameter else 0.0,
            "_LATHE_RADIUS_MODE": 0.0 if self.modal.diameter else 1.0,
            "_TASK": 1.0,
            "_VALUE": 0.0,
            "_VALUE_RETURNED": 0.0,
            # LinuxCNC 2.9's version as its interpreter reads it ("2.9" major, 0 minor)
            "_VMAJOR": 2.9,
            "_VMINOR": 0.0,
            "_CCOMP": float(modal.comp_code),
            "_INVERSE_TIME": float(modal.feed_mode == G.G93),
            "_UNITS_PER_MINUTE": float(modal.feed_mode == G.G94),
            "_UNITS_PER_REV": float(modal.feed_mode == G.G95),
            "_COORD_SYSTEM": float(modal.work_code),
            "_TOOL_OFFSET": float(modal.tlo_code != G.G49),
            "_SPINDLE_RPM_MODE": float(self.css_max_rpm is None),
            "_SPINDLE_CSS_MODE": float(self.css_max_rpm is not None),
            "_IJK_ABSOLUTE_MODE": float(modal.arc_absolute),
            "_SPINDLE_ON": float(modal.spindle_dir != 0),
            "_SPINDLE_CW": float(modal.spindle_dir > 0),
            "_MIST": float(bool(modal.coolant & 1)),
            "_FLOOD": float(bool(modal.coolant & 2)),
            "_SPEED_OVERRIDE": float(modal.spindle_override_on),
            "_FEED_OVERRIDE": float(modal.feed_override_on),
            "_ADAPTIVE_FEED": 0.0,         # M52 P1 is refused: no input scales the feed here
            "_FEED_HOLD": float(modal.feed_hold_on),
            "_CURRENT_POCKET": float(self.pocket_of(self.tool)),
            "_SELECTED_POCKET": float(self.pocket_of(self.selected)) if self.selected else -1.0,
            "_CALL_LEVEL": float(self.calls.level),
            "_REMAP_LEVEL": 0.0,           # no remapping: every code is the interpreter's own
        }.get(name)

    def pocket_of(self, number: int) -> int:
        """The pocket of tool ``number`` in the tool table (its number where there is no table
        or the tool is not in it; 0, the spindle, for T0)."""
        tool = self.tools.get(number) if self.tools is not None and number else None
        return tool.pocket if tool is not None else number

    def convert_coord_system(self, b: Block) -> None:
        """G54-G59.3: the system in use, its offsets and XY rotation (#5220 its number)."""
        code = b.groups.get(Group.COORD_SYSTEM)
        if code is None:
            return
        self.comp_refuses("change the coordinate system", gname(code))
        self.modal.work_code = code
        self.set_offset(work=self.offsets.systems[code],
                        rotation=self.params.numbered.get(system_base(code) + 9, 0.0))
        self.params.numbered[P_SYSTEM] = float(SYSTEMS.index(code) + 1)
