"""Reading the worker (<= 30 Hz): positions, alarms, the trace, the job as the drives run it,
what the panel shows (positions, path speed, tracking samples, the bus)."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from app.machine.infra.drives import DriveLink
from app.machine.infra.events import MachineEvents, PanelChannels
from app.machine.model import BusStatus
from app.machine.motion.coordinates import Coordinates
from app.machine.motion.positions import Positions
from app.machine.motion.streamer import Streamer
from app.machine.ports import Settings
from app.machine.state.alarms import AlarmLog
from ethercat.worker import WorkerSnapshot

__all__ = ["StatusPoller"]


class StatusPoller:
    """The poll and what it tells the panel (``controller.poller``)."""

    def __init__(self, settings: Settings, drives: DriveLink, positions: Positions, coordinates: Coordinates,
                 alarms: AlarmLog, motion: Streamer, out: PanelChannels, events: MachineEvents) -> None:
        self._settings = settings
        self._drives = drives
        self._positions = positions
        self._coordinates = coordinates
        self._alarms = alarms
        self._motion = motion
        self._out = out
        self.bus_status = BusStatus(kind=settings.config.bus.kind)
        self.speed = 0.0                      # the commanded path speed, mm/s
        self._last_emit_pos: tuple[float, ...] = ()
        self._last_ref_time = 0.0
        self._last_ref_pos: np.ndarray | None = None
        self._hooks: list[Callable[[WorkerSnapshot], None]] = []
        events.coordinates_changed.connect(self.emit_positions)
        events.announce.connect(self.emit_positions)
        events.poll_now.connect(self.poll)

    def on_poll(self, hook: Callable[[WorkerSnapshot], None]) -> None:
        """``hook(snapshot)`` at every poll, before the job is polled (homing, the simulated
        probe surface)."""
        self._hooks.append(hook)

    def poll(self) -> None:
        snap = self._drives.snapshot()
        if snap is None:
            return
        self._positions.update(snap.actual_position, snap.reference_position)
        self._alarms.handle_worker_alarms(snap)
        self._alarms.handle_worker_events(self._drives.events())
        trace = self._drives.drain_trace()
        if trace is not None:
            self._motion.trace_drained(trace)
        for hook in self._hooks:
            hook(snap)
        self._motion.poll(snap)
        self._emit_positions(snap)
        self._emit_bus_from(snap)

    def _work(self) -> tuple[float, ...]:
        return tuple(float(x) for x in self._coordinates.work_pos())

    def emit_positions(self) -> None:
        """Tell the panel the positions now (the coordinates changed while standing)."""
        mpos = tuple(float(x) for x in self._positions.machine_pos())
        self._last_emit_pos = ()       # the next poll tells them again
        self._out.positionChanged.emit(mpos, self._work())

    def _emit_positions(self, snap: WorkerSnapshot) -> None:
        mpos = tuple(float(x) for x in self._positions.machine_pos())
        if mpos != self._last_emit_pos:
            self._last_emit_pos = mpos
            self._out.positionChanged.emit(mpos, self._work())
        ref_m = self._positions.reference_pos()
        self._out.trackingSample.emit(float(snap.time_s), tuple(float(x) for x in ref_m), mpos)
        lin = np.array([not r for r in self._settings.config.machine.rotary])
        if self._last_ref_pos is not None and snap.time_s > self._last_ref_time:
            d = (ref_m - self._last_ref_pos)[lin] if lin.any() else ref_m - self._last_ref_pos
            speed = float(np.linalg.norm(d)) / (snap.time_s - self._last_ref_time)
            if abs(speed - self.speed) > 1e-6:
                self.speed = speed
                self._out.speedChanged.emit(speed)
        self._last_ref_pos = ref_m.copy()
        self._last_ref_time = float(snap.time_s)

    def _emit_bus_from(self, snap: WorkerSnapshot) -> None:
        tm = snap.timing
        status = BusStatus(
            kind=self._settings.config.bus.kind,
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
            spindle_state=snap.spindle_drive_state.name if snap.spindle_drive_state is not None else "",
            gantry_skew=snap.gantry_skew if len(snap.gantry_skew) > len(self._settings.config.axes) else (),
            compensation=snap.compensation if self._settings.config.compensation else (),
        )
        self.emit_bus(status)

    def _probe_text(self, snap: WorkerSnapshot) -> str:
        cfg = self._settings.config.probe
        inputs = tuple(snap.digital_inputs or ())
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
        ) or abs(old.buffer_level - status.buffer_level) > 50 or _moved(old.gantry_skew, status.gantry_skew) \
                or _moved(old.compensation, status.compensation):
            self._out.busStateChanged.emit(status)


def _moved(old: tuple[float, ...], new: tuple[float, ...]) -> bool:
    """A gantry's skew or a leadscrew correction changed by half the last digit Diagnostics
    shows (0.05 µm) or more, or appeared, or went."""
    return len(old) != len(new) or any(abs(a - b) >= 5e-5 for a, b in zip(old, new))
