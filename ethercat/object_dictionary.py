"""The object dictionary of the project's CiA 402 drive model: every object's index, subindex,
name, type, access and whether it can be mapped to process data, with the value coding of
SDO transfers. Used by the model (``drive_model``) and the software slave (``emulator``)."""

from __future__ import annotations

import struct
from dataclasses import dataclass

from .errors import SdoAbortError

# CiA 402 / CiA 301 error codes (0x603F) produced by the model.
ERROR_FOLLOWING = 0x8611       # following error
ERROR_OVERCURRENT = 0x2310     # continuous over-current (default injected fault)
ERROR_SYNC = 0x8700            # process data / sync lost (watchdog)


@dataclass(frozen=True, slots=True)
class ObjectEntry:
    """One object dictionary entry: type as in CiA 301 (INTEGER8..UNSIGNED32)."""

    index: int
    subindex: int
    name: str
    data_type: str        # "i8", "u8", "i16", "u16", "i32", "u32"
    access: str           # "ro" or "rw"
    pdo_mappable: bool = False

    @property
    def size_bytes(self) -> int:
        return int(self.data_type[1:]) // 8

    @property
    def bit_length(self) -> int:
        return int(self.data_type[1:])

    @property
    def signed(self) -> bool:
        return self.data_type[0] == "i"

    @property
    def struct_format(self) -> str:
        return {"i8": "<b", "u8": "<B", "i16": "<h", "u16": "<H", "i32": "<i", "u32": "<I"}[self.data_type]

    def check_range(self, value: int) -> bool:
        bits = self.bit_length
        if self.signed:
            return -(1 << (bits - 1)) <= value < (1 << (bits - 1))
        return 0 <= value < (1 << bits)


def _entries(*rows: tuple[int, int, str, str, str, bool]) -> dict[tuple[int, int], ObjectEntry]:
    return {(r[0], r[1]): ObjectEntry(*r) for r in rows}


#: Object dictionary of the model (PDO mapping objects 0x16xx/0x1Axx/0x1C1x belong to the
#: emulator's ESC model, not to the drive).
OBJECTS: dict[tuple[int, int], ObjectEntry] = _entries(
    (0x1000, 0, "device type", "u32", "ro", False),
    (0x1018, 0, "identity: number of entries", "u8", "ro", False),
    (0x1018, 1, "vendor id", "u32", "ro", False),
    (0x1018, 2, "product code", "u32", "ro", False),
    (0x1018, 3, "revision number", "u32", "ro", False),
    (0x1018, 4, "serial number", "u32", "ro", False),
    (0x603F, 0, "error code", "u16", "ro", True),
    (0x6040, 0, "controlword", "u16", "rw", True),
    (0x6041, 0, "statusword", "u16", "ro", True),
    (0x605A, 0, "quick stop option code", "i16", "rw", False),
    (0x6060, 0, "modes of operation", "i8", "rw", True),
    (0x6061, 0, "modes of operation display", "i8", "ro", True),
    (0x6062, 0, "position demand value", "i32", "ro", True),
    (0x6064, 0, "position actual value", "i32", "ro", True),
    (0x6065, 0, "following error window", "u32", "rw", False),
    (0x6066, 0, "following error time out", "u16", "rw", False),
    (0x606C, 0, "velocity actual value", "i32", "ro", True),
    (0x606D, 0, "velocity window", "u16", "rw", False),
    (0x607A, 0, "target position", "i32", "rw", True),
    (0x607C, 0, "home offset", "i32", "rw", False),
    (0x6083, 0, "profile acceleration", "u32", "rw", False),
    (0x6084, 0, "profile deceleration", "u32", "rw", False),
    (0x6085, 0, "quick stop deceleration", "u32", "rw", False),
    (0x6098, 0, "homing method", "i8", "rw", False),
    (0x6099, 0, "homing speeds: number of entries", "u8", "ro", False),
    (0x6099, 1, "speed during search for switch", "u32", "rw", False),
    (0x6099, 2, "speed during search for zero", "u32", "rw", False),
    (0x609A, 0, "homing acceleration", "u32", "rw", False),
    (0x60B8, 0, "touch probe function", "u16", "rw", True),
    (0x60B9, 0, "touch probe status", "u16", "ro", True),
    (0x60BA, 0, "touch probe position 1 positive value", "i32", "ro", True),
    (0x60F4, 0, "following error actual value", "i32", "ro", True),
    (0x60FD, 0, "digital inputs", "u32", "ro", True),
    (0x60FE, 0, "digital outputs: number of entries", "u8", "ro", False),
    (0x60FE, 1, "digital outputs: physical outputs", "u32", "rw", True),
    (0x60FF, 0, "target velocity", "i32", "rw", True),
)

OBJECT_INDICES = frozenset(i for i, _ in OBJECTS)

#: Further CiA 402 objects a third-party drive may map or need at start-up, for naming and
#: typing what is found on a drive; the project's drive model does not have them.
CIA402_EXTRA: dict[tuple[int, int], ObjectEntry] = _entries(
    (0x6063, 0, "position actual internal value", "i32", "ro", True),
    (0x606B, 0, "velocity demand value", "i32", "ro", True),
    (0x6071, 0, "target torque", "i16", "rw", True),
    (0x6072, 0, "max torque", "u16", "rw", True),
    (0x6077, 0, "torque actual value", "i16", "ro", True),
    (0x6078, 0, "current actual value", "i16", "ro", True),
    (0x60B0, 0, "position offset", "i32", "rw", True),
    (0x60B1, 0, "velocity offset", "i32", "rw", True),
    (0x60B2, 0, "torque offset", "i16", "rw", True),
    (0x6502, 0, "supported drive modes", "u32", "ro", False),
)

#: every object this package can name: the model's and the further CiA 402 ones
KNOWN_OBJECTS: dict[tuple[int, int], ObjectEntry] = {**CIA402_EXTRA, **OBJECTS}


def encode_object(entry: ObjectEntry, value: int) -> bytes:
    """Little-endian bytes of `value` in the object's type."""
    return struct.pack(entry.struct_format, value)


def decode_object(entry: ObjectEntry, data: bytes) -> int:
    """Value of the object's type from little-endian bytes (length must match)."""
    if len(data) != entry.size_bytes:
        raise SdoAbortError(-1, entry.index, entry.subindex, SdoAbortError.LENGTH_MISMATCH,
                            f"{len(data)} bytes for {entry.data_type}")
    return int(struct.unpack(entry.struct_format, data)[0])


def wrap(value: int, entry: ObjectEntry) -> int:
    """Wrap an int into the object's type range (int32 positions wrap like real drives)."""
    bits = entry.bit_length
    value &= (1 << bits) - 1
    if entry.signed and value >= 1 << (bits - 1):
        value -= 1 << bits
    return value
