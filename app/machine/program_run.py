"""Program commands: cycle start, feed hold, resume, stop, single block,
optional stop, run from line, feed and rapid override (loading: ``app.machine.program_load``).
Part of ``MachineController`` (mixed in).
"""

from __future__ import annotations

import numpy as np

from app.machine.jobs import Job, ResumePoint
from app.machine.model import (
    Activity,
    CommandResult,
    MachineState,
    Severity,
    SpindleState,
)
from planner.errors import PlannerError
from planner.program import Program
from planner.resume import (
    approach_moves,
    locate,
    modal_state_before_move,
    program_from_moves,
    remaining_program,
)

__all__ = ["ProgramMixin"]


class ProgramMixin:
    """Start, hold, resume, stop, run from line, overrides (loading: ``LoadMixin``).

    Mixed into ``MachineController``, which holds the state.
    """

    def _fresh_program(self, action: str, wait: bool) -> Program | str | CommandResult:
        """The loaded program when it is still valid (same configuration and offsets, the
        machine where it was interpreted from), else it is checked again: with ``wait`` here
        (the synchronous path: headless use), otherwise in the worker thread (the caller is
        refused; cycle start is possible once ``programLoaded`` follows). Returns the program
        or the reason for refusing ``action``."""
        info = self._program_info
        if info is None:
            return "no program loaded"
        stale = self._program_stale()
        if stale:
            if not self._recheck_program(wait):
                return "the program no longer passes its checks (see the errors)"
            if not wait:
                if action == "cycle_start":
                    return self._start_when_ready(f"{stale}: {info.name} is being checked again")
                return f"{stale}: {info.name} is being checked again (press run from line when it is loaded)"
            info = self._program_info
            assert info is not None
        return info.program  # type: ignore[return-value]

    def _start_when_ready(self, why: str) -> CommandResult:
        """Cycle start pressed while the program must first be checked or planned again in the
        worker thread: accept the press and start by itself once that is done (``_pending_start``
        is cleared by a failed check, a new load, stop, reset, E-stop or any state change).
        An operator presses cycle start once."""
        self._start_pending = True
        self.message.emit(f"{why}; it starts when ready")
        return self._ok("cycle_start")

    def _pending_start(self) -> None:
        """Called when a background check or plan has finished: start if a press is waiting."""
        if self._start_pending and self._load_request is None and self._run_plan_request is None:
            self._start_pending = False
            self.cycle_start()

    def cycle_start(self, *, wait: bool = False) -> CommandResult:
        """Start the loaded program from its beginning (IDLE), or continue (HOLD). Needs homed
        axes (unless the configuration says otherwise) and no active alarm of severity STOP or
        above. Runs the plan made at load time; when the configuration, the work offsets or
        the machine position changed since loading, the program is checked again first, and
        with single block on its single-block plan is made first: both in a worker thread
        (refused meanwhile with the reason; ``loadingChanged``), or here with ``wait=True``
        (headless use).
        """
        if self._state is MachineState.HOLD:
            return self.resume()
        if wait:  # headless: finish a load or a single-block plan under way first
            if self._load_request is not None:
                self.wait_loaded(None)
            self.wait_run_plan(None)
        why = self.refusal("cycle_start")
        if why:
            return self._refuse("cycle_start", why)
        if any(a.active and a.severity >= Severity.STOP for a in self._alarms):
            return self._refuse("cycle_start", "acknowledge the active alarms first")
        prog = self._fresh_program("cycle_start", wait)
        if isinstance(prog, CommandResult):  # accepted: starts once checked again
            return prog
        if isinstance(prog, str):
            return self._refuse("cycle_start", prog)
        info = self._program_info
        assert info is not None
        single = self._single_block
        plan = self._run_plan(single)
        if plan is None and not wait:
            self._start_run_plan(single)
            return self._start_when_ready(f"{info.name} is being planned for single block")
        try:
            job = self._make_job(Activity.PROGRAM, prog, info.name, single_block=single, plan=plan)
        except PlannerError as exc:
            return self._refuse("cycle_start", f"planner: {exc}")
        job.origin = (prog, 0, 0.0)
        self._resume = None
        self._line = 0
        self._start_job(job)
        return self._ok("cycle_start")

    def feed_hold(self) -> CommandResult:
        """Jerk-limited stop along the path (time-optimal, ``planner.stopping``, or the time
        scale to 0 where that would exceed a limit): RUNNING -> HOLD. The stop starts a few
        cycles (``SPLICE_MARGIN_S``) after the request: the set-points queued in the worker
        beyond that are replaced (``FeederMixin._change_motion``), not run first.
        """
        why = self.refusal("feed_hold")
        if why:
            return self._refuse("feed_hold", why)
        with self._lock:
            job = self._job
            if job is None:
                return self._refuse("feed_hold", "nothing is moving")
            self._hold_motion()
        self._set_state(MachineState.HOLD, "feed hold")
        return self._ok("feed_hold")

    def resume(self) -> CommandResult:
        """HOLD -> RUNNING: continue after a feed hold, a single-block stop or M00/M01/M06 to the
        same end. In IDLE after a fault or E-stop mid-program: move safely to the point where the
        program stopped (``resume_line``) and continue from exactly there.
        """
        why = self.refusal("resume")
        if why:
            return self._refuse("resume", why)
        if self._state is MachineState.IDLE and self._resume is not None:
            return self._resume_from_point(self._resume)
        with self._lock:
            job = self._job
            if job is None:
                return self._refuse("resume", "nothing to resume")
            if job.stopping:
                return self._refuse("resume", "the program is being stopped")
            if (
                job.kind is Activity.PROGRAM
                and job.single_block != self._single_block
                and (job.executor.standing or job.waiting)
                and self._consumed() >= self._pushed_total
            ):
                replanned = self._replan_here(job)
                if replanned is not None:
                    self._set_state(MachineState.RUNNING, "program")
                    return self._ok("resume")
            job.executor.hold = False
            if job.pause is not None and job.waiting:
                job.pause = None
                job.waiting = False
                job.executor.release_pause()
        self._set_state(MachineState.RUNNING, job.kind.value)
        return self._ok("resume")

    def _replan_here(self, job: Job) -> Job | None:
        """At a standstill on the path (hold or pause point): plan the rest of the program again
        from exactly here (single block switched on or off); the new plan starts at rest."""
        if job.origin is None:
            return None
        prog, base, u0 = job.origin
        ex = job.executor
        _, _, move, s_cum = ex.evaluate(np.array([ex.tau]))
        m = int(move[0])
        u = float(s_cum[0] - job.plan.segment.s0[m])
        index, u_orig = base + m, (u0 + u if m == 0 else u)
        if index >= len(prog.moves) - 1 and u_orig >= prog.moves[-1].length_mm - 1e-12:
            return None  # at the very end: nothing to re-plan
        try:
            rest = remaining_program(prog, index, u_orig)
            new = self._make_job(Activity.PROGRAM, rest, job.name, single_block=self._single_block)
        except PlannerError:
            return None
        full_t = self._program_info.cycle_time_s if self._program_info else new.estimated_s
        new.tau_offset_s = new.time_offset_s = max(full_t - new.executor.t_end, 0.0)
        new.origin = (prog, index, u_orig)
        new.start_time_s = job.start_time_s
        new.trace = job.trace
        new.samples, new.dwell_total_s = job.samples, job.dwell_total_s
        new.carried_limits = job.meter.final()
        new.estimated_s = job.estimated_s
        new.serial_base = job.serial_base
        self._job = new
        if self._worker_mode != "manual":
            self._feed()
        return new

    def stop(self) -> CommandResult:
        """Jerk-limited stop along the path, then abandon the program (-> IDLE). In IDLE it
        cancels a cycle start that waits for the program to be checked again."""
        if self._start_pending and self._state is MachineState.IDLE:
            self._start_pending = False
            return self._ok("stop")
        if self._state not in (MachineState.RUNNING, MachineState.HOLD, MachineState.HOMING):
            return self._refuse("stop", f"nothing to stop: machine is {self._state.label.lower()}")
        if self._state is MachineState.HOMING:
            return self._refuse("stop", "homing cannot be stopped mid-way: use E-stop")
        with self._lock:
            job = self._job
            if job is not None:
                self._hold_motion()
                job.stopping = True
                job.stop_reason = "stopped by the operator"
                if job.kind is Activity.PROGRAM:
                    self._resume = None
        if job is None:
            self._set_state(MachineState.IDLE, "stopped")
        elif self._state is MachineState.RUNNING:
            self._set_state(MachineState.HOLD, "stopping")
        return self._ok("stop")

    def set_single_block(self, on: bool) -> CommandResult:
        """Single block: the plan stops at every block end (HOLD there; cycle start goes on).
        Switched while running, it takes effect at the next standstill (feed hold, pause point):
        the rest of the program is planned again from there."""
        self._single_block = bool(on)
        if self._single_block and self._job is None and self._program_info is not None \
                and not self._program_stale() and self._load_request is None:
            self._start_run_plan(True)  # ready by the time cycle start is pressed
        self.modesChanged.emit(self._single_block, self._optional_stop)
        if self._job is not None and self._job.kind is Activity.PROGRAM:
            self.message.emit("single block takes effect at the next stop (feed hold, block end, M00)")
        return self._ok("set_single_block")

    def set_optional_stop(self, on: bool) -> CommandResult:
        """Honour M01 (optional pause); may change while running."""
        self._optional_stop = bool(on)
        self.modesChanged.emit(self._single_block, self._optional_stop)
        return self._ok("set_optional_stop")

    def run_from_line(self, line: int, *, wait: bool = False) -> CommandResult:
        """Start the loaded program at source line ``line``: the spindle as of that line is
        restored, a safe approach (retract Z to the higher of the current and target heights,
        move the other axes, then down) brings the tool to the line's start point, then the
        program runs on from there. As cycle start, a program stale since loading is checked
        again first (in the worker thread, refused meanwhile; here with ``wait=True``).
        """
        if wait and self._load_request is not None:
            self.wait_loaded(None)
        why = self.refusal("run_from_line")
        if why:
            return self._refuse("run_from_line", why)
        prog = self._fresh_program("run_from_line", wait)
        if isinstance(prog, str):
            return self._refuse("run_from_line", prog)
        try:
            i = locate(prog, int(line))
        except PlannerError as exc:
            return self._refuse("run_from_line", str(exc))
        point = ResumePoint(
            program=prog, move_index=i, u_mm=0.0, line=prog.moves[i].line, cause=f"run from line {line}"
        )
        return self._resume_from_point(point, action="run_from_line")

    def _resume_from_point(self, point: ResumePoint, action: str = "resume") -> CommandResult:
        if self._cfg.homing.required and not all(self._homed):
            return self._refuse(action, "axes not homed")
        if any(a.active and a.severity >= Severity.STOP for a in self._alarms):
            return self._refuse(action, "acknowledge the active alarms first")
        prog = point.program
        try:
            rest = remaining_program(prog, point.move_index, point.u_mm)
        except PlannerError as exc:
            return self._refuse(action, str(exc))
        modal = modal_state_before_move(prog, point.move_index)
        spindle = SpindleState(direction=int(np.sign(modal.spindle_rpm)), rpm=abs(modal.spindle_rpm))
        cur = self._machine_pos()
        retract = "Z" if "Z" in self._cfg.axes else ""
        moves = approach_moves(cur, rest.start_position, self._cfg.axes, self._cfg.machine.rotary, retract)
        name = self._program_info.name if self._program_info else prog.name
        try:
            main = self._make_job(Activity.PROGRAM, rest, name, single_block=self._single_block)
        except PlannerError as exc:
            return self._refuse(action, f"planner: {exc}")
        # progress relative to the whole program
        full_t = self._program_info.cycle_time_s if self._program_info else main.estimated_s
        main.tau_offset_s = max(full_t - main.executor.t_end, 0.0)
        main.time_offset_s = main.tau_offset_s
        main.origin = (prog, point.move_index, point.u_mm)
        main.spindle_before = spindle
        self._resume = None
        self._line = point.line
        if moves:
            approach = program_from_moves(prog, moves, [], cur, name="approach")
            issues = self._check_program_limits(approach)
            if issues:
                return self._refuse(action, f"approach move: soft limit: {issues[0]}")
            job = self._make_job(Activity.APPROACH, approach, "approach", overrides=True)
            job.then = main
            self._start_job(job)
        else:
            self._apply_spindle(spindle)
            self._start_job(main)
        return self._ok(action)

    @property
    def resume_line(self) -> int:
        """Line a resume (after a fault or E-stop mid-program) would continue from, 0 if none."""
        return self._resume.line if self._resume is not None else 0

    def set_feed_override(self, percent: float) -> CommandResult:
        """Feed override 0-150 %, applied while running without a jump and within every limit
        (``app.machine.timescale``); above 100 % the speed stays capped by the machine limits.
        """
        p = float(percent)
        if not 0.0 <= p <= 150.0:
            return self._refuse("set_feed_override", f"feed override must be 0-150 %, got {p:g}")
        self._feed_pct = p
        with self._lock:
            job = self._job
            if job is not None and job.overrides and job.executor.feed_override != min(p / 100.0, 1.5):
                self._change_motion(lambda ex: ex.set_overrides(feed=p / 100.0))
            if self._job is not None and self._job.then is not None:
                self._job.then.executor.set_overrides(feed=p / 100.0)
        self.overridesChanged.emit(self._feed_pct, self._rapid_pct)
        return self._ok("set_feed_override")

    def set_rapid_override(self, percent: float) -> CommandResult:
        """Rapid override 0-100 % (rapid moves only), applied like the feed override."""
        p = float(percent)
        if not 0.0 <= p <= 100.0:
            return self._refuse("set_rapid_override", f"rapid override must be 0-100 %, got {p:g}")
        self._rapid_pct = p
        with self._lock:
            job = self._job
            if job is not None and job.overrides and job.executor.rapid_override != min(p / 100.0, 1.0):
                self._change_motion(lambda ex: ex.set_overrides(rapid=p / 100.0))
            if job is not None and job.then is not None and job.then.overrides:
                job.then.executor.set_overrides(rapid=p / 100.0)
        self.overridesChanged.emit(self._feed_pct, self._rapid_pct)
        return self._ok("set_rapid_override")
