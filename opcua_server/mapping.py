"""The controller's status snapshot read as OPC 40501 values: pure functions, no server.

The enumerations carry the numbers of the Machine Tools nodeset (OPC 40501-1 1.01); the
choices where the specification leaves room are stated here, once:

- ``OperationMode``: Setup while homing; Manual for jog and MDI and when nothing is loaded;
  Automatic while a program runs or stands loaded; Other while the bus is down.
- ``ChannelState``: Active while anything moves; Interrupted in a hold, an alarm, or while a
  stopped program keeps its resume point; Reset otherwise.
- ``ChannelMode``: Reference while homing, MdaMdi for MDI, JogManual for jog and for an idle
  machine with no program, Automatic with a program.
- Program ``State``: Initializing once a program is loaded and until it starts; Running;
  Interrupted in a hold or stopped with a resume point; Ended when the run completed;
  Aborted when it stopped for good (alarm, E-stop, reset).
- The stack light: red for E-stop or an active alarm, yellow for a hold or an interrupted
  program, green while running.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

from machine_status import (
    Activity,
    Alarm,
    ControllerSnapshot,
    MachineState,
    Prompt,
    RunSummary,
    Severity,
)

__all__ = ["AlarmEvent", "ChannelMode", "ChannelState", "ConditionClass", "MachineOperationMode",
           "MessageTracker", "ProgramState", "ProgramTracker", "Stacklight", "UaView", "condition_class",
           "severity_of", "view_of"]


class MachineOperationMode(enum.IntEnum):
    MANUAL = 0
    AUTOMATIC = 1
    SETUP = 2
    AUTO_WITH_MANUAL_INTERVENTION = 3
    SERVICE = 4
    OTHER = 5


class ChannelState(enum.IntEnum):
    ACTIVE = 0
    INTERRUPTED = 1
    RESET = 2


class ChannelMode(enum.IntEnum):
    AUTOMATIC = 0
    MDA_MDI = 1
    JOG_MANUAL = 2
    JOG_INCREMENT = 3
    TEACHING_HANDLE = 4
    REMOTE = 5
    REFERENCE = 6
    OTHER = 7


class ProgramState(enum.Enum):
    """The states of ProductionProgramStateMachineType, by their browse names."""

    INITIALIZING = "Initializing"
    RUNNING = "Running"
    ENDED = "Ended"
    INTERRUPTED = "Interrupted"
    ABORTED = "Aborted"


@dataclass(frozen=True, slots=True)
class Stacklight:
    red: bool
    yellow: bool
    green: bool


@dataclass(frozen=True, slots=True)
class UaView:
    """Every value the server shows, read from one snapshot."""

    operation_mode: MachineOperationMode
    channel_state: ChannelState
    channel_mode: ChannelMode
    feed_override_pct: float
    rapid_override_pct: float
    single_block: bool
    optional_stop: bool
    block_delete: bool
    spindle_rotating: bool
    spindle_override_pct: float
    spindle_commanded_rpm: float
    program_name: str
    program_state: ProgramState
    line: int
    progress_pct: float
    estimated_cycle_s: float
    remaining_s: float
    stacklight: Stacklight
    machine_pos: tuple[float, ...]
    work_pos: tuple[float, ...]
    homed: tuple[bool, ...]
    tool_in_spindle: int
    machine_state: str


def _moving(snap: ControllerSnapshot) -> bool:
    return snap.state in (MachineState.RUNNING, MachineState.HOMING)


def operation_mode(snap: ControllerSnapshot) -> MachineOperationMode:
    if snap.state is MachineState.DISCONNECTED:
        return MachineOperationMode.OTHER
    if snap.state is MachineState.HOMING or snap.activity is Activity.HOMING:
        return MachineOperationMode.SETUP
    if snap.activity in (Activity.PROGRAM, Activity.APPROACH):
        return MachineOperationMode.AUTOMATIC
    if snap.activity in (Activity.JOG, Activity.MDI):
        return MachineOperationMode.MANUAL
    return MachineOperationMode.AUTOMATIC if snap.program_name else MachineOperationMode.MANUAL


def channel_state(snap: ControllerSnapshot) -> ChannelState:
    if _moving(snap):
        return ChannelState.ACTIVE
    if snap.state in (MachineState.HOLD, MachineState.ALARM) or snap.resume_line > 0:
        return ChannelState.INTERRUPTED
    return ChannelState.RESET


def channel_mode(snap: ControllerSnapshot) -> ChannelMode:
    if snap.state is MachineState.HOMING or snap.activity is Activity.HOMING:
        return ChannelMode.REFERENCE
    if snap.activity is Activity.MDI:
        return ChannelMode.MDA_MDI
    if snap.activity is Activity.JOG:
        return ChannelMode.JOG_MANUAL
    if snap.activity in (Activity.PROGRAM, Activity.APPROACH) or snap.program_name:
        return ChannelMode.AUTOMATIC
    return ChannelMode.JOG_MANUAL


class ProgramTracker:
    """The program's state machine, which needs what came before: a newly loaded program
    is Initializing even though the previous one Ended."""

    def __init__(self) -> None:
        self._program: tuple[str, int, float] | None = None
        self._run: RunSummary | None = None
        self._started = False

    def state(self, snap: ControllerSnapshot) -> ProgramState:
        program = (snap.program_path or snap.program_name, snap.program_lines, snap.estimated_cycle_s)
        if program != self._program:
            self._program, self._run, self._started = program, snap.last_run, False
        in_program = snap.activity in (Activity.PROGRAM, Activity.APPROACH)
        if snap.state is MachineState.RUNNING and in_program:
            self._started = True
            return ProgramState.RUNNING
        if snap.state is MachineState.HOLD and in_program:
            self._started = True
            return ProgramState.INTERRUPTED
        if self._started and snap.resume_line > 0:
            return ProgramState.INTERRUPTED
        if self._started and snap.last_run is not None and snap.last_run is not self._run:
            return ProgramState.ENDED if snap.last_run.completed else ProgramState.ABORTED
        if self._started and snap.state in (MachineState.ALARM, MachineState.ESTOP):
            return ProgramState.ABORTED
        return ProgramState.INITIALIZING


def stacklight(snap: ControllerSnapshot) -> Stacklight:
    red = snap.state in (MachineState.ESTOP, MachineState.ALARM) or bool(snap.active_alarms)
    yellow = snap.state is MachineState.HOLD or (not _moving(snap) and snap.resume_line > 0)
    return Stacklight(red=red, yellow=yellow and not red, green=_moving(snap) and not red)


def view_of(snap: ControllerSnapshot, program_state: ProgramState) -> UaView:
    return UaView(
        operation_mode=operation_mode(snap), channel_state=channel_state(snap),
        channel_mode=channel_mode(snap), feed_override_pct=float(snap.feed_override_pct),
        rapid_override_pct=float(snap.rapid_override_pct), single_block=snap.single_block,
        optional_stop=snap.optional_stop, block_delete=snap.block_delete,
        spindle_rotating=snap.spindle.on, spindle_override_pct=float(snap.spindle.override_pct),
        spindle_commanded_rpm=float(snap.spindle.commanded_rpm if snap.spindle.on else 0.0),
        program_name=snap.program_name, program_state=program_state, line=max(0, int(snap.line)),
        progress_pct=100.0 * float(snap.progress), estimated_cycle_s=float(snap.estimated_cycle_s),
        remaining_s=float(snap.remaining_s), stacklight=stacklight(snap),
        machine_pos=tuple(float(v) for v in snap.machine_pos),
        work_pos=tuple(float(v) for v in snap.work_pos),
        homed=tuple(bool(h) for h in snap.homed), tool_in_spindle=int(snap.tool_in_spindle),
        machine_state=snap.state.label)


#: OPC UA severities (1-1000) of the alarm log's: recorded, warning, stop, quick stop, E-stop
_SEVERITY = {Severity.INFO: 100, Severity.WARNING: 400, Severity.STOP: 700, Severity.QUICK_STOP: 800,
             Severity.ESTOP: 1000}


def severity_of(severity: Severity) -> int:
    return _SEVERITY[severity]


class ConditionClass(enum.Enum):
    """What an alarm is about (OPC 10000-9's condition classes): the machine's safety chain,
    its own equipment (drives, bus, server, configuration), or the process it runs."""

    PROCESS = "process"
    SYSTEM = "system"
    SAFETY = "safety"


_SYSTEM_SOURCES = ("worker", "drive", "bus", "opcua", "config")


def condition_class(alarm: Alarm) -> ConditionClass:
    if alarm.severity is Severity.ESTOP:
        return ConditionClass.SAFETY
    if alarm.source.startswith(_SYSTEM_SOURCES):
        return ConditionClass.SYSTEM
    return ConditionClass.PROCESS


@dataclass(frozen=True, slots=True)
class AlarmEvent:
    """One event for the notifiers: a state of an alarm's condition (``alarm`` set), or a
    program prompt (``alarm`` None).

    An alarm's condition is Active while the alarm is active at the panel. Alarms that stopped
    the machine (STOP and above) wait for the operator's acknowledgement: Unacknowledged while
    active, and acknowledging at the panel makes them Acknowledged and Inactive at once.
    Warnings and records need no acknowledgement: Acknowledged from the start, Inactive when
    the operator clears them (a record, cleared as it is raised, is told as both). A condition
    is retained (replayed by ConditionRefresh) while it is Active or Unacknowledged."""

    identifier: str
    message: str
    severity: int
    alarm: Alarm | None = None
    acknowledged: bool = False
    active: bool = True

    @property
    def needs_acknowledgement(self) -> bool:
        return self.alarm is not None and self.alarm.severity >= Severity.STOP

    @property
    def acked_state(self) -> bool:
        return self.acknowledged or not self.needs_acknowledgement

    @property
    def retain(self) -> bool:
        return self.active or not self.acked_state

    @property
    def condition_class(self) -> ConditionClass:
        assert self.alarm is not None
        return condition_class(self.alarm)


def _alarm_event(alarm: Alarm, cleared: bool) -> AlarmEvent:
    return AlarmEvent(f"alarm-{alarm.id}", f"{alarm.source}: {alarm.cause}", severity_of(alarm.severity),
                      alarm, acknowledged=cleared, active=not cleared)


class MessageTracker:
    """What happened since the last snapshot, as events: each alarm once when raised and once
    when acknowledged or cleared, and each program prompt (M0/M1 message, tool change) once."""

    def __init__(self) -> None:
        self._seen: dict[int, bool] = {}
        self._prompt: Prompt | None = None
        self._first = True

    def events(self, snap: ControllerSnapshot) -> list[AlarmEvent]:
        out: list[AlarmEvent] = []
        for alarm in snap.alarms:
            cleared = not alarm.active
            before = self._seen.get(alarm.id)
            if before is None and not (self._first and cleared):
                out.append(_alarm_event(alarm, False))
                if cleared:                  # raised and cleared between two snapshots
                    out.append(_alarm_event(alarm, True))
            elif before is False and cleared:
                out.append(_alarm_event(alarm, True))
            self._seen[alarm.id] = cleared
        prompt = snap.prompt
        if prompt is not None and prompt != self._prompt:
            text = prompt.text or prompt.kind.value.replace("_", " ")
            if prompt.tool:
                text = f"{text} (tool T{prompt.tool})"
            out.append(AlarmEvent(f"line-{prompt.line}-{prompt.kind.value}", f"line {prompt.line}: {text}",
                                  200))
        self._prompt = prompt
        self._first = False
        return out
