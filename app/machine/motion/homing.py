"""Machine zero: homing to the switches, by the drive, or "set here".

- "switches" (LinuxCNC's homing): the axes home in the order of their ``sequence`` (equal values
  together); the 1 ms loop runs each group's search and latch (``ethercat.worker.switch_homing``)
  and reports where each switch changed; that position is the switch's machine coordinate
  (``offset``), and the group then moves to its ``home`` position (at ``final_vel``, or rapid)
  before the next group homes. The state's reason names the axes and the step they are at.
- "drive": the drive's own CiA 402 homing (mode 6), axis after axis, Z first.
- "set_here": the current position is machine zero. A machine without reference switches:
  after a power loss the control cannot know where the machine stands, and says so.

Homing ends on E-stop, a fault or a homing error; the machine then needs homing again for the
axes not done."""

from __future__ import annotations

from app.machine.errors import MachineError
from app.machine.infra.drives import DriveLink
from app.machine.infra.events import MachineEvents
from app.machine.model import Activity, CommandResult, MachineState, Severity
from app.machine.motion.manual import ManualMotion
from app.machine.motion.positions import Positions
from app.machine.ports import AlarmSink, Settings
from app.machine.state.gate import Action, guarded
from app.machine.state.states import StateMachine
from ethercat.worker import HomingState, HomingStep, WorkerSnapshot, WorkerState

#: the operator's words for the steps of homing to a switch
STEP_TEXT = {HomingStep.OFF_SWITCH: "moving off the switch", HomingStep.SEARCH: "searching the switch",
             HomingStep.BACK_OFF: "backing off the switch", HomingStep.LATCH: "latching the switch edge",
             HomingStep.INDEX: "searching the index pulse", HomingStep.DONE: "at the switch",
             HomingStep.SQUARE: "squaring the gantry"}

__all__ = ["Homing"]


class Homing:
    """The homing under way: the axes still to home and the one homing (``controller.homing``)."""

    def __init__(self, settings: Settings, states: StateMachine, drives: DriveLink, positions: Positions,
                 alarms: AlarmSink, events: MachineEvents, manual: ManualMotion) -> None:
        self._settings = settings
        self._manual = manual
        #: homing to switches: the groups still to home (axis indices), the one homing, and the
        #: step last told
        self.groups: list[list[int]] = []
        self.group: list[int] = []
        self._told = ""
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
        self.groups.clear()
        self.group = []

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
        """Home every axis by the configured method (to switches: in the sequence configured;
        by the drive: Z first)."""
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
        if cfg.homing.method == "switches":
            wanted = set(axes)
            self.groups = [g for g in ([i for i in group if i in wanted]
                                       for group in cfg.wiring.homing_groups(cfg.axes)) if g]
            self._states.set_state(MachineState.HOMING, "homing " + " ".join(cfg.axes[i] for i in axes))
            self._states.set_activity(Activity.HOMING)
            self._next_group()
            return self._states.ok(Action.HOME)
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

    # ------------------------------------------------------------------ to the switches
    def _next_group(self) -> None:
        cfg = self._settings.config
        if not self.groups:
            self.group = []
            self._events.coordinates_changed.emit()
            if self._states.state in (MachineState.HOMING, MachineState.IDLE):
                self._states.set_state(MachineState.IDLE, "homed")
            return
        group = self.groups.pop(0)
        self.group = group
        self._told = ""
        if self._states.state is not MachineState.HOMING:
            self._states.set_state(MachineState.HOMING, "homing " + " ".join(cfg.axes[i] for i in group))
        for i in group:
            self._positions.homing_started(i)
        try:
            self._drives.home_to_switches(group)
        except Exception as exc:  # noqa: BLE001 - told to the operator
            self.groups.clear()
            self.group = []
            self._alarms.raise_alarm("homing", f"homing refused: {exc}", Severity.STOP, "homing_error")
            self._states.set_state(MachineState.ALARM, f"homing refused: {exc}")

    def _switch_poll(self, snap: WorkerSnapshot) -> None:
        """A group homing to its switches: the step told; once every axis latched, its machine
        coordinates set and the move to the home positions."""
        cfg = self._settings.config
        group = self.group
        steps = snap.homing_steps
        text = ", ".join(f"{cfg.axes[i]} {STEP_TEXT.get(steps[i], '')}" for i in group if i < len(steps))
        if text and text != self._told:
            self._told = text
            self._states.tell_state("homing " + text)
        done = all(snap.homing[i] is HomingState.DONE for i in group)
        if snap.state is not WorkerState.ENABLED or not done:
            return
        targets: dict[int, float] = {}
        for i in group:
            h = cfg.wiring.homing_of(cfg.axes[i])
            assert h is not None
            self._positions.homed_at_switch(i, float(snap.home_latched[i]) - h.offset)
            targets[i] = h.home
        self.group = []
        self._final_move(targets)

    def _final_move(self, targets: dict[int, float]) -> None:
        """The homed group to its home positions (LinuxCNC's HOME at HOME_FINAL_VEL), then the
        next group."""
        cfg = self._settings.config
        here = self._positions.machine_pos()
        if all(abs(float(here[i]) - v) < 1e-6 for i, v in targets.items()):
            self._next_group()
            return
        vel = min((h.final_vel for h in cfg.wiring.homing if cfg.axes.index(h.axis) in targets), default=0.0)
        words = " ".join(f"{cfg.axes[i]}{v:.6f}" for i, v in sorted(targets.items()))
        block = f"G53 G1 {words} F{vel * 60.0:.6f}" if vel > 0 else f"G53 G0 {words}"
        names = " ".join(cfg.axes[i] for i in sorted(targets))
        result = self._manual.run_routine(block, f"homing {names}: to the home position", Action.HOME,
                                          when_done=lambda _job: self._next_group(),
                                          reason=f"homing {names}: to the home position")
        if not result:
            self.groups.clear()
            self._alarms.raise_alarm("homing", f"the move to the home position was refused: {result.reason}",
                                     Severity.STOP, "homing_error")
            if self._states.state is not MachineState.ALARM:
                self._states.set_state(MachineState.ALARM,
                                       "homing: the move to the home position was refused")

    def poll(self, snap: WorkerSnapshot) -> None:
        """The drive's homing seen done: the next axis; homing to switches: its steps."""
        if self.group and self._states.state is MachineState.HOMING:
            self._switch_poll(snap)
            return
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
