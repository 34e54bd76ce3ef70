"""Emulated EtherCAT terminals (``ethercat.terminals``): couplers, digital I/O, encoders.

A terminal has no mailbox and no object dictionary, as Beckhoff's EL1xxx/EL2xxx/EK1100: the
master learns its process image from the SII alone (the TxPDO and RxPDO categories, 50 and 51,
ETG.2010), which is what SOEM reads for a slave without CoE. The image is the terminal type's
(``TerminalType.rx_format`` / ``tx_format``): one bit per channel, an encoder's status, counter
and latch. The emulator's control socket sets its input bits and reads its outputs.
"""

from __future__ import annotations

import struct
from collections.abc import Callable

from ..terminals import TerminalKind, TerminalType
from .coe import PdoLayout
from .sii import SiiLayout

__all__ = ["TerminalObjects", "terminal_layout"]


def terminal_layout(t: TerminalType, position: int) -> SiiLayout:
    """The SII of a terminal: its identity, no mailbox, the process data sync managers and
    its PDOs (EL1xxx: one entry of 1 bit per channel, 0x6000 + 0x10 c : 1; EL2xxx: 0x7000 +
    0x10 c : 1; EL4xxx: 0x7000 + 0x10 c : 0x11 INT16 out; EL5101: 0x6000:1 u8, :2 u16, :3 u16
    in, 0x7000:1 u8, :2 u16 out)."""
    rx: list[tuple[int, int, int, tuple[tuple[int, int, int], ...]]] = []
    tx: list[tuple[int, int, int, tuple[tuple[int, int, int], ...]]] = []
    if t.kind is TerminalKind.DIGITAL_IN:
        tx = [(0x1A00 + c, 3, 1, ((0x6000 + 0x10 * c, 1, 1),)) for c in range(t.channels)]
    elif t.kind is TerminalKind.DIGITAL_OUT:
        rx = [(0x1600 + c, 2, 1, ((0x7000 + 0x10 * c, 1, 1),)) for c in range(t.channels)]
    elif t.kind is TerminalKind.ANALOG_OUT:
        rx = [(0x1600 + 2 * c, 2, 1, ((0x7000 + 0x10 * c, 0x11, 16),)) for c in range(t.channels)]
    elif t.kind is TerminalKind.ENCODER:
        rx = [(0x1600, 2, 1, ((0x7000, 1, 8), (0x7000, 2, 16)))]
        tx = [(0x1A00, 3, 1, ((0x6000, 1, 8), (0x6000, 2, 16), (0x6000, 3, 16)))]
    return SiiLayout(vendor_id=t.vendor_id, product_code=t.product_code, revision=0x0011_0000,
                     serial=position + 1, name=t.name, mbx_out_size=0, mbx_in_size=0, coe_details=0,
                     rx_pdos=tuple(rx), tx_pdos=tuple(tx), group="Terminals")


class TerminalObjects:
    """What the slave asks of its process data side: layouts, and the image in both
    directions (``inputs`` set by the control socket, ``outputs`` as the master wrote them)."""

    def __init__(self, t: TerminalType) -> None:
        self.type = t
        self.inputs = 0           # channel bits (an encoder's status byte)
        self.counter = 0
        self.latch = 0
        self.outputs = 0
        self.set_value = 0
        self.sync_mode = {0x1C32: 0, 0x1C33: 0}
        self._rx = struct.Struct("<" + t.rx_format) if t.rx_format else None
        self._tx = struct.Struct("<" + t.tx_format) if t.tx_format else None

    def rx_layout(self) -> PdoLayout:
        return PdoLayout(self._rx.size if self._rx else 0, self._rx or struct.Struct("<"), ())

    def tx_layout(self) -> PdoLayout:
        return PdoLayout(self._tx.size if self._tx else 0, self._tx or struct.Struct("<"), ())

    def make_output_setter(self, layout: PdoLayout) -> Callable[[bytes | memoryview], None]:
        unpack = layout.fmt.unpack_from

        analog = self.type.kind is TerminalKind.ANALOG_OUT

        def apply(data: bytes | memoryview) -> None:
            values = unpack(data)
            if analog:                    # the channels' INT16 values in one word, 16 bits each
                self.outputs = sum((int(v) & 0xFFFF) << 16 * c for c, v in enumerate(values))
                return
            self.outputs = int(values[0])
            if len(values) > 1:
                self.set_value = int(values[1])

        return apply

    def make_input_getter(self, layout: PdoLayout) -> Callable[[bytearray, int], None]:
        pack_into = layout.fmt.pack_into
        bits = 8 * layout.fmt.size
        encoder = self.type.kind is TerminalKind.ENCODER

        def fill(buf: bytearray, offset: int) -> None:
            if encoder:
                pack_into(buf, offset, self.inputs & 0xFF, self.counter & 0xFFFF, self.latch & 0xFFFF)
            else:
                pack_into(buf, offset, self.inputs & ((1 << bits) - 1))

        return fill

    def assignment(self, _index: int) -> list[int]:
        return []

    def mapping(self, _index: int) -> list[int]:
        return []
