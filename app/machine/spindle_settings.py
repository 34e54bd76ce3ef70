"""``[spindle]``: a spindle on its own CiA 402 drive in a velocity mode (left out, the spindle
is the pair of output bits of ``[controller] spindle_drive``), or a VFD whose speed is set by an
analog output (``analog_out``) beside those bits.

    [spindle]
    drive = 4                  # its slave position on the bus
    mode = 9                   # 9 cyclic synchronous velocity (the control ramps), 3 profile velocity
    velocity_per_rpm = 166.667 # the drive's velocity units (0x60FF, 0x606C) per rpm
    accel_rpm_s = 2000         # the ramp of the speed (mode 9), rpm/s
    at_speed_pct = 5           # at speed: the speed read within this share of the speed commanded
    speed_loss_s = 0.5         # below that band this long while turning at speed: the program holds

    [spindle]                  # or: a VFD run by the output bits, its speed from 0-10 V
    analog_out = "9:0"         # an EL4xxx's slave position and channel
    analog_rpm_at_10v = 24000  # the speed at 10 V (left out: [controller] spindle_max_rpm)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ethercat.bus import SpindleDriveSpec

__all__ = ["SpindleDriveSettings", "spindle_lines"]


@dataclass(frozen=True, slots=True)
class SpindleDriveSettings:
    drive: int | None = None
    mode: int = 9
    velocity_per_rpm: float = 10_000.0 / 60.0
    accel_rpm_s: float = 2000.0
    at_speed_pct: float = 5.0
    speed_loss_s: float = 0.5
    vendor_id: int = 0
    product_code: int = 0
    analog_out: str = ""
    analog_rpm_at_10v: float | None = None

    @classmethod
    def from_valid(cls, s: dict[str, Any]) -> SpindleDriveSettings:
        return cls(**{k: s[k] for k in cls.__dataclass_fields__})

    @property
    def spec(self) -> SpindleDriveSpec | None:
        """What the 1 ms loop drives (None: no spindle drive)."""
        if self.drive is None:
            return None
        return SpindleDriveSpec(self.drive, self.velocity_per_rpm, self.mode, self.vendor_id,
                                self.product_code)

    def at_speed(self, commanded_rpm: float, actual_rpm: float) -> bool:
        """Whether the speed read is within the band of the one commanded (signed: the right way)."""
        return abs(actual_rpm - commanded_rpm) <= self.at_speed_pct / 100.0 * abs(commanded_rpm)

    def analog_share(self, commanded_rpm: float, on: bool, max_rpm: float) -> float:
        """A VFD's analog output as a share of 10 V: S x override (``commanded_rpm``) over the
        speed at 10 V (``analog_rpm_at_10v``, else the spindle's maximum ``max_rpm``), 0 while
        it stands; never beyond 10 V."""
        top = self.analog_rpm_at_10v or max_rpm
        return min(1.0, abs(commanded_rpm) / top) if on and top > 0 else 0.0

    def spin_up_s(self, from_rpm: float, to_rpm: float) -> float:
        """How long the ramp from one speed to the other takes (its least wait)."""
        return abs(to_rpm - from_rpm) / self.accel_rpm_s


def spindle_lines(s: SpindleDriveSettings) -> list[str]:
    if s.analog_out:
        out = ["[spindle]", f'analog_out = "{s.analog_out}"']
        if s.analog_rpm_at_10v is not None:
            out.append(f"analog_rpm_at_10v = {s.analog_rpm_at_10v!r}")
        return out + [""]
    if s.drive is None:
        return []
    out = ["[spindle]", f"drive = {s.drive}", f"mode = {s.mode}",
           f"velocity_per_rpm = {s.velocity_per_rpm!r}",
           f"accel_rpm_s = {s.accel_rpm_s!r}", f"at_speed_pct = {s.at_speed_pct!r}",
           f"speed_loss_s = {s.speed_loss_s!r}"]
    if s.vendor_id or s.product_code:
        out += [f"vendor_id = 0x{s.vendor_id:08X}", f"product_code = 0x{s.product_code:08X}"]
    return out + [""]
