"""Program commands: cycle start, feed hold, resume, stop, single block, optional stop, block
delete, run from line, feed and rapid override (loading: ``app.machine.program.loader``)."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace

import numpy as np

from app.machine.infra.events import MachineEvents, PanelChannels
from app.machine.model import Activity, CommandResult, HoldKind, MachineState, ProgramInfo, RestartPreview
from app.machine.motion.jobs import JobTerms, ResumePoint
from app.machine.motion.making import JobMaker
from app.machine.motion.refusals import violation_issues
from app.machine.motion.streamer import Streamer
from app.machine.ports import AlarmSink, PositionsView, Settings, ToolView
from app.machine.program.loader import ProgramLoader
from app.machine.program.switches import RunSwitches
from app.machine.state.gate import Action, guarded
from app.machine.state.states import StateMachine
from planner.core.errors import PlannerError
from planner.core.program import Event, EventKind, Program, ToolNumber
from planner.geometry.resume import (
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
from planner.pipeline import SoftLimitError, travel

__all__ = ["ProgramRunner"]


class ProgramRunner:
    """Start, hold, resume, stop, run from line, and the operator's switches for a run: feed
    and rapid override, single block, optional stop, block delete (``controller.run``)."""

    def __init__(self, settings: Settings, states: StateMachine, positions: PositionsView, tools: ToolView,
                 loader: ProgramLoader, motion: Streamer, jobs: JobMaker, switches: RunSwitches,
                 alarms: AlarmSink, out: PanelChannels, events: MachineEvents,
                 parts: Callable[[], str] | None = None) -> None:
        """``parts``: why the part counter refuses a new run ("" when it does not)."""
        self._settings = settings
        self._parts = parts
        self._states = states
        self._positions = positions
        self._tools = tools
        self._loader = loader
        self._motion = motion
        self._jobs = jobs
        self._alarms = alarms
        self._out = out
        self._events = events
        self._switches = switches
        self.start_pending = False  # cycle start pressed while the program is checked again
        self.pending_line = 0       # ... or run from this line
        self.first_move = 0         # the move the program's current (or last) run began with
        # a cycle start waiting for a check does not outlive a state change, a new program, a
        # refused check or a reset
        events.transition.connect(lambda _old, _new: self._cancel_pending())
        events.load_requested.connect(self._cancel_pending)
        events.program_refused.connect(self._cancel_pending)
        events.reset.connect(lambda _state: self._cancel_pending())
        # the run a power loss or a kill cut (its program's file and line) until a program runs
        self.interrupted: tuple[str, int] | None = None
        events.run_interrupted.connect(self._run_interrupted)
        events.transition.connect(self._transition)
        events.program_loaded.connect(self._resume_interrupted)
        events.program_loaded.connect(lambda _info: self.pending_start())
        events.run_plan_done.connect(self._run_plan_done)

    @property
    def gate(self) -> ProgramRunner:
        return self

    def refusal(self, action: str) -> str:
        """Why ``action`` would be refused now (``StateMachine.refusal``), with what the program
        loaded and the point a stopped program resumes from add: cycle start and run from line
        need a program that is loaded, not being checked, nor (cycle start) being planned for
        single block; resume in IDLE needs a point to resume from. "" when allowed."""
        why = self._states.refusal(action)
        if why:
            return why
        st, loader = self._states.state, self._loader
        if action in (Action.CYCLE_START, Action.RUN_FROM_LINE) and st is not MachineState.HOLD:
            if loader.checking_name:
                return f"the program {loader.checking_name} is still being checked (wait until it is loaded)"
            if action == Action.CYCLE_START and loader.planning_name:
                return (f"the program {loader.planning_name} is being planned for single block "
                        "(wait until it is ready)")
            if loader.program_info is None:
                return "no program loaded"
        if action == Action.RESUME and st is MachineState.IDLE and self._motion.resume_point is None:
            return f"nothing to resume: machine is {st.label.lower()}"
        return ""

    def claim(self, action: str) -> str:
        return self._states.claim(action)

    def refuse(self, action: str, reason: str) -> CommandResult:
        return self._states.refuse(action, reason)

    def ok(self, action: str) -> CommandResult:
        return self._states.ok(action)

    def reset(self) -> CommandResult:
        """HOLD: abandon the program (after standstill; while moving, the stop first) -> IDLE.
        ALARM: once the motion has stopped, ``StateMachine.reset`` (acknowledge, re-enable ->
        IDLE, the resume point kept); IDLE: forget the resume point. Also cancels a cycle start
        waiting for a check."""
        st = self._states.state
        if st is MachineState.HOLD:
            if not self._motion.standing():
                return self.stop()
            self._events.reset.emit(st)
            self._states.set_state(MachineState.IDLE, "reset")
            return self._states.ok(Action.RESET)
        if st is MachineState.ALARM and self._motion.busy:
            return self._states.refuse(Action.RESET, "the machine is still stopping: wait for standstill")
        return self._states.reset()

    @property
    def resume_point(self) -> ResumePoint | None:
        return self._motion.resume_point

    def _run_interrupted(self, path: str, line: int, _saved_s: float) -> None:
        self.interrupted = (path, line)

    def _transition(self, _old: MachineState, new: MachineState) -> None:
        if new is MachineState.RUNNING and self._states.activity in (Activity.PROGRAM, Activity.APPROACH):
            self.interrupted = None          # a program runs again: what a power loss cut is past

    def _resume_interrupted(self, info: ProgramInfo) -> None:
        """The program a power loss or a kill cut is loaded again: it stopped part-way, as after
        an E-stop, so cycle start asks to resume at its line (the safe approach) or to start
        again from the beginning, never runs it from line 1 by itself."""
        cut = self.interrupted
        if cut is None or cut[0] not in (info.path, info.name) or self._motion.resume_point is not None:
            return
        try:
            index = locate(info.program, cut[1])
        except PlannerError:
            return                  # no motion from that line on: nothing to resume
        line = info.program.moves[index].line
        self._motion.keep_resume_point(ResumePoint(program=info.program, move_index=index, u_mm=0.0,
                                                   line=line, cause="power loss or killed"))

    def _cancel_pending(self) -> None:
        self.start_pending = False

    def _run_plan_done(self, ok: bool) -> None:
        if not ok:
            self.start_pending = False
        self.pending_start()

    def _fresh_program(self, action: str, wait: bool) -> Program | str | CommandResult:
        """The loaded program when it is still valid (same configuration and offsets, the
        machine where it was interpreted from), else it is checked again: with ``wait`` here
        (the synchronous path: headless use), otherwise in the worker thread (the caller is
        accepted; the run starts once ``programLoaded`` follows). Returns the program or the
        reason for refusing ``action``."""
        info = self._loader.program_info
        if info is None:
            return "no program loaded"
        stale = self._loader.program_stale()
        if stale:
            if not self._loader.recheck_program(wait):
                return "the program no longer passes its checks (see the errors)"
            if not wait:
                return self._start_when_ready(f"{stale}: {info.name} is being checked again", action)
            info = self._loader.program_info
            assert info is not None
        return info.program

    def _start_when_ready(self, why: str, action: str = Action.CYCLE_START) -> CommandResult:
        """Cycle start or run from line pressed while the program must first be checked or
        planned again in the worker thread: accept the press and start by itself once that is
        done (``start_pending`` is cleared by a failed check, a new load, stop, reset, E-stop or
        any state change). An operator presses once."""
        self.start_pending = True
        if action != Action.RUN_FROM_LINE:
            self.pending_line = 0
        self._out.message.emit(f"{why}; it starts when ready")
        return self._states.ok(action)

    def pending_start(self) -> None:
        """A background check or plan has finished: start if a press is waiting."""
        if self.start_pending and self._loader.load_request is None and self._loader.run_plan_request is None:
            self.start_pending = False
            line, self.pending_line = self.pending_line, 0
            if line:
                self.run_from_line(line)
            else:
                self.cycle_start()

    def cycle_start(self, *, wait: bool = False, from_start: bool = False) -> CommandResult:
        """Start the loaded program from its beginning (IDLE), or continue (HOLD). A program
        that stopped part-way (Stop, E-stop and reset, an alarm) is never started again by
        default: cycle start is refused, saying where it stopped, until the operator chooses
        to resume there (``resume``) or to start from the beginning (``from_start``). Needs homed
        axes (unless the configuration says otherwise) and no active alarm of severity STOP or
        above. Runs the plan made at load time; when the configuration, the work offsets or
        the machine position changed since loading, the program is checked again first, and
        with single block on its single-block plan is made first: both in a worker thread
        (refused meanwhile with the reason; ``loadingChanged``), or here with ``wait=True``
        (headless use).
        """
        action = Action.CYCLE_START
        if self._states.state is MachineState.HOLD:
            return self.resume()
        if wait:  # headless: finish a load or a single-block plan under way first
            if self._loader.load_request is not None:
                self._loader.wait_loaded(None)
            self._loader.wait_run_plan(None)
        why = self.refusal(action)
        if why:
            return self._states.refuse(action, why)
        if self._alarms.stops_motion():
            return self._states.refuse(action, "acknowledge the active alarms first")
        counted = self._parts() if self._parts is not None else ""
        if counted:
            return self._states.refuse(action, counted)
        why = self._states.claim(action)
        if why:
            return self._states.refuse(action, why)
        point = self._motion.resume_point
        if point is not None:
            if not from_start:
                return self._states.refuse(
                    action, f"the program stopped at line {point.line}: resume there or start it again from "
                            "the beginning (choose one)")
            self._motion.forget_resume_point()
        prog = self._fresh_program(action, wait)
        if isinstance(prog, CommandResult):  # accepted: starts once checked again
            return prog
        if isinstance(prog, str):
            return self._states.refuse(action, prog)
        info = self._loader.program_info
        assert info is not None
        single = self._switches.single_block
        plan = self._loader.run_plan(single)
        if plan is None and not wait:
            self._loader.start_run_plan(single)
            return self._start_when_ready(f"{info.name} is being planned for single block")
        try:
            job = self._jobs.make_job(Activity.PROGRAM, prog, info.name, single_block=single, plan=plan,
                                      stops=None if single else info.stops,
                                      terms=JobTerms(origin=(prog, 0, 0.0), source=info.path))
        except PlannerError as exc:
            return self._states.refuse(action, f"planner: {exc}")
        self.first_move = 0
        self._motion.run_program(job, 0)
        return self._states.ok(action)

    @guarded(Action.FEED_HOLD)
    def feed_hold(self) -> CommandResult:
        """Jerk-limited stop along the path (time-optimal, ``planner.motion.stopping``, or the time
        scale to 0 where that would exceed a limit): RUNNING -> HOLD. The stop starts a few
        cycles (``SPLICE_MARGIN_S``) after the request: the set-points queued in the worker
        beyond that are replaced (``Streamer.change_motion``), not run first. In a tap (G74,
        G84, G33.1) the stop waits until the tap is out of the hole, where it ends at rest.
        """
        waits = self._motion.hold()
        if waits is None:
            return self._states.refuse(Action.FEED_HOLD, "nothing is moving")
        # the operator sees why the axes go on: the hold takes effect where the tap has ended
        reason = "feed hold: the tap runs out of the hole first" if waits else "feed hold"
        self._states.set_state(MachineState.HOLD, reason, HoldKind.FEED_HOLD)
        return self._states.ok(Action.FEED_HOLD)

    @guarded(Action.RESUME)
    def resume(self) -> CommandResult:
        """HOLD -> RUNNING: continue after a feed hold, a single-block stop or M00/M01/M06 to the
        same end. In IDLE after a fault or E-stop mid-program: move safely to the point where the
        program stopped (``resume_line``) and continue from exactly there.
        """
        point = self._motion.resume_point
        if self._states.state is MachineState.IDLE and point is not None:
            return self._resume_from_point(point)
        why = self._motion.continue_held(self._switches.single_block)
        if why:
            return self._states.refuse(Action.RESUME, why)
        job = self._motion.job
        self._states.set_state(MachineState.RUNNING, job.kind.value if job is not None else "program")
        return self._states.ok(Action.RESUME)

    def stop(self) -> CommandResult:
        """Jerk-limited stop along the path, then abandon the program (-> IDLE). In IDLE it
        cancels a cycle start that waits for the program to be checked again."""
        st = self._states.state
        if self.start_pending and st is MachineState.IDLE:
            self.start_pending = False
            return self._states.ok(Action.STOP)
        if st not in (MachineState.RUNNING, MachineState.HOLD, MachineState.HOMING):
            return self._states.refuse(Action.STOP, f"nothing to stop: machine is {st.label.lower()}")
        if st is MachineState.HOMING:
            return self._states.refuse(Action.STOP, "homing cannot be stopped mid-way: use E-stop")
        had_job = self._motion.stop_job("stopped by the operator", keep_point=True)
        if not had_job:
            self._states.set_state(MachineState.IDLE, "stopped")
        elif self._states.state is MachineState.RUNNING:
            self._states.set_state(MachineState.HOLD, "stopping", HoldKind.STOPPING)
        return self._states.ok(Action.STOP)

    def set_single_block(self, on: bool) -> CommandResult:
        """Single block: the plan stops at every block end (HOLD there; cycle start goes on).
        Switched while running, it takes effect at the next standstill (feed hold, pause point):
        the rest of the program is planned again from there."""
        self._switches.set_modes(single_block=bool(on))
        loader = self._loader
        if (on and not self._motion.busy and loader.program_info is not None
                and not loader.program_stale() and loader.load_request is None):
            loader.start_run_plan(True)  # ready by the time cycle start is pressed
        job = self._motion.job
        if job is not None and job.kind is Activity.PROGRAM:
            self._out.message.emit("single block takes effect at the next stop (feed hold, block end, M00)")
        return self._states.ok(Action.SET_SINGLE_BLOCK)

    def set_optional_stop(self, on: bool) -> CommandResult:
        """Honour M01 (optional pause); may change while running."""
        self._switches.set_modes(optional_stop=bool(on))
        return self._states.ok(Action.SET_OPTIONAL_STOP)

    def set_block_delete(self, on: bool) -> CommandResult:
        """Block delete: lines starting with '/' are skipped (on) or run (off). The program is
        read whole before it runs, so the switch cannot change a run under way: refused while a
        program or MDI runs or holds. A loaded program is checked again with it (the preview
        then shows the path it gives), as after an offset change."""
        on = bool(on)
        if on == self._switches.block_delete:
            return self._states.ok(Action.SET_BLOCK_DELETE)
        if self._motion.busy:
            self._switches.set_modes()
            return self._states.refuse(Action.SET_BLOCK_DELETE,
                                       "block delete changes which lines the program "
                                       "has: switch it before cycle start, not during a run")
        self._switches.set_modes(block_delete=on)
        loader = self._loader
        if loader.program_info is not None and loader.load_request is None:
            loader.recheck_program(wait=False)
        return self._states.ok(Action.SET_BLOCK_DELETE)

    def run_from_line(self, line: int, *, wait: bool = False) -> CommandResult:
        """Start the loaded program at source line ``line``: a safe approach (up to the restart
        clearance, across, the spindle as of that line started and at speed, down to the
        program's retract plane, then at feed to the line's start point) and the program runs
        on from there. As cycle start, a program stale since loading is checked again first: in
        the worker thread, and the run starts by itself when it passes (here with ``wait=True``).
        """
        action = Action.RUN_FROM_LINE
        if wait and self._loader.load_request is not None:
            self._loader.wait_loaded(None)
        why = self.refusal(action) or self._states.claim(action)
        if why:
            return self._states.refuse(action, why)
        self.pending_line = int(line)
        prog = self._fresh_program(action, wait)
        if isinstance(prog, CommandResult):
            return prog          # checked again first; it starts from the line when ready
        self.pending_line = 0
        if isinstance(prog, str):
            return self._states.refuse(action, prog)
        try:
            i = locate(prog, int(line))
        except PlannerError as exc:
            return self._states.refuse(action, str(exc))
        point = ResumePoint(program=prog, move_index=i, u_mm=0.0, line=prog.moves[i].line,
                            cause=f"run from line {line}")
        done = self._resume_from_point(point, action=action)
        if done:
            self.first_move = i            # what lies before the line was not run in this run
        return done

    def _resume_from_point(self, point: ResumePoint, action: str = Action.RESUME) -> CommandResult:
        cfg = self._settings.config
        if cfg.homing.required and not all(self._positions.homed):
            return self._states.refuse(action, "axes not homed")
        if self._alarms.stops_motion():
            return self._states.refuse(action, "acknowledge the active alarms first")
        prog = point.program
        reads = reads_before(prog, point.move_index, point.line)
        if action == Action.RUN_FROM_LINE and reads:
            first = reads[0]
            what = "the probe" if first.kind is EventKind.PROBE else "M66"
            return self._states.refuse(
                action, f"line {point.line} comes after {what} at line {first.line}: what follows depends on "
                        f"what it read; run from line {first.line} (or before) to read it again")
        probing = probe_move_at(prog, point.move_index)
        if probing is not None and point.u_mm > 0.0:
            # stopped during a probe move: it starts again from its start, the probe armed there
            point = replace(point, u_mm=0.0, line=probing.line)
        try:
            rest = remaining_program(prog, point.move_index, point.u_mm, line=point.line)
        except PlannerError as exc:
            return self._states.refuse(action, str(exc))
        modal = modal_state_before_move(prog, point.move_index)
        loads = (EventKind.TOOL_CHANGE, EventKind.TOOL_SET)
        changes = [e for e in prog.events if e.kind in loads and e.after_move < point.move_index]
        need = changes[-1].payload_as(ToolNumber).number if changes else self._tools.in_spindle
        if need != self._tools.in_spindle:
            # the program from here was checked with that tool's length: never cut with another
            have = self._tools.in_spindle
            return self._states.refuse(
                action, f"line {point.line} needs T{need} in the spindle (T{have} is in it): put it in and "
                        f"set it on the Tools page, or run from the M6 line {changes[-1].line}")
        cur = np.asarray(self._positions.machine_pos(), dtype=float)
        try:
            approach = self._approach(prog, point.move_index, cur, rest.start_position, modal.feed_mm_s)
        except PlannerError as exc:
            return self._states.refuse(action, f"approach move: {exc}")
        # the spindle as of the restart point, on (and at speed) before the tool goes below the
        # clearance height: in the approach after its last move at the top, or first thing
        spindle_event = Event(EventKind.SPINDLE, point.line, approach.spindle_after, modal.spindle)
        way = None
        if approach.moves:
            way = program_from_moves(prog, list(approach.moves), [spindle_event], cur, name="approach")
            try:
                travel(way, self._jobs.machine())
            except SoftLimitError as exc:
                issue = violation_issues(list(exc.violations))[0]
                return self._states.refuse(action, f"approach move: soft limit: {issue}")
        else:
            rest = replace(rest, events=(spindle_event, *rest.events))
        info: ProgramInfo | None = self._loader.program_info
        name = info.name if info is not None else prog.name
        # a long rest is planned as it runs: its time estimated by the share of moves left
        left = 1.0 - point.move_index / max(len(prog.moves), 1)
        terms = JobTerms(origin=(prog, point.move_index, point.u_mm),
                         source=info.path if info is not None else "", probe_results=point.probe_results,
                         wait_results=point.wait_results)
        try:
            # progress relative to the whole program
            main = self._jobs.make_job(Activity.PROGRAM, rest, name, single_block=self._switches.single_block,
                                       estimate_s=info.cycle_time_s * left if info else math.nan, terms=terms,
                                       whole_s=info.cycle_time_s if info else math.nan)
            if way is not None:
                main = self._jobs.make_job(Activity.APPROACH, way, "approach", overrides=True,
                                           terms=JobTerms(then=main))
        except PlannerError as exc:
            return self._states.refuse(action, f"planner: {exc}")
        self._motion.run_program(main, point.line)
        return self._states.ok(action)

    def _approach(self, prog: Program, move_index: int, cur: np.ndarray, target: np.ndarray,
                  feed_mm_s: float) -> Approach:
        """Up to the restart clearance, across, down to the program's own retract plane there,
        then at the program's feed to the restart point (``planner.geometry.resume.approach_moves``)."""
        cfg = self._settings.config
        axes = cfg.axes
        c = cfg.controller
        clearance, safe = self._clearance(), None
        if "Z" in axes:
            safe = last_safe_height(prog, move_index, axes.index("Z"))
        feed = feed_mm_s if feed_mm_s > 0.0 else c.jog_speed_mm_s
        return approach_moves(cur, target, axes, cfg.machine.rotary, clearance=clearance,
                              feed_mm_s=feed, safe_height=safe)

    def restart_preview(self, line: int = 0) -> RestartPreview | str:
        """What a restart would do, for the operator to see before confirming: ``line`` > 0 a
        run from that line, else a resume at the point where the program stopped; or why
        there is none."""
        point = self._motion.resume_point
        if line > 0:
            info = self._loader.program_info
            if info is None:
                return "no program loaded"
            prog = info.program
            try:
                i = locate(prog, int(line))
            except PlannerError as exc:
                return str(exc)
            u, cause, at_line = 0.0, f"run from line {line}", int(line)
        elif point is not None:
            prog, i, u, cause, at_line = point.program, point.move_index, point.u_mm, point.cause, point.line
        else:
            return "no program stopped part-way"
        try:
            target = remaining_program(prog, i, u).start_position
            modal = modal_state_before_move(prog, i)
            cur = np.asarray(self._positions.machine_pos(), dtype=float)
            approach = self._approach(prog, i, cur, target, modal.feed_mm_s)
        except PlannerError as exc:
            return str(exc)
        path = np.array([cur, *(m.end for m in approach.moves)])
        return RestartPreview(line=at_line, cause=cause, path=path, clearance_mm=self._clearance(),
                              spindle_rpm=modal.spindle.signed_rpm,
                              tool=int(modal.tool) if modal.tool else self._tools.in_spindle)

    def _clearance(self) -> float:
        """The machine height a restart rises to first (-inf on a machine without Z)."""
        cfg = self._settings.config
        if "Z" not in cfg.axes:
            return -math.inf
        z_axis = cfg.machine.axes[cfg.axes.index("Z")]
        c = cfg.controller
        return z_axis.max_pos if c.restart_clearance_mm is None else c.restart_clearance_mm

    @property
    def resume_line(self) -> int:
        """Line a resume (after a fault or E-stop mid-program) would continue from, 0 if none."""
        point = self._motion.resume_point
        return point.line if point is not None else 0

    def set_feed_override(self, percent: float) -> CommandResult:
        """Feed override 0-200 %, applied while running without a jump and within every limit
        (``app.machine.motion.timescale``); above 100 % the speed stays capped by the machine
        limits, and the controller says so (``message``) where they cap it.
        """
        p = float(percent)
        why = self._switches.set_overrides(feed_pct=p)
        if why:
            return self._states.refuse(Action.SET_FEED_OVERRIDE, why)
        self._motion.set_overrides(feed=p / 100.0)
        return self._states.ok(Action.SET_FEED_OVERRIDE)

    def set_rapid_override(self, percent: float) -> CommandResult:
        """Rapid override 0-100 % (rapid moves only), applied like the feed override."""
        p = float(percent)
        why = self._switches.set_overrides(rapid_pct=p)
        if why:
            return self._states.refuse(Action.SET_RAPID_OVERRIDE, why)
        self._motion.set_overrides(rapid=p / 100.0)
        return self._states.ok(Action.SET_RAPID_OVERRIDE)
