"""Program commands: cycle start, feed hold, resume, stop, single block,
optional stop, run from line, feed and rapid override (loading: ``app.machine.program_load``).
A part of ``MachineController``.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from app.machine.jobs import Job, ResumePoint
from app.machine.model import (
    Activity,
    CommandResult,
    HoldKind,
    MachineState,
    Severity,
)
from app.machine.timescale import SIGMA_MAX
from planner.errors import PlannerError
from planner.program import Event, EventKind, Program
from planner.resume import (
    Approach,
    approach_moves,
    last_safe_height,
    locate,
    modal_state_before_move,
    probe_move_at,
    program_from_moves,
    reads_before,
    remaining_program,
)

if TYPE_CHECKING:
    from app.machine.controller import MachineController

__all__ = ["ProgramRunner"]


class ProgramRunner:
    """Start, hold, resume, stop, run from line, overrides (loading: ``ProgramLoader``).

    A part of ``MachineController`` (``controller.run``): it owns the state set up in
    ``__init__`` and reaches the other parts through the facade ``m``.
    """

    def __init__(self, m: MachineController) -> None:
        self.m = m
        self.feed_pct = 100.0
        self.rapid_pct = 100.0
        self.single_block = False
        self.optional_stop = False
        # lines starting with '/' skipped; off as LinuxCNC starts. The program is read whole
        # before it runs, so the switch changes the program loaded: it is read again
        self.block_delete = False
        self.resume_point: ResumePoint | None = None
        self.start_pending = False  # cycle start pressed while the program is checked again
        self.pending_line = 0       # ... or run from this line

    def _fresh_program(self, action: str, wait: bool) -> Program | str | CommandResult:
        """The loaded program when it is still valid (same configuration and offsets, the
        machine where it was interpreted from), else it is checked again: with ``wait`` here
        (the synchronous path: headless use), otherwise in the worker thread (the caller is
        refused; cycle start is possible once ``programLoaded`` follows). Returns the program
        or the reason for refusing ``action``."""
        info = self.m.loader.program_info
        if info is None:
            return "no program loaded"
        stale = self.m.loader.program_stale()
        if stale:
            if not self.m.loader.recheck_program(wait):
                return "the program no longer passes its checks (see the errors)"
            if not wait:
                return self._start_when_ready(f"{stale}: {info.name} is being checked again",
                                              action)
            info = self.m.loader.program_info
            assert info is not None
        return info.program  # type: ignore[return-value]

    def _start_when_ready(self, why: str, action: str = "cycle_start") -> CommandResult:
        """Cycle start or run from line pressed while the program must first be checked or
        planned again in the worker thread: accept the press and start by itself once that is
        done (``start_pending`` is cleared by a failed check, a new load, stop, reset, E-stop or
        any state change). An operator presses once."""
        self.start_pending = True
        if action != "run_from_line":
            self.pending_line = 0
        self.m.message.emit(f"{why}; it starts when ready")
        return self.m.states.ok(action)

    def pending_start(self) -> None:
        """Called when a background check or plan has finished: start if a press is waiting."""
        if (
            self.start_pending
            and self.m.loader.load_request is None
            and self.m.loader.run_plan_request is None
        ):
            self.start_pending = False
            line, self.pending_line = self.pending_line, 0
            if line:
                self.run_from_line(line)
            else:
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
        if self.m.states.state is MachineState.HOLD:
            return self.resume()
        if wait:  # headless: finish a load or a single-block plan under way first
            if self.m.loader.load_request is not None:
                self.m.loader.wait_loaded(None)
            self.m.loader.wait_run_plan(None)
        why = self.m.states.refusal("cycle_start")
        if why:
            return self.m.states.refuse("cycle_start", why)
        if any(a.active and a.severity >= Severity.STOP for a in self.m.alarm_log.alarms):
            return self.m.states.refuse("cycle_start", "acknowledge the active alarms first")
        prog = self._fresh_program("cycle_start", wait)
        if isinstance(prog, CommandResult):  # accepted: starts once checked again
            return prog
        if isinstance(prog, str):
            return self.m.states.refuse("cycle_start", prog)
        info = self.m.loader.program_info
        assert info is not None
        single = self.single_block
        plan = self.m.loader.run_plan(single)
        if plan is None and not wait:
            self.m.loader.start_run_plan(single)
            return self._start_when_ready(f"{info.name} is being planned for single block")
        try:
            job = self.m.stream.make_job(Activity.PROGRAM, prog, info.name, single_block=single, plan=plan,
                                         stops=None if single else info.stops)
        except PlannerError as exc:
            return self.m.states.refuse("cycle_start", f"planner: {exc}")
        job.origin = (prog, 0, 0.0)
        self.resume_point = None
        self.m.stream.line = 0
        self.m.stream.start_job(job)
        return self.m.states.ok("cycle_start")

    def feed_hold(self) -> CommandResult:
        """Jerk-limited stop along the path (time-optimal, ``planner.stopping``, or the time
        scale to 0 where that would exceed a limit): RUNNING -> HOLD. The stop starts a few
        cycles (``SPLICE_MARGIN_S``) after the request: the set-points queued in the worker
        beyond that are replaced (``Streamer.change_motion``), not run first. In a tap (G74,
        G84, G33.1) the stop waits until the tap is out of the hole, where it ends at rest.
        """
        why = self.m.states.refusal("feed_hold")
        if why:
            return self.m.states.refuse("feed_hold", why)
        with self.m._lock:
            job = self.m.stream.job
            if job is None:
                return self.m.states.refuse("feed_hold", "nothing is moving")
            self.m.stream.hold_motion(wait_for_tap=True)
            waits = job.executor.hold_deferred
        # the operator sees why the axes go on: the hold takes effect where the tap has ended
        reason = "feed hold: the tap runs out of the hole first" if waits else "feed hold"
        self.m.states.set_state(MachineState.HOLD, reason, HoldKind.FEED_HOLD)
        return self.m.states.ok("feed_hold")

    def resume(self) -> CommandResult:
        """HOLD -> RUNNING: continue after a feed hold, a single-block stop or M00/M01/M06 to the
        same end. In IDLE after a fault or E-stop mid-program: move safely to the point where the
        program stopped (``resume_line``) and continue from exactly there.
        """
        why = self.m.states.refusal("resume")
        if why:
            return self.m.states.refuse("resume", why)
        if self.m.states.state is MachineState.IDLE and self.resume_point is not None:
            return self._resume_from_point(self.resume_point)
        with self.m._lock:
            job = self.m.stream.job
            if job is None:
                return self.m.states.refuse("resume", "nothing to resume")
            if job.stopping:
                return self.m.states.refuse("resume", "the program is being stopped")
            if (
                job.kind is Activity.PROGRAM
                and job.single_block != self.single_block
                and (job.executor.standing or job.waiting)
                and self.m.stream.consumed() >= self.m.stream.pushed_total
            ):
                replanned = self._replan_here(job)
                if replanned is not None:
                    self.m.states.set_state(MachineState.RUNNING, "program")
                    return self.m.states.ok("resume")
            job.executor.hold = False
            if job.pause is not None and job.waiting:
                if job.pause.kind == "tool_change":      # the operator has put the tool in
                    self.m.tools.loaded_by_program(int(job.pause.value))
                # back from a tool change: the spindle as it was, at speed before moving on
                paused, job.spindle_paused = job.spindle_paused, None
                if paused is not None:
                    self.m.stream.start_spindle(job, paused, float(self.m.conn.snapshot_now().time_s))
                else:
                    self.m.stream.release(job)
        self.m.states.set_state(MachineState.RUNNING, job.kind.value)
        return self.m.states.ok("resume")

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
            return self.m.stream.follow(job, remaining_program(prog, index, u_orig), (prog, index, u_orig))
        except PlannerError:
            return None

    def stop(self) -> CommandResult:
        """Jerk-limited stop along the path, then abandon the program (-> IDLE). In IDLE it
        cancels a cycle start that waits for the program to be checked again."""
        if self.start_pending and self.m.states.state is MachineState.IDLE:
            self.start_pending = False
            return self.m.states.ok("stop")
        if self.m.states.state not in (MachineState.RUNNING, MachineState.HOLD, MachineState.HOMING):
            return self.m.states.refuse(
                "stop", f"nothing to stop: machine is {self.m.states.state.label.lower()}"
            )
        if self.m.states.state is MachineState.HOMING:
            return self.m.states.refuse("stop", "homing cannot be stopped mid-way: use E-stop")
        with self.m._lock:
            job = self.m.stream.job
            if job is not None:
                self.m.stream.hold_motion()
                job.stopping = True
                job.stop_reason = "stopped by the operator"
                if job.kind is Activity.PROGRAM:
                    self.resume_point = None
        if job is None:
            self.m.states.set_state(MachineState.IDLE, "stopped")
        elif self.m.states.state is MachineState.RUNNING:
            self.m.states.set_state(MachineState.HOLD, "stopping", HoldKind.STOPPING)
        return self.m.states.ok("stop")

    def set_single_block(self, on: bool) -> CommandResult:
        """Single block: the plan stops at every block end (HOLD there; cycle start goes on).
        Switched while running, it takes effect at the next standstill (feed hold, pause point):
        the rest of the program is planned again from there."""
        self.single_block = bool(on)
        if (
            self.single_block
            and self.m.stream.job is None
            and self.m.loader.program_info is not None
            and not self.m.loader.program_stale()
            and self.m.loader.load_request is None
        ):
            self.m.loader.start_run_plan(True)  # ready by the time cycle start is pressed
        self.m.modesChanged.emit(self.single_block, self.optional_stop, self.block_delete)
        if self.m.stream.job is not None and self.m.stream.job.kind is Activity.PROGRAM:
            self.m.message.emit("single block takes effect at the next stop (feed hold, block end, M00)")
        return self.m.states.ok("set_single_block")

    def set_optional_stop(self, on: bool) -> CommandResult:
        """Honour M01 (optional pause); may change while running."""
        self.optional_stop = bool(on)
        self.m.modesChanged.emit(self.single_block, self.optional_stop, self.block_delete)
        return self.m.states.ok("set_optional_stop")

    def set_block_delete(self, on: bool) -> CommandResult:
        """Block delete: lines starting with '/' are skipped (on) or run (off). The program is
        read whole before it runs, so the switch cannot change a run under way: refused while a
        program or MDI runs or holds. A loaded program is checked again with it (the preview
        then shows the path it gives), as after an offset change."""
        on = bool(on)
        if on == self.block_delete:
            return self.m.states.ok("set_block_delete")
        if self.m.stream.job is not None:
            self.m.modesChanged.emit(self.single_block, self.optional_stop, self.block_delete)
            return self.m.states.refuse("set_block_delete", "block delete changes which lines the program "
                                        "has: switch it before cycle start, not during a run")
        self.block_delete = on
        self.m.modesChanged.emit(self.single_block, self.optional_stop, self.block_delete)
        loader = self.m.loader
        if loader.program_info is not None and loader.load_request is None:
            loader.recheck_program(wait=False)
        return self.m.states.ok("set_block_delete")

    def run_from_line(self, line: int, *, wait: bool = False) -> CommandResult:
        """Start the loaded program at source line ``line``: a safe approach (up to the restart
        clearance, across, the spindle as of that line started and at speed, down to the
        program's retract plane, then at feed to the line's start point) and the program runs
        on from there. As cycle start, a program stale since loading is checked again first: in
        the worker thread, and the run starts by itself when it passes (here with ``wait=True``).
        """
        if wait and self.m.loader.load_request is not None:
            self.m.loader.wait_loaded(None)
        why = self.m.states.refusal("run_from_line")
        if why:
            return self.m.states.refuse("run_from_line", why)
        self.pending_line = int(line)
        prog = self._fresh_program("run_from_line", wait)
        if isinstance(prog, CommandResult):
            return prog          # checked again first; it starts from the line when ready
        self.pending_line = 0
        if isinstance(prog, str):
            return self.m.states.refuse("run_from_line", prog)
        try:
            i = locate(prog, int(line))
        except PlannerError as exc:
            return self.m.states.refuse("run_from_line", str(exc))
        point = ResumePoint(
            program=prog, move_index=i, u_mm=0.0, line=prog.moves[i].line, cause=f"run from line {line}"
        )
        return self._resume_from_point(point, action="run_from_line")

    def _resume_from_point(self, point: ResumePoint, action: str = "resume") -> CommandResult:
        if self.m.config.homing.required and not all(self.m.pos.homed):
            return self.m.states.refuse(action, "axes not homed")
        if any(a.active and a.severity >= Severity.STOP for a in self.m.alarm_log.alarms):
            return self.m.states.refuse(action, "acknowledge the active alarms first")
        prog = point.program
        reads = reads_before(prog, point.move_index, point.line)
        if action == "run_from_line" and reads:
            first = reads[0]
            what = "the probe" if first.kind is EventKind.PROBE else "M66"
            return self.m.states.refuse(
                action, f"line {point.line} comes after {what} at line {first.line}: what follows depends on "
                        f"what it read; run from line {first.line} (or before) to read it again")
        probing = probe_move_at(prog, point.move_index)
        if probing is not None and point.u_mm > 0.0:
            # stopped during a probe move: it starts again from its start, the probe armed there
            point = replace(point, u_mm=0.0, line=probing.line)
        try:
            rest = remaining_program(prog, point.move_index, point.u_mm, line=point.line)
        except PlannerError as exc:
            return self.m.states.refuse(action, str(exc))
        modal = modal_state_before_move(prog, point.move_index)
        loads = (EventKind.TOOL_CHANGE, EventKind.TOOL_SET)
        changes = [e for e in prog.events if e.kind in loads and e.after_move < point.move_index]
        if changes and int(changes[-1].value) != self.m.tools.in_spindle:
            # the program from here was checked with that tool's length: never cut with another
            need, have = int(changes[-1].value), self.m.tools.in_spindle
            return self.m.states.refuse(
                action, f"line {point.line} needs T{need} in the spindle (T{have} is in it): put it in and "
                        f"set it on the Tools page, or run from the M6 line {changes[-1].line}")
        cur = np.asarray(self.m.states.machine_pos(), dtype=float)
        try:
            approach = self._approach(prog, point.move_index, cur, rest.start_position, modal.feed_mm_s)
        except PlannerError as exc:
            return self.m.states.refuse(action, f"approach move: {exc}")
        # the spindle as of the restart point, on (and at speed) before the tool goes below the
        # clearance height: in the approach after its last move at the top, or first thing
        spindle_event = Event(EventKind.SPINDLE, point.line, approach.spindle_after, float(modal.spindle_rpm))
        way = None
        if approach.moves:
            way = program_from_moves(prog, list(approach.moves), [spindle_event], cur, name="approach")
            issues = self.m.loader.check_program_limits(way)
            if issues:
                return self.m.states.refuse(action, f"approach move: soft limit: {issues[0]}")
        else:
            rest = replace(rest, events=(spindle_event, *rest.events))
        name = self.m.loader.program_info.name if self.m.loader.program_info else prog.name
        info = self.m.loader.program_info
        # a long rest is planned as it runs: its time estimated by the share of moves left
        left = 1.0 - point.move_index / max(len(prog.moves), 1)
        try:
            main = self.m.stream.make_job(Activity.PROGRAM, rest, name, single_block=self.single_block,
                                          estimate_s=info.cycle_time_s * left if info else math.nan)
        except PlannerError as exc:
            return self.m.states.refuse(action, f"planner: {exc}")
        # progress relative to the whole program
        full_t = info.cycle_time_s if info else main.estimated_s
        main.tau_offset_s = max(full_t - main.executor.planned_end_s, 0.0)
        main.time_offset_s = main.tau_offset_s
        main.origin = (prog, point.move_index, point.u_mm)
        main.probe_results, main.wait_results = point.probe_results, point.wait_results
        self.resume_point = None
        self.m.stream.line = point.line
        if way is not None:
            job = self.m.stream.make_job(Activity.APPROACH, way, "approach", overrides=True)
            job.then = main
            self.m.stream.start_job(job)
        else:
            self.m.stream.start_job(main)
        return self.m.states.ok(action)

    def _approach(self, prog: Program, move_index: int, cur: np.ndarray, target: np.ndarray,
                  feed_mm_s: float) -> Approach:
        """Up to the restart clearance, across, down to the program's own retract plane there,
        then at the program's feed to the restart point (``planner.resume.approach_moves``)."""
        axes = self.m.config.axes
        c = self.m.config.controller
        clearance, safe = -math.inf, None
        if "Z" in axes:
            k = axes.index("Z")
            z_axis = self.m.config.machine.axes[k]
            clearance = z_axis.max_pos if c.restart_clearance_mm is None else c.restart_clearance_mm
            safe = last_safe_height(prog, move_index, k)
        feed = feed_mm_s if feed_mm_s > 0.0 else c.jog_speed_mm_s
        return approach_moves(cur, target, axes, self.m.config.machine.rotary, clearance=clearance,
                              feed_mm_s=feed, safe_height=safe)

    def approach_preview(self, line: int) -> np.ndarray | str:
        """The way a run from ``line`` would take to its start point (machine coordinates,
        one row per corner, from where the machine stands), for the operator to see before
        confirming; or why there is none."""
        info = self.m.loader.program_info
        if info is None:
            return "no program loaded"
        prog = info.program
        try:
            i = locate(prog, int(line))
            target = remaining_program(prog, i, 0.0).start_position
            modal = modal_state_before_move(prog, i)
            cur = np.asarray(self.m.states.machine_pos(), dtype=float)
            approach = self._approach(prog, i, cur, target, modal.feed_mm_s)
        except PlannerError as exc:
            return str(exc)
        return np.array([cur, *(m.end for m in approach.moves)])

    @property
    def resume_line(self) -> int:
        """Line a resume (after a fault or E-stop mid-program) would continue from, 0 if none."""
        return self.resume_point.line if self.resume_point is not None else 0

    def set_feed_override(self, percent: float) -> CommandResult:
        """Feed override 0-200 %, applied while running without a jump and within every limit
        (``app.machine.timescale``); above 100 % the speed stays capped by the machine limits,
        and the controller says so (``message``) where they cap it.
        """
        p = float(percent)
        top = 100.0 * SIGMA_MAX
        if not 0.0 <= p <= top:
            return self.m.states.refuse("set_feed_override", f"feed override must be 0-{top:g} %, got {p:g}")
        self.feed_pct = p
        with self.m._lock:
            job = self.m.stream.job
            if job is not None and job.overrides and job.executor.feed_override != min(p / 100.0, SIGMA_MAX):
                self.m.stream.change_motion(lambda ex: ex.set_overrides(feed=p / 100.0))
            if self.m.stream.job is not None and self.m.stream.job.then is not None:
                self.m.stream.job.then.executor.set_overrides(feed=p / 100.0)
        self.m.overridesChanged.emit(self.feed_pct, self.rapid_pct)
        return self.m.states.ok("set_feed_override")

    def set_rapid_override(self, percent: float) -> CommandResult:
        """Rapid override 0-100 % (rapid moves only), applied like the feed override."""
        p = float(percent)
        if not 0.0 <= p <= 100.0:
            return self.m.states.refuse("set_rapid_override", f"rapid override must be 0-100 %, got {p:g}")
        self.rapid_pct = p
        with self.m._lock:
            job = self.m.stream.job
            if job is not None and job.overrides and job.executor.rapid_override != min(p / 100.0, 1.0):
                self.m.stream.change_motion(lambda ex: ex.set_overrides(rapid=p / 100.0))
            if job is not None and job.then is not None and job.then.overrides:
                job.then.executor.set_overrides(rapid=p / 100.0)
        self.m.overridesChanged.emit(self.feed_pct, self.rapid_pct)
        return self.m.states.ok("set_rapid_override")
