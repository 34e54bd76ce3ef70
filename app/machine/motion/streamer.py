"""Running a motion: jobs planned with the override budget, set-points streamed to the worker
``lead_s`` ahead (the feeder thread), pause points, program end, run summaries and the trace.

Serial numbers and splicing (how a hold, a stop or an override takes effect a few cycles ahead
of the drives): ``app.machine.motion.feeding``.

The streamer owns the job and the lock that the feeder thread and the controller's thread
share over it; no other part takes that lock. It also owns the point a stopped program
resumes from: kept where the motion was interrupted (E-stop, a fault, a STOP alarm, a
shutdown), forgotten by a reset, a new program, the operator's stop and the program's end.
What happens at a pause point of another part's (a probe, an input, an output, a tool, the
offsets) is that part's: it registers a handler (``app.machine.motion.pauses``).
"""

from __future__ import annotations

import threading
from collections.abc import Callable

import numpy as np

from app.machine.infra.drives import DriveLink
from app.machine.infra.events import MachineEvents, PanelChannels
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
from app.machine.motion.feeding import SetpointQueue, SpliceInfo
from app.machine.motion.jobs import Job, Reads, ResumePoint, merge_max
from app.machine.motion.making import JobMaker
from app.machine.motion.pauses import PauseHandlers, why_stopped
from app.machine.motion.runs import save_trace, tracking_report
from app.machine.motion.timescale import (
    SIGMA_MAX,
    PauseKind,
    PausePoint,
    TimeScaledExecutor,
)
from app.machine.ports import (
    AlarmSink,
    CoordinatesView,
    PositionsView,
    RunModes,
    Settings,
    SpindleDrive,
    ToolView,
)
from app.machine.state.states import StateMachine
from ethercat.worker import TraceChunk, WorkerSnapshot, WorkerState
from planner.core.errors import PlannerError
from planner.core.program import Dwell, EventKind, Program, SpindleSpeed, TableRef, ToolNumber
from planner.geometry.resume import remaining_program

__all__ = ["Streamer"]

#: (cycles, reference, actual, line of each row's set-point; machine coordinates)
TraceSink = Callable[[np.ndarray, np.ndarray, np.ndarray, np.ndarray], None]

_OPERATOR_STOPS = {
    PauseKind.PAUSE: HoldKind.PROGRAM_STOP, PauseKind.OPTIONAL_PAUSE: HoldKind.OPTIONAL_STOP,
    PauseKind.TOOL_CHANGE: HoldKind.TOOL_CHANGE, PauseKind.SINGLE_BLOCK: HoldKind.SINGLE_BLOCK,
}


class Streamer:
    """The job under way and its set-points (``controller.motion``)."""

    def __init__(self, settings: Settings, states: StateMachine, drives: DriveLink, positions: PositionsView,
                 coordinates: CoordinatesView, spindle: SpindleDrive, tools: ToolView, modes: RunModes,
                 alarms: AlarmSink, pauses: PauseHandlers, trace_path: str, out: PanelChannels,
                 events: MachineEvents) -> None:
        self._settings = settings
        self._states = states
        self._drives = drives
        self._positions = positions
        self._coordinates = coordinates
        self._spindle = spindle
        self._tools = tools
        self._alarms = alarms
        self._trace_path = trace_path
        self._out = out
        # the feeder thread and the controller's thread both touch the job: this lock is theirs
        self._lock = threading.RLock()
        self.job: Job | None = None
        self._queue = SetpointQueue(settings, drives, positions)
        self.line = 0
        self.progress = (0.0, 0.0)
        # what is left of the move the drives are on, per axis (machine units; () at rest)
        self.distance_to_go: tuple[float, ...] = ()
        self.feed_note = ""          # feedOverrideNote as last emitted
        self.tracking = TrackingReport(axes=settings.config.axes)
        self.last_summary: RunSummary | None = None
        self.resume_point: ResumePoint | None = None
        self._tracking_emit_t = 0.0
        self._pauses = pauses
        self._feed_hooks: list[Callable[[], None]] = []
        self._poll_hooks: list[Callable[[Job, bool], None]] = []
        self._end_hooks: list[Callable[[], None]] = []
        self._sinks: list[TraceSink] = []
        self._modes = modes
        #: how jobs are made (plans, overrides, spin-ups) for this machine
        self.jobs = JobMaker(settings, coordinates, spindle, modes, events)
        events.estop.connect(lambda reason: self.abandon(f"E-stop: {reason}", keep_point=reason))
        events.fault.connect(lambda cause: self.abandon(cause, keep_point=cause))
        events.alarm_stop.connect(self._alarm_stop)
        events.reset.connect(self._reset)
        events.spindle_speed_changed.connect(self._wait_for_spindle)
        events.program_let_go.connect(self.forget_resume_point)
        events.program_loaded.connect(lambda _info: self.forget_resume_point())
        events.program_refused.connect(self.forget_resume_point)

    # ------------------------------------------------------------------ registrations
    def on_feed(self, hook: Callable[[], None]) -> None:
        """``hook()`` runs before every feed, in the feeder thread under the motion's lock (a
        probe's contact stops the motion from there)."""
        self._feed_hooks.append(hook)

    def on_poll(self, hook: Callable[[Job, bool], None]) -> None:
        """``hook(job, all_done)`` runs at every poll of a job (the controller's thread)."""
        self._poll_hooks.append(hook)

    def on_job_end(self, hook: Callable[[], None]) -> None:
        """``hook()`` runs when a job is dropped (ended, stopped, abandoned)."""
        self._end_hooks.append(hook)

    def add_trace_sink(self, sink: TraceSink) -> None:
        """Every drained set-point chunk (cycles, reference, actual, the source line of each
        row's set-point; machine coordinates)."""
        self._sinks.append(sink)

    # ------------------------------------------------------------------ views
    @property
    def busy(self) -> bool:
        return self.job is not None

    def standing(self) -> bool:
        """At rest on the path: no job, held still, or at a pause point."""
        with self._lock:
            job = self.job
            return job is None or job.executor.standing or job.pause is not None

    @property
    def _lead_samples(self) -> int:
        cfg = self._settings.config
        return max(int(cfg.controller.lead_s / cfg.machine.planner.ts_s), 10)

    def consumed(self) -> int:
        snap = self._drives.last_snapshot
        return int(snap.samples_consumed) if snap is not None else 0

    def keep_resume_point(self, point: ResumePoint) -> None:
        """A point to resume the loaded program from that no run of this control left (the run
        a power loss cut)."""
        self.resume_point = point

    def forget_resume_point(self) -> None:
        self.resume_point = None

    def clear_line(self) -> None:
        self.line = 0
        self._out.lineChanged.emit(0)

    # ------------------------------------------------------------------ jobs
    def run_program(self, job: Job, line: int = 0) -> None:
        """Start a program run (its ``origin`` set), shown from ``line``; the point a stop
        left to resume from is forgotten."""
        self.resume_point = None
        self.line = line
        self.start_job(job)

    def follow(self, job: Job, rest: Program, origin: tuple[Program, int, float], held: bool = False,
               reads: Reads | None = None) -> Job:
        """At rest on the path: run ``rest`` (what is left of the program from here, planned
        anew) in place of ``job``, as the same run (time, progress, trace, limits); ``held``:
        it waits for cycle start (the operator's feed hold); ``reads``: the probe and input
        results so far. Raises PlannerError when the rest cannot be planned (``job`` is then
        unchanged)."""
        new = self.jobs.successor(job, rest, origin, held, reads)
        with self._lock:                  # the feeder thread reads the job under the lock
            self.job = new
        if self._drives.realtime:
            self.feed()
        return new

    def finish_now(self, job: Job, rest: Program) -> None:
        """The job ends at rest here, ``rest`` (events only) being what was left of it: what its
        events keep is kept (G10 and G92, G10 L1, M61, M62-M65), as the motion would have done at
        their pause points, then its messages are shown."""
        output, snap = self._pauses.get(PauseKind.OUTPUT), self._drives.last_snapshot
        for ev in rest.events:
            if ev.kind is EventKind.OFFSETS and 0 <= ev.payload_as(TableRef).index < len(rest.parameter_sets):
                self._coordinates.apply_parameters(rest.parameter_sets[ev.payload_as(TableRef).index])
            elif ev.kind is EventKind.TOOL_DATA and 0 <= ev.payload_as(TableRef).index < len(rest.tool_sets):
                self._tools.set_by_program(rest.tool_sets[ev.payload_as(TableRef).index])
            elif ev.kind is EventKind.TOOL_SET:
                self._tools.loaded_by_program(ev.payload_as(ToolNumber).number)
            elif ev.kind is EventKind.OUTPUT and output is not None and snap is not None:
                output(job, PausePoint(0.0, PauseKind.OUTPUT, ev.line, -1, ev.payload), snap)
        job.messages.clear()
        job.messages.extend((e.line, e.message) for e in rest.events if e.kind is EventKind.MESSAGE)
        self._finish_job(job, self._drives.last_snapshot)

    def start_job(self, job: Job) -> None:
        snap = self._drives.snapshot()
        assert snap is not None
        job.start_time_s = float(snap.time_s) if job.start_time_s < 0 else job.start_time_s
        if job.kind is Activity.PROGRAM:
            self._drives.reset_tracking()
            trace = self._drives.drain_trace()            # not this job's: before it
            if trace is not None:
                self._deliver(trace)
        with self._lock:
            # serial numbers of set-points: the worker's consumed count (+ what is still queued;
            # a stale snapshot still counts the queue, a flushed buffer counts nothing)
            job.serial_base = self._queue.restart_at(int(snap.samples_consumed) + int(snap.buffer_level))
            self.job = job
        self._states.set_activity(job.kind)
        why = job.reason or job.kind.value
        if self._states.state in (MachineState.RUNNING, MachineState.HOMING):  # homing: to the home position
            self._states.tell_state(why)
        else:
            self._states.set_state(MachineState.RUNNING, why)
        if self._drives.realtime:
            self.feed()

    def reset_serials(self) -> None:
        """A new worker counts its set-points from zero."""
        self._queue.restart_at(0)

    # ------------------------------------------------------------------ the operator's commands
    def hold(self) -> bool | None:
        """The operator's feed hold: None when nothing moves, else whether it waits for a tap
        to come out of the hole first."""
        with self._lock:
            job = self.job
            if job is None:
                return None
            self.hold_motion(wait_for_tap=True)
            return bool(job.executor.hold_deferred)

    def stop_job(self, reason: str, only: Activity | None = None, keep_point: bool = False) -> bool:
        """Stop the job along its path and end it at standstill (``only``: just a job of that
        kind); ``keep_point``: a program keeps the point where it comes to rest to resume from
        (the operator's Stop: cycle start then asks to resume there or start again). Whether
        there was one to stop."""
        with self._lock:
            job = self.job
            if job is None or (only is not None and job.kind is not only):
                return False
            self.hold_motion()
            job.stopping = True
            job.stop_reason = reason
            if job.kind is Activity.PROGRAM:
                self.resume_point = None
                job.keep_point = keep_point
            return True

    def abandon(self, reason: str, keep_point: str | None = None) -> None:
        """End the job at once (the drives are stopped or stopping by themselves): E-stop, a
        fault, a disconnect. ``keep_point``: the cause to keep the point to resume from under."""
        with self._lock:
            job = self.job
            if job is not None and keep_point is not None:
                self.resume_point = job.resume_point(self.consumed(), keep_point)
            self.drop_job(completed=False, reason=reason)

    def _alarm_stop(self, cause: str, resumable: bool) -> None:
        with self._lock:
            job = self.job
            if job is not None:
                self.hold_motion()
                job.stopping = True
                job.stop_reason = cause
                self.resume_point = job.resume_point(self.consumed(), cause) if resumable else None
        if not resumable:
            self.resume_point = None

    def _reset(self, state: MachineState) -> None:
        """Reset keeps a program's point to resume from (after E-stop, an alarm, a stop or a
        pause): cycle start then asks to resume there or start again; the line shown goes."""
        if state is MachineState.HOLD:
            with self._lock:
                job = self.job
                if job is not None and job.kind is Activity.PROGRAM and job.origin is not None \
                        and self.resume_point is None:
                    self.resume_point = job.resume_point(self.consumed(), "reset")
            self.drop_job(completed=False, reason="reset")
        elif state is MachineState.IDLE:
            self.clear_line()

    def set_overrides(self, feed: float | None = None, rapid: float | None = None) -> None:
        """The operator's feed or rapid override (fractions) for the job and the one after it."""
        with self._lock:
            job = self.job
            if job is None:
                return
            if feed is not None and job.overrides and job.executor.feed_override != min(feed, SIGMA_MAX):
                self.change_motion(lambda ex: ex.set_overrides(feed=feed))
            if rapid is not None and job.overrides and job.executor.rapid_override != min(rapid, 1.0):
                self.change_motion(lambda ex: ex.set_overrides(rapid=rapid))
            nxt = job.then
            if nxt is not None and (feed is not None or nxt.overrides):
                nxt.executor.set_overrides(feed=feed, rapid=rapid)

    def continue_held(self, single_block: bool) -> str:
        """Cycle start in HOLD: go on after a feed hold, a single-block stop or M00/M01/M06 (a
        tool change: the tool is in; the spindle stays off until the program's M3/M4; a
        spindle the door stopped turns again, at speed before the motion goes on), with single
        block switched meanwhile planned again from here. "" when it goes on, else why not."""
        with self._lock:
            job = self.job
            if job is None:
                return "nothing to resume"
            if job.stopping:
                return "the program is being stopped"
            if (
                job.kind is Activity.PROGRAM
                and job.single_block != single_block
                and (job.executor.standing or job.waiting)
                and self.consumed() >= self.pushed_total
                and self._replan_here(job) is not None
            ):
                return ""
            wait = self._spindle.restart_after_hold() if job.executor.hold else 0.0
            snap = self._drives.last_snapshot
            if wait > 0.0 and snap is not None:     # the door stopped the spindle: at speed first
                job.resume_at_s = float(snap.time_s) + wait
                return ""
            job.executor.hold = False
            if job.pause is not None and job.waiting:
                if job.pause.kind is PauseKind.TOOL_CHANGE:      # the operator has put the tool in
                    self._tools.loaded_by_program(job.pause.payload_as(ToolNumber).number)
                self.release(job)
            return ""

    def _replan_here(self, job: Job) -> Job | None:
        """At a standstill on the path (hold or pause point): plan the rest of the program again
        from exactly here (single block switched on or off); the new plan starts at rest."""
        if job.origin is None:
            return None
        prog, base, u0 = job.origin
        ex = job.executor
        _, _, move, s_cum = ex.evaluate(np.array([ex.tau]))
        m = int(move[0])
        u = float(s_cum[0] - ex.move_start_s(m))
        index, u_orig = base + m, (u0 + u if m == 0 else u)
        if index >= len(prog.moves) - 1 and u_orig >= prog.moves[-1].length_mm - 1e-12:
            return None  # at the very end: nothing to re-plan
        try:
            return self.follow(job, remaining_program(prog, index, u_orig), (prog, index, u_orig))
        except PlannerError:
            return None

    def ramp_down(self, reason: str) -> bool:
        """Bring the job to a standstill on its path before the worker is stopped (the same
        jerk-limited stop as the operator's), keeping a program's point to resume from unless
        one is kept already. True when there is nothing to wait for (``still``)."""
        with self._lock:
            job = self.job
            if job is None or not self._drives.attached:
                return True
            if self._drives.state() is not WorkerState.ENABLED:
                return True  # the worker already stopped the drives (quick stop, fault)
            if job.kind is Activity.PROGRAM and job.origin is not None and self.resume_point is None:
                self.resume_point = job.resume_point(self.consumed(), reason)
            self.hold_motion()
            job.stopping = True
            job.stop_reason = job.stop_reason or reason
            return False

    def still(self, job_at_start: Job | None = None) -> bool:
        """Whether the job is at rest with nothing queued (or gone)."""
        with self._lock:
            job = self.job
            if job is None or not self._drives.attached or (job_at_start not in (None, job)):
                return True
            standing = job.executor.standing or job.pause is not None or job.executor.finished
            return standing and self._drives.buffer_level() == 0

    # ------------------------------------------------------------------ feeding
    @property
    def pushed_total(self) -> int:
        """The serial the next set-point pushed gets."""
        return self._queue.pushed_total

    @property
    def last_splice(self) -> SpliceInfo | None:
        return self._queue.last_splice

    @property
    def recent_splices(self) -> tuple[SpliceInfo, ...]:
        return tuple(self._queue.recent_splices)

    def feed(self, max_new: int | None = None) -> None:
        """Keep the worker's queue ``lead_s`` ahead (at most ``max_new`` set-points now)."""
        with self._lock:
            job = self.job
            if job is None or job.aborted or not self._drives.attached:
                return
            if self._drives.state() is not WorkerState.ENABLED:
                return
            for hook in self._feed_hooks:
                hook()                      # a probe's contact stops the motion from here
            if self.job is job:
                self._queue.feed(job, self._lead_samples, max_new)

    def change_motion(self, change: Callable[[TimeScaledExecutor], None]) -> None:
        """Apply ``change`` (hold, override) to the running job's executor from a serial a few
        cycles ahead of the drives, replacing the worker's queue from there (module docstring).
        Without a job nothing happens."""
        with self._lock:
            job = self.job
            if job is not None:
                self._queue.change(job, change, self._lead_samples)

    def _wait_for_spindle(self) -> None:
        """The spindle's speed changed under a running program or MDI block (its override): the
        feed holds along the path and goes on once the spindle reads its new speed (``poll``)."""
        job, snap = self.job, self._drives.last_snapshot
        if (job is not None and snap is not None and job.kind in (Activity.PROGRAM, Activity.MDI)
                and not job.executor.hold and job.resume_at_s is None):
            self.change_motion(lambda ex: setattr(ex, "hold", True))
            job.resume_at_s = float(snap.time_s)

    def hold_motion(self, wait_for_tap: bool = False) -> None:
        """The running job's executor to hold (sigma -> 0 / the time-optimal path stop), from a
        few cycles ahead of the drives (stop, STOP alarms, jog release, a probe's contact: at
        once; the operator's feed hold, ``wait_for_tap``: once a tap in the hole is out)."""
        with self._lock:
            job = self.job
            if job is not None:
                self._queue.hold(job, wait_for_tap, self._lead_samples)

    # ------------------------------------------------------------------ the poll
    def trace_drained(self, trace: TraceChunk) -> None:
        """A chunk of the worker's trace (the poll): the job's record and the sinks."""
        self._deliver(trace)
        job = self.job
        if job is not None and len(trace.cycle):
            job.trace.append((trace.cycle.copy(), trace.reference.copy(), trace.actual.copy()))

    def _deliver(self, trace: TraceChunk) -> None:
        if self._sinks and len(trace.cycle):
            offset = self._positions.home_offset
            reference, actual = trace.reference - offset, trace.actual - offset
            job = self.job
            lines = (job.lines_of(trace.serial) if job is not None and trace.serial is not None
                     else np.zeros(len(trace.cycle), dtype=np.int64))
            for sink in self._sinks:
                sink(trace.cycle, reference, actual, lines)

    def poll(self, snap: WorkerSnapshot) -> None:
        """The job as the drives run it (the poll): line, progress, notes, pause points, end."""
        job = self.job
        if job is None:
            return
        modes = self._modes
        if job.resume_at_s is not None and self._spindle.at_speed(float(snap.time_s), job.resume_at_s):
            job.resume_at_s = None
            self.change_motion(lambda ex: setattr(ex, "hold", False))
        consumed = int(snap.samples_consumed)
        self._ran_dry(job, consumed)
        info = job.info_at(consumed)
        if info is not None:
            line, tau = info
            # a stop that prompts the operator shows its own line (the M6), not the last move's
            if line != self.line and job.kind in (Activity.PROGRAM, Activity.MDI) and not job.waiting:
                self.line = line
                self._out.lineChanged.emit(line)
            if job.kind in (Activity.PROGRAM, Activity.MDI):
                # the DRO reads the tool tip in the program's own frame where the drives are
                self._coordinates.follow_program(job.frame_in_force(consumed))
            self.distance_to_go = job.distance_to_go(consumed, self._positions.reference_pos())
            while job.messages and job.messages[0][0] <= line:
                self.show_message(job.messages.popleft()[1])
            if job.kind is Activity.PROGRAM:
                t_end = job.executor.planned_end_s + job.time_offset_s
                tau_g = tau + job.tau_offset_s
                frac = min(tau_g / t_end, 1.0) if t_end > 0 else 1.0
                capped = job.executor.capped_to
                ovr = max(modes.feed_pct / 100.0 if capped is None else capped, 1e-3)
                remaining = max(t_end - tau_g, 0.0) / ovr + job.spin_ups_left(tau, float(snap.time_s))
                self.progress = (frac, remaining)
                self._out.progressChanged.emit(frac, remaining)
        capped = job.executor.capped_to
        if (capped is not None) != job.cap_reported:
            job.cap_reported = capped is not None
            if capped is not None:
                self._out.message.emit(f"feed override {modes.feed_pct:g} % capped at {100 * capped:.0f} % "
                                       "here: the machine's speed, acceleration or jerk limit")
        if job.spindle_locked is not None and (job.pause is None or consumed < job.pause_serial):
            self._spindle_lock_at(job, job.move_at(consumed))      # (a pause point sets it itself)
        off = job.executor.override_off_here and job.overrides and modes.feed_pct != 100.0
        if off != job.override_off_reported:
            job.override_off_reported = off
            if off:
                self._out.message.emit(f"feed override {modes.feed_pct:g} % not applied here: the program "
                                       "turned it off (tapping, M49 or M50 P0) and runs its own feed")
        self.set_feed_note("runs 100 %: program" if off else
                           f"runs {100 * capped:.0f} %: limits" if capped is not None else "")
        if snap.time_s - self._tracking_emit_t >= 1.0 and job.kind is Activity.PROGRAM:
            self._tracking_emit_t = snap.time_s
            self.tracking = tracking_report(snap, self._settings.config.axes, self.tracking.trace_path)
            self._out.trackingUpdated.emit(self.tracking)
        all_done = consumed >= self.pushed_total
        for hook in self._poll_hooks:
            hook(job, all_done)
        if self.job is not job:              # the probe's result: the rest runs as a new job
            return
        # pause points reached by the drives
        if job.pause is not None and consumed >= job.pause_serial:
            self._at_pause(job, job.pause, snap)
            return
        if job.stopping and job.executor.standing and all_done:
            self._finish_stop(job)

    def _ran_dry(self, job: Job, consumed: int) -> None:
        """The drives ran into the braking tail (the feeder fell behind): the job stops where
        the tail brought it to rest, with the alarm (resumable from there)."""
        with self._lock:
            ran = self._queue.ran_into_tail(job, max(self._drives.samples_consumed() or 0, consumed))
        if ran is not None:
            self._alarms.alarm_stop(
                f"the set-points ran out after {ran} (the control's process fell behind): the axes "
                "braked to rest along the path within their limits", "controller", "setpoints_ran_out")

    def _spindle_lock_at(self, job: Job, move: int | None) -> None:
        """The spindle override as the program wants it for ``move`` (off in a tap, after M49)."""
        locked = job.spindle_locked
        if locked is not None and job.overrides and move is not None and 0 <= move < len(locked):
            self._spindle.set_program_lock(bool(locked[move]))

    def set_feed_note(self, note: str) -> None:
        if note != self.feed_note:
            self.feed_note = note
            self._out.feedOverrideNote.emit(note)

    def _at_pause(self, job: Job, p: PausePoint, snap: WorkerSnapshot) -> None:
        kind = p.kind
        if kind is PauseKind.END:
            self._finish_job(job, snap)
            return
        if job.stopping:
            self._finish_stop(job)
            return
        if job.spinup_until is not None:      # a spindle started here: on at speed first
            if self._spindle.at_speed(float(snap.time_s), job.spinup_until):
                job.spinup_until = None
                self.release(job)
            return
        handler = self._pauses.get(kind)
        if kind is PauseKind.SPINDLE:
            speed = p.payload_as(SpindleSpeed)
            self.start_spindle(job, SpindleState(speed.direction, speed.rpm), float(snap.time_s))
        elif kind is PauseKind.TAPPING:          # a tap's overrides change here, at rest
            self._spindle_lock_at(job, p.move + 1)
            self.release(job)
        elif kind is PauseKind.DWELL:
            if job.dwell_until is None:
                job.dwell_until = snap.time_s + p.payload_as(Dwell).seconds
                job.dwell_total_s += p.payload_as(Dwell).seconds
            elif snap.time_s >= job.dwell_until:
                job.dwell_until = None
                self.release(job)
        elif handler is not None:
            if handler(job, p, snap):
                self.release(job)
        elif kind is PauseKind.OPTIONAL_PAUSE and not self._modes.optional_stop:
            self.release(job)
        elif not job.waiting:
            self._operator_stop(job, p)

    def _operator_stop(self, job: Job, p: PausePoint) -> None:
        """A stop that waits for the operator's cycle start (M00, M01, M06, single block)."""
        job.waiting = True
        kind = p.kind
        if kind is PauseKind.TOOL_CHANGE and self._spindle.spindle.on:
            # hands go near the spindle: it stops and stays stopped until the program's own
            # M3/M4 (LinuxCNC's M6: STOP_SPINDLE_TURNING, CHANGE_TOOL; the program's M6 stops
            # it first, this is the guard for a spindle the operator started meanwhile)
            self._spindle.stop_spindle()
        tool = p.payload_as(ToolNumber).number if kind is PauseKind.TOOL_CHANGE else 0
        reason = why_stopped(kind, p.line, self._tools.table.label(tool),
                             bool(self._settings.config.machine.after_tool_change))
        hold = _OPERATOR_STOPS.get(kind, HoldKind.FEED_HOLD)
        if p.line > 0 and p.line != self.line:   # the line that stopped, not the next one
            self.line = p.line
            self._out.lineChanged.emit(p.line)
        self._states.set_state(MachineState.HOLD, reason, hold, Prompt(hold, p.line, tool, reason))

    def start_spindle(self, job: Job, sp: SpindleState, now_s: float) -> None:
        """Switch the spindle at a pause point (a program's M3/M4/M5/S, or back after a tool
        change); when it starts, reverses or speeds up, the motion waits ``spindle_spinup_s``
        there before it goes on, else it goes on at once."""
        wait = self._spindle.spin_up_s(sp)
        self._spindle.apply_spindle(sp)
        job.waiting = False
        if wait > 0.0:
            job.spinup_until = now_s + wait
            job.dwell_total_s += wait
        else:
            self.release(job)

    def release(self, job: Job) -> None:
        with self._lock:
            job.waiting = False
            self._queue.release(job)

    def count_wait(self, job: Job, seconds: float) -> None:
        """A wait at a pause point (M66) counts in the run's time, as a dwell does."""
        job.dwell_total_s += seconds

    def show_message(self, text: str) -> None:
        """A program's message for the operator: the status line and the alarm log (information)."""
        self._out.message.emit(text)
        self._alarms.raise_alarm("program", text, Severity.INFO, "program_message")

    # ------------------------------------------------------------------ the end of a job
    def _finish_stop(self, job: Job) -> None:
        self.drop_job(completed=False, reason=job.stop_reason or "stopped")
        # the axes stand: now the spindle may stop too (stopping it while the tool still moves
        # along the path would drag a standing cutter through the material)
        self._spindle.stop_spindle()
        if self._states.state is not MachineState.ALARM:
            self._states.set_state(MachineState.IDLE, job.stop_reason or "stopped")

    def _finish_job(self, job: Job, snap: WorkerSnapshot | None) -> None:
        while job.messages:                      # messages after the last move (before M2)
            self.show_message(job.messages.popleft()[1])
        nxt = job.then
        completed_summary = self.drop_job(completed=True, reason="completed", snap=snap)
        if nxt is not None:
            self.start_job(nxt)
            return
        if job.kind is Activity.PROGRAM:
            self._spindle.stop_spindle()      # program end: spindle off (M2/M30 or the last line)
        self._states.set_state(MachineState.IDLE, "program end" if completed_summary else "done")
        if job.when_done is not None:
            job.when_done(job)

    def drop_job(self, completed: bool, reason: str, snap: WorkerSnapshot | None = None) -> RunSummary | None:
        """End the current job. Emits programFinished for program jobs."""
        with self._lock:
            job, self.job = self.job, None
            self.distance_to_go = ()
            if job is None:
                return None
            if (not completed and job.keep_point and job.kind is Activity.PROGRAM and job.origin is not None
                    and self.resume_point is None):
                # the operator's stop: where the drives came to rest
                self.resume_point = job.resume_point(self.consumed(), job.stop_reason)
            job.aborted = True
            self._spindle.set_program_lock(False)
            self.set_feed_note("")
            for hook in self._end_hooks:
                hook()
            if not completed:
                self._drives.flush()
        if job.kind in (Activity.PROGRAM, Activity.MDI) and job.then is None:
            # what the program leaves in force (the tool length offset) stays, as in LinuxCNC
            self._coordinates.program_left(*job.left_at(self.consumed(), completed))
        if job.kind is not Activity.PROGRAM:
            return None
        last_line = self.line
        if completed and job.then is None:
            self.resume_point = None
            self.line = 0
        if snap is None:
            snap = self._drives.last_snapshot
        # motion time: set-points sent (holds included) plus dwells; waits for the operator excluded
        measured = job.samples * job.plan.ts_s + job.dwell_total_s
        axes, alarm = self._settings.config.axes, self._alarms.raise_alarm
        trace_path = save_trace(job, self._trace_path, self._positions.home_offset, axes, job.plan.ts_s,
                                lambda why: alarm("persistence", why, Severity.WARNING, "trace"))
        tracking = (tracking_report(snap, axes, trace_path or self.tracking.trace_path) if snap is not None
                    else TrackingReport())
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
        self._out.trackingUpdated.emit(tracking)
        if completed:
            self._out.progressChanged.emit(1.0, 0.0)
        self._out.programFinished.emit(summary)
        return summary

