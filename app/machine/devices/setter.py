"""Measuring a tool's length on the tool setter (``[probe] setter_x_mm``, ``setter_y_mm``,
``setter_z_mm``): a routine of G-code run as MDI is, so every check of a program applies."""

from __future__ import annotations

from app.machine.config import probe_overtravel_mm
from app.machine.devices.probing import RoutineRunner
from app.machine.devices.tools import ToolControl
from app.machine.model import CommandResult, MachineState, Severity
from app.machine.motion.jobs import Job
from app.machine.ports import AlarmSink, CoordinatesView, PositionsView, Settings
from app.machine.state.gate import Action
from app.machine.state.states import StateMachine

__all__ = ["ToolSetter"]


class ToolSetter:
    """The tool setter (``controller.setter``)."""

    def __init__(self, settings: Settings, states: StateMachine, tools: ToolControl, positions: PositionsView,
                 coordinates: CoordinatesView, manual: RoutineRunner, alarms: AlarmSink) -> None:
        self._settings = settings
        self._states = states
        self._tools = tools
        self._positions = positions
        self._coordinates = coordinates
        self._manual = manual
        self._alarms = alarms

    def measure_tool(self, number: int) -> CommandResult:
        """Measure the length (Z offset) of tool ``number``, which must be in the spindle, on the
        tool setter (``[probe] setter_*``): up to the restart clearance, across over the setter,
        a probe down at ``max_feed_mm_min``, back up by more than that probe's overtravel, a
        second probe at a tenth of the feed, and back up to the clearance. The length is the
        machine Z of the second contact less ``setter_z_mm``; the table takes it at the end."""
        action = Action.MEASURE_TOOL
        states, tools = self._states, self._tools
        if states.state is not MachineState.IDLE:
            return states.refuse(action, f"machine is {states.state.label.lower()}")
        cfg = self._settings.config
        probe = cfg.probe
        sx, sy, sz = probe.setter_x_mm, probe.setter_y_mm, probe.setter_z_mm
        if not probe.has_setter or sx is None or sy is None or sz is None:
            return states.refuse(action, "no tool setter on this machine ([probe] drive, setter_x_mm, "
                                         "setter_y_mm and setter_z_mm in the machine configuration)")
        tool = tools.table.get(number)
        if tool is None:
            return states.refuse(action, f"T{number} is not in the tool table")
        if number != tools.in_spindle:
            return states.refuse(action, f"T{number} is not in the spindle: put it in and set it "
                                         "(In the spindle) first")
        axes = cfg.axes
        if not {"X", "Y", "Z"} <= set(axes):
            return states.refuse(action, "measuring on a tool setter needs X, Y and Z axes")
        if not all(self._positions.homed):
            return states.refuse(action, "axes not homed: the setter's position is not known")
        k = axes.index("Z")
        z_axis = cfg.machine.axes[k]
        c = cfg.controller
        clear = z_axis.max_pos if c.restart_clearance_mm is None else c.restart_clearance_mm
        # program Z of a machine Z: the routine runs in the active coordinate system, without G43
        frame = self._coordinates.frame().without_tool()
        shift = frame.total[k]
        fast = probe.max_feed_mm_min
        overtravel = probe_overtravel_mm(fast, cfg.machine.limits.j_max_mm_s3)
        bottom = max(sz - 1.0, z_axis.min_pos) - shift
        text = "\n".join((
            f"G21 G90 G94 G49 {self._coordinates.active_offset}",
            f"G53 G0 Z{clear:.4f}",
            f"G53 G0 X{sx:.4f} Y{sy:.4f}",
            f"G38.2 Z{bottom:.4f} F{fast:g}",
            # up from the contact (#5063), not from where the motion stopped: however late the
            # stop came (a busy computer), the slow probe starts clear of the setter
            f"G90 G0 Z[#5063 + {max(2.0, 2.0 * overtravel + 1.0):.4f}]",
            f"G38.2 Z{bottom:.4f} F{fast / 10.0:g}",
            f"G53 G0 Z{clear:.4f}",
        ))
        steps = {2: "the move up to the clearance height", 3: "the move over the tool setter",
                 4: "the fast probe down to the setter", 5: "the move up from the first contact",
                 6: "the slow probe down to the setter", 7: "the move back up"}

        def done(job: Job) -> None:
            results = job.probe_results
            second = results[1] if len(results) > 1 else None
            if second is None or not second.tripped:
                self._alarms.raise_alarm("tools", f"T{number}: the measurement has no second contact",
                                         Severity.WARNING, "measure_tool")
                return
            length = round(float(second.trip_position[k]) - sz, 6)
            res = tools.set_tool(tool.with_offset("Z", length))
            if res:
                self._manual.show_message(f"T{number} measured on the tool setter: length {length:.4f} mm")

        return self._manual.run_routine(text, f"measure T{number}", action, done,
                                        reason=f"measuring tool T{number}", steps=steps)

