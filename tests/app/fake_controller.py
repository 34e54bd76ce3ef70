"""A test double of the controller's public face (``app.machine.api.MachineApi``, checked by
tests/app/test_api.py): signals and commands, no worker, no threads.

Page tests use it to drive the widgets fast and deterministically; the flow tests use the
real controller on simulated drives.
"""

from __future__ import annotations

import os
from dataclasses import replace
from pathlib import Path

import numpy as np
from PySide6.QtCore import QObject, Signal

from app.machine.config import MachineConfig
from app.machine.model import (
    Activity,
    Alarm,
    AlarmState,
    BusStatus,
    CommandResult,
    ControllerSnapshot,
    HandwheelStatus,
    HoldKind,
    MachineState,
    ProbingRequest,
    ProbingResult,
    ProgramInfo,
    ProgramIssue,
    Prompt,
    RestartPreview,
    RunSummary,
    Severity,
    SignalReading,
    SpindleState,
    TrackingReport,
)
from ethercat.sim_part import SimPart
from planner.core.errors import ProgramError
from planner.core.program import Program
from planner.core.tools import Tool, ToolTable
from planner.gcode.interpreter import parse_program


class FakeController(QObject):
    stateChanged = Signal(object, str)
    activityChanged = Signal(object)
    positionChanged = Signal(object, object)
    programLoaded = Signal(object)
    programErrors = Signal(object)
    programReadAgain = Signal(object)
    loadingChanged = Signal(bool, str)
    programFinished = Signal(object)
    lineChanged = Signal(int)
    progressChanged = Signal(float, float)
    speedChanged = Signal(float)
    overridesChanged = Signal(float, float)
    feedOverrideNote = Signal(str)
    modesChanged = Signal(bool, bool, bool)
    alarmsChanged = Signal(object)
    homedChanged = Signal(object)
    offsetsChanged = Signal(object, str)
    spindleChanged = Signal(object)
    toolsChanged = Signal(object, int)
    busStateChanged = Signal(object)
    trackingUpdated = Signal(object)
    trackingSample = Signal(float, object, object)
    configChanged = Signal(object)
    commandRefused = Signal(str, str)
    message = Signal(str)
    probingFinished = Signal(object)
    handwheelChanged = Signal(object)
    spindleSample = Signal(float, float, float)
    statusChanged = Signal(object)

    def __init__(self, config: MachineConfig | None = None) -> None:
        super().__init__()
        self.config = config or MachineConfig.default()
        n = len(self.config.axes)
        self.calls: list[tuple] = []
        self.state = MachineState.IDLE
        self.activity = Activity.NONE
        self.machine_position = (0.0,) * n
        self.work_position = (0.0,) * n
        self.homed = (False,) * n
        self.work_offsets = dict(self.config.machine.work_offsets)
        self.active_offset = "G54"
        self.g92_offset: tuple[float, ...] | None = None
        self.xy_rotation_deg = 0.0
        self.program_info: ProgramInfo | None = None
        self.current_line = 0
        self.feed_override_pct = 100.0
        self.rapid_override_pct = 100.0
        self.single_block = False
        self.optional_stop = False
        self.block_delete = False
        self.spindle = SpindleState()
        self.tool_table = ToolTable()
        self.tool_in_spindle = 0
        self.alarms: tuple[Alarm, ...] = ()
        self.bus_status = BusStatus(kind="sim", connected=True, state="op",
                                    drive_states=("operation enabled",) * n)
        self.tracking = TrackingReport()
        self.state_reason = ""
        self.hold_kind = HoldKind.NONE
        self.prompt: Prompt | None = None
        self.reference_position = (0.0,) * n
        self.progress = (0.0, 0.0)
        self.resume_line = 0
        self.run_first_move = 0
        self.rotations: dict[str, float] = {}
        self.part_count = 0
        self.distance_to_go: tuple[float, ...] = ()
        self.part_target = 0
        self.run_log: list = []
        self.interrupted: tuple[str, int] | None = None
        self.opcua_status = None
        self.opcua_settings = self.config.opcua
        self.last_run: RunSummary | None = None
        self.last_probing: ProbingResult | None = None
        self.config_path = Path(self.config.path) if self.config.path else Path("machine.toml")
        self.coolant = (False, False)
        self.readings: tuple[SignalReading, ...] = ()
        wheel = self.config.wiring.handwheel
        self.handwheel = HandwheelStatus(configured=wheel.terminal is not None, step=wheel.steps[0])

    @property
    def program(self) -> object | None:
        return self.program_info.program if self.program_info else None

    @property
    def plan(self) -> object | None:
        return self.program_info.plan if self.program_info else None

    def snapshot(self) -> ControllerSnapshot:
        return ControllerSnapshot(
            state=self.state, activity=self.activity, axes=self.axes, machine_pos=self.machine_position,
            work_pos=self.work_position, homed=self.homed, active_offset=self.active_offset,
            line=self.current_line, progress=self.progress[0], remaining_s=self.progress[1],
            path_speed_mm_s=0.0, feed_override_pct=self.feed_override_pct,
            rapid_override_pct=self.rapid_override_pct, single_block=self.single_block,
            optional_stop=self.optional_stop, block_delete=self.block_delete, spindle=self.spindle,
            alarms=self.alarms, bus=self.bus_status)

    @property
    def axes(self) -> tuple[str, ...]:
        return self.config.axes

    @property
    def active_alarms(self) -> tuple[Alarm, ...]:
        return tuple(a for a in self.alarms if a.active)

    def _ok(self, action: str, *args: object) -> CommandResult:
        self.calls.append((action, *args))
        return CommandResult(True, action)

    def _set_state(self, state: MachineState, reason: str = "", hold: HoldKind = HoldKind.NONE) -> None:
        self.state = state
        self.hold_kind = hold if state is MachineState.HOLD else HoldKind.NONE
        if state is not MachineState.HOLD:
            self.prompt = None
        self.stateChanged.emit(state, reason)

    def refusal(self, action: str) -> str:
        if action in ("cycle_start", "run_from_line") and self.program_info is None:
            return "no program loaded"
        return ""

    # commands
    def connect_bus(self) -> CommandResult:
        return self._ok("connect_bus")

    def disconnect_bus(self) -> CommandResult:
        return self._ok("disconnect_bus")

    def shutdown(self) -> None:
        self.calls.append(("shutdown",))

    loading = False  # the fake checks synchronously (the real controller in a worker thread)
    loading_name = ""
    loading_progress = 0.0

    def load_program(self, source: str | os.PathLike[str], name: str | None = None, *, wait: bool = False,
                     timeout_s: float | None = None) -> CommandResult:
        if isinstance(source, os.PathLike) or (isinstance(source, str) and "\n" not in source
                                               and Path(source).is_file()):
            path, text = str(source), Path(source).read_text()
            name = name or Path(source).name
        else:
            path, text, name = "", str(source), name or "<text>"
        try:
            program = parse_program(text, name=name, machine=self.config.machine)
        except ProgramError as exc:
            self.program_info = None
            self.programErrors.emit(tuple(ProgramIssue(e.line, e.col, e.message) for e in exc.errors))
            return CommandResult(False, "load_program", str(exc))
        n = len(self.axes)
        self.program_info = ProgramInfo(name=name, path=path, text=text, line_count=text.count("\n") + 1,
                                        move_count=len(program.moves), cycle_time_s=12.0,
                                        length_mm=sum(m.length_mm for m in program.moves),
                                        bounds_min=(0.0,) * n, bounds_max=(0.0,) * n, program=program)
        self.programLoaded.emit(self.program_info)
        return self._ok("load_program", name)

    def wait_loaded(self, timeout_s: float | None = 60.0) -> CommandResult:
        ok = self.program_info is not None
        return CommandResult(ok, "load_program", "" if ok else "no program loaded")

    def cycle_start(self, *, wait: bool = False, from_start: bool = False) -> CommandResult:
        if self.program_info is None:
            self.commandRefused.emit("cycle_start", "no program loaded")
            return CommandResult(False, "cycle_start", "no program loaded")
        self._set_state(MachineState.RUNNING)
        return self._ok("cycle_start")

    def feed_hold(self) -> CommandResult:
        self._set_state(MachineState.HOLD, "feed hold", HoldKind.FEED_HOLD)
        return self._ok("feed_hold")

    def resume(self) -> CommandResult:
        self._set_state(MachineState.RUNNING)
        return self._ok("resume")

    def stop(self) -> CommandResult:
        self._set_state(MachineState.IDLE)
        return self._ok("stop")

    def reset(self) -> CommandResult:
        return self._ok("reset")

    def estop(self, reason: str = "operator") -> CommandResult:
        self._set_state(MachineState.ESTOP, reason)
        return self._ok("estop", reason)

    def estop_release(self) -> CommandResult:
        self._set_state(MachineState.IDLE)
        return self._ok("estop_release")

    def set_single_block(self, on: bool) -> CommandResult:
        self.single_block = on
        self.modesChanged.emit(self.single_block, self.optional_stop, self.block_delete)
        return self._ok("set_single_block", on)

    def set_optional_stop(self, on: bool) -> CommandResult:
        self.optional_stop = on
        self.modesChanged.emit(self.single_block, self.optional_stop, self.block_delete)
        return self._ok("set_optional_stop", on)

    def set_block_delete(self, on: bool) -> CommandResult:
        self.block_delete = on
        self.modesChanged.emit(self.single_block, self.optional_stop, self.block_delete)
        return self._ok("set_block_delete", on)

    def restart_preview(self, line: int = 0):
        self.calls.append(("restart_preview", line))
        start = np.asarray(self.machine_position, float)
        top = start.copy()
        top[-1] = 100.0
        return RestartPreview(line=line, cause=f"run from line {line}", path=np.array([start, top]),
                              clearance_mm=100.0, spindle_rpm=6000.0, tool=self.tool_in_spindle)

    def run_from_line(self, line: int, *, wait: bool = False) -> CommandResult:
        return self._ok("run_from_line", line)

    def set_feed_override(self, percent: float) -> CommandResult:
        self.feed_override_pct = percent
        self.overridesChanged.emit(self.feed_override_pct, self.rapid_override_pct)
        return self._ok("set_feed_override", percent)

    def set_rapid_override(self, percent: float) -> CommandResult:
        self.rapid_override_pct = percent
        self.overridesChanged.emit(self.feed_override_pct, self.rapid_override_pct)
        return self._ok("set_rapid_override", percent)

    def jog_start(self, axis: str | int, direction: int, speed_fraction: float = 1.0) -> CommandResult:
        self.jog_speed_fraction = speed_fraction
        return self._ok("jog_start", axis, direction)

    def jog_stop(self, axis: str | int | None = None) -> CommandResult:
        return self._ok("jog_stop", axis)

    def jog_increment(self, axis: str | int, step: float, direction: int = 1) -> CommandResult:
        return self._ok("jog_increment", axis, step, direction)

    def mdi(self, block: str) -> CommandResult:
        return self._ok("mdi", block)

    def home_axis(self, axis: str | int) -> CommandResult:
        i = self.axes.index(axis) if isinstance(axis, str) else axis
        homed = list(self.homed)
        homed[i] = True
        self.homed = tuple(homed)
        self.homedChanged.emit(self.homed)
        return self._ok("home_axis", axis)

    def home_all(self) -> CommandResult:
        self.homed = (True,) * len(self.axes)
        self.homedChanged.emit(self.homed)
        return self._ok("home_all")

    def set_machine_zero_here(self, axis: str | int | None = None) -> CommandResult:
        return self._ok("set_machine_zero_here", axis)

    def set_work_offset(self, name: str, values) -> CommandResult:
        self.work_offsets[name] = tuple(values)
        self.offsetsChanged.emit(dict(self.work_offsets), self.active_offset)
        return self._ok("set_work_offset", name, tuple(values))

    def set_part_target(self, target: int) -> None:
        self.part_target = int(target)
        self.calls.append(("set_part_target", int(target)))

    def reset_part_count(self) -> None:
        self.part_count = 0
        self.calls.append(("reset_part_count",))

    def runs(self, newest: int = 500) -> list:
        return list(self.run_log)

    def export_runs(self, folder: Path) -> tuple[Path, Path]:
        self.calls.append(("export_runs", folder))
        return folder / "runs.csv", folder / "runs.json"

    def set_work_rotation(self, name: str, degrees: float) -> CommandResult:
        self.rotations[name] = float(degrees)
        self.offsetsChanged.emit(dict(self.work_offsets), self.active_offset)
        return self._ok("set_work_rotation", name, degrees)

    def work_rotation(self, name: str) -> float:
        return self.rotations.get(name, 0.0)

    def select_work_offset(self, name: str) -> CommandResult:
        self.active_offset = name
        self.offsetsChanged.emit(dict(self.work_offsets), self.active_offset)
        return self._ok("select_work_offset", name)

    def clear_g92(self) -> CommandResult:
        self.g92_offset = None
        self.offsetsChanged.emit(dict(self.work_offsets), self.active_offset)
        return self._ok("clear_g92")

    def touch_off(self, axis: str | int, work_value: float = 0.0, offset: str | None = None) -> CommandResult:
        return self._ok("touch_off", axis, work_value, offset)

    def spindle_on(self, clockwise: bool = True, rpm: float | None = None) -> CommandResult:
        self.spindle = SpindleState(1 if clockwise else -1, rpm or self.spindle.rpm)
        self.spindleChanged.emit(self.spindle)
        return self._ok("spindle_on", clockwise, rpm)

    def spindle_off(self) -> CommandResult:
        self.spindle = SpindleState(0, self.spindle.rpm)
        self.spindleChanged.emit(self.spindle)
        return self._ok("spindle_off")

    def set_spindle_override(self, percent: float) -> CommandResult:
        self.spindle = replace(self.spindle, override_pct=percent)
        self.spindleChanged.emit(self.spindle)
        return self._ok("set_spindle_override", percent)

    def _tools(self, table: ToolTable, in_spindle: int) -> None:
        self.tool_table, self.tool_in_spindle = table, in_spindle
        self.toolsChanged.emit(table, in_spindle)

    def set_tool(self, tool: Tool) -> CommandResult:
        self._tools(self.tool_table.with_tool(tool), self.tool_in_spindle)
        return self._ok("set_tool", tool)

    def remove_tool(self, number: int) -> CommandResult:
        self._tools(self.tool_table.without(number), self.tool_in_spindle)
        return self._ok("remove_tool", number)

    def set_tool_in_spindle(self, number: int) -> CommandResult:
        self._tools(self.tool_table, number)
        return self._ok("set_tool_in_spindle", number)

    def touch_off_tool(self, number: int, surface_z_mm: float = 0.0) -> CommandResult:
        return self._ok("touch_off_tool", number, surface_z_mm)

    def import_tool_table(self, path: str) -> CommandResult:
        return self._ok("import_tool_table", path)

    def measure_tool(self, number: int) -> CommandResult:
        return self._ok("measure_tool", number)

    def probe_routine(self, req: ProbingRequest) -> str:
        return f"o<{req.wizard.value}> call"

    def preview_probing(self, req: ProbingRequest) -> Program | CommandResult:
        """A square around where the machine stands: what a wizard's preview draws."""
        self.calls.append(("preview_probing", req))
        return parse_program("G91 G0 X5\nG0 Y5\nG0 X-5\nG0 Y-5\n", "probe", self.config.machine)

    def run_probing(self, req: ProbingRequest) -> CommandResult:
        return self._ok("run_probing", req)

    def simulate_part(self, part: SimPart | None) -> bool:
        self.calls.append(("simulate_part", part))
        return True

    def spindle_speed(self, rpm: float) -> CommandResult:
        self.spindle = replace(self.spindle, rpm=rpm)
        self.spindleChanged.emit(self.spindle)
        return self._ok("spindle_speed", rpm)

    def set_coolant(self, flood: bool | None = None, mist: bool | None = None) -> CommandResult:
        f, m = self.coolant
        self.coolant = (f if flood is None else bool(flood), m if mist is None else bool(mist))
        return self._ok("set_coolant", flood, mist)

    def set_work_light(self, on: bool) -> CommandResult:
        return self._ok("set_work_light", on)

    def override_limits(self, on: bool = True) -> CommandResult:
        return self._ok("override_limits", on)

    def signal_readings(self) -> tuple[SignalReading, ...]:
        return self.readings

    def simulate_input(self, key: str, value: bool | None) -> CommandResult:
        return self._ok("simulate_input", key, value)

    def acknowledge_alarm(self, alarm_id: int | None = None) -> CommandResult:
        self.alarms = tuple(replace(a, state=AlarmState.ACKNOWLEDGED)
                            if alarm_id is None or a.id == alarm_id else a for a in self.alarms)
        self.alarmsChanged.emit(self.alarms)
        return self._ok("acknowledge_alarm", alarm_id)

    def update_config(self, config: MachineConfig, *, wait: bool = False) -> CommandResult:
        self.config = config
        self.configChanged.emit(config)
        return self._ok("update_config")

    def select_handwheel(self, axis: str) -> CommandResult:
        self.handwheel = replace(self.handwheel, axis=axis.upper(), live=bool(axis))
        self.handwheelChanged.emit(self.handwheel)
        return self._ok("select_handwheel", axis)

    def set_handwheel_step(self, scale_index: int) -> CommandResult:
        steps = self.config.wiring.handwheel.steps
        self.handwheel = replace(self.handwheel, scale_index=scale_index, step=steps[scale_index])
        self.handwheelChanged.emit(self.handwheel)
        return self._ok("set_handwheel_step", scale_index)

    def turn_handwheel(self, counts: int) -> CommandResult:
        return self._ok("turn_handwheel", counts)

    def simulate_spindle_load(self, rpm: float | None) -> CommandResult:
        return self._ok("simulate_spindle_load", rpm)

    # test helpers
    def raise_alarm(self, cause: str, source: str = "drive X") -> None:
        alarm = Alarm(len(self.alarms) + 1, 0.0, source, cause, Severity.QUICK_STOP)
        self.alarms = self.alarms + (alarm,)
        self.alarmsChanged.emit(self.alarms)
