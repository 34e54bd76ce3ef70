"""How one drive is brought up, beyond its identity: which PDO mapping, whether it may be
rewritten, the drive's own start-up SDOs and its distributed-clock settings. The machine
configuration's ``[[bus.drives]]`` tables become one `DriveSetup` per slave position; a drive
without one gets the defaults, which adapt to what the drive allows."""

from __future__ import annotations

import enum
import struct
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from .errors import ConfigurationError, EtherCATError
from .pdo import PdoMapping

__all__ = ["DriveSetup", "MappingPolicy", "StartupSdo", "StartupStep", "drive_table_problem"]


#: the process data watchdog's range at an ESC's standard divider (0x0400 = 2498: 100 us units
#: in the 16-bit register 0x0420); a longer one is refused at bring-up when the drive's divider
#: does not reach it
MIN_WATCHDOG_MS = 1.0
MAX_WATCHDOG_MS = 6553.5


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
    answer it properly. ``sync_mode`` (0x1C32:1, 2 = DC SYNC0) is written when set.
    ``watchdog_ms``: the process data (SM) watchdog, register 0x0420, written in PRE-OP when
    set (None: the drive's own, 100 ms on most ESCs); the drive leaves OP and faults when its
    outputs stop arriving for this long."""

    mapping: PdoMapping | None = None
    policy: MappingPolicy = MappingPolicy.ADAPT
    startup_sdos: tuple[StartupSdo, ...] = ()
    dc: bool = True
    sync0_shift_ns: int = 0
    sync_mode: int | None = None
    complete_access: bool | None = None
    watchdog_ms: float | None = None

    def __post_init__(self) -> None:
        if not -1_000_000_000 < self.sync0_shift_ns < 1_000_000_000:
            raise ConfigurationError(f"SYNC0 shift must be within +-1 s, got {self.sync0_shift_ns} ns")
        if self.sync_mode is not None and self.sync_mode not in (0, 1, 2, 3):
            raise ConfigurationError(f"0x1C32:1 sync mode must be 0 (free run), 1 (SM2 event), 2 (DC SYNC0) "
                                     f"or 3 (DC SYNC1), got {self.sync_mode}")
        if self.watchdog_ms is not None and not MIN_WATCHDOG_MS <= self.watchdog_ms <= MAX_WATCHDOG_MS:
            raise ConfigurationError(f"process data watchdog must be {MIN_WATCHDOG_MS:g} to "
                                     f"{MAX_WATCHDOG_MS:g} ms (0x0420 counts 100 us units), "
                                     f"got {self.watchdog_ms:g} ms")


def drive_table_problem(d: Mapping[str, Any]) -> tuple[tuple[str | int, ...], str] | None:
    """What is wrong with one ``[[bus.drives]]`` table of the machine configuration (already
    checked key by key), as the bring-up would find it: the key within the table and the
    reason, or None. Every reader of the configuration asks this, so they refuse alike."""
    from .pdo import is_velocity, parse_entry

    entries: dict[str, list[Any]] = {}
    for key in ("rx", "tx"):
        entries[key] = []
        for k, text in enumerate(d[key]):
            try:
                entries[key].append(parse_entry(text))
            except EtherCATError as exc:
                return (key, k), str(exc)
    sdos = []
    for k, x in enumerate(d["sdo"]):
        try:
            sdos.append(StartupSdo(x["index"], x["subindex"], x["value"], x["size"]))
        except EtherCATError as exc:
            return ("sdo", k), str(exc)
    try:
        mapping = PdoMapping(tuple(entries["rx"]), tuple(entries["tx"]), d["rx_pdo"], d["tx_pdo"],
                             velocity=is_velocity(entries["rx"])) if entries["rx"] or entries["tx"] else None
        DriveSetup(mapping=mapping, policy=MappingPolicy(d["mapping"]), startup_sdos=tuple(sdos), dc=d["dc"],
                   sync0_shift_ns=d["sync0_shift_ns"], sync_mode=d["sync_mode"],
                   complete_access={"auto": None, "on": True, "off": False}[d["complete_access"]],
                   watchdog_ms=d["watchdog_ms"])
    except EtherCATError as exc:
        return ("tx" if "TxPDO" in str(exc) else "rx",), str(exc)
    return None
