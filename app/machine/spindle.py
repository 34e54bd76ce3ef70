"""Spindle on CW/CCW/off and speed, by hand and from the program: the drive's digital outputs
(bit 0 on, bit 1 counter-clockwise). A part of ``MachineController``.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import replace
from typing import TYPE_CHECKING, Any

import numpy as np

from app.machine.model import CommandResult, Severity, SpindleState

if TYPE_CHECKING:
    from app.machine.controller import MachineController
    from planner.program import Program

__all__ = ["OVERRIDE_MAX_PCT", "OVERRIDE_MIN_PCT", "SpindleControl", "spin_up_waits", "spins_up",
           "synchronised_refusal"]

# never below half: a slowed spindle under the same feed overloads the cutter
OVERRIDE_MIN_PCT = 50.0
OVERRIDE_MAX_PCT = 150.0


def synchronised_refusal(program: Program) -> tuple[int, str]:
    """Why this machine cannot run a program's spindle-synchronised motion (G33, G76), with its
    line ((0, "") when it has none). Each pass of a thread must start at the same spindle angle;
    this spindle is switched by a drive's digital outputs and has no encoder to give its angle,
    so the passes would each cut a thread of their own. (G33.1 rigid tapping runs: it goes in
    and back out once, and a floating tap holder takes up the difference.)"""
    for motion in program.synchronised:
        return motion.line, (f"{motion.code} is spindle-synchronised motion: every pass of a thread must "
                             "start at the same spindle angle, and this machine's spindle has no encoder "
                             "to give it; it cannot run here")
    return 0, ""


def spins_up(old: SpindleState, new: SpindleState) -> bool:
    """Whether switching from ``old`` to ``new`` makes the motion wait for the spindle: it
    starts, reverses or speeds up."""
    return new.on and (not old.on or old.direction != new.direction or new.rpm > old.rpm)


def spin_up_waits(pauses: Iterable[Any], start: SpindleState, spin_up_s: float) -> list[tuple[float, float]]:
    """(planned time, wait) of every spin-up a run through these pause points
    (``timescale.pause_points``) waits for, from the spindle state ``start``: an M3/M4/S that
    starts, reverses or speeds the spindle up, and the restart after a tool change with the
    spindle on (it stops while hands are near it). The run's cycle time and the time left
    count them: the motion stands while the spindle comes up to speed."""
    waits: list[tuple[float, float]] = []
    state = start
    for p in pauses:
        if p.kind == "spindle":
            new = SpindleState(direction=int(np.sign(p.value)), rpm=abs(float(p.value)))
            if spins_up(state, new) and spin_up_s > 0.0:
                waits.append((float(p.tau_s), spin_up_s))
            state = new
        elif p.kind == "tool_change" and state.on and spin_up_s > 0.0:
            waits.append((float(p.tau_s), spin_up_s))
    return waits


class SpindleControl:
    """Spindle commands and output.

    A part of ``MachineController`` (``controller.spindle_ctl``): it owns the state set up in
    ``__init__`` and reaches the other parts through the facade ``m``.
    """

    def __init__(self, m: MachineController) -> None:
        self.m = m
        self.spindle = SpindleState()
        self.override_pct = 100.0
        # the running program turned the spindle override off here (tapping, M49, M51 P0): the
        # spindle turns at S whatever the knob says, and back at the knob once it turns it on
        self.program_lock = False

    def _override_for(self, rpm: float) -> float:
        """The override the spindle takes at ``rpm``: the knob's, or 100 % where the program
        turned it off; capped so S x override never exceeds the maximum."""
        top = 100.0 * self.m.config.controller.spindle_max_rpm / rpm if rpm > 0 else OVERRIDE_MAX_PCT
        return min(100.0 if self.program_lock else self.override_pct, top)

    def apply_spindle(self, sp: SpindleState) -> None:
        rpm = min(abs(sp.rpm), self.m.config.controller.spindle_max_rpm)
        sp = SpindleState(direction=int(np.sign(sp.direction)), rpm=rpm, override_pct=self._override_for(rpm))
        if self.m.worker is not None:
            bits = 0 if sp.direction == 0 else (0b01 | (0b10 if sp.direction < 0 else 0))
            try:
                self.m.outputs.set_bits(self.m.config.controller.spindle_drive, 0b11, bits)
            except Exception as exc:  # noqa: BLE001
                if self.m.stream.job is not None and sp.on:
                    self.m.alarm_log.alarm_stop(f"spindle output failed: {exc}", "spindle", "spindle")
                else:
                    self.m.alarm_log.raise_alarm(
                        "spindle", f"spindle output failed: {exc}", Severity.WARNING, "spindle"
                    )
        self.spindle = sp
        self.m.spindleChanged.emit(sp)

    def set_program_lock(self, locked: bool) -> None:
        """The program turned the spindle override off (True) or on again from here: the speed
        follows; the outputs (direction) stay as they are."""
        if locked != self.program_lock:
            self.program_lock = locked
            self.spindle = replace(self.spindle, override_pct=self._override_for(self.spindle.rpm))
            self.m.spindleChanged.emit(self.spindle)

    def spin_up_s(self, new: SpindleState) -> float:
        """How long the motion waits after switching to ``new``: the configured spin-up time
        when the spindle starts, reverses or speeds up, else 0."""
        return float(self.m.config.controller.spindle_spinup_s) if spins_up(self.spindle, new) else 0.0

    def set_override(self, percent: float) -> CommandResult:
        """Spindle override 50-150 %: the speed the program asks for times this, at once
        (capped at the spindle's maximum speed, and the operator told so)."""
        p = float(percent)
        if not OVERRIDE_MIN_PCT <= p <= OVERRIDE_MAX_PCT:
            return self.m.states.refuse(
                "set_spindle_override",
                f"spindle override must be {OVERRIDE_MIN_PCT:g}-{OVERRIDE_MAX_PCT:g} %, got {p:g}")
        self.override_pct = p
        self.apply_spindle(self.spindle)
        if self.program_lock:
            self.m.message.emit(f"spindle override {p:g} % not applied now: the program turned it off "
                                "(tapping, M49 or M51 P0); it applies once the program turns it on")
        elif self.spindle.override_pct < p:
            self.m.message.emit(f"spindle override {p:g} % capped at {self.spindle.override_pct:.0f} %: "
                                f"the spindle's maximum is {self.m.config.controller.spindle_max_rpm:g} rpm")
        return self.m.states.ok("set_spindle_override")

    def stop_spindle(self) -> None:
        """Spindle off if it runs (stop, reset, program end, alarms, E-stop); the speed is kept
        for the next start."""
        if self.spindle.on:
            self.apply_spindle(SpindleState(direction=0, rpm=self.spindle.rpm))

    def spindle_on(self, clockwise: bool = True, rpm: float | None = None) -> CommandResult:
        """Spindle on, clockwise (M03) or counter-clockwise (M04), at ``rpm`` (last speed if None)."""
        why = self.m.states.refusal("spindle_on")
        if why:
            return self.m.states.refuse("spindle_on", why)
        speed = self.spindle.rpm if rpm is None else float(rpm)
        if not 0.0 <= speed <= self.m.config.controller.spindle_max_rpm:
            return self.m.states.refuse(
                "spindle_on", f"speed must be 0-{self.m.config.controller.spindle_max_rpm:g} rpm"
            )
        self.apply_spindle(SpindleState(direction=1 if clockwise else -1, rpm=speed))
        return self.m.states.ok("spindle_on")

    def spindle_off(self) -> CommandResult:
        """Spindle off (M05); always allowed."""
        self.apply_spindle(SpindleState(direction=0, rpm=self.spindle.rpm))
        return self.m.states.ok("spindle_off")

    def spindle_speed(self, rpm: float) -> CommandResult:
        """Set the spindle speed (applied at once when running)."""
        speed = float(rpm)
        if not 0.0 <= speed <= self.m.config.controller.spindle_max_rpm:
            return self.m.states.refuse(
                "spindle_speed", f"speed must be 0-{self.m.config.controller.spindle_max_rpm:g} rpm"
            )
        if self.spindle.on:
            self.apply_spindle(SpindleState(direction=self.spindle.direction, rpm=speed))
        else:
            self.spindle = SpindleState(direction=0, rpm=speed)
            self.m.spindleChanged.emit(self.spindle)
        return self.m.states.ok("spindle_speed")
