"""M66 on the machine: at rest (pause point INPUT) the input is read at once (L0) or waited for
(rise, fall, high, low) at the poll's rate, for at most Q seconds; #5399 holds the value, -1
after the timeout, as in LinuxCNC. What follows is read again with the value
(``app.machine.devices.reads``)."""

from __future__ import annotations

from dataclasses import dataclass

from app.machine.devices.reads import ReadAgain
from app.machine.motion.jobs import Job
from app.machine.motion.pauses import PauseHandlers
from app.machine.motion.streamer import Streamer
from app.machine.motion.timescale import PauseKind, PausePoint
from app.machine.ports import CoordinatesView, Settings
from ethercat.worker import WorkerSnapshot
from planner.core.machine import io_place
from planner.core.program import EventKind, InputRequest, TableRef, WaitMode

__all__ = ["InputWaiter"]


@dataclass
class _Wait:
    index: int
    request: InputRequest
    drive: int
    bit: int
    since_s: float            # worker time the wait began
    seen: int                 # the level read last (RISE / FALL need the other one first)


class InputWaiter:
    """M66: the wait under way, polled at rest (``controller.waiter``)."""

    def __init__(self, settings: Settings, coordinates: CoordinatesView, motion: Streamer, reads: ReadAgain,
                 pauses: PauseHandlers) -> None:
        self._settings = settings
        self._coordinates = coordinates
        self._motion = motion
        self._reads = reads
        self.wait: _Wait | None = None
        motion.on_job_end(self.cancel)
        pauses.on(PauseKind.INPUT, self._at_input)

    def fail(self, cause: str) -> None:
        self._reads.stop(cause, "input")

    def cancel(self) -> None:
        self.wait = None

    def _at_input(self, job: Job, point: PausePoint, snap: WorkerSnapshot) -> bool:
        self.at_pause(job, point.payload_as(TableRef).index, snap)
        return False

    def at_pause(self, job: Job, index: int, snap: WorkerSnapshot) -> None:
        """At the INPUT pause point (called by every poll while there)."""
        w = self.wait
        if w is None or w.index != index:
            inputs = job.plan.program.inputs
            if not 0 <= index < len(inputs):
                self.fail(f"input {index} is not in the program")
                return
            req = inputs[index]
            bits = self._coordinates.machine().input_bits.get(req.number)
            if bits is None:
                self.fail(f"M66 (line {req.line}): input P{req.number} is not on this machine ([[inputs]])")
                return
            level = self._level(snap, bits[0], bits[1])
            if level is None:
                if bits[0] >= 0:
                    self.fail(f"M66 (line {req.line}): the drive of input P{req.number} does not send its "
                              "digital inputs (0x60FD)")
                else:
                    self.fail(f"M66 (line {req.line}): the terminal of input P{req.number} is not on the bus")
                return
            w = self.wait = _Wait(index, req, bits[0], bits[1], float(snap.time_s), level)
            if req.mode is not WaitMode.IMMEDIATE:
                name = self._coordinates.machine().input_bits[req.number][2]
                how = {WaitMode.RISE: "to rise", WaitMode.FALL: "to fall", WaitMode.HIGH: "to read 1",
                       WaitMode.LOW: "to read 0"}[req.mode]
                self._motion.show_message(f"M66 (line {req.line}): waiting for input P{req.number}"
                                           + (f" ({name})" if name else "") + f" {how}, "
                                           f"{req.timeout_s:g} s at most")
        level = self._level(snap, w.drive, w.bit)
        value = self._value(w, level, float(snap.time_s))
        if value is None:
            return
        self.wait = None
        self._motion.count_wait(job, float(snap.time_s) - w.since_s)   # the run's time, as a dwell's
        req = w.request
        if value < 0:
            self._motion.show_message(f"M66 (line {req.line}): input P{req.number} timed out after "
                                       f"{req.timeout_s:g} s: #5399 = -1")
        results: list[float | None] = list(job.wait_results)
        results += [None] * (index + 1 - len(results))
        results[index] = value
        self._reads.continue_after(job, EventKind.INPUT, index, f"M66 (line {req.line})", job.probe_results,
                                   tuple(results), "input")

    def _level(self, snap: WorkerSnapshot, drive: int, bit: int) -> int | None:
        """An ``[[inputs]]`` bit now: of a drive's 0x60FD, or a terminal's channel (``io_place``);
        None when it is not in the process data."""
        kind, where = io_place(drive)
        if kind == "slave":
            where = self._settings.config.wiring.terminal_index(where)
            inputs = tuple(snap.terminal_inputs)
        else:
            inputs = tuple(getattr(snap, "digital_inputs", ()) or ())
        return int(inputs[where]) >> bit & 1 if 0 <= where < len(inputs) else None

    @staticmethod
    def _value(w: _Wait, level: int | None, now_s: float) -> float | None:
        """The value for #5399 once the wait is over, else None."""
        mode = w.request.mode
        if level is None:
            return None
        if mode is WaitMode.IMMEDIATE:
            return float(level)
        done = ((mode is WaitMode.HIGH and level == 1) or (mode is WaitMode.LOW and level == 0)
                or (mode is WaitMode.RISE and w.seen == 0 and level == 1)
                or (mode is WaitMode.FALL and w.seen == 1 and level == 0))
        w.seen = level
        if done:
            return float(level)
        if now_s - w.since_s >= w.request.timeout_s:
            return -1.0
        return None
