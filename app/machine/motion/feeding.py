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

The braking tail: behind the last set-point pushed, the queue always holds a stop along the
path from there (the executor's hold, made on a copy of its state: the time-optimal path stop
or sigma -> 0, within every limit). Each top-up replaces the tail with new set-points and a
new tail. The queue is topped up in steps of ``REFILL_S`` (each step pays for one tail).
Should the feeder fall behind (the panel's process stalled longer than the lead), the worker
plays the tail and the axes come to rest on the path instead of stopping dead; the queue then
takes the tail as executed (``take_tail``): the executor stands held where it ended, and the
streamer raises the alarm.

``SetpointQueue`` belongs to the streamer (``app.machine.motion.streamer``), which calls it
under its lock only.
"""

from __future__ import annotations

import collections
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from app.machine.errors import MachineError
from app.machine.infra.drives import DriveLink
from app.machine.motion.jobs import ChunkRecord, Job
from app.machine.motion.timescale import ScaledChunk, TimeScaledExecutor
from app.machine.ports import PositionsView, Settings
from ethercat.worker import ReplaceResult

__all__ = ["CHUNK", "REFILL_S", "SPLICE_ATTEMPTS", "SPLICE_MARGIN_S", "SetpointQueue", "SpliceInfo"]

SPLICE_MARGIN_S = 0.005  # splice this far ahead of the drives (the worker takes ~1 set-point/ms)
SPLICE_ATTEMPTS = 6
CHUNK = 20  # executor samples per pushed chunk
TAIL_CHUNK = 100  # executor samples per chunk of the braking tail
#: the queue is topped up once this much of the lead was taken (at most a fifth of the lead)
REFILL_S = 0.1

_Made = tuple[tuple, ScaledChunk, np.ndarray]   # (executor state before, chunk, set-points)


@dataclass(frozen=True, slots=True)
class _Tail:
    """The braking tail queued behind the last set-point pushed (serial ``serial`` on)."""

    job: Job           # whose executor made it (a successor's is another: its tail is its own)
    serial: int
    made: tuple[_Made, ...]
    end_state: tuple   # the executor held where the tail ends


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
        self._tail: _Tail | None = None
        # the serial the worker ran into the braking tail at, until ``ran_into_tail`` tells it
        self._ran_dry: int | None = None

    def restart_at(self, serial: int) -> int:
        """The next set-point pushed gets ``serial`` (a new job, a new worker)."""
        self.pushed_total = serial
        self._tail = None
        return serial

    def feed(self, job: Job, lead: int, max_new: int | None = None) -> None:
        """Keep the worker's queue ``lead`` set-points ahead (at most ``max_new`` now), its
        braking tail behind them (module docstring)."""
        self._prune_chunks(job)
        consumed = self._drives.samples_consumed()
        if consumed is None or self.take_tail(job, consumed):
            return
        want = lead - max(self.pushed_total - consumed, 0)
        if max_new is not None:
            want = min(want, max_new)
        elif self._tail is not None and want < min(self._refill(), lead // 5 + 1):
            return                  # the queued set-points and their tail still reach far enough
        ex = job.executor
        before = ex.save_state()
        made: list[_Made] = []
        while want > 0 and job.pause is None:
            if ex.held:
                break  # held still on the path: the worker keeps the last set-point
            state = ex.save_state()
            ch = ex.generate(min(want, CHUNK))
            if ch is None:
                break
            raw = self._chunk_raw(ch)
            made.append((state, ch, raw))
            want -= len(raw)
            if ch.pause is not None:
                break
        if not made:
            return
        tail = self._braking_tail(ex)
        q = np.vstack([m[2] for m in made] + [m[2] for m in tail[0]])
        if self._tail is None:
            n = self._drives.push(q)
            if n < 0:
                ex.restore_state(before)
                return              # disconnected meanwhile
        else:
            result, n = self._drives.replace(self.pushed_total, q)
            if result is not ReplaceResult.DONE:
                ex.restore_state(before)
                if result is ReplaceResult.TOO_LATE:
                    self.take_tail(job, self._drives.samples_consumed() or consumed)
                else:
                    self._tail = None  # the worker dropped its queue (quick stop, flush)
                return
        if n < len(q):  # pragma: no cover - the ring holds the lead and the longest tail
            raise MachineError("worker buffer full")
        for state, ch, raw in made:
            self._record_chunk(job, ch, state, len(raw))
        self._tail = _Tail(job, self.pushed_total, tail[0], tail[1]) if tail[0] else None

    def _refill(self) -> int:
        return max(int(REFILL_S / self._settings.config.machine.planner.ts_s), CHUNK)

    def _braking_tail(self, ex: TimeScaledExecutor) -> tuple[tuple[_Made, ...], tuple]:
        """The stop along the path from where the executor is (made on its state, which is put
        back): its chunks and the executor's state at its end; none when it stands still."""
        if ex.finished or ex.paused is not None or ex.held:
            return (), ()
        cap = int(1.1 * ex.time_to_ramp_s / self._settings.config.machine.planner.ts_s) + CHUNK
        start = ex.save_state()
        _set_hold(ex)
        made: list[_Made] = []
        total = 0
        while total < cap and not ex.held:
            state = ex.save_state()
            ch = ex.generate(TAIL_CHUNK)
            if ch is None:
                break
            raw = self._chunk_raw(ch)
            made.append((state, ch, raw))
            total += len(raw)
            if ch.pause is not None:
                break
        end = ex.save_state()
        ex.restore_state(start)
        return tuple(made), end

    def ran_into_tail(self, job: Job, consumed: int) -> int | None:
        """``take_tail``, and the serial the worker ran into the tail at (told once; None when
        it did not)."""
        self.take_tail(job, consumed)
        ran, self._ran_dry = self._ran_dry, None
        return ran

    def take_tail(self, job: Job, consumed: int) -> bool:
        """When the worker has run into the braking tail (set-points taken beyond the last one
        pushed), take the tail as executed: its chunks recorded, the executor held where it
        ends, the serial kept for ``ran_into_tail``. Whether it had."""
        tail = self._tail
        if tail is not None and tail.job is not job:
            # another job's (a successor goes on only from rest, where no tail is queued)
            self._tail = tail = None
        if tail is None or consumed <= tail.serial:
            return False
        self._tail = None
        self._ran_dry = tail.serial
        for state, ch, raw in tail.made:
            self._record_chunk(job, ch, state, len(raw))
        job.executor.restore_state(tail.end_state)
        return True

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
        job.record(ch, serial, pushed)
        job.samples += len(ch.q)
        job.chunks.append(ChunkRecord(serial, len(ch.q), pushed, state, ch.pause is not None))
        self.pushed_total = serial + pushed
        if ch.pause is not None:
            job.pause_serial = self.pushed_total  # before .pause: the poll reads both
            job.pause = ch.pause

    def release(self, job: Job) -> None:
        """The motion goes on from the pause point it stands at (under the streamer's lock)."""
        job.pause = None
        job.executor.release_pause()

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
        if consumed is not None:
            self.take_tail(job, consumed)
        if consumed is None or consumed >= self.pushed_total:
            change(ex)
            if self._tail is not None:
                self.feed(job, lead, max_new=self._refill())
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
                self._tail = None
                ex.restore_state(current)
                change(ex)
                done = None
            if done is None or done is ReplaceResult.DONE:
                if done is ReplaceResult.DONE:
                    self._splice_est_s = {**self._splice_est_s, hold: dt}
                elif self._tail is not None:
                    # changed after the last set-point queued: its tail goes with the change
                    self.feed(job, lead, max_new=self._refill())
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
        dropped, pause = job.rewind(rec.serial)
        job.samples -= dropped
        if pause:
            job.pause, job.pause_serial = None, 0
        self.pushed_total = rec.serial
        self._tail = None           # the replace dropped it with the rest of the queue
        if prefix is not None:
            self._record_chunk(job, prefix, rec.state, p)
        for state, ch, raw in new:
            self._record_chunk(job, ch, state, len(raw))
        # a plain push (no race with the loop) of 0.1 s more now; the feeder thread adds the rest
        self.feed(job, lead, max_new=int(0.1 / self._settings.config.machine.planner.ts_s))
        return ReplaceResult.DONE

