"""The machine state machine: states, legal transitions, refusals with reasons, and the safety
transitions (E-stop, faults, alarms, reset).

``TRANSITIONS`` is the table every state change is checked against (an illegal one is an
internal error, never an operator refusal); ``refusal(action)`` says why a command would be
refused now. E-stop, faults and STOP alarms are told to the other parts as events
(``MachineEvents``: motion, homing, spindle and outputs each stop what is theirs), then the
state changes; a reset is told the same way once accepted.
"""

from __future__ import annotations

from app.machine.errors import MachineError
from app.machine.infra.drives import DriveLink
from app.machine.infra.events import AlarmReaction, MachineEvents, PanelChannels
from app.machine.model import Activity, CommandResult, HoldKind, MachineState, Prompt, Severity
from app.machine.ports import AlarmSink, Interlocks, MotionClaim, PositionsView, Settings
from app.machine.state.gate import Action, Answers

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

_NEED_IDLE = frozenset({Action.CYCLE_START, Action.RUN_FROM_LINE, Action.JOG, Action.MDI, Action.HOME,
                        Action.UPDATE_CONFIG, Action.LOAD_PROGRAM})
# loading a program and changing the configuration touch no axis: allowed while not connected,
# in an alarm or in E-stop as in IDLE
_NOT_MOVING_OK = frozenset({Action.LOAD_PROGRAM, Action.UPDATE_CONFIG})
_STANDING = frozenset({MachineState.DISCONNECTED, MachineState.ALARM, MachineState.ESTOP})
# the tool table is read when a program is checked: it changes only while nothing runs
_TOOL_EDITS = frozenset({Action.SET_TOOL, Action.REMOVE_TOOL, Action.SET_TOOL_IN_SPINDLE,
                         Action.TOUCH_OFF_TOOL,
                         Action.IMPORT_TOOL_TABLE})


class StateMachine:
    """States, transitions, refusals, E-stop, faults, alarms and reset (``controller.states``).

    It owns the state, its reason, the kind of hold, the prompt and the activity: every other
    part changes them through ``set_state`` and ``set_activity``."""

    def __init__(self, settings: Settings, out: PanelChannels, events: MachineEvents, drives: DriveLink,
                 positions: PositionsView, alarms: AlarmSink, interlocks: Interlocks,
                 claims: MotionClaim) -> None:
        self._settings = settings
        self._interlocks = interlocks
        self._claims = claims
        self._out = out
        self._events = events
        self._drives = drives
        self._positions = positions
        self._alarms = alarms
        self._answers = Answers(out)
        self.state = MachineState.DISCONNECTED
        self.state_reason = "not connected"
        self.hold_kind = HoldKind.NONE
        self.prompt: Prompt | None = None
        self.activity = Activity.NONE
        events.alarm_reaction.connect(self._react)

    @property
    def gate(self) -> StateMachine:
        return self

    # ------------------------------------------------------------------ answers
    def refuse(self, action: str, reason: str) -> CommandResult:
        return self._answers.refuse(action, reason)

    def ok(self, action: str) -> CommandResult:
        return self._answers.ok(action)

    def axis(self, axis: str | int) -> int:
        """The column of ``axis`` (a name or an index); MachineError naming the axes if none."""
        axes = self._settings.config.axes
        if isinstance(axis, str):
            name = axis.upper()
            if name not in axes:
                raise MachineError(f"unknown axis {axis!r}; axes: {' '.join(axes)}")
            return axes.index(name)
        if not 0 <= int(axis) < len(axes):
            raise MachineError(f"axis index {axis} out of range")
        return int(axis)

    # ------------------------------------------------------------------ state
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
                self._out.stateChanged.emit(new, reason)
            return
        if new not in TRANSITIONS[old]:
            raise MachineError(f"internal error: illegal transition {old.value} -> {new.value}")
        self.state = new
        self.state_reason = reason
        self.hold_kind = hold
        if new in (MachineState.IDLE, MachineState.DISCONNECTED, MachineState.ALARM, MachineState.ESTOP):
            self.set_activity(Activity.NONE)
        self._events.transition.emit(old, new)
        self._out.stateChanged.emit(new, reason)

    def tell_state(self, reason: str) -> None:
        """The state stays; the panel is told it again with ``reason`` (a new job in RUNNING)."""
        self._out.stateChanged.emit(self.state, reason)

    def set_activity(self, act: Activity) -> None:
        if act is not self.activity:
            self.activity = act
            self._out.activityChanged.emit(act)

    def refusal(self, action: str) -> str:
        """Why ``action`` ("cycle_start", "run_from_line", "jog", "mdi", "home", "feed_hold",
        "resume", "touch_off", "spindle_on", "update_config", ...) would be refused now; "" when
        allowed (for enabling buttons).
        """
        st = self.state
        cfg = self._settings.config
        blocked = self._interlocks.refusal(action)
        if blocked and st is not MachineState.DISCONNECTED:
            return blocked
        if action == Action.CYCLE_START and st is MachineState.HOLD:
            return ""
        if action in _TOOL_EDITS:
            if st in _STANDING or st is MachineState.IDLE:
                return ""
            return (f"the tool table cannot change while the machine is {st.label.lower()}: "
                    "a program reads the offsets when it is checked")
        if action in _NEED_IDLE and st is not MachineState.IDLE:
            if action in _NOT_MOVING_OK and st in _STANDING:
                return ""
            return f"machine is {st.label.lower()}" + (f" ({self.state_reason})" if self.state_reason else "")
        if action in (Action.CYCLE_START, Action.RUN_FROM_LINE, Action.MDI):
            homed = self._positions.homed
            if cfg.homing.required and not all(homed):
                missing = [a for a, h in zip(cfg.axes, homed) if not h]
                return f"axes not homed: {' '.join(missing)} (home them or set machine zero first)"
        if action == Action.FEED_HOLD and st is not MachineState.RUNNING:
            return f"nothing to hold: machine is {st.label.lower()}"
        if action == Action.RESUME and st not in (MachineState.HOLD, MachineState.IDLE):
            return f"nothing to resume: machine is {st.label.lower()}"
        if action in (Action.TOUCH_OFF, Action.SET_WORK_OFFSET, Action.SELECT_WORK_OFFSET,
                      Action.CLEAR_G92) and st in (MachineState.RUNNING, MachineState.HOLD,
                                                   MachineState.HOMING):
            return f"not while the machine is {st.label.lower()}"
        if action == Action.SPINDLE_ON and st not in (MachineState.IDLE, MachineState.HOLD):
            return f"spindle cannot start: machine is {st.label.lower()}"
        return ""

    def claim(self, action: str) -> str:
        """Once ``action`` is allowed: the axes taken from what else moves them (the handwheel)
        before the motion is planned; "" when free, else why it must wait."""
        return self._claims.claim(action)

    # ------------------------------------------------------------------ safety
    def reset(self) -> CommandResult:
        """ALARM: acknowledge the alarms, fault-reset and re-enable the drives -> IDLE (the
        resume point is kept). IDLE: forget the resume point. Spindle and the program's outputs
        go off. (A hold, and an alarm whose motion is still stopping, are the runner's:
        ``ProgramRunner.reset``.)
        """
        st = self.state
        if st is MachineState.ALARM:
            self._alarms.acknowledge_all()
            try:
                self._drives.enable_drives()
            except Exception as exc:  # noqa: BLE001
                return self.refuse(Action.RESET, f"the drives cannot be re-enabled: {exc}")
            self._events.poll_now.emit()
            if self.state is not MachineState.ALARM:
                return self.refuse(Action.RESET, f"machine is {self.state.label.lower()}")
            self._events.reset.emit(st)
            self.set_state(MachineState.IDLE, "reset")
            return self.ok(Action.RESET)
        if st is MachineState.IDLE:
            self._events.reset.emit(st)
            return self.ok(Action.RESET)
        return self.refuse(Action.RESET, f"reset not possible: machine is {st.label.lower()}")

    def enter_estop(self, reason: str) -> None:
        """The machine is in E-stop: every part stops what is its own (motion abandoned with
        its point to resume from, homing, spindle, outputs), then the state."""
        self._events.estop.emit(reason)
        if self.state is not MachineState.ESTOP:
            self.set_state(MachineState.ESTOP, reason)

    def estop(self, reason: str = "operator") -> CommandResult:
        """Emergency stop: the drives' quick stop at once, program abandoned (resume point kept),
        spindle off, -> ESTOP.
        """
        self._drives.estop(reason)
        # the operator's own E-stop says so once ("operator: E-stop pressed"), another names its cause
        by_operator = reason.startswith("operator")
        cause = "E-stop pressed" + (reason[len("operator"):] if by_operator else f": {reason}")
        self._alarms.raise_alarm("operator" if by_operator else "controller", cause, Severity.ESTOP, "estop")
        self.enter_estop(reason)
        if self._drives.attached:
            self._events.poll_now.emit()
        return self.ok("estop")

    def estop_release(self) -> CommandResult:
        """Release the E-stop: fault reset and re-enable the drives, -> IDLE."""
        if self.state is not MachineState.ESTOP:
            return self.refuse(Action.ESTOP_RELEASE, "E-stop is not active")
        blocked = self._interlocks.refusal(Action.ESTOP_RELEASE)
        if blocked:
            return self.refuse(Action.ESTOP_RELEASE, blocked)
        if not self._drives.attached:
            self.set_state(MachineState.DISCONNECTED, "E-stop released; not connected")
            return self.ok(Action.ESTOP_RELEASE)
        try:
            self._drives.enable_drives()
        except Exception as exc:  # noqa: BLE001
            return self.refuse(Action.ESTOP_RELEASE, f"the drives cannot be re-enabled: {exc}")
        self._alarms.acknowledge_code("estop")
        self._alarms.acknowledge_code("estop_chain")
        self._drives.snapshot()
        self.set_state(MachineState.IDLE, "E-stop released")
        return self.ok(Action.ESTOP_RELEASE)

    def _react(self, reaction: AlarmReaction, cause: str, resumable: bool) -> None:
        """An alarm that stops the machine (``AlarmLog``)."""
        if reaction is AlarmReaction.ESTOP:
            self.enter_estop(cause)
        elif reaction is AlarmReaction.FAULT:
            self.fault(cause)
        elif reaction is AlarmReaction.STOP:
            self.alarm_stop(cause, resumable)
        else:
            self.homing_failed(cause)

    def fault(self, cause: str) -> None:
        """A quick-stop class alarm: the drives stopped by themselves. Motion (its point to
        resume from kept), homing and the spindle stop; the machine is in ALARM."""
        self._events.fault.emit(cause)
        if self.state not in (MachineState.ESTOP, MachineState.DISCONNECTED, MachineState.ALARM):
            self.set_state(MachineState.ALARM, cause)

    def alarm_stop(self, cause: str, resumable: bool = True) -> None:
        """A STOP-class alarm: a jerk-limited stop along the path, the program abandoned (its
        point to resume from kept when ``resumable``), state ALARM. Motion ends by itself; the
        poll drops the job at standstill."""
        self._events.alarm_stop.emit(cause, resumable)
        if self.state in (MachineState.IDLE, MachineState.RUNNING, MachineState.HOLD, MachineState.HOMING):
            self.set_state(MachineState.ALARM, cause)

    def homing_failed(self, cause: str) -> None:
        """A drive's homing failed: homing ends; in HOMING or IDLE the machine is in ALARM."""
        self._events.homing_failed.emit(cause)
        if self.state in (MachineState.HOMING, MachineState.IDLE):
            self.set_state(MachineState.ALARM, cause)
