"""Spindle on CW/CCW/off and speed, by hand and from the program: the drive's digital outputs
(bit 0 on, bit 1 counter-clockwise), with a VFD's speed on an analog output terminal's channel
(``[spindle] analog_out``: 0-10 V for 0 to ``analog_rpm_at_10v``); or the spindle's own CiA 402
drive in a velocity mode (``[spindle] drive``): then the speed (S x override, signed) goes to
that drive, at speed is the speed its drive reads within ``at_speed_pct`` of it, and a spindle
that falls below that band for ``speed_loss_s`` while a program turns it at speed holds the
program with an alarm.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from app.machine.devices.outputs import DigitalOutputs
from app.machine.infra.drives import DriveLink
from app.machine.infra.events import MachineEvents, PanelChannels
from app.machine.model import CommandResult, MachineState, Severity, SpindleState
from app.machine.motion.spinup import spins_up
from app.machine.ports import AlarmSink, Settings, SignalValues
from app.machine.spindle_settings import SpindleDriveSettings
from app.machine.state.gate import Action, guarded
from app.machine.state.overrides import Override, Overrides
from app.machine.state.states import StateMachine
from app.machine.wiring import analog_place
from ethercat.terminals import ANALOG_FULL_SCALE
from ethercat.worker import WorkerSnapshot

__all__ = ["SpindleControl"]

# never below half: a slowed spindle under the same feed overloads the cutter


#: with the at-speed signal wired: the least wait after a spin-up command (the drive sees it)
AT_SPEED_MIN_S = 0.1


def at_speed_timeout_s(spinup_s: float) -> float:
    """How long a spin-up may take before the missing at-speed signal is an alarm."""
    return max(10.0, 5.0 * spinup_s)


class SpindleControl:
    """The spindle: its state, turned at S times the override the override model gives it
    (``Overrides.spindle_pct_at``: the knob, the program's lock, the cap) (``controller.spindle_ctl``).
    It stops on E-stop, faults and reset."""

    def __init__(self, settings: Settings, states: StateMachine, drives: DriveLink, outputs: DigitalOutputs,
                 alarms: AlarmSink, out: PanelChannels, events: MachineEvents, signals: SignalValues,
                 overrides: Overrides) -> None:
        self._settings = settings
        self._overrides = overrides
        self._signals = signals
        self._states = states
        self._drives = drives
        self._outputs = outputs
        self._alarms = alarms
        self._out = out
        self._events = events
        self.spindle = SpindleState()
        # what turned before the door opened in a hold: it turns again, at speed, before the
        # program goes on (``restart_after_hold``)
        self.stopped_for_hold: SpindleState | None = None
        self._at_speed_late = False
        #: the spindle's own drive as last read: the speed commanded and read (rpm, signed),
        #: whether it has been at speed since its last change, and since when it is not
        self.drive_rpm = (0.0, 0.0)
        self._reached = False
        self._below_since: float | None = None
        self._lost_told = False
        events.estop.connect(lambda _reason: self._stop_for_good())
        events.fault.connect(lambda _cause: self._stop_for_good())
        events.reset.connect(lambda _state: self._stop_for_good())
        events.shutdown.connect(self.stop_spindle)
        events.announce.connect(self.announce)

    @property
    def gate(self) -> StateMachine:
        return self._states

    @property
    def _max_rpm(self) -> float:
        return float(self._settings.config.controller.spindle_max_rpm)

    def _override_for(self, rpm: float) -> float:
        return self._overrides.spindle_pct_at(rpm, self._max_rpm)

    @property
    def _drive(self) -> SpindleDriveSettings | None:
        s = self._settings.config.spindle
        return s if s.drive is not None else None

    def apply_spindle(self, sp: SpindleState) -> None:
        rpm = min(abs(sp.rpm), self._max_rpm)
        sp = SpindleState(direction=int(np.sign(sp.direction)), rpm=rpm, override_pct=self._override_for(rpm))
        drive = self._drive
        if drive is not None:
            self._apply_drive(sp, drive)
        elif self._drives.attached:
            bits = 0 if sp.direction == 0 else (0b01 | (0b10 if sp.direction < 0 else 0))
            try:
                self._outputs.set_bits(self._settings.config.controller.spindle_drive, 0b11, bits)
            except Exception as exc:  # noqa: BLE001
                if sp.on and self._states.state in (MachineState.RUNNING, MachineState.HOLD):
                    self._alarms.alarm_stop(f"spindle output failed: {exc}", "spindle", "spindle")
                else:
                    self._alarms.raise_alarm("spindle", f"spindle output failed: {exc}", Severity.WARNING,
                                             "spindle")
            if self._settings.config.wiring.has("spindle_enable"):
                self._outputs.set_signal("spindle_enable", sp.on)
            if self._settings.config.spindle.analog_out:
                self._set_analog(sp)
        self.spindle = sp
        self._out.spindleChanged.emit(sp)

    def analog_value(self, sp: SpindleState) -> int:
        """The VFD's analog output for ``sp``: S x override over the speed at 10 V, in the
        terminal's INT16 (0x7FFF = 10 V), 0 while it stands; never beyond 10 V."""
        cfg = self._settings.config
        return round(ANALOG_FULL_SCALE * cfg.spindle.analog_share(sp.commanded_rpm, sp.on,
                                                                  cfg.controller.spindle_max_rpm))

    def _set_analog(self, sp: SpindleState) -> None:
        k, channel = analog_place(self._settings.config.wiring, self._settings.config.spindle.analog_out)
        shift = 16 * channel
        try:
            self._outputs.set_terminal_bits(k, 0xFFFF << shift, self.analog_value(sp) << shift)
        except Exception as exc:  # noqa: BLE001 - told as the bits' failure is
            self._alarms.raise_alarm("spindle", f"the spindle's speed output failed: {exc}", Severity.WARNING,
                                     "spindle")

    def _apply_drive(self, sp: SpindleState, drive: SpindleDriveSettings) -> None:
        """The spindle's own drive to S x override, signed by the direction (0: it stops)."""
        rpm = sp.direction * sp.commanded_rpm
        if rpm != self.drive_rpm[0]:
            self._reached = False
            self._below_since = None
        if not self._drives.attached:
            return
        if not self._drives.spindle(rpm, drive.accel_rpm_s) and sp.on:
            if self._states.state in (MachineState.RUNNING, MachineState.HOLD):
                self._alarms.alarm_stop("the spindle's drive refused to turn (faulted, stopping, or the "
                                        "drives are off)", "spindle", "spindle")
            else:
                self._alarms.raise_alarm("spindle", "the spindle's drive refused to turn (faulted, stopping, "
                                         "or the drives are off)", Severity.WARNING, "spindle")
        if self._settings.config.wiring.has("spindle_enable"):
            self._outputs.set_signal("spindle_enable", sp.on)

    def poll(self, snap: WorkerSnapshot) -> None:
        """The spindle's own drive as read: its speeds; a loss of speed while a program turns it
        at speed is a STOP alarm (the program holds where it is, resumable)."""
        drive = self._drive
        if drive is None:
            return
        cmd, act = float(snap.spindle_rpm_command), float(snap.spindle_rpm_actual)
        self.drive_rpm = (cmd, act)
        self._out.spindleSample.emit(float(snap.time_s), cmd, act)
        target = self.spindle.direction * self.spindle.commanded_rpm
        if not self.spindle.on or cmd != target:
            self._reached, self._below_since = False, None
            return
        now = float(snap.time_s)
        if drive.at_speed(cmd, act):
            self._reached, self._below_since, self._lost_told = True, None, False
        elif self._reached:
            if self._below_since is None:
                self._below_since = now
            elif (now - self._below_since >= drive.speed_loss_s and not self._lost_told
                  and self._states.state is MachineState.RUNNING):
                self._lost_told = True
                self._alarms.alarm_stop(
                    f"the spindle lost speed: {abs(act):.0f} rpm read against {abs(cmd):.0f} commanded for "
                    f"{drive.speed_loss_s:g} s (a band of {drive.at_speed_pct:g} %)", "spindle",
                    "spindle_speed")

    def simulate_spindle_load(self, rpm: float | None) -> CommandResult:
        """A simulated machine's spindle drive bogged down by a load to at most ``rpm`` (None:
        the load taken off): a spindle losing speed in the cut, for a demo or a script."""
        why = self._load_refusal(rpm)
        if why:
            return self._states.refuse("simulate_spindle_load", why)
        if rpm is None:
            self._drives.inject("spindle_unload", 0, 0)
        else:
            self._drives.inject("spindle_load", 0, int(round(rpm)))
        return self._states.ok("simulate_spindle_load")

    def _load_refusal(self, rpm: float | None) -> str:
        if self._drive is None:
            return ("this machine's spindle has no drive of its own ([spindle] drive): no speed is read "
                    "to lose")
        if self._settings.config.bus.kind != "sim":
            return "only a simulated spindle drive can be loaded"
        if not self._drives.attached:
            return "the bus is not connected"
        if rpm is not None and not 0.0 <= rpm <= self._max_rpm:
            return f"a load holds the spindle at 0-{self._max_rpm:g} rpm, got {rpm:g}"
        return ""

    def _stop_for_good(self) -> None:
        self.stopped_for_hold = None
        self.stop_spindle()

    def stop_for_hold(self) -> None:
        """The door opened in a hold: the spindle stops, and turns again on the way out of the
        hold (``restart_after_hold``)."""
        if self.spindle.on:
            self.stopped_for_hold = self.spindle
            self.stop_spindle()

    def restart_after_hold(self) -> float:
        """Leaving a hold: a spindle the door stopped turns again as before; one on its own
        drive that does not read its speed (the override changed during the hold) is waited
        for. Returns how long the motion waits at least before it asks ``at_speed`` (0: it
        goes on at once)."""
        before, self.stopped_for_hold = self.stopped_for_hold, None
        if before is None or self.spindle.on:
            waits = self._drive is not None and self.spindle.on and not self._reached
            return AT_SPEED_MIN_S if waits else 0.0
        wait = self.spin_up_s(before)
        self.apply_spindle(SpindleState(direction=before.direction, rpm=before.rpm))
        return wait

    def set_program_lock(self, locked: bool) -> None:
        """The program turned the spindle override off (True) or on again from here: the speed
        follows; the outputs (direction) stay as they are."""
        if self._overrides.lock_spindle(locked):
            self.spindle = replace(self.spindle, override_pct=self._override_for(self.spindle.rpm))
            self._out.spindleChanged.emit(self.spindle)

    def spin_up_s(self, new: SpindleState) -> float:
        """How long the motion waits after switching to ``new``: the configured spin-up time
        when the spindle starts, reverses or speeds up, else 0. With ``spindle_at_speed`` wired,
        the motion waits for that signal instead (``at_speed``), at least ``AT_SPEED_MIN_S``: the
        time the drive takes to see the new speed (its signal may still be true from before)."""
        if not spins_up(self.spindle, new):
            return 0.0
        if self._drive is not None or self._settings.config.wiring.has("spindle_at_speed"):
            return AT_SPEED_MIN_S
        return float(self._settings.config.controller.spindle_spinup_s)

    def at_speed(self, now_s: float, until_s: float) -> bool:
        """Whether the motion may go on after a spin-up that waits until ``until_s``: then, and
        with ``spindle_at_speed`` wired, once it reads true. It not reading true within
        ``at_speed_timeout_s`` of that is a STOP alarm (the motion stays at rest)."""
        if now_s < until_s:
            return False
        drive = self._drive
        if drive is None and not self._settings.config.wiring.has("spindle_at_speed"):
            return True
        if self._reached if drive is not None else self._signals.value("spindle_at_speed"):
            self._at_speed_late = False
            return True
        spinup = self._settings.config.controller.spindle_spinup_s
        if drive is not None:
            spinup = max(spinup, drive.spin_up_s(0.0, self._max_rpm))
        timeout = at_speed_timeout_s(spinup)
        if now_s > until_s + timeout and not self._at_speed_late:
            self._at_speed_late = True
            if drive is not None:
                self._alarms.alarm_stop(f"the spindle did not reach its speed within {timeout:g} s: its "
                                        f"drive reads {abs(self.drive_rpm[1]):.0f} rpm", "spindle",
                                        "spindle_at_speed")
            else:
                self._alarms.alarm_stop(f"the spindle did not report at speed (spindle_at_speed) within "
                                        f"{timeout:g} s", "spindle", "spindle_at_speed")
        return False

    def set_override(self, percent: float) -> CommandResult:
        """Spindle override 50-150 %: the speed the program asks for times this, at once
        (capped at the spindle's maximum speed, and the operator told so)."""
        p = float(percent)
        why = self._overrides.set(Override.SPINDLE, p)
        if why:
            return self._states.refuse(Action.SET_SPINDLE_OVERRIDE, why)
        before = self.drive_rpm[1]
        self.apply_spindle(self.spindle)
        drive = self._drive
        rpm = self.spindle.direction * self.spindle.commanded_rpm
        if (drive is not None and self.spindle.on and self._states.state is MachineState.RUNNING
                and not drive.at_speed(rpm, before)):
            self._out.message.emit(f"spindle override {p:g} %: the feed waits until the spindle turns at "
                                   f"{abs(rpm):.0f} rpm")
            self._events.spindle_speed_changed.emit()
        if self._overrides.spindle_locked:
            self._out.message.emit(f"spindle override {p:g} % not applied now: the program turned it off "
                                   "(tapping, M49 or M51 P0); it applies once the program turns it on")
        elif self.spindle.override_pct < p:
            self._out.message.emit(f"spindle override {p:g} % capped at {self.spindle.override_pct:.0f} %: "
                                   f"the spindle's maximum is {self._max_rpm:g} rpm")
        return self._states.ok(Action.SET_SPINDLE_OVERRIDE)

    def stop_spindle(self) -> None:
        """Spindle off if it runs (stop, reset, program end, alarms, E-stop); the speed is kept
        for the next start."""
        if self.spindle.on:
            self.apply_spindle(SpindleState(direction=0, rpm=self.spindle.rpm))

    @guarded(Action.SPINDLE_ON)
    def spindle_on(self, clockwise: bool = True, rpm: float | None = None) -> CommandResult:
        """Spindle on, clockwise (M03) or counter-clockwise (M04), at ``rpm`` (last speed if None)."""
        speed = self.spindle.rpm if rpm is None else float(rpm)
        if not 0.0 <= speed <= self._max_rpm:
            return self._states.refuse(Action.SPINDLE_ON, f"speed must be 0-{self._max_rpm:g} rpm")
        self.apply_spindle(SpindleState(direction=1 if clockwise else -1, rpm=speed))
        return self._states.ok(Action.SPINDLE_ON)

    def spindle_off(self) -> CommandResult:
        """Spindle off (M05); always allowed."""
        self.apply_spindle(SpindleState(direction=0, rpm=self.spindle.rpm))
        return self._states.ok("spindle_off")

    def spindle_speed(self, rpm: float) -> CommandResult:
        """Set the spindle speed (applied at once when running)."""
        speed = float(rpm)
        if not 0.0 <= speed <= self._max_rpm:
            return self._states.refuse(Action.SPINDLE_SPEED, f"speed must be 0-{self._max_rpm:g} rpm")
        if self.spindle.on:
            self.apply_spindle(SpindleState(direction=self.spindle.direction, rpm=speed))
        else:
            self.spindle = SpindleState(direction=0, rpm=speed)
            self._out.spindleChanged.emit(self.spindle)
        return self._states.ok(Action.SPINDLE_SPEED)

    def announce(self) -> None:
        self._out.spindleChanged.emit(self.spindle)
