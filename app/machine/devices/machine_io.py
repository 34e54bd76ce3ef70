"""What the machine does when its signals change (``app.machine.wiring``; read through
``MachineSignals``), and the coolant a program switches.

At every poll (30 Hz), on a change of:

- the machine's buttons ``cycle_start``, ``feed_hold``, ``stop`` (a press: the rising edge): the
  panel's command of the same name, with the same refusals (told as the panel's are);
- ``door_closed`` opening: a running program holds (feed hold along the path); once the axes
  stand, the spindle stops and turns again, at speed, when cycle start goes on with the door
  closed (``SpindleControl.restart_after_hold``); a spindle turning by hand stops at once.
  While the door is open cycle start, MDI, homing and the spindle are refused, and a jog runs
  at the setup speed or not at all (``MachineSignals.refusal``);
- ``air_ok`` or ``lube_ok`` going false: the configured alarm (``[interlocks]``: "stop" stops
  the motion along its path, "warning" tells).

The E-stop chain and the limit switches act in the 1 ms loop itself (``ethercat.worker``); this
part only offers the operator's limit override.

Coolant: M7/M8/M9 of a program switch the outputs when the drives reach the move after them
(at the poll); a program's end or stop switches the coolant off (LinuxCNC's M2/M30 and abort),
as E-stop and reset do (``DigitalOutputs``).
"""

from __future__ import annotations

import collections
from typing import Protocol

from app.machine.devices.outputs import DigitalOutputs
from app.machine.devices.signals import MachineSignals
from app.machine.devices.spindle import SpindleControl
from app.machine.infra.drives import DriveLink
from app.machine.infra.events import MachineEvents
from app.machine.model import Activity, CommandResult, MachineState, Severity
from app.machine.motion.jobs import Job
from app.machine.motion.streamer import Streamer
from app.machine.ports import AlarmSink, Settings
from app.machine.state.states import StateMachine
from app.machine.wiring import Direction, axis_at
from ethercat.sim_io import input_value
from ethercat.worker import WorkerSnapshot
from planner.core.program import Coolant, CoolantSwitch, EventKind

__all__ = ["Buttons", "MachineIo"]


class Buttons(Protocol):
    """The panel's commands the machine's buttons press."""

    def cycle_start(self) -> CommandResult: ...

    def feed_hold(self) -> CommandResult: ...

    def stop(self) -> CommandResult: ...


_WATCHED = ("cycle_start", "feed_hold", "stop", "door_closed", "air_ok", "lube_ok")


class MachineIo:
    """The machine's buttons, door, air and lube, and the program's coolant (``controller.io``)."""

    def __init__(self, settings: Settings, states: StateMachine, signals: MachineSignals, drives: DriveLink,
                 spindle: SpindleControl, outputs: DigitalOutputs, alarms: AlarmSink, motion: Streamer,
                 events: MachineEvents, buttons: Buttons) -> None:
        self._settings = settings
        self._states = states
        self._signals = signals
        self._drives = drives
        self._spindle = spindle
        self._outputs = outputs
        self._alarms = alarms
        self._motion = motion
        self._buttons = buttons
        self._last: dict[str, bool | None] = {}
        # the job whose coolant events are followed, and those not switched yet: (after move, bits)
        self._job: Job | None = None
        self._coolant: collections.deque[tuple[int, Coolant]] = collections.deque()
        self._ended: Job | None = None          # the job that ended last, until the machine stands
        motion.on_poll(self._follow_job)
        motion.on_job_end(self._job_ended)
        events.transition.connect(self._transition)

    @property
    def gate(self) -> StateMachine:
        return self._states

    # ------------------------------------------------------------------ the signals
    def poll(self, snap: WorkerSnapshot) -> None:
        """The signals' changes since the last poll, and what the door asks while it is open."""
        now = {key: self._signals.value(key, snap) for key in _WATCHED}
        last, self._last = self._last, now
        if not last:
            return                            # the first reading: a state, not a change
        pressed = [k for k in ("cycle_start", "feed_hold", "stop") if now[k] and last.get(k) is False]
        for key in pressed:
            getattr(self._buttons, key)()
        if now["door_closed"] is False and last.get("door_closed") is not False:
            self._door_opened()
        if now["door_closed"] is False:
            self._door_open()
        for key, what in (("air_ok", "air pressure"), ("lube_ok", "lubrication")):
            if now[key] is False and last.get(key) is not False:
                self._lost(key, what)

    def _door_opened(self) -> None:
        st = self._states.state
        if st is MachineState.RUNNING:
            self._buttons.feed_hold()
            self._states.tell_state("feed hold: the door was opened")
        elif st is MachineState.HOMING:
            self._alarms.alarm_stop("the door was opened while homing", "door", "door_open", resumable=False)

    def _door_open(self) -> None:
        """While the door is open: a spindle that turns stops, in a hold once the axes stand."""
        if not self._spindle.spindle.on:
            return
        st = self._states.state
        if st is MachineState.HOLD and self._motion.still():
            self._spindle.stop_for_hold()
            self._states.tell_state("door open: the spindle stopped; close the door and press cycle start")
        elif st in (MachineState.IDLE, MachineState.ALARM):
            self._spindle.stop_spindle()
            self._alarms.raise_alarm("door", "the door was opened: the spindle stopped", Severity.WARNING,
                                     "door_open")

    def _lost(self, key: str, what: str) -> None:
        action = getattr(self._settings.config.wiring.interlocks, key.replace("_ok", "_lost"))
        text = f"{what} lost ({key} reads false)"
        moving = (MachineState.RUNNING, MachineState.HOLD, MachineState.HOMING)
        if action == "stop" and self._states.state in moving:
            self._alarms.alarm_stop(text + ": the motion stops", key, f"{key}_lost")
        else:
            self._alarms.raise_alarm(key, text, Severity.WARNING if action == "warning" else Severity.STOP,
                                     f"{key}_lost")

    # ------------------------------------------------------------------ the operator's
    def override_limits(self, on: bool = True) -> CommandResult:
        """While on, an axis standing on a limit switch may be re-enabled (reset) and jogged
        off it, never toward it (the 1 ms loop stops such a motion); it ends by itself once no
        limit switch reads active (LinuxCNC's override limits)."""
        if not self._drives.attached:
            return self._states.refuse("override_limits", "not connected")
        self._drives.override_limits(on)
        return self._states.ok("override_limits")

    def set_coolant(self, flood: bool | None = None, mist: bool | None = None) -> CommandResult:
        """The operator's coolant buttons (as M8 / M7 / M9); None leaves one as it is."""
        f = self._outputs.signal_on("coolant_flood") if flood is None else bool(flood)
        m = self._outputs.signal_on("coolant_mist") if mist is None else bool(mist)
        if self._states.state in (MachineState.ESTOP, MachineState.DISCONNECTED) and (f or m):
            return self._states.refuse("coolant", f"machine is {self._states.state.label.lower()}")
        why = self._outputs.set_coolant_state(f, m)
        return self._states.refuse("coolant", why) if why else self._states.ok("coolant")

    def set_work_light(self, on: bool) -> CommandResult:
        why = self._outputs.set_signal("work_light", on)
        return self._states.refuse("work_light", why) if why else self._states.ok("work_light")

    def simulate_input(self, key: str, value: bool | None) -> CommandResult:
        """Simulated drives: signal ``key`` reads ``value`` (the door opened, a button pressed,
        the E-stop chain cut) until released with None (back to what the simulated machine
        gives: its switches, its rest state). Refused on a real bus."""
        cfg = self._settings.config
        s = cfg.wiring.get(key)
        if cfg.bus.kind != "sim":
            return self._states.refuse("simulate_input", "only a simulated machine's inputs can be set")
        if s is None or s.signal.direction is not Direction.IN:
            known = " ".join(x.key for x in cfg.wiring.signals if x.signal.direction is Direction.IN)
            return self._states.refuse("simulate_input", f"{key!r} is not a wired input (inputs: {known})")
        if not self._drives.attached:
            return self._states.refuse("simulate_input", "not connected")
        k = cfg.wiring.terminal_index(s.wire.slave)
        level = value is not None and value != s.wire.inverted
        code = input_value(s.wire.bit, level, release=value is None)
        if k >= 0:
            self._drives.inject("terminal_input", k, code)
        else:
            self._drives.inject("drive_input", axis_at(cfg.machine, s.wire.slave), code)
        return self._states.ok("simulate_input")

    @property
    def coolant(self) -> tuple[bool, bool]:
        """(flood, mist) as switched now."""
        return self._outputs.signal_on("coolant_flood"), self._outputs.signal_on("coolant_mist")

    # ------------------------------------------------------------------ the program's coolant
    def _follow_job(self, job: Job, _all_done: bool) -> None:
        if job is not self._job:
            self._job = job
            program = getattr(job.plan, "program", None)
            events = program.events if program is not None else ()
            self._coolant = collections.deque((ev.after_move, ev.payload_as(CoolantSwitch).switch)
                                              for ev in events if ev.kind is EventKind.COOLANT)
        if not self._coolant:
            return
        snap = self._drives.last_snapshot
        move = job.move_at(int(snap.samples_consumed)) if snap is not None else None
        if move is None:
            return
        while self._coolant and self._coolant[0][0] < move:
            self._switch(self._coolant.popleft()[1])

    def _switch(self, switch: Coolant) -> None:
        why = self._outputs.set_coolant(switch)
        if why:
            self._alarms.alarm_stop(why, "coolant", "coolant")

    def _job_ended(self) -> None:
        """A job ends: an MDI block's coolant after its last move is switched now and stays; a
        program's goes off once the machine stands (``_transition``: the next piece of the same
        run may follow first)."""
        job, self._job = self._job, None
        pending, self._coolant = self._coolant, collections.deque()
        self._ended = job
        if job is not None and job.kind is not Activity.PROGRAM:
            for _after, switch in pending:
                self._switch(switch)

    def _transition(self, _old: MachineState, new: MachineState) -> None:
        """A program ended or stopped (the machine stands in IDLE): coolant off."""
        if new is not MachineState.IDLE:
            return
        ended, self._ended = self._ended, None
        if ended is not None and ended.kind is Activity.PROGRAM and any(self.coolant):
            self._switch(Coolant.ALL_OFF)

