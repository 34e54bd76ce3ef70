"""The controller's public face, as a type: what the panel may use of ``MachineController``.

The pages and widgets talk to the controller through these signals, read-only properties
and commands only; the panel's tests drive the same pages with a test double, and both the
controller and the double are checked against this protocol (``tests/app/test_api.py``), so
a page cannot come to depend on something only one of them has.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Protocol

from PySide6.QtCore import SignalInstance

from app.machine.config import MachineConfig
from app.machine.model import (
    Activity,
    Alarm,
    BusStatus,
    CommandResult,
    ControllerSnapshot,
    HandwheelStatus,
    HoldKind,
    MachineState,
    ProbingRequest,
    ProbingResult,
    ProgramInfo,
    Prompt,
    RestartPreview,
    RunSummary,
    SignalReading,
    SpindleState,
    TrackingReport,
)
from app.machine.program.joblog import RunRecord
from ethercat.sim_part import SimPart
from opcua_server.server import ServerStatus
from opcua_server.settings import OpcUaSettings
from planner.core.program import Program
from planner.core.tools import Tool, ToolTable

__all__ = ["MachineApi"]


class MachineApi(Protocol):
    """Signals (emitted in the controller's thread), state and commands of the machine. The
    controller has more for headless use (simulated time: ``advance``, ``run_until``; blocking
    waits; the worker itself), which the panel never needs.
    Commands never raise for an operator-level refusal: they return a falsy ``CommandResult``
    with the reason and emit ``commandRefused``."""

    stateChanged: SignalInstance  # (MachineState, reason text)
    activityChanged: SignalInstance  # Activity
    positionChanged: SignalInstance  # (machine pos tuple, work pos tuple), <= 30 Hz
    trackingSample: SignalInstance  # (time s, reference, actual) machine coords, <= 30 Hz
    programLoaded: SignalInstance  # ProgramInfo (checked: no errors, within soft limits)
    programErrors: SignalInstance  # tuple[ProgramIssue, ...] (parse errors, soft limits)
    # planner.core.program.Program: the running program read again with what a probe or M66 read
    # (the path from there on is the machine's, not the one assumed at the check)
    programReadAgain: SignalInstance
    loadingChanged: SignalInstance  # (a program is being checked, its name)
    programFinished: SignalInstance  # RunSummary (completed or not)
    lineChanged: SignalInstance  # current source line (1-based), 0 when none
    progressChanged: SignalInstance  # (fraction 0..1, remaining time s at current override)
    speedChanged: SignalInstance  # commanded path speed mm/s
    overridesChanged: SignalInstance  # (feed %, rapid %)
    feedOverrideNote: SignalInstance  # what the feed override does here when not its value ("" when it is)
    modesChanged: SignalInstance  # (single block, optional stop, block delete)
    alarmsChanged: SignalInstance  # tuple[Alarm, ...] (active and history)
    homedChanged: SignalInstance  # tuple[bool, ...] per axis
    offsetsChanged: SignalInstance  # (dict name -> tuple per axis, active name)
    spindleChanged: SignalInstance  # SpindleState
    toolsChanged: SignalInstance  # (ToolTable, tool in the spindle; 0: none)
    busStateChanged: SignalInstance  # BusStatus
    trackingUpdated: SignalInstance  # TrackingReport (during a run ~1 Hz, and at the end)
    configChanged: SignalInstance  # MachineConfig (after update_config / load)
    commandRefused: SignalInstance  # (action, reason)
    message: SignalInstance  # informational text for the status line
    probingFinished: SignalInstance  # ProbingResult: what a probing wizard found (and wrote)
    handwheelChanged: SignalInstance  # HandwheelStatus: its axis, step, whether it is live and why not
    spindleSample: SignalInstance  # (time s, rpm commanded, rpm read) of the spindle's own drive, <= 30 Hz
    # ControllerSnapshot: the status in one object, published when anything in it changed (at
    # most once an event-loop turn); ``snapshot()`` makes one now
    statusChanged: SignalInstance

    @property
    def state(self) -> MachineState:
        """Current machine state."""
        ...

    @property
    def prompt(self) -> Prompt | None:
        """What the program stop in force asks of the operator (tool to insert, line), None
        outside HOLD or in a feed hold."""
        ...

    @property
    def hold_kind(self) -> HoldKind:
        """Why the machine is in HOLD (``HoldKind.NONE`` otherwise)."""
        ...

    @property
    def state_reason(self) -> str:
        """Why the machine is in its state (text for the panel)."""
        ...

    @property
    def activity(self) -> Activity:
        """What the machine is doing while RUNNING / HOLD."""
        ...

    @property
    def config(self) -> MachineConfig:
        """The applied machine configuration."""
        ...

    @property
    def axes(self) -> tuple[str, ...]:
        """Axis names, in configuration order."""
        ...

    @property
    def machine_position(self) -> tuple[float, ...]:
        """Actual position, machine coordinates."""
        ...

    @property
    def work_position(self) -> tuple[float, ...]:
        """Actual position in the active work offset's coordinates."""
        ...

    @property
    def reference_position(self) -> tuple[float, ...]:
        """Last set-point sent to the drives (machine coordinates)."""
        ...

    @property
    def homed(self) -> tuple[bool, ...]:
        """Homed flag per axis."""
        ...

    @property
    def work_offsets(self) -> dict[str, tuple[float, ...]]:
        """The G54-G59 table."""
        ...

    @property
    def active_offset(self) -> str:
        """Name of the active work offset."""
        ...

    @property
    def g92_offset(self) -> tuple[float, ...] | None:
        """The G92/G52 offset per axis when it is on, else None."""
        ...

    @property
    def xy_rotation_deg(self) -> float:
        """The XY rotation (G10 L2 R) of the active work offset, degrees."""
        ...

    def clear_g92(self) -> CommandResult:
        """Switch the G92/G52 offset off and zero its parameters (G92.1)."""
        ...

    @property
    def program_info(self) -> ProgramInfo | None:
        """The loaded program (None if none)."""
        ...

    @property
    def program(self) -> object | None:
        """The loaded, checked ``planner.core.program.Program`` (None if none)."""
        ...

    @property
    def plan(self) -> object | None:
        """The ``planner.motion.plan.Plan`` of the loaded program (planned with the override budget)."""
        ...

    @property
    def current_line(self) -> int:
        """Source line the drives are executing (0 when none)."""
        ...

    @property
    def progress(self) -> tuple[float, float]:
        """(fraction 0..1, remaining time s at the current feed override) of the running program."""
        ...

    @property
    def feed_override_pct(self) -> float:
        """Feed override in percent."""
        ...

    @property
    def rapid_override_pct(self) -> float:
        """Rapid override in percent."""
        ...

    @property
    def single_block(self) -> bool:
        """Single-block mode."""
        ...

    @property
    def optional_stop(self) -> bool:
        """Optional stop (M01) honoured."""
        ...

    @property
    def block_delete(self) -> bool:
        """Block delete: lines starting with '/' skipped."""
        ...

    @property
    def spindle(self) -> SpindleState:
        """Spindle state."""
        ...

    @property
    def tool_table(self) -> ToolTable:
        """The tool table (persisted in the state folder as ``tools.tbl``)."""
        ...

    @property
    def tool_in_spindle(self) -> int:
        """The tool in the spindle (0: none)."""
        ...

    @property
    def alarms(self) -> tuple[Alarm, ...]:
        """All alarms (active and history), oldest first."""
        ...

    @property
    def active_alarms(self) -> tuple[Alarm, ...]:
        """Alarms not yet acknowledged."""
        ...

    @property
    def bus_status(self) -> BusStatus:
        """Bus / worker state."""
        ...

    @property
    def tracking(self) -> TrackingReport:
        """Tracking RMSE/MSE of the last (or current) run."""
        ...

    @property
    def last_run(self) -> RunSummary | None:
        """Summary of the last program run (None before the first)."""
        ...

    @property
    def last_probing(self) -> ProbingResult | None:
        """What the last probing wizard found (None before one ended, or while one runs)."""
        ...

    @property
    def config_path(self) -> Path:
        """The machine configuration file that ``update_config`` writes."""
        ...

    @property
    def loading(self) -> bool:
        """True while a program is being read, checked and planned, or checked again, or planned for
        single block (cycle start refused meanwhile)."""
        ...

    @property
    def loading_name(self) -> str:
        """Name of the program being checked ("" when none)."""
        ...

    @property
    def loading_progress(self) -> float:
        """How far the program being checked is, 0 .. 1 (0 when none)."""
        ...

    @property
    def interrupted(self) -> tuple[str, int] | None:
        """After a power loss or a kill: the program that was running (its file, or its name)
        and its line; None when the last end was clean or a program has run since."""
        ...

    @property
    def opcua_status(self) -> ServerStatus | None:
        """The OPC UA server: where it serves, or why it does not (None when it is off)."""
        ...

    @property
    def opcua_settings(self) -> OpcUaSettings:
        """What the server was asked to be (the configuration's ``[opcua]`` or the command line's)."""
        ...

    @property
    def distance_to_go(self) -> tuple[float, ...]:
        """What is left of the move the drives are on, per axis (() at rest)."""
        ...

    @property
    def part_count(self) -> int:
        """Parts made: program runs to their end, counted in the state folder."""
        ...

    @property
    def part_target(self) -> int:
        """The parts to make (0: no target); reached, cycle start is refused."""
        ...

    def set_part_target(self, target: int) -> None:
        """Set the part target (0: none)."""
        ...

    def reset_part_count(self) -> None:
        """Start counting parts again from 0."""
        ...

    def runs(self, newest: int = 500) -> list[RunRecord]:
        """The run log's complete runs, oldest first."""
        ...

    def export_runs(self, folder: Path) -> tuple[Path, Path]:
        """The run log as runs.csv and runs.json in ``folder``."""
        ...

    @property
    def run_first_move(self) -> int:
        """The move of the loaded program its current (or last) run began with: 0 from the
        beginning, the line's first move after run from line (a resume keeps it)."""
        ...

    @property
    def resume_line(self) -> int:
        """Line a resume (after a fault or E-stop mid-program) would continue from, 0 if none."""
        ...

    def snapshot(self) -> ControllerSnapshot:
        """The status now in one immutable object: state and mode, program, line, progress,
        overrides, spindle, tool, positions in machine and work coordinates with the offsets in
        force (``frame``), alarms, the bus."""
        ...

    def refusal(self, action: str) -> str:
        """Why ``action`` ("cycle_start", "run_from_line", "jog", "mdi", "home", "feed_hold",
        "resume", "touch_off", "spindle_on", "update_config", ...) would be refused now; "" when
        allowed (for enabling buttons)."""
        ...

    def reset(self) -> CommandResult:
        """HOLD (at standstill): abandon the program; ALARM: acknowledge, fault reset and re-enable
        (the resume point is kept); IDLE: forget the resume point. Ends in IDLE."""
        ...

    def estop(self, reason: str = "operator") -> CommandResult:
        """Emergency stop: the drives' quick stop at once, program abandoned (resume point kept),
        spindle off, -> ESTOP."""
        ...

    def estop_release(self) -> CommandResult:
        """Release the E-stop: fault reset and re-enable the drives, -> IDLE."""
        ...

    def update_config(self, config: MachineConfig, *, wait: bool = False) -> CommandResult:
        """Validate, write atomically (temp + os.replace, old file kept as .bak) and apply."""
        ...

    def connect_bus(self) -> CommandResult:
        """Start the worker (simulated drives when the bus kind is "sim") and enable the drives:
        DISCONNECTED -> IDLE."""
        ...

    def disconnect_bus(self) -> CommandResult:
        """Stop any motion (a jerk-limited stop along the path, at most ``RAMP_DOWN_TIMEOUT_S``),
        abandon it, disable the drives and stop the worker, then the feeder: -> DISCONNECTED."""
        ...

    def shutdown(self) -> None:
        """Stop any motion (jerk-limited), spindle off, disconnect (worker stopped before the
        feeder), persist positions and offsets; safe to call twice."""
        ...

    def load_program(
        self,
        source: str | os.PathLike[str],
        name: str | None = None,
        *,
        wait: bool = False,
        timeout_s: float | None = None,
    ) -> CommandResult:
        """Load a program from a path (``os.PathLike`` or an existing file name) or G-code text."""
        ...

    def cycle_start(self, *, wait: bool = False, from_start: bool = False) -> CommandResult:
        """Start the loaded program from its beginning (IDLE), or continue (HOLD). After a
        program stopped part-way (``resume_line``), refused until the operator chooses:
        ``resume()`` there, or ``from_start``."""
        ...

    def feed_hold(self) -> CommandResult:
        """Jerk-limited stop along the path (time-optimal, ``planner.motion.stopping``, or the time scale
        to 0 where that would exceed a limit): RUNNING -> HOLD."""
        ...

    def resume(self) -> CommandResult:
        """HOLD -> RUNNING: continue after a feed hold, a single-block stop or M00/M01/M06 to the
        same end. In IDLE after a program stopped part-way (``resume_line``): the safe approach
        to where it stopped (up, across, spindle, down), and on from there."""
        ...

    def stop(self) -> CommandResult:
        """Jerk-limited stop along the path, then abandon the program (-> IDLE), keeping the
        point where it stopped (``resume_line``)."""
        ...

    def set_single_block(self, on: bool) -> CommandResult:
        """Single block: the plan stops at every block end (HOLD there; cycle start goes on)."""
        ...

    def set_optional_stop(self, on: bool) -> CommandResult:
        """Honour M01 (optional pause); may change while running."""
        ...

    def set_block_delete(self, on: bool) -> CommandResult:
        """Skip lines starting with '/'; refused while a program runs (it is read whole before
        it runs), a loaded program checked again with it."""
        ...

    def restart_preview(self, line: int = 0) -> RestartPreview | str:
        """What a restart would do before it moves (``line`` > 0: run from that line; else
        resume where the program stopped): the way there, the clearance height, the spindle,
        the tool; or why there is none."""
        ...

    def run_from_line(self, line: int, *, wait: bool = False) -> CommandResult:
        """Start the loaded program at source line ``line``: the spindle as of that line is
        restored, a safe approach (retract Z to the higher of the current and target heights,
        move the other axes, then down) brings the tool to the line's start point, then the
        program runs on from there."""
        ...

    def set_feed_override(self, percent: float) -> CommandResult:
        """Feed override 0-200 %, applied while running without a jump and within every limit
        (``app.machine.timescale``); above 100 % the speed stays capped by the machine limits."""
        ...

    def set_rapid_override(self, percent: float) -> CommandResult:
        """Rapid override 0-100 % (rapid moves only), applied like the feed override."""
        ...

    def jog_start(self, axis: str | int, direction: int, speed_fraction: float = 1.0) -> CommandResult:
        """Continuous jog of one axis toward + (1) or - (-1) at ``speed_fraction`` of the jog speed."""
        ...

    def jog_stop(self, axis: str | int | None = None) -> CommandResult:
        """Release: jerk-limited stop of the jog (harmless when nothing jogs)."""
        ...

    def jog_increment(self, axis: str | int, step: float, direction: int = 1) -> CommandResult:
        """Move one axis by ``direction * step`` (0.001 / 0.01 / 0.1 / 1 mm or degrees), refused
        when the target is beyond the soft limit."""
        ...

    def mdi(self, block: str) -> CommandResult:
        """Execute one G-code block with the active work offset and the same checks as a program
        (parse, soft limits on the whole path, homed rule)."""
        ...

    def home_axis(self, axis: str | int) -> CommandResult:
        """Home one axis by the configured method: "drive" (CiA 402 homing mode 6 with
        ``homing.drive_method``, via the worker) or "set_here" (current position = machine zero)."""
        ...

    def home_all(self) -> CommandResult:
        """Home every axis (Z first) by the configured method."""
        ...

    def set_machine_zero_here(self, axis: str | int | None = None) -> CommandResult:
        """Declare the current position machine zero for one axis (all when None); homed; persisted."""
        ...

    def set_work_offset(self, name: str, values: dict[str, float] | tuple[float, ...]) -> CommandResult:
        """Set a G54-G59 offset (machine coordinates of part zero; a dict by axis name or one value
        per axis); persisted."""
        ...

    def select_work_offset(self, name: str) -> CommandResult:
        """Make one of G54-G59.3 the active work offset (MDI and work coordinates); persisted."""
        ...

    def set_work_rotation(self, name: str, degrees: float) -> CommandResult:
        """The XY rotation of a coordinate system (G10 L2 R, degrees), persisted."""
        ...

    def work_rotation(self, name: str) -> float:
        """The XY rotation (degrees) of coordinate system ``name``."""
        ...

    def touch_off(self, axis: str | int, work_value: float = 0.0, offset: str | None = None) -> CommandResult:
        """Set part zero here: choose the offset (active unless named) so that the current position
        reads ``work_value`` in work coordinates on ``axis``."""
        ...

    def spindle_on(self, clockwise: bool = True, rpm: float | None = None) -> CommandResult:
        """Spindle on, clockwise (M03) or counter-clockwise (M04), at ``rpm`` (last speed if None)."""
        ...

    def spindle_off(self) -> CommandResult:
        """Spindle off (M05); always allowed."""
        ...

    def spindle_speed(self, rpm: float) -> CommandResult:
        """Set the spindle speed (applied at once when running)."""
        ...

    def set_spindle_override(self, percent: float) -> CommandResult:
        """Spindle override 50-150 % (S times it, capped at the spindle's maximum)."""
        ...

    def set_tool(self, tool: Tool) -> CommandResult:
        """Add or replace a tool in the table (refused while a program runs)."""
        ...

    def remove_tool(self, number: int) -> CommandResult:
        """Remove a tool from the table (not the one in the spindle)."""
        ...

    def set_tool_in_spindle(self, number: int) -> CommandResult:
        """The tool now in the spindle, without a change (as M61 Q)."""
        ...

    def touch_off_tool(self, number: int, surface_z_mm: float = 0.0) -> CommandResult:
        """Set a tool's length so the work Z here reads ``surface_z_mm`` (LinuxCNC G10 L10 Z)."""
        ...

    def import_tool_table(self, path: str) -> CommandResult:
        """Replace the table by a LinuxCNC .tbl file (refused whole if a line is wrong)."""
        ...

    def measure_tool(self, number: int) -> CommandResult:
        """Measure the length of the tool in the spindle on the tool setter (``[probe] setter_*``):
        the machine moves by itself; the table takes the length when it is done."""
        ...

    def probe_routine(self, req: ProbingRequest) -> str:
        """The blocks a probing wizard runs (the shipped routine's call, with the probe's length
        and the system that takes the result)."""
        ...

    def preview_probing(self, req: ProbingRequest) -> Program | CommandResult:
        """A probing wizard's moves as read and checked before it runs (each probe to the end of
        its search), to draw before the operator confirms; the refusal otherwise."""
        ...

    def run_probing(self, req: ProbingRequest) -> CommandResult:
        """Run a probing wizard; ``probingFinished`` says what it found and wrote."""
        ...

    def simulate_part(self, part: SimPart | None) -> bool:
        """Simulated drives: a workpiece the probe touches (False on a real bus)."""
        ...

    def acknowledge_alarm(self, alarm_id: int | None = None) -> CommandResult:
        """Acknowledge one alarm (all active ones when None); persisted."""
        ...

    # ------------------------------------------------------------------ the machine around the drives
    @property
    def coolant(self) -> tuple[bool, bool]:
        """(flood, mist) as switched now."""
        ...

    def set_coolant(self, flood: bool | None = None, mist: bool | None = None) -> CommandResult:
        """The coolant buttons (M8, M7; both off: M9); None leaves one as it is."""
        ...

    def set_work_light(self, on: bool) -> CommandResult:
        """The work light on or off (refused when it is not wired)."""
        ...

    def override_limits(self, on: bool = True) -> CommandResult:
        """Let an axis standing on a limit switch be reset and jogged off it (never toward it);
        ends by itself once no limit switch reads active."""
        ...

    def signal_readings(self) -> tuple[SignalReading, ...]:
        """Every wired signal: where it is wired and what it reads now."""
        ...

    def simulate_input(self, key: str, value: bool | None) -> CommandResult:
        """Simulated drives: signal ``key`` reads ``value`` until released with None."""
        ...

    @property
    def handwheel(self) -> HandwheelStatus:
        """The handwheel: its axis and step, whether it moves the axis now and why not."""
        ...

    def select_handwheel(self, axis: str) -> CommandResult:
        """Give the handwheel axis ``axis`` ("": off); refused when the machine has none or its
        pendant's selector chooses."""
        ...

    def set_handwheel_step(self, scale_index: int) -> CommandResult:
        """The handwheel's step per detent: 0 x1, 1 x10, 2 x100 (``[handwheel] steps``)."""
        ...

    def turn_handwheel(self, counts: int) -> CommandResult:
        """A simulated machine's handwheel turned by ``counts`` (refused on a real bus)."""
        ...

    def simulate_spindle_load(self, rpm: float | None) -> CommandResult:
        """A simulated spindle drive bogged down to ``rpm`` by a load (None: off; refused without a
        spindle drive or on a real bus)."""
        ...
