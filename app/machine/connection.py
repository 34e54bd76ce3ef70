"""Configuration, persistence and the bus connection: the worker's life cycle and the feeder thread.

connect_bus starts the worker (WorkerConfig defaults for core, priority and spin) and the
feeder thread; disconnect_bus/shutdown first stop any motion along its path, then stop the
worker (drives disabled) and only then the feeder. ``advance``/``run_until`` drive simulated
time in worker mode "manual". Part of ``MachineController`` (mixed in).
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
from typing import Any

import numpy as np

from app.machine.config import MachineConfig, load_config, recover_config, save_config
from app.machine.errors import ConfigError
from app.machine.model import Activity, BusStatus, CommandResult, MachineState, Severity
from app.machine.timescale import Budget
from planner.machine import WORK_OFFSET_NAMES, MachineSpec
from resources import shipped_machine

__all__ = ["ConnectionMixin", "RAMP_DOWN_TIMEOUT_S"]

RAMP_DOWN_TIMEOUT_S = 3.0  # disconnect/shutdown mid-run: longest wait for the stop along the path


class ConnectionMixin:
    """Configuration, persistence, worker and feeder life cycle, simulated time.

    Mixed into ``MachineController``, which holds the state.
    """

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

    def update_config(self, config: MachineConfig, *, wait: bool = False) -> CommandResult:
        """Validate, write atomically (temp + os.replace, old file kept as .bak) and apply.
        Refused while moving; bus and drive changes take effect at the next connect; the loaded
        program is checked again against the new limits: in a worker thread like a load (cycle
        start refused until it is done; ``loadingChanged``), or before returning with ``wait``
        (headless; the outcome is the same).
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
        if self._load_request is not None:  # a load in flight restarts with the new configuration
            req = self._load_request
            if wait:
                self._load_text(req.text, req.name, req.path)
            else:
                self._start_load(req.text, req.name, req.path)
        elif self._program_info is not None:
            self._recheck_program(wait)
        if saved.axes != old_axes and self._worker is not None:
            self.message.emit("axes changed: reconnect the bus to apply")
        return self._ok("update_config")

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
            self._hold_motion()
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
