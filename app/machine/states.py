"""The machine state machine: states, legal transitions, refusals with reasons, E-stop and reset.

``TRANSITIONS`` is the table every state change is checked against (an illegal one is an
internal error, never an operator refusal); ``refusal(action)`` says why a command would be
refused now. Part of ``MachineController`` (mixed in; see ``app.machine.controller``).
"""

from __future__ import annotations

import numpy as np

from app.machine.errors import MachineError
from app.machine.model import Activity, CommandResult, MachineState, Severity, SpindleState

__all__ = ["StateMixin", "TRANSITIONS"]

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


class StateMixin:
    """States, transitions, refusals, E-stop and reset.

    Mixed into ``MachineController``, which holds the state.
    """

    def _refuse(self, action: str, reason: str) -> CommandResult:
        self.commandRefused.emit(action, reason)
        return CommandResult(False, action, reason)

    def _ok(self, action: str) -> CommandResult:
        return CommandResult(True, action, "")

    def _axis(self, axis: str | int) -> int:
        if isinstance(axis, str):
            name = axis.upper()
            if name not in self._cfg.axes:
                raise MachineError(f"unknown axis {axis!r}; axes: {' '.join(self._cfg.axes)}")
            return self._cfg.axes.index(name)
        if not 0 <= int(axis) < len(self._cfg.axes):
            raise MachineError(f"axis index {axis} out of range")
        return int(axis)

    def _set_state(self, new: MachineState, reason: str = "") -> None:
        old = self._state
        if new is old:
            if reason != self._state_reason:
                self._state_reason = reason
                self.stateChanged.emit(new, reason)
            return
        if new not in TRANSITIONS[old]:
            raise MachineError(f"internal error: illegal transition {old.value} -> {new.value}")
        self._state = new
        self._state_reason = reason
        self._start_pending = False  # a cycle start waiting for a check does not outlive a state change
        if new in (MachineState.IDLE, MachineState.DISCONNECTED, MachineState.ALARM, MachineState.ESTOP):
            self._set_activity(Activity.NONE)
            self._persist_state()
        self.stateChanged.emit(new, reason)

    def _set_activity(self, act: Activity) -> None:
        if act is not self._activity:
            self._activity = act
            self.activityChanged.emit(act)

    def _machine_pos(self) -> np.ndarray:
        return self._raw_pos - self._home_offset

    def _work_pos(self) -> np.ndarray:
        return self._machine_pos() - np.asarray(
            self._offsets.get(self._active_offset, (0.0,) * len(self._raw_pos))
        )

    def refusal(self, action: str) -> str:
        """Why ``action`` ("cycle_start", "run_from_line", "jog", "mdi", "home", "feed_hold",
        "resume", "touch_off", "spindle_on", "update_config", ...) would be refused now; "" when
        allowed (for enabling buttons).
        """
        st = self._state
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
            return f"machine is {st.label.lower()}" + (
                f" ({self._state_reason})" if self._state_reason else ""
            )
        if action in ("cycle_start", "run_from_line", "mdi"):
            if self._cfg.homing.required and not all(self._homed):
                missing = [a for a, h in zip(self._cfg.axes, self._homed) if not h]
                return f"axes not homed: {' '.join(missing)} (home them or set machine zero first)"
        if action in ("cycle_start", "run_from_line") and self._load_request is not None:
            return f"the program {self._load_request.name} is still being checked (wait until it is loaded)"
        if action == "cycle_start" and self._run_plan_request is not None:
            return (f"the program {self._run_plan_request.info.name} is being planned for single block "
                    "(wait until it is ready)")
        if action in ("cycle_start", "run_from_line") and self._program_info is None:
            return "no program loaded"
        if action == "feed_hold" and st is not MachineState.RUNNING:
            return f"nothing to hold: machine is {st.label.lower()}"
        if (
            action == "resume"
            and st is not MachineState.HOLD
            and not (st is MachineState.IDLE and self._resume)
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
        self._start_pending = False
        st = self._state
        if st is MachineState.HOLD:
            with self._lock:
                job = self._job
                standing = job is None or job.executor.standing or job.pause is not None
            if not standing:
                return self.stop()
            self._drop_job(completed=False, reason="reset")
            self._resume = None
            self._set_state(MachineState.IDLE, "reset")
            return self._ok("reset")
        if st is MachineState.ALARM:
            if self._job is not None:
                return self._refuse("reset", "the machine is still stopping: wait for standstill")
            self.acknowledge_alarm(None)
            try:
                self._enable_worker()
            except Exception as exc:  # noqa: BLE001
                return self._refuse("reset", f"the drives cannot be re-enabled: {exc}")
            self._poll()
            if self._state is not MachineState.ALARM:
                return self._refuse("reset", f"machine is {self._state.label.lower()}")
            self._set_state(MachineState.IDLE, "reset")
            return self._ok("reset")
        if st is MachineState.IDLE:
            self._resume = None
            self._line = 0
            self.lineChanged.emit(0)
            return self._ok("reset")
        return self._refuse("reset", f"reset not possible: machine is {st.label.lower()}")

    def _enter_estop(self, reason: str) -> None:
        with self._lock:
            job = self._job
            if job is not None:
                self._resume = job.resume_point(self._consumed(), reason)
            self._drop_job(completed=False, reason=f"E-stop: {reason}")
        self._homing_queue.clear()
        self._homing_axis = -1
        if self._spindle.on:
            self._apply_spindle(SpindleState())
        if self._state is not MachineState.ESTOP:
            self._set_state(MachineState.ESTOP, reason)

    def estop(self, reason: str = "operator") -> CommandResult:
        """Emergency stop: the drives' quick stop at once, program abandoned (resume point kept),
        spindle off, -> ESTOP.
        """
        if self._worker is not None:
            try:
                with self._lock:
                    self._worker.estop(reason)
            except Exception:  # noqa: BLE001 - E-stop proceeds whatever the worker says
                pass
        self._raise_alarm(
            "operator" if reason == "operator" else "controller", f"E-stop: {reason}", Severity.ESTOP, "estop"
        )
        self._enter_estop(reason)
        if self._worker is not None:
            self._poll()
        return self._ok("estop")

    def estop_release(self) -> CommandResult:
        """Release the E-stop: fault reset and re-enable the drives, -> IDLE."""
        if self._state is not MachineState.ESTOP:
            return self._refuse("estop_release", "E-stop is not active")
        if self._worker is None:
            self._set_state(MachineState.DISCONNECTED, "E-stop released; not connected")
            return self._ok("estop_release")
        try:
            self._enable_worker()
        except Exception as exc:  # noqa: BLE001
            return self._refuse("estop_release", f"the drives cannot be re-enabled: {exc}")
        for a in list(self._alarms):
            if a.active and a.code == "estop":
                self._ack(a.id)
        self._alarms_changed()
        self._snapshot_now()
        self._set_state(MachineState.IDLE, "E-stop released")
        return self._ok("estop_release")
