"""The drives' digital outputs (0x60FE:1) as one word per drive: the spindle's bits and the
program's outputs (M62-M65, user M-codes; ``[[outputs]]`` in the machine configuration) share
a word, so setting one never clears the other.

Safety: the program's outputs go off on E-stop and on every reset, as the spindle does; they stay as
set through a feed hold, a stop and a program end (a program switches off what it switched on).
"""

from __future__ import annotations

from app.machine.infra.drives import DriveLink
from app.machine.infra.events import MachineEvents
from app.machine.model import Severity
from app.machine.motion.pauses import PauseHandlers
from app.machine.motion.timescale import PauseKind, PausePoint
from app.machine.ports import AlarmSink, Settings

__all__ = ["DigitalOutputs"]


class DigitalOutputs:
    """Output words by drive index, and the program's outputs by number (``controller.outputs``)."""

    def __init__(self, settings: Settings, drives: DriveLink, alarms: AlarmSink, events: MachineEvents,
                 pauses: PauseHandlers) -> None:
        self._settings = settings
        self._drives = drives
        self._alarms = alarms
        self.words: dict[int, int] = {}
        self.on: dict[int, bool] = {}          # program outputs by number
        events.estop.connect(lambda _reason: self.all_off())
        events.reset.connect(lambda _state: self.all_off())
        pauses.on(PauseKind.OUTPUT, self.at_pause)

    def set_bits(self, drive: int, mask: int, bits: int) -> None:
        """Set the masked bits of a drive's word and send it (raises what the worker raises)."""
        word = (self.words.get(drive, 0) & ~mask) | (bits & mask)
        self.words[drive] = word
        self._drives.set_digital_output(drive, word)

    def set_output(self, number: int, on: bool) -> str:
        """A program output on or off; "" when done, else why not (a STOP alarm is raised too)."""
        spec = self._settings.config.machine.output_bits.get(number)
        if spec is None:
            why = f"output {number} is not defined in [[outputs]]"
        else:
            drive, bit, _name = spec
            try:
                self.set_bits(drive, 1 << bit, (1 << bit) if on else 0)
                self.on[number] = on
                return ""
            except Exception as exc:  # noqa: BLE001 - reported to the operator
                why = f"output {number} ({self.label(number)}) could not be switched: {exc}"
        self._alarms.alarm_stop(why, "outputs", "output")
        return why

    def at_pause(self, _job: object, point: PausePoint, _snap: object) -> bool:
        """M62-M65 or a user M-code reached by the motion: the output switches here (the value
        is its number, or -(number + 1) to switch it off); the motion goes on when it did."""
        number = int(point.value) if point.value >= 0 else -int(point.value) - 1
        return not self.set_output(number, point.value >= 0)

    def label(self, number: int) -> str:
        spec = self._settings.config.machine.output_bits.get(number)
        return (spec[2] or f"drive {spec[0]} bit {spec[1]}") if spec else f"output {number}"

    def all_off(self) -> None:
        """E-stop and reset: every program output off (best effort; the spindle is its own)."""
        for number, on in list(self.on.items()):
            if not on:
                continue
            spec = self._settings.config.machine.output_bits.get(number)
            if spec is None:
                continue
            drive, bit, _ = spec
            try:
                self.set_bits(drive, 1 << bit, 0)
                self.on[number] = False
            except Exception as exc:  # noqa: BLE001
                self._alarms.raise_alarm("outputs", f"output {number} could not be switched off: {exc}",
                                         Severity.WARNING, "output")
