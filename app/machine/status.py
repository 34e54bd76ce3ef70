"""Reading the worker (<= 30 Hz): positions, path speed, tracking samples, bus status; the
signals that carry them. A part of ``MachineController``.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from app.machine.model import BusStatus, MachineState

if TYPE_CHECKING:
    from app.machine.controller import MachineController

__all__ = ["PERSIST_EVERY_S", "StatusPoller"]

PERSIST_EVERY_S = 1.0  # position and homed flags saved this often while the axes may move
_MOVING = frozenset({MachineState.RUNNING, MachineState.HOLD, MachineState.HOMING})


class StatusPoller:
    """Polling the worker and emitting what the panel shows.

    A part of ``MachineController`` (``controller.poller``): it owns the state set up in
    ``__init__`` and reaches the other parts through the facade ``m``.
    """

    def __init__(self, m: MachineController) -> None:
        self.m = m
        self.last_snap: Any = None
        self.bus_status = BusStatus(kind=m.config.bus.kind)
        self.last_emit_pos: tuple[float, ...] = ()
        self._last_ref_time = 0.0
        self._last_ref_pos: np.ndarray | None = None
        self.tracking_emit_t = 0.0
        # every drained set-point chunk (cycles, reference, actual) also goes here when set
        # (``app.machine.scenario.Recorder``)
        self.sink: Callable[[np.ndarray, np.ndarray, np.ndarray], None] | None = None

    def poll(self) -> None:
        w = self.m.worker
        if w is None:
            return
        snap = self.m.conn.snapshot_now()
        self.m.pos.raw_pos = np.asarray(snap.actual_position, dtype=float).copy()
        self.m.pos.ref_raw = np.asarray(snap.reference_position, dtype=float).copy()
        self.m.alarm_log.handle_worker_alarms(snap)
        events = getattr(w, "events", None)
        if events is not None:
            self.m.alarm_log.handle_worker_events(events())
        with self.m._lock:
            trace = w.drain_trace()
        self.deliver(trace)
        job = self.m.stream.job
        if job is not None and len(trace.cycle):
            job.trace.append((trace.cycle.copy(), trace.reference.copy(), trace.actual.copy()))
        self.m.pos.poll_homing(snap)
        self.m.prober.place_simulated_surface()
        if job is not None:
            self.m.stream.poll_job(job, snap)
        self._emit_positions(snap)
        self._emit_bus_from(snap)
        if self.m.conn.feeder_error:
            text, self.m.conn.feeder_error = self.m.conn.feeder_error, ""
            self.m.alarm_log.fault(text, "controller", "feeder")
        if self.m.states.state in _MOVING and time.monotonic() - self.m.conn.persisted_at >= PERSIST_EVERY_S:
            self.m.conn.persist_state()     # a power cut loses at most this much of the position

    def deliver(self, trace: Any) -> None:
        """Hand a drained trace chunk to the sink (if any)."""
        if self.sink is not None and len(trace.cycle):
            self.sink(trace.cycle, trace.reference, trace.actual)

    def _emit_positions(self, snap: Any) -> None:
        mpos = tuple(float(x) for x in self.m.states.machine_pos())
        if mpos != self.last_emit_pos:
            self.last_emit_pos = mpos
            self.m.positionChanged.emit(mpos, tuple(float(x) for x in self.m.states.work_pos()))
        ref_m = self.m.pos.ref_raw - self.m.pos.home_offset
        self.m.trackingSample.emit(float(snap.time_s), tuple(float(x) for x in ref_m), mpos)
        lin = np.array([not r for r in self.m.config.machine.rotary])
        if self._last_ref_pos is not None and snap.time_s > self._last_ref_time:
            d = (ref_m - self._last_ref_pos)[lin] if lin.any() else ref_m - self._last_ref_pos
            speed = float(np.linalg.norm(d)) / (snap.time_s - self._last_ref_time)
            if abs(speed - self.m.stream.speed) > 1e-6:
                self.m.stream.speed = speed
                self.m.speedChanged.emit(speed)
        self._last_ref_pos = ref_m.copy()
        self._last_ref_time = float(snap.time_s)

    def _emit_bus_from(self, snap: Any) -> None:
        tm = snap.timing
        status = BusStatus(
            kind=self.m.config.bus.kind,
            connected=True,
            state=snap.state.name.lower(),
            drive_states=tuple(s.name for s in snap.drive_states),
            buffer_level=int(snap.buffer_level),
            late_cycles=int(tm.late_cycles),
            period_p99_us=float(tm.jitter_p99_s * 1e6),
            jitter_hist_bin_us=float(tm.histogram_bin_s * 1e6),
            jitter_hist_counts=tuple(tm.jitter_histogram),
            jitter_max_us=float(tm.jitter_max_s * 1e6),
            probe=self._probe_text(snap),
        )
        self.emit_bus(status)

    def _probe_text(self, snap: Any) -> str:
        cfg = self.m.config.probe
        inputs = tuple(getattr(snap, "digital_inputs", ()) or ())
        if cfg.drive is None or cfg.drive >= len(inputs):
            return ""
        reads = inputs[cfg.drive] >> cfg.bit & 1
        return "touching" if reads == cfg.touching_level else "free"

    def emit_bus(self, status: BusStatus) -> None:
        old = self.bus_status
        self.bus_status = status
        if (old.state, old.drive_states, old.connected, old.late_cycles, old.probe) != (
            status.state,
            status.drive_states,
            status.connected,
            status.late_cycles,
            status.probe,
        ) or abs(old.buffer_level - status.buffer_level) > 50:
            self.m.busStateChanged.emit(status)

    def emit_all(self) -> None:
        self.m.homedChanged.emit(tuple(self.m.pos.homed))
        self.m.offsetsChanged.emit(dict(self.m.pos.offsets), self.m.pos.active_offset)
        self.m.overridesChanged.emit(self.m.run.feed_pct, self.m.run.rapid_pct)
        self.m.modesChanged.emit(self.m.run.single_block, self.m.run.optional_stop, self.m.run.block_delete)
        self.m.spindleChanged.emit(self.m.spindle_ctl.spindle)
        self.m.alarmsChanged.emit(tuple(self.m.alarm_log.alarms))
        self.last_emit_pos = ()
        mpos = tuple(float(x) for x in self.m.states.machine_pos())
        self.m.positionChanged.emit(mpos, tuple(float(x) for x in self.m.states.work_pos()))
