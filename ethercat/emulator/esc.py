"""Register model of one emulated EtherCAT slave controller (ESC) with a CiA 402 drive.

What it models (ETG.1000.4/.6, Beckhoff ESC datasheet section II register map):
- 64 KiB address space: ESC registers below 0x1000, process data RAM above.
- Identity/feature registers (0x0000-0x0008, DC supported + 64-bit DC), station address
  0x0010, alias 0x0012, DL status 0x0110 (a line: port 0 in, port 1 on to the next slave).
- AL control 0x0120 / AL status 0x0130 / AL status code 0x0134: INIT, PRE-OP, SAFE-OP,
  OP with error indication, acknowledge and status codes (0x0011, 0x0012, 0x0013, 0x0016,
  0x001B watchdog, 0x001D/0x001E invalid output/input configuration, 0x0030/0x0036 DC).
- SII EEPROM interface 0x0500-0x050F (read, write, 32-bit data register).
- FMMUs 0x0600 (logical -> physical, byte granular), sync managers 0x0800: SM0/SM1
  mailboxes (CoE), SM2 outputs, SM3 inputs.
- DC: receive time latch 0x0900-0x090C and 0x0918 on a write to 0x0900, system time
  0x0910 (local clock + offset 0x0920), delay 0x0928, SYNC0 activation 0x0981, start
  time 0x0990, cycle 0x09A0.
- Process data watchdog (0x0400 divider, 0x0420 time): OP -> SAFE-OP + error 0x001B.
"""

from __future__ import annotations

import struct
from collections.abc import Callable

from ..cia402 import Cia402State
from ..drive_model import DriveModel
from ..errors import SdoAbortError
from .coe import DriveObjects
from .sii import SiiLayout, build_sii
from .terminal import TerminalObjects
from .variants import VARIANTS, DriveVariant

INIT, PREOP, BOOT, SAFEOP, OP = 1, 2, 3, 4, 8
STATE_NAMES = {INIT: "INIT", PREOP: "PRE-OP", BOOT: "BOOT", SAFEOP: "SAFE-OP", OP: "OP"}
_ORDER = {INIT: 0, PREOP: 1, SAFEOP: 2, OP: 3}

# AL status codes (ETG.1000.6 table 11)
AL_OK = 0x0000
AL_INVALID_STATE_CHANGE = 0x0011
AL_UNKNOWN_STATE = 0x0012
AL_BOOTSTRAP_NOT_SUPPORTED = 0x0013
AL_INVALID_MAILBOX_CONFIG = 0x0016
AL_SM_WATCHDOG = 0x001B
AL_INVALID_OUTPUT_CONFIG = 0x001D
AL_INVALID_INPUT_CONFIG = 0x001E
AL_INVALID_DC_SYNC = 0x0030
AL_SYNC_CYCLE_TOO_SMALL = 0x0036

REG_STADR = 0x0010
REG_ALIAS = 0x0012
REG_DLSTAT = 0x0110
REG_ALCTL = 0x0120
REG_ALSTAT = 0x0130
REG_ALCODE = 0x0134
REG_WD_DIV = 0x0400
REG_WD_PD = 0x0420
REG_EEPCTL = 0x0502
REG_EEPADR = 0x0504
REG_EEPDAT = 0x0508
REG_FMMU0 = 0x0600
REG_SM0 = 0x0800
REG_DCTIME0 = 0x0900
REG_DCSYSTIME = 0x0910
REG_DCSOF = 0x0918
REG_DCSYSOFFSET = 0x0920
REG_DCSYNCACT = 0x0981
REG_DCCYCLE0 = 0x09A0

_MBX_HEADER = struct.Struct("<HHBB")
MBX_TYPE_ERR = 0x00
MBX_TYPE_COE = 0x03
COE_SDO_REQUEST = 2
COE_SDO_RESPONSE = 3
COE_SDO_INFO = 8

#: regions the master cannot write: identity, DL status, AL status/code, DC latches
_READ_ONLY = ((0x0000, 0x0010), (REG_DLSTAT, REG_DLSTAT + 2), (REG_ALSTAT, REG_ALSTAT + 6),
              (REG_DCSYSTIME, REG_DCSOF + 8))
_SM_STATUS = tuple(REG_SM0 + 8 * k + 5 for k in range(8))


class EscSlave:
    """One slave: registers, SII, AL state machine, mailbox, FMMU, DC, watchdog, drive."""

    def __init__(self, position: int, model: DriveModel | None, layout: SiiLayout, last_in_line: bool,
                 clock_ns: Callable[[], int], variant: DriveVariant = VARIANTS["standard"],
                 objects: TerminalObjects | None = None) -> None:
        """``model`` None: a terminal (``objects`` its process image, no mailbox)."""
        self.position = position
        self.model = model
        self.layout = layout
        self.sii = build_sii(layout)
        self.objects: DriveObjects | TerminalObjects
        if objects is not None:
            self.objects = objects
        else:
            assert model is not None, "a drive's slave needs its model"
            self.objects = DriveObjects(model, layout.name, lambda: self.al_state, variant)
        self.clock_ns = clock_ns
        self.last_in_line = last_in_line
        self.n_after = 0          # slaves behind this one in the line (DC delay latches)
        self.lost = False
        self.regs = bytearray(0x10000)
        self.frames = 0
        self.sdo_requests = 0
        self._reset_registers()
        if model is not None:
            model.step(0.001)     # power-on self test: NOT READY -> SWITCH ON DISABLED

    # ------------------------------------------------------------------ power-on state
    def _reset_registers(self) -> None:
        r = self.regs
        r[:] = bytes(len(r))
        r[0x0000] = 0x11                                    # ESC type: ET1100-like
        r[0x0001] = 0x02                                    # revision
        struct.pack_into("<H", r, 0x0002, 0x0001)           # build
        r[0x0004] = 8                                       # FMMUs
        r[0x0005] = 8                                       # sync managers
        r[0x0006] = 8                                       # RAM KiB
        r[0x0007] = 0x0F                                    # port descriptor
        struct.pack_into("<H", r, 0x0008, 0x000C)           # DC + 64-bit DC
        # DL status: PDI operational, link + communication on port 0 (and port 1 to the
        # next slave unless last), unused ports closed (ET1100 0x0110 bit layout)
        dl = 0x0001 | 0x0010 | 0x0200 | 0x1000 | 0x4000
        dl |= 0x0400 if self.last_in_line else (0x0020 | 0x0800)
        struct.pack_into("<H", r, REG_DLSTAT, dl)
        r[0x0140] = 0x05                                    # PDI control
        struct.pack_into("<H", r, REG_WD_DIV, 0x09C2)       # 100 us watchdog unit
        struct.pack_into("<H", r, REG_WD_PD, 1000)          # 100 ms process data watchdog
        self.station_address = 0
        self.alias = 0
        self.al_state = INIT
        self.al_error = False
        self.al_code = AL_OK
        self._write_al_status()
        self.fmmus: list[tuple[int, int, int, int]] = []    # (log start, length, phys start, type)
        self.sms: list[tuple[int, int, int, int]] = [(0, 0, 0, 0)] * 8  # start, length, control, activate
        self.out_size = 0
        self.in_size = 0
        self._apply_outputs: Callable[[bytes | memoryview], None] | None = None
        self._fill_inputs: Callable[[bytearray, int], None] | None = None
        self.outputs_dirty = False
        self.last_output_ns = 0
        self.last_step_ns = self.clock_ns()
        self.watchdog_trips = 0
        self._last_mailbox = b""

    def power_cycle(self) -> None:
        """Back to the power-on state (a slave that was lost and comes back): registers
        reset, AL state INIT, the drive restarts (faults cleared, power stage off)."""
        self._reset_registers()
        m = self.model
        if m is None:
            return
        m.controlword = 0
        m.error_code = 0
        m.state = Cia402State.NOT_READY_TO_SWITCH_ON
        m.step(0.001)

    # ------------------------------------------------------------------ AL state machine
    def _write_al_status(self) -> None:
        struct.pack_into("<HHH", self.regs, REG_ALSTAT, self.al_state | (0x10 if self.al_error else 0), 0,
                         self.al_code)

    def _fail(self, code: int) -> None:
        self.al_error = True
        self.al_code = code
        self._write_al_status()

    def al_control(self, value: int) -> None:
        """AL control write (ETG.1000.6 5.3): bits 0-3 requested state, bit 4 acknowledge."""
        req = value & 0x0F
        ack = bool(value & 0x10)
        if self.al_error:
            if ack:
                self.al_error = False
                self.al_code = AL_OK
            elif not (req in _ORDER and _ORDER[req] < _ORDER[self.al_state]):
                self._write_al_status()
                return
        if req == BOOT:
            self._fail(AL_BOOTSTRAP_NOT_SUPPORTED)
            return
        if req not in _ORDER:
            self._fail(AL_UNKNOWN_STATE)
            return
        cur = self.al_state
        if req == cur:
            self._write_al_status()
            return
        if _ORDER[req] < _ORDER[cur]:
            self._enter(req)
            return
        if _ORDER[req] - _ORDER[cur] != 1:
            self._fail(AL_INVALID_STATE_CHANGE)
            return
        code = {PREOP: self._check_mailbox, SAFEOP: self._check_process_data, OP: self._check_sync}[req]()
        if code:
            self._fail(code)
        else:
            self._enter(req)

    def _enter(self, state: int) -> None:
        prev = self.al_state
        if prev == OP and state != OP:
            self._outputs_invalid()
        self.al_state = state
        if state == OP:
            self.last_output_ns = self.clock_ns()
        if state == INIT:
            self.regs[REG_SM0 + 8 + 5] &= ~0x08 & 0xFF
        self._write_al_status()

    def _outputs_invalid(self) -> None:
        """Leaving OP: the drive loses its set-points (a running drive faults, 0x8700)."""
        m = self.model
        if m is None:
            return
        if m.state in (Cia402State.OPERATION_ENABLED, Cia402State.QUICK_STOP_ACTIVE):
            m.watchdog_expired()
        m.controlword = 0

    def _check_mailbox(self) -> int:
        sm0, sm1 = self.sms[0], self.sms[1]
        lay = self.layout
        if not lay.has_mailbox:
            return AL_OK
        ok = (sm0[0] == lay.mbx_out_start and sm0[1] == lay.mbx_out_size and sm0[3] & 1
              and sm1[0] == lay.mbx_in_start and sm1[1] == lay.mbx_in_size and sm1[3] & 1)
        return AL_OK if ok else AL_INVALID_MAILBOX_CONFIG

    def _check_process_data(self) -> int:
        rx = self.objects.rx_layout()
        tx = self.objects.tx_layout()
        sm2, sm3 = self.sms[2], self.sms[3]
        lay = self.layout
        if rx.size_bytes and (sm2[1] != rx.size_bytes or not sm2[3] & 1 or sm2[0] != lay.outputs_start):
            return AL_INVALID_OUTPUT_CONFIG
        if tx.size_bytes and (sm3[1] != tx.size_bytes or not sm3[3] & 1 or sm3[0] != lay.inputs_start):
            return AL_INVALID_INPUT_CONFIG
        self.out_size = rx.size_bytes
        self.in_size = tx.size_bytes
        self._apply_outputs = self.objects.make_output_setter(rx)
        self._fill_inputs = self.objects.make_input_getter(tx)
        return AL_OK

    def _check_sync(self) -> int:
        if self.objects.sync_mode[0x1C32] != 2:
            return AL_OK
        cycle_ns = struct.unpack_from("<I", self.regs, REG_DCCYCLE0)[0]
        if self.regs[REG_DCSYNCACT] & 0x03 != 0x03 or cycle_ns == 0:
            return AL_INVALID_DC_SYNC
        if cycle_ns < 125_000:
            return AL_SYNC_CYCLE_TOO_SMALL
        return AL_OK

    # ------------------------------------------------------------------ register access
    def read(self, ado: int, length: int) -> bytes:
        """EtherCAT read of `length` bytes at physical address `ado` (with side effects)."""
        end = ado + length
        if ado < REG_DCSYSTIME + 8 and end > REG_DCSYSTIME:
            struct.pack_into("<Q", self.regs, REG_DCSYSTIME, self.system_time_ns())
        if self.in_size and ado < self.layout.inputs_start + self.in_size and end > self.layout.inputs_start:
            self.refresh_inputs()
        data = bytes(self.regs[ado:end])
        sm1_start, sm1_len = self.sms[1][0], self.sms[1][1]
        if sm1_len and ado <= sm1_start + sm1_len - 1 < end:
            self.regs[REG_SM0 + 8 + 5] &= ~0x08 & 0xFF       # mailbox read: SM1 empty again
        return data

    def write(self, ado: int, data: bytes | memoryview) -> None:
        """EtherCAT write at physical address `ado` (with side effects)."""
        end = ado + len(data)
        if end > 0x10000:
            return
        if ado >= 0x1000:                                    # process data / mailbox RAM
            self.regs[ado:end] = data
            self._ram_written(ado, end)
            return
        if REG_DCSYSTIME <= ado and end <= REG_DCSOF + 8:
            return      # ARMW/FRMW time distribution: drift compensation is not modelled
        saved = [(a, b, bytes(self.regs[a:b])) for a, b in _READ_ONLY if ado < b and end > a]
        saved_status = [(k, self.regs[k]) for k in _SM_STATUS if ado <= k < end]
        self.regs[ado:end] = data
        for a, b, old in saved:
            self.regs[a:b] = old
        for k, old_byte in saved_status:
            self.regs[k] = old_byte
        self._register_side_effects(ado, end)

    def _ram_written(self, ado: int, end: int) -> None:
        sm0_start, sm0_len = self.sms[0][0], self.sms[0][1]
        if sm0_len and ado <= sm0_start + sm0_len - 1 < end and self.al_state != INIT:
            self._mailbox_request()
        out_start = self.layout.outputs_start
        if self.out_size and ado < out_start + self.out_size and end > out_start:
            self._outputs_written()

    def _register_side_effects(self, ado: int, end: int) -> None:
        def hit(a: int, n: int = 1) -> bool:
            return ado < a + n and end > a

        r = self.regs
        if hit(REG_STADR, 2):
            self.station_address = struct.unpack_from("<H", r, REG_STADR)[0]
        if hit(REG_ALIAS, 2):
            self.alias = struct.unpack_from("<H", r, REG_ALIAS)[0]
        if hit(REG_ALCTL):
            self.al_control(struct.unpack_from("<H", r, REG_ALCTL)[0])
        if hit(REG_EEPCTL + 1):
            self._eeprom_command()
        if hit(REG_FMMU0, 0x100):
            self._parse_fmmus()
        if hit(REG_SM0, 0x80):
            self.sms = [(*struct.unpack_from("<HH", r, REG_SM0 + 8 * k), r[REG_SM0 + 8 * k + 4],
                         r[REG_SM0 + 8 * k + 6]) for k in range(8)]
        if hit(REG_DCTIME0):
            self._latch_receive_times()

    def _parse_fmmus(self) -> None:
        fmmus = []
        for k in range(8):
            log, length, _sb, _eb, phys, _pb, ftype, act = struct.unpack_from("<IHBBHBBB", self.regs,
                                                                             REG_FMMU0 + 16 * k)
            if act & 1 and length and ftype in (1, 2, 3):
                fmmus.append((log, length, phys, ftype))
        self.fmmus = fmmus

    def _eeprom_command(self) -> None:
        r = self.regs
        ctl = struct.unpack_from("<H", r, REG_EEPCTL)[0]
        addr_words = struct.unpack_from("<I", r, REG_EEPADR)[0]
        cmd = (ctl >> 8) & 0x07
        status = ctl & 0x0001                                # keep the write enable bit
        byte_addr = 2 * addr_words
        if cmd == 0x01:                                      # read 4 bytes
            chunk = bytes(self.sii[byte_addr: byte_addr + 4]).ljust(4, b"\xff")
            r[REG_EEPDAT: REG_EEPDAT + 4] = chunk
        elif cmd == 0x02:                                    # write one word
            if byte_addr + 2 <= len(self.sii):
                self.sii[byte_addr: byte_addr + 2] = r[REG_EEPDAT: REG_EEPDAT + 2]
        elif cmd not in (0x00, 0x04):
            status |= 0x2000                                 # unknown command: NACK
        struct.pack_into("<H", r, REG_EEPCTL, status)

    def system_time_ns(self) -> int:
        offset = struct.unpack_from("<Q", self.regs, REG_DCSYSOFFSET)[0]
        return (self.clock_ns() + offset) & 0xFFFF_FFFF_FFFF_FFFF

    def _latch_receive_times(self) -> None:
        # frame passes port 0 of every slave going out and port 1 coming back (500 ns/hop)
        now = self.clock_ns()
        t0 = now + 500 * self.position
        t1 = t0 + 1000 * self.n_after if not self.last_in_line else 0
        struct.pack_into("<IIII", self.regs, REG_DCTIME0, t0 & 0xFFFF_FFFF, t1 & 0xFFFF_FFFF, 0, 0)
        struct.pack_into("<Q", self.regs, REG_DCSOF, t0)

    # ------------------------------------------------------------------ mailbox (CoE)
    def _mailbox_request(self) -> None:
        start, size = self.sms[0][0], self.sms[0][1]
        mbx = bytes(self.regs[start: start + size])
        if mbx == self._last_mailbox and self.regs[REG_SM0 + 8 + 5] & 0x08:
            return      # the master repeated a write whose answer is still unread: execute once
        self._last_mailbox = mbx
        length, _address, _prio, type_cnt = _MBX_HEADER.unpack_from(mbx)
        mbx_type = type_cnt & 0x0F
        cnt = (type_cnt >> 4) & 0x07
        payload = mbx[6: 6 + length]
        self.sdo_requests += 1
        if mbx_type != MBX_TYPE_COE:
            self._mailbox_response(MBX_TYPE_ERR, cnt, struct.pack("<HH", 0x0001, 0x0002))
            return
        service = struct.unpack_from("<H", payload)[0] >> 12
        if service == COE_SDO_REQUEST:
            assert isinstance(self.objects, DriveObjects)       # a terminal has no mailbox
            answer = self.objects.handle_sdo(payload[2:], self.sms[1][1] - 6)
            if not answer:
                return
            reply_service = COE_SDO_REQUEST if answer[0] == 0x80 else COE_SDO_RESPONSE
            self._mailbox_response(MBX_TYPE_COE, cnt, struct.pack("<H", reply_service << 12) + answer)
        elif service == COE_SDO_INFO:
            # SDO information is not offered (General category): answer with an SDO info error
            err = struct.pack("<BBHI", 0x07, 0, 0, SdoAbortError.GENERAL)
            self._mailbox_response(MBX_TYPE_COE, cnt, struct.pack("<H", COE_SDO_INFO << 12) + err)
        else:
            self._mailbox_response(MBX_TYPE_ERR, cnt, struct.pack("<HH", 0x0001, 0x0003))

    def _mailbox_response(self, mbx_type: int, cnt: int, payload: bytes) -> None:
        start, size = self.sms[1][0], self.sms[1][1]
        if not size:
            return
        out = bytearray(size)
        _MBX_HEADER.pack_into(out, 0, len(payload), 0, 0, mbx_type | (cnt << 4))
        out[6: 6 + len(payload)] = payload[: size - 6]
        self.regs[start: start + size] = out
        self.regs[REG_SM0 + 8 + 5] |= 0x08                   # SM1 mailbox full

    # ------------------------------------------------------------------ process data
    def refresh_inputs(self) -> None:
        if self._fill_inputs is not None:
            self._fill_inputs(self.regs, self.layout.inputs_start)

    def _outputs_written(self) -> None:
        self.outputs_dirty = True
        self.last_output_ns = self.clock_ns()

    def logical(self, laddr: int, data: memoryview, do_read: bool, do_write: bool) -> int:
        """LRD/LWR/LRW through the FMMUs: returns this slave's working counter increment."""
        if self.al_state not in (SAFEOP, OP) or not self.fmmus:
            return 0
        end = laddr + len(data)
        wrote = read = False
        regs = self.regs
        if do_write:
            for log, length, phys, ftype in self.fmmus:
                if ftype & 2 and log < end and log + length > laddr:
                    a = max(log, laddr)
                    b = min(log + length, end)
                    regs[phys + a - log: phys + b - log] = data[a - laddr: b - laddr]
                    wrote = True
            if wrote:
                self._outputs_written()
        if do_read:
            for log, length, phys, ftype in self.fmmus:
                if ftype & 1 and log < end and log + length > laddr:
                    if not read:
                        self.refresh_inputs()
                    a = max(log, laddr)
                    b = min(log + length, end)
                    data[a - laddr: b - laddr] = regs[phys + a - log: phys + b - log]
                    read = True
        return (1 if read else 0) + (2 if wrote else 0) if do_read and do_write else int(read or wrote)

    def end_of_frame(self) -> None:
        """After a frame carrying outputs: hand them to the drive (in OP) and run one cycle."""
        if not self.outputs_dirty:
            return
        self.outputs_dirty = False
        self.frames += 1
        now = self.clock_ns()
        if self.al_state == OP and self._apply_outputs is not None:
            start = self.layout.outputs_start
            self._apply_outputs(memoryview(self.regs)[start: start + self.out_size])
        cycle_ns = struct.unpack_from("<I", self.regs, REG_DCCYCLE0)[0]
        if self.regs[REG_DCSYNCACT] & 0x03 == 0x03 and cycle_ns:
            dt_s = cycle_ns * 1e-9
        else:
            dt_s = min(0.01, max(0.000_1, (now - self.last_step_ns) * 1e-9))
        if self.model is not None:
            self.model.step(dt_s)
        self.last_step_ns = now

    def watchdog_ns(self) -> int:
        """The process data watchdog time: 0x0420 in units of (0x0400 + 2) x 40 ns; 0 = off."""
        div = struct.unpack_from("<H", self.regs, REG_WD_DIV)[0]
        wd = struct.unpack_from("<H", self.regs, REG_WD_PD)[0]
        return int(wd * (div + 2) * 40)

    def housekeeping(self) -> None:
        """Called every few ms: process data watchdog and the drive's idle time."""
        now = self.clock_ns()
        if self.al_state == OP:                              # runs on while disconnected too
            wd_ns = self.watchdog_ns()
            if wd_ns and now - self.last_output_ns > wd_ns:
                self.watchdog_trips += 1
                self._enter(SAFEOP)
                self._fail(AL_SM_WATCHDOG)
        if now - self.last_step_ns > 20_000_000 and self.model is not None:
            self.model.step(min(0.1, (now - self.last_step_ns) * 1e-9))
            self.last_step_ns = now

    # ------------------------------------------------------------------ diagnostics
    def status(self) -> dict[str, object]:
        m = self.model
        objects = self.objects
        if m is None:
            assert isinstance(objects, TerminalObjects)
            return {"position": self.position, "station_address": self.station_address,
                    "al_state": STATE_NAMES.get(self.al_state, str(self.al_state)), "al_error": self.al_error,
                    "al_status_code": self.al_code, "lost": self.lost, "terminal": objects.type.name,
                    "inputs": objects.inputs, "outputs": objects.outputs, "counter": objects.counter,
                    "frames": self.frames, "watchdog_trips": self.watchdog_trips}
        assert isinstance(objects, DriveObjects)
        return {"position": self.position, "station_address": self.station_address,
                "al_state": STATE_NAMES.get(self.al_state, str(self.al_state)), "al_error": self.al_error,
                "al_status_code": self.al_code, "lost": self.lost, "drive_state": m.state.name,
                "statusword": m.statusword, "position_actual": m.position_actual,
                "target_position": m.target_position, "error_code": m.error_code,
                "frames": self.frames, "sdo_requests": self.sdo_requests,
                "watchdog_trips": self.watchdog_trips, "watchdog_ms": self.watchdog_ns() * 1e-6,
                "sync0_active": self.regs[REG_DCSYNCACT] & 0x03 == 0x03,
                "sync0_cycle_ns": struct.unpack_from("<I", self.regs, REG_DCCYCLE0)[0],
                "rx_mapping": [f"0x{v:08X}" for p in objects.assignment(0x1C12)
                               for v in objects.mapping(p)],
                "tx_mapping": [f"0x{v:08X}" for p in objects.assignment(0x1C13)
                               for v in objects.mapping(p)]}
