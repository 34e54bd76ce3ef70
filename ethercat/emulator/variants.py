"""Ways third-party CiA 402 drives differ from the project's own, as options of the emulated
drive, so the master's start-up is tested against them without a third-party binary:

- ``standard``: the project's drive (mapping writable, every object, complete access right);
- ``fixed``: a fixed PDO mapping in other mapping objects (0x1601/0x1A01), in another order,
  with padding and objects the master does not use, that refuses to be rewritten; no
  following error, error code or digital I/O in it;
- ``minimal``: the optional objects 0x60F4, 0x603F, 0x60FD and 0x60FE do not exist, and the
  mode display 0x6061 shows the new mode only 0.3 s after 0x6060 changed;
- ``picky``: announces SDO complete access but answers it without the pad byte after
  sub-index 0 (as KickCAT's drive does), starts in FAULT (error code 0x7500) and needs a
  fault reset, and faults when enabled with a target far from its position.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["VARIANTS", "DriveVariant"]


@dataclass(frozen=True, slots=True)
class DriveVariant:
    """Options of one emulated drive (see the module docstring)."""

    name: str = "standard"
    fixed_mapping: bool = False
    #: default mapping: (RxPDO object, entries), (TxPDO object, entries); entries are
    #: (index, subindex, bits), index 0 = padding
    rx_default: tuple[int, tuple[tuple[int, int, int], ...]] = (0x1600, ((0x6040, 0, 16), (0x607A, 0, 32)))
    tx_default: tuple[int, tuple[tuple[int, int, int], ...]] = (0x1A00, ((0x6041, 0, 16), (0x6064, 0, 32)))
    missing: frozenset[int] = frozenset()
    ca_without_pad: bool = False
    fault_at_power_up: int = 0
    mode_display_delay_s: float = 0.0
    enable_target_window_counts: int = 0


VARIANTS: dict[str, DriveVariant] = {
    "standard": DriveVariant(),
    "fixed": DriveVariant(
        "fixed", fixed_mapping=True,
        rx_default=(0x1601, ((0x607A, 0, 32), (0x6040, 0, 16), (0x6060, 0, 8), (0, 0, 8))),
        tx_default=(0x1A01, ((0x6064, 0, 32), (0x6041, 0, 16), (0x6061, 0, 8), (0, 0, 8),
                             (0x606C, 0, 32)))),
    "minimal": DriveVariant("minimal", missing=frozenset({0x60F4, 0x603F, 0x60FD, 0x60FE}),
                            mode_display_delay_s=0.3),
    "picky": DriveVariant("picky", ca_without_pad=True, fault_at_power_up=0x7500,
                          enable_target_window_counts=1000),
}
