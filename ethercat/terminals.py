"""EtherCAT terminals beside the drives: couplers, digital inputs and outputs, encoders.

A terminal is known by its identity (vendor id, product code) and has a fixed process image
(the default PDO assignment of its ESI file, which SOEM maps from the slave's SII or CoE
objects unchanged). The bus keeps one word per terminal in each direction, so the cycle
reads and writes terminals as it reads drives: by index into preallocated arrays.

    inputs   ``terminal_inputs[k]``   EL1xxx: channel c at bit c (0x6000 + 0x10 c : 1)
                                      EL5101: its status byte (0x6000:1; bit 5 the input)
             ``terminal_counts[k]``   EL5101: counter value (0x6000:2, 16 bit, unsigned)
             ``terminal_latches[k]``  EL5101: latch value (0x6000:3, 16 bit, unsigned)
    outputs  ``terminal_outputs[k]``  EL2xxx: channel c at bit c (0x7000 + 0x10 c : 1)
                                      EL5101: its control byte (0x7000:1)
                                      EL4xxx: channel c's value at bits 16 c .. 16 c + 15
                                      (0x7000 + 0x10 c : 0x11, INT16: 0x7FFF = 10 V)

Beckhoff's EL terminals have vendor id 2 and product code (type number << 16) | 0x3052;
EK couplers (type << 16) | 0x2C52 (linuxcnc-ethercat's drivers list the same codes).
"""

from __future__ import annotations

import enum
import struct
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from .errors import ConfigurationError

__all__ = ["ANALOG_FULL_SCALE", "ANALOG_FULL_SCALE_V", "BECKHOFF", "TERMINAL_TYPES", "analog_channels",
           "analog_word", "TerminalIo", "TerminalKind", "TerminalSpec", "TerminalType",
           "terminal_type", "type_of_identity"]

BECKHOFF = 0x0000_0002


class TerminalKind(enum.Enum):
    COUPLER = "coupler"            # no process data (EK1100)
    DIGITAL_IN = "digital in"      # EL1xxx
    DIGITAL_OUT = "digital out"    # EL2xxx
    ENCODER = "encoder"            # EL5101: incremental encoder with latch
    ANALOG_OUT = "analog out"      # EL4xxx: 0-10 V outputs, one INT16 a channel


@dataclass(frozen=True, slots=True)
class TerminalType:
    """One terminal type: identity, kind, channels and its process image (struct formats of
    its output and input bytes, little endian)."""

    name: str
    product_code: int
    kind: TerminalKind
    channels: int
    rx_format: str = ""            # master -> terminal
    tx_format: str = ""            # terminal -> master
    vendor_id: int = BECKHOFF
    description: str = ""

    @property
    def rx_bytes(self) -> int:
        return struct.calcsize("<" + self.rx_format) if self.rx_format else 0

    @property
    def tx_bytes(self) -> int:
        return struct.calcsize("<" + self.tx_format) if self.tx_format else 0

    @property
    def working_counter(self) -> int:
        """What this terminal adds to the working counter of one LRW (2 for outputs written,
        1 for inputs read)."""
        return (2 if self.rx_bytes else 0) + (1 if self.tx_bytes else 0)


def _bits(channels: int) -> str:
    """A digital terminal's image: one bit per channel, packed in whole bytes."""
    return {1: "B", 2: "H", 4: "I"}[(channels + 7) // 8]


def _el(number: int) -> int:
    return number << 16 | 0x3052


def _digital_in(number: int, channels: int) -> TerminalType:
    return TerminalType(f"EL{number}", _el(number), TerminalKind.DIGITAL_IN, channels, "", _bits(channels),
                        description=f"{channels} digital inputs 24 V")


def _digital_out(number: int, channels: int) -> TerminalType:
    return TerminalType(f"EL{number}", _el(number), TerminalKind.DIGITAL_OUT, channels, _bits(channels), "",
                        description=f"{channels} digital outputs 24 V 0.5 A")


def _analog_out(number: int, channels: int, bits: int) -> TerminalType:
    return TerminalType(f"EL{number}", _el(number), TerminalKind.ANALOG_OUT, channels, "h" * channels, "",
                        description=f"{channels} analog outputs 0-10 V, {bits} bit")


#: an analog output's full scale: INT16 0x7FFF is 10 V (Beckhoff's EL40xx/EL41xx)
ANALOG_FULL_SCALE = 0x7FFF
ANALOG_FULL_SCALE_V = 10.0


def analog_word(word: int, channel: int, value: int) -> int:
    """An analog terminal's output word with channel ``channel`` set to ``value`` (INT16)."""
    shift = 16 * channel
    return (word & ~(0xFFFF << shift)) | ((value & 0xFFFF) << shift)


def analog_channels(word: int, channels: int) -> tuple[int, ...]:
    """The INT16 values of an analog terminal's output word."""
    out = []
    for c in range(channels):
        v = (word >> 16 * c) & 0xFFFF
        out.append(v - 0x10000 if v & 0x8000 else v)
    return tuple(out)


#: the terminals the bus knows, by name
TERMINAL_TYPES: dict[str, TerminalType] = {t.name: t for t in (
    TerminalType("EK1100", 0x044C_2C52, TerminalKind.COUPLER, 0, description="EtherCAT coupler"),
    TerminalType("EK1101", 0x044D_2C52, TerminalKind.COUPLER, 0,
                 description="EtherCAT coupler with ID switch"),
    _digital_in(1002, 2), _digital_in(1004, 4), _digital_in(1008, 8), _digital_in(1014, 4),
    _digital_in(1018, 8), _digital_in(1809, 16),
    _digital_out(2002, 2), _digital_out(2004, 4), _digital_out(2008, 8), _digital_out(2809, 16),
    _analog_out(4001, 1, 12), _analog_out(4002, 2, 12), _analog_out(4004, 4, 12), _analog_out(4102, 2, 16),
    _analog_out(4104, 4, 16),
    # status u8, counter value u16, latch value u16 / control u8, set counter value u16
    TerminalType("EL5101", _el(5101), TerminalKind.ENCODER, 1, "BH", "BHH",
                 description="incremental encoder interface, 16 bit counter, latch"),
)}

#: EL5101 status and control bits (0x6000:1, 0x7000:1)
ENC_STATUS_LATCH_C_VALID = 1 << 0
ENC_STATUS_LATCH_EXT_VALID = 1 << 1
ENC_STATUS_SET_DONE = 1 << 2
ENC_STATUS_INPUT = 1 << 5
ENC_CTRL_ENABLE_LATCH_C = 1 << 0
ENC_CTRL_SET_COUNTER = 1 << 2


def terminal_type(name: str) -> TerminalType:
    """The type named ``name`` ("EL1008"); an unknown name is refused with the known ones."""
    try:
        return TERMINAL_TYPES[name.upper()]
    except KeyError:
        raise ConfigurationError(f"unknown terminal type {name!r}; known: {', '.join(sorted(TERMINAL_TYPES))}"
                                 ) from None


def type_of_identity(vendor_id: int, product_code: int) -> TerminalType | None:
    """The known terminal with this identity, or None (a drive, or a terminal not catalogued)."""
    for t in TERMINAL_TYPES.values():
        if t.vendor_id == vendor_id and t.product_code == product_code:
            return t
    return None


@dataclass(frozen=True, slots=True)
class TerminalSpec:
    """One terminal of the machine (``[[bus.terminals]]``): its slave position and type."""

    position: int
    type_name: str
    name: str = ""
    type: TerminalType = field(init=False)

    def __post_init__(self) -> None:
        if self.position < 0:
            raise ConfigurationError(f"terminal {self.type_name}: position must be >= 0, got {self.position}")
        object.__setattr__(self, "type", terminal_type(self.type_name))

    @property
    def kind(self) -> TerminalKind:
        return self.type.kind

    @property
    def label(self) -> str:
        return self.name or f"{self.type.name} at slave {self.position}"


def check_terminals(terminals: Sequence[TerminalSpec],
                    drive_positions: Sequence[int]) -> tuple[TerminalSpec, ...]:
    """Distinct positions, none a drive's."""
    terminals = tuple(terminals)
    seen: dict[int, str] = {p: "a drive" for p in drive_positions}
    for t in terminals:
        if t.position in seen:
            raise ConfigurationError(f"terminal {t.type.name} at slave position {t.position}: that position "
                                     f"is already {seen[t.position]}")
        seen[t.position] = f"a {t.type.name}"
    return terminals


@dataclass(slots=True)
class TerminalIo:
    """Packs one terminal's outputs and unpacks its inputs on a real bus (SOEM's slave object
    with ``input`` bytes and an ``output`` property), by index into the bus's arrays."""

    bus: Any
    k: int
    slave: Any
    type: TerminalType
    rx: struct.Struct | None = field(init=False)
    tx: struct.Struct | None = field(init=False)

    def __post_init__(self) -> None:
        self.rx = struct.Struct("<" + self.type.rx_format) if self.type.rx_format else None
        self.tx = struct.Struct("<" + self.type.tx_format) if self.type.tx_format else None

    def write(self) -> None:
        rx, k = self.rx, self.k
        if rx is None:
            return
        if self.type.kind is TerminalKind.ENCODER:
            self.slave.output = rx.pack(int(self.bus.terminal_outputs[k]) & 0xFF,
                                        int(self.bus.terminal_set_counts[k]) & 0xFFFF)
        elif self.type.kind is TerminalKind.ANALOG_OUT:
            word = int(self.bus.terminal_outputs[k])
            self.slave.output = rx.pack(*analog_channels(word, self.type.channels))
        else:
            self.slave.output = rx.pack(int(self.bus.terminal_outputs[k]) & ((1 << 8 * rx.size) - 1))

    def read(self) -> None:
        tx, k = self.tx, self.k
        if tx is None:
            return
        values = tx.unpack(self.slave.input)
        self.bus.terminal_inputs[k] = values[0]
        if self.type.kind is TerminalKind.ENCODER:
            self.bus.terminal_counts[k] = values[1]
            self.bus.terminal_latches[k] = values[2]
