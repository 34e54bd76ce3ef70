"""A line of emulated slaves answering EtherCAT frames (ETG.1000.4 datagram handling).

`Segment.process_frame(frame)` takes one Ethernet frame (EtherType 0x88A4) as the
master sent it and returns the frame as it comes back from the end of the line: every
datagram handled by every slave in order, with data, address and working counter
updated as real ESCs do:

    APRD/APWR/APRW/ARMW  auto-increment address: the slave that sees ADP == 0 acts,
                         every slave increments ADP
    FPRD/FPWR/FPRW/FRMW  configured station address (0x0010) or alias (0x0012)
    BRD/BWR/BRW          every slave; BRD ORs the register into the data
    LRD/LWR/LRW          logical addressing through each slave's FMMUs
    ARMW/FRMW            the addressed slave reads, all others write (DC time distribution)

Working counter: +1 per slave for a read or a write, +3 for a read-write that did both
(LRW: +1 inputs read, +2 outputs written). A slave marked `lost` passes frames on
untouched, as a slave that lost power behind a bypass would.
"""

from __future__ import annotations

import struct
import time
from collections.abc import Callable, Sequence

from ..drive_model import DriveModel, DriveParams
from ..terminals import TerminalType
from .esc import EscSlave
from .sii import SiiLayout
from .terminal import TerminalObjects, terminal_layout
from .variants import VARIANTS, DriveVariant

ETHERTYPE_ECAT = 0x88A4

APRD, APWR, APRW, FPRD, FPWR, FPRW, BRD, BWR, BRW, LRD, LWR, LRW, ARMW, FRMW = range(1, 15)
COMMAND_NAMES = {APRD: "APRD", APWR: "APWR", APRW: "APRW", FPRD: "FPRD", FPWR: "FPWR", FPRW: "FPRW",
                 BRD: "BRD", BWR: "BWR", BRW: "BRW", LRD: "LRD", LWR: "LWR", LRW: "LRW",
                 ARMW: "ARMW", FRMW: "FRMW"}
_AUTO = (APRD, APWR, APRW, ARMW)
_FIXED = (FPRD, FPWR, FPRW, FRMW)
_READS = (APRD, FPRD, BRD)
_WRITES = (APWR, FPWR, BWR)
_RW = (APRW, FPRW, BRW)

_DGRAM = struct.Struct("<BBHHHH")


class Segment:
    """N emulated CiA 402 drives in a line. `models` are the shared drive models."""

    def __init__(self, models: Sequence[DriveModel], layouts: Sequence[SiiLayout] | None = None,
                 clock_ns: Callable[[], int] | None = None,
                 variant: DriveVariant = VARIANTS["standard"],
                 terminals: Sequence[TerminalType] = ()) -> None:
        """The drives first, then ``terminals`` (couplers, I/O) behind them in the line."""
        t0 = time.monotonic_ns()
        self.clock_ns = clock_ns if clock_ns is not None else (lambda: time.monotonic_ns() - t0)
        n = len(models) + len(terminals)
        if layouts is None:
            layouts = [default_layout(m.params, i) for i, m in enumerate(models)]
        self.variant = variant
        self.slaves = [EscSlave(i, m, lay, last_in_line=(i == n - 1), clock_ns=self.clock_ns, variant=variant)
                       for i, (m, lay) in enumerate(zip(models, layouts))]
        for k, t in enumerate(terminals):
            i = len(models) + k
            self.slaves.append(EscSlave(i, None, terminal_layout(t, i), last_in_line=(i == n - 1),
                                        clock_ns=self.clock_ns, objects=TerminalObjects(t)))
        for i, s in enumerate(self.slaves):
            s.n_after = n - 1 - i
        self.frames_in = 0
        self.datagrams = 0
        self.unknown_commands = 0

    @classmethod
    def of_drives(cls, n_drives: int, params: DriveParams | None = None,
                  variant: DriveVariant = VARIANTS["standard"],
                  terminals: Sequence[TerminalType] = ()) -> Segment:
        """`n_drives` drives with the default drive parameters (serial = position), each
        behaving as `variant` says."""
        p = params if params is not None else DriveParams.for_axis(10_000.0)
        from dataclasses import replace
        p = replace(p, fault_at_power_up=variant.fault_at_power_up,
                    mode_display_delay_s=variant.mode_display_delay_s,
                    enable_target_window_counts=variant.enable_target_window_counts)
        models = [DriveModel(replace(p, serial=i + 1), position=i) for i in range(n_drives)]
        return cls(models, variant=variant, terminals=terminals)

    # ------------------------------------------------------------------ frames
    def process_frame(self, frame: bytes | bytearray | memoryview) -> bytearray | None:
        """The answer to one Ethernet frame, or None if it is not an EtherCAT frame."""
        buf = bytearray(frame)
        if len(buf) < 16 + 12:
            return None
        offset = 12
        ethertype = struct.unpack_from(">H", buf, offset)[0]
        if ethertype == 0x8100:                             # VLAN tag
            offset += 4
            ethertype = struct.unpack_from(">H", buf, offset)[0]
        if ethertype != ETHERTYPE_ECAT:
            return None
        header = struct.unpack_from("<H", buf, offset + 2)[0]
        if header >> 12 != 1:                               # type 1: EtherCAT commands
            return None
        self.process_datagrams(buf, offset + 4, min(len(buf), offset + 4 + (header & 0x07FF)))
        buf[6] |= 0x02                                      # ESC marks the source MAC
        self.frames_in += 1
        return buf

    def process_datagrams(self, buf: bytearray, pos: int, end: int) -> None:
        """Handle the datagrams of an EtherCAT frame body in place."""
        view = memoryview(buf)
        touched: list[EscSlave] = []
        while pos + 12 <= end:
            cmd, _idx, adp, ado, len_flags, _irq = _DGRAM.unpack_from(buf, pos)
            dlen = len_flags & 0x07FF
            data_at = pos + 10
            if data_at + dlen + 2 > len(buf):
                break
            data = view[data_at: data_at + dlen]
            wkc = struct.unpack_from("<H", buf, data_at + dlen)[0]
            adp, wkc = self._datagram(cmd, adp, ado, data, wkc, touched)
            struct.pack_into("<H", buf, pos + 2, adp)
            struct.pack_into("<H", buf, data_at + dlen, wkc & 0xFFFF)
            self.datagrams += 1
            pos = data_at + dlen + 2
            if not len_flags & 0x8000:
                break
        view.release()
        for s in touched:
            s.end_of_frame()

    def _datagram(self, cmd: int, adp: int, ado: int, data: memoryview, wkc: int,
                  touched: list[EscSlave]) -> tuple[int, int]:
        n = len(data)
        if cmd in (LRD, LWR, LRW):
            laddr = adp | (ado << 16)
            do_read = cmd != LWR
            do_write = cmd != LRD
            for s in self.slaves:
                if s.lost:
                    continue
                inc = s.logical(laddr, data, do_read, do_write)
                if inc:
                    wkc += inc
                    if s.outputs_dirty and s not in touched:
                        touched.append(s)
            return adp, wkc
        if cmd in _AUTO:
            for s in self.slaves:
                if s.lost:
                    continue
                if adp == 0:
                    wkc += self._access(s, cmd, ado, data, True)
                elif cmd == ARMW:
                    wkc += self._access(s, cmd, ado, data, False)
                adp = (adp + 1) & 0xFFFF
            return adp, wkc
        if cmd in _FIXED:
            for s in self.slaves:
                if s.lost:
                    continue
                if s.station_address == adp or (s.alias and s.alias == adp and s.regs[0x0100 + 3] & 0x01):
                    wkc += self._access(s, cmd, ado, data, True)
                elif cmd == FRMW:
                    wkc += self._access(s, cmd, ado, data, False)
            return adp, wkc
        if cmd in (BRD, BWR, BRW):
            for s in self.slaves:
                if s.lost:
                    continue
                if cmd == BRD:
                    reg = s.read(ado, n)
                    data[:] = _or_bytes(data, reg)
                    wkc += 1
                elif cmd == BWR:
                    s.write(ado, data)
                    wkc += 1
                else:
                    incoming = bytes(data)
                    reg = s.read(ado, n)
                    s.write(ado, incoming)
                    data[:] = _or_bytes(incoming, reg)
                    wkc += 3
                adp = (adp + 1) & 0xFFFF
            return adp, wkc
        self.unknown_commands += 1
        return adp, wkc

    @staticmethod
    def _access(s: EscSlave, cmd: int, ado: int, data: memoryview, addressed: bool) -> int:
        n = len(data)
        if cmd in _READS:
            data[:] = s.read(ado, n)
            return 1
        if cmd in _WRITES:
            s.write(ado, data)
            return 1
        if cmd in _RW:
            incoming = bytes(data)
            data[:] = s.read(ado, n)
            s.write(ado, incoming)
            return 3
        # ARMW / FRMW: the addressed slave reads, the others write
        if addressed:
            data[:] = s.read(ado, n)
        else:
            s.write(ado, data)
        return 1

    # ------------------------------------------------------------------ housekeeping
    def housekeeping(self) -> None:
        for s in self.slaves:
            s.housekeeping()

    def status(self) -> dict[str, object]:
        return {"frames": self.frames_in, "datagrams": self.datagrams,
                "unknown_commands": self.unknown_commands,
                "slaves": [s.status() for s in self.slaves]}


def _or_bytes(a: bytes | memoryview, b: bytes) -> bytes:
    return (int.from_bytes(a, "little") | int.from_bytes(b, "little")).to_bytes(len(b), "little")


def default_layout(params: DriveParams, position: int) -> SiiLayout:
    """SII identity of an emulated drive: the drive model's vendor/product/revision."""
    return SiiLayout(vendor_id=params.vendor_id, product_code=params.product_code,
                     revision=params.revision, serial=params.serial or position + 1,
                     name="CNC-Servo-402")
