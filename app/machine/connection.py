"""Configuration, persistence and the bus connection: the worker's life cycle and the feeder thread.

connect_bus starts the worker (WorkerConfig defaults for core, priority and spin) and the
feeder thread; disconnect_bus/shutdown first stop any motion along its path, then stop the
worker (drives disabled) and only then the feeder. ``advance``/``run_until`` drive simulated
time in worker mode "manual". A part of ``MachineController``.
"""

from __future__ import annotations

import os
import shutil
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from PySide6.QtCore import QTimer

from app.machine.config import MachineConfig, load_config, recover_config, save_config
from app.machine.errors import ConfigError
from app.machine.model import Activity, BusStatus, CommandResult, MachineState, Severity
from app.machine.persist import StateStore
from app.machine.timescale import Budget
from app.paths import DEFAULT_STATE_DIR
from planner.machine import WORK_OFFSET_NAMES, MachineSpec
from resources import shipped_machine

if TYPE_CHECKING:
    from app.machine.controller import MachineController

__all__ = ["Connection", "RAMP_DOWN_TIMEOUT_S"]

RAMP_DOWN_TIMEOUT_S = 3.0  # disconnect/shutdown mid-run: longest wait for the stop along the path


class Connection:
    """Configuration, persistence, worker and feeder life cycle, simulated time.

    A part of ``MachineController`` (``controller.conn``): it owns the state set up in
    ``__init__`` and reaches the other parts through the facade ``m``.
    """

    def __init__(
        self,
        m: MachineController,
        config: MachineConfig | str | os.PathLike[str] | None,
        state_dir: str | os.PathLike[str] | None,
        worker_factory: Callable[..., object] | None,
        worker_mode: str,
        poll_hz: float,
    ) -> None:
        self.m = m
        self.store = StateStore(state_dir if state_dir is not None else DEFAULT_STATE_DIR, exclusive=True)
        self._worker_factory = worker_factory
        self.worker_mode = worker_mode
        self.worker: Any = None
        self.unclean_shutdown = False   # the state folder says the last run did not end cleanly
        self.persisted_at = 0.0         # time.monotonic() of the last save of the machine state
        self.config_notice = ""
        self._config_path = Path()
        self.cfg = self._load_initial_config(config)
        self._feeder: threading.Thread | None = None
        self._feeder_stop = threading.Event()
        self.timer = QTimer(m)
        self.timer.setInterval(max(int(1000.0 / poll_hz), 5))
        self._shutdown = False
        self.feeder_error = ""  # set by the feeder thread, reported by the poll

    def _load_initial_config(self, config: MachineConfig | str | os.PathLike[str] | None) -> MachineConfig:
        if isinstance(config, MachineConfig):
            self._config_path = Path(config.path) if config.path else self.store.path("machine.toml")
            return config
        if config is None:
            path = self.store.path("machine.toml")
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
            self.config_notice = f"machine configuration damaged: {text}"
            return cfg

    @property
    def config_path(self) -> Path:
        """The machine configuration file that ``update_config`` writes."""
        return self._config_path

    def restore_persisted(self) -> None:
        axes = self.cfg.axes
        st = self.store.load_state(axes)
        if st is not None:
            self.m.pos.raw_pos = np.array(st["raw_position"], dtype=float)
            self.m.pos.home_offset = np.array(st["home_offset"], dtype=float)
            self.m.pos.homed = list(st["homed"])
            self.unclean_shutdown = st["running"]
            if st["running"]:
                # the last run ended without a shutdown (power loss, kill): the drives may have
                # moved or lost their count since the position was saved
                if not self.cfg.homing.absolute_encoders and any(self.m.pos.homed):
                    self.m.pos.homed = [False] * len(axes)
                    why = "axes are not homed any more: home them before running a program"
                else:
                    why = "the drives have absolute encoders: homed flags kept"
                when = time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(st["saved"])) if st["saved"] else "?"
                cause = (f"the control did not shut down cleanly (power loss or killed; position last "
                         f"saved {when}): {why}")
                self.m.alarm_log.raise_alarm("controller", cause, Severity.WARNING, "unclean_shutdown")
            if st["active_offset"] in WORK_OFFSET_NAMES:
                self.m.pos.active_offset = st["active_offset"]
        offs = self.store.load_offsets(len(axes))
        if offs is not None:
            self.m.pos.offsets.update({k: v for k, v in offs.items() if k in WORK_OFFSET_NAMES})
        self.m.pos.parameters = self.store.load_parameters()
        self.m.pos.ref_raw = self.m.pos.raw_pos.copy()

    def persist_state(self) -> None:
        self.persisted_at = time.monotonic()
        try:
            self.store.save_state(
                self.cfg.axes,
                [float(x) for x in self.m.pos.raw_pos],
                [float(x) for x in self.m.pos.home_offset],
                list(self.m.pos.homed),
                self.m.pos.active_offset,
                running=self.worker is not None and not self._shutdown,
            )
        except OSError as exc:
            self.m.alarm_log.raise_alarm(
                "persistence", f"cannot save machine state: {exc}", Severity.WARNING, "state_file"
            )

    @property
    def machine(self) -> MachineSpec:
        return replace(self.cfg.machine, work_offsets=dict(self.m.pos.offsets))

    @property
    def budget(self) -> Budget:
        c = self.cfg.controller
        return Budget(k_a=1.0 - c.accel_reserve, k_j=1.0 - c.jerk_reserve)

    def update_config(self, config: MachineConfig, *, wait: bool = False) -> CommandResult:
        """Validate, write atomically (temp + os.replace, old file kept as .bak) and apply.
        Refused while moving; bus and drive changes take effect at the next connect; the loaded
        program is checked again against the new limits: in a worker thread like a load (cycle
        start refused until it is done; ``loadingChanged``), or before returning with ``wait``
        (headless; the outcome is the same).
        """
        why = self.m.states.refusal("update_config")
        if why:
            return self.m.states.refuse("update_config", why)
        try:
            saved = save_config(config, self._config_path)
        except ConfigError as exc:
            return self.m.states.refuse("update_config", str(exc))
        except OSError as exc:
            return self.m.states.refuse("update_config", f"cannot write {self._config_path}: {exc}")
        old_axes = self.cfg.axes
        self.cfg = saved
        n = len(saved.axes)
        if saved.axes != old_axes:
            self.m.pos.raw_pos = np.zeros(n) if self.worker is None else self.m.pos.raw_pos[:n]
            self.m.pos.home_offset = np.zeros(n)
            self.m.pos.homed = [False] * n
            self.m.pos.offsets = {k: tuple(v) for k, v in saved.machine.work_offsets.items()}
            self.store.save_offsets(self.m.pos.offsets)
            self.m.homedChanged.emit(tuple(self.m.pos.homed))
        self.persist_state()
        self.m.configChanged.emit(saved)
        if self.m.loader.load_request is not None:  # a load in flight restarts with the new configuration
            req = self.m.loader.load_request
            if wait:
                self.m.loader.load_text(req.text, req.name, req.path)
            else:
                self.m.loader.start_load(req.text, req.name, req.path)
        elif self.m.loader.program_info is not None:
            self.m.loader.recheck_program(wait)
        if saved.axes != old_axes and self.worker is not None:
            self.m.message.emit("axes changed: reconnect the bus to apply")
        return self.m.states.ok("update_config")

    def _worker_config(self) -> Any:
        from ethercat.worker import DriveSpec, WorkerConfig
        from ethercat.worker.shared import ordered_stores

        cfg = self.cfg
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
        if cfg.bus.kind == "soem":
            options = (("setups", tuple((d.position, d.setup()) for d in cfg.bus.drives)),)
        if cfg.bus.kind == "sim":
            counts = tuple(
                float(a.direction * a.counts_per_unit * x)
                for a, x in zip(cfg.machine.axes, self.m.pos.raw_pos)
            )
            options = (("initial_positions_counts", counts),)
        # core, real-time priority and spin: the WorkerConfig defaults (the worker picks a free
        # core itself and uses SCHED_FIFO 49, below PREEMPT_RT's interrupt threads)
        mode = self.worker_mode
        if mode == "process" and not ordered_stores():
            # the worker's own process shares memory in a way that needs x86's store order;
            # elsewhere (ARM panel PCs) the same loop runs as a thread of the panel
            mode = "thread"
            self.m.alarm_log.raise_alarm(
                "worker", "this CPU does not keep stores in order: the 1 ms loop runs as a thread "
                "of the panel, not in its own process (less punctual under GUI load)",
                Severity.WARNING, "worker_thread_mode")
        return WorkerConfig(
            drives=drives,
            ts_s=cfg.machine.planner.ts_s,
            bus_kind=cfg.bus.kind,
            adapter=cfg.bus.adapter,
            wkc_error_limit=cfg.bus.wkc_error_limit,
            mode=mode,
            bus_options=options,
            homing_timeout_s=cfg.homing.timeout_s,
        )

    def connect_bus(self) -> CommandResult:
        """Start the worker (simulated drives when the bus kind is "sim") and enable the drives:
        DISCONNECTED -> IDLE. Saved positions are restored (simulated drives start there); an axis
        whose reported position differs from the saved one loses its homed state (warning alarm).
        """
        if self.m.states.state is not MachineState.DISCONNECTED:
            return self.m.states.refuse(
                "connect", f"already connected (machine is {self.m.states.state.label.lower()})"
            )
        wcfg = self._worker_config()
        try:
            if self._worker_factory is not None:
                worker = self._worker_factory(wcfg)
            else:
                from ethercat.worker import CyclicWorker

                worker = CyclicWorker(wcfg)
            worker.start()
        except Exception as exc:  # noqa: BLE001 - any bus failure is shown to the operator
            self.m.alarm_log.raise_alarm("bus", f"cannot start the bus: {exc}", Severity.WARNING, "bus_start")
            return self.m.states.refuse("connect", f"cannot start the bus: {exc}")
        self.worker = worker
        self.m.alarm_log.seen_worker_alarms.clear()
        # what the bus start-up adapted to (a drive's own mapping, objects it lacks): recorded
        # for the integrator, nothing to acknowledge
        for k, note in enumerate(getattr(worker, "bus_notes", ())):
            self.m.alarm_log.raise_alarm("bus", note, Severity.INFO, f"bus_note_{k}")
        try:
            self.enable_worker()
        except Exception as exc:  # noqa: BLE001
            self._stop_worker()
            self.m.alarm_log.raise_alarm(
                "bus", f"drives cannot be enabled: {exc}", Severity.WARNING, "enable"
            )
            return self.m.states.refuse("connect", f"drives cannot be enabled: {exc}")
        snap = self.snapshot_now()
        actual = np.asarray(snap.actual_position, dtype=float)
        tol = self.cfg.controller.position_tolerance
        moved = np.abs(actual - self.m.pos.raw_pos) > max(tol, 1e-9)
        if any(h and m for h, m in zip(self.m.pos.homed, moved)):
            names = [a for a, h, m in zip(self.cfg.axes, self.m.pos.homed, moved) if h and m]
            self.m.pos.homed = [h and not m for h, m in zip(self.m.pos.homed, moved)]
            self.m.alarm_log.raise_alarm(
                "controller",
                f"axes {' '.join(names)} report another position than saved: homed state cleared, home again",
                Severity.WARNING,
                "position_lost",
            )
            self.m.homedChanged.emit(tuple(self.m.pos.homed))
        self.m.pos.raw_pos = actual.copy()
        self.m.pos.ref_raw = actual.copy()
        self.m.stream.pushed_total = 0
        self.m.states.set_state(MachineState.IDLE, "ready")
        if self.worker_mode != "manual":
            # the feeder thread shares the GIL with the GUI: a short switch interval keeps it on
            # time while the GUI computes (NOTES.md: 5 ms default stretches 1 ms loops to 5 ms)
            if sys.getswitchinterval() > 0.001:
                sys.setswitchinterval(0.001)
            self._feeder_stop.clear()
            self._feeder = threading.Thread(target=self._feeder_main, name="cnc-feeder", daemon=True)
            self._feeder.start()
            self.timer.start()
        self.m.poller.emit_all()
        self.persist_state()            # "running" from now on, until a clean shutdown
        return self.m.states.ok("connect")

    def enable_worker(self) -> None:
        from ethercat.worker import WorkerState

        w = self.worker
        with self.m._lock:
            st = w.state()
            if st in (WorkerState.FAULT, WorkerState.QUICK_STOP, WorkerState.FAULT_RESET):
                w.fault_reset()
                w.wait_for((WorkerState.DISABLED,), timeout_s=2.0)
            w.flush()
            w.enable()
            w.wait_for((WorkerState.ENABLED,), timeout_s=3.0)

    def snapshot_now(self) -> Any:
        with self.m._lock:
            snap = self.worker.snapshot()
        self.m.poller.last_snap = snap
        return snap

    def _stop_worker(self) -> None:
        """Stop the worker (drives disabled, bus closed), then the feeder thread."""
        self.timer.stop()
        with self.m._lock:
            w, self.worker = self.worker, None  # the feeder sees no worker from here on
        if w is not None:
            try:
                with self.m._lock:
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
        if self.m.states.state is MachineState.DISCONNECTED:
            return self.m.states.ok("disconnect")
        self._ramp_down("disconnected")
        if self.worker is not None:
            try:
                self.m.poller.poll()
            except Exception:  # noqa: BLE001
                pass
        with self.m._lock:
            self.m.stream.drop_job(completed=False, reason="disconnected")
        self._stop_worker()
        self.persist_state()            # no controller has the drives any more
        self.m.states.set_state(MachineState.DISCONNECTED, "disconnected")
        self.m.poller.emit_bus(BusStatus(kind=self.cfg.bus.kind, connected=False, state="disconnected"))
        return self.m.states.ok("disconnect")

    def _ramp_down(self, reason: str, timeout_s: float = RAMP_DOWN_TIMEOUT_S) -> bool:
        """Bring any motion to a standstill on its path before the worker is stopped: the same
        jerk-limited stop as ``stop()``, fed as usual, waited for here (the poll timer may be
        gone at exit). Without it, stopping the feeder first let the worker's buffer run dry
        while moving (a bogus "set-point buffer underrun" alarm persisted at every quit
        mid-run) and stopping the worker first cut the drives at speed. True at standstill."""
        from ethercat.worker import WorkerState

        with self.m._lock:
            job, w = self.m.stream.job, self.worker
            if job is None or w is None:
                return True
            if w.state() is not WorkerState.ENABLED:
                return True  # the worker already stopped the drives (quick stop, fault)
            if job.kind is Activity.PROGRAM and job.origin is not None and self.m.run.resume_point is None:
                self.m.run.resume_point = job.resume_point(self.m.stream.consumed(), reason)
            self.m.stream.hold_motion()
            job.stopping = True
            job.stop_reason = job.stop_reason or reason

        def still() -> bool:
            with self.m._lock:
                if self.worker is None or self.m.stream.job is not job:
                    return True
                standing = job.executor.standing or job.pause is not None or job.executor.finished
                return standing and self.worker.buffer_level() == 0

        if self.worker_mode == "manual":
            return self.run_until(still, timeout_s)
        t_end = time.monotonic() + timeout_s
        while not still():
            if time.monotonic() > t_end:
                return False
            if self._feeder is None or not self._feeder.is_alive():
                self.m.stream.feed()
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
            if self.m.spindle_ctl.spindle.on:
                self.m.spindle_ctl.spindle_off()
            self.disconnect_bus()
        finally:
            self.persist_state()
            self.store.release()

    def _feeder_main(self) -> None:
        while not self._feeder_stop.wait(0.002):
            try:
                self.m.stream.feed()
            except Exception as exc:  # noqa: BLE001 - never let the feeder die silently
                with self.m._lock:
                    self.feeder_error = f"set-point feeder failed: {exc}"
                return

    def advance(self, seconds: float, step_cycles: int = 10) -> None:
        """Manual worker mode only: run the machine for ``seconds`` of simulated time
        (feed set-points, run the cycles, poll and emit signals). For tests and tools."""
        if self.worker is None:
            return
        ts = self.cfg.machine.planner.ts_s
        cycles = int(round(seconds / ts))
        since_poll = 0
        poll_every = max(int(round(1.0 / (30.0 * ts))), 1)
        while cycles > 0 and self.worker is not None:
            k = min(step_cycles, cycles)
            self.m.stream.feed()
            with self.m._lock:
                self.worker.step(k)
            cycles -= k
            since_poll += k
            if since_poll >= poll_every or cycles <= 0:
                since_poll = 0
                self.m.poller.poll()

    def run_until(self, predicate: Callable[[], bool], timeout_s: float = 10.0) -> bool:
        """Manual mode: advance until ``predicate()`` is true (True) or ``timeout_s`` of
        simulated time passed (False)."""
        ts = self.cfg.machine.planner.ts_s
        step_s = 33 * ts
        steps = int(timeout_s / step_s) + 1
        for _ in range(steps):
            if predicate():
                return True
            self.advance(step_s, step_cycles=11)
        return bool(predicate())
