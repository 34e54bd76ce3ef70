"""The handle on the drives: the one place the controller calls the cyclic worker.

``DriveLink`` holds the worker while the bus is connected (``attach``/``detach``, by the
connection) and its last snapshot. Every call goes through its own lock, which no other part
takes: ``detach`` waits for a call in flight (the feeder thread's push, say) and every call
after it finds no worker and does nothing (a push takes none, a snapshot is None). The worker
is itself safe to call from the controller's thread and the feeder thread at once (its own
lock orders the commands and the set-point ring).

The controller sees the machine's axes: a gantry's second drive (the loop's drive after the
axes) is part of its axis. Snapshots, traces and probe latches are cut to the axes
(``machine_view``); the per-drive fields (states, status words, inputs, the gantries' skews)
keep every drive, for Diagnostics.
"""

from __future__ import annotations

import dataclasses
import threading
from collections.abc import Sequence

import numpy as np

from ethercat.worker import (
    CyclicWorker,
    HomingState,
    HomingStep,
    ReplaceResult,
    TraceChunk,
    WorkerEvent,
    WorkerSnapshot,
    WorkerState,
)

__all__ = ["DriveLink", "machine_view"]


def machine_view(snap: WorkerSnapshot, worker: CyclicWorker) -> WorkerSnapshot:
    """``snap`` with its per-axis fields for the machine's axes only: a gantry axis is homed
    when both its sides are, homes while either does, and shows its second side's step while
    that side squares the pair."""
    cfg = worker.config
    m = cfg.n_motion_axes
    if m == cfg.n_axes:
        return snap
    homing, homed = list(snap.homing[:m]), list(snap.homed[:m])
    steps = list(snap.homing_steps[:m])
    for g in cfg.gantry:
        i, f = g.axis, g.follower
        both = (snap.homing[i], snap.homing[f])
        for state in (HomingState.ERROR, HomingState.RUNNING):
            if state in both:
                homing[i] = state
                break
        homed[i] = snap.homed[i] and snap.homed[f]
        if steps[i] is HomingStep.DONE and snap.homing_steps[f] is not HomingStep.DONE:
            steps[i] = snap.homing_steps[f]
    probe = dataclasses.replace(snap.probe, position=snap.probe.position[:m])
    t = snap.tracking
    tracking = dataclasses.replace(t, rmse=t.rmse[:m], mse=t.mse[:m], max_abs=t.max_abs[:m],
                                   window_rmse=t.window_rmse[:m], window_mse=t.window_mse[:m])
    return dataclasses.replace(
        snap, actual_position=snap.actual_position[:m], reference_position=snap.reference_position[:m],
        following_error=snap.following_error[:m], homing=tuple(homing), homed=tuple(homed),
        homing_steps=tuple(steps), home_latched=snap.home_latched[:m], compensation=snap.compensation[:m],
        compensation_on=snap.compensation_on[:m], probe=probe, tracking=tracking)


class DriveLink:
    """The connected worker (or none) and what the controller asks of it."""

    def __init__(self, worker_mode: str) -> None:
        #: "process" (the 1 ms loop in its own process), "thread", or "manual" (no clock:
        #: ``step`` runs the cycles; tests and fast headless runs)
        self.worker_mode = worker_mode
        self._lock = threading.RLock()
        self._worker: CyclicWorker | None = None
        #: the newest snapshot taken (``snapshot``), None before the first
        self.last_snapshot: WorkerSnapshot | None = None

    # ---------------------------------------------------------------- life cycle
    def attach(self, worker: CyclicWorker) -> None:
        with self._lock:
            self._worker = worker
            self.last_snapshot = None

    def detach(self) -> CyclicWorker | None:
        """Let go of the worker (after the call in flight); the caller stops it."""
        with self._lock:
            w, self._worker = self._worker, None
            return w

    @property
    def attached(self) -> bool:
        return self._worker is not None

    @property
    def worker(self) -> CyclicWorker | None:
        """The worker itself, for diagnostics and tests (None when disconnected)."""
        return self._worker

    @property
    def realtime(self) -> bool:
        """Whether the loop runs on its own clock (not stepped by ``step``)."""
        return self.worker_mode != "manual"

    # ---------------------------------------------------------------- state
    def state(self) -> WorkerState:
        with self._lock:
            return self._worker.state() if self._worker is not None else WorkerState.STOPPED

    def snapshot(self) -> WorkerSnapshot | None:
        """A fresh snapshot (kept as ``last_snapshot``); None when disconnected."""
        with self._lock:
            if self._worker is None:
                return None
            snap = machine_view(self._worker.snapshot(), self._worker)
            self.last_snapshot = snap
            return snap

    def events(self) -> tuple[WorkerEvent, ...]:
        with self._lock:
            return self._worker.events() if self._worker is not None else ()

    def drain_trace(self) -> TraceChunk | None:
        """The trace since the last drain, the machine's axes' columns."""
        with self._lock:
            w = self._worker
            if w is None:
                return None
            t = w.drain_trace()
            m = w.config.n_motion_axes
            if m == w.config.n_axes:
                return t
            return dataclasses.replace(t, reference=t.reference[:, :m], actual=t.actual[:, :m])

    def bus_notes(self) -> tuple[str, ...]:
        w = self._worker
        return tuple(w.bus_notes) if w is not None else ()

    def samples_consumed(self) -> int | None:
        """The serial the drives reached, read live (None when disconnected)."""
        with self._lock:
            return self._worker.samples_consumed() if self._worker is not None else None

    def buffer_level(self) -> int:
        with self._lock:
            return self._worker.buffer_level() if self._worker is not None else 0

    def probe_latched(self) -> tuple[float, ...] | None:
        with self._lock:
            w = self._worker
            if w is None:
                return None
            latched = w.probe_latched()
            return None if latched is None else latched[:w.config.n_motion_axes]

    # ---------------------------------------------------------------- set-points
    def push(self, q: np.ndarray) -> int:
        """Queue set-points (drive units); how many were taken, -1 when disconnected."""
        with self._lock:
            return self._worker.push(q) if self._worker is not None else -1

    def replace(self, serial: int, q: np.ndarray) -> tuple[ReplaceResult, int]:
        """Replace the queue from ``serial`` (``CyclicWorker.replace``); BEYOND_END when
        disconnected (nothing queued to replace)."""
        with self._lock:
            if self._worker is None:
                return ReplaceResult.BEYOND_END, 0
            return self._worker.replace(serial, q)

    def flush(self) -> None:
        """Drop the queued set-points (best effort: a stopping worker queues nothing)."""
        with self._lock:
            if self._worker is not None:
                try:
                    self._worker.flush()
                except Exception:  # noqa: BLE001 - the queue is gone either way
                    pass

    def step(self, cycles: int) -> None:
        """Manual worker mode: run ``cycles`` cycles now."""
        with self._lock:
            if self._worker is not None:
                self._worker.step(cycles)

    def reset_tracking(self) -> None:
        with self._lock:
            if self._worker is not None:
                self._worker.reset_tracking()

    # ---------------------------------------------------------------- commands
    def enable_drives(self) -> None:
        """Fault reset where needed, then enable every drive (raises what the worker raises)."""
        with self._lock:
            w = self._worker
            if w is None:
                raise RuntimeError("not connected")
            st = w.state()
            if st in (WorkerState.FAULT, WorkerState.QUICK_STOP, WorkerState.FAULT_RESET):
                w.fault_reset()
                w.wait_for((WorkerState.DISABLED,), timeout_s=2.0)
            w.flush()
            w.enable()
            w.wait_for((WorkerState.ENABLED,), timeout_s=3.0)

    def estop(self, reason: str) -> None:
        """The drives' quick stop at once (best effort: an E-stop goes on whatever happens)."""
        with self._lock:
            if self._worker is not None:
                try:
                    self._worker.estop(reason)
                except Exception:  # noqa: BLE001
                    pass

    def home(self, axis: int, method: int) -> None:
        with self._lock:
            if self._worker is None:
                raise RuntimeError("not connected")
            self._worker.home(axis, method)

    def home_to_switches(self, axes: Sequence[int]) -> None:
        with self._lock:
            if self._worker is None:
                raise RuntimeError("not connected")
            self._worker.home_to_switches(list(axes))

    def handwheel(self, axis: int, mode: int, scale: float, limits: Sequence[float]) -> bool:
        """Axis ``axis`` follows the handwheel (``CyclicWorker.handwheel``); False when refused
        or disconnected."""
        with self._lock:
            return self._worker.handwheel(axis, mode, scale, limits) if self._worker is not None else False

    def handwheel_off(self) -> bool:
        """The handwheel lets its axis go: True when it stood (or nothing was connected), False
        while it brakes to rest."""
        with self._lock:
            return self._worker.handwheel_off() if self._worker is not None else True

    def spindle(self, rpm: float, ramp_rpm_s: float) -> bool:
        """The spindle's own drive to ``rpm`` (signed) along ``ramp_rpm_s``
        (``CyclicWorker.spindle``); False when refused or disconnected."""
        with self._lock:
            return self._worker.spindle(rpm, ramp_rpm_s) if self._worker is not None else False

    def compensate(self, axis: int, on: bool, home_offset: float) -> bool:
        """Leadscrew compensation of ``axis`` on or off (``CyclicWorker.compensate``); False when
        the axis has none or nothing is connected."""
        with self._lock:
            return self._worker.compensate(axis, on, home_offset) if self._worker is not None else False

    def set_terminal_output(self, terminal: int, word: int) -> None:
        with self._lock:
            if self._worker is not None:
                self._worker.set_terminal_output(terminal, word)

    def override_limits(self, on: bool) -> None:
        with self._lock:
            if self._worker is not None:
                self._worker.override_limits(on)

    def set_digital_output(self, drive: int, word: int) -> None:
        with self._lock:
            if self._worker is not None:
                self._worker.set_digital_output(drive, word)

    def arm_probe(self, drive: int, bit: int, level: bool) -> bool:
        with self._lock:
            return self._worker.arm_probe(drive, bit, level) if self._worker is not None else False

    def disarm_probe(self) -> None:
        with self._lock:
            if self._worker is not None:
                try:
                    self._worker.disarm_probe()
                except Exception:  # noqa: BLE001 - a worker going away watches nothing
                    pass

    def inject(self, name: str, axis: int, value: int) -> None:
        with self._lock:
            if self._worker is not None:
                self._worker.inject(name, axis, value)

    def digital_inputs(self) -> Sequence[int]:
        snap = self.last_snapshot
        return tuple(snap.digital_inputs) if snap is not None else ()
