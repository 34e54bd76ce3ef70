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

Modules. ``MachineController`` is the one public facade (signals, construction, read-only
properties); its behaviour is mixed in from one module per responsibility, all sharing the
facade's state:

    app.machine.states       state machine: TRANSITIONS, refusals, E-stop, reset
    app.machine.connection   configuration, persistence, worker + feeder life cycle, shutdown
    app.machine.feeder       jobs, set-point streaming (lead_s), pause points, end of a run
    app.machine.program_load load (parse, soft limits, plan), re-checks, single-block plans:
                             in a worker thread (cycle start runs the load-time plan)
    app.machine.program_run  cycle start, feed hold, resume, stop, run from line, overrides
    app.machine.manual       jog (continuous, incremental), MDI
    app.machine.homing       machine zero (homing), work offsets, touch-off
    app.machine.spindle      spindle
    app.machine.alarms       alarm list and reactions
    app.machine.status       polling the worker, positions/bus signals
    app.machine.jobs         Job, ResumePoint, SentLimits records
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from typing import Any

import numpy as np
from PySide6.QtCore import QObject, QTimer, Signal

from app.machine.alarms import AlarmMixin
from app.machine.config import MachineConfig
from app.machine.connection import RAMP_DOWN_TIMEOUT_S, ConnectionMixin
from app.machine.feeder import FeederMixin
from app.machine.homing import HomingMixin
from app.machine.jobs import Job, ResumePoint, SentLimits
from app.machine.manual import JOG_INCREMENTS, ManualMixin
from app.machine.model import (
    Activity,
    Alarm,
    BusStatus,
    ControllerSnapshot,
    MachineState,
    ProgramInfo,
    RunSummary,
    Severity,
    SpindleState,
    TrackingReport,
)
from app.machine.persist import StateStore
from app.machine.program_load import LoadMixin, LoadRequest, RunPlanRequest
from app.machine.program_run import ProgramMixin
from app.machine.spindle import SpindleMixin
from app.machine.states import TRANSITIONS, StateMixin
from app.machine.status import StatusMixin
from app.paths import DEFAULT_STATE_DIR

__all__ = [
    "DEFAULT_STATE_DIR",
    "JOG_INCREMENTS",
    "RAMP_DOWN_TIMEOUT_S",
    "TRANSITIONS",
    "SentLimits",
    "MachineController",
]



class MachineController(
    StateMixin,
    ConnectionMixin,
    FeederMixin,
    ProgramMixin,
    LoadMixin,
    ManualMixin,
    HomingMixin,
    SpindleMixin,
    AlarmMixin,
    StatusMixin,
    QObject,
):
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
    programErrors = Signal(object)  # tuple[ProgramIssue, ...] (parse errors, soft limits)
    loadingChanged = Signal(bool, str)  # (a program is being checked, its name)
    _loadDone = Signal(object)  # LoadRequest finished in its worker thread (queued)
    programFinished = Signal(object)  # RunSummary (completed or not)
    lineChanged = Signal(int)  # current source line (1-based), 0 when none
    progressChanged = Signal(float, float)  # (fraction 0..1, remaining time s at current override)
    speedChanged = Signal(float)  # commanded path speed mm/s
    overridesChanged = Signal(float, float)  # (feed %, rapid %)
    modesChanged = Signal(bool, bool)  # (single block, optional stop)
    alarmsChanged = Signal(object)  # tuple[Alarm, ...] (active and history)
    homedChanged = Signal(object)  # tuple[bool, ...] per axis
    offsetsChanged = Signal(object, str)  # (dict name -> tuple per axis, active name)
    spindleChanged = Signal(object)  # SpindleState
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
        self._lock = threading.RLock()
        self._store = StateStore(state_dir if state_dir is not None else DEFAULT_STATE_DIR)
        self._worker_factory = worker_factory
        self._worker_mode = worker_mode
        self._worker: Any = None
        self._alarms: list[Alarm] = self._store.load_alarms()
        self._next_alarm_id = max((a.id for a in self._alarms), default=0) + 1
        self._config_notice = ""
        self._cfg = self._load_initial_config(config)
        self._state = MachineState.DISCONNECTED
        self._state_reason = "not connected"
        self._activity = Activity.NONE
        n = len(self._cfg.axes)
        self._raw_pos = np.zeros(n)
        self._ref_raw = np.zeros(n)
        self._home_offset = np.zeros(n)
        self._homed = [False] * n
        self._active_offset = "G54"
        self._offsets: dict[str, tuple[float, ...]] = {
            k: tuple(v) for k, v in self._cfg.machine.work_offsets.items()
        }
        self._restore_persisted()
        self._feed_pct = 100.0
        self._rapid_pct = 100.0
        self._single_block = False
        self._optional_stop = False
        self._spindle = SpindleState()
        self._program_info: ProgramInfo | None = None
        self._program_text = ""
        self._program_path = ""
        self._load_request: LoadRequest | None = None  # the load in flight (program_load)
        self._load_generation = 0
        self._load_reason = ""  # why the last load was refused
        self._start_pending = False  # cycle start pressed while the program is checked again
        self._program_cfg: object = None  # configuration and offsets the program was checked with
        self._program_offsets: dict[str, tuple[float, ...]] = {}
        self._run_plan_request: RunPlanRequest | None = None  # single-block plan in flight
        self._run_plan_ready: RunPlanRequest | None = None  # ... and the one made
        self._loadDone.connect(self._on_load_done)
        self._job: Job | None = None
        self._pushed_total = 0
        self._line = 0
        self._progress = (0.0, 0.0)
        self._speed = 0.0
        self._resume: ResumePoint | None = None
        self._tracking = TrackingReport(axes=self._cfg.axes)
        self._bus_status = BusStatus(kind=self._cfg.bus.kind)
        self._last_snap: Any = None
        self._seen_worker_alarms: set[tuple[int, int, str]] = set()
        self._homing_queue: list[int] = []
        self._homing_axis = -1
        self._last_emit_pos: tuple[float, ...] = ()
        self._last_ref_time = 0.0
        self._last_ref_pos: np.ndarray | None = None
        self._tracking_emit_t = 0.0
        self._feeder: threading.Thread | None = None
        self._feeder_stop = threading.Event()
        self._timer = QTimer(self)
        self._timer.setInterval(max(int(1000.0 / poll_hz), 5))
        self._timer.timeout.connect(self._poll)
        self._shutdown = False
        self._feeder_error = ""  # set by the feeder thread, reported by the poll
        self._last_summary: RunSummary | None = None
        for text in self._store.problems:
            self._raise_alarm("persistence", text, Severity.WARNING, "state_file")
        if self._config_notice:
            self._raise_alarm("config", self._config_notice, Severity.WARNING, "config_recovered")

    @property
    def state(self) -> MachineState:
        """Current machine state."""
        return self._state

    @property
    def state_reason(self) -> str:
        """Why the machine is in its state (text for the panel)."""
        return self._state_reason

    @property
    def activity(self) -> Activity:
        """What the machine is doing while RUNNING / HOLD."""
        return self._activity

    @property
    def config(self) -> MachineConfig:
        """The applied machine configuration."""
        return self._cfg

    @property
    def axes(self) -> tuple[str, ...]:
        """Axis names, in configuration order."""
        return self._cfg.axes

    @property
    def machine_position(self) -> tuple[float, ...]:
        """Actual position, machine coordinates."""
        return tuple(float(x) for x in self._machine_pos())

    @property
    def work_position(self) -> tuple[float, ...]:
        """Actual position in the active work offset's coordinates."""
        return tuple(float(x) for x in self._work_pos())

    @property
    def reference_position(self) -> tuple[float, ...]:
        """Last set-point sent to the drives (machine coordinates)."""
        return tuple(float(x) for x in self._ref_raw - self._home_offset)

    @property
    def homed(self) -> tuple[bool, ...]:
        """Homed flag per axis."""
        return tuple(self._homed)

    @property
    def work_offsets(self) -> dict[str, tuple[float, ...]]:
        """The G54-G59 table."""
        return dict(self._offsets)

    @property
    def active_offset(self) -> str:
        """Name of the active work offset."""
        return self._active_offset

    @property
    def program_info(self) -> ProgramInfo | None:
        """The loaded program (None if none)."""
        return self._program_info

    @property
    def program(self) -> object | None:
        """The loaded, checked ``planner.program.Program`` (None if none)."""
        return self._program_info.program if self._program_info else None

    @property
    def plan(self) -> object | None:
        """The ``planner.plan.Plan`` of the loaded program (planned with the override budget)."""
        return self._program_info.plan if self._program_info else None

    @property
    def current_line(self) -> int:
        """Source line the drives are executing (0 when none)."""
        return self._line

    @property
    def progress(self) -> tuple[float, float]:
        """(fraction 0..1, remaining time s at the current feed override) of the running program."""
        return self._progress

    @property
    def feed_override_pct(self) -> float:
        """Feed override in percent."""
        return self._feed_pct

    @property
    def rapid_override_pct(self) -> float:
        """Rapid override in percent."""
        return self._rapid_pct

    @property
    def single_block(self) -> bool:
        """Single-block mode."""
        return self._single_block

    @property
    def optional_stop(self) -> bool:
        """Optional stop (M01) honoured."""
        return self._optional_stop

    @property
    def spindle(self) -> SpindleState:
        """Spindle state."""
        return self._spindle

    @property
    def alarms(self) -> tuple[Alarm, ...]:
        """All alarms (active and history), oldest first."""
        return tuple(self._alarms)

    @property
    def active_alarms(self) -> tuple[Alarm, ...]:
        """Alarms not yet acknowledged."""
        return tuple(a for a in self._alarms if a.active)

    @property
    def bus_status(self) -> BusStatus:
        """Bus / worker state."""
        return self._bus_status

    @property
    def tracking(self) -> TrackingReport:
        """Tracking RMSE/MSE of the last (or current) run."""
        return self._tracking

    @property
    def last_run(self) -> RunSummary | None:
        """Summary of the last program run (None before the first)."""
        return self._last_summary

    @property
    def worker(self) -> Any:
        """The CyclicWorker (diagnostics and tests; None when disconnected)."""
        return self._worker

    def snapshot(self) -> ControllerSnapshot:
        """Everything the panel shows, in one immutable object."""
        return ControllerSnapshot(
            state=self._state,
            activity=self._activity,
            axes=self._cfg.axes,
            machine_pos=self.machine_position,
            work_pos=self.work_position,
            homed=self.homed,
            active_offset=self._active_offset,
            line=self._line,
            progress=self._progress[0],
            remaining_s=self._progress[1],
            path_speed_mm_s=self._speed,
            feed_override_pct=self._feed_pct,
            rapid_override_pct=self._rapid_pct,
            single_block=self._single_block,
            optional_stop=self._optional_stop,
            spindle=self._spindle,
            alarms=tuple(self._alarms),
            bus=self._bus_status,
        )
