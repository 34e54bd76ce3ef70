"""The tool table and the tool in the spindle: edited by the operator (Tools page), loaded by
the program (M6, M61), persisted in the state folder. A part of ``MachineController``.

The offsets are read when a program is checked (G43 takes them from the table then): editing
the table while a program runs is refused, and a loaded program is checked again before it
starts when the table changed since.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from app.machine.inputs import probe_overtravel_mm
from app.machine.model import CommandResult, MachineState, Severity
from planner.errors import PlannerError
from planner.tools import Tool, ToolTable, read_tbl

if TYPE_CHECKING:
    from app.machine.controller import MachineController

__all__ = ["ToolControl"]

_EDITABLE = (MachineState.IDLE, MachineState.DISCONNECTED, MachineState.ALARM, MachineState.ESTOP)


class ToolControl:
    """A part of ``MachineController`` (``controller.tools``): it owns the table and the tool
    in the spindle, and reaches the other parts through the facade ``m``."""

    def __init__(self, m: MachineController) -> None:
        self.m = m
        self.table, self.in_spindle = m.conn.store.load_tools()
        self.version = 0          # changes with every edit: a loaded program knows its version

    def _refusal(self) -> str:
        if self.m.states.state not in _EDITABLE:
            return (f"the tool table cannot change while the machine is {self.m.states.state.label.lower()}: "
                    "a program reads the offsets when it is checked")
        return ""

    def _commit(self, table: ToolTable, in_spindle: int, action: str) -> CommandResult:
        try:
            self.m.conn.store.save_tools(table, in_spindle)
        except OSError as exc:
            self.m.alarm_log.raise_alarm("persistence", f"cannot save the tool table: {exc}",
                                         Severity.WARNING, "tools")
            return self.m.states.refuse(action, f"cannot save the tool table: {exc}")
        self.table, self.in_spindle = table, in_spindle
        self.version += 1
        self.m.toolsChanged.emit(self.table, self.in_spindle)
        return self.m.states.ok(action)

    def set_tool(self, tool: Tool) -> CommandResult:
        """Add or replace a tool (number, pocket, offsets, diameter, description)."""
        why = self._refusal()
        if why:
            return self.m.states.refuse("set_tool", why)
        try:
            table = self.table.with_tool(tool)
        except PlannerError as exc:
            return self.m.states.refuse("set_tool", str(exc))
        return self._commit(table, self.in_spindle, "set_tool")

    def remove_tool(self, number: int) -> CommandResult:
        why = self._refusal()
        if why:
            return self.m.states.refuse("remove_tool", why)
        if number not in self.table:
            return self.m.states.refuse("remove_tool", f"T{number} is not in the tool table")
        if number == self.in_spindle:
            return self.m.states.refuse("remove_tool", f"T{number} is in the spindle: set another tool first")
        return self._commit(self.table.without(number), self.in_spindle, "remove_tool")

    def set_tool_in_spindle(self, number: int) -> CommandResult:
        """The tool now in the spindle, without a change (as M61 Q); 0: the spindle is empty."""
        why = self._refusal()
        if why:
            return self.m.states.refuse("set_tool_in_spindle", why)
        if number and number not in self.table:
            return self.m.states.refuse("set_tool_in_spindle", f"T{number} is not in the tool table")
        return self._commit(self.table, int(number), "set_tool_in_spindle")

    def touch_off_tool(self, number: int, surface_z_mm: float = 0.0) -> CommandResult:
        """Set the length (Z offset) of tool ``number`` so that, with it in the spindle at the
        machine's Z now, the work Z reads ``surface_z_mm`` (LinuxCNC's G10 L10 for Z): the tip
        touches a surface at that height in the active work coordinates."""
        why = self._refusal()
        if why:
            return self.m.states.refuse("touch_off_tool", why)
        tool = self.table.get(number)
        if tool is None:
            return self.m.states.refuse("touch_off_tool", f"T{number} is not in the tool table")
        if "Z" not in self.m.config.axes:
            return self.m.states.refuse("touch_off_tool", "the machine has no Z axis")
        if not math.isfinite(surface_z_mm):
            return self.m.states.refuse("touch_off_tool", "the surface height must be a number")
        if self.m.config.homing.required and not all(self.m.pos.homed):
            return self.m.states.refuse("touch_off_tool", "axes not homed: the machine Z is not known")
        k = self.m.config.axes.index("Z")
        machine_z = float(self.m.states.machine_pos()[k])
        work_z = float(self.m.pos.offsets.get(self.m.pos.active_offset, (0.0,) * (k + 1))[k])
        length = machine_z - work_z - float(surface_z_mm)
        try:
            table = self.table.with_tool(tool.with_offset("Z", round(length, 6)))
        except PlannerError as exc:
            return self.m.states.refuse("touch_off_tool", str(exc))
        return self._commit(table, self.in_spindle, "touch_off_tool")

    def measure_tool(self, number: int) -> CommandResult:
        """Measure the length (Z offset) of tool ``number``, which must be in the spindle, on the
        tool setter (``[probe] setter_*``): up to the restart clearance, across over the setter,
        a probe down at ``max_feed_mm_min``, back up by more than that probe's overtravel, a
        second probe at a tenth of the feed, and back up to the clearance. The length is the
        machine Z of the second contact less ``setter_z_mm``; the table takes it at the end."""
        action = "measure_tool"
        if self.m.states.state is not MachineState.IDLE:
            return self.m.states.refuse(action, f"machine is {self.m.states.state.label.lower()}")
        probe = self.m.config.probe
        sx, sy, sz = probe.setter_x_mm, probe.setter_y_mm, probe.setter_z_mm
        if not probe.has_setter or sx is None or sy is None or sz is None:
            return self.m.states.refuse(action, "no tool setter on this machine ([probe] drive, setter_x_mm, "
                                                "setter_y_mm and setter_z_mm in the machine configuration)")
        tool = self.table.get(number)
        if tool is None:
            return self.m.states.refuse(action, f"T{number} is not in the tool table")
        if number != self.in_spindle:
            return self.m.states.refuse(action, f"T{number} is not in the spindle: put it in and set it "
                                                "(In the spindle) first")
        axes = self.m.config.axes
        if not {"X", "Y", "Z"} <= set(axes):
            return self.m.states.refuse(action, "measuring on a tool setter needs X, Y and Z axes")
        if not all(self.m.pos.homed):
            return self.m.states.refuse(action, "axes not homed: the setter's position is not known")
        k = axes.index("Z")
        z_axis = self.m.config.machine.axes[k]
        c = self.m.config.controller
        clear = z_axis.max_pos if c.restart_clearance_mm is None else c.restart_clearance_mm
        # program Z of a machine Z: the routine runs in the active coordinate system, without G43
        work = self.m.pos.offsets.get(self.m.pos.active_offset, (0.0,) * len(axes))
        shift = float(work[k]) + float(self.m.pos.g92_offset()[k])
        fast = probe.max_feed_mm_min
        overtravel = probe_overtravel_mm(fast, self.m.config.machine.limits.j_max_mm_s3)
        bottom = max(sz - 1.0, z_axis.min_pos) - shift
        text = "\n".join((
            f"G21 G90 G94 G49 {self.m.pos.active_offset}",
            f"G53 G0 Z{clear:.4f}",
            f"G53 G0 X{sx:.4f} Y{sy:.4f}",
            f"G38.2 Z{bottom:.4f} F{fast:g}",
            f"G91 G0 Z{max(2.0, 2.0 * overtravel + 1.0):.4f}",
            f"G90 G38.2 Z{bottom:.4f} F{fast / 10.0:g}",
            f"G53 G0 Z{clear:.4f}",
        ))

        def done(job: object) -> None:
            results = getattr(job, "probe_results", ())
            second = results[1] if len(results) > 1 else None
            if second is None or not second.tripped:
                self.m.alarm_log.raise_alarm("tools", f"T{number}: the measurement has no second contact",
                                             Severity.WARNING, "measure_tool")
                return
            length = round(float(second.trip_position[k]) - sz, 6)
            res = self.set_tool(tool.with_offset("Z", length))
            if res:
                self.m.stream.show_message(f"T{number} measured on the tool setter: length {length:.4f} mm")

        return self.m.manual.run_routine(text, f"measure T{number}", action, done)

    def import_table(self, path: str) -> CommandResult:
        """Replace the table by a LinuxCNC ``.tbl`` file (refused whole if any line is wrong)."""
        why = self._refusal()
        if why:
            return self.m.states.refuse("import_tool_table", why)
        try:
            table = read_tbl(path)
        except PlannerError as exc:
            return self.m.states.refuse("import_tool_table", str(exc))
        in_spindle = self.in_spindle if self.in_spindle in table else 0
        return self._commit(table, in_spindle, "import_tool_table")

    def set_by_program(self, tool: Tool) -> None:
        """G10 L1/L10/L11 reached by the motion (or typed in MDI): the table takes the tool as
        the program set it, and keeps it (tools.tbl), as LinuxCNC writes its tool table."""
        try:
            table = self.table.with_tool(tool)
        except PlannerError as exc:
            self.m.alarm_log.raise_alarm("tools", f"G10: {exc}", Severity.WARNING, "tools")
            return
        self._commit(table, self.in_spindle, "g10_tool")

    def loaded_by_program(self, number: int) -> None:
        """M6 done or M61 reached: the program put ``number`` in the spindle."""
        if number != self.in_spindle:
            try:
                self.m.conn.store.save_tools(self.table, number)
            except OSError as exc:
                self.m.alarm_log.raise_alarm("persistence", f"cannot save the tool in the spindle: {exc}",
                                             Severity.WARNING, "tools")
            self.in_spindle = number
            self.m.toolsChanged.emit(self.table, self.in_spindle)
