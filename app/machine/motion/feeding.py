"""The set-points in the worker's queue: pushed ``lead_s`` ahead of the drives in chunks, and
replaced from a few cycles ahead of them when the motion changes (a hold, a stop, an override).

Serial numbers: every set-point pushed gets the next serial; the worker's ``samples_consumed``
says which one the drives reached. Splicing: the executor's state is kept per pushed chunk
(``Job.chunks``). A change is applied at serial S = the worker's live consumed serial + a
margin of a few cycles (``SPLICE_MARGIN_S``, raised to the time a splice took when that was
longer): the executor is rewound to the chunk holding S, regenerates the part of it before S
(bit-identical: same state, same chunk start), takes the change, and the new set-points
replace the worker's queue from S (``CyclicWorker.replace``, applied between two cycles). When
the loop took S meanwhile (refused, queue unchanged) the executor is put back and the splice
is retried from a later serial; after ``SPLICE_ATTEMPTS`` it falls back to applying the change
after the queued set-points. So a hold starts decelerating within ~5-10 ms of the request
instead of after the lead.

``SetpointQueue`` belongs to the streamer (``app.machine.motion.streamer``), which calls it
under its lock only.
"""

from __future__ import annotations

import collections
import time
from collections.abc import Callable

import numpy as np

from app.machine.errors import MachineError
from app.machine.infra.drives import DriveLink
from app.machine.motion.jobs import ChunkRecord, Job
from app.machine.motion.timescale import ScaledChunk, TimeScaledExecutor
from app.machine.ports import PositionsView, Settings
from ethercat.worker import ReplaceResult

__all__ = ["CHUNK", "SPLICE_ATTEMPTS", "SPLICE_MARGIN_S", "SetpointQueue", "SpliceInfo"]

SPLICE_MARGIN_S = 0.005  # splice this far ahead of the drives (the worker takes ~1 set-point/ms)
SPLICE_ATTEMPTS = 6
CHUNK = 20  # executor samples per pushed chunk


class SpliceInfo:
    """The last splice (diagnostics, tests): serial spliced at, live consumed serial when it
    was asked for, attempts, time it took (s), and whether it fell back to the queue end."""

    __slots__ = ("serial", "consumed", "attempts", "elapsed_s", "fallback")

    def __init__(self, serial: int, consumed: int, attempts: int, elapsed_s: float, fallback: bool) -> None:
        self.serial, self.consumed, self.attempts = serial, consumed, attempts
        self.elapsed_s, self.fallback = elapsed_s, fallback

    def __repr__(self) -> str:
        return (
            f"SpliceInfo(serial={self.serial}, consumed={self.consumed}, attempts={self.attempts}, "
            f"elapsed_s={self.elapsed_s:.4f}, fallback={self.fallback})"
        )


def _set_hold(ex: TimeScaledExecutor) -> None:
    ex.hold = True
    ex.hold_waits_for_tap = False


def _set_feed_hold(ex: TimeScaledExecutor) -> None:
    ex.hold = True
    ex.hold_waits_for_tap = True


_HOLDS = (_set_hold, _set_feed_hold)


class SetpointQueue:
    """What was pushed to the worker for the job, and how to change it in place."""

    def __init__(self, settings: Settings, drives: DriveLink, positions: PositionsView) -> None:
        self._settings = settings
        self._drives = drives
        self._positions = positions
        self.pushed_total = 0
        self.last_splice: SpliceInfo | None = None
        # the last splices (diagnostics, tests: how far ahead of the drives each one took effect)
        self.recent_splices: collections.deque[SpliceInfo] = collections.deque(maxlen=32)
        self._splice_est_s: dict[bool, float] = {}
        self._splice_critical_s = 0.0

    def restart_at(self, serial: int) -> int:
        """The next set-point pushed gets ``serial`` (a new job, a new worker)."""
        self.pushed_total = serial
        return serial

    def feed(self, job: Job, lead: int, max_new: int | None = None) -> None:
        """Keep the worker's queue ``lead`` set-points ahead (at most ``max_new`` now)."""
        self._prune_chunks(job)
        want = lead - self._drives.buffer_level()
        if max_new is not None:
            want = min(want, max_new)
        ex = job.executor
        while want > 0 and job.pause is None:
            if ex.held:
                break  # held still on the path: the worker keeps the last set-point
            state = ex.save_state()
            ch = ex.generate(min(want, CHUNK))
            if ch is None:
                break
            raw = self._chunk_raw(ch)
            n = self._drives.push(raw)
            if n < 0:
                return              # disconnected meanwhile
            if n < len(raw):  # pragma: no cover - lead is far below the ring capacity
                raise MachineError("worker buffer full")
            self._record_chunk(job, ch, state, len(raw))
            want -= n

    def _chunk_raw(self, ch: ScaledChunk) -> np.ndarray:
        """Set-points of a chunk in drive units; at a pause point the plan stands still, so the
        point is repeated: the worker sees the motion end before its buffer runs empty."""
        raw = ch.q + self._positions.home_offset
        if ch.pause is not None:
            raw = np.vstack([raw, np.repeat(raw[-1:], 2, axis=0)])
        return raw

    def _record_chunk(self, job: Job, ch: ScaledChunk, state: tuple[object, ...], pushed: int) -> None:
        """Bookkeeping of a chunk the worker queued at serial ``pushed_total`` (under the lock)."""
        serial = self.pushed_total
        job.record(ch, serial)
        job.samples += len(ch.q)
        job.chunks.append(ChunkRecord(serial, len(ch.q), pushed, state, ch.pause is not None))
        self.pushed_total = serial + pushed
        if ch.pause is not None:
            job.pause_serial = self.pushed_total  # before .pause: the poll reads both
            job.pause = ch.pause

    def _prune_chunks(self, job: Job) -> None:
        consumed = self._drives.samples_consumed()
        if consumed is None:
            return
        chunks = job.chunks
        while len(chunks) > 1 and chunks[0].serial + chunks[0].pushed <= consumed:
            chunks.popleft()

    def change(self, job: Job, change: Callable[[TimeScaledExecutor], None], lead: int) -> None:
        """Apply ``change`` (hold, override) to the job's executor from a serial a few cycles
        ahead of the drives, replacing the worker's queue from there (module docstring); without
        a queue the change simply applies to the next set-points generated."""
        ex = job.executor
        consumed = self._drives.samples_consumed() if not job.aborted else None
        if consumed is None or consumed >= self.pushed_total:
            change(ex)
            return
        current = ex.save_state()
        ts = self._settings.config.machine.planner.ts_s
        hold = change in _HOLDS
        margin_s = SPLICE_MARGIN_S
        if self._drives.realtime:
            # real time: the loop runs on while we compute (a hold plans the time-optimal
            # stop, ~6 ms here); the margin covers the last such splice's critical part
            est = self._splice_est_s.get(hold, 0.008 if hold else 0.003)
            margin_s = max(margin_s, 1.2 * est + 0.001)
        t_start = time.perf_counter()
        first_consumed = consumed
        for attempt in range(1, SPLICE_ATTEMPTS + 1):
            consumed = self._drives.samples_consumed() or 0
            serial = consumed + max(int(round(margin_s / ts)), 1)
            done = self._splice_at(job, serial, change, lead)
            dt = self._splice_critical_s
            if done is ReplaceResult.BEYOND_END:  # the worker dropped its queue (quick stop, flush)
                ex.restore_state(current)
                change(ex)
                done = None
            if done is None or done is ReplaceResult.DONE:
                if done is ReplaceResult.DONE:
                    self._splice_est_s = {**self._splice_est_s, hold: dt}
                took = time.perf_counter() - t_start
                self.last_splice = SpliceInfo(serial, first_consumed, attempt, took, done is None)
                self.recent_splices.append(self.last_splice)
                return
            ex.restore_state(current)  # refused: the queue is unchanged, so is the executor
            margin_s = max(2.0 * margin_s, 1.5 * dt + 0.002)
        change(ex)  # the loop kept outrunning us: apply after the queued set-points
        took = time.perf_counter() - t_start
        self.last_splice = SpliceInfo(-1, first_consumed, SPLICE_ATTEMPTS, took, True)
        self.recent_splices.append(self.last_splice)

    def hold(self, job: Job, wait_for_tap: bool, lead: int) -> None:
        """The job's executor to hold (sigma -> 0 / the time-optimal path stop); the operator's
        feed hold, ``wait_for_tap``, once a tap in the hole is out."""
        ex = job.executor
        if wait_for_tap and not ex.hold:
            self.change(job, _set_feed_hold, lead)
        elif not wait_for_tap and not ex.holding:
            self.change(job, _set_hold, lead)

    def _splice_at(self, job: Job, serial: int, change: Callable[[TimeScaledExecutor], None],
                   lead: int) -> ReplaceResult | None:
        """One splice attempt at ``serial``: DONE, None when applied without a splice (nothing
        queued there to replace), or the worker's refusal (TOO_LATE, BEYOND_END; the executor
        state is then to be restored by the caller)."""
        t0 = time.perf_counter()
        ex = job.executor
        rec = next((r for r in reversed(job.chunks) if r.serial <= serial), None)
        if serial >= self.pushed_total or rec is None or serial >= rec.serial + rec.pushed:
            change(ex)
            return None
        p = serial - rec.serial
        if rec.pause and p >= rec.samples:
            change(ex)  # in the standstill after a pause point: nothing to decelerate
            return None
        ex.restore_state(rec.state)
        prefix = ex.generate(p) if p > 0 else None
        if p > 0 and (prefix is None or len(prefix.q) != p):  # pragma: no cover - deterministic
            return ReplaceResult.TOO_LATE
        change(ex)
        new: list[tuple[tuple[object, ...], ScaledChunk, np.ndarray]] = []
        # only the first set-points go in the replace (the sooner it reaches the loop, the
        # smaller the margin a splice needs); the feeder tops the queue up right after it
        state = ex.save_state()
        ch = ex.generate(CHUNK)
        if ch is not None:
            new.append((state, ch, self._chunk_raw(ch)))
        q = np.vstack([r for _, _, r in new]) if new else np.zeros((0, len(self._positions.home_offset)))
        result, n = self._drives.replace(serial, q)
        self._splice_critical_s = time.perf_counter() - t0
        if result is not ReplaceResult.DONE:
            return result
        if n < len(q):  # pragma: no cover - lead is far below the ring capacity
            raise MachineError("worker buffer full")
        job.rewind(rec.serial)
        self.pushed_total = rec.serial
        if prefix is not None:
            self._record_chunk(job, prefix, rec.state, p)
        for state, ch, raw in new:
            self._record_chunk(job, ch, state, len(raw))
        # a plain push (no race with the loop) of 0.1 s more now; the feeder thread adds the rest
        self.feed(job, lead, max_new=int(0.1 / self._settings.config.machine.planner.ts_s))
        return ReplaceResult.DONE

