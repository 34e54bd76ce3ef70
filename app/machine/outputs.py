"""The drives' digital outputs (0x60FE:1) as one word per drive: the spindle's bits and the
program's outputs (M62-M65, user M-codes; ``[[outputs]]`` in the machine configuration) share
a word, so setting one never clears the other. A part of ``MachineController``.

Safety: the program's outputs go off on E-stop and on reset, as the spindle does; they stay as
set through a feed hold, a stop and a program end (a program switches off what it switched on).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from app.machine.model import Severity

if TYPE_CHECKING:
    from app.machine.controller import MachineController
    from planner.program import Program

__all__ = ["DigitalOutputs", "analog_refusal"]


def analog_refusal(program: Program) -> tuple[int, str]:
    """Why this machine cannot run a program's M67/M68, with the line ((0, "") when it has
    none): its drives' outputs are digital (0x60FE); it has no analog output to set."""
    for out in program.analog_outputs:
        return out.line, (f"{out.code} E{out.index} sets an analog output, and this machine has none "
                          "(its drives' outputs are digital: M62-M65)")
    return 0, ""


class DigitalOutputs:
    """Output words by drive index, and the program's outputs by number."""

    def __init__(self, m: MachineController) -> None:
        self.m = m
        self.words: dict[int, int] = {}
        self.on: dict[int, bool] = {}          # program outputs by number

    def set_bits(self, drive: int, mask: int, bits: int) -> None:
        """Set the masked bits of a drive's word and send it (raises what the worker raises)."""
        word = (self.words.get(drive, 0) & ~mask) | (bits & mask)
        self.words[drive] = word
        if self.m.worker is not None:
            with self.m._lock:
                self.m.worker.set_digital_output(drive, word)

    def set_output(self, number: int, on: bool) -> str:
        """A program output on or off; "" when done, else why not (an alarm is raised too)."""
        spec = self.m.config.machine.output_bits.get(number)
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
        self.m.alarm_log.alarm_stop(why, "outputs", "output")
        return why

    def label(self, number: int) -> str:
        spec = self.m.config.machine.output_bits.get(number)
        return (spec[2] or f"drive {spec[0]} bit {spec[1]}") if spec else f"output {number}"

    def all_off(self) -> None:
        """E-stop and reset: every program output off (best effort; the spindle is its own)."""
        for number, on in list(self.on.items()):
            if not on:
                continue
            spec = self.m.config.machine.output_bits.get(number)
            if spec is None:
                continue
            drive, bit, _ = spec
            try:
                self.set_bits(drive, 1 << bit, 0)
                self.on[number] = False
            except Exception as exc:  # noqa: BLE001
                self.m.alarm_log.raise_alarm("outputs", f"output {number} could not be switched off: {exc}",
                                             Severity.WARNING, "output")
