"""The emulator's datagram handling, fed frames in process (no network, no root).

A small master here builds real EtherCAT frames (Ethernet header, EtherType 0x88A4,
datagrams with working counters) the way SOEM does and checks what comes back: working
counters per command, auto-increment / configured / broadcast / logical addressing, SII
EEPROM reads, the AL state machine and its status codes, CoE SDO (expedited, normal,
segmented, complete access, aborts), FMMU process data, DC registers and the watchdog.
"""

from __future__ import annotations

import struct

import pytest

from ethercat.drive_model import DriveModel, DriveParams
from ethercat.emulator import Segment
from ethercat.emulator.segment import (
    APRD,
    APWR,
    ARMW,
    BRD,
    BWR,
    FPRD,
    FPRW,
    FPWR,
    FRMW,
    LRD,
    LRW,
    LWR,
    default_layout,
)
from ethercat.emulator.sii import CAT_GENERAL, CAT_SM, CAT_STRINGS, SiiLayout, sii_categories
from ethercat.errors import SdoAbortError

SRC_MAC = b"\x01\x01\x01\x01\x01\x01"


class FakeClock:
    def __init__(self) -> None:
        self.ns = 1_000_000_000

    def __call__(self) -> int:
        return self.ns

    def advance(self, seconds: float) -> None:
        self.ns += int(seconds * 1e9)


def frame(*datagrams: tuple[int, int, int, bytes]) -> bytes:
    """Ethernet frame with datagrams (cmd, adp, ado, data); logical commands: adp|ado<<16."""
    body = b""
    for k, (cmd, adp, ado, data) in enumerate(datagrams):
        more = 0x8000 if k < len(datagrams) - 1 else 0
        body += struct.pack("<BBHHHH", cmd, k, adp, ado, len(data) | more, 0) + data + b"\x00\x00"
    out = b"\xff" * 6 + SRC_MAC + struct.pack(">H", 0x88A4) + struct.pack("<H", len(body) | 0x1000) + body
    return out.ljust(60, b"\x00")


def parse(answer: bytes) -> list[tuple[int, bytes, int]]:
    """[(adp, data, wkc)] of each datagram in an answered frame."""
    out = []
    pos = 16
    while True:
        _cmd, _idx, adp, _ado, len_flags, _irq = struct.unpack_from("<BBHHHH", answer, pos)
        n = len_flags & 0x7FF
        data = bytes(answer[pos + 10: pos + 10 + n])
        wkc = struct.unpack_from("<H", answer, pos + 10 + n)[0]
        out.append((adp, data, wkc))
        pos += 12 + n
        if not len_flags & 0x8000:
            return out


class MiniMaster:
    """Just enough of a master to walk the emulator through SOEM's sequence."""

    def __init__(self, segment: Segment) -> None:
        self.seg = segment
        self.mbx_cnt = 0

    def dg(self, cmd: int, adp: int, ado: int, data: bytes) -> tuple[int, bytes, int]:
        answer = self.seg.process_frame(frame((cmd, adp, ado, data)))
        assert answer is not None
        assert answer[6] & 0x02, "ESC marks the source MAC"
        return parse(answer)[0]

    def rd(self, cmd: int, adp: int, ado: int, n: int) -> tuple[bytes, int]:
        _adp, data, wkc = self.dg(cmd, adp, ado, bytes(n))
        return data, wkc

    def wr(self, cmd: int, adp: int, ado: int, data: bytes) -> int:
        return self.dg(cmd, adp, ado, data)[2]

    def fprd_u16(self, station: int, ado: int) -> int:
        return struct.unpack("<H", self.rd(FPRD, station, ado, 2)[0])[0]

    # -------------------------------------------------------------- config_init-like
    def init(self) -> int:
        n = self.rd(BRD, 0, 0x0000, 2)[1]
        self.wr(BWR, 0, 0x0120, b"\x11")
        for pos in range(n):
            assert self.wr(APWR, (-pos) & 0xFFFF, 0x0010, struct.pack("<H", 0x1001 + pos)) == 1
        return n

    def eeprom_read(self, station: int, word: int) -> bytes:
        assert self.wr(FPWR, station, 0x0502, struct.pack("<HHH", 0x0100, word, 0)) == 1
        assert self.fprd_u16(station, 0x0502) & 0x8000 == 0
        return self.rd(FPRD, station, 0x0508, 4)[0]

    def set_al(self, station: int, state: int) -> tuple[int, int]:
        self.wr(FPWR, station, 0x0120, struct.pack("<H", state))
        st, code = struct.unpack("<HxxH", self.rd(FPRD, station, 0x0130, 6)[0])
        return st, code

    def mailbox_sms(self, station: int, layout: SiiLayout) -> None:
        sm = struct.pack("<HHI", layout.mbx_out_start, layout.mbx_out_size, 0x00010026)
        sm += struct.pack("<HHI", layout.mbx_in_start, layout.mbx_in_size, 0x00010022)
        assert self.wr(FPWR, station, 0x0800, sm) == 1

    # -------------------------------------------------------------- CoE
    def coe(self, station: int, layout: SiiLayout, sdo: bytes) -> bytes:
        """Send one CoE SDO request (bytes after the CoE header), return the answer's."""
        status = self.rd(FPRD, station, 0x0805, 1)[0][0]
        assert status & 0x08 == 0, "SM0 mailbox must be empty"
        self.mbx_cnt = self.mbx_cnt % 7 + 1
        payload = struct.pack("<H", 2 << 12) + sdo
        mbx = struct.pack("<HHBB", len(payload), 0, 0, 0x03 | (self.mbx_cnt << 4)) + payload
        assert self.wr(FPWR, station, layout.mbx_out_start, mbx.ljust(layout.mbx_out_size, b"\0")) == 1
        assert self.rd(FPRD, station, 0x080D, 2)[0][0] & 0x08, "answer in SM1"
        answer, wkc = self.rd(FPRD, station, layout.mbx_in_start, layout.mbx_in_size)
        assert wkc == 1
        assert self.rd(FPRD, station, 0x080D, 2)[0][0] & 0x08 == 0, "read empties SM1"
        length, _a, _c, type_cnt = struct.unpack_from("<HHBB", answer)
        assert type_cnt & 0x0F == 0x03
        return answer[6: 6 + length]

    def upload(self, station: int, layout: SiiLayout, index: int, sub: int, ca: bool = False) -> bytes:
        ans = self.coe(station, layout, struct.pack("<BHBI", 0x50 if ca else 0x40, index, sub, 0))
        cmd = ans[2]
        if cmd == 0x80:
            raise SdoAbortError(0, index, sub, struct.unpack_from("<I", ans, 6)[0])
        assert ans[0:2] == struct.pack("<H", 3 << 12)
        assert struct.unpack_from("<H", ans, 3)[0] == index
        if cmd & 0x02:
            return ans[6: 6 + 4 - ((cmd >> 2) & 3)]
        total = struct.unpack_from("<I", ans, 6)[0]
        data = ans[10:]
        toggle = 0
        while len(data) < total:
            seg = self.coe(station, layout, struct.pack("<BHBI", 0x60 | toggle, index, sub, 0))
            assert seg[2] & 0xE0 == 0 and seg[2] & 0x10 == toggle
            n = len(seg) - 3
            if seg[2] & 0x01 and n == 7:
                n -= (seg[2] >> 1) & 0x07
            data += seg[3: 3 + n]
            toggle ^= 0x10
        return data[:total]

    def download(self, station: int, layout: SiiLayout, index: int, sub: int, data: bytes,
                 ca: bool = False) -> None:
        rest = b""
        if len(data) <= 4 and not ca:
            req = struct.pack("<BHB", 0x23 | ((4 - len(data)) << 2), index, sub) + data.ljust(4, b"\0")
        else:
            room = layout.mbx_out_size - 16
            req = struct.pack("<BHBI", 0x31 if ca else 0x21, index, sub, len(data)) + data[:room]
            rest = data[room:]
        ans = self.coe(station, layout, req)
        if ans[2] == 0x80:
            raise SdoAbortError(0, index, sub, struct.unpack_from("<I", ans, 6)[0])
        assert ans[2] == 0x60
        toggle = 0
        while len(data) > 4 or ca:
            if not rest:
                break
            chunk, rest = rest[: layout.mbx_out_size - 9], rest[layout.mbx_out_size - 9:]
            unused = max(0, 7 - len(chunk))
            cmd = toggle | (unused << 1) | (0 if rest else 1)
            ans = self.coe(station, layout, bytes([cmd]) + chunk.ljust(7, b"\0"))
            if ans[2] == 0x80:
                raise SdoAbortError(0, index, sub, struct.unpack_from("<I", ans, 6)[0])
            assert ans[2] == 0x20 | toggle
            toggle ^= 0x10


@pytest.fixture
def clock() -> FakeClock:
    return FakeClock()


@pytest.fixture
def seg(clock: FakeClock) -> Segment:
    models = [DriveModel(DriveParams.for_axis(10_000.0), position=i) for i in range(3)]
    return Segment(models, clock_ns=clock)


@pytest.fixture
def master(seg: Segment) -> MiniMaster:
    return MiniMaster(seg)


LAYOUT = default_layout(DriveParams(), 0)
CSP_RX = (0x60400010, 0x607A0020, 0x60600008)
CSP_TX = (0x60410010, 0x60640020, 0x60F40020, 0x603F0010)


def to_preop(m: MiniMaster, station: int) -> None:
    m.mailbox_sms(station, LAYOUT)
    assert m.set_al(station, 0x12) == (0x02, 0)


def map_csp(m: MiniMaster, station: int) -> None:
    """CSP mapping by complete access, then SM2/SM3 and FMMUs as SOEM's config_map does."""
    m.download(station, LAYOUT, 0x1C12, 0, b"\x00\x00", ca=True)
    m.download(station, LAYOUT, 0x1600, 0, struct.pack("<Bx3I", 3, *CSP_RX), ca=True)
    m.download(station, LAYOUT, 0x1C12, 0, struct.pack("<BxH", 1, 0x1600), ca=True)
    m.download(station, LAYOUT, 0x1C13, 0, b"\x00\x00", ca=True)
    m.download(station, LAYOUT, 0x1A00, 0, struct.pack("<Bx4I", 4, *CSP_TX), ca=True)
    m.download(station, LAYOUT, 0x1C13, 0, struct.pack("<BxH", 1, 0x1A00), ca=True)
    k = station - 0x1001
    m.wr(FPWR, station, 0x0810, struct.pack("<HHI", LAYOUT.outputs_start, 7, 0x00010064))
    m.wr(FPWR, station, 0x0818, struct.pack("<HHI", LAYOUT.inputs_start, 12, 0x00010020))
    # outputs of all slaves first (7 bytes each), then inputs (12 bytes each)
    fmmu = struct.Struct("<IHBBHBBBxH")         # SOEM's ec_fmmut
    m.wr(FPWR, station, 0x0600, fmmu.pack(7 * k, 7, 0, 7, LAYOUT.outputs_start, 0, 2, 1, 0))
    m.wr(FPWR, station, 0x0610, fmmu.pack(21 + 12 * k, 12, 0, 7, LAYOUT.inputs_start, 0, 1, 1, 0))


def dc_sync(m: MiniMaster, station: int, cycle_ns: int = 1_000_000) -> None:
    m.wr(FPWR, station, 0x0981, b"\x00")
    m.wr(FPWR, station, 0x09A0, struct.pack("<I", cycle_ns))
    m.wr(FPWR, station, 0x0981, b"\x03")


def bring_to_op(m: MiniMaster) -> None:
    n = m.init()
    for k in range(n):
        st = 0x1001 + k
        to_preop(m, st)
        map_csp(m, st)
        assert m.set_al(st, 0x04) == (0x04, 0)
        dc_sync(m, st)
        assert m.set_al(st, 0x08) == (0x08, 0)


# ---------------------------------------------------------------------- addressing
def test_broadcast_read_counts_slaves_and_auto_increment_addresses(master: MiniMaster) -> None:
    adp, data, wkc = master.dg(BRD, 0, 0x0000, bytes(2))
    assert wkc == 3 and adp == 3, "every slave answers and increments ADP"
    assert data[0] == 0x11
    # APRD: ADP 0 = first slave, 0xFFFF = second, ...
    assert master.init() == 3
    for pos in range(3):
        data, wkc = master.rd(APRD, (-pos) & 0xFFFF, 0x0010, 2)
        assert wkc == 1 and struct.unpack("<H", data)[0] == 0x1001 + pos
    # an address nobody has: working counter 0
    assert master.rd(APRD, 0xFFF0, 0x0010, 2)[1] == 0
    assert master.rd(FPRD, 0x2000, 0x0010, 2)[1] == 0
    # features: DC and 64-bit DC, DL status: line topology, last slave with port 1 closed
    assert master.fprd_u16(0x1001, 0x0008) & 0x0C == 0x0C
    assert master.fprd_u16(0x1001, 0x0110) & 0x0F00 == 0x0A00
    assert master.fprd_u16(0x1003, 0x0110) & 0x0F00 == 0x0600


def test_read_write_combined_commands_and_read_only_registers(master: MiniMaster) -> None:
    master.init()
    # FPRW: returns the old value, stores the new one, working counter 3
    _adp, data, wkc = master.dg(FPRW, 0x1002, 0x0980, b"\x01")
    assert wkc == 3 and data == b"\x00"
    assert master.rd(FPRD, 0x1002, 0x0980, 1)[0] == b"\x01"
    # identity and AL status are read only for the master
    assert master.wr(FPWR, 0x1001, 0x0000, b"\x00\x00") == 1
    assert master.rd(FPRD, 0x1001, 0x0000, 1)[0] == b"\x11"
    master.wr(FPWR, 0x1001, 0x0130, b"\x08\x00")
    assert master.fprd_u16(0x1001, 0x0130) == 0x0001
    # BRD ORs the AL state of all slaves: one in PRE-OP shows as INIT|PRE-OP
    to_preop(master, 0x1002)
    assert master.rd(BRD, 0, 0x0130, 2)[0] == b"\x03\x00"


def test_several_datagrams_in_one_frame(master: MiniMaster, seg: Segment) -> None:
    master.init()
    answer = seg.process_frame(frame((FPRD, 0x1001, 0x0010, bytes(2)), (FPRD, 0x1003, 0x0010, bytes(2)),
                                     (BRD, 0, 0x0130, bytes(2))))
    assert answer is not None
    (_, d1, w1), (_, d2, w2), (_, d3, w3) = parse(answer)
    assert (d1, w1) == (struct.pack("<H", 0x1001), 1)
    assert (d2, w2) == (struct.pack("<H", 0x1003), 1)
    assert (d3, w3) == (b"\x01\x00", 3)


def test_non_ethercat_frames_are_ignored(seg: Segment) -> None:
    ipv6 = b"\xff" * 6 + SRC_MAC + b"\x86\xdd" + bytes(60)
    assert seg.process_frame(ipv6) is None


# ---------------------------------------------------------------------- SII
def test_sii_identity_mailbox_and_categories(master: MiniMaster, seg: Segment) -> None:
    master.init()
    p = DriveParams()
    assert struct.unpack("<I", master.eeprom_read(0x1001, 0x08))[0] == p.vendor_id
    assert struct.unpack("<I", master.eeprom_read(0x1001, 0x0A))[0] == p.product_code
    assert struct.unpack("<I", master.eeprom_read(0x1001, 0x0C))[0] == p.revision
    assert struct.unpack("<HH", master.eeprom_read(0x1001, 0x18)) == (0x1000, 128)
    assert struct.unpack("<HH", master.eeprom_read(0x1001, 0x1A)) == (0x1400, 128)
    assert struct.unpack("<H", master.eeprom_read(0x1001, 0x1C)[:2])[0] & 0x04, "CoE"
    cats = sii_categories(seg.slaves[0].sii)
    assert cats[CAT_STRINGS][1:1 + cats[CAT_STRINGS][1] + 1][1:] == b"CNC-Servo-402"
    assert cats[CAT_GENERAL][5] & 0x2D == 0x2D, "SDO, PDO assign/config, complete access"
    sms = [struct.unpack_from("<HHBBBB", cats[CAT_SM], 8 * k) for k in range(4)]
    assert [s[5] for s in sms] == [1, 2, 3, 4]


# ---------------------------------------------------------------------- AL state machine
def test_al_state_machine_codes_and_acknowledge(master: MiniMaster) -> None:
    master.init()
    st = 0x1001
    assert master.set_al(st, 0x08) == (0x11, 0x0011), "INIT -> OP is not a valid transition"
    assert master.set_al(st, 0x02) == (0x11, 0x0011), "error pending: request ignored without ack"
    assert master.set_al(st, 0x12) == (0x11, 0x0016), "ack, but no mailbox sync managers"
    assert master.set_al(st, 0x11) == (0x01, 0x0000), "ack clears the error"
    assert master.set_al(st, 0x03) == (0x11, 0x0013), "bootstrap not supported"
    assert master.set_al(st, 0x16) == (0x11, 0x0012), "unknown state"
    to_preop(master, st)
    assert master.set_al(st, 0x04) == (0x12, 0x001D), "default mapping 6 bytes, SM2 not configured"
    map_csp(master, st)
    assert master.set_al(st, 0x14) == (0x04, 0)
    assert master.set_al(st, 0x08) == (0x14, 0x0030), "CSP with DC: SYNC0 must be active"
    dc_sync(master, st, 100_000)
    assert master.set_al(st, 0x18) == (0x14, 0x0036), "SYNC0 cycle below the drive's minimum"
    dc_sync(master, st, 1_000_000)
    assert master.set_al(st, 0x18) == (0x08, 0)
    assert master.set_al(st, 0x01) == (0x01, 0)


# ---------------------------------------------------------------------- CoE
def test_sdo_expedited_normal_and_aborts(master: MiniMaster) -> None:
    master.init()
    st = 0x1001
    to_preop(master, st)
    assert struct.unpack("<H", master.upload(st, LAYOUT, 0x6041, 0))[0] & 0x4F == 0x40
    assert struct.unpack("<I", master.upload(st, LAYOUT, 0x1018, 1))[0] == DriveParams().vendor_id
    assert master.upload(st, LAYOUT, 0x1008, 0) == b"CNC-Servo-402"          # normal upload
    master.download(st, LAYOUT, 0x6065, 0, struct.pack("<I", 1234))
    assert struct.unpack("<I", master.upload(st, LAYOUT, 0x6065, 0))[0] == 1234
    cases = [(0x2FFF, 0, None, SdoAbortError.OBJECT_DOES_NOT_EXIST),
             (0x6099, 7, None, SdoAbortError.SUBINDEX_DOES_NOT_EXIST),
             (0x6041, 0, b"\x00\x00", SdoAbortError.READ_ONLY),
             (0x6065, 0, b"\x01\x00", SdoAbortError.LENGTH_MISMATCH),
             (0x1A00, 1, struct.pack("<I", 0x60410010), 0x06010003)]     # sub 0 must be 0 first
    for index, sub, data, code in cases:
        with pytest.raises(SdoAbortError) as exc:
            if data is None:
                master.upload(st, LAYOUT, index, sub)
            else:
                master.download(st, LAYOUT, index, sub, data)
        assert exc.value.abort_code == code, hex(index)


def test_sdo_segmented_upload_with_small_mailbox(clock: FakeClock) -> None:
    model = DriveModel(DriveParams(), position=0)
    layout = SiiLayout(1, 2, 3, 4, "tiny-mailbox", mbx_out_size=32, mbx_in_size=32)
    m = MiniMaster(Segment([model], [layout], clock_ns=clock))
    m.init()
    m.mailbox_sms(0x1001, layout)
    assert m.set_al(0x1001, 0x12) == (0x02, 0)
    assert m.upload(0x1001, layout, 0x100A, 0) == b"cnc-ethercat emulator 1.0"
    # segmented download of a complete access mapping (26 bytes > 32 - 16)
    entries = (*CSP_TX, 0x60610008, 0x606C0020)
    m.download(0x1001, layout, 0x1A00, 0, struct.pack("<Bx6I", 6, *entries), ca=True)
    assert m.upload(0x1001, layout, 0x1A00, 0, ca=True)[0] == 6


def test_pdo_mapping_rules_and_complete_access(master: MiniMaster) -> None:
    master.init()
    st = 0x1001
    to_preop(master, st)
    map_csp(master, st)
    assert master.upload(st, LAYOUT, 0x1600, 0, ca=True) == struct.pack("<Bx3I", 3, *CSP_RX)
    assert master.upload(st, LAYOUT, 0x1C12, 0, ca=True) == struct.pack("<BxH", 1, 0x1600)
    assert master.upload(st, LAYOUT, 0x1C00, 0, ca=True) == bytes([4, 0, 1, 2, 3, 4])
    # not mappable: statusword into the RxPDO, wrong bit length, assignment of a TxPDO to SM2
    for index, data, code in ((0x1601, struct.pack("<Bx1I", 1, 0x60410010), 0x06040041),
                              (0x1601, struct.pack("<Bx1I", 1, 0x607A0010), 0x06040041),
                              (0x1C12, struct.pack("<BxH", 1, 0x1A00), SdoAbortError.VALUE_RANGE)):
        with pytest.raises(SdoAbortError) as exc:
            master.download(st, LAYOUT, index, 0, data, ca=True)
        assert exc.value.abort_code == code
    assert master.set_al(st, 0x04) == (0x04, 0)
    with pytest.raises(SdoAbortError) as exc:
        master.download(st, LAYOUT, 0x1C12, 0, b"\x00")
    assert exc.value.abort_code == 0x08000022, "PDO configuration only in PRE-OP"


# ---------------------------------------------------------------------- process data
def test_lrw_working_counter_outputs_inputs_and_drive_motion(master: MiniMaster, seg: Segment) -> None:
    bring_to_op(master)
    n_out, n_in = 21, 36

    def cycle(cw: int, targets: list[int]) -> tuple[bytes, int]:
        out = b"".join(struct.pack("<HiB", cw, t, 8) for t in targets)
        _adp, data, wkc = master.dg(LRW, 0, 0, out + bytes(n_in))
        return data[n_out:], wkc

    inputs, wkc = cycle(0, [0, 0, 0])
    assert wkc == 9, "LRW: +2 outputs written, +1 inputs read per slave"
    sw = [struct.unpack_from("<HiiH", inputs, 12 * k) for k in range(3)]
    assert all(s[0] & 0x4F == 0x40 for s in sw)
    for cw in (0x06, 0x07, 0x0F, 0x0F):
        cycle(cw, [0, 0, 0])
    targets = [100, -200, 300]
    for _ in range(200):
        inputs, wkc = cycle(0x0F, targets)
        assert wkc == 9
    actual = [struct.unpack_from("<HiiH", inputs, 12 * k)[1] for k in range(3)]
    assert actual == targets
    assert [s.model.position_actual for s in seg.slaves] == targets
    # LRD reads only, LWR writes only: +1 per slave each
    assert master.dg(LRD, 0, 0, bytes(n_out + n_in))[2] == 3
    assert master.dg(LWR, 0, 0, bytes(n_out + n_in))[2] == 3


def test_dc_registers_and_time_distribution(master: MiniMaster, clock: FakeClock) -> None:
    master.init()
    master.wr(BWR, 0, 0x0900, bytes(4))                          # latch receive times
    t0 = [struct.unpack("<II", master.rd(FPRD, 0x1001 + k, 0x0900, 8)[0]) for k in range(3)]
    assert t0[0][0] < t0[1][0] < t0[2][0], "port 0 sees the frame later down the line"
    assert t0[0][1] > t0[0][0], "port 1 sees it come back"
    master.wr(FPWR, 0x1002, 0x0920, struct.pack("<Q", 5_000))    # system time offset
    clock.advance(0.001)
    sys1 = struct.unpack("<Q", master.rd(FPRD, 0x1001, 0x0910, 8)[0])[0]
    sys2 = struct.unpack("<Q", master.rd(FPRD, 0x1002, 0x0910, 8)[0])[0]
    assert sys2 - sys1 == 5_000
    # FRMW: the reference clock (first slave) reads, the others write: +1 each
    _adp, data, wkc = master.dg(FRMW, 0x1001, 0x0910, bytes(8))
    assert wkc == 3 and struct.unpack("<Q", data)[0] == sys1
    _adp, data, wkc = master.dg(ARMW, 0, 0x0910, bytes(8))
    assert wkc == 3


def test_watchdog_drops_op_to_safeop_with_0x001b(master: MiniMaster, seg: Segment, clock: FakeClock) -> None:
    bring_to_op(master)
    out = b"".join(struct.pack("<HiB", 0, 0, 8) for _ in range(3))
    for cw in (0x06, 0x07, 0x0F, 0x0F):
        out = b"".join(struct.pack("<HiB", cw, 0, 8) for _ in range(3))
        master.dg(LRW, 0, 0, out + bytes(36))
        clock.advance(0.001)
    assert seg.slaves[0].model.state.name == "OPERATION_ENABLED"
    clock.advance(0.05)
    seg.housekeeping()
    assert master.fprd_u16(0x1001, 0x0130) == 0x08, "50 ms: still OP"
    clock.advance(0.06)
    seg.housekeeping()
    st, code = struct.unpack("<HxxH", master.rd(FPRD, 0x1001, 0x0130, 6)[0])
    assert (st, code) == (0x14, 0x001B)
    clock.advance(0.03)
    seg.housekeeping()
    assert seg.slaves[0].model.error_code == 0x8700, "the drive faults on lost set-points"
    assert master.dg(LRW, 0, 0, out + bytes(36))[2] == 9, "SAFE-OP still exchanges process data"


def test_lost_slave_passes_frames_untouched(master: MiniMaster, seg: Segment) -> None:
    bring_to_op(master)
    seg.slaves[2].lost = True
    assert master.dg(LRW, 0, 0, bytes(21 + 36))[2] == 6
    assert master.rd(BRD, 0, 0x0000, 2)[1] == 2
    assert master.rd(FPRD, 0x1003, 0x0130, 2)[1] == 0
    seg.slaves[2].power_cycle()
    seg.slaves[2].lost = False
    assert master.rd(BRD, 0, 0x0000, 2)[1] == 3
    assert master.fprd_u16(0x1001, 0x0130) == 0x08
    assert master.rd(APRD, 0xFFFE, 0x0010, 2)[0] == b"\x00\x00", "power cycled: no station address"
