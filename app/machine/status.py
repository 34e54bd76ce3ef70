"""Reading the worker (<= 30 Hz): positions, path speed, tracking samples, bus status; the
signals that carry them. Part of ``MachineController`` (mixed in).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from app.machine.model import BusStatus

__all__ = ["StatusMixin"]


class StatusMixin:
    """Polling the worker and emitting what the panel shows.

    Mixed into ``MachineController``, which holds the state.
    """

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
        if self._feeder_error:
            text, self._feeder_error = self._feeder_error, ""
            self._fault(text, "controller", "feeder")

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
