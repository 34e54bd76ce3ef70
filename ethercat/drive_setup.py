"""How one drive is brought up, beyond its identity: which PDO mapping, whether it may be
rewritten, the drive's own start-up SDOs and its distributed-clock settings. The machine
configuration's ``[[bus.drives]]`` tables become one `DriveSetup` per slave position; a drive
without one gets the defaults, which adapt to what the drive allows."""

from __future__ import annotations

import enum
import struct
from dataclasses import dataclass

from .errors import ConfigurationError
from .pdo import PdoMapping

__all__ = ["DriveSetup", "MappingPolicy", "StartupSdo", "StartupStep"]


class MappingPolicy(enum.Enum):
    """What to do with the drive's PDO mapping."""

    #: write the wanted mapping (without optional objects the drive lacks); when the drive
    #: refuses, restore and use its own mapping if it carries the mandatory objects
    ADAPT = "adapt"
    #: write the wanted mapping or fail (the integrator's mapping must be used)
    WRITE = "write"
    #: never write: use the mapping the drive has (drives with a fixed mapping)
    KEEP = "keep"


class StartupStep(enum.Enum):
    """The steps of bringing the bus up, as named in every start-up error."""

    ADAPTER = "opening the network adapter"
    SCAN = "scanning the bus"
    IDENTITY = "checking the drives' identity"
    MAILBOX = "checking the drives' mailbox (SDO complete access)"
    MAPPING = "configuring the PDO mapping"
    STARTUP_SDO = "writing the drives' start-up SDOs"
    PROCESS_DATA = "mapping the process data"
    DC = "starting distributed clocks (SYNC0)"
    SAFEOP = "going to SAFE-OP"
    OP = "going to OP"
    MODE = "checking cyclic synchronous position mode (0x6061 = 8)"


_SIZES = {1: ("<b", "<B"), 2: ("<h", "<H"), 4: ("<i", "<I"), 8: ("<q", "<Q")}


@dataclass(frozen=True, slots=True)
class StartupSdo:
    """One SDO written in PRE-OP before the process data is mapped (vendor parameters,
    modes, scaling): object, value and its size in bytes (1, 2, 4 or 8)."""

    index: int
    subindex: int
    value: int
    size_bytes: int

    def __post_init__(self) -> None:
        if self.size_bytes not in _SIZES:
            raise ConfigurationError(f"start-up SDO 0x{self.index:04X}:{self.subindex}: size must be 1, 2, 4 "
                                     f"or 8 bytes, got {self.size_bytes}")
        if not 0 <= self.index <= 0xFFFF or not 0 <= self.subindex <= 0xFF:
            raise ConfigurationError(f"start-up SDO 0x{self.index:X}:{self.subindex}: index must be "
                                     "0..0xFFFF and subindex 0..255")
        bits = 8 * self.size_bytes
        if not -(1 << (bits - 1)) <= self.value < (1 << bits):
            raise ConfigurationError(f"start-up SDO 0x{self.index:04X}:{self.subindex}: value {self.value} "
                                     f"does not fit in {self.size_bytes} byte(s)")

    @property
    def data(self) -> bytes:
        signed, unsigned = _SIZES[self.size_bytes]
        return struct.pack(signed if self.value < 0 else unsigned, self.value)

    def text(self) -> str:
        return f"0x{self.index:04X}:{self.subindex} = {self.value} ({self.size_bytes} byte)"


@dataclass(frozen=True, slots=True)
class DriveSetup:
    """Start-up settings of one drive. ``mapping`` None: the drive model's known mapping or
    the CSP default. ``complete_access`` None: tried, and not used when the drive does not
    answer it properly. ``sync_mode`` (0x1C32:1, 2 = DC SYNC0) is written when set."""

    mapping: PdoMapping | None = None
    policy: MappingPolicy = MappingPolicy.ADAPT
    startup_sdos: tuple[StartupSdo, ...] = ()
    dc: bool = True
    sync0_shift_ns: int = 0
    sync_mode: int | None = None
    complete_access: bool | None = None

    def __post_init__(self) -> None:
        if not -1_000_000_000 < self.sync0_shift_ns < 1_000_000_000:
            raise ConfigurationError(f"SYNC0 shift must be within +-1 s, got {self.sync0_shift_ns} ns")
        if self.sync_mode is not None and self.sync_mode not in (0, 1, 2, 3):
            raise ConfigurationError(f"0x1C32:1 sync mode must be 0 (free run), 1 (SM2 event), 2 (DC SYNC0) "
                                     f"or 3 (DC SYNC1), got {self.sync_mode}")
