"""Process data of a CiA 402 drive in cyclic synchronous position mode: which objects are
mapped (``PdoMapping``, CiA 301 mapping rules), the mapping used unless a drive has its own,
and the packing of one drive's outputs and inputs into its slice of the frame."""

from __future__ import annotations

import struct
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from .bus import Bus
from .errors import ConfigurationError
from .object_dictionary import KNOWN_OBJECTS

__all__ = ["CSP_MAPPING", "DRIVE_MAPPINGS", "MANDATORY_RX", "MANDATORY_TX", "OPTIONAL_OBJECTS",
           "VELOCITY_MAPPING", "DriveIo", "PdoEntry", "PdoMapping", "is_velocity", "parse_entry"]

_TYPES = {8: "b", 16: "h", 32: "i", 64: "q"}

#: objects a CSP drive must have in its process data; everything else is optional and is
#: obtained another way when the drive does not have it (see `OPTIONAL_OBJECTS`)
MANDATORY_RX = frozenset({0x6040, 0x607A})
MANDATORY_TX = frozenset({0x6041, 0x6064})
#: ... and what a drive turning the spindle in a velocity mode must have
VELOCITY_RX = frozenset({0x6040, 0x60FF})
VELOCITY_TX = frozenset({0x6041, 0x606C})
#: what the master does without each optional object in the process data
OPTIONAL_OBJECTS = {
    0x6060: "modes of operation written once by SDO before OP",
    0x60FE: "no digital outputs (spindle enable/direction) through this drive",
    0x60F4: "following error computed by the master (set-point minus position actual)",
    0x603F: "error code read by SDO when the drive reports a fault",
    0x6061: "mode display read by SDO at start-up",
    0x60FD: "no limit, home or probe inputs through this drive",
    0x60B8: "no homing to the encoder's index (touch probe function)",
    0x60B9: "no homing to the encoder's index (touch probe status)",
    0x60BA: "no homing to the encoder's index (touch probe position)",
}


@dataclass(frozen=True, slots=True)
class PdoEntry:
    """One mapped object: index, subindex, bit length (8, 16, 32 or 64), signed. Index 0 is
    padding (gap of `bits` bits, whole bytes)."""

    index: int
    subindex: int
    bits: int
    signed: bool = False

    @property
    def value(self) -> int:
        """Mapping entry as written to 0x16xx/0x1Axx: index << 16 | subindex << 8 | bits."""
        return (self.index << 16) | (self.subindex << 8) | self.bits

    @property
    def is_padding(self) -> bool:
        return self.index == 0

    @property
    def code(self) -> str:
        if self.is_padding:
            return f"{self.bits // 8}x"
        c = _TYPES[self.bits]
        return c if self.signed else c.upper()

    @classmethod
    def from_value(cls, value: int) -> PdoEntry:
        """The entry of a raw mapping value, typed from the objects this package knows
        (an unknown object is read as unsigned)."""
        index, sub, bits = value >> 16, (value >> 8) & 0xFF, value & 0xFF
        known = KNOWN_OBJECTS.get((index, sub))
        return cls(index, sub, bits, bool(known is not None and known.signed))

    def text(self) -> str:
        if self.is_padding:
            return f"padding {self.bits} bit"
        known = KNOWN_OBJECTS.get((self.index, self.subindex))
        name = f" {known.name}" if known is not None else ""
        return f"0x{self.index:04X}:{self.subindex:02X} {self.bits} bit{name}"


def is_velocity(rx: tuple[PdoEntry, ...] | list[PdoEntry]) -> bool:
    """Whether an RxPDO's entries are a velocity-mode drive's (target velocity 0x60FF and no
    target position 0x607A): a spindle's drive, configured by its ``[[bus.drives]]`` table."""
    objects = {e.index for e in rx}
    return 0x60FF in objects and 0x607A not in objects


def parse_entry(text: str) -> PdoEntry:
    """``"0x6040:0:16"`` (index:subindex:bits, numbers in any base) as a `PdoEntry`, for the
    machine configuration's mapping lists; an ``s`` after the bits marks a signed value of an
    object this package does not know (``"0x2010:1:32s"``)."""
    parts = text.strip().split(":")
    signed_mark = parts[-1].lower().endswith("s") if parts else False
    if signed_mark:
        parts[-1] = parts[-1][:-1]
    try:
        index, sub, bits = (int(x, 0) for x in parts)
    except ValueError:
        raise ConfigurationError(f"PDO entry {text!r}: write index:subindex:bits, "
                                 "e.g. '0x6040:0:16'") from None
    if not 0 <= index <= 0xFFFF or not 0 <= sub <= 0xFF or not 0 < bits <= 64:
        raise ConfigurationError(f"PDO entry {text!r}: index 0..0xFFFF, subindex 0..255, bits 1..64")
    known = KNOWN_OBJECTS.get((index, sub))
    if known is not None and index and known.bit_length != bits:
        raise ConfigurationError(f"PDO entry {text!r}: 0x{index:04X}:{sub} ({known.name}) has "
                                 f"{known.bit_length} bits, not {bits}")
    return PdoEntry(index, sub, bits, signed_mark or bool(known is not None and known.signed))


@dataclass(frozen=True, slots=True)
class PdoMapping:
    """Process data layout of one drive, written by SDO in PRE-OP or found on the drive.

    rx: RxPDO entries (master -> drive) in `rx_pdo`, assigned to SM2 via 0x1C12;
    tx: TxPDO entries (drive -> master) in `tx_pdo`, assigned to SM3 via 0x1C13.
    complete_access: write each object in one SDO (CoE complete access) instead of
    entry by entry. dc_sync_mode: also write 0x1C32:1 = 2 (DC SYNC0), which some drives
    need for CSP with distributed clocks.
    """

    rx: tuple[PdoEntry, ...]
    tx: tuple[PdoEntry, ...]
    rx_pdo: int = 0x1600
    tx_pdo: int = 0x1A00
    complete_access: bool = False
    dc_sync_mode: bool = False
    velocity: bool = False      # a spindle's drive in a velocity mode (not an axis in CSP)

    @property
    def mandatory(self) -> frozenset[int]:
        """The objects this kind of drive cannot run without."""
        return VELOCITY_RX | VELOCITY_TX if self.velocity else MANDATORY_RX | MANDATORY_TX

    def __post_init__(self) -> None:
        rx_objects = {e.index for e in self.rx}
        tx_objects = {e.index for e in self.tx}
        if self.velocity:
            if not (VELOCITY_RX <= rx_objects and VELOCITY_TX <= tx_objects):
                raise ConfigurationError("a spindle drive's PDO mapping must contain controlword 0x6040 "
                                         "and target velocity 0x60FF, statusword 0x6041 and velocity "
                                         "actual 0x606C")
        elif not MANDATORY_RX <= rx_objects:
            raise ConfigurationError("RxPDO mapping must contain controlword 0x6040 and target "
                                     "position 0x607A")
        elif not MANDATORY_TX <= tx_objects:
            raise ConfigurationError("TxPDO mapping must contain statusword 0x6041 and position "
                                     "actual 0x6064")
        for e in self.rx + self.tx:
            if e.is_padding:
                if e.bits % 8 or not e.bits:
                    raise ConfigurationError(f"PDO padding of {e.bits} bits: only whole bytes are supported")
            elif e.bits not in _TYPES:
                raise ConfigurationError(f"PDO entry 0x{e.index:04X}:{e.subindex}: {e.bits} bits unsupported "
                                         "(8, 16, 32 or 64)")

    @classmethod
    def from_values(cls, rx: list[int] | tuple[int, ...], tx: list[int] | tuple[int, ...],
                    rx_pdo: int = 0x1600, tx_pdo: int = 0x1A00, velocity: bool = False) -> PdoMapping:
        """A mapping from raw entry values as read from a drive (0x16xx/0x1Axx sub-indices)."""
        return cls(tuple(PdoEntry.from_value(v) for v in rx), tuple(PdoEntry.from_value(v) for v in tx),
                   rx_pdo, tx_pdo, velocity=velocity)

    @property
    def objects(self) -> frozenset[int]:
        """Indices of every mapped object (both directions)."""
        return frozenset(e.index for e in self.rx + self.tx if not e.is_padding)

    def without(self, indices: frozenset[int] | set[int]) -> PdoMapping:
        """This mapping without the entries of `indices` (optional objects a drive lacks)."""
        return replace(self, rx=tuple(e for e in self.rx if e.index not in indices),
                       tx=tuple(e for e in self.tx if e.index not in indices))

    def same_entries(self, other: PdoMapping) -> bool:
        return ([e.value for e in self.rx] == [e.value for e in other.rx]
                and [e.value for e in self.tx] == [e.value for e in other.tx])

    @property
    def rx_struct(self) -> struct.Struct:
        return struct.Struct("<" + "".join(e.code for e in self.rx))

    @property
    def tx_struct(self) -> struct.Struct:
        return struct.Struct("<" + "".join(e.code for e in self.tx))


#: CSP mapping used unless a drive model has its own: controlword, target position, mode and
#: digital outputs (spindle enable/direction); statusword, position actual, following error,
#: error code, mode display and digital inputs (switches, probe); touch probe 1 (function,
#: status, position: the encoder's index for homing). The digital I/O travels in the process
#: data so that nothing in the cycle needs an SDO.
CSP_MAPPING = PdoMapping(
    rx=(PdoEntry(0x6040, 0, 16), PdoEntry(0x607A, 0, 32, True), PdoEntry(0x6060, 0, 8, True),
        PdoEntry(0x60FE, 1, 32), PdoEntry(0x60B8, 0, 16)),
    tx=(PdoEntry(0x6041, 0, 16), PdoEntry(0x6064, 0, 32, True), PdoEntry(0x60F4, 0, 32, True),
        PdoEntry(0x603F, 0, 16), PdoEntry(0x6061, 0, 8, True), PdoEntry(0x60FD, 0, 32),
        PdoEntry(0x60B9, 0, 16), PdoEntry(0x60BA, 0, 32, True)),
)

#: a spindle's drive in cyclic synchronous or profile velocity: controlword, target velocity,
#: mode; statusword, velocity actual, error code, mode display
VELOCITY_MAPPING = PdoMapping(
    rx=(PdoEntry(0x6040, 0, 16), PdoEntry(0x60FF, 0, 32, True), PdoEntry(0x6060, 0, 8, True)),
    tx=(PdoEntry(0x6041, 0, 16), PdoEntry(0x606C, 0, 32, True), PdoEntry(0x603F, 0, 16),
        PdoEntry(0x6061, 0, 8, True)),
    velocity=True,
)

#: drive model (vendor id, product code) -> mapping; extend for real drives. The
#: emulator's drive (ethercat.drive_model.DriveParams defaults) uses complete access.
DRIVE_MAPPINGS: dict[tuple[int, int], PdoMapping] = {
    (0x0000_0A5E, 0x0402_0001): PdoMapping(CSP_MAPPING.rx, CSP_MAPPING.tx, complete_access=True,
                                           dc_sync_mode=True),
}

# bus array attribute per object (outputs / inputs)
_RX_ARRAYS = {0x6040: "controlword", 0x607A: "target_position", 0x6060: "modes_of_operation",
              0x60FE: "digital_outputs", 0x60B8: "touch_probe_function"}
_TX_ARRAYS = {0x6041: "statusword", 0x6064: "position_actual", 0x60F4: "following_error",
              0x603F: "error_code", 0x6061: "modes_display", 0x60FD: "digital_inputs",
              0x60B9: "touch_probe_status", 0x60BA: "touch_probe_value"}
# ... and a spindle drive's (its index in the bus's ``spindles``)
_SPINDLE_RX = {0x6040: "spindle_controlword", 0x60FF: "spindle_target_velocity", 0x6060: "spindle_modes"}
_SPINDLE_TX = {0x6041: "spindle_statusword", 0x606C: "spindle_velocity_actual", 0x603F: "spindle_error_code",
               0x6061: "spindle_modes_display"}


@dataclass(slots=True)
class DriveIo:
    """Packs one drive's outputs and unpacks its inputs (mapping order, little endian)."""

    bus: Bus
    i: int
    slave: Any
    mapping: PdoMapping
    rx: struct.Struct = field(init=False)
    tx: struct.Struct = field(init=False)
    out_arrays: tuple[np.ndarray | None, ...] = field(init=False)
    in_arrays: tuple[np.ndarray | None, ...] = field(init=False)

    def __post_init__(self) -> None:
        self.rx = self.mapping.rx_struct
        self.tx = self.mapping.tx_struct
        # padding takes no value; objects the bus has no array for are written as 0 and not read
        velocity = self.mapping.velocity
        rx_arrays, tx_arrays = (_SPINDLE_RX, _SPINDLE_TX) if velocity else (_RX_ARRAYS, _TX_ARRAYS)
        self.out_arrays = tuple(getattr(self.bus, rx_arrays[e.index]) if e.index in rx_arrays else None
                                for e in self.mapping.rx if not e.is_padding)
        self.in_arrays = tuple(getattr(self.bus, tx_arrays[e.index]) if e.index in tx_arrays else None
                               for e in self.mapping.tx if not e.is_padding)

    def write(self) -> None:
        i = self.i
        self.slave.output = self.rx.pack(*[0 if a is None else int(a[i]) for a in self.out_arrays])

    def read(self) -> None:
        i = self.i
        for a, v in zip(self.in_arrays, self.tx.unpack(self.slave.input)):
            if a is not None:
                a[i] = v
