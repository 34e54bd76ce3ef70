"""Running a motion: jobs planned with the override budget, set-points streamed to the worker
``lead_s`` ahead (the feeder), pause points, program end, run summaries and the saved trace.

Serial numbers: every set-point pushed gets the next serial; the worker's ``samples_consumed``
says which one the drives reached (line, progress, resume point). Part of
``MachineController``.

Splicing (feed hold, stop, stop-class alarms, jog release, overrides): the executor's state is
kept per pushed chunk (``Job.chunks``). A change is applied at serial S = the worker's live
consumed serial + a margin of a few cycles (``SPLICE_MARGIN_S``, raised to the time a splice
took when that was longer): the executor is rewound to the chunk holding S, regenerates the
part of it before S (bit-identical: same state, same chunk start), takes the change, and the
new set-points replace the worker's queue from S (``CyclicWorker.replace``, applied between
two cycles). When the loop took S meanwhile (refused, queue unchanged) the executor is put
back and the splice is retried from a later serial; after ``SPLICE_ATTEMPTS`` it falls back
to applying the change after the queued set-points (the behaviour without splicing). So a
hold starts decelerating within ~5-10 ms of the request instead of after the lead.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from app.machine.errors import MachineError
from app.machine.jobs import ChunkRecord, Job, merge_max
from app.machine.model import (
    Activity,
    HoldKind,
    MachineState,
    Prompt,
    RunSummary,
    Severity,
    SpindleState,
    TrackingReport,
)
from app.machine.spindle import spin_up_waits
from app.machine.timescale import (
    PauseFeed,
    PausePoint,
    ScaledChunk,
    TimeScaledExecutor,
    pause_points,
    reduced_machine,
)
from ethercat.worker import ReplaceResult
from planner.files import write_output
from planner.machine import MachineSpec
from planner.movestore import MoveStore
from planner.plan import Plan, plan_program
from planner.program import EventKind, Program
from planner.window import PlanWindow

if TYPE_CHECKING:
    from app.machine.controller import MachineController

__all__ = ["SPLICE_ATTEMPTS", "SPLICE_MARGIN_S", "WINDOWED_RUN_MOVES", "RunPlanner", "Streamer", "SpliceInfo",
           "single_block_program"]

SPLICE_MARGIN_S = 0.005  # splice this far ahead of the drives (the worker takes ~1 set-point/ms)
SPLICE_ATTEMPTS = 6
CHUNK = 20  # executor samples per pushed chunk
#: programs of more moves run from a plan made as they run (``planner.window``): a whole plan
#: holds about 150 bytes a move (1.5 GB at 10,000,000 moves), a window a few thousand moves
WINDOWED_RUN_MOVES = 200_000


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


def single_block_program(program: Program) -> Program:
    """The program with an exact stop (G61) at every block end: single block's plan."""
    moves = program.moves
    if isinstance(moves, MoveStore):        # millions of moves: the columns, not Move objects
        return replace(program, moves=moves.with_exact_stops())
    return replace(program, moves=tuple(replace(m, exact_stop=True) for m in moves))


@dataclass(frozen=True, eq=False)
class RunPlanner:
    """Plans for runs, bound to the machine and the override budget of the moment it was made
    (a change of the configuration meanwhile cannot reach into a plan under way in a worker
    thread): called as ``plan_program`` is (a whole ``Plan``), or ``window`` (planned as the
    run reaches it) for programs of more than ``WINDOWED_RUN_MOVES`` moves."""

    machine: MachineSpec   # the reduced limits the plan is made with

    def __call__(self, program: Program, progress: Callable[[int, int], None] | None = None) -> Plan:
        return plan_program(program, self.machine, progress=progress)

    def window(self, program: Program, estimate_s: float = math.nan) -> PlanWindow:
        return PlanWindow(program, self.machine, estimate_s=estimate_s)

    def for_run(self, program: Program, estimate_s: float = math.nan) -> Plan | PlanWindow:
        """What a run of ``program`` plays: a window for a long program, else the whole plan."""
        if len(program.moves) > WINDOWED_RUN_MOVES:
            return self.window(program, estimate_s)
        return self(program)


def _set_hold(ex: TimeScaledExecutor) -> None:
    ex.hold = True
    ex.hold_waits_for_tap = False


def _set_feed_hold(ex: TimeScaledExecutor) -> None:
    ex.hold = True
    ex.hold_waits_for_tap = True


_HOLDS = (_set_hold, _set_feed_hold)


class Streamer:
    """Jobs, set-point streaming, pause points, end of a run.

    A part of ``MachineController`` (``controller.stream``): it owns the state set up in
    ``__init__`` and reaches the other parts through the facade ``m``.
    """

    def __init__(self, m: MachineController) -> None:
        self.m = m
        self.job: Job | None = None
        self.pushed_total = 0
        self.line = 0
        self.progress = (0.0, 0.0)
        self.feed_note = ""          # feedOverrideNote as last emitted
        self.speed = 0.0
        self.tracking = TrackingReport(axes=m.config.axes)
        self.last_summary: RunSummary | None = None
        self._splice_est_s: dict[bool, float] = {}
        self._splice_critical_s = 0.0
        self.last_splice: SpliceInfo | None = None

    @property
    def _lead_samples(self) -> int:
        ts = self.m.config.machine.planner.ts_s
        return max(int(self.m.config.controller.lead_s / ts), 10)

    def plan(self, program: Program, progress: Callable[[int, int], None] | None = None) -> Plan:
        return self.planner()(program, progress)

    def planner(self) -> RunPlanner:
        """Plans bound to the machine and budget of now (for a worker thread)."""
        return RunPlanner(reduced_machine(self.m.conn.machine, self.m.conn.budget))

    def make_job(
        self,
        kind: Activity,
        program: Program,
        name: str,
        *,
        overrides: bool = True,
        single_block: bool = False,
        plan: Plan | PlanWindow | None = None,
        estimate_s: float = math.nan,
        stops: tuple[PausePoint, ...] | None = None,
    ) -> Job:
        """A job for ``program``. ``plan``: a ready plan of exactly this program (already the
        single-block variant when ``single_block``) with the current machine and budget, e.g.
        the one made at load time (``ProgramInfo.plan``): then nothing is planned here. A long
        program is planned as it runs (``RunPlanner.for_run``); ``estimate_s``: its planned
        time as far as known (the time left shows it), ``stops``: its pause points as a check
        pass found them (the spin-ups the time left counts)."""
        if plan is None:
            if single_block:
                program = single_block_program(program)
            plan = self.planner().for_run(program, estimate_s)
        else:
            program = plan.program
        overrides_now = (self.m.run.feed_pct / 100.0 if overrides else 1.0,
                         self.m.run.rapid_pct / 100.0 if overrides else 1.0)
        if isinstance(plan, PlanWindow):
            # its pause points come with its segments; the spin-ups from the check pass's
            pauses = list(stops or ())
            ex = TimeScaledExecutor(plan, self.m.conn.machine, self.m.conn.budget, None, *overrides_now,
                                    pause_feed=PauseFeed(program, single_block, True))
        else:
            pauses = pause_points(plan, single_block, True)
            ex = TimeScaledExecutor(plan, self.m.conn.machine, self.m.conn.budget, pauses, *overrides_now)
        spin_ups = spin_up_waits(pauses, self.m.spindle_ctl.spindle,
                                 self.m.config.controller.spindle_spinup_s)
        job = Job(
            kind=kind,
            name=name,
            program=program,
            plan=plan,
            executor=ex,
            overrides=overrides,
            estimated_s=ex.planned_end_s + sum(wait for _tau, wait in spin_ups),
            machine=self.m.conn.machine,
        )
        job.single_block = single_block
        job.spin_ups = spin_ups
        info = self.m.loader.program_info
        if kind is Activity.PROGRAM and info is not None:
            job.reread = info.reread        # G38.x, M66: the program is read again with each result
        return job

    def follow(self, job: Job, rest: Program, origin: tuple[Program, int, float], held: bool = False) -> Job:
        """At rest on the path: run ``rest`` (what is left of the program from here, planned
        anew) in place of ``job``, as the same run (time, progress, trace, limits); ``held``:
        it waits for cycle start (the operator's feed hold). Raises PlannerError when the rest
        cannot be planned (``job`` is then unchanged)."""
        info = self.m.loader.program_info
        # where the run stands on the whole program's timeline: a long rest is planned as it
        # runs, its end estimated from there
        at_s = job.tau_offset_s + job.executor.tau
        full_t = info.cycle_time_s if info is not None and job.kind is Activity.PROGRAM else math.nan
        new = self.make_job(job.kind, rest, job.name,
                            single_block=self.m.run.single_block and job.kind is Activity.PROGRAM,
                            estimate_s=max(job.executor.planned_end_s + job.tau_offset_s - at_s, 0.0))
        if math.isnan(full_t):
            full_t = new.estimated_s
        new.tau_offset_s = new.time_offset_s = max(full_t - new.executor.planned_end_s, 0.0)
        new.origin = origin
        new.start_time_s = job.start_time_s
        new.trace = job.trace
        new.samples, new.dwell_total_s = job.samples, job.dwell_total_s
        new.carried_limits = merge_max(job.carried_limits, job.meter.final())
        new.estimated_s = job.estimated_s
        new.serial_base = job.serial_base
        new.reread, new.probe_results, new.wait_results = job.reread, job.probe_results, job.wait_results
        new.when_done = job.when_done
        new.executor.hold = held
        with self.m._lock:                  # the feeder thread reads the job under the lock
            self.job = new
        if self.m.conn.worker_mode != "manual":
            self.feed()
        return new

    def finish_now(self, job: Job, rest: Program) -> None:
        """The job ends at rest here, ``rest`` (events only) being what was left of it."""
        job.messages.clear()
        job.messages.extend((e.line, e.message) for e in rest.events if e.kind is EventKind.MESSAGE)
        self._finish_job(job, self.m.poller.last_snap)

    def start_job(self, job: Job) -> None:
        snap = self.m.conn.snapshot_now()
        job.start_time_s = float(snap.time_s) if job.start_time_s < 0 else job.start_time_s
        if job.kind is Activity.PROGRAM and self.m.worker is not None:
            with self.m._lock:
                self.m.worker.reset_tracking()
                self.m.poller.deliver(self.m.worker.drain_trace())   # not this job's: before it
        with self.m._lock:
            # serial numbers of set-points: the worker's consumed count (+ what is still queued;
            # a stale snapshot still counts the queue, a flushed buffer counts nothing)
            self.pushed_total = int(snap.samples_consumed) + int(snap.buffer_level)
            job.serial_base = self.pushed_total
            self.job = job
        self.m.states.set_activity(job.kind)
        if self.m.states.state is not MachineState.RUNNING:
            self.m.states.set_state(MachineState.RUNNING, job.kind.value)
        else:
            self.m.stateChanged.emit(self.m.states.state, job.kind.value)
        if self.m.conn.worker_mode != "manual":
            self.feed()

    def feed(self, max_new: int | None = None) -> None:
        """Keep the worker's queue ``lead_s`` ahead (at most ``max_new`` set-points now)."""
        from ethercat.worker import WorkerState

        with self.m._lock:
            job, w = self.job, self.m.worker
            if job is None or w is None or job.aborted:
                return
            if w.state() is not WorkerState.ENABLED:
                return
            self.m.prober.watch()           # a probe's contact stops the motion from here
            self._prune_chunks(job, w)
            want = self._lead_samples - w.buffer_level()
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
                n = w.push(raw)
                if n < len(raw):  # pragma: no cover - lead is far below the ring capacity
                    raise MachineError("worker buffer full")
                self._record_chunk(job, ch, state, len(raw))
                want -= n

    def _chunk_raw(self, ch: ScaledChunk) -> np.ndarray:
        """Set-points of a chunk in drive units; at a pause point the plan stands still, so the
        point is repeated: the worker sees the motion end before its buffer runs empty."""
        raw = ch.q + self.m.pos.home_offset
        if ch.pause is not None:
            raw = np.vstack([raw, np.repeat(raw[-1:], 2, axis=0)])
        return raw

    def _record_chunk(self, job: Job, ch: ScaledChunk, state: tuple, pushed: int) -> None:
        """Bookkeeping of a chunk the worker queued at serial ``_pushed_total`` (under the lock)."""
        serial = self.pushed_total
        job.record(ch, serial)
        job.samples += len(ch.q)
        job.chunks.append(ChunkRecord(serial, len(ch.q), pushed, state, ch.pause is not None))
        self.pushed_total = serial + pushed
        if ch.pause is not None:
            job.pause_serial = self.pushed_total  # before .pause: the poll reads both
            job.pause = ch.pause

    @staticmethod
    def _live_consumed(w: Any) -> int | None:
        live = getattr(w, "samples_consumed", None)
        return int(live()) if callable(live) else None

    def _prune_chunks(self, job: Job, w: Any) -> None:
        consumed = self._live_consumed(w)
        if consumed is None:
            return
        chunks = job.chunks
        while len(chunks) > 1 and chunks[0].serial + chunks[0].pushed <= consumed:
            chunks.popleft()

    def change_motion(self, change: Callable[[TimeScaledExecutor], None]) -> None:
        """Apply ``change`` (hold, override) to the running job's executor from a serial a few
        cycles ahead of the drives, replacing the worker's queue from there (module docstring).
        Without a job nothing happens; without a queue (or a worker that cannot replace) the
        change simply applies to the next set-points generated."""
        with self.m._lock:
            job, w = self.job, self.m.worker
            if job is None:
                return
            ex = job.executor
            consumed = self._live_consumed(w) if w is not None and not job.aborted else None
            if consumed is None or not hasattr(w, "replace") or consumed >= self.pushed_total:
                change(ex)
                return
            current = ex.save_state()
            ts = self.m.config.machine.planner.ts_s
            hold = change in _HOLDS
            margin_s = SPLICE_MARGIN_S
            if self.m.conn.worker_mode != "manual":
                # real time: the loop runs on while we compute (a hold plans the time-optimal
                # stop, ~6 ms here); the margin covers the last such splice's critical part
                est = self._splice_est_s.get(hold, 0.008 if hold else 0.003)
                margin_s = max(margin_s, 1.2 * est + 0.001)
            t_start = time.perf_counter()
            first_consumed = consumed
            for attempt in range(1, SPLICE_ATTEMPTS + 1):
                consumed = self._live_consumed(w) or 0
                serial = consumed + max(int(round(margin_s / ts)), 1)
                done = self._splice_at(job, w, serial, consumed, change)
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
                    return
                ex.restore_state(current)  # refused: the queue is unchanged, so is the executor
                margin_s = max(2.0 * margin_s, 1.5 * dt + 0.002)
            change(ex)  # the loop kept outrunning us: apply after the queued set-points
            took = time.perf_counter() - t_start
            self.last_splice = SpliceInfo(-1, first_consumed, SPLICE_ATTEMPTS, took, True)

    def hold_motion(self, wait_for_tap: bool = False) -> None:
        """The running job's executor to hold (sigma -> 0 / the time-optimal path stop), from a
        few cycles ahead of the drives (stop, STOP alarms, jog release, a probe's contact: at
        once; the operator's feed hold, ``wait_for_tap``: once a tap in the hole is out)."""
        job = self.job
        if job is None:
            return
        ex = job.executor
        if wait_for_tap and not ex.hold:
            self.change_motion(_set_feed_hold)
        elif not wait_for_tap and not ex.holding:
            self.change_motion(_set_hold)

    def _splice_at(
        self, job: Job, w: Any, serial: int, consumed: int, change: Callable[[TimeScaledExecutor], None]
    ) -> ReplaceResult | None:
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
        new: list[tuple[tuple, ScaledChunk, np.ndarray]] = []
        # only the first set-points go in the replace (the sooner it reaches the loop, the
        # smaller the margin a splice needs); the feeder tops the queue up right after it
        state = ex.save_state()
        ch = ex.generate(CHUNK)
        if ch is not None:
            new.append((state, ch, self._chunk_raw(ch)))
        q = np.vstack([r for _, _, r in new]) if new else np.zeros((0, len(self.m.pos.home_offset)))
        result, n = w.replace(serial, q)
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
        self.feed(max_new=int(0.1 / self.m.config.machine.planner.ts_s))
        return ReplaceResult.DONE

    def consumed(self) -> int:
        snap = self.m.poller.last_snap
        return int(snap.samples_consumed) if snap is not None else 0

    @staticmethod
    def _spin_ups_left(job: Job, tau: float, now_s: float) -> float:
        """The spindle's waits still ahead of planned time ``tau``, and what is left of the one
        under way (the motion stands meanwhile: the time left counts them)."""
        left = sum(wait for at, wait in job.spin_ups if at > tau)
        if job.spinup_until is not None:
            left += max(job.spinup_until - now_s, 0.0)
        return left

    def poll_job(self, job: Job, snap: Any) -> None:
        consumed = int(snap.samples_consumed)
        info = job.info_at(consumed)
        if info is not None:
            line, tau = info
            # a stop that prompts the operator shows its own line (the M6), not the last move's
            if line != self.line and job.kind in (Activity.PROGRAM, Activity.MDI) and not job.waiting:
                self.line = line
                self.m.lineChanged.emit(line)
            while job.messages and job.messages[0][0] <= line:
                self.show_message(job.messages.popleft()[1])
            if job.kind is Activity.PROGRAM:
                t_end = job.executor.planned_end_s + job.time_offset_s
                tau_g = tau + job.tau_offset_s
                frac = min(tau_g / t_end, 1.0) if t_end > 0 else 1.0
                capped = job.executor.capped_to
                ovr = max(self.m.run.feed_pct / 100.0 if capped is None else capped, 1e-3)
                remaining = max(t_end - tau_g, 0.0) / ovr + self._spin_ups_left(job, tau, float(snap.time_s))
                self.progress = (frac, remaining)
                self.m.progressChanged.emit(frac, remaining)
        capped = job.executor.capped_to
        if (capped is not None) != job.cap_reported:
            job.cap_reported = capped is not None
            if capped is not None:
                self.m.message.emit(f"feed override {self.m.run.feed_pct:g} % capped at {100 * capped:.0f} % "
                                    "here: the machine's speed, acceleration or jerk limit")
        if job.spindle_locked is not None and (job.pause is None or consumed < job.pause_serial):
            self._spindle_lock_at(job, job.move_at(consumed))      # (a pause point sets it itself)
        off = job.executor.override_off_here and job.overrides and self.m.run.feed_pct != 100.0
        if off != job.override_off_reported:
            job.override_off_reported = off
            if off:
                self.m.message.emit(f"feed override {self.m.run.feed_pct:g} % not applied here: the program "
                                    "turned it off (tapping, M49 or M50 P0) and runs its own feed")
        self.set_feed_note("runs 100 %: program" if off else
                           f"runs {100 * capped:.0f} %: limits" if capped is not None else "")
        if snap.time_s - self.m.poller.tracking_emit_t >= 1.0 and job.kind is Activity.PROGRAM:
            self.m.poller.tracking_emit_t = snap.time_s
            self.tracking = self._tracking_from(snap, "")
            self.m.trackingUpdated.emit(self.tracking)
        all_done = consumed >= self.pushed_total
        self.m.prober.poll(job, all_done)
        if self.job is not job:              # the probe's result: the rest runs as a new job
            return
        # pause points reached by the drives
        if job.pause is not None and consumed >= job.pause_serial:
            self._at_pause(job, job.pause, snap)
            return
        if job.stopping and job.executor.standing and all_done:
            self._finish_stop(job)

    def _spindle_lock_at(self, job: Job, move: int | None) -> None:
        """The spindle override as the program wants it for ``move`` (off in a tap, after M49)."""
        locked = job.spindle_locked
        if locked is not None and job.overrides and move is not None and 0 <= move < len(locked):
            self.m.spindle_ctl.set_program_lock(bool(locked[move]))

    def set_feed_note(self, note: str) -> None:
        if note != self.feed_note:
            self.feed_note = note
            self.m.feedOverrideNote.emit(note)

    def _at_pause(self, job: Job, p: PausePoint, snap: Any) -> None:
        kind = p.kind
        if kind == "end":
            self._finish_job(job, snap)
            return
        if job.stopping:
            self._finish_stop(job)
            return
        if job.spinup_until is not None:      # a spindle started here: on at speed first
            if snap.time_s >= job.spinup_until:
                job.spinup_until = None
                self.release(job)
            return
        if kind == "spindle":
            self.start_spindle(job, SpindleState(direction=int(np.sign(p.value)), rpm=abs(p.value)),
                               float(snap.time_s))
        elif kind == "probe_start":              # G38.x: the input watched from here, at rest
            why = self.m.prober.arm(job, int(p.value))
            if why:
                self.m.prober.fail(why)
            else:
                self.release(job)
        elif kind == "probe":                    # the probe move's end point reached
            self.m.prober.finish(job)
        elif kind == "input":                    # M66: read or waited for here, at rest
            self.m.waiter.at_pause(job, int(p.value), snap)
        elif kind == "tapping":                  # a tap's overrides change here, at rest
            self._spindle_lock_at(job, p.move + 1)
            self.release(job)
        elif kind == "tool_set":                 # M61 Q: the program says which tool is in
            self.m.tools.loaded_by_program(int(p.value))
            self.release(job)
        elif kind == "output":                   # M62-M65, a user M-code: the output switches here
            number = int(p.value) if p.value >= 0 else -int(p.value) - 1
            if not self.m.outputs.set_output(number, p.value >= 0):
                self.release(job)
        elif kind == "tool_data":                # G10 L1/L10/L11: the tool table takes the tool
            tools = job.plan.program.tool_sets
            if 0 <= int(p.value) < len(tools):
                self.m.tools.set_by_program(tools[int(p.value)])
            self.release(job)
        elif kind == "offsets":                  # G10, G92, G52, G28.1 ...: the machine keeps them
            sets = job.plan.program.parameter_sets
            if 0 <= int(p.value) < len(sets):
                self.m.pos.apply_parameters(sets[int(p.value)])
            self.release(job)
        elif kind == "dwell":
            if job.dwell_until is None:
                job.dwell_until = snap.time_s + p.value
                job.dwell_total_s += p.value
            elif snap.time_s >= job.dwell_until:
                job.dwell_until = None
                self.release(job)
        elif kind == "optional_pause" and not self.m.run.optional_stop:
            self.release(job)
        elif not job.waiting:
            job.waiting = True
            if kind == "tool_change" and self.m.spindle_ctl.spindle.on:
                # hands go near the spindle: it stops, and cycle start brings it back
                job.spindle_paused = self.m.spindle_ctl.spindle
                self.m.spindle_ctl.stop_spindle()
            tool = int(p.value) if kind == "tool_change" else 0
            label = self.m.tools.table.label(tool)
            reason = {
                "pause": f"program paused (M00, line {p.line}): press cycle start",
                "optional_pause": f"optional stop (M01, line {p.line}): press cycle start",
                "tool_change": (f"tool change (M06, line {p.line}): insert tool {label} and "
                                "press cycle start"),
                "single_block": f"single block: end of line {p.line}",
            }.get(kind, kind)
            hold = {"pause": HoldKind.PROGRAM_STOP, "optional_pause": HoldKind.OPTIONAL_STOP,
                    "tool_change": HoldKind.TOOL_CHANGE, "single_block": HoldKind.SINGLE_BLOCK}.get(
                kind, HoldKind.FEED_HOLD)
            if p.line > 0 and p.line != self.line:   # the line that stopped, not the next one
                self.line = p.line
                self.m.lineChanged.emit(p.line)
            self.m.states.set_state(MachineState.HOLD, reason, hold, Prompt(hold, p.line, tool, reason))

    def start_spindle(self, job: Job, sp: SpindleState, now_s: float) -> None:
        """Switch the spindle at a pause point (a program's M3/M4/M5/S, or back after a tool
        change); when it starts, reverses or speeds up, the motion waits ``spindle_spinup_s``
        there before it goes on, else it goes on at once."""
        wait = self.m.spindle_ctl.spin_up_s(sp)
        self.m.spindle_ctl.apply_spindle(sp)
        job.waiting = False
        if wait > 0.0:
            job.spinup_until = now_s + wait
            job.dwell_total_s += wait
        else:
            self.release(job)

    def _finish_stop(self, job: Job) -> None:
        resume = self.m.run.resume_point
        self.drop_job(completed=False, reason=job.stop_reason or "stopped")
        # the axes stand: now the spindle may stop too (stopping it while the tool still moves
        # along the path would drag a standing cutter through the material)
        self.m.spindle_ctl.stop_spindle()
        if self.m.states.state is MachineState.ALARM:
            self.m.run.resume_point = resume  # a STOP alarm keeps the point to resume from
            return
        self.m.states.set_state(MachineState.IDLE, job.stop_reason or "stopped")

    def release(self, job: Job) -> None:
        with self.m._lock:
            job.pause = None
            job.waiting = False
            job.executor.release_pause()

    def show_message(self, text: str) -> None:
        """A program's message for the operator: the status line and the alarm log (information)."""
        self.m.message.emit(text)
        self.m.alarm_log.raise_alarm("program", text, Severity.INFO, "program_message")

    def _finish_job(self, job: Job, snap: Any) -> None:
        while job.messages:                      # messages after the last move (before M2)
            self.show_message(job.messages.popleft()[1])
        nxt = job.then
        completed_summary = self.drop_job(completed=True, reason="completed", snap=snap)
        if nxt is not None:
            self.start_job(nxt)
            return
        if job.kind is Activity.PROGRAM:
            self.m.spindle_ctl.stop_spindle()      # program end: spindle off (M2/M30 or the last line)
        self.m.states.set_state(MachineState.IDLE, "program end" if completed_summary else "done")
        if job.when_done is not None:
            job.when_done(job)

    def drop_job(self, completed: bool, reason: str, snap: Any = None) -> RunSummary | None:
        """End the current job (under the lock). Emits programFinished for program jobs."""
        with self.m._lock:
            job, self.job = self.job, None
            if job is None:
                return None
            job.aborted = True
            self.m.spindle_ctl.set_program_lock(False)
            self.set_feed_note("")
            self.m.prober.cancel()
            self.m.waiter.cancel()
            if self.m.worker is not None and not completed:
                try:
                    self.m.worker.flush()
                except Exception:  # noqa: BLE001
                    pass
        if job.kind is not Activity.PROGRAM:
            return None
        last_line = self.line
        if completed and job.then is None:
            self.m.run.resume_point = None
            self.line = 0
        if snap is None:
            snap = self.m.poller.last_snap
        # motion time: set-points sent (holds included) plus dwells; waits for the operator excluded
        measured = job.samples * job.plan.ts_s + job.dwell_total_s
        trace_path = self._save_trace(job)
        tracking = self._tracking_from(snap, trace_path) if snap is not None else TrackingReport()
        self.tracking = tracking
        summary = RunSummary(
            name=job.name,
            completed=completed,
            cycle_time_s=measured,
            estimated_s=job.estimated_s,
            last_line=last_line,
            tracking=tracking,
            limits=merge_max(job.carried_limits, job.meter.final()),
            reason=reason,
        )
        self.last_summary = summary
        self.m.trackingUpdated.emit(tracking)
        if completed:
            self.m.progressChanged.emit(1.0, 0.0)
        self.m.programFinished.emit(summary)
        return summary

    def _tracking_from(self, snap: Any, trace_path: str) -> TrackingReport:
        t = snap.tracking
        return TrackingReport(
            axes=self.m.config.axes,
            samples=int(t.samples),
            rmse=tuple(t.rmse),
            mse=tuple(t.mse),
            max_abs=tuple(t.max_abs),
            trace_path=trace_path or self.tracking.trace_path,
        )

    def _save_trace(self, job: Job) -> str:
        if not job.trace:
            return ""
        cyc = np.concatenate([c for c, _, _ in job.trace])
        ref = np.concatenate([r for _, r, _ in job.trace]) - self.m.pos.home_offset
        act = np.concatenate([a for _, _, a in job.trace]) - self.m.pos.home_offset
        path = self.m.conn.store.path("last_run.npz")
        e = ref - act
        mse = (e * e).mean(axis=0) if len(e) else np.zeros(len(self.m.config.axes))
        try:
            write_output(
                path,
                lambda fh: np.savez_compressed(
                    fh,
                    t=cyc * self.m.config.machine.planner.ts_s,
                    reference=ref,
                    actual=act,
                    axes=np.array(self.m.config.axes),
                    rmse=np.sqrt(mse),
                    mse=mse,
                ),
            )
        except OSError as exc:
            self.m.alarm_log.raise_alarm(
                "persistence", f"cannot save the run trace: {exc}", Severity.WARNING, "trace"
            )
            return ""
        return str(path)
