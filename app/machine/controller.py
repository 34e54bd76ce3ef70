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
exceeding a limit. Continuous jog is a move planned to the soft limit (a lost release stops
there); a release is a hold followed by abandoning the move. Faults keep the point to resume
from (``resume_line``; ``resume()`` in IDLE moves there safely and continues).

Machine vs drive coordinates: machine = drive position - home offset (set by homing); work =
machine - active work offset (G54-G59). Persisted in the state directory (``persist.py``).

Beyond the commands listed above: ``advance(seconds)`` / ``run_until(pred)`` drive simulated
time in ``worker_mode="manual"`` (tests, fast headless runs); read-only ``resume_line``,
``reference_position``, ``progress``, ``last_run`` (RunSummary), ``state_reason``,
``config_path``, ``worker``.

Units: positions mm / degrees (rotary), speeds mm/s, times s, overrides in percent.
"""

from __future__ import annotations

import collections
import math
import os
import shutil
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
from PySide6.QtCore import QObject, QTimer, Signal

from app.machine.config import MachineConfig, load_config, recover_config, save_config
from app.machine.errors import ConfigError, MachineError
from app.machine.limits import check_program, program_bounds
from app.machine.model import (
    Activity,
    Alarm,
    AlarmState,
    BusStatus,
    CommandResult,
    ControllerSnapshot,
    MachineState,
    ProgramInfo,
    ProgramIssue,
    RunSummary,
    Severity,
    SpindleState,
    TrackingReport,
)
from app.machine.persist import StateStore
from app.machine.timescale import (
    Budget,
    PausePoint,
    ScaledChunk,
    TimeScaledExecutor,
    check_limits,
    pause_points,
    reduced_machine,
)
from planner.errors import PlannerError, ProgramError
from planner.interpreter import parse_program
from planner.machine import WORK_OFFSET_NAMES, MachineSpec, shipped_machine
from planner.plan import Plan, plan_program
from planner.program import EventKind, Move, MoveKind, Program
from planner.resume import (
    approach_moves,
    locate,
    modal_state_before_move,
    program_from_moves,
    remaining_program,
)

__all__ = ["JOG_INCREMENTS", "TRANSITIONS", "MachineController"]


S = MachineState
TRANSITIONS: dict[MachineState, frozenset[MachineState]] = {
    S.DISCONNECTED: frozenset({S.IDLE, S.ESTOP}),
    S.IDLE: frozenset({S.RUNNING, S.HOMING, S.ALARM, S.ESTOP, S.DISCONNECTED}),
    S.HOMING: frozenset({S.IDLE, S.ALARM, S.ESTOP, S.DISCONNECTED}),
    S.RUNNING: frozenset({S.HOLD, S.IDLE, S.ALARM, S.ESTOP, S.DISCONNECTED}),
    S.HOLD: frozenset({S.RUNNING, S.IDLE, S.ALARM, S.ESTOP, S.DISCONNECTED}),
    S.ALARM: frozenset({S.IDLE, S.ESTOP, S.DISCONNECTED}),
    S.ESTOP: frozenset({S.IDLE, S.DISCONNECTED}),
}
JOG_INCREMENTS: tuple[float, ...] = (0.001, 0.01, 0.1, 1.0)  # mm or degrees
RAMP_DOWN_TIMEOUT_S = 3.0  # disconnect/shutdown mid-run: longest wait for the stop along the path
DEFAULT_STATE_DIR = Path(os.path.expanduser("~/.local/state/cnc-panel"))


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
    programErrors = Signal(object)  # tuple[ProgramIssue, ...] (parse errors, soft limits)
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
        self._job: _Job | None = None
        self._pushed_total = 0
        self._line = 0
        self._progress = (0.0, 0.0)
        self._speed = 0.0
        self._resume: _ResumePoint | None = None
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
        for text in self._store.problems:
            self._raise_alarm("persistence", text, Severity.WARNING, "state_file")
        if self._config_notice:
            self._raise_alarm("config", self._config_notice, Severity.WARNING, "config_recovered")

    # ================================================================== configuration
    def _load_initial_config(self, config: MachineConfig | str | os.PathLike[str] | None) -> MachineConfig:
        if isinstance(config, MachineConfig):
            self._config_path = Path(config.path) if config.path else self._store.path("machine.toml")
            return config
        if config is None:
            path = self._store.path("machine.toml")
            if not path.exists():
                shutil.copyfile(shipped_machine("xyz_mill"), path)
        else:
            path = Path(config)
        self._config_path = path
        try:
            return load_config(path)
        except ConfigError as exc:
            if exc.backup is None:
                raise
            cfg, text = recover_config(path)
            self._config_notice = f"machine configuration damaged: {text}"
            return cfg

    @property
    def config_path(self) -> Path:
        """The machine configuration file that ``update_config`` writes."""
        return self._config_path

    def _restore_persisted(self) -> None:
        axes = self._cfg.axes
        st = self._store.load_state(axes)
        if st is not None:
            self._raw_pos = np.array(st["raw_position"], dtype=float)
            self._home_offset = np.array(st["home_offset"], dtype=float)
            self._homed = list(st["homed"])
            if st["active_offset"] in WORK_OFFSET_NAMES:
                self._active_offset = st["active_offset"]
        offs = self._store.load_offsets(len(axes))
        if offs is not None:
            self._offsets.update({k: v for k, v in offs.items() if k in WORK_OFFSET_NAMES})
        self._ref_raw = self._raw_pos.copy()

    def _persist_state(self) -> None:
        try:
            self._store.save_state(
                self._cfg.axes,
                [float(x) for x in self._raw_pos],
                [float(x) for x in self._home_offset],
                list(self._homed),
                self._active_offset,
            )
        except OSError as exc:
            self._raise_alarm(
                "persistence", f"cannot save machine state: {exc}", Severity.WARNING, "state_file"
            )

    @property
    def _machine(self) -> MachineSpec:
        return replace(self._cfg.machine, work_offsets=dict(self._offsets))

    @property
    def _budget(self) -> Budget:
        c = self._cfg.controller
        return Budget(k_a=1.0 - c.accel_reserve, k_j=1.0 - c.jerk_reserve)

    # ================================================================== helpers
    def _refuse(self, action: str, reason: str) -> CommandResult:
        self.commandRefused.emit(action, reason)
        return CommandResult(False, action, reason)

    def _ok(self, action: str) -> CommandResult:
        return CommandResult(True, action, "")

    def _axis(self, axis: str | int) -> int:
        if isinstance(axis, str):
            name = axis.upper()
            if name not in self._cfg.axes:
                raise MachineError(f"unknown axis {axis!r}; axes: {' '.join(self._cfg.axes)}")
            return self._cfg.axes.index(name)
        if not 0 <= int(axis) < len(self._cfg.axes):
            raise MachineError(f"axis index {axis} out of range")
        return int(axis)

    def _set_state(self, new: MachineState, reason: str = "") -> None:
        old = self._state
        if new is old:
            if reason != self._state_reason:
                self._state_reason = reason
                self.stateChanged.emit(new, reason)
            return
        if new not in TRANSITIONS[old]:
            raise MachineError(f"internal error: illegal transition {old.value} -> {new.value}")
        self._state = new
        self._state_reason = reason
        if new in (MachineState.IDLE, MachineState.DISCONNECTED, MachineState.ALARM, MachineState.ESTOP):
            self._set_activity(Activity.NONE)
            self._persist_state()
        self.stateChanged.emit(new, reason)

    def _set_activity(self, act: Activity) -> None:
        if act is not self._activity:
            self._activity = act
            self.activityChanged.emit(act)

    def _raise_alarm(self, source: str, cause: str, severity: Severity, code: str = "") -> Alarm:
        alarm = Alarm(
            id=self._next_alarm_id,
            time_s=time.time(),
            source=source,
            cause=cause,
            severity=severity,
            state=AlarmState.ACTIVE if severity >= Severity.WARNING else AlarmState.ACKNOWLEDGED,
            code=code,
        )
        self._next_alarm_id += 1
        self._alarms.append(alarm)
        del self._alarms[:-500]
        try:
            self._store.save_alarms(self._alarms)
        except OSError:
            pass
        self.alarmsChanged.emit(tuple(self._alarms))
        self.message.emit(f"{source}: {cause}")
        return alarm

    def _machine_pos(self) -> np.ndarray:
        return self._raw_pos - self._home_offset

    def _work_pos(self) -> np.ndarray:
        return self._machine_pos() - np.asarray(
            self._offsets.get(self._active_offset, (0.0,) * len(self._raw_pos))
        )

    def refusal(self, action: str) -> str:
        """Why ``action`` ("cycle_start", "run_from_line", "jog", "mdi", "home", "feed_hold",
        "resume", "touch_off", "spindle_on", "update_config", ...) would be refused now; "" when
        allowed (for enabling buttons).
        """
        st = self._state
        need_idle = {"cycle_start", "run_from_line", "jog", "mdi", "home", "update_config", "load_program"}
        if action == "cycle_start" and st is MachineState.HOLD:
            return ""
        if action in need_idle and st is not MachineState.IDLE:
            if action == "load_program" and st in (
                MachineState.DISCONNECTED,
                MachineState.ALARM,
                MachineState.ESTOP,
            ):
                return ""
            if action == "update_config" and st in (
                MachineState.DISCONNECTED,
                MachineState.ALARM,
                MachineState.ESTOP,
            ):
                return ""
            return f"machine is {st.label.lower()}" + (
                f" ({self._state_reason})" if self._state_reason else ""
            )
        if action in ("cycle_start", "run_from_line", "mdi"):
            if self._cfg.homing.required and not all(self._homed):
                missing = [a for a, h in zip(self._cfg.axes, self._homed) if not h]
                return f"axes not homed: {' '.join(missing)} (home them or set machine zero first)"
        if action in ("cycle_start", "run_from_line") and self._program_info is None:
            return "no program loaded"
        if action == "feed_hold" and st is not MachineState.RUNNING:
            return f"nothing to hold: machine is {st.label.lower()}"
        if (
            action == "resume"
            and st is not MachineState.HOLD
            and not (st is MachineState.IDLE and self._resume)
        ):
            return f"nothing to resume: machine is {st.label.lower()}"
        if action in ("touch_off", "set_work_offset", "select_work_offset") and st in (
            MachineState.RUNNING,
            MachineState.HOLD,
            MachineState.HOMING,
        ):
            return f"not while the machine is {st.label.lower()}"
        if action == "spindle_on" and st not in (MachineState.IDLE, MachineState.HOLD):
            return f"spindle cannot start: machine is {st.label.lower()}"
        return ""

    # ================================================================== connection
    def _worker_config(self) -> Any:
        from ethercat.worker import DriveSpec, WorkerConfig

        cfg = self._cfg
        ids = {d.position: d for d in cfg.bus.drives}
        drives = tuple(
            DriveSpec(
                position=a.drive_position,
                axis_name=a.name,
                counts_per_unit=a.counts_per_unit,
                direction=a.direction,
                following_error_window=a.following_error_window,
                vendor_id=ids[a.drive_position].vendor_id if a.drive_position in ids else 0,
                product_code=ids[a.drive_position].product_code if a.drive_position in ids else 0,
            )
            for a in cfg.machine.axes
        )
        options: tuple[tuple[str, Any], ...] = ()
        if cfg.bus.kind == "sim":
            counts = tuple(
                float(a.direction * a.counts_per_unit * x) for a, x in zip(cfg.machine.axes, self._raw_pos)
            )
            options = (("initial_positions_counts", counts),)
        # core, real-time priority and spin: the WorkerConfig defaults (the worker picks a free
        # core itself and uses SCHED_FIFO 49, below PREEMPT_RT's interrupt threads)
        return WorkerConfig(
            drives=drives,
            ts_s=cfg.machine.planner.ts_s,
            bus_kind=cfg.bus.kind,
            adapter=cfg.bus.adapter,
            wkc_error_limit=cfg.bus.wkc_error_limit,
            mode=self._worker_mode,
            bus_options=options,
            homing_timeout_s=cfg.homing.timeout_s,
        )

    def connect_bus(self) -> CommandResult:
        """Start the worker (simulated drives when the bus kind is "sim") and enable the drives:
        DISCONNECTED -> IDLE. Saved positions are restored (simulated drives start there); an axis
        whose reported position differs from the saved one loses its homed state (warning alarm).
        """
        if self._state is not MachineState.DISCONNECTED:
            return self._refuse("connect", f"already connected (machine is {self._state.label.lower()})")
        wcfg = self._worker_config()
        try:
            if self._worker_factory is not None:
                worker = self._worker_factory(wcfg)
            else:
                from ethercat.worker import CyclicWorker

                worker = CyclicWorker(wcfg)
            worker.start()
        except Exception as exc:  # noqa: BLE001 - any bus failure is shown to the operator
            self._raise_alarm("bus", f"cannot start the bus: {exc}", Severity.WARNING, "bus_start")
            return self._refuse("connect", f"cannot start the bus: {exc}")
        self._worker = worker
        self._seen_worker_alarms.clear()
        try:
            self._enable_worker()
        except Exception as exc:  # noqa: BLE001
            self._stop_worker()
            self._raise_alarm("bus", f"drives cannot be enabled: {exc}", Severity.WARNING, "enable")
            return self._refuse("connect", f"drives cannot be enabled: {exc}")
        snap = self._snapshot_now()
        actual = np.asarray(snap.actual_position, dtype=float)
        tol = self._cfg.controller.position_tolerance
        moved = np.abs(actual - self._raw_pos) > max(tol, 1e-9)
        if any(h and m for h, m in zip(self._homed, moved)):
            names = [a for a, h, m in zip(self._cfg.axes, self._homed, moved) if h and m]
            self._homed = [h and not m for h, m in zip(self._homed, moved)]
            self._raise_alarm(
                "controller",
                f"axes {' '.join(names)} report another position than saved: homed state cleared, home again",
                Severity.WARNING,
                "position_lost",
            )
            self.homedChanged.emit(tuple(self._homed))
        self._raw_pos = actual.copy()
        self._ref_raw = actual.copy()
        self._pushed_total = 0
        self._set_state(MachineState.IDLE, "ready")
        if self._worker_mode != "manual":
            # the feeder thread shares the GIL with the GUI: a short switch interval keeps it on
            # time while the GUI computes (NOTES.md: 5 ms default stretches 1 ms loops to 5 ms)
            if sys.getswitchinterval() > 0.001:
                sys.setswitchinterval(0.001)
            self._feeder_stop.clear()
            self._feeder = threading.Thread(target=self._feeder_main, name="cnc-feeder", daemon=True)
            self._feeder.start()
            self._timer.start()
        self._emit_all()
        return self._ok("connect")

    def _enable_worker(self) -> None:
        from ethercat.worker import WorkerState

        w = self._worker
        with self._lock:
            st = w.state()
            if st in (WorkerState.FAULT, WorkerState.QUICK_STOP, WorkerState.FAULT_RESET):
                w.fault_reset()
                w.wait_for((WorkerState.DISABLED,), timeout_s=2.0)
            w.flush()
            w.enable()
            w.wait_for((WorkerState.ENABLED,), timeout_s=3.0)

    def _snapshot_now(self) -> Any:
        with self._lock:
            snap = self._worker.snapshot()
        self._last_snap = snap
        return snap

    def _stop_worker(self) -> None:
        """Stop the worker (drives disabled, bus closed), then the feeder thread."""
        self._timer.stop()
        with self._lock:
            w, self._worker = self._worker, None  # the feeder sees no worker from here on
        if w is not None:
            try:
                with self._lock:
                    w.stop()
            except Exception:  # noqa: BLE001 - stopping must not fail
                pass
        self._feeder_stop.set()
        if self._feeder is not None and self._feeder is not threading.current_thread():
            self._feeder.join(timeout=2.0)
        self._feeder = None

    def disconnect_bus(self) -> CommandResult:
        """Stop any motion (a jerk-limited stop along the path, at most ``RAMP_DOWN_TIMEOUT_S``),
        abandon it, disable the drives and stop the worker, then the feeder: -> DISCONNECTED."""
        if self._state is MachineState.DISCONNECTED:
            return self._ok("disconnect")
        self._ramp_down("disconnected")
        if self._worker is not None:
            try:
                self._poll()
            except Exception:  # noqa: BLE001
                pass
        with self._lock:
            self._drop_job(completed=False, reason="disconnected")
        self._stop_worker()
        self._set_state(MachineState.DISCONNECTED, "disconnected")
        self._emit_bus(BusStatus(kind=self._cfg.bus.kind, connected=False, state="disconnected"))
        return self._ok("disconnect")

    def _ramp_down(self, reason: str, timeout_s: float = RAMP_DOWN_TIMEOUT_S) -> bool:
        """Bring any motion to a standstill on its path before the worker is stopped: the same
        jerk-limited stop as ``stop()``, fed as usual, waited for here (the poll timer may be
        gone at exit). Without it, stopping the feeder first let the worker's buffer run dry
        while moving (a bogus "set-point buffer underrun" alarm persisted at every quit
        mid-run) and stopping the worker first cut the drives at speed. True at standstill."""
        from ethercat.worker import WorkerState

        with self._lock:
            job, w = self._job, self._worker
            if job is None or w is None:
                return True
            if w.state() is not WorkerState.ENABLED:
                return True  # the worker already stopped the drives (quick stop, fault)
            if job.kind is Activity.PROGRAM and job.origin is not None and self._resume is None:
                self._resume = job.resume_point(self._consumed(), reason)
            job.executor.hold = True
            job.stopping = True
            job.stop_reason = job.stop_reason or reason

        def still() -> bool:
            with self._lock:
                if self._worker is None or self._job is not job:
                    return True
                standing = job.executor.standing or job.pause is not None or job.executor.finished
                return standing and self._worker.buffer_level() == 0

        if self._worker_mode == "manual":
            return self.run_until(still, timeout_s)
        t_end = time.monotonic() + timeout_s
        while not still():
            if time.monotonic() > t_end:
                return False
            if self._feeder is None or not self._feeder.is_alive():
                self._feed()
            time.sleep(0.005)  # the feeder thread keeps the buffer filled meanwhile
        return True

    def shutdown(self) -> None:
        """Stop any motion (jerk-limited), spindle off, disconnect (worker stopped before the
        feeder), persist positions and offsets; safe to call twice."""
        if self._shutdown:
            return
        self._shutdown = True
        try:
            self._ramp_down("shutdown")
            if self._spindle.on:
                self.spindle_off()
            self.disconnect_bus()
        finally:
            self._persist_state()

    def _feeder_main(self) -> None:
        while not self._feeder_stop.wait(0.002):
            try:
                self._feed()
            except Exception as exc:  # noqa: BLE001 - never let the feeder die silently
                with self._lock:
                    self._feeder_error = f"set-point feeder failed: {exc}"
                return

    # ================================================================== time (manual mode)
    def advance(self, seconds: float, step_cycles: int = 10) -> None:
        """Manual worker mode only: run the machine for ``seconds`` of simulated time
        (feed set-points, run the cycles, poll and emit signals). For tests and tools."""
        if self._worker is None:
            return
        ts = self._cfg.machine.planner.ts_s
        cycles = int(round(seconds / ts))
        since_poll = 0
        poll_every = max(int(round(1.0 / (30.0 * ts))), 1)
        while cycles > 0 and self._worker is not None:
            k = min(step_cycles, cycles)
            self._feed()
            with self._lock:
                self._worker.step(k)
            cycles -= k
            since_poll += k
            if since_poll >= poll_every or cycles <= 0:
                since_poll = 0
                self._poll()

    def run_until(self, predicate: Callable[[], bool], timeout_s: float = 10.0) -> bool:
        """Manual mode: advance until ``predicate()`` is true (True) or ``timeout_s`` of
        simulated time passed (False)."""
        ts = self._cfg.machine.planner.ts_s
        step_s = 33 * ts
        steps = int(timeout_s / step_s) + 1
        for _ in range(steps):
            if predicate():
                return True
            self.advance(step_s, step_cycles=11)
        return bool(predicate())

    # ================================================================== feeding
    @property
    def _lead_samples(self) -> int:
        ts = self._cfg.machine.planner.ts_s
        return max(int(self._cfg.controller.lead_s / ts), 10)

    def _feed(self) -> None:
        from ethercat.worker import WorkerState

        with self._lock:
            job, w = self._job, self._worker
            if job is None or w is None or job.aborted:
                return
            if w.state() is not WorkerState.ENABLED:
                return
            want = self._lead_samples - w.buffer_level()
            while want > 0 and job.pause is None:
                if job.executor.hold and job.executor.standing:
                    break  # held still on the path: the worker keeps the last set-point
                ch = job.executor.generate(min(want, 20))
                if ch is None:
                    break
                raw = ch.q + self._home_offset
                n = w.push(raw)
                if n < len(raw):  # pragma: no cover - lead is far below the ring capacity
                    raise MachineError("worker buffer full")
                job.record(ch, self._pushed_total)
                job.samples += n
                self._pushed_total += n
                want -= n
                if ch.pause is not None:
                    # the plan stands still here: repeat the point so the worker sees the
                    # motion end before its buffer runs empty (no underrun alarm)
                    hold = np.repeat(raw[-1:], 2, axis=0)
                    self._pushed_total += w.push(hold)
                    job.pause_serial = self._pushed_total  # before .pause: the poll reads both
                    job.pause = ch.pause

    # ================================================================== polling
    def _poll(self) -> None:
        w = self._worker
        if w is None:
            return
        snap = self._snapshot_now()
        self._raw_pos = np.asarray(snap.actual_position, dtype=float).copy()
        self._ref_raw = np.asarray(snap.reference_position, dtype=float).copy()
        self._handle_worker_alarms(snap)
        with self._lock:
            trace = w.drain_trace()
        job = self._job
        if job is not None and len(trace.cycle):
            job.trace.append((trace.cycle.copy(), trace.reference.copy(), trace.actual.copy()))
        self._poll_homing(snap)
        if job is not None:
            self._poll_job(job, snap)
        self._emit_positions(snap)
        self._emit_bus_from(snap)
        if getattr(self, "_feeder_error", ""):
            text, self._feeder_error = self._feeder_error, ""
            self._fault(text, "controller", "feeder")

    def _handle_worker_alarms(self, snap: Any) -> None:
        from ethercat.worker import AlarmCode

        for a in snap.alarms:
            key = (int(a.code), int(a.cycle), a.axis)
            if key in self._seen_worker_alarms:
                continue
            self._seen_worker_alarms.add(key)
            source = f"drive {a.axis}" if a.axis else "worker"
            if a.code is AlarmCode.UNDERRUN:
                self._raise_alarm(source, a.message, Severity.WARNING, "underrun")
            elif a.code is AlarmCode.ESTOP:
                if self._state is not MachineState.ESTOP:
                    self._raise_alarm(source, a.message, Severity.ESTOP, "estop")
                    self._enter_estop(a.message)
            elif a.code is AlarmCode.QUICK_STOP and self._state is MachineState.ESTOP:
                continue
            elif a.code is AlarmCode.HOMING_ERROR:
                self._raise_alarm(source, a.message, Severity.STOP, "homing_error")
                self._homing_queue.clear()
                self._homing_axis = -1
                if self._state in (MachineState.HOMING, MachineState.IDLE):
                    self._set_state(MachineState.ALARM, a.message)
            else:
                self._fault(a.message, source, a.code.name.lower())

    def _fault(self, cause: str, source: str, code: str) -> None:
        """A quick-stop class alarm: the worker already stopped the drives; keep the resume point."""
        self._raise_alarm(source, cause, Severity.QUICK_STOP, code)
        with self._lock:
            job = self._job
            if job is not None:
                self._resume = job.resume_point(self._consumed(), cause)
            self._drop_job(completed=False, reason=cause)
            if self._worker is not None:
                try:
                    self._worker.flush()
                except Exception:  # noqa: BLE001
                    pass
        self._homing_queue.clear()
        self._homing_axis = -1
        if self._state not in (MachineState.ESTOP, MachineState.DISCONNECTED, MachineState.ALARM):
            self._set_state(MachineState.ALARM, cause)
        if self._spindle.on:
            self._apply_spindle(SpindleState())

    def _alarm_stop(self, cause: str, source: str, code: str) -> None:
        """A STOP-class alarm: jerk-limited stop along the path, program abandoned (its resume
        point kept), state ALARM. Motion ends by itself; the poll drops the job at standstill."""
        self._raise_alarm(source, cause, Severity.STOP, code)
        with self._lock:
            job = self._job
            if job is not None:
                job.executor.hold = True
                job.stopping = True
                job.stop_reason = cause
                self._resume = job.resume_point(self._consumed(), cause)
        if self._state in (MachineState.IDLE, MachineState.RUNNING, MachineState.HOLD, MachineState.HOMING):
            self._set_state(MachineState.ALARM, cause)

    def _consumed(self) -> int:
        snap = self._last_snap
        return int(snap.samples_consumed) if snap is not None else 0

    def _poll_job(self, job: _Job, snap: Any) -> None:
        consumed = int(snap.samples_consumed)
        info = job.info_at(consumed)
        if info is not None:
            line, tau = info
            if line != self._line and job.kind in (Activity.PROGRAM, Activity.MDI):
                self._line = line
                self.lineChanged.emit(line)
            if job.kind is Activity.PROGRAM:
                t_end = job.executor.t_end + job.time_offset_s
                tau_g = tau + job.tau_offset_s
                frac = min(tau_g / t_end, 1.0) if t_end > 0 else 1.0
                ovr = max(self._feed_pct / 100.0, 1e-3)
                remaining = max(t_end - tau_g, 0.0) / ovr
                self._progress = (frac, remaining)
                self.progressChanged.emit(frac, remaining)
        if snap.time_s - self._tracking_emit_t >= 1.0 and job.kind is Activity.PROGRAM:
            self._tracking_emit_t = snap.time_s
            self._tracking = self._tracking_from(snap, "")
            self.trackingUpdated.emit(self._tracking)
        all_done = consumed >= self._pushed_total
        # pause points reached by the drives
        if job.pause is not None and consumed >= job.pause_serial:
            self._at_pause(job, job.pause, snap)
            return
        if job.stopping and job.executor.standing and all_done:
            self._finish_stop(job)

    def _at_pause(self, job: _Job, p: PausePoint, snap: Any) -> None:
        kind = p.kind
        if kind == "end":
            self._finish_job(job, snap)
            return
        if job.stopping:
            self._finish_stop(job)
            return
        if kind == "spindle":
            self._apply_spindle(SpindleState(direction=int(np.sign(p.value)), rpm=abs(p.value)))
            self._release(job)
        elif kind == "dwell":
            if job.dwell_until is None:
                job.dwell_until = snap.time_s + p.value
                job.dwell_total_s += p.value
            elif snap.time_s >= job.dwell_until:
                job.dwell_until = None
                self._release(job)
        elif kind == "optional_pause" and not self._optional_stop:
            self._release(job)
        elif not job.waiting:
            job.waiting = True
            reason = {
                "pause": f"program paused (M00, line {p.line}): press cycle start",
                "optional_pause": f"optional stop (M01, line {p.line}): press cycle start",
                "tool_change": f"tool change (M06 T{int(p.value)}, line {p.line}): press cycle start",
                "single_block": f"single block: end of line {p.line}",
            }.get(kind, kind)
            self._set_state(MachineState.HOLD, reason)

    def _finish_stop(self, job: _Job) -> None:
        resume = self._resume
        self._drop_job(completed=False, reason=job.stop_reason or "stopped")
        if self._state is MachineState.ALARM:
            self._resume = resume  # a STOP alarm keeps the point to resume from
            return
        self._set_state(MachineState.IDLE, job.stop_reason or "stopped")

    def _release(self, job: _Job) -> None:
        with self._lock:
            job.pause = None
            job.waiting = False
            job.executor.release_pause()

    def _finish_job(self, job: _Job, snap: Any) -> None:
        nxt = job.then
        completed_summary = self._drop_job(completed=True, reason="completed", snap=snap)
        if nxt is not None:
            if nxt.spindle_before is not None:
                self._apply_spindle(nxt.spindle_before)
            self._start_job(nxt)
            return
        self._set_state(MachineState.IDLE, "program end" if completed_summary else "done")

    def _drop_job(self, completed: bool, reason: str, snap: Any = None) -> RunSummary | None:
        """End the current job (under the lock). Emits programFinished for program jobs."""
        with self._lock:
            job, self._job = self._job, None
            if job is None:
                return None
            job.aborted = True
            if self._worker is not None and not completed:
                try:
                    self._worker.flush()
                except Exception:  # noqa: BLE001
                    pass
        if job.kind is not Activity.PROGRAM:
            return None
        last_line = self._line
        if completed and job.then is None:
            self._resume = None
            self._line = 0
        if snap is None:
            snap = self._last_snap
        # motion time: set-points sent (holds included) plus dwells; waits for the operator excluded
        measured = job.samples * job.plan.ts_s + job.dwell_total_s
        trace_path = self._save_trace(job)
        tracking = self._tracking_from(snap, trace_path) if snap is not None else TrackingReport()
        self._tracking = tracking
        summary = RunSummary(
            name=job.name,
            completed=completed,
            cycle_time_s=measured,
            estimated_s=job.estimated_s,
            last_line=last_line,
            tracking=tracking,
            limits=_merge_max(job.carried_limits, job.meter.final()),
            reason=reason,
        )
        self._last_summary = summary
        self.trackingUpdated.emit(tracking)
        if completed:
            self.progressChanged.emit(1.0, 0.0)
        self.programFinished.emit(summary)
        return summary

    def _tracking_from(self, snap: Any, trace_path: str) -> TrackingReport:
        t = snap.tracking
        return TrackingReport(
            axes=self._cfg.axes,
            samples=int(t.samples),
            rmse=tuple(t.rmse),
            mse=tuple(t.mse),
            max_abs=tuple(t.max_abs),
            trace_path=trace_path or self._tracking.trace_path,
        )

    def _save_trace(self, job: _Job) -> str:
        if not job.trace:
            return ""
        cyc = np.concatenate([c for c, _, _ in job.trace])
        ref = np.concatenate([r for _, r, _ in job.trace]) - self._home_offset
        act = np.concatenate([a for _, _, a in job.trace]) - self._home_offset
        path = self._store.path("last_run.npz")
        tmp = path.with_name(".last_run.tmp.npz")
        e = ref - act
        mse = (e * e).mean(axis=0) if len(e) else np.zeros(len(self._cfg.axes))
        try:
            np.savez_compressed(
                tmp,
                t=cyc * self._cfg.machine.planner.ts_s,
                reference=ref,
                actual=act,
                axes=np.array(self._cfg.axes),
                rmse=np.sqrt(mse),
                mse=mse,
            )
            os.replace(tmp, path)
        except OSError as exc:
            self._raise_alarm("persistence", f"cannot save the run trace: {exc}", Severity.WARNING, "trace")
            return ""
        return str(path)

    # ================================================================== emitting
    def _emit_positions(self, snap: Any) -> None:
        mpos = tuple(float(x) for x in self._machine_pos())
        if mpos != self._last_emit_pos:
            self._last_emit_pos = mpos
            self.positionChanged.emit(mpos, tuple(float(x) for x in self._work_pos()))
        ref_m = self._ref_raw - self._home_offset
        self.trackingSample.emit(float(snap.time_s), tuple(float(x) for x in ref_m), mpos)
        lin = np.array([not r for r in self._cfg.machine.rotary])
        if self._last_ref_pos is not None and snap.time_s > self._last_ref_time:
            d = (ref_m - self._last_ref_pos)[lin] if lin.any() else ref_m - self._last_ref_pos
            speed = float(np.linalg.norm(d)) / (snap.time_s - self._last_ref_time)
            if abs(speed - self._speed) > 1e-6:
                self._speed = speed
                self.speedChanged.emit(speed)
        self._last_ref_pos = ref_m.copy()
        self._last_ref_time = float(snap.time_s)

    def _emit_bus_from(self, snap: Any) -> None:
        tm = snap.timing
        status = BusStatus(
            kind=self._cfg.bus.kind,
            connected=True,
            state=snap.state.name.lower(),
            drive_states=tuple(s.name for s in snap.drive_states),
            buffer_level=int(snap.buffer_level),
            late_cycles=int(tm.late_cycles),
            period_p99_us=float(tm.jitter_p99_s * 1e6),
            jitter_hist_bin_us=float(tm.histogram_bin_s * 1e6),
            jitter_hist_counts=tuple(tm.jitter_histogram),
            jitter_max_us=float(tm.jitter_max_s * 1e6),
        )
        self._emit_bus(status)

    def _emit_bus(self, status: BusStatus) -> None:
        old = self._bus_status
        self._bus_status = status
        if (old.state, old.drive_states, old.connected, old.late_cycles) != (
            status.state,
            status.drive_states,
            status.connected,
            status.late_cycles,
        ) or abs(old.buffer_level - status.buffer_level) > 50:
            self.busStateChanged.emit(status)

    def _emit_all(self) -> None:
        self.homedChanged.emit(tuple(self._homed))
        self.offsetsChanged.emit(dict(self._offsets), self._active_offset)
        self.overridesChanged.emit(self._feed_pct, self._rapid_pct)
        self.modesChanged.emit(self._single_block, self._optional_stop)
        self.spindleChanged.emit(self._spindle)
        self.alarmsChanged.emit(tuple(self._alarms))
        self._last_emit_pos = ()
        mpos = tuple(float(x) for x in self._machine_pos())
        self.positionChanged.emit(mpos, tuple(float(x) for x in self._work_pos()))

    # ================================================================== jobs
    def _plan(self, program: Program) -> Plan:
        return plan_program(program, reduced_machine(self._machine, self._budget))

    def _make_job(
        self,
        kind: Activity,
        program: Program,
        name: str,
        *,
        overrides: bool = True,
        single_block: bool = False,
    ) -> _Job:
        if single_block:
            program = replace(program, moves=tuple(replace(m, exact_stop=True) for m in program.moves))
        plan = self._plan(program)
        pauses = pause_points(plan, single_block, True)
        ex = TimeScaledExecutor(
            plan,
            self._machine,
            self._budget,
            pauses,
            feed_override=self._feed_pct / 100.0 if overrides else 1.0,
            rapid_override=self._rapid_pct / 100.0 if overrides else 1.0,
        )
        job = _Job(
            kind=kind,
            name=name,
            program=program,
            plan=plan,
            executor=ex,
            overrides=overrides,
            estimated_s=plan.cycle_time_s,
            machine=self._machine,
        )
        job.single_block = single_block
        return job

    def _start_job(self, job: _Job) -> None:
        snap = self._snapshot_now()
        job.start_time_s = float(snap.time_s) if job.start_time_s < 0 else job.start_time_s
        if job.kind is Activity.PROGRAM and self._worker is not None:
            with self._lock:
                self._worker.reset_tracking()
                self._worker.drain_trace()
        with self._lock:
            # serial numbers of set-points: the worker's consumed count (+ what is still queued;
            # a stale snapshot still counts the queue, a flushed buffer counts nothing)
            self._pushed_total = int(snap.samples_consumed) + int(snap.buffer_level)
            job.serial_base = self._pushed_total
            self._job = job
        self._set_activity(job.kind)
        if self._state is not MachineState.RUNNING:
            self._set_state(MachineState.RUNNING, job.kind.value)
        else:
            self.stateChanged.emit(self._state, job.kind.value)
        if self._worker_mode != "manual":
            self._feed()

    def _check_program_limits(self, program: Program) -> list[ProgramIssue]:
        return [
            ProgramIssue(v.line, 1, str(v).split(": ", 1)[1], v.axis)
            for v in check_program(program, self._machine)
        ]

    # ================================================================== program
    def load_program(self, source: str | os.PathLike[str], name: str | None = None) -> CommandResult:
        """Load a program from a path (``os.PathLike`` or an existing file name) or G-code text.

        Parses, plans and checks the whole path against the soft limits (arcs by their exact
        extremes) before anything moves. Emits ``programLoaded`` or ``programErrors`` (all
        errors, with lines and axes). Refused while running. Programs start in the interpreter's
        reset state (G54) unless they select a work offset; the active offset
        (``select_work_offset``) applies to MDI blocks and to the work coordinates shown.
        """
        why = self.refusal("load_program")
        if why:
            return self._refuse("load_program", why)
        path = ""
        if isinstance(source, os.PathLike) or (
            "\n" not in source and len(source) < 4096 and Path(source).is_file()
        ):
            path = str(source)
            try:
                data = Path(path).read_bytes()
            except OSError as exc:
                return self._load_failed(
                    (ProgramIssue(0, 0, f"cannot read: {exc.strerror or exc}"),),
                    f"{path}: cannot read: {exc.strerror or exc}",
                )
            try:
                text = data.decode("utf-8")
            except UnicodeDecodeError:
                text = data.decode("latin-1")
            name = name or Path(path).name
        else:
            text = str(source)
            name = name or "<text>"
        return self._load_text(text, name, path)

    def _load_text(self, text: str, name: str, path: str) -> CommandResult:
        try:
            program = parse_program(text, name, machine=self._machine, start_position=self._machine_pos())
        except ProgramError as exc:
            issues = tuple(ProgramIssue(e.line, e.col, e.message) for e in exc.errors)
            return self._load_failed(issues, f"{len(issues)} error(s) in the program; first: {issues[0]}")
        except PlannerError as exc:
            return self._load_failed((ProgramIssue(0, 0, str(exc)),), str(exc))
        limit_issues = self._check_program_limits(program)
        if limit_issues:
            return self._load_failed(tuple(limit_issues), f"soft limit: {limit_issues[0]}")
        try:
            plan = self._plan(program)
        except PlannerError as exc:
            return self._load_failed((ProgramIssue(0, 0, f"planner: {exc}"),), f"planner: {exc}")
        lo, hi = program_bounds(program)
        tab = plan.segment.table
        info = ProgramInfo(
            name=name,
            path=path,
            text=text,
            line_count=program.line_count or text.count("\n") + 1,
            move_count=len(program.moves),
            cycle_time_s=float(plan.cycle_time_s),
            length_mm=float(np.sum(tab.length)) if len(tab) else 0.0,
            bounds_min=tuple(float(x) for x in lo),
            bounds_max=tuple(float(x) for x in hi),
            line_times_s=tuple((int(tab.line[i]), float(plan.t0[i])) for i in range(len(tab))),
            program=program,
            plan=plan,
        )
        self._program_info = info
        self._program_text = text
        self._program_path = path
        self._resume = None
        self.programLoaded.emit(info)
        return self._ok("load_program")

    def _load_failed(self, issues: tuple[ProgramIssue, ...], reason: str) -> CommandResult:
        """A failed load unloads the previous program (as LinuxCNC drops the file on a failed
        open): cycle start is then refused with "no program loaded" instead of running the old
        program while the operator looks at the new one's errors."""
        self._program_info = None
        self._program_text = ""
        self._program_path = ""
        self._resume = None
        self.programErrors.emit(issues)
        return self._refuse("load_program", reason)

    def _fresh_program(self) -> Program | None:
        """The loaded program, re-interpreted if the machine moved since it was loaded."""
        info = self._program_info
        if info is None:
            return None
        prog: Program = info.program  # type: ignore[assignment]
        if np.max(np.abs(np.asarray(prog.start_position) - self._machine_pos()), initial=0.0) > 1e-6:
            if not self._load_text(self._program_text, info.name, self._program_path):
                return None
            prog = self._program_info.program  # type: ignore[union-attr,assignment]
        return prog

    def cycle_start(self) -> CommandResult:
        """Start the loaded program from its beginning (IDLE; re-interpreted first if the machine
        moved since loading), or continue (HOLD). Needs homed axes (unless the configuration
        says otherwise) and no active alarm of severity STOP or above.
        """
        if self._state is MachineState.HOLD:
            return self.resume()
        why = self.refusal("cycle_start")
        if why:
            return self._refuse("cycle_start", why)
        if any(a.active and a.severity >= Severity.STOP for a in self._alarms):
            return self._refuse("cycle_start", "acknowledge the active alarms first")
        prog = self._fresh_program()
        if prog is None:
            return self._refuse("cycle_start", "the program no longer passes its checks (see the errors)")
        info = self._program_info
        assert info is not None
        try:
            job = self._make_job(Activity.PROGRAM, prog, info.name, single_block=self._single_block)
        except PlannerError as exc:
            return self._refuse("cycle_start", f"planner: {exc}")
        job.origin = (prog, 0, 0.0)
        self._resume = None
        self._line = 0
        self._start_job(job)
        return self._ok("cycle_start")

    def feed_hold(self) -> CommandResult:
        """Jerk-limited stop along the path (time scale to 0): RUNNING -> HOLD. The stop starts
        after the set-points already queued in the worker (``lead_s``, 0.1 s).
        """
        why = self.refusal("feed_hold")
        if why:
            return self._refuse("feed_hold", why)
        with self._lock:
            job = self._job
            if job is None:
                return self._refuse("feed_hold", "nothing is moving")
            job.executor.hold = True
        self._set_state(MachineState.HOLD, "feed hold")
        return self._ok("feed_hold")

    def resume(self) -> CommandResult:
        """HOLD -> RUNNING: continue after a feed hold, a single-block stop or M00/M01/M06 to the
        same end. In IDLE after a fault or E-stop mid-program: move safely to the point where the
        program stopped (``resume_line``) and continue from exactly there.
        """
        why = self.refusal("resume")
        if why:
            return self._refuse("resume", why)
        if self._state is MachineState.IDLE and self._resume is not None:
            return self._resume_from_point(self._resume)
        with self._lock:
            job = self._job
            if job is None:
                return self._refuse("resume", "nothing to resume")
            if job.stopping:
                return self._refuse("resume", "the program is being stopped")
            if (
                job.kind is Activity.PROGRAM
                and job.single_block != self._single_block
                and (job.executor.standing or job.waiting)
                and self._consumed() >= self._pushed_total
            ):
                replanned = self._replan_here(job)
                if replanned is not None:
                    self._set_state(MachineState.RUNNING, "program")
                    return self._ok("resume")
            job.executor.hold = False
            if job.pause is not None and job.waiting:
                job.pause = None
                job.waiting = False
                job.executor.release_pause()
        self._set_state(MachineState.RUNNING, job.kind.value)
        return self._ok("resume")

    def _replan_here(self, job: _Job) -> _Job | None:
        """At a standstill on the path (hold or pause point): plan the rest of the program again
        from exactly here (single block switched on or off); the new plan starts at rest."""
        if job.origin is None:
            return None
        prog, base, u0 = job.origin
        ex = job.executor
        _, _, move, s_cum = ex.evaluate(np.array([ex.tau]))
        m = int(move[0])
        u = float(s_cum[0] - job.plan.segment.s0[m])
        index, u_orig = base + m, (u0 + u if m == 0 else u)
        if index >= len(prog.moves) - 1 and u_orig >= prog.moves[-1].length_mm - 1e-12:
            return None  # at the very end: nothing to re-plan
        try:
            rest = remaining_program(prog, index, u_orig)
            new = self._make_job(Activity.PROGRAM, rest, job.name, single_block=self._single_block)
        except PlannerError:
            return None
        full_t = self._program_info.cycle_time_s if self._program_info else new.estimated_s
        new.tau_offset_s = new.time_offset_s = max(full_t - new.executor.t_end, 0.0)
        new.origin = (prog, index, u_orig)
        new.start_time_s = job.start_time_s
        new.trace = job.trace
        new.samples, new.dwell_total_s = job.samples, job.dwell_total_s
        new.carried_limits = job.meter.final()
        new.estimated_s = job.estimated_s
        new.serial_base = job.serial_base
        self._job = new
        if self._worker_mode != "manual":
            self._feed()
        return new

    def stop(self) -> CommandResult:
        """Jerk-limited stop along the path, then abandon the program (-> IDLE)."""
        if self._state not in (MachineState.RUNNING, MachineState.HOLD, MachineState.HOMING):
            return self._refuse("stop", f"nothing to stop: machine is {self._state.label.lower()}")
        if self._state is MachineState.HOMING:
            return self._refuse("stop", "homing cannot be stopped mid-way: use E-stop")
        with self._lock:
            job = self._job
            if job is not None:
                job.executor.hold = True
                job.stopping = True
                job.stop_reason = "stopped by the operator"
                if job.kind is Activity.PROGRAM:
                    self._resume = None
        if job is None:
            self._set_state(MachineState.IDLE, "stopped")
        elif self._state is MachineState.RUNNING:
            self._set_state(MachineState.HOLD, "stopping")
        return self._ok("stop")

    def reset(self) -> CommandResult:
        """HOLD: abandon the program (after standstill) -> IDLE. ALARM: acknowledge the alarms,
        fault-reset and re-enable the drives -> IDLE (the resume point is kept). IDLE: forget the
        resume point.
        """
        st = self._state
        if st is MachineState.HOLD:
            with self._lock:
                job = self._job
                standing = job is None or job.executor.standing or job.pause is not None
            if not standing:
                return self.stop()
            self._drop_job(completed=False, reason="reset")
            self._resume = None
            self._set_state(MachineState.IDLE, "reset")
            return self._ok("reset")
        if st is MachineState.ALARM:
            if self._job is not None:
                return self._refuse("reset", "the machine is still stopping: wait for standstill")
            self.acknowledge_alarm(None)
            try:
                self._enable_worker()
            except Exception as exc:  # noqa: BLE001
                return self._refuse("reset", f"the drives cannot be re-enabled: {exc}")
            self._poll()
            if self._state is not MachineState.ALARM:
                return self._refuse("reset", f"machine is {self._state.label.lower()}")
            self._set_state(MachineState.IDLE, "reset")
            return self._ok("reset")
        if st is MachineState.IDLE:
            self._resume = None
            self._line = 0
            self.lineChanged.emit(0)
            return self._ok("reset")
        return self._refuse("reset", f"reset not possible: machine is {st.label.lower()}")

    def _enter_estop(self, reason: str) -> None:
        with self._lock:
            job = self._job
            if job is not None:
                self._resume = job.resume_point(self._consumed(), reason)
            self._drop_job(completed=False, reason=f"E-stop: {reason}")
        self._homing_queue.clear()
        self._homing_axis = -1
        if self._spindle.on:
            self._apply_spindle(SpindleState())
        if self._state is not MachineState.ESTOP:
            self._set_state(MachineState.ESTOP, reason)

    def estop(self, reason: str = "operator") -> CommandResult:
        """Emergency stop: the drives' quick stop at once, program abandoned (resume point kept),
        spindle off, -> ESTOP.
        """
        if self._worker is not None:
            try:
                with self._lock:
                    self._worker.estop(reason)
            except Exception:  # noqa: BLE001 - E-stop proceeds whatever the worker says
                pass
        self._raise_alarm(
            "operator" if reason == "operator" else "controller", f"E-stop: {reason}", Severity.ESTOP, "estop"
        )
        self._enter_estop(reason)
        if self._worker is not None:
            self._poll()
        return self._ok("estop")

    def estop_release(self) -> CommandResult:
        """Release the E-stop: fault reset and re-enable the drives, -> IDLE."""
        if self._state is not MachineState.ESTOP:
            return self._refuse("estop_release", "E-stop is not active")
        if self._worker is None:
            self._set_state(MachineState.DISCONNECTED, "E-stop released; not connected")
            return self._ok("estop_release")
        try:
            self._enable_worker()
        except Exception as exc:  # noqa: BLE001
            return self._refuse("estop_release", f"the drives cannot be re-enabled: {exc}")
        for a in list(self._alarms):
            if a.active and a.code == "estop":
                self._ack(a.id)
        self._alarms_changed()
        self._snapshot_now()
        self._set_state(MachineState.IDLE, "E-stop released")
        return self._ok("estop_release")

    def set_single_block(self, on: bool) -> CommandResult:
        """Single block: the plan stops at every block end (HOLD there; cycle start goes on).
        Switched while running, it takes effect at the next standstill (feed hold, pause point):
        the rest of the program is planned again from there."""
        self._single_block = bool(on)
        self.modesChanged.emit(self._single_block, self._optional_stop)
        if self._job is not None and self._job.kind is Activity.PROGRAM:
            self.message.emit("single block takes effect at the next stop (feed hold, block end, M00)")
        return self._ok("set_single_block")

    def set_optional_stop(self, on: bool) -> CommandResult:
        """Honour M01 (optional pause); may change while running."""
        self._optional_stop = bool(on)
        self.modesChanged.emit(self._single_block, self._optional_stop)
        return self._ok("set_optional_stop")

    def run_from_line(self, line: int) -> CommandResult:
        """Start the loaded program at source line ``line``: the spindle as of that line is
        restored, a safe approach (retract Z to the higher of the current and target heights,
        move the other axes, then down) brings the tool to the line's start point, then the
        program runs on from there.
        """
        why = self.refusal("run_from_line")
        if why:
            return self._refuse("run_from_line", why)
        prog = self._fresh_program()
        if prog is None:
            return self._refuse("run_from_line", "the program no longer passes its checks")
        try:
            i = locate(prog, int(line))
        except PlannerError as exc:
            return self._refuse("run_from_line", str(exc))
        point = _ResumePoint(
            program=prog, move_index=i, u_mm=0.0, line=prog.moves[i].line, cause=f"run from line {line}"
        )
        return self._resume_from_point(point, action="run_from_line")

    def _resume_from_point(self, point: _ResumePoint, action: str = "resume") -> CommandResult:
        if self._cfg.homing.required and not all(self._homed):
            return self._refuse(action, "axes not homed")
        if any(a.active and a.severity >= Severity.STOP for a in self._alarms):
            return self._refuse(action, "acknowledge the active alarms first")
        prog = point.program
        try:
            rest = remaining_program(prog, point.move_index, point.u_mm)
        except PlannerError as exc:
            return self._refuse(action, str(exc))
        modal = modal_state_before_move(prog, point.move_index)
        spindle = SpindleState(direction=int(np.sign(modal.spindle_rpm)), rpm=abs(modal.spindle_rpm))
        cur = self._machine_pos()
        retract = "Z" if "Z" in self._cfg.axes else ""
        moves = approach_moves(cur, rest.start_position, self._cfg.axes, self._cfg.machine.rotary, retract)
        name = self._program_info.name if self._program_info else prog.name
        try:
            main = self._make_job(Activity.PROGRAM, rest, name, single_block=self._single_block)
        except PlannerError as exc:
            return self._refuse(action, f"planner: {exc}")
        # progress relative to the whole program
        full_t = self._program_info.cycle_time_s if self._program_info else main.estimated_s
        main.tau_offset_s = max(full_t - main.executor.t_end, 0.0)
        main.time_offset_s = main.tau_offset_s
        main.origin = (prog, point.move_index, point.u_mm)
        main.spindle_before = spindle
        self._resume = None
        self._line = point.line
        if moves:
            approach = program_from_moves(prog, moves, [], cur, name="approach")
            issues = self._check_program_limits(approach)
            if issues:
                return self._refuse(action, f"approach move: soft limit: {issues[0]}")
            job = self._make_job(Activity.APPROACH, approach, "approach", overrides=True)
            job.then = main
            self._start_job(job)
        else:
            self._apply_spindle(spindle)
            self._start_job(main)
        return self._ok(action)

    @property
    def resume_line(self) -> int:
        """Line a resume (after a fault or E-stop mid-program) would continue from, 0 if none."""
        return self._resume.line if self._resume is not None else 0

    def set_feed_override(self, percent: float) -> CommandResult:
        """Feed override 0-150 %, applied while running without a jump and within every limit
        (``app.machine.timescale``); above 100 % the speed stays capped by the machine limits.
        """
        p = float(percent)
        if not 0.0 <= p <= 150.0:
            return self._refuse("set_feed_override", f"feed override must be 0-150 %, got {p:g}")
        self._feed_pct = p
        with self._lock:
            if self._job is not None and self._job.overrides:
                self._job.executor.set_overrides(feed=p / 100.0)
            if self._job is not None and self._job.then is not None:
                self._job.then.executor.set_overrides(feed=p / 100.0)
        self.overridesChanged.emit(self._feed_pct, self._rapid_pct)
        return self._ok("set_feed_override")

    def set_rapid_override(self, percent: float) -> CommandResult:
        """Rapid override 0-100 % (rapid moves only), applied like the feed override."""
        p = float(percent)
        if not 0.0 <= p <= 100.0:
            return self._refuse("set_rapid_override", f"rapid override must be 0-100 %, got {p:g}")
        self._rapid_pct = p
        with self._lock:
            for job in (self._job, self._job.then if self._job else None):
                if job is not None and job.overrides:
                    job.executor.set_overrides(rapid=p / 100.0)
        self.overridesChanged.emit(self._feed_pct, self._rapid_pct)
        return self._ok("set_rapid_override")

    # ================================================================== manual
    def _single_axis_program(self, i: int, target: float, feed_mm_s: float, name: str) -> Program:
        cur = self._machine_pos()
        end = cur.copy()
        end[i] = target
        rotary = self._cfg.machine.rotary
        length = abs(target - cur[i])
        move = Move(
            index=0,
            line=0,
            kind=MoveKind.LINE,
            start=cur.copy(),
            end=end,
            feed_mm_s=feed_mm_s,
            length_mm=length,
            arc=None,
            exact_stop=True,
        )
        return Program(
            name=name,
            axes=self._cfg.axes,
            rotary=rotary,
            moves=(move,),
            events=(),
            start_position=cur.copy(),
            line_count=0,
        )

    def jog_start(self, axis: str | int, direction: int, speed_fraction: float = 1.0) -> CommandResult:
        """Continuous jog of one axis toward + (1) or - (-1) at ``speed_fraction`` of the jog
        speed. The motion is planned to end at the soft limit, so a lost release stops exactly
        there; ``jog_stop`` is a jerk-limited stop.
        """
        try:
            i = self._axis(axis)
        except MachineError as exc:
            return self._refuse("jog", str(exc))
        why = self.refusal("jog")
        if why:
            return self._refuse("jog", why)
        if direction not in (1, -1):
            return self._refuse("jog", f"direction must be +1 or -1, got {direction}")
        ax = self._cfg.machine.axes[i]
        cur = float(self._machine_pos()[i])
        limit = ax.max_pos if direction > 0 else ax.min_pos
        if (limit - cur) * direction <= 1e-9:
            return self._refuse("jog", f"axis {ax.name} is at its soft limit {limit:g}")
        frac = min(max(float(speed_fraction), 0.01), 1.0)
        feed = min(self._cfg.controller.jog_speed_mm_s * frac, ax.v_max)
        prog = self._single_axis_program(i, limit, feed, f"jog {ax.name}{'+' if direction > 0 else '-'}")
        job = self._make_job(Activity.JOG, prog, prog.name, overrides=False)
        self._start_job(job)
        return self._ok("jog")

    def jog_stop(self, axis: str | int | None = None) -> CommandResult:
        """Release: jerk-limited stop of the jog (harmless when nothing jogs)."""
        with self._lock:
            job = self._job
            if job is None or job.kind is not Activity.JOG:
                return self._ok("jog_stop")
            job.executor.hold = True
            job.stopping = True
            job.stop_reason = "jog released"
        return self._ok("jog_stop")

    def jog_increment(self, axis: str | int, step: float, direction: int = 1) -> CommandResult:
        """Move one axis by ``direction * step`` (0.001 / 0.01 / 0.1 / 1 mm or degrees), refused
        when the target is beyond the soft limit.
        """
        try:
            i = self._axis(axis)
        except MachineError as exc:
            return self._refuse("jog", str(exc))
        why = self.refusal("jog")
        if why:
            return self._refuse("jog", why)
        step = abs(float(step))
        if not any(abs(step - s) < 1e-12 for s in JOG_INCREMENTS):
            return self._refuse("jog", f"increment must be one of {JOG_INCREMENTS}, got {step:g}")
        ax = self._cfg.machine.axes[i]
        target = float(self._machine_pos()[i]) + (1 if direction > 0 else -1) * step
        if not ax.min_pos - 1e-9 <= target <= ax.max_pos + 1e-9:
            return self._refuse(
                "jog",
                f"axis {ax.name} would reach {target:.4f}, beyond its soft limit "
                f"[{ax.min_pos:g}, {ax.max_pos:g}]",
            )
        prog = self._single_axis_program(
            i, target, min(self._cfg.controller.jog_speed_mm_s, ax.v_max), f"jog {ax.name} {step:g}"
        )
        job = self._make_job(Activity.JOG, prog, prog.name, overrides=False)
        self._start_job(job)
        return self._ok("jog")

    def mdi(self, block: str) -> CommandResult:
        """Execute one G-code block with the active work offset and the same checks as a program
        (parse, soft limits on the whole path, homed rule).
        """
        why = self.refusal("mdi")
        if why:
            return self._refuse("mdi", why)
        text = block.strip()
        if not text:
            return self._refuse("mdi", "empty block")
        if "\n" in text:
            return self._refuse("mdi", "MDI takes one block (one line)")
        if self._active_offset != "G54":
            text = f"{self._active_offset} {text}"
        try:
            prog = parse_program(text, "MDI", machine=self._machine, start_position=self._machine_pos())
        except ProgramError as exc:
            return self._refuse("mdi", "; ".join(e.message for e in exc.errors))
        except PlannerError as exc:
            return self._refuse("mdi", str(exc))
        issues = self._check_program_limits(prog)
        if issues:
            return self._refuse("mdi", f"soft limit: {issues[0].message}")
        if not prog.moves:
            for ev in prog.events:
                if ev.kind is EventKind.SPINDLE:
                    self._apply_spindle(SpindleState(direction=int(np.sign(ev.value)), rpm=abs(ev.value)))
            return self._ok("mdi")
        try:
            job = self._make_job(Activity.MDI, prog, "MDI")
        except PlannerError as exc:
            return self._refuse("mdi", f"planner: {exc}")
        self._start_job(job)
        return self._ok("mdi")

    # ================================================================== homing / offsets
    def home_axis(self, axis: str | int) -> CommandResult:
        """Home one axis by the configured method: "drive" (CiA 402 homing mode 6 with
        ``homing.drive_method``, via the worker) or "set_here" (current position = machine zero).
        """
        try:
            i = self._axis(axis)
        except MachineError as exc:
            return self._refuse("home", str(exc))
        return self._home([i])

    def home_all(self) -> CommandResult:
        """Home every axis (Z first) by the configured method."""
        order = list(range(len(self._cfg.axes)))
        if "Z" in self._cfg.axes:  # Z first: clear the part before the others move
            z = self._cfg.axes.index("Z")
            order.remove(z)
            order.insert(0, z)
        return self._home(order)

    def _home(self, axes: list[int]) -> CommandResult:
        why = self.refusal("home")
        if why:
            return self._refuse("home", why)
        if self._cfg.homing.method == "set_here":
            return self.set_machine_zero_here(None if len(axes) == len(self._cfg.axes) else axes[0])
        self._homing_queue = list(axes)
        self._set_state(MachineState.HOMING, "homing " + " ".join(self._cfg.axes[i] for i in axes))
        self._set_activity(Activity.HOMING)
        self._next_homing()
        return self._ok("home")

    def _next_homing(self) -> None:
        if not self._homing_queue:
            self._homing_axis = -1
            self._persist_state()
            if self._state is MachineState.HOMING:
                self._set_state(MachineState.IDLE, "homed")
            return
        i = self._homing_queue.pop(0)
        self._homing_axis = i
        self._homed[i] = False
        self.homedChanged.emit(tuple(self._homed))
        try:
            with self._lock:
                self._worker.home(i, self._cfg.homing.drive_method)
        except Exception as exc:  # noqa: BLE001
            self._homing_queue.clear()
            self._homing_axis = -1
            self._raise_alarm(
                f"drive {self._cfg.axes[i]}", f"homing refused: {exc}", Severity.STOP, "homing_error"
            )
            self._set_state(MachineState.ALARM, f"homing refused: {exc}")

    def _poll_homing(self, snap: Any) -> None:
        from ethercat.worker import HomingState, WorkerState

        i = self._homing_axis
        if i < 0 or self._state is not MachineState.HOMING:
            return
        if snap.homing[i] is HomingState.DONE and snap.state is WorkerState.ENABLED:
            self._home_offset[i] = 0.0  # the drive's own zero is machine zero
            self._homed[i] = True
            self.homedChanged.emit(tuple(self._homed))
            self._next_homing()

    def set_machine_zero_here(self, axis: str | int | None = None) -> CommandResult:
        """Declare the current position machine zero for one axis (all when None); homed; persisted."""
        if self._state not in (MachineState.IDLE,):
            return self._refuse("set_machine_zero_here", f"machine is {self._state.label.lower()}")
        try:
            idx = list(range(len(self._cfg.axes))) if axis is None else [self._axis(axis)]
        except MachineError as exc:
            return self._refuse("set_machine_zero_here", str(exc))
        for i in idx:
            self._home_offset[i] = self._raw_pos[i]
            self._homed[i] = True
        self._persist_state()
        self.homedChanged.emit(tuple(self._homed))
        self._last_emit_pos = ()
        self.positionChanged.emit(
            tuple(float(x) for x in self._machine_pos()), tuple(float(x) for x in self._work_pos())
        )
        return self._ok("set_machine_zero_here")

    def set_work_offset(self, name: str, values: dict[str, float] | tuple[float, ...]) -> CommandResult:
        """Set a G54-G59 offset (machine coordinates of part zero; a dict by axis name or one value
        per axis); persisted.
        """
        why = self.refusal("set_work_offset")
        if why:
            return self._refuse("set_work_offset", why)
        name = name.upper()
        if name not in WORK_OFFSET_NAMES:
            return self._refuse("set_work_offset", f"unknown work offset {name!r} (G54-G59)")
        cur = list(self._offsets.get(name, (0.0,) * len(self._cfg.axes)))
        if isinstance(values, dict):
            for k, v in values.items():
                try:
                    cur[self._axis(k)] = float(v)
                except MachineError as exc:
                    return self._refuse("set_work_offset", str(exc))
        else:
            if len(values) != len(cur):
                return self._refuse("set_work_offset", f"{name} needs {len(cur)} values")
            cur = [float(v) for v in values]
        if not all(math.isfinite(v) for v in cur):
            return self._refuse("set_work_offset", "offsets must be finite numbers")
        self._offsets[name] = tuple(cur)
        self._offsets_changed()
        return self._ok("set_work_offset")

    def _offsets_changed(self) -> None:
        try:
            self._store.save_offsets(self._offsets)
        except OSError as exc:
            self._raise_alarm(
                "persistence", f"cannot save work offsets: {exc}", Severity.WARNING, "state_file"
            )
        self._persist_state()
        self.offsetsChanged.emit(dict(self._offsets), self._active_offset)
        self._last_emit_pos = ()
        self.positionChanged.emit(
            tuple(float(x) for x in self._machine_pos()), tuple(float(x) for x in self._work_pos())
        )

    def select_work_offset(self, name: str) -> CommandResult:
        """Make G54-G59 the active work offset (MDI and work coordinates); persisted."""
        why = self.refusal("select_work_offset")
        if why:
            return self._refuse("select_work_offset", why)
        name = name.upper()
        if name not in WORK_OFFSET_NAMES:
            return self._refuse("select_work_offset", f"unknown work offset {name!r} (G54-G59)")
        self._active_offset = name
        self._offsets_changed()
        return self._ok("select_work_offset")

    def touch_off(self, axis: str | int, work_value: float = 0.0, offset: str | None = None) -> CommandResult:
        """Set part zero here: choose the offset (active unless named) so that the current
        position reads ``work_value`` in work coordinates on ``axis``.
        """
        why = self.refusal("touch_off")
        if why:
            return self._refuse("touch_off", why)
        try:
            i = self._axis(axis)
        except MachineError as exc:
            return self._refuse("touch_off", str(exc))
        name = (offset or self._active_offset).upper()
        if name not in WORK_OFFSET_NAMES:
            return self._refuse("touch_off", f"unknown work offset {name!r} (G54-G59)")
        cur = list(self._offsets.get(name, (0.0,) * len(self._cfg.axes)))
        cur[i] = float(self._machine_pos()[i]) - float(work_value)
        self._offsets[name] = tuple(cur)
        self._offsets_changed()
        return self._ok("touch_off")

    # ================================================================== spindle
    def _apply_spindle(self, sp: SpindleState) -> None:
        rpm = min(abs(sp.rpm), self._cfg.controller.spindle_max_rpm)
        sp = SpindleState(direction=int(np.sign(sp.direction)), rpm=rpm)  # rpm capped by the config
        if self._worker is not None:
            bits = 0 if sp.direction == 0 else (0b01 | (0b10 if sp.direction < 0 else 0))
            try:
                with self._lock:
                    self._worker.set_digital_output(self._cfg.controller.spindle_drive, bits)
            except Exception as exc:  # noqa: BLE001
                if self._job is not None and sp.on:
                    self._alarm_stop(f"spindle output failed: {exc}", "spindle", "spindle")
                else:
                    self._raise_alarm("spindle", f"spindle output failed: {exc}", Severity.WARNING, "spindle")
        self._spindle = sp
        self.spindleChanged.emit(sp)

    def spindle_on(self, clockwise: bool = True, rpm: float | None = None) -> CommandResult:
        """Spindle on, clockwise (M03) or counter-clockwise (M04), at ``rpm`` (last speed if None)."""
        why = self.refusal("spindle_on")
        if why:
            return self._refuse("spindle_on", why)
        speed = self._spindle.rpm if rpm is None else float(rpm)
        if not 0.0 <= speed <= self._cfg.controller.spindle_max_rpm:
            return self._refuse("spindle_on", f"speed must be 0-{self._cfg.controller.spindle_max_rpm:g} rpm")
        self._apply_spindle(SpindleState(direction=1 if clockwise else -1, rpm=speed))
        return self._ok("spindle_on")

    def spindle_off(self) -> CommandResult:
        """Spindle off (M05); always allowed."""
        self._apply_spindle(SpindleState(direction=0, rpm=self._spindle.rpm))
        return self._ok("spindle_off")

    def spindle_speed(self, rpm: float) -> CommandResult:
        """Set the spindle speed (applied at once when running)."""
        speed = float(rpm)
        if not 0.0 <= speed <= self._cfg.controller.spindle_max_rpm:
            return self._refuse(
                "spindle_speed", f"speed must be 0-{self._cfg.controller.spindle_max_rpm:g} rpm"
            )
        if self._spindle.on:
            self._apply_spindle(SpindleState(direction=self._spindle.direction, rpm=speed))
        else:
            self._spindle = SpindleState(direction=0, rpm=speed)
            self.spindleChanged.emit(self._spindle)
        return self._ok("spindle_speed")

    # ================================================================== alarms
    def _ack(self, alarm_id: int) -> bool:
        for k, a in enumerate(self._alarms):
            if a.id == alarm_id and a.active:
                self._alarms[k] = replace(a, state=AlarmState.ACKNOWLEDGED)
                return True
        return False

    def _alarms_changed(self) -> None:
        try:
            self._store.save_alarms(self._alarms)
        except OSError:
            pass
        self.alarmsChanged.emit(tuple(self._alarms))

    def acknowledge_alarm(self, alarm_id: int | None = None) -> CommandResult:
        """Acknowledge one alarm (all active ones when None); persisted."""
        if alarm_id is None:
            for a in list(self._alarms):
                if a.active:
                    self._ack(a.id)
        elif not self._ack(int(alarm_id)):
            return self._refuse("acknowledge_alarm", f"no active alarm with id {alarm_id}")
        self._alarms_changed()
        return self._ok("acknowledge_alarm")

    # ================================================================== configuration
    def update_config(self, config: MachineConfig) -> CommandResult:
        """Validate, write atomically (temp + os.replace, old file kept as .bak) and apply.
        Refused while moving; bus and drive changes take effect at the next connect; the loaded
        program is checked again against the new limits.
        """
        why = self.refusal("update_config")
        if why:
            return self._refuse("update_config", why)
        try:
            saved = save_config(config, self._config_path)
        except ConfigError as exc:
            return self._refuse("update_config", str(exc))
        except OSError as exc:
            return self._refuse("update_config", f"cannot write {self._config_path}: {exc}")
        old_axes = self._cfg.axes
        self._cfg = saved
        n = len(saved.axes)
        if saved.axes != old_axes:
            self._raw_pos = np.zeros(n) if self._worker is None else self._raw_pos[:n]
            self._home_offset = np.zeros(n)
            self._homed = [False] * n
            self._offsets = {k: tuple(v) for k, v in saved.machine.work_offsets.items()}
            self._store.save_offsets(self._offsets)
            self.homedChanged.emit(tuple(self._homed))
        self._persist_state()
        self.configChanged.emit(saved)
        if self._program_info is not None:
            self._load_text(self._program_text, self._program_info.name, self._program_path)
        if saved.axes != old_axes and self._worker is not None:
            self.message.emit("axes changed: reconnect the bus to apply")
        return self._ok("update_config")

    # ================================================================== properties
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
        return getattr(self, "_last_summary", None)

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


# ====================================================================== internal records
@dataclass(frozen=True, slots=True)
class _ResumePoint:
    program: Program
    move_index: int
    u_mm: float
    line: int
    cause: str


class _Job:
    """One motion being executed (program, MDI block, jog, approach); owned by the controller."""

    def __init__(
        self,
        kind: Activity,
        name: str,
        program: Program,
        plan: Plan,
        executor: TimeScaledExecutor,
        overrides: bool,
        estimated_s: float,
        machine: MachineSpec,
    ) -> None:
        self.kind = kind
        self.name = name
        self.program = program
        self.plan = plan
        self.executor = executor
        self.overrides = overrides
        self.estimated_s = estimated_s
        self.serial_base = 0
        self.start_time_s = -1.0
        self.pause: PausePoint | None = None
        self.pause_serial = 0
        self.waiting = False
        self.dwell_until: float | None = None
        self.dwell_total_s = 0.0
        self.samples = 0
        self.stopping = False
        self.stop_reason = ""
        self.aborted = False
        self.then: _Job | None = None
        self.spindle_before: SpindleState | None = None
        self.origin: tuple[Program, int, float] | None = None
        self.single_block = False
        self.carried_limits: dict[str, float] = {}
        self.tau_offset_s = 0.0
        self.time_offset_s = 0.0
        self.trace: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
        self.meter = LimitMeter(
            machine, plan.ts_s, plan.segment.table.is_rapid if len(plan.segment.table) else np.zeros(0, bool)
        )
        # per pushed chunk: serial of its last sample, line, tau, move, u within the move
        self._marks: collections.deque[tuple[int, int, float, int, float]] = collections.deque()
        self._last_mark: tuple[int, int, float, int, float] | None = None

    def record(self, ch: ScaledChunk, serial_start: int) -> None:
        end = serial_start + len(ch.q) - 1
        move = int(ch.move[-1])
        u = float(ch.s_mm[-1] - self.plan.segment.s0[move]) if len(self.plan.segment.table) else 0.0
        self._marks.append((end, int(ch.line[-1]), float(ch.tau[-1]), move, u))
        if len(self._marks) > 4096:
            self._marks.popleft()
        self.meter.update(ch.q, ch.s_mm, ch.move)

    def info_at(self, consumed: int) -> tuple[int, float] | None:
        """(line, tau) of the set-point the drives reached (the last consumed one)."""
        serial = consumed - 1
        m = self._mark_at(serial)
        return (m[1], m[2]) if m is not None else None

    def _mark_at(self, serial: int) -> tuple[int, int, float, int, float] | None:
        marks = self._marks
        while len(marks) > 1 and marks[0][0] < serial:
            self._last_mark = marks.popleft()
        if marks and marks[0][0] <= serial + 20:
            return marks[0] if marks[0][0] <= serial or self._last_mark is None else self._last_mark
        return self._last_mark

    def resume_point(self, consumed: int, cause: str) -> _ResumePoint | None:
        if self.kind is not Activity.PROGRAM or self.origin is None:
            return self.then.resume_point(consumed, cause) if self.then is not None else None
        prog, base, u0 = self.origin
        m = self._mark_at(consumed - 1)
        if m is None:
            return _ResumePoint(prog, base, u0, prog.moves[base].line if prog.moves else 0, cause)
        _, line, _, move, u = m
        orig = base + move
        u_orig = (u0 + u) if move == 0 else u
        if orig >= len(prog.moves):
            return None
        return _ResumePoint(prog, orig, u_orig, line, cause)


def _merge_max(a: dict[str, float], b: dict[str, float]) -> dict[str, float]:
    return {k: max(a.get(k, 0.0), b.get(k, 0.0)) for k in set(a) | set(b)}


class LimitMeter:
    """Running maxima of the set-points' velocity/acceleration/jerk ratios (``check_limits``)."""

    def __init__(self, machine: MachineSpec, ts_s: float, rapid_move: np.ndarray) -> None:
        self.machine = machine
        self.ts = ts_s
        self.rapid = rapid_move
        self.result: dict[str, float] = {}
        self._q: np.ndarray | None = None
        self._s: np.ndarray | None = None
        self._m: np.ndarray | None = None
        self._pending: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
        self._n = 0

    def update(self, q: np.ndarray, s: np.ndarray, move: np.ndarray) -> None:
        self._pending.append((q, s, move))
        self._n += len(q)
        if self._n >= 500:
            self.flush()

    def flush(self) -> None:
        if not self._pending:
            return
        q = np.concatenate([p[0] for p in self._pending])
        s = np.concatenate([p[1] for p in self._pending])
        move = np.concatenate([p[2] for p in self._pending])
        self._pending.clear()
        self._n = 0
        if self._q is not None:
            q = np.concatenate([self._q, q])
            s = np.concatenate([self._s, s])  # type: ignore[list-item]
            move = np.concatenate([self._m, move])  # type: ignore[list-item]
        if len(q) >= 4:
            r = check_limits(q, s, move, self.machine, self.ts, self.rapid)
            for k, v in r.items():
                self.result[k] = max(self.result.get(k, 0.0), v)
        self._q, self._s, self._m = q[-3:].copy(), s[-3:].copy(), move[-3:].copy()

    def final(self) -> dict[str, float]:
        self.flush()
        return dict(self.result)
