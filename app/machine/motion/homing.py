"""Machine zero: homing by the drive (CiA 402 homing mode, axis after axis, Z first) or "set
here" (the current position is machine zero). Homing ends on E-stop, a fault or a homing
error; the machine then needs homing again for the axes not done."""

from __future__ import annotations

from app.machine.errors import MachineError
from app.machine.infra.drives import DriveLink
from app.machine.infra.events import MachineEvents
from app.machine.model import Activity, CommandResult, MachineState, Severity
from app.machine.motion.positions import Positions
from app.machine.ports import AlarmSink, Settings
from app.machine.state.gate import Action, guarded
from app.machine.state.states import StateMachine
from ethercat.worker import HomingState, WorkerSnapshot, WorkerState

__all__ = ["Homing"]


class Homing:
    """The homing under way: the axes still to home and the one homing (``controller.homing``)."""

    def __init__(self, settings: Settings, states: StateMachine, drives: DriveLink, positions: Positions,
                 alarms: AlarmSink, events: MachineEvents) -> None:
        self._settings = settings
        self._states = states
        self._drives = drives
        self._positions = positions
        self._alarms = alarms
        self._events = events
        self.queue: list[int] = []
        self.axis = -1
        for channel in (events.estop, events.fault, events.homing_failed):
            channel.connect(self._abandon)

    @property
    def gate(self) -> StateMachine:
        return self._states

    def _abandon(self, _cause: str) -> None:
        self.queue.clear()
        self.axis = -1

    def home_axis(self, axis: str | int) -> CommandResult:
        """Home one axis by the configured method: "drive" (CiA 402 homing mode 6 with
        ``homing.drive_method``, via the worker) or "set_here" (current position = machine zero).
        """
        try:
            i = self._states.axis(axis)
        except MachineError as exc:
            return self._states.refuse(Action.HOME, str(exc))
        return self._home([i])

    def home_all(self) -> CommandResult:
        """Home every axis (Z first) by the configured method."""
        axes = self._settings.config.axes
        order = list(range(len(axes)))
        if "Z" in axes:  # Z first: clear the part before the others move
            z = axes.index("Z")
            order.remove(z)
            order.insert(0, z)
        return self._home(order)

    @guarded(Action.HOME)
    def _home(self, axes: list[int]) -> CommandResult:
        cfg = self._settings.config
        if cfg.homing.method == "set_here":
            return self.set_machine_zero_here(None if len(axes) == len(cfg.axes) else axes[0])
        self.queue = list(axes)
        self._states.set_state(MachineState.HOMING, "homing " + " ".join(cfg.axes[i] for i in axes))
        self._states.set_activity(Activity.HOMING)
        self._next()
        return self._states.ok(Action.HOME)

    def _next(self) -> None:
        if not self.queue:
            self.axis = -1
            self._events.coordinates_changed.emit()
            if self._states.state is MachineState.HOMING:
                self._states.set_state(MachineState.IDLE, "homed")
            return
        i = self.queue.pop(0)
        self.axis = i
        self._positions.homing_started(i)
        cfg = self._settings.config
        try:
            self._drives.home(i, cfg.homing.drive_method)
        except Exception as exc:  # noqa: BLE001
            self.queue.clear()
            self.axis = -1
            self._alarms.raise_alarm(f"drive {cfg.axes[i]}", f"homing refused: {exc}", Severity.STOP,
                                     "homing_error")
            self._states.set_state(MachineState.ALARM, f"homing refused: {exc}")

    def poll(self, snap: WorkerSnapshot) -> None:
        """The drive's homing seen done: the next axis."""
        i = self.axis
        if i < 0 or self._states.state is not MachineState.HOMING:
            return
        if snap.homing[i] is HomingState.DONE and snap.state is WorkerState.ENABLED:
            self._positions.homed_by_drive(i)
            self._next()

    def set_machine_zero_here(self, axis: str | int | None = None) -> CommandResult:
        """Declare the current position machine zero for one axis (all when None); homed; persisted."""
        action = Action.SET_MACHINE_ZERO_HERE
        if self._states.state is not MachineState.IDLE:
            return self._states.refuse(action, f"machine is {self._states.state.label.lower()}")
        try:
            idx = list(range(len(self._settings.config.axes))) if axis is None else [self._states.axis(axis)]
        except MachineError as exc:
            return self._states.refuse(action, str(exc))
        self._positions.zero_here(idx)
        self._events.coordinates_changed.emit()
        return self._states.ok(action)
