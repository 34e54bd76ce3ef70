"""Alarms: raised with time, source, cause and severity, persisted, acknowledged; the worker's
alarms mapped to reactions (quick-stop class: keep the resume point; STOP class: a stop along
the path). A part of ``MachineController``.
"""

from __future__ import annotations

import time
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from app.machine.model import Alarm, AlarmState, CommandResult, MachineState, Severity

if TYPE_CHECKING:
    from app.machine.controller import MachineController

__all__ = ["AlarmLog"]


class AlarmLog:
    """Alarm list, acknowledgement and reactions.

    A part of ``MachineController`` (``controller.alarm_log``): it owns the state set up in
    ``__init__`` and reaches the other parts through the facade ``m``.
    """

    def __init__(self, m: MachineController) -> None:
        self.m = m
        self.alarms: list[Alarm] = m.conn.store.load_alarms()
        self._next_alarm_id = max((a.id for a in self.alarms), default=0) + 1
        self.seen_worker_alarms: set[tuple[int, int, str]] = set()

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
        del self.alarms[:-500]
        try:
            self.m.conn.store.save_alarms(self.alarms)
        except OSError:
            pass
        self.m.alarmsChanged.emit(tuple(self.alarms))
        self.m.message.emit(f"{source}: {cause}")
        return alarm

    def ack(self, alarm_id: int) -> bool:
        for k, a in enumerate(self.alarms):
            if a.id == alarm_id and a.active:
                self.alarms[k] = replace(a, state=AlarmState.ACKNOWLEDGED)
                return True
        return False

    def alarms_changed(self) -> None:
        try:
            self.m.conn.store.save_alarms(self.alarms)
        except OSError:
            pass
        self.m.alarmsChanged.emit(tuple(self.alarms))

    def acknowledge_alarm(self, alarm_id: int | None = None) -> CommandResult:
        """Acknowledge one alarm (all active ones when None); persisted."""
        if alarm_id is None:
            for a in list(self.alarms):
                if a.active:
                    self.ack(a.id)
        elif not self.ack(int(alarm_id)):
            return self.m.states.refuse("acknowledge_alarm", f"no active alarm with id {alarm_id}")
        self.alarms_changed()
        return self.m.states.ok("acknowledge_alarm")

    def handle_worker_alarms(self, snap: Any) -> None:
        from ethercat.worker import AlarmCode

        for a in snap.alarms:
            key = (int(a.code), int(a.cycle), a.axis)
            if key in self.seen_worker_alarms:
                continue
            self.seen_worker_alarms.add(key)
            source = f"drive {a.axis}" if a.axis else "worker"
            if a.code is AlarmCode.UNDERRUN:
                self.raise_alarm(source, a.message, Severity.WARNING, "underrun")
            elif a.code is AlarmCode.ESTOP:
                if self.m.states.state is not MachineState.ESTOP:
                    self.raise_alarm(source, a.message, Severity.ESTOP, "estop")
                    self.m.states.enter_estop(a.message)
            elif a.code is AlarmCode.QUICK_STOP and self.m.states.state is MachineState.ESTOP:
                continue
            elif a.code is AlarmCode.HOMING_ERROR:
                self.raise_alarm(source, a.message, Severity.STOP, "homing_error")
                self.m.pos.homing_queue.clear()
                self.m.pos.homing_axis = -1
                if self.m.states.state in (MachineState.HOMING, MachineState.IDLE):
                    self.m.states.set_state(MachineState.ALARM, a.message)
            else:
                self.fault(a.message, source, a.code.name.lower())

    def handle_worker_events(self, events: Any) -> None:
        """The worker's events (a slave answering again, a drive reset at start-up, an error
        code read by SDO), recorded for the operator once each."""
        for e in events:
            key = (int(e.code), int(e.cycle), e.axis)
            if key in self.seen_worker_alarms:
                continue
            self.seen_worker_alarms.add(key)
            source = f"drive {e.axis}" if e.axis else "bus"
            self.raise_alarm(source, e.message, Severity.INFO, e.code.name.lower())

    def fault(self, cause: str, source: str, code: str) -> None:
        """A quick-stop class alarm: the worker already stopped the drives; keep the resume point."""
        self.raise_alarm(source, cause, Severity.QUICK_STOP, code)
        with self.m._lock:
            job = self.m.stream.job
            if job is not None:
                self.m.run.resume_point = job.resume_point(self.m.stream.consumed(), cause)
            self.m.stream.drop_job(completed=False, reason=cause)
            if self.m.worker is not None:
                try:
                    self.m.worker.flush()
                except Exception:  # noqa: BLE001
                    pass
        self.m.pos.homing_queue.clear()
        self.m.pos.homing_axis = -1
        if self.m.states.state not in (MachineState.ESTOP, MachineState.DISCONNECTED, MachineState.ALARM):
            self.m.states.set_state(MachineState.ALARM, cause)
        self.m.spindle_ctl.stop_spindle()

    def alarm_stop(self, cause: str, source: str, code: str) -> None:
        """A STOP-class alarm: jerk-limited stop along the path, program abandoned (its resume
        point kept), state ALARM. Motion ends by itself; the poll drops the job at standstill."""
        self.raise_alarm(source, cause, Severity.STOP, code)
        with self.m._lock:
            job = self.m.stream.job
            if job is not None:
                self.m.stream.hold_motion()
                job.stopping = True
                job.stop_reason = cause
                self.m.run.resume_point = job.resume_point(self.m.stream.consumed(), cause)
        if self.m.states.state in (
            MachineState.IDLE,
            MachineState.RUNNING,
            MachineState.HOLD,
            MachineState.HOMING,
        ):
            self.m.states.set_state(MachineState.ALARM, cause)
