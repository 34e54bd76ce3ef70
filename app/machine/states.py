"""The machine state machine: states, legal transitions, refusals with reasons, E-stop and reset.

``TRANSITIONS`` is the table every state change is checked against (an illegal one is an
internal error, never an operator refusal); ``refusal(action)`` says why a command would be
refused now. A part of ``MachineController`` (see ``app.machine.controller``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from app.machine.errors import MachineError
from app.machine.model import Activity, CommandResult, HoldKind, MachineState, Prompt, Severity

if TYPE_CHECKING:
    from app.machine.controller import MachineController

__all__ = ["StateMachine", "TRANSITIONS"]

S = MachineState
TRANSITIONS: dict[MachineState, frozenset[MachineState]] = {
    S.DISCONNECTED: frozenset({S.IDLE, S.ESTOP}),
    S.IDLE: frozenset({S.RUNNING, S.HOMING, S.ALARM, S.ESTOP, S.DISCONNECTED}),
    S.HOMING: frozenset({S.IDLE, S.ALARM, S.ESTOP, S.DISCONNECTED}),
    S.RUNNING: frozenset({S.HOLD, S.IDLE, S.ALARM, S.ESTOP, S.DISCONNECTED}),
    S.HOLD: frozenset({S.RUNNING, S.IDLE, S.ALARM, S.ESTOP, S.DISCONNECTED}),
    S.ALARM: frozenset({S.IDLE, S.ESTOP, S.DISCONNECTED}),
    S.ESTOP: frozenset({S.IDLE, S.DISCONNECTED}),
}


class StateMachine:
    """States, transitions, refusals, E-stop and reset.

    A part of ``MachineController`` (``controller.states``): it owns the state set up in
    ``__init__`` and reaches the other parts through the facade ``m``.
    """

    def __init__(self, m: MachineController) -> None:
        self.m = m
        self.state = MachineState.DISCONNECTED
        self.state_reason = "not connected"
        self.hold_kind = HoldKind.NONE
        self.prompt: Prompt | None = None
        self.activity = Activity.NONE

    def refuse(self, action: str, reason: str) -> CommandResult:
        self.m.commandRefused.emit(action, reason)
        return CommandResult(False, action, reason)

    def ok(self, action: str) -> CommandResult:
        return CommandResult(True, action, "")

    def axis(self, axis: str | int) -> int:
        if isinstance(axis, str):
            name = axis.upper()
            if name not in self.m.config.axes:
                raise MachineError(f"unknown axis {axis!r}; axes: {' '.join(self.m.config.axes)}")
            return self.m.config.axes.index(name)
        if not 0 <= int(axis) < len(self.m.config.axes):
            raise MachineError(f"axis index {axis} out of range")
        return int(axis)

    def set_state(self, new: MachineState, reason: str = "", hold: HoldKind = HoldKind.NONE,
                  prompt: Prompt | None = None) -> None:
        """``hold``: why, when ``new`` is HOLD (the header names the stop after it);
        ``prompt``: what that stop asks of the operator (kept while in HOLD)."""
        old = self.state
        hold = hold if new is MachineState.HOLD else HoldKind.NONE
        self.prompt = prompt if new is MachineState.HOLD else None
        if new is old:
            if reason != self.state_reason or hold is not self.hold_kind:
                self.state_reason = reason
                self.hold_kind = hold
                self.m.stateChanged.emit(new, reason)
            return
        if new not in TRANSITIONS[old]:
            raise MachineError(f"internal error: illegal transition {old.value} -> {new.value}")
        self.state = new
        self.state_reason = reason
        self.hold_kind = hold
        self.m.run.start_pending = False  # a cycle start waiting for a check does not outlive a state change
        if new in (MachineState.IDLE, MachineState.DISCONNECTED, MachineState.ALARM, MachineState.ESTOP):
            self.set_activity(Activity.NONE)
            self.m.conn.persist_state()
        self.m.stateChanged.emit(new, reason)

    def set_activity(self, act: Activity) -> None:
        if act is not self.activity:
            self.activity = act
            self.m.activityChanged.emit(act)

    def machine_pos(self) -> np.ndarray:
        return self.m.pos.raw_pos - self.m.pos.home_offset

    def work_pos(self) -> np.ndarray:
        """Machine position minus the active work offset, turned back by the system's XY rotation
        (G10 L2 R) and minus the G92 offset when it is on: what a program reads as its position,
        as LinuxCNC's display."""
        rel = self.machine_pos() - np.asarray(
            self.m.pos.offsets.get(self.m.pos.active_offset, (0.0,) * len(self.m.pos.raw_pos)))
        rotation = self.m.pos.rotation()
        axes = self.m.config.axes
        if rotation and "X" in axes and "Y" in axes:
            ix, iy = axes.index("X"), axes.index("Y")
            c, s = np.cos(np.radians(rotation)), np.sin(np.radians(rotation))
            rel[ix], rel[iy] = c * rel[ix] + s * rel[iy], -s * rel[ix] + c * rel[iy]
        return rel - self.m.pos.g92_offset()

    def refusal(self, action: str) -> str:
        """Why ``action`` ("cycle_start", "run_from_line", "jog", "mdi", "home", "feed_hold",
        "resume", "touch_off", "spindle_on", "update_config", ...) would be refused now; "" when
        allowed (for enabling buttons).
        """
        st = self.state
        need_idle = {"cycle_start", "run_from_line", "jog", "mdi", "home", "update_config", "load_program"}
        if action == "cycle_start" and st is MachineState.HOLD:
            return ""
        if action in need_idle and st is not MachineState.IDLE:
            if action == "load_program" and st in (
                MachineState.DISCONNECTED,
                MachineState.ALARM,
                MachineState.ESTOP,
            ):
                return ""
            if action == "update_config" and st in (
                MachineState.DISCONNECTED,
                MachineState.ALARM,
                MachineState.ESTOP,
            ):
                return ""
            return f"machine is {st.label.lower()}" + (f" ({self.state_reason})" if self.state_reason else "")
        if action in ("cycle_start", "run_from_line", "mdi"):
            if self.m.config.homing.required and not all(self.m.pos.homed):
                missing = [a for a, h in zip(self.m.config.axes, self.m.pos.homed) if not h]
                return f"axes not homed: {' '.join(missing)} (home them or set machine zero first)"
        if action in ("cycle_start", "run_from_line") and self.m.loader.load_request is not None:
            name = self.m.loader.load_request.name
            return f"the program {name} is still being checked (wait until it is loaded)"
        if action == "cycle_start" and self.m.loader.run_plan_request is not None:
            return (
                f"the program {self.m.loader.run_plan_request.info.name} is being planned for single block "
                "(wait until it is ready)"
            )
        if action in ("cycle_start", "run_from_line") and self.m.loader.program_info is None:
            return "no program loaded"
        if action == "feed_hold" and st is not MachineState.RUNNING:
            return f"nothing to hold: machine is {st.label.lower()}"
        if (
            action == "resume"
            and st is not MachineState.HOLD
            and not (st is MachineState.IDLE and self.m.run.resume_point)
        ):
            return f"nothing to resume: machine is {st.label.lower()}"
        if action in ("touch_off", "set_work_offset", "select_work_offset") and st in (
            MachineState.RUNNING,
            MachineState.HOLD,
            MachineState.HOMING,
        ):
            return f"not while the machine is {st.label.lower()}"
        if action == "spindle_on" and st not in (MachineState.IDLE, MachineState.HOLD):
            return f"spindle cannot start: machine is {st.label.lower()}"
        return ""

    def reset(self) -> CommandResult:
        """HOLD: abandon the program (after standstill) -> IDLE. ALARM: acknowledge the alarms,
        fault-reset and re-enable the drives -> IDLE (the resume point is kept). IDLE: forget the
        resume point. Also cancels a cycle start waiting for a check.
        """
        self.m.run.start_pending = False
        st = self.state
        if st is MachineState.HOLD:
            with self.m._lock:
                job = self.m.stream.job
                standing = job is None or job.executor.standing or job.pause is not None
            if not standing:
                return self.m.run.stop()
            self.m.stream.drop_job(completed=False, reason="reset")
            self.m.run.resume_point = None
            self.m.spindle_ctl.stop_spindle()
            self.set_state(MachineState.IDLE, "reset")
            return self.ok("reset")
        if st is MachineState.ALARM:
            if self.m.stream.job is not None:
                return self.refuse("reset", "the machine is still stopping: wait for standstill")
            self.m.alarm_log.acknowledge_alarm(None)
            try:
                self.m.conn.enable_worker()
            except Exception as exc:  # noqa: BLE001
                return self.refuse("reset", f"the drives cannot be re-enabled: {exc}")
            self.m.poller.poll()
            if self.state is not MachineState.ALARM:
                return self.refuse("reset", f"machine is {self.state.label.lower()}")
            self.m.spindle_ctl.stop_spindle()
            self.m.outputs.all_off()
            self.set_state(MachineState.IDLE, "reset")
            return self.ok("reset")
        if st is MachineState.IDLE:
            self.m.run.resume_point = None
            self.m.stream.line = 0
            self.m.lineChanged.emit(0)
            self.m.spindle_ctl.stop_spindle()      # reset means everything off
            self.m.outputs.all_off()
            return self.ok("reset")
        return self.refuse("reset", f"reset not possible: machine is {st.label.lower()}")

    def enter_estop(self, reason: str) -> None:
        with self.m._lock:
            job = self.m.stream.job
            if job is not None:
                self.m.run.resume_point = job.resume_point(self.m.stream.consumed(), reason)
            self.m.stream.drop_job(completed=False, reason=f"E-stop: {reason}")
        self.m.pos.homing_queue.clear()
        self.m.pos.homing_axis = -1
        self.m.spindle_ctl.stop_spindle()
        self.m.outputs.all_off()
        if self.state is not MachineState.ESTOP:
            self.set_state(MachineState.ESTOP, reason)

    def estop(self, reason: str = "operator") -> CommandResult:
        """Emergency stop: the drives' quick stop at once, program abandoned (resume point kept),
        spindle off, -> ESTOP.
        """
        if self.m.worker is not None:
            try:
                with self.m._lock:
                    self.m.worker.estop(reason)
            except Exception:  # noqa: BLE001 - E-stop proceeds whatever the worker says
                pass
        self.m.alarm_log.raise_alarm(
            "operator" if reason == "operator" else "controller", f"E-stop: {reason}", Severity.ESTOP, "estop"
        )
        self.enter_estop(reason)
        if self.m.worker is not None:
            self.m.poller.poll()
        return self.ok("estop")

    def estop_release(self) -> CommandResult:
        """Release the E-stop: fault reset and re-enable the drives, -> IDLE."""
        if self.state is not MachineState.ESTOP:
            return self.refuse("estop_release", "E-stop is not active")
        if self.m.worker is None:
            self.set_state(MachineState.DISCONNECTED, "E-stop released; not connected")
            return self.ok("estop_release")
        try:
            self.m.conn.enable_worker()
        except Exception as exc:  # noqa: BLE001
            return self.refuse("estop_release", f"the drives cannot be re-enabled: {exc}")
        for a in list(self.m.alarm_log.alarms):
            if a.active and a.code == "estop":
                self.m.alarm_log.ack(a.id)
        self.m.alarm_log.alarms_changed()
        self.m.conn.snapshot_now()
        self.set_state(MachineState.IDLE, "E-stop released")
        return self.ok("estop_release")
