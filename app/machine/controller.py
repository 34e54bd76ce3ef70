"""MachineController: what a CNC control does between the operator's buttons and the drives.

Public API (stable; the panel builds against it). QtCore only, no widgets: it runs headless.

Threads. The controller object lives in the GUI thread. A feeder thread (no Qt) turns the
plan into set-points and keeps the worker's buffer filled ``lead_s`` ahead; a 30 Hz QTimer
reads the worker's snapshot and emits the signals below (never per control cycle).

Commands never raise for an operator-level refusal: they return a ``CommandResult`` (truthy
when accepted, ``reason`` otherwise) and emit ``commandRefused(action, reason)``.

States (``MachineState``) and the legal transitions (``TRANSITIONS``)::

    DISCONNECTED -> IDLE (connect_bus) | ESTOP
    IDLE    -> RUNNING (cycle_start, mdi, jog, run_from_line) | HOMING | ALARM | ESTOP | DISCONNECTED
    HOMING  -> IDLE | ALARM | ESTOP
    RUNNING -> HOLD (feed_hold, single block, M00/M01) | IDLE (end, stop) | ALARM | ESTOP
    HOLD    -> RUNNING (resume / cycle_start) | IDLE (stop, reset) | ALARM | ESTOP
    ALARM   -> IDLE (reset, alarms acknowledged) | ESTOP
    ESTOP   -> IDLE (estop_release) | DISCONNECTED

How motion is made. Every motion (program, MDI block, jog, approach move) is parsed, checked
against the soft limits on its whole path (arcs by their exact extremes) and planned with the
override budget (``app.machine.timescale``: acceleration and jerk limits reduced to 85 % and
70 %); a ``TimeScaledExecutor`` then runs the plan at a time scale sigma that carries feed
override (0-150 %), rapid override (0-100 %) and feed hold without leaving the path or
exceeding a limit; a hold or stop while moving is the time-optimal jerk-limited stop along the
path (``planner.stopping``) when it keeps every limit, else sigma's own ramp. Continuous jog
is a move planned to the soft limit (a lost release stops there); a release is a hold followed
by abandoning the move. Faults keep the point to resume from (``resume_line``; ``resume()`` in
IDLE moves there safely and continues).

Machine vs drive coordinates: machine = drive position - home offset (set by homing); work =
machine - active work offset (G54-G59). Persisted in the state directory (``persist.py``).

Beyond the commands listed above: ``advance(seconds)`` / ``run_until(pred)`` drive simulated
time in ``worker_mode="manual"`` (tests, fast headless runs); read-only ``resume_line``,
``reference_position``, ``progress``, ``last_run`` (RunSummary), ``state_reason``,
``config_path``, ``worker``.

Units: positions mm / degrees (rotary), speeds mm/s, times s, overrides in percent.

Parts. ``MachineController`` is the one public facade: the signals, the public commands and
read-only properties (``MachineApi`` in ``app.machine.api`` lists them; the panel's test
double is checked against it). Behind it, one collaborator per responsibility, each owning
the state it sets up in its ``__init__`` and reaching the others through the facade:

    controller.states      StateMachine    state, reason, activity; TRANSITIONS, refusals, E-stop, reset
    controller.conn        Connection      configuration, persistence, worker + feeder life cycle, shutdown
    controller.stream      Streamer        jobs, set-point streaming (lead_s), pause points, end of a run
    controller.loader      ProgramLoader   load (parse, soft limits, plan), re-checks, single-block plans,
                                           in a worker thread (cycle start runs the load-time plan)
    controller.run         ProgramRunner   cycle start, feed hold, resume, stop, run from line, overrides
    controller.manual      ManualMotion    jog (continuous, incremental), MDI
    controller.pos         Positions       positions, homed flags, machine zero (homing), work offsets
    controller.spindle_ctl SpindleControl  spindle
    controller.tools       ToolControl     tool table, tool in the spindle
    controller.alarm_log   AlarmLog        alarm list and reactions
    controller.poller      StatusPoller    polling the worker, positions/bus signals
    app.machine.jobs       Job, ResumePoint, SentLimits records
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

from PySide6.QtCore import QObject, Signal

from app.machine.alarms import AlarmLog
from app.machine.config import MachineConfig
from app.machine.connection import RAMP_DOWN_TIMEOUT_S, Connection
from app.machine.feeder import Streamer
from app.machine.homing import Positions
from app.machine.inputs import InputWaiter, Prober
from app.machine.jobs import SentLimits
from app.machine.manual import JOG_INCREMENTS, ManualMotion
from app.machine.model import (
    Activity,
    Alarm,
    BusStatus,
    CommandResult,
    ControllerSnapshot,
    HoldKind,
    MachineState,
    ProgramInfo,
    Prompt,
    RunSummary,
    Severity,
    SpindleState,
    TrackingReport,
)
from app.machine.outputs import DigitalOutputs
from app.machine.program_load import ProgramLoader
from app.machine.program_run import ProgramRunner
from app.machine.spindle import SpindleControl
from app.machine.states import TRANSITIONS, StateMachine
from app.machine.status import StatusPoller
from app.machine.tooling import ToolControl
from app.paths import DEFAULT_STATE_DIR
from planner.tools import Tool, ToolTable

__all__ = [
    "DEFAULT_STATE_DIR",
    "JOG_INCREMENTS",
    "RAMP_DOWN_TIMEOUT_S",
    "TRANSITIONS",
    "SentLimits",
    "MachineController",
]


class MachineController(QObject):
    """The machine: program run, hold/override, jog, MDI, homing, offsets, limits, alarms.

    Construct with a configuration (``MachineConfig``, a TOML path, or None for the state
    dir's saved ``machine.toml`` / the shipped XYZ mill) and a state directory for persisted
    positions, offsets, homed flags and alarms. Call ``connect_bus()`` to start the worker
    (simulated drives when the configuration's bus kind is "sim"), ``shutdown()`` at exit.
    """

    # --- signals (all emitted in the controller's thread) -------------------------------
    stateChanged = Signal(object, str)  # (MachineState, reason text)
    activityChanged = Signal(object)  # Activity
    positionChanged = Signal(object, object)  # (machine pos tuple, work pos tuple), <= 30 Hz
    trackingSample = Signal(float, object, object)  # (time s, reference, actual) machine coords, <= 30 Hz
    programLoaded = Signal(object)  # ProgramInfo (checked: no errors, within soft limits)
    # Program: the running program read again with what a probe or M66 read (app.machine.inputs)
    programReadAgain = Signal(object)
    programErrors = Signal(object)  # tuple[ProgramIssue, ...] (parse errors, soft limits)
    loadingChanged = Signal(bool, str)  # (a program is being checked, its name)
    programFinished = Signal(object)  # RunSummary (completed or not)
    lineChanged = Signal(int)  # current source line (1-based), 0 when none
    progressChanged = Signal(float, float)  # (fraction 0..1, remaining time s at current override)
    speedChanged = Signal(float)  # commanded path speed mm/s
    overridesChanged = Signal(float, float)  # (feed %, rapid %)
    # what the feed override does where the run is, when not what the knob says ("runs 100 %:
    # program" where a tap or M49 turned it off, "runs 120 %: limits" where they cap it; "")
    feedOverrideNote = Signal(str)
    modesChanged = Signal(bool, bool, bool)  # (single block, optional stop, block delete)
    alarmsChanged = Signal(object)  # tuple[Alarm, ...] (active and history)
    homedChanged = Signal(object)  # tuple[bool, ...] per axis
    offsetsChanged = Signal(object, str)  # (dict name -> tuple per axis, active name)
    spindleChanged = Signal(object)  # SpindleState
    toolsChanged = Signal(object, int)  # (ToolTable, tool in the spindle; 0: none)
    busStateChanged = Signal(object)  # BusStatus
    trackingUpdated = Signal(object)  # TrackingReport (during a run ~1 Hz, and at the end)
    configChanged = Signal(object)  # MachineConfig (after update_config / load)
    commandRefused = Signal(str, str)  # (action, reason)
    message = Signal(str)  # informational text for the status line

    def __init__(
        self,
        config: MachineConfig | str | os.PathLike[str] | None = None,
        *,
        state_dir: str | os.PathLike[str] | None = None,
        worker_factory: Callable[..., object] | None = None,
        parent: QObject | None = None,
        worker_mode: str = "process",
        poll_hz: float = 30.0,
    ) -> None:
        """``worker_mode``: "process" (default, the real-time worker in its own process),
        "thread", or "manual" (no clock: tests and tools drive time with ``advance``)."""
        super().__init__(parent)
        # one lock for what the feeder thread and the GUI thread both touch (job, worker)
        self._lock = threading.RLock()
        self.conn = Connection(self, config, state_dir, worker_factory, worker_mode, poll_hz)
        self.states = StateMachine(self)
        self.pos = Positions(self)
        self.alarm_log = AlarmLog(self)
        self.conn.restore_persisted()
        self.run = ProgramRunner(self)
        self.spindle_ctl = SpindleControl(self)
        self.outputs = DigitalOutputs(self)
        self.tools = ToolControl(self)
        self.loader = ProgramLoader(self)
        self.stream = Streamer(self)
        self.prober = Prober(self)
        self.waiter = InputWaiter(self)
        self.manual = ManualMotion(self)
        self.poller = StatusPoller(self)
        self.conn.timer.timeout.connect(self.poller.poll)
        for text in self.conn.store.problems:
            self.alarm_log.raise_alarm("persistence", text, Severity.WARNING, "state_file")
        if self.conn.config_notice:
            self.alarm_log.raise_alarm(
                "config", self.conn.config_notice, Severity.WARNING, "config_recovered"
            )

    @property
    def state(self) -> MachineState:
        """Current machine state."""
        return self.states.state

    @property
    def prompt(self) -> Prompt | None:
        return self.states.prompt

    @property
    def hold_kind(self) -> HoldKind:
        """Why the machine is in HOLD (``HoldKind.NONE`` otherwise)."""
        return self.states.hold_kind

    @property
    def state_reason(self) -> str:
        """Why the machine is in its state (text for the panel)."""
        return self.states.state_reason

    @property
    def activity(self) -> Activity:
        """What the machine is doing while RUNNING / HOLD."""
        return self.states.activity

    @property
    def config(self) -> MachineConfig:
        """The applied machine configuration."""
        return self.conn.cfg

    @property
    def axes(self) -> tuple[str, ...]:
        """Axis names, in configuration order."""
        return self.conn.cfg.axes

    @property
    def machine_position(self) -> tuple[float, ...]:
        """Actual position, machine coordinates."""
        return tuple(float(x) for x in self.states.machine_pos())

    @property
    def work_position(self) -> tuple[float, ...]:
        """Actual position in the active work offset's coordinates."""
        return tuple(float(x) for x in self.states.work_pos())

    @property
    def reference_position(self) -> tuple[float, ...]:
        """Last set-point sent to the drives (machine coordinates)."""
        return tuple(float(x) for x in self.pos.ref_raw - self.pos.home_offset)

    @property
    def homed(self) -> tuple[bool, ...]:
        """Homed flag per axis."""
        return tuple(self.pos.homed)

    @property
    def work_offsets(self) -> dict[str, tuple[float, ...]]:
        """The G54-G59 table."""
        return dict(self.pos.offsets)

    @property
    def active_offset(self) -> str:
        """Name of the active work offset."""
        return self.pos.active_offset

    @property
    def g92_offset(self) -> tuple[float, ...] | None:
        """The G92/G52 offset per axis when it is on (a program left it), else None."""
        if not self.pos.parameters.get(5210, 0.0):
            return None
        return tuple(float(v) for v in self.pos.g92_offset())

    @property
    def xy_rotation_deg(self) -> float:
        """The XY rotation (G10 L2 R) of the active work offset, degrees."""
        return self.pos.rotation()

    def clear_g92(self) -> CommandResult:
        """Switch the G92/G52 offset off and zero its parameters (G92.1)."""
        return self.pos.clear_g92()

    @property
    def program_info(self) -> ProgramInfo | None:
        """The loaded program (None if none)."""
        return self.loader.program_info

    @property
    def program(self) -> object | None:
        """The loaded, checked ``planner.program.Program`` (None if none)."""
        return self.loader.program_info.program if self.loader.program_info else None

    @property
    def plan(self) -> object | None:
        """The ``planner.plan.Plan`` of the loaded program (planned with the override budget)."""
        return self.loader.program_info.plan if self.loader.program_info else None

    @property
    def current_line(self) -> int:
        """Source line the drives are executing (0 when none)."""
        return self.stream.line

    @property
    def progress(self) -> tuple[float, float]:
        """(fraction 0..1, remaining time s at the current feed override) of the running program."""
        return self.stream.progress

    @property
    def feed_override_pct(self) -> float:
        """Feed override in percent."""
        return self.run.feed_pct

    @property
    def rapid_override_pct(self) -> float:
        """Rapid override in percent."""
        return self.run.rapid_pct

    @property
    def single_block(self) -> bool:
        """Single-block mode."""
        return self.run.single_block

    @property
    def optional_stop(self) -> bool:
        """Optional stop (M01) honoured."""
        return self.run.optional_stop

    @property
    def block_delete(self) -> bool:
        """Block delete: lines starting with '/' skipped."""
        return self.run.block_delete

    @property
    def spindle(self) -> SpindleState:
        """Spindle state."""
        return self.spindle_ctl.spindle

    @property
    def alarms(self) -> tuple[Alarm, ...]:
        """All alarms (active and history), oldest first."""
        return tuple(self.alarm_log.alarms)

    @property
    def active_alarms(self) -> tuple[Alarm, ...]:
        """Alarms not yet acknowledged."""
        return tuple(a for a in self.alarm_log.alarms if a.active)

    @property
    def bus_status(self) -> BusStatus:
        """Bus / worker state."""
        return self.poller.bus_status

    @property
    def tracking(self) -> TrackingReport:
        """Tracking RMSE/MSE of the last (or current) run."""
        return self.stream.tracking

    @property
    def last_run(self) -> RunSummary | None:
        """Summary of the last program run (None before the first)."""
        return self.stream.last_summary

    @property
    def worker(self) -> Any:
        """The CyclicWorker (diagnostics and tests; None when disconnected)."""
        return self.conn.worker

    def snapshot(self) -> ControllerSnapshot:
        """Everything the panel shows, in one immutable object."""
        return ControllerSnapshot(
            state=self.states.state,
            activity=self.states.activity,
            axes=self.conn.cfg.axes,
            machine_pos=self.machine_position,
            work_pos=self.work_position,
            homed=self.homed,
            active_offset=self.pos.active_offset,
            line=self.stream.line,
            progress=self.stream.progress[0],
            remaining_s=self.stream.progress[1],
            path_speed_mm_s=self.stream.speed,
            feed_override_pct=self.run.feed_pct,
            rapid_override_pct=self.run.rapid_pct,
            single_block=self.run.single_block,
            optional_stop=self.run.optional_stop,
            block_delete=self.run.block_delete,
            spindle=self.spindle_ctl.spindle,
            alarms=tuple(self.alarm_log.alarms),
            bus=self.poller.bus_status,
        )

    # ------------------------------------------------------------------ commands
    # Each is its part's method; ``app.machine.api.MachineApi`` documents them for the panel.
    def refusal(self, action: str) -> str:
        return self.states.refusal(action)

    def reset(self) -> CommandResult:
        return self.states.reset()

    def estop(self, reason: str = "operator") -> CommandResult:
        return self.states.estop(reason)

    def estop_release(self) -> CommandResult:
        return self.states.estop_release()

    # ---- end of states

    @property
    def config_path(self) -> Path:
        return self.conn.config_path

    def update_config(self, config: MachineConfig, *, wait: bool = False) -> CommandResult:
        return self.conn.update_config(config, wait=wait)

    def connect_bus(self) -> CommandResult:
        return self.conn.connect_bus()

    def disconnect_bus(self) -> CommandResult:
        return self.conn.disconnect_bus()

    def shutdown(self) -> None:
        return self.conn.shutdown()

    def advance(self, seconds: float, step_cycles: int = 10) -> None:
        return self.conn.advance(seconds, step_cycles)

    def run_until(self, predicate: Callable[[], bool], timeout_s: float = 10.0) -> bool:
        return self.conn.run_until(predicate, timeout_s)

    # ---- end of conn

    # ---- end of stream

    @property
    def loading(self) -> bool:
        return self.loader.loading

    @property
    def loading_name(self) -> str:
        return self.loader.loading_name

    @property
    def loading_progress(self) -> float:
        return self.loader.loading_progress

    def load_program(
        self,
        source: str | os.PathLike[str],
        name: str | None = None,
        *,
        wait: bool = False,
        timeout_s: float | None = None,
    ) -> CommandResult:
        """Load a program from a path (``os.PathLike`` or an existing file name) or G-code text.

        Parses, checks the whole path against the soft limits (arcs by their exact extremes)
        and plans it before anything moves, in a worker thread: returns at once (truthy:
        accepted and being checked), then emits ``programLoaded`` or ``programErrors`` (all
        errors, with lines and axes) from the controller's thread. ``wait=True`` does the work
        in the calling thread and returns the outcome (falsy with the reason when refused), as
        ``wait_loaded`` does for a load already started. A newer load supersedes one in flight.
        Refused while running. Programs start in the interpreter's reset state (G54) unless they
        select a work offset; the active offset (``select_work_offset``) applies to MDI blocks
        and to the work coordinates shown.
        """
        return self.loader.load_program(source, name, wait=wait, timeout_s=timeout_s)

    def wait_loaded(self, timeout_s: float | None = 60.0) -> CommandResult:
        return self.loader.wait_loaded(timeout_s)

    def wait_run_plan(self, timeout_s: float | None = 60.0) -> bool:
        return self.loader.wait_run_plan(timeout_s)

    # ---- end of loader

    def cycle_start(self, *, wait: bool = False) -> CommandResult:
        return self.run.cycle_start(wait=wait)

    def feed_hold(self) -> CommandResult:
        return self.run.feed_hold()

    def resume(self) -> CommandResult:
        return self.run.resume()

    def stop(self) -> CommandResult:
        return self.run.stop()

    def set_single_block(self, on: bool) -> CommandResult:
        return self.run.set_single_block(on)

    def set_optional_stop(self, on: bool) -> CommandResult:
        return self.run.set_optional_stop(on)

    def set_block_delete(self, on: bool) -> CommandResult:
        return self.run.set_block_delete(on)

    def approach_preview(self, line: int) -> Any:
        return self.run.approach_preview(line)

    def run_from_line(self, line: int, *, wait: bool = False) -> CommandResult:
        return self.run.run_from_line(line, wait=wait)

    @property
    def resume_line(self) -> int:
        return self.run.resume_line

    def set_feed_override(self, percent: float) -> CommandResult:
        return self.run.set_feed_override(percent)

    def set_rapid_override(self, percent: float) -> CommandResult:
        return self.run.set_rapid_override(percent)

    # ---- end of run

    def jog_start(self, axis: str | int, direction: int, speed_fraction: float = 1.0) -> CommandResult:
        return self.manual.jog_start(axis, direction, speed_fraction)

    def jog_stop(self, axis: str | int | None = None) -> CommandResult:
        return self.manual.jog_stop(axis)

    def jog_increment(self, axis: str | int, step: float, direction: int = 1) -> CommandResult:
        return self.manual.jog_increment(axis, step, direction)

    def mdi(self, block: str) -> CommandResult:
        return self.manual.mdi(block)

    # ---- end of manual

    def home_axis(self, axis: str | int) -> CommandResult:
        return self.pos.home_axis(axis)

    def home_all(self) -> CommandResult:
        return self.pos.home_all()

    def set_machine_zero_here(self, axis: str | int | None = None) -> CommandResult:
        return self.pos.set_machine_zero_here(axis)

    def set_work_offset(self, name: str, values: dict[str, float] | tuple[float, ...]) -> CommandResult:
        return self.pos.set_work_offset(name, values)

    def select_work_offset(self, name: str) -> CommandResult:
        return self.pos.select_work_offset(name)

    def touch_off(self, axis: str | int, work_value: float = 0.0, offset: str | None = None) -> CommandResult:
        return self.pos.touch_off(axis, work_value, offset)

    # ---- end of pos

    def spindle_on(self, clockwise: bool = True, rpm: float | None = None) -> CommandResult:
        return self.spindle_ctl.spindle_on(clockwise, rpm)

    def spindle_off(self) -> CommandResult:
        return self.spindle_ctl.spindle_off()

    def spindle_speed(self, rpm: float) -> CommandResult:
        return self.spindle_ctl.spindle_speed(rpm)

    def set_spindle_override(self, percent: float) -> CommandResult:
        return self.spindle_ctl.set_override(percent)

    # ---- end of spindle_ctl

    @property
    def tool_table(self) -> ToolTable:
        return self.tools.table

    @property
    def tool_in_spindle(self) -> int:
        return self.tools.in_spindle

    def set_tool(self, tool: Tool) -> CommandResult:
        return self.tools.set_tool(tool)

    def remove_tool(self, number: int) -> CommandResult:
        return self.tools.remove_tool(number)

    def set_tool_in_spindle(self, number: int) -> CommandResult:
        return self.tools.set_tool_in_spindle(number)

    def touch_off_tool(self, number: int, surface_z_mm: float = 0.0) -> CommandResult:
        return self.tools.touch_off_tool(number, surface_z_mm)

    def measure_tool(self, number: int) -> CommandResult:
        return self.tools.measure_tool(number)

    def import_tool_table(self, path: str) -> CommandResult:
        return self.tools.import_table(path)

    # ---- end of tools

    def acknowledge_alarm(self, alarm_id: int | None = None) -> CommandResult:
        return self.alarm_log.acknowledge_alarm(alarm_id)

    # ---- end of alarm_log

    # ---- end of poller
