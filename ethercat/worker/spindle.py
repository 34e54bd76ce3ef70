"""The spindle on its own CiA 402 drive, cycle by cycle (``WorkerConfig.spindle``).

The drive runs in cyclic synchronous velocity (mode 9: the loop ramps the speed and sends the
ramp every cycle) or profile velocity (mode 3: the loop sends the speed, the drive ramps it
with its own 0x6083 and 0x6084). A speed other than 0 enables the drive (walking its state
machine to OPERATION ENABLED) and turns it; 0 ramps it down and, once the commanded speed is
0, disables it. The loop reports the speed it commands and the one the drive reads (0x606C),
both in rpm.

Safety: a quick stop of the machine (E-stop, a drive fault, a lost slave, a limit switch ...)
quick-stops the spindle too, and its command is 0 until the controller asks again; a fault of
the spindle's drive (or its not enabling in time) is an alarm. Nothing here allocates.
"""

from __future__ import annotations

import enum

from .. import cia402
from ..bus import Bus, SpindleDriveSpec
from ..cia402 import Cia402State
from .shared import LiveFields

__all__ = ["SpindleFault", "SpindleLoop", "SpindleState"]

_OE = int(Cia402State.OPERATION_ENABLED)
_FAULTS = (int(Cia402State.FAULT), int(Cia402State.FAULT_REACTION_ACTIVE))
#: OPERATION ENABLED seen this many cycles in a row: enabled (a drive answers a cycle late)
CONFIRM_CYCLES = 3


class SpindleState(enum.IntEnum):
    OFF = 0           # drive disabled, at rest
    ENABLING = 1      # walking to OPERATION ENABLED
    RUNNING = 2       # enabled, following the commanded speed
    STOPPING = 3      # quick stop (the machine stopped) until at rest
    FAULT = 4         # its drive in FAULT: a fault reset clears it


class SpindleFault(enum.IntEnum):
    DRIVE = 1         # the drive faulted (b: 0x603F)
    ENABLE = 2        # it did not reach OPERATION ENABLED in time (b: the state it stood in)


class SpindleLoop:
    """The spindle drive's commands and supervision inside the cycle. ``live``: the shared
    block's live record (``spindle_*`` fields)."""

    def __init__(self, spec: SpindleDriveSpec | None, ts_s: float, enable_timeout_s: float,
                 live: LiveFields) -> None:
        self.spec = spec
        self.ts = ts_s
        self.live = live
        self.k = 1.0 / spec.velocity_per_rpm if spec else 1.0     # rpm per velocity unit
        self.per_rpm = spec.velocity_per_rpm if spec else 1.0
        self.profile = spec is not None and spec.mode == 3
        self.state = SpindleState.OFF
        self.target_rpm = 0.0       # what the controller asked for (signed)
        self.ramp_rpm_s = 1.0       # how fast the command goes there (mode 9)
        self.cmd_rpm = 0.0          # what is sent now
        self.confirmed = 0
        self.cycles = 0             # in this state
        self.enable_cycles = max(1, int(enable_timeout_s / ts_s))
        self.drive_state = int(Cia402State.NOT_READY_TO_SWITCH_ON)
        self.reset_cycle = 0
        self.fault: tuple[int, int] | None = None     # (SpindleFault, b) to raise this cycle

    @property
    def present(self) -> bool:
        return self.spec is not None

    def command(self, rpm: float, ramp_rpm_s: float) -> bool:
        """Turn at ``rpm`` (signed: negative counter-clockwise; 0 stop), the command ramped at
        ``ramp_rpm_s``. False while the spindle is quick-stopping or faulted."""
        if self.spec is None or self.state in (SpindleState.STOPPING, SpindleState.FAULT) \
                or not ramp_rpm_s > 0.0 or rpm != rpm:
            return False
        self.target_rpm, self.ramp_rpm_s = rpm, ramp_rpm_s
        if rpm != 0.0 and self.state is SpindleState.OFF:
            self._set(SpindleState.ENABLING)
        return True

    def quick_stop(self) -> None:
        """The machine stopped: the spindle quick-stops (its drive's 0x6085), then is off."""
        self.target_rpm = 0.0
        if self.state in (SpindleState.ENABLING, SpindleState.RUNNING):
            self._set(SpindleState.STOPPING)

    def fault_reset(self) -> None:
        if self.state is SpindleState.FAULT:
            self._set(SpindleState.OFF)
            self.reset_cycle = 1

    def _set(self, st: SpindleState) -> None:
        self.state = st
        self.cycles = 0
        self.confirmed = 0
        self.live.spindle_state[...] = int(st)

    def outputs(self, bus: Bus) -> None:
        """This cycle's controlword and target velocity."""
        st = self.state
        ds = self.drive_state
        self.cycles += 1
        if st is SpindleState.RUNNING:
            target = self.target_rpm
            if self.profile:
                self.cmd_rpm = target
            else:
                step = self.ramp_rpm_s * self.ts
                d = target - self.cmd_rpm
                self.cmd_rpm = target if abs(d) <= step else self.cmd_rpm + (step if d > 0 else -step)
            bus.spindle_controlword[0] = cia402.CW_ENABLE_OPERATION
            if self.cmd_rpm == 0.0 and target == 0.0:
                self._set(SpindleState.OFF)              # at 0: let go (disabled next cycle)
        elif st is SpindleState.ENABLING:
            self.cmd_rpm = 0.0
            bus.spindle_controlword[0] = cia402.ENABLE_LUT[ds]
        elif st is SpindleState.STOPPING:
            self.cmd_rpm = 0.0
            bus.spindle_controlword[0] = cia402.QUICK_STOP_LUT[ds]
        elif self.reset_cycle:
            bus.spindle_controlword[0] = cia402.fault_reset_controlword(self.reset_cycle)
            self.reset_cycle = self.reset_cycle + 1 if self.reset_cycle < 4 else 0
        else:                                            # OFF, FAULT
            self.cmd_rpm = 0.0
            bus.spindle_controlword[0] = cia402.DISABLE_LUT[ds]
        bus.spindle_target_velocity[0] = int(round(self.cmd_rpm * self.per_rpm))
        self.live.spindle_cmd[...] = self.cmd_rpm

    def inputs(self, bus: Bus) -> None:
        """The drive's state and speed; a fault or a failed enable set ``fault``."""
        ds = int(cia402.STATE_LUT[int(bus.spindle_statusword[0]) & 0x7F])
        self.drive_state = ds
        live = self.live
        live.spindle_drive[...] = ds
        live.spindle_rpm[...] = float(bus.spindle_velocity_actual[0]) * self.k
        live.spindle_error[...] = int(bus.spindle_error_code[0])
        st = self.state
        if ds in _FAULTS and st is not SpindleState.FAULT and not self.reset_cycle:
            self.fault = (int(SpindleFault.DRIVE), int(bus.spindle_error_code[0]))
            self.target_rpm = self.cmd_rpm = 0.0
            self._set(SpindleState.FAULT)
        elif st is SpindleState.ENABLING:
            self.confirmed = self.confirmed + 1 if ds == _OE else 0
            if self.confirmed >= CONFIRM_CYCLES:
                self._set(SpindleState.RUNNING)
            elif self.cycles > self.enable_cycles:
                self.fault = (int(SpindleFault.ENABLE), ds)
                self.target_rpm = 0.0
                self._set(SpindleState.OFF)
        elif st is SpindleState.RUNNING and ds != _OE:
            self.fault = (int(SpindleFault.DRIVE), int(bus.spindle_error_code[0]))   # left on its own
            self.target_rpm = self.cmd_rpm = 0.0
            self._set(SpindleState.OFF)
        elif st is SpindleState.STOPPING and ds != int(Cia402State.QUICK_STOP_ACTIVE) and \
                abs(float(bus.spindle_velocity_actual[0])) * self.k < 1.0:
            self._set(SpindleState.OFF)
