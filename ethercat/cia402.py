"""CiA 402 (IEC 61800-7-201) drive logic, written once and used on every bus.

Master side: statusword decoding, the controlword that walks a drive to OPERATION
ENABLED and back, fault reset (rising edge of controlword bit 7), quick stop, modes of
operation (CSP = 8, homing = 6), and counts <-> axis units (mm or degrees) by scale and
direction. The drive model (`drive_model.py`) uses the same constants from the drive side.

Per-cycle functions work on preallocated NumPy arrays with `out=` and a lookup table, so
the 1 ms loop allocates nothing (`decode_states`, `controlwords`, `units_to_counts`,
`counts_to_units`).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np

from .errors import ConfigurationError


class Cia402State(enum.IntEnum):
    """Drive states of the CiA 402 power state machine (values index the lookup tables)."""

    NOT_READY_TO_SWITCH_ON = 0
    SWITCH_ON_DISABLED = 1
    READY_TO_SWITCH_ON = 2
    SWITCHED_ON = 3
    OPERATION_ENABLED = 4
    QUICK_STOP_ACTIVE = 5
    FAULT_REACTION_ACTIVE = 6
    FAULT = 7
    UNKNOWN = 8


class ModeOfOperation(enum.IntEnum):
    """Object 0x6060 values used here."""

    NONE = 0
    PROFILE_POSITION = 1
    PROFILE_VELOCITY = 3
    HOMING = 6
    CYCLIC_SYNC_POSITION = 8
    CYCLIC_SYNC_VELOCITY = 9


CSP = ModeOfOperation.CYCLIC_SYNC_POSITION
CSV = ModeOfOperation.CYCLIC_SYNC_VELOCITY
PV = ModeOfOperation.PROFILE_VELOCITY
HOMING = ModeOfOperation.HOMING

# Controlword commands (CiA 402 table "device control commands"; bits 0-3 and 7).
CW_DISABLE_VOLTAGE = 0x0000
CW_QUICK_STOP = 0x0002
CW_SHUTDOWN = 0x0006
CW_SWITCH_ON = 0x0007
CW_DISABLE_OPERATION = 0x0007
CW_ENABLE_OPERATION = 0x000F
CW_FAULT_RESET = 0x0080
CW_HOMING_START = 0x0010  # bit 4 "operation mode specific": homing start in mode 6
CW_HALT = 0x0100

# Statusword bits.
SW_READY_TO_SWITCH_ON = 1 << 0
SW_SWITCHED_ON = 1 << 1
SW_OPERATION_ENABLED = 1 << 2
SW_FAULT = 1 << 3
SW_VOLTAGE_ENABLED = 1 << 4
SW_QUICK_STOP = 1 << 5  # active low: 1 = no quick stop
SW_SWITCH_ON_DISABLED = 1 << 6
SW_WARNING = 1 << 7
SW_REMOTE = 1 << 9
SW_TARGET_REACHED = 1 << 10
SW_INTERNAL_LIMIT = 1 << 11
SW_OP_SPECIFIC_12 = 1 << 12  # CSP: drive follows the target; homing: homing attained
SW_OP_SPECIFIC_13 = 1 << 13  # CSP: following error; homing: homing error
SW_HOMING_ATTAINED = SW_OP_SPECIFIC_12
SW_HOMING_ERROR = SW_OP_SPECIFIC_13
SW_FOLLOWING_ERROR = SW_OP_SPECIFIC_13

# Touch probe 1 (0x60B8 function, 0x60B9 status), CiA 402 / IEC 61800-7-201
TP_ENABLE = 1 << 0             # function: touch probe 1 on
TP_CONTINUOUS = 1 << 1         # function: every event (0: the first only, until re-armed)
TP_SOURCE_INDEX = 1 << 2       # function bits 2-3 = 01: the encoder's zero impulse (00: probe input)
TP_POSITIVE_EDGE = 1 << 4      # function: sample at the positive edge
TP_INDEX_FIRST_POSITIVE = TP_ENABLE | TP_SOURCE_INDEX | TP_POSITIVE_EDGE   # 0x15
TP_ENABLED = 1 << 0            # status: touch probe 1 is on
TP_POSITIVE_STORED = 1 << 1    # status: a positive-edge position is in 0x60BA

# Statusword pattern of each state (bits 0-3, 5, 6), CiA 402 "state coding".
STATE_STATUSWORD: dict[Cia402State, int] = {
    Cia402State.NOT_READY_TO_SWITCH_ON: 0x00,
    Cia402State.SWITCH_ON_DISABLED: 0x40,
    Cia402State.READY_TO_SWITCH_ON: 0x21,
    Cia402State.SWITCHED_ON: 0x23,
    Cia402State.OPERATION_ENABLED: 0x27,
    Cia402State.QUICK_STOP_ACTIVE: 0x07,
    Cia402State.FAULT_REACTION_ACTIVE: 0x0F,
    Cia402State.FAULT: 0x08,
}


def decode_statusword(statusword: int) -> Cia402State:
    """The CiA 402 state coded in a statusword (masks 0x4F / 0x6F as in the standard)."""
    sw4f = statusword & 0x4F
    sw6f = statusword & 0x6F
    if sw4f == 0x00:
        return Cia402State.NOT_READY_TO_SWITCH_ON
    if sw4f == 0x40:
        return Cia402State.SWITCH_ON_DISABLED
    if sw6f == 0x21:
        return Cia402State.READY_TO_SWITCH_ON
    if sw6f == 0x23:
        return Cia402State.SWITCHED_ON
    if sw6f == 0x27:
        return Cia402State.OPERATION_ENABLED
    if sw6f == 0x07:
        return Cia402State.QUICK_STOP_ACTIVE
    if sw4f == 0x0F:
        return Cia402State.FAULT_REACTION_ACTIVE
    if sw4f == 0x08:
        return Cia402State.FAULT
    return Cia402State.UNKNOWN


# Lookup table over the 7 relevant bits (0-6) of the statusword -> state value.
STATE_LUT: np.ndarray = np.array([decode_statusword(i) for i in range(128)], dtype=np.int8)
STATE_LUT.setflags(write=False)


def decode_states(statusword: np.ndarray, out: np.ndarray, scratch: np.ndarray) -> np.ndarray:
    """Decode an array of statuswords into `out` (int8 state values), allocation free.

    `scratch` is an integer array of the same shape used for the masked bits.
    """
    np.bitwise_and(statusword, 0x7F, out=scratch, casting="unsafe")
    STATE_LUT.take(scratch, out=out)
    return out


def _lut(table: dict[Cia402State, int]) -> np.ndarray:
    lut = np.array([table[Cia402State(i)] for i in range(len(Cia402State))], dtype=np.uint16)
    lut.setflags(write=False)
    return lut


# Controlword that moves a drive one step towards OPERATION ENABLED. A drive in QUICK STOP
# ACTIVE gets "disable voltage" (transition 12, valid for every quick stop option code),
# then goes the normal way. FAULT needs an explicit fault reset (`FAULT_RESET_SEQUENCE`).
ENABLE_LUT = _lut({
    Cia402State.NOT_READY_TO_SWITCH_ON: CW_DISABLE_VOLTAGE,
    Cia402State.SWITCH_ON_DISABLED: CW_SHUTDOWN,            # transition 2
    Cia402State.READY_TO_SWITCH_ON: CW_SWITCH_ON,           # transition 3
    Cia402State.SWITCHED_ON: CW_ENABLE_OPERATION,           # transition 4
    Cia402State.OPERATION_ENABLED: CW_ENABLE_OPERATION,
    Cia402State.QUICK_STOP_ACTIVE: CW_DISABLE_VOLTAGE,      # transition 12
    Cia402State.FAULT_REACTION_ACTIVE: CW_DISABLE_VOLTAGE,
    Cia402State.FAULT: CW_DISABLE_VOLTAGE,
    Cia402State.UNKNOWN: CW_DISABLE_VOLTAGE,
})

# Controlword that moves a drive towards READY TO SWITCH ON (power stage off).
DISABLE_LUT = _lut({
    Cia402State.NOT_READY_TO_SWITCH_ON: CW_DISABLE_VOLTAGE,
    Cia402State.SWITCH_ON_DISABLED: CW_SHUTDOWN,            # transition 2
    Cia402State.READY_TO_SWITCH_ON: CW_SHUTDOWN,
    Cia402State.SWITCHED_ON: CW_SHUTDOWN,                   # transition 6
    Cia402State.OPERATION_ENABLED: CW_SHUTDOWN,             # transition 8
    Cia402State.QUICK_STOP_ACTIVE: CW_DISABLE_VOLTAGE,      # transition 12
    Cia402State.FAULT_REACTION_ACTIVE: CW_DISABLE_VOLTAGE,
    Cia402State.FAULT: CW_DISABLE_VOLTAGE,
    Cia402State.UNKNOWN: CW_DISABLE_VOLTAGE,
})

# Quick stop: transition 11 from OPERATION ENABLED; 7 and 10 from READY/SWITCHED ON.
QUICK_STOP_LUT = _lut({
    Cia402State.NOT_READY_TO_SWITCH_ON: CW_DISABLE_VOLTAGE,
    Cia402State.SWITCH_ON_DISABLED: CW_QUICK_STOP,
    Cia402State.READY_TO_SWITCH_ON: CW_QUICK_STOP,
    Cia402State.SWITCHED_ON: CW_QUICK_STOP,
    Cia402State.OPERATION_ENABLED: CW_QUICK_STOP,
    Cia402State.QUICK_STOP_ACTIVE: CW_QUICK_STOP,
    Cia402State.FAULT_REACTION_ACTIVE: CW_DISABLE_VOLTAGE,
    Cia402State.FAULT: CW_DISABLE_VOLTAGE,
    Cia402State.UNKNOWN: CW_DISABLE_VOLTAGE,
})


def enable_controlword(state: Cia402State) -> int:
    """Next controlword on the way to OPERATION ENABLED (see `ENABLE_LUT`)."""
    return int(ENABLE_LUT[state])


def disable_controlword(state: Cia402State) -> int:
    """Next controlword on the way to READY TO SWITCH ON."""
    return int(DISABLE_LUT[state])


def quick_stop_controlword(state: Cia402State) -> int:
    """Controlword requesting quick stop from `state`."""
    return int(QUICK_STOP_LUT[state])


def fault_reset_controlword(cycle: int) -> int:
    """Fault reset is the rising edge of bit 7: alternate 0x00 and 0x80 every cycle."""
    return CW_FAULT_RESET if cycle & 1 else CW_DISABLE_VOLTAGE


def is_enabled(statusword: int) -> bool:
    return decode_statusword(statusword) is Cia402State.OPERATION_ENABLED


def is_fault(statusword: int) -> bool:
    return bool(statusword & SW_FAULT)


@dataclass(frozen=True, slots=True)
class AxisScale:
    """Counts <-> axis units for one drive: counts = direction * counts_per_unit * q + offset.

    `q` is in mm (linear) or degrees (rotary); `offset_counts` is the count value at q = 0.
    """

    counts_per_unit: float
    direction: int = 1
    offset_counts: float = 0.0

    def __post_init__(self) -> None:
        if not (self.counts_per_unit > 0.0 and np.isfinite(self.counts_per_unit)):
            raise ConfigurationError(f"counts_per_unit must be > 0, got {self.counts_per_unit}")
        if self.direction not in (1, -1):
            raise ConfigurationError(f"direction must be +1 or -1, got {self.direction}")

    @property
    def gain(self) -> float:
        """Signed counts per unit."""
        return self.direction * self.counts_per_unit

    def to_counts(self, q_units: float) -> int:
        return int(round(self.gain * q_units + self.offset_counts))

    def to_units(self, counts: int | float) -> float:
        return (float(counts) - self.offset_counts) / self.gain


def scale_arrays(scales: tuple[AxisScale, ...]) -> tuple[np.ndarray, np.ndarray]:
    """(gain counts/unit with sign, offset counts) arrays for the vectorised conversions."""
    gain = np.array([s.gain for s in scales], dtype=np.float64)
    offset = np.array([s.offset_counts for s in scales], dtype=np.float64)
    return gain, offset


def units_to_counts(q_units: np.ndarray, gain: np.ndarray, offset: np.ndarray,
                    out: np.ndarray, scratch: np.ndarray) -> np.ndarray:
    """counts = round(gain * q + offset) into the int32 array `out` (scratch: float64)."""
    np.multiply(q_units, gain, out=scratch)
    np.add(scratch, offset, out=scratch)
    np.rint(scratch, out=scratch)
    np.copyto(out, scratch, casting="unsafe")
    return out


def counts_to_units(counts: np.ndarray, gain: np.ndarray, offset: np.ndarray,
                    out: np.ndarray) -> np.ndarray:
    """q = (counts - offset) / gain into the float64 array `out`."""
    np.subtract(counts, offset, out=out)
    np.divide(out, gain, out=out)
    return out
