"""The machine's digital outputs: the drives' (0x60FE:1) and the output terminals', one word
per slave, so setting one bit never clears another (the spindle's bits, the program's outputs of
M62-M65 and user M-codes, the machine's output signals: coolant, lube pump, work light, spindle
enable).

Safety: the program's outputs and the coolant go off on E-stop and on every reset, as the
spindle does (LinuxCNC's iocontrol switches coolant off at E-stop and abort); the program's
outputs stay as set through a feed hold, a stop and a program end (a program switches off what
it switched on). The lube pump runs while the drives are on. Outputs wired normally closed
("!" in ``[signals]``) are driven to their off level when the bus comes up.
"""

from __future__ import annotations

from app.machine.infra.drives import DriveLink
from app.machine.infra.events import MachineEvents
from app.machine.model import MachineState, Severity
from app.machine.motion.pauses import PauseHandlers
from app.machine.motion.timescale import PauseKind, PausePoint
from app.machine.ports import AlarmSink, Settings
from app.machine.wiring import Direction, axis_at
from planner.core.machine import io_place
from planner.core.program import Coolant, OutputLevel

__all__ = ["DigitalOutputs"]


class DigitalOutputs:
    """Output words by drive index, and the program's outputs by number (``controller.outputs``)."""

    def __init__(self, settings: Settings, drives: DriveLink, alarms: AlarmSink, events: MachineEvents,
                 pauses: PauseHandlers) -> None:
        self._settings = settings
        self._drives = drives
        self._alarms = alarms
        self.words: dict[int, int] = {}
        self.terminal_words: dict[int, int] = {}
        self.on: dict[int, bool] = {}          # program outputs by number
        self.signals_on: dict[str, bool] = {}  # output signals by key
        events.estop.connect(lambda _reason: self.all_off())
        events.reset.connect(lambda _state: self.all_off())
        events.connecting.connect(self._bus_up)
        events.transition.connect(self._transition)
        pauses.on(PauseKind.OUTPUT, self.at_pause)

    def set_bits(self, drive: int, mask: int, bits: int) -> None:
        """Set the masked bits of a drive's word and send it (raises what the worker raises)."""
        word = (self.words.get(drive, 0) & ~mask) | (bits & mask)
        self.words[drive] = word
        self._drives.set_digital_output(drive, word)

    def set_terminal_bits(self, terminal: int, mask: int, bits: int) -> None:
        """Set the masked bits of a terminal's output word and send it."""
        word = (self.terminal_words.get(terminal, 0) & ~mask) | (bits & mask)
        self.terminal_words[terminal] = word
        self._drives.set_terminal_output(terminal, word)

    def set_signal(self, key: str, on: bool) -> str:
        """An output signal (``coolant_flood``, ``work_light`` ...) on or off: "" when done, else why
        not (not wired, or the bus refused)."""
        cfg = self._settings.config
        s = cfg.wiring.get(key)
        if s is None:
            return f"{key} is not wired on this machine ([signals] {key})"
        level = on != s.wire.inverted
        mask = 1 << s.wire.bit
        try:
            k = cfg.wiring.terminal_index(s.wire.slave)
            if k >= 0:
                self.set_terminal_bits(k, mask, mask if level else 0)
            else:
                self.set_bits(axis_at(cfg.machine, s.wire.slave), mask, mask if level else 0)
        except Exception as exc:  # noqa: BLE001 - told to the caller
            return f"{key} could not be switched: {exc}"
        self.signals_on[key] = on
        return ""

    def set_coolant(self, switch: Coolant) -> str:
        """As a program's coolant event: M7 switches mist on, M8 flood, the other stays as it
        is; M9 switches both off. "" when done, else why not."""
        if switch is Coolant.ALL_OFF:
            return self.set_coolant_state(False, False)
        return self.set_coolant_state(switch is Coolant.FLOOD_ON or self.signal_on("coolant_flood"),
                                      switch is Coolant.MIST_ON or self.signal_on("coolant_mist"))

    def set_coolant_state(self, flood: bool, mist: bool) -> str:
        """Flood and mist coolant as given. "" when done, else why not."""
        for key, on in (("coolant_mist", mist), ("coolant_flood", flood)):
            if self._settings.config.wiring.has(key):
                why = self.set_signal(key, on)
                if why:
                    return why
            elif on:
                return f"{key} is not wired on this machine ([signals] {key})"
        return ""

    def signal_on(self, key: str) -> bool:
        return self.signals_on.get(key, False)

    def _bus_up(self) -> None:
        """A new worker starts with every output word 0: the output signals are driven to their
        off level (a normally closed one's bit set), as is what their words hold."""
        self.words.clear()
        self.terminal_words.clear()
        self.signals_on.clear()
        for s in self._settings.config.wiring.signals:
            if s.signal.direction is Direction.OUT and s.wire.inverted:
                self.set_signal(s.key, False)

    def _transition(self, _old: MachineState, new: MachineState) -> None:
        """The lube pump runs while the drives are on (any state but E-stop and disconnected)."""
        if not self._settings.config.wiring.has("lube_pump"):
            return
        on = new not in (MachineState.ESTOP, MachineState.DISCONNECTED)
        if on != self.signal_on("lube_pump"):
            self.set_signal("lube_pump", on)

    def set_output(self, number: int, on: bool) -> str:
        """A program output on or off; "" when done, else why not (a STOP alarm is raised too)."""
        spec = self._settings.config.machine.output_bits.get(number)
        if spec is None:
            why = f"output {number} is not defined in [[outputs]]"
        else:
            drive, bit, _name = spec
            try:
                self._set_place(drive, bit, on)
                self.on[number] = on
                return ""
            except Exception as exc:  # noqa: BLE001 - reported to the operator
                why = f"output {number} ({self.label(number)}) could not be switched: {exc}"
        self._alarms.alarm_stop(why, "outputs", "output")
        return why

    def at_pause(self, _job: object, point: PausePoint, _snap: object) -> bool:
        """M62-M65 or a user M-code reached by the motion: the output switches here; the motion
        goes on when it did."""
        output = point.payload_as(OutputLevel)
        return not self.set_output(output.number, output.on)

    def label(self, number: int) -> str:
        spec = self._settings.config.machine.output_bits.get(number)
        if spec is None:
            return f"output {number}"
        kind, where = io_place(spec[0])
        return spec[2] or f"{kind} {where} {'bit' if kind == 'drive' else 'channel'} {spec[1]}"

    def _set_place(self, drive: int, bit: int, on: bool) -> None:
        """An ``[[outputs]]`` bit: of a drive's word, or a terminal's channel (``io_place``)."""
        kind, where = io_place(drive)
        if kind == "drive":
            self.set_bits(where, 1 << bit, (1 << bit) if on else 0)
            return
        k = self._settings.config.wiring.terminal_index(where)
        self.set_terminal_bits(k, 1 << bit, (1 << bit) if on else 0)

    def all_off(self) -> None:
        """E-stop and reset: the coolant and every program output off (best effort; the spindle
        is its own)."""
        for key in ("coolant_mist", "coolant_flood"):
            if self.signal_on(key):
                why = self.set_signal(key, False)
                if why:
                    self._alarms.raise_alarm("outputs", why, Severity.WARNING, "output")
        for number, on in list(self.on.items()):
            if not on:
                continue
            spec = self._settings.config.machine.output_bits.get(number)
            if spec is None:
                continue
            drive, bit, _ = spec
            try:
                self._set_place(drive, bit, False)
                self.on[number] = False
            except Exception as exc:  # noqa: BLE001
                self._alarms.raise_alarm("outputs", f"output {number} could not be switched off: {exc}",
                                         Severity.WARNING, "output")
