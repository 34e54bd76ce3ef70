"""Alarms: raised with time, source, cause and severity, persisted, acknowledged; the worker's
alarms mapped to reactions (quick-stop class: keep the resume point; STOP class: a stop along
the path). Part of ``MachineController`` (mixed in).
"""

from __future__ import annotations

import time
from dataclasses import replace
from typing import Any

from app.machine.model import Alarm, AlarmState, CommandResult, MachineState, Severity, SpindleState

__all__ = ["AlarmMixin"]


class AlarmMixin:
    """Alarm list, acknowledgement and reactions.

    Mixed into ``MachineController``, which holds the state.
    """

    def _raise_alarm(self, source: str, cause: str, severity: Severity, code: str = "") -> Alarm:
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
        self._alarms.append(alarm)
        del self._alarms[:-500]
        try:
            self._store.save_alarms(self._alarms)
        except OSError:
            pass
        self.alarmsChanged.emit(tuple(self._alarms))
        self.message.emit(f"{source}: {cause}")
        return alarm

    def _ack(self, alarm_id: int) -> bool:
        for k, a in enumerate(self._alarms):
            if a.id == alarm_id and a.active:
                self._alarms[k] = replace(a, state=AlarmState.ACKNOWLEDGED)
                return True
        return False

    def _alarms_changed(self) -> None:
        try:
            self._store.save_alarms(self._alarms)
        except OSError:
            pass
        self.alarmsChanged.emit(tuple(self._alarms))

    def acknowledge_alarm(self, alarm_id: int | None = None) -> CommandResult:
        """Acknowledge one alarm (all active ones when None); persisted."""
        if alarm_id is None:
            for a in list(self._alarms):
                if a.active:
                    self._ack(a.id)
        elif not self._ack(int(alarm_id)):
            return self._refuse("acknowledge_alarm", f"no active alarm with id {alarm_id}")
        self._alarms_changed()
        return self._ok("acknowledge_alarm")

    def _handle_worker_alarms(self, snap: Any) -> None:
        from ethercat.worker import AlarmCode

        for a in snap.alarms:
            key = (int(a.code), int(a.cycle), a.axis)
            if key in self._seen_worker_alarms:
                continue
            self._seen_worker_alarms.add(key)
            source = f"drive {a.axis}" if a.axis else "worker"
            if a.code is AlarmCode.UNDERRUN:
                self._raise_alarm(source, a.message, Severity.WARNING, "underrun")
            elif a.code is AlarmCode.ESTOP:
                if self._state is not MachineState.ESTOP:
                    self._raise_alarm(source, a.message, Severity.ESTOP, "estop")
                    self._enter_estop(a.message)
            elif a.code is AlarmCode.QUICK_STOP and self._state is MachineState.ESTOP:
                continue
            elif a.code is AlarmCode.HOMING_ERROR:
                self._raise_alarm(source, a.message, Severity.STOP, "homing_error")
                self._homing_queue.clear()
                self._homing_axis = -1
                if self._state in (MachineState.HOMING, MachineState.IDLE):
                    self._set_state(MachineState.ALARM, a.message)
            else:
                self._fault(a.message, source, a.code.name.lower())

    def _fault(self, cause: str, source: str, code: str) -> None:
        """A quick-stop class alarm: the worker already stopped the drives; keep the resume point."""
        self._raise_alarm(source, cause, Severity.QUICK_STOP, code)
        with self._lock:
            job = self._job
            if job is not None:
                self._resume = job.resume_point(self._consumed(), cause)
            self._drop_job(completed=False, reason=cause)
            if self._worker is not None:
                try:
                    self._worker.flush()
                except Exception:  # noqa: BLE001
                    pass
        self._homing_queue.clear()
        self._homing_axis = -1
        if self._state not in (MachineState.ESTOP, MachineState.DISCONNECTED, MachineState.ALARM):
            self._set_state(MachineState.ALARM, cause)
        if self._spindle.on:
            self._apply_spindle(SpindleState())

    def _alarm_stop(self, cause: str, source: str, code: str) -> None:
        """A STOP-class alarm: jerk-limited stop along the path, program abandoned (its resume
        point kept), state ALARM. Motion ends by itself; the poll drops the job at standstill."""
        self._raise_alarm(source, cause, Severity.STOP, code)
        with self._lock:
            job = self._job
            if job is not None:
                self._hold_motion()
                job.stopping = True
                job.stop_reason = cause
                self._resume = job.resume_point(self._consumed(), cause)
        if self._state in (MachineState.IDLE, MachineState.RUNNING, MachineState.HOLD, MachineState.HOMING):
            self._set_state(MachineState.ALARM, cause)
