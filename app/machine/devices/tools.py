"""The tool table and the tool in the spindle: edited by the operator (Tools page), loaded by
the program (M6, M61), persisted in the state folder.

The offsets are read when a program is checked (G43 takes them from the table then): editing
the table while a program runs is refused, and a loaded program is checked again before it
starts when the table changed since.
"""

from __future__ import annotations

import math

from app.machine.infra.events import PanelChannels
from app.machine.infra.persist import StateStore
from app.machine.model import CommandResult, Severity
from app.machine.motion.jobs import Job
from app.machine.motion.pauses import PauseHandlers
from app.machine.motion.timescale import PauseKind, PausePoint
from app.machine.ports import AlarmSink, CoordinatesView, PositionsView, Settings
from app.machine.state.gate import Action, guarded
from app.machine.state.states import StateMachine
from ethercat.worker import WorkerSnapshot
from planner.core.errors import PlannerError
from planner.core.program import TableRef, ToolNumber
from planner.core.tools import Tool, ToolTable, read_tbl

__all__ = ["ToolControl"]


class ToolControl:
    """The tool table and the tool in the spindle (``controller.tools``)."""

    def __init__(self, settings: Settings, states: StateMachine, positions: PositionsView,
                 coordinates: CoordinatesView, store: StateStore, alarms: AlarmSink, out: PanelChannels,
                 pauses: PauseHandlers) -> None:
        self._settings = settings
        self._states = states
        self._positions = positions
        self._coordinates = coordinates
        self._store = store
        self._alarms = alarms
        self._out = out
        self.table, self.in_spindle = store.load_tools()
        self.version = 0          # changes with every edit: a loaded program knows its version
        self._tell_coordinates()
        pauses.on(PauseKind.TOOL_SET, self.at_tool_set)
        pauses.on(PauseKind.TOOL_DATA, self.at_tool_data)

    @property
    def gate(self) -> StateMachine:
        return self._states

    def _commit(self, table: ToolTable, in_spindle: int, action: str) -> CommandResult:
        try:
            self._store.save_tools(table, in_spindle)
        except OSError as exc:
            self._alarms.raise_alarm("persistence", f"cannot save the tool table: {exc}", Severity.WARNING,
                                     "tools")
            return self._states.refuse(action, f"cannot save the tool table: {exc}")
        self.table, self.in_spindle = table, in_spindle
        self.version += 1
        self._tell_coordinates()
        self._out.toolsChanged.emit(self.table, self.in_spindle)
        return self._states.ok(action)

    def spindle_tool_offsets(self) -> tuple[float, ...]:
        """The offsets (per axis, machine units) of the tool in the spindle; 0 without one."""
        axes = self._settings.config.axes
        tool = self.table.get(self.in_spindle) if self.in_spindle else None
        return tuple(float(tool.offset(a)) if tool is not None else 0.0 for a in axes)

    def _tell_coordinates(self) -> None:
        """The tool length offset in force follows the tool in the spindle (G43 of it)."""
        self._coordinates.set_spindle_tool(self.in_spindle, self.spindle_tool_offsets())

    def _length_outside_travel(self, number: int, length: float) -> str:
        """Why a Z length cannot be a tool's: longer than the Z travel; "" when it can."""
        cfg = self._settings.config
        if "Z" not in cfg.axes:
            return ""
        z = cfg.machine.axes[cfg.axes.index("Z")]
        span = z.max_pos - z.min_pos
        if not math.isfinite(length):
            return f"T{number}: the length is not a number"
        if abs(length) > span:
            return (f"T{number} length {length:.4f} mm is longer than the Z travel ({span:g} mm): check the "
                    "value and the surface it was touched off on")
        return ""

    @guarded(Action.SET_TOOL)
    def set_tool(self, tool: Tool) -> CommandResult:
        """Add or replace a tool (number, pocket, offsets, diameter, description); a length
        longer than the Z travel is refused."""
        why = self._length_outside_travel(tool.number, tool.length_mm)
        if why:
            return self._states.refuse(Action.SET_TOOL, why)
        try:
            table = self.table.with_tool(tool)
        except PlannerError as exc:
            return self._states.refuse(Action.SET_TOOL, str(exc))
        return self._commit(table, self.in_spindle, Action.SET_TOOL)

    @guarded(Action.REMOVE_TOOL)
    def remove_tool(self, number: int) -> CommandResult:
        """Take a tool out of the table (not the one in the spindle)."""
        if number not in self.table:
            return self._states.refuse(Action.REMOVE_TOOL, f"T{number} is not in the tool table")
        if number == self.in_spindle:
            return self._states.refuse(Action.REMOVE_TOOL,
                                       f"T{number} is in the spindle: set another tool first")
        return self._commit(self.table.without(number), self.in_spindle, Action.REMOVE_TOOL)

    @guarded(Action.SET_TOOL_IN_SPINDLE)
    def set_tool_in_spindle(self, number: int) -> CommandResult:
        """The tool now in the spindle, without a change (as M61 Q); 0: the spindle is empty."""
        if number and number not in self.table:
            return self._states.refuse(Action.SET_TOOL_IN_SPINDLE, f"T{number} is not in the tool table")
        return self._commit(self.table, int(number), Action.SET_TOOL_IN_SPINDLE)

    @guarded(Action.TOUCH_OFF_TOOL)
    def touch_off_tool(self, number: int, surface_z_mm: float = 0.0) -> CommandResult:
        """Set the length (Z offset) of tool ``number`` so that, with it in the spindle at the
        machine's Z now, the work Z reads ``surface_z_mm`` (LinuxCNC's G10 L10 for Z): the tip
        touches a surface at that height in the active work coordinates."""
        action = Action.TOUCH_OFF_TOOL
        cfg = self._settings.config
        tool = self.table.get(number)
        if tool is None:
            return self._states.refuse(action, f"T{number} is not in the tool table")
        if "Z" not in cfg.axes:
            return self._states.refuse(action, "the machine has no Z axis")
        if not math.isfinite(surface_z_mm):
            return self._states.refuse(action, "the surface height must be a number")
        if cfg.homing.required and not all(self._positions.homed):
            return self._states.refuse(action, "axes not homed: the machine Z is not known")
        k = cfg.axes.index("Z")
        # the tool length with which the tip here reads the surface's height (G5x and G92; the
        # tool's own length what is measured)
        frame = self._coordinates.panel_frame()
        machine = [float(v) for v in self._positions.machine_pos()]
        length = round(frame.tool_reading(machine, {k: float(surface_z_mm)}, frame.tool)[k], 6) + 0.0
        why = self._length_outside_travel(number, length)
        if why:
            return self._states.refuse(action, why)
        try:
            table = self.table.with_tool(tool.with_offset("Z", length))
        except PlannerError as exc:
            return self._states.refuse(action, str(exc))
        return self._commit(table, self.in_spindle, action)

    @guarded(Action.IMPORT_TOOL_TABLE)
    def import_table(self, path: str) -> CommandResult:
        """Replace the table by a LinuxCNC ``.tbl`` file (refused whole if any line is wrong)."""
        try:
            table = read_tbl(path)
        except PlannerError as exc:
            return self._states.refuse(Action.IMPORT_TOOL_TABLE, str(exc))
        in_spindle = self.in_spindle if self.in_spindle in table else 0
        return self._commit(table, in_spindle, Action.IMPORT_TOOL_TABLE)

    def set_by_program(self, tool: Tool) -> None:
        """G10 L1/L10/L11 reached by the motion (or typed in MDI): the table takes the tool as
        the program set it, and keeps it (tools.tbl), as LinuxCNC writes its tool table."""
        try:
            table = self.table.with_tool(tool)
        except PlannerError as exc:
            self._alarms.raise_alarm("tools", f"G10: {exc}", Severity.WARNING, "tools")
            return
        self._commit(table, self.in_spindle, "g10_tool")

    def loaded_by_program(self, number: int) -> None:
        """M6 done or M61 reached: the program put ``number`` in the spindle."""
        if number != self.in_spindle:
            try:
                self._store.save_tools(self.table, number)
            except OSError as exc:
                self._alarms.raise_alarm("persistence", f"cannot save the tool in the spindle: {exc}",
                                         Severity.WARNING, "tools")
            self.in_spindle = number
            self._tell_coordinates()
            self._out.toolsChanged.emit(self.table, self.in_spindle)

    # ------------------------------------------------------------------ at pause points
    def at_tool_set(self, _job: Job, point: PausePoint, _snap: WorkerSnapshot) -> bool:
        """M61 Q reached: the program says which tool is in; the motion goes on."""
        self.loaded_by_program(point.payload_as(ToolNumber).number)
        return True

    def at_tool_data(self, job: Job, point: PausePoint, _snap: WorkerSnapshot) -> bool:
        """G10 L1/L10/L11 reached: the table takes the tool; the motion goes on."""
        tools = job.plan.program.tool_sets
        index = point.payload_as(TableRef).index
        if 0 <= index < len(tools):
            self.set_by_program(tools[index])
        return True
