"""Spindle on CW/CCW/off and speed, by hand and from the program: the drive's digital outputs
(bit 0 on, bit 1 counter-clockwise). Part of ``MachineController`` (mixed in).
"""

from __future__ import annotations

import numpy as np

from app.machine.model import CommandResult, Severity, SpindleState

__all__ = ["SpindleMixin"]


class SpindleMixin:
    """Spindle commands and output.

    Mixed into ``MachineController``, which holds the state.
    """

    def _apply_spindle(self, sp: SpindleState) -> None:
        rpm = min(abs(sp.rpm), self._cfg.controller.spindle_max_rpm)
        sp = SpindleState(direction=int(np.sign(sp.direction)), rpm=rpm)  # rpm capped by the config
        if self._worker is not None:
            bits = 0 if sp.direction == 0 else (0b01 | (0b10 if sp.direction < 0 else 0))
            try:
                with self._lock:
                    self._worker.set_digital_output(self._cfg.controller.spindle_drive, bits)
            except Exception as exc:  # noqa: BLE001
                if self._job is not None and sp.on:
                    self._alarm_stop(f"spindle output failed: {exc}", "spindle", "spindle")
                else:
                    self._raise_alarm("spindle", f"spindle output failed: {exc}", Severity.WARNING, "spindle")
        self._spindle = sp
        self.spindleChanged.emit(sp)

    def spindle_on(self, clockwise: bool = True, rpm: float | None = None) -> CommandResult:
        """Spindle on, clockwise (M03) or counter-clockwise (M04), at ``rpm`` (last speed if None)."""
        why = self.refusal("spindle_on")
        if why:
            return self._refuse("spindle_on", why)
        speed = self._spindle.rpm if rpm is None else float(rpm)
        if not 0.0 <= speed <= self._cfg.controller.spindle_max_rpm:
            return self._refuse("spindle_on", f"speed must be 0-{self._cfg.controller.spindle_max_rpm:g} rpm")
        self._apply_spindle(SpindleState(direction=1 if clockwise else -1, rpm=speed))
        return self._ok("spindle_on")

    def spindle_off(self) -> CommandResult:
        """Spindle off (M05); always allowed."""
        self._apply_spindle(SpindleState(direction=0, rpm=self._spindle.rpm))
        return self._ok("spindle_off")

    def spindle_speed(self, rpm: float) -> CommandResult:
        """Set the spindle speed (applied at once when running)."""
        speed = float(rpm)
        if not 0.0 <= speed <= self._cfg.controller.spindle_max_rpm:
            return self._refuse(
                "spindle_speed", f"speed must be 0-{self._cfg.controller.spindle_max_rpm:g} rpm"
            )
        if self._spindle.on:
            self._apply_spindle(SpindleState(direction=self._spindle.direction, rpm=speed))
        else:
            self._spindle = SpindleState(direction=0, rpm=speed)
            self.spindleChanged.emit(self._spindle)
        return self._ok("spindle_speed")
