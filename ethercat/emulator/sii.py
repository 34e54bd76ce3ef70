"""SII EEPROM image of an emulated slave (ETG.2010 layout, 16-bit words, little endian).

Words 0x00-0x07 ESC configuration, 0x08 vendor id, 0x0A product code, 0x0C revision,
0x0E serial number, 0x18/0x19 receive (master -> slave) mailbox offset/size, 0x1A/0x1B
send mailbox offset/size, 0x1C mailbox protocols, then categories from word 0x40:
Strings (10), General (30), FMMU (40), SyncManager (41), for a slave without a mailbox its
TxPDOs (50) and RxPDOs (51) (what a master maps from when it cannot ask by CoE), end marker
0xFFFF.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass

CAT_STRINGS = 10
CAT_GENERAL = 30
CAT_FMMU = 40
CAT_SM = 41
CAT_TXPDO = 50
CAT_RXPDO = 51
CAT_END = 0xFFFF

MBX_PROTOCOL_COE = 0x0004

# General category byte 5, CoE details (ETG.2010 table "General").
COE_SDO = 0x01
COE_SDO_INFO = 0x02
COE_PDO_ASSIGN = 0x04
COE_PDO_CONFIG = 0x08
COE_UPLOAD_AT_STARTUP = 0x10
COE_COMPLETE_ACCESS = 0x20


@dataclass(frozen=True, slots=True)
class SmConfig:
    """One sync manager as the SII SM category describes it."""

    start: int
    length: int
    control: int
    enable: int
    sm_type: int  # 1 mailbox out, 2 mailbox in, 3 process data outputs, 4 inputs


@dataclass(frozen=True, slots=True)
class SiiLayout:
    """Identity and memory layout written into the SII image."""

    vendor_id: int
    product_code: int
    revision: int
    serial: int
    name: str
    mbx_out_start: int = 0x1000
    mbx_out_size: int = 128
    mbx_in_start: int = 0x1400
    mbx_in_size: int = 128
    outputs_start: int = 0x1800
    inputs_start: int = 0x1C00
    coe_details: int = COE_SDO | COE_PDO_ASSIGN | COE_PDO_CONFIG | COE_COMPLETE_ACCESS
    # PDOs in the SII (a slave without CoE): (pdo index, sync manager, 1 fixed, ((index, sub,
    # bits), ...)) per PDO
    rx_pdos: tuple[tuple[int, int, int, tuple[tuple[int, int, int], ...]], ...] = ()
    tx_pdos: tuple[tuple[int, int, int, tuple[tuple[int, int, int], ...]], ...] = ()
    group: str = "Drives"

    @property
    def has_mailbox(self) -> bool:
        return self.mbx_out_size > 0

    @property
    def sync_managers(self) -> tuple[SmConfig, ...]:
        return (
            SmConfig(self.mbx_out_start, self.mbx_out_size, 0x26, 0x01, 1),
            SmConfig(self.mbx_in_start, self.mbx_in_size, 0x22, 0x01, 2),
            SmConfig(self.outputs_start, 0, 0x64, 0x01, 3),
            SmConfig(self.inputs_start, 0, 0x20, 0x01, 4),
        )


def _category(cat_type: int, data: bytes) -> bytes:
    if len(data) % 2:
        data += b"\x00"
    return struct.pack("<HH", cat_type, len(data) // 2) + data


def _pdo(index: int, sm: int, flags: int, entries: tuple[tuple[int, int, int], ...]) -> bytes:
    """One PDO of the TxPDO/RxPDO category: index, entry count, sync manager, synchronisation,
    name, flags; then per entry index, sub-index, name, data type, bit length, flags."""
    head = struct.pack("<HBBBBH", index, len(entries), sm, 0, 0, flags)
    types = {1: 0x01, 8: 0x05, 16: 0x06}               # BOOL, UINT8, UINT16 (else UINT32)
    return head + b"".join(struct.pack("<HBBBBH", i, sub, 0, types.get(bits, 0x07), bits, 0)
                           for i, sub, bits in entries)


def build_sii(layout: SiiLayout, size_bytes: int = 2048) -> bytearray:
    """The EEPROM image (bytes) for `layout`."""
    words = bytearray(0x80)
    struct.pack_into("<H", words, 0x00, 0x0C08)          # PDI control: SPI/uC, as typical drives
    struct.pack_into("<IIII", words, 0x10, layout.vendor_id, layout.product_code, layout.revision,
                     layout.serial)
    struct.pack_into("<HHHHH", words, 0x30, layout.mbx_out_start, layout.mbx_out_size,
                     layout.mbx_in_start, layout.mbx_in_size, MBX_PROTOCOL_COE if layout.has_mailbox else 0)
    struct.pack_into("<HH", words, 0x7C, size_bytes * 8 // 1024 - 1, 1)   # size (Kbit - 1), version
    strings = [layout.name.encode("ascii", "replace")[:255], layout.group.encode("ascii"), b"CiA402"]
    sdata = bytes([len(strings)]) + b"".join(bytes([len(s)]) + s for s in strings)
    general = bytearray(32)
    general[0] = 2            # group: string 2
    general[1] = 0            # image
    general[2] = 3            # order: string 3
    general[3] = 1            # name: string 1
    general[5] = layout.coe_details
    general[9] = 1 if layout.has_mailbox else 0     # DS402 channels
    general[12:14] = struct.pack("<h", 0)   # E-bus current
    fmmu = bytes([1, 2, 3, 0xFF])
    sm = b"".join(struct.pack("<HHBBBB", s.start, s.length, s.control, 0, s.enable, s.sm_type)
                  for s in layout.sync_managers)
    image = bytearray(words)
    image += _category(CAT_STRINGS, sdata)
    image += _category(CAT_GENERAL, bytes(general))
    image += _category(CAT_FMMU, fmmu)
    image += _category(CAT_SM, sm)
    for cat, pdos in ((CAT_TXPDO, layout.tx_pdos), (CAT_RXPDO, layout.rx_pdos)):
        if pdos:
            image += _category(cat, b"".join(_pdo(*p) for p in pdos))
    image += struct.pack("<H", CAT_END)
    if len(image) > size_bytes:
        raise ValueError(f"SII image of {len(image)} bytes exceeds {size_bytes}")
    image += b"\xff" * (size_bytes - len(image))
    return image


def sii_categories(image: bytes) -> dict[int, bytes]:
    """Category type -> data of an SII image (for tests and `cnc-ethercat`)."""
    out: dict[int, bytes] = {}
    addr = 0x80
    while addr + 4 <= len(image):
        cat_type, n_words = struct.unpack_from("<HH", image, addr)
        if cat_type == CAT_END:
            break
        out[cat_type] = bytes(image[addr + 4: addr + 4 + 2 * n_words])
        addr += 4 + 2 * n_words
    return out
