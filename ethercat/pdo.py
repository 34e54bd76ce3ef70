"""Process data of a CiA 402 drive in cyclic synchronous position mode: which objects are
mapped (``PdoMapping``, CiA 301 mapping rules), the mapping used unless a drive has its own,
and the packing of one drive's outputs and inputs into its slice of the frame."""

from __future__ import annotations

import struct
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .bus import Bus
from .errors import ConfigurationError

__all__ = ["CSP_MAPPING", "DRIVE_MAPPINGS", "DriveIo", "PdoEntry", "PdoMapping"]

_TYPES = {8: "b", 16: "h", 32: "i"}


@dataclass(frozen=True, slots=True)
class PdoEntry:
    """One mapped object: index, subindex, bit length (8, 16 or 32), signed."""

    index: int
    subindex: int
    bits: int
    signed: bool = False

    @property
    def value(self) -> int:
        """Mapping entry as written to 0x16xx/0x1Axx: index << 16 | subindex << 8 | bits."""
        return (self.index << 16) | (self.subindex << 8) | self.bits

    @property
    def code(self) -> str:
        c = _TYPES[self.bits]
        return c if self.signed else c.upper()


@dataclass(frozen=True, slots=True)
class PdoMapping:
    """Process data layout of one drive model, written by SDO in PRE-OP.

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

    def __post_init__(self) -> None:
        rx_objects = {e.index for e in self.rx}
        tx_objects = {e.index for e in self.tx}
        if not {0x6040, 0x607A} <= rx_objects:
            raise ConfigurationError("RxPDO mapping must contain controlword 0x6040 and target "
                                     "position 0x607A")
        if not {0x6041, 0x6064} <= tx_objects:
            raise ConfigurationError("TxPDO mapping must contain statusword 0x6041 and position "
                                     "actual 0x6064")
        for e in self.rx + self.tx:
            if e.bits not in _TYPES:
                raise ConfigurationError(f"PDO entry 0x{e.index:04X}:{e.subindex}: {e.bits} bits unsupported")

    @property
    def rx_struct(self) -> struct.Struct:
        return struct.Struct("<" + "".join(e.code for e in self.rx))

    @property
    def tx_struct(self) -> struct.Struct:
        return struct.Struct("<" + "".join(e.code for e in self.tx))


#: CSP mapping used unless a drive model has its own: controlword, target position, mode and
#: digital outputs (spindle enable/direction); statusword, position actual, following error,
#: error code, mode display and digital inputs (switches, probe). The digital I/O travels in
#: the process data so that nothing in the cycle needs an SDO.
CSP_MAPPING = PdoMapping(
    rx=(PdoEntry(0x6040, 0, 16), PdoEntry(0x607A, 0, 32, True), PdoEntry(0x6060, 0, 8, True),
        PdoEntry(0x60FE, 1, 32)),
    tx=(PdoEntry(0x6041, 0, 16), PdoEntry(0x6064, 0, 32, True), PdoEntry(0x60F4, 0, 32, True),
        PdoEntry(0x603F, 0, 16), PdoEntry(0x6061, 0, 8, True), PdoEntry(0x60FD, 0, 32)),
)

#: drive model (vendor id, product code) -> mapping; extend for real drives. The
#: emulator's drive (ethercat.drive_model.DriveParams defaults) uses complete access.
DRIVE_MAPPINGS: dict[tuple[int, int], PdoMapping] = {
    (0x0000_0A5E, 0x0402_0001): PdoMapping(CSP_MAPPING.rx, CSP_MAPPING.tx, complete_access=True,
                                           dc_sync_mode=True),
}

# bus array attribute per object (outputs / inputs)
_RX_ARRAYS = {0x6040: "controlword", 0x607A: "target_position", 0x6060: "modes_of_operation",
              0x60FE: "digital_outputs"}
_TX_ARRAYS = {0x6041: "statusword", 0x6064: "position_actual", 0x60F4: "following_error",
              0x603F: "error_code", 0x6061: "modes_display", 0x60FD: "digital_inputs"}


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
        self.out_arrays = tuple(getattr(self.bus, _RX_ARRAYS[e.index]) if e.index in _RX_ARRAYS else None
                                for e in self.mapping.rx)
        self.in_arrays = tuple(getattr(self.bus, _TX_ARRAYS[e.index]) if e.index in _TX_ARRAYS else None
                               for e in self.mapping.tx)

    def write(self) -> None:
        i = self.i
        self.slave.output = self.rx.pack(*[0 if a is None else int(a[i]) for a in self.out_arrays])

    def read(self) -> None:
        i = self.i
        for a, v in zip(self.in_arrays, self.tx.unpack(self.slave.input)):
            if a is not None:
                a[i] = v
