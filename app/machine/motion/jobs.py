"""Records of a motion being executed: the job (plan, executor, pushed set-point marks, limit
meter, trace), the point to resume a program from, and the running limit meter."""

from __future__ import annotations

import collections
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from app.machine.model import Activity, ResumePoint
from app.machine.motion.timescale import PausePoint, ScaledChunk, TimeScaledExecutor
from planner.core.frames import Frame
from planner.core.machine import MachineSpec
from planner.core.program import SPINDLE_OVERRIDE_OFF, EventKind, ProbeResult, Program
from planner.motion.meter import LimitMeter, PathSpeedLimits
from planner.motion.plan import Plan
from planner.motion.window import PlanWindow
from planner.pipeline import Reread

__all__ = ["NO_TERMS", "ChunkRecord", "Job", "JobTerms", "Reads", "Reread", "ResumePoint", "SentLimits",
           "merge_max"]


@dataclass(frozen=True, slots=True)
class ChunkRecord:
    """One pushed chunk: serial of its first set-point, executor samples in it, set-points
    pushed (plus the repeats after a pause point), and the executor's state before it
    (``TimeScaledExecutor.save_state``): the controller rewinds to it to splice the queue."""

    serial: int
    samples: int
    pushed: int
    state: tuple
    pause: bool


#: the probe results and the values of the inputs read so far in a run (by index)
Reads = tuple[tuple[ProbeResult | None, ...], tuple[float | None, ...]]


@dataclass(frozen=True, slots=True)
class JobTerms:
    """What a job is part of and what follows it, fixed when the job maker makes it."""

    reason: str = ""                 # what the state says while it runs ("": its kind)
    steps: tuple[tuple[int, str], ...] = ()   # a routine's lines by what they do (its errors name them)
    source: str = ""                 # the program's file ("" for a text): what a power loss interrupted
    # the program whose moves this job's count from, the move and the distance into it it starts at
    origin: tuple[Program, int, float] | None = None
    # G38.x and M66: the whole program read again with the results (None: the job cannot)
    reread: Reread | None = None
    probe_results: tuple[ProbeResult | None, ...] = ()
    wait_results: tuple[float | None, ...] = ()
    # called with the job (the last of its followers) once it has run to its end
    when_done: Callable[[Job], None] | None = None
    then: Job | None = None          # the job that runs once this one has (an approach's program)
    offset_s: float = 0.0            # where the job starts on its whole program's timeline


#: pushed chunks whose lines a job keeps (20 set-points a chunk: seconds of set-points, more
#: than the lead queued and the trace drained between two polls)
LINES_KEPT = 512

#: a job that is no part of anything else (a jog)
NO_TERMS = JobTerms()


class Job:
    """One motion being executed (program, MDI block, jog, approach). Its terms are fixed when
    the job maker (``app.machine.motion.making``) makes it; what the run does to it is the
    streamer's to write (its set-point queue the samples and pause points, the streamer the
    rest), and a job that goes on from another (``follows``) carries that run's progress."""

    def __init__(
        self,
        kind: Activity,
        name: str,
        program: Program,
        plan: Plan | PlanWindow,
        executor: TimeScaledExecutor,
        overrides: bool,
        estimated_s: float,
        machine: MachineSpec,
        single_block: bool = False,
        spin_ups: list[tuple[float, float]] | None = None,
        terms: JobTerms = NO_TERMS,
        follows: Job | None = None,
    ) -> None:
        self.kind = kind
        self.name = name
        self.reason = terms.reason
        self.steps = dict(terms.steps)
        self.source = terms.source
        self.program = program
        # (MSG,...), (DEBUG,...) and user M-code texts, shown when the motion reaches their line
        self.messages: collections.deque[tuple[int, str]] = collections.deque(
            (e.line, e.message) for e in program.events if e.kind is EventKind.MESSAGE)
        self.plan = plan
        self.executor = executor
        self.overrides = overrides
        self.estimated_s = estimated_s
        # the run's progress: carried over from the job this one goes on from
        self.serial_base: int = follows.serial_base if follows is not None else 0
        self.start_time_s: float = follows.start_time_s if follows is not None else -1.0
        self.samples: int = follows.samples if follows is not None else 0
        self.dwell_total_s: float = follows.dwell_total_s if follows is not None else 0.0
        self.trace: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = \
            follows.trace if follows is not None else []
        self.carried_limits: dict[str, float] = (merge_max(follows.carried_limits, follows.meter.final())
                                                 if follows is not None else {})
        if follows is not None:
            self.estimated_s = follows.estimated_s
        self.pause: PausePoint | None = None
        self.pause_serial = 0
        self.waiting = False
        self.dwell_until: float | None = None
        self.stopping = False
        self.stop_reason = ""
        self.aborted = False
        self.then = terms.then
        self.keep_point = False   # stopped by the operator: the point where it rests is kept to resume
        self.spinup_until: float | None = None   # worker time the spindle is at speed
        self.resume_at_s: float | None = None    # worker time a hold ends (the spindle at speed again)
        # (planned time, wait) of each spin-up of the spindle the run will wait for
        self.spin_ups = spin_ups if spin_ups is not None else []
        self.cap_reported = False  # the operator was told the limits cap the feed override here
        self.override_off_reported = False  # ... that the program turned the feed override off here
        locks = plan.program.override_locks
        # moves the program runs with the spindle override off (None: none)
        self.spindle_locked = None if locks is None else (locks & SPINDLE_OVERRIDE_OFF).astype(bool)
        self.origin = terms.origin
        # G38.x and M66: reads the whole program again with the probe results and the values of
        # the inputs (None: the job cannot), and those so far by index
        self.reread = terms.reread
        self.probe_results = terms.probe_results
        self.wait_results = terms.wait_results
        self.when_done = terms.when_done
        self.single_block = single_block
        self.tau_offset_s = terms.offset_s
        self.time_offset_s = terms.offset_s
        self.meter: SentLimits = SentLimits(machine, plan.ts_s, plan.program.rapid_moves,
                                            plan.program.rotary_only_moves)
        # per pushed chunk: serial of its last sample, line, tau, move, u within the move
        self._marks: collections.deque[tuple[int, int, float, int, float]] = collections.deque()
        self._last_mark: tuple[int, int, float, int, float] | None = None
        # pushed chunks still (partly) queued in the worker, oldest first
        self.chunks: collections.deque[ChunkRecord] = collections.deque()
        # the source line of each set-point pushed lately: (first serial, set-points, lines), so
        # that every row of the drives' trace is told its own line (``lines_of``)
        self._lines: collections.deque[tuple[int, int, np.ndarray]] = collections.deque(maxlen=LINES_KEPT)

    def rewind(self, serial: int) -> tuple[int, bool]:
        """Forget what was pushed from ``serial`` on (a chunk start; the worker's queue is being
        replaced from there): marks, chunk records and metered samples. The samples dropped,
        and whether a chunk that ended at a pause point was among them."""
        while self._marks and self._marks[-1][0] >= serial:
            self._marks.pop()
        while self._lines and self._lines[-1][0] >= serial:
            self._lines.pop()
        dropped, pause = 0, False
        while self.chunks and self.chunks[-1].serial >= serial:
            rec = self.chunks.pop()
            dropped += rec.samples
            pause = pause or rec.pause
        self.meter.rewind(dropped)
        return dropped, pause

    def record(self, ch: ScaledChunk, serial_start: int, pushed: int) -> None:
        """A chunk queued from ``serial_start`` (``pushed`` set-points: its samples, and the
        repeats of a pause point's). Its last sample at a pause point and the repeats stand for
        the line that stops there (an M6's, an M0's): the sample lies at the end of the move
        before, where the plan's own lookup already names the move after the stop."""
        lines = ch.line
        if ch.pause is not None:
            stop = np.full(pushed - len(lines) + 1, ch.pause.line, dtype=lines.dtype)
            lines = np.concatenate([lines[:-1], stop])
        self._lines.append((serial_start, pushed, lines))
        end = serial_start + len(ch.q) - 1
        move = int(ch.move[-1])
        u = float(ch.s_mm[-1] - self.executor.move_start_s(move)) if self.executor.n_moves else 0.0
        self._marks.append((end, int(ch.line[-1]), float(ch.tau[-1]), move, u))
        if len(self._marks) > 4096:
            self._marks.popleft()
        self.meter.update(ch.q, ch.s_mm, ch.move)

    def lines_of(self, serials: np.ndarray) -> np.ndarray:
        """The source line of each set-point serial (0: not one of this job's, or too old)."""
        out = np.zeros(len(serials), dtype=np.int64)
        if not self._lines or not len(serials):
            return out
        starts = np.fromiter((c[0] for c in self._lines), np.int64, len(self._lines))
        pushed = np.fromiter((c[1] for c in self._lines), np.int64, len(self._lines))
        at = np.searchsorted(starts, serials, side="right") - 1
        ok = (at >= 0) & (serials - starts[np.maximum(at, 0)] < pushed[np.maximum(at, 0)])
        for k in np.flatnonzero(ok):
            start, _, lines = self._lines[int(at[k])]
            out[k] = lines[min(int(serials[k]) - start, len(lines) - 1)]   # a pause's repeats: its line
        return out

    def info_at(self, consumed: int) -> tuple[int, float] | None:
        """(line, tau) of the set-point the drives reached (the last consumed one)."""
        serial = consumed - 1
        m = self._mark_at(serial)
        return (m[1], m[2]) if m is not None else None

    def move_at(self, consumed: int) -> int | None:
        """The move of the set-point the drives reached."""
        m = self._mark_at(consumed - 1)
        return m[3] if m is not None else None

    def _source(self) -> tuple[Program, int]:
        """The program whose moves this job's move numbers count from, and where they start in
        it (a run from a line runs a piece of the loaded program: its ``origin``)."""
        return (self.origin[0], self.origin[1]) if self.origin is not None else (self.plan.program, 0)

    def frame_at(self, consumed: int) -> Frame | None:
        """The offsets in force (the program's own, ``Program.frame_at``) at the set-point the
        drives reached; None before the first."""
        m = self.move_at(consumed)
        if m is None:
            return None
        prog, base = self._source()
        return prog.frame_at(base + m)

    def frame_in_force(self, consumed: int) -> Frame | None:
        """The offsets in force at the set-point the drives reached (``frame_at``); stopped at a
        pause point they reached, those in force there (``Program.frame_before``: at an M6 the
        old tool's length, not that of the G43 after it)."""
        pause = self.pause
        if pause is None or consumed < self.pause_serial:
            return self.frame_at(consumed)
        prog, base = self._source()
        return prog.frame_before(base + pause.move, pause.line)

    def left_at(self, consumed: int, completed: bool) -> tuple[Program, int]:
        """The program this job ran and the move it ended with (``len(moves)`` when it ran to
        its end): what it leaves in force is the program's state there."""
        prog, base = self._source()
        if completed:
            return prog, len(prog.moves)
        m = self.move_at(consumed)
        return prog, base + (m if m is not None else 0)

    def distance_to_go(self, consumed: int, reference: np.ndarray) -> tuple[float, ...]:
        """The end of the move the drives are on, less where the set-point ``reference`` is (as
        LinuxCNC's DTG reads it); () when they are on none."""
        m = self.move_at(consumed)
        moves = self.plan.program.moves
        if m is None or not 0 <= m < len(moves):
            return ()
        return tuple(float(v) for v in np.asarray(moves[m].end, dtype=float) - reference)

    def spin_ups_left(self, tau: float, now_s: float) -> float:
        """The spindle's waits still ahead of planned time ``tau``, and what is left of the one
        under way (the motion stands meanwhile: the time left counts them)."""
        left = sum(wait for at, wait in self.spin_ups if at > tau)
        if self.spinup_until is not None:
            left += max(self.spinup_until - now_s, 0.0)
        return left

    def _mark_at(self, serial: int) -> tuple[int, int, float, int, float] | None:
        marks = self._marks
        while len(marks) > 1 and marks[0][0] < serial:
            self._last_mark = marks.popleft()
        if marks and marks[0][0] <= serial + 20:
            return marks[0] if marks[0][0] <= serial or self._last_mark is None else self._last_mark
        return self._last_mark

    def resume_point(self, consumed: int, cause: str) -> ResumePoint | None:
        if self.kind is not Activity.PROGRAM or self.origin is None:
            return self.then.resume_point(consumed, cause) if self.then is not None else None
        prog, base, u0 = self.origin
        m = self._mark_at(consumed - 1)
        reads = (self.probe_results, self.wait_results)
        if m is None:
            return ResumePoint(prog, base, u0, prog.moves[base].line if prog.moves else 0, cause, *reads)
        _, line, _, move, u = m
        orig = base + move
        u_orig = (u0 + u) if move == 0 else u
        if orig >= len(prog.moves):
            return None
        return ResumePoint(prog, orig, u_orig, line, cause, *reads)


def merge_max(a: dict[str, float], b: dict[str, float]) -> dict[str, float]:
    return {k: max(a.get(k, 0.0), b.get(k, 0.0)) for k in set(a) | set(b)}


class SentLimits:
    """The set-points sent to the drives, measured by the planner's limit meter
    (``planner.motion.meter``) against the machine's limits, as ratios (<= 1 holds).

    The newest ``keep`` samples stay unmetered, so a splice of the worker's queue (at most its
    capacity, 2000 set-points) can take them back (``rewind``) before they count."""

    def __init__(self, machine: MachineSpec, ts_s: float, rapid_move: np.ndarray,
                 rotary_only: np.ndarray | None = None, keep: int = 4096) -> None:
        lim = machine.limits
        v_path = (PathSpeedLimits(rapid_move, lim.rapid_mm_s, lim.v_max_mm_s, rotary_only, lim.rapid_deg_s,
                                  lim.v_max_deg_s) if len(rapid_move)
                  else np.array([max(lim.v_max_mm_s, lim.rapid_mm_s)]))
        self._meter = LimitMeter(machine, ts_s, v_path)
        self.keep = keep
        self._pending: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
        self._n = 0

    def update(self, q: np.ndarray, s: np.ndarray, move: np.ndarray) -> None:
        self._pending.append((q, s, move))
        self._n += len(q)
        if self._n >= self.keep + 500:
            self._flush(self._n - self.keep)

    def rewind(self, n: int) -> None:
        """Drop the newest ``n`` samples (never executed: replaced in the worker's queue)."""
        n = min(n, self._n)
        while n > 0 and self._pending:
            q, s, m = self._pending[-1]
            if len(q) <= n:
                self._pending.pop()
                self._n -= len(q)
                n -= len(q)
            else:
                k = len(q) - n
                self._pending[-1] = (q[:k], s[:k], m[:k])
                self._n -= n
                n = 0

    def flush(self) -> None:
        self._flush(self._n)

    def _flush(self, count: int) -> None:
        if not self._pending or count <= 0:
            return
        q = np.concatenate([p[0] for p in self._pending])
        s = np.concatenate([p[1] for p in self._pending])
        move = np.concatenate([p[2] for p in self._pending])
        self._pending = [(q[count:], s[count:], move[count:])] if count < len(q) else []
        self._n = len(q) - min(count, len(q))
        self._meter.add(q[:count], s[:count], move[:count])

    def final(self) -> dict[str, float]:
        self.flush()
        return self._meter.ratio_report()
