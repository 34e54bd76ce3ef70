"""Drive-side homing (CiA 402 mode 6) of one axis, cycle by cycle.

Sequence: the homing method (0x6098) is written by SDO outside the cycle (the loop's
acyclic helper) while the axis holds its position in CSP; then mode 6 is requested, bit 4 of
the controlword raised once the drive displays mode 6, the result read from the statusword
(homing attained + target reached, or homing error, or the timeout), and mode 8 (CSP)
requested again; the loop follows set-points once the drive displays CSP.
"""

from __future__ import annotations

import enum

import numpy as np

from .. import cia402
from ..bus import Bus
from .types import HomingState

__all__ = ["Homing", "HomingPhase", "HomingResult"]


class HomingPhase(enum.IntEnum):
    WRITING_METHOD = 0   # 0x6098 being written by the acyclic helper
    MODE_REQUESTED = 1   # mode 6 requested, waiting for the drive to display it
    START = 2            # bit 4 raised this cycle
    RUNNING = 3          # waiting for attained / error / timeout
    LEAVING = 4          # mode 8 requested, waiting for the drive to display it


class HomingResult(enum.Enum):
    GOING = "going"
    FINISHED = "finished"          # back in CSP (homed or not: see homing state)
    FAILED = "failed"              # stopped with an error (alarm reason in `failure`)


class Homing:
    """One axis' homing, driven by the loop's outputs and inputs steps."""

    EDGE_CYCLES = 2  # cycles the drive gets to see the start edge before its bits are judged

    def __init__(self, homing_state: np.ndarray, homed: np.ndarray, timeout_cycles: int) -> None:
        self.state = homing_state          # shared: HomingState per axis
        self.homed = homed                 # shared: 1 per homed axis
        self.timeout_cycles = timeout_cycles
        self.axis = -1
        self.method = 0
        self.phase = HomingPhase.WRITING_METHOD
        self.cycles = 0
        self.failure = 0                   # HOMING_ERROR's reason: 0 drive error, 1 timeout, 2 method refused

    @property
    def active(self) -> bool:
        return self.axis >= 0

    def begin(self, axis: int, method: int) -> None:
        self.axis = axis
        self.method = method
        self.phase = HomingPhase.WRITING_METHOD
        self.cycles = 0
        self.state[axis] = HomingState.RUNNING
        self.homed[axis] = 0

    def cancel(self) -> None:
        self.axis = -1

    def method_written(self, bus: Bus, error: str) -> HomingResult:
        """The acyclic write of 0x6098 finished (error "" when it was accepted)."""
        a = self.axis
        if error:
            self.state[a] = HomingState.ERROR
            self.failure = 2
            self.axis = -1
            return HomingResult.FAILED
        bus.modes_of_operation[a] = cia402.HOMING
        self.phase = HomingPhase.MODE_REQUESTED
        return HomingResult.GOING

    def outputs(self, bus: Bus) -> None:
        """Controlword of the homing axis (the others keep following their set-points)."""
        a = self.axis
        bus.target_position[a] = bus.position_actual[a]
        cw = cia402.CW_ENABLE_OPERATION
        if self.phase is HomingPhase.START or self.phase is HomingPhase.RUNNING:
            cw |= cia402.CW_HOMING_START
        bus.controlword[a] = cw

    def inputs(self, bus: Bus) -> HomingResult:
        """Advance on the drive's answer; FINISHED once the drive is back in CSP."""
        a = self.axis
        self.cycles += 1
        phase = self.phase
        if phase is HomingPhase.MODE_REQUESTED:
            if int(bus.modes_display[a]) == cia402.HOMING:
                self.phase = HomingPhase.START
                self.cycles = 0
        elif phase is HomingPhase.START:
            self.phase = HomingPhase.RUNNING
            self.cycles = 0
        elif phase is HomingPhase.RUNNING and self.cycles > self.EDGE_CYCLES:
            sw = int(bus.statusword[a])
            attained = sw & cia402.SW_HOMING_ATTAINED and sw & cia402.SW_TARGET_REACHED
            error = sw & cia402.SW_HOMING_ERROR
            timeout = self.cycles > self.timeout_cycles
            if attained or error or timeout:
                ok = bool(attained) and not error
                self.state[a] = HomingState.DONE if ok else HomingState.ERROR
                self.homed[a] = 1 if ok else 0
                self.failure = 1 if timeout and not ok else 0
                bus.modes_of_operation[a] = cia402.CSP
                self.phase = HomingPhase.LEAVING
                if not ok:
                    return HomingResult.FAILED
        elif phase is HomingPhase.LEAVING:
            if int(bus.modes_display[a]) == cia402.CSP:
                self.axis = -1
                return HomingResult.FINISHED
        return HomingResult.GOING
