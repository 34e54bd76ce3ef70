"""Alarms: raised with time, source, cause and severity, persisted, acknowledged; the worker's
alarms classified; an alarm that stops the machine is announced for the state machine to react
(``MachineEvents.alarm_reaction``: E-stop; quick-stop class: the drives stopped, the resume
point kept; STOP class: a stop along the path; homing errors).
"""

from __future__ import annotations

import time
from dataclasses import replace

from app.machine.infra.events import AlarmReaction, MachineEvents, PanelChannels
from app.machine.model import Alarm, AlarmState, CommandResult, MachineState, Severity
from app.machine.ports import AlarmStore
from app.machine.state.gate import Action, Answers
from ethercat.worker import AlarmCode, WorkerEvent, WorkerSnapshot

__all__ = ["AlarmLog"]

#: entries kept (oldest dropped first)
KEEP_ALARMS = 500


class AlarmLog:
    """The alarm list, its acknowledgement and the worker's alarms (``controller.alarm_log``)."""

    def __init__(self, store: AlarmStore, out: PanelChannels, events: MachineEvents) -> None:
        self._store = store
        self._out = out
        self._events = events
        self._state = MachineState.DISCONNECTED      # the machine's, as its transitions tell
        self._answers = Answers(out)
        self.alarms: list[Alarm] = store.load_alarms()
        self._next_alarm_id = max((a.id for a in self.alarms), default=0) + 1
        self._seen_worker: set[tuple[int, int, str]] = set()
        events.announce.connect(lambda: self._out.alarmsChanged.emit(tuple(self.alarms)))
        events.connecting.connect(self._seen_worker.clear)
        events.transition.connect(self._transition)

    def _transition(self, _old: MachineState, new: MachineState) -> None:
        self._state = new

    @property
    def all(self) -> tuple[Alarm, ...]:
        """All alarms (active and history), oldest first."""
        return tuple(self.alarms)

    @property
    def active(self) -> tuple[Alarm, ...]:
        return tuple(a for a in self.alarms if a.active)

    def stops_motion(self) -> bool:
        """Whether an alarm of severity STOP or above is still to be acknowledged."""
        return any(a.active and a.severity >= Severity.STOP for a in self.alarms)

    def raise_alarm(self, source: str, cause: str, severity: Severity, code: str = "") -> Alarm:
        alarm = Alarm(
            id=self._next_alarm_id,
            time_s=time.time(),
            source=source,
            cause=cause,
            severity=severity,
            state=AlarmState.ACTIVE if severity >= Severity.WARNING else AlarmState.ACKNOWLEDGED,
            code=code,
        )
        self._next_alarm_id += 1
        self.alarms.append(alarm)
        del self.alarms[:-KEEP_ALARMS]
        self._save()
        self._out.alarmsChanged.emit(tuple(self.alarms))
        self._out.message.emit(f"{source}: {cause}")
        return alarm

    def _ack(self, alarm_id: int) -> bool:
        for k, a in enumerate(self.alarms):
            if a.id == alarm_id and a.active:
                self.alarms[k] = replace(a, state=AlarmState.ACKNOWLEDGED)
                return True
        return False

    def _save(self) -> None:
        try:
            self._store.save_alarms(self.alarms)
        except OSError:
            pass        # the list is shown all the same; the next save tries again

    def _changed(self) -> None:
        self._save()
        self._out.alarmsChanged.emit(tuple(self.alarms))

    def acknowledge_alarm(self, alarm_id: int | None = None) -> CommandResult:
        """Acknowledge one alarm (all active ones when None); persisted."""
        if alarm_id is None:
            for a in list(self.alarms):
                if a.active:
                    self._ack(a.id)
        elif not self._ack(int(alarm_id)):
            return self._answers.refuse(Action.ACKNOWLEDGE_ALARM, f"no active alarm with id {alarm_id}")
        self._changed()
        return self._answers.ok(Action.ACKNOWLEDGE_ALARM)

    def acknowledge_all(self) -> None:
        self.acknowledge_alarm(None)

    def acknowledge_code(self, code: str) -> None:
        """Acknowledge every active alarm of ``code`` (the E-stop's once released)."""
        for a in list(self.alarms):
            if a.active and a.code == code:
                self._ack(a.id)
        self._changed()

    # ------------------------------------------------------------------ the worker's alarms
    def handle_worker_alarms(self, snap: WorkerSnapshot) -> None:
        react = self._events.alarm_reaction.emit
        for a in snap.alarms:
            key = (int(a.code), int(a.cycle), a.axis)
            if key in self._seen_worker:
                continue
            self._seen_worker.add(key)
            source = f"drive {a.axis}" if a.axis else "worker"
            if a.code is AlarmCode.UNDERRUN:
                self.raise_alarm(source, a.message, Severity.WARNING, "underrun")
            elif a.code is AlarmCode.ESTOP:
                if self._state is not MachineState.ESTOP:
                    self.raise_alarm(source, a.message, Severity.ESTOP, "estop")
                    react(AlarmReaction.ESTOP, a.message, True)
            elif a.code is AlarmCode.ESTOP_CHAIN:
                # the machine's E-stop chain: an E-stop, told even when one is in force already
                self.raise_alarm("E-stop chain", a.message, Severity.ESTOP, "estop_chain")
                if self._state is not MachineState.ESTOP:
                    react(AlarmReaction.ESTOP, "E-stop chain open", True)
            elif a.code is AlarmCode.QUICK_STOP and self._state is MachineState.ESTOP:
                continue
            elif a.code is AlarmCode.SPINDLE:         # the spindle stopped: the axes stop on the path
                self.alarm_stop(a.message, "spindle", "spindle_drive")
            elif a.code is AlarmCode.HANDWHEEL:       # the wheel stopped; nothing else did
                self.raise_alarm("handwheel", a.message, Severity.WARNING, "handwheel")
            elif a.code in (AlarmCode.HOMING_ERROR, AlarmCode.HOMING_SWITCH):
                self.raise_alarm(source, a.message, Severity.STOP, "homing_error")
                react(AlarmReaction.HOMING_FAILED, a.message, False)
            else:
                self.fault(a.message, source, a.code.name.lower())

    def handle_worker_events(self, events: tuple[WorkerEvent, ...]) -> None:
        """The worker's events (a slave answering again, a drive reset at start-up, an error
        code read by SDO), recorded for the operator once each."""
        for e in events:
            key = (int(e.code), int(e.cycle), e.axis)
            if key in self._seen_worker:
                continue
            self._seen_worker.add(key)
            source = f"drive {e.axis}" if e.axis else "bus"
            self.raise_alarm(source, e.message, Severity.INFO, e.code.name.lower())

    def fault(self, cause: str, source: str, code: str) -> None:
        """A quick-stop class alarm: the worker already stopped the drives (the machine keeps
        the point to resume from)."""
        self.raise_alarm(source, cause, Severity.QUICK_STOP, code)
        self._events.alarm_reaction.emit(AlarmReaction.FAULT, cause, True)

    def alarm_stop(self, cause: str, source: str, code: str, resumable: bool = True) -> None:
        """A STOP-class alarm: a jerk-limited stop along the path, the program abandoned (its
        point to resume from kept when ``resumable``), state ALARM."""
        self.raise_alarm(source, cause, Severity.STOP, code)
        self._events.alarm_reaction.emit(AlarmReaction.STOP, cause, resumable)
