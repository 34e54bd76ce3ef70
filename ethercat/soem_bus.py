"""SoemBus: the `Bus` interface on real EtherCAT frames through pysoem (SOEM 1.4 API).

Start-up (`open()`), each step failing with an `EtherCATError` that says what and where:

1. open the adapter by name (`AdapterError`, also a `ConnectionError`);
2. `config_init()`: enumerate the slaves (-1: no frame came back; 0: no slave answered);
3. check every configured drive's vendor id and product code against the slave at its
   position (`SlaveIdentityError` names the position and both identities);
4. PDO mapping by SDO in each drive's setup hook (PRE-OP -> SAFE-OP): RxPDO controlword
   0x6040, target position 0x607A, mode 0x6060; TxPDO statusword 0x6041, position
   actual 0x6064, following error 0x60F4, error code 0x603F, mode display 0x6061. The
   mapping is a `PdoMapping`, chosen per drive model (vendor id, product code);
5. `config_map()`: SOEM raises `ConfigMapError` whenever its error list is not empty,
   even when the mapping worked; the list is inspected and only SDO/mailbox errors of
   the drives' own mapping (or a wrong process data size) are fatal;
6. distributed clocks: `config_dc()` and SYNC0 = Ts on EVERY slave (not just the last);
7. SAFE-OP, then OP with process data running, each with a timeout; every state error
   names the slave, its AL state and its AL status code (with SOEM's text).

Cyclic: `exchange()` packs each drive's outputs exactly to the slave's output size
(pysoem copies `len(bytes)` without a bounds check), sends one LRW (+ the DC FRMW),
receives with a timeout and checks the working counter every cycle: inputs are unpacked
only when it is right, otherwise `wkc_errors` counts and the caller (the worker) reacts.
`lost_slaves()` names the slaves that stopped answering; `recover_slaves()` brings back
slaves that returned (identity checked, mapping rewritten, SYNC0 restarted, OP).
pysoem releases the GIL in every call (`always_release_gil`), so an SDO in one thread
does not stall the cyclic thread. `close()` disables SYNC0 and takes the bus to INIT.

Per-cycle cost: one small `bytes` per drive for `slave.output` and one from
`slave.input` (pysoem's API takes and returns `bytes`); no NumPy allocation.
"""

from __future__ import annotations

import os
import struct
import time
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np

from .bus import Bus, DriveSpec, SlaveInfo
from .errors import (
    AdapterError,
    AlStateError,
    AlStateTimeoutError,
    ConfigurationError,
    EtherCATError,
    EtherCATTimeoutError,
    SdoAbortError,
    SdoError,
    SdoTimeoutError,
    SlaveIdentityError,
)
from .pdo import CSP_MAPPING, DRIVE_MAPPINGS, DriveIo, PdoMapping

AL_INIT, AL_PREOP, AL_BOOT, AL_SAFEOP, AL_OP = 1, 2, 3, 4, 8
AL_STATE_NAMES = {0: "NONE", AL_INIT: "INIT", AL_PREOP: "PRE-OP", AL_BOOT: "BOOT",
                  AL_SAFEOP: "SAFE-OP", AL_OP: "OP"}



def al_state_name(state: int) -> str:
    """'OP', 'SAFE-OP + ERROR', ... for an AL status value (bit 4 = error indication)."""
    name = AL_STATE_NAMES.get(state & 0x0F, f"0x{state & 0x0F:X}")
    return name + (" + ERROR" if state & 0x10 else "")


def al_status_text(code: int) -> str:
    try:
        import pysoem

        return str(pysoem.al_status_code_to_string(code))
    except Exception:  # pragma: no cover - text is a convenience only
        return ""


def _import_pysoem() -> Any:
    try:
        import pysoem
    except ImportError as exc:  # pragma: no cover - pysoem is a dependency
        raise ConfigurationError(f"pysoem is not installed: {exc}") from exc
    return pysoem


FRAME_TIMEOUT_ENV = "CNC_ETHERCAT_FRAME_TIMEOUT_US"


def frame_timeout_us() -> int | None:
    """SOEM's receive timeout for non-cyclic frames (configuration, SDO; EC_TIMEOUTRET, 2000 us
    by default) from CNC_ETHERCAT_FRAME_TIMEOUT_US, or None to keep SOEM's. Real slaves answer in
    microseconds; a software slave on a loaded or virtual machine may need more."""
    raw = os.environ.get(FRAME_TIMEOUT_ENV, "").strip()
    if not raw:
        return None
    try:
        value = int(raw)
    except ValueError:
        value = 0
    if not 100 <= value <= 1_000_000:
        raise ConfigurationError(f"{FRAME_TIMEOUT_ENV} must be a whole number of microseconds "
                                 f"from 100 to 1000000, got {raw!r}")
    return value


def open_master(adapter: str) -> Any:
    """A pysoem Master opened on `adapter`, releasing the GIL in every call."""
    pysoem = _import_pysoem()
    if not adapter:
        raise AdapterError("no network adapter given for the EtherCAT bus")
    timeout_us = frame_timeout_us()
    if timeout_us is not None:
        pysoem.settings.timeouts.ret = timeout_us  # process-wide in SOEM: one master per process
    master = pysoem.Master()
    master.always_release_gil = True
    try:
        master.open(adapter)
    except ConnectionError as exc:
        raise AdapterError(f"cannot open network adapter {adapter!r} ({exc}); it must exist and "
                           "the process needs root or CAP_NET_RAW") from exc
    return master


def config_init(master: Any, adapter: str) -> int:
    """Enumerate slaves; raise if none answer."""
    n = int(master.config_init())
    if n < 0:
        raise EtherCATTimeoutError(f"no EtherCAT frame came back on {adapter!r} (config_init returned {n}): "
                                   "cable, link or slave power?")
    if n == 0:
        raise ConfigurationError(f"no EtherCAT slave answered on {adapter!r}")
    return n


#: SOEM's packet errors (``ecx_packeterror``): the slave's answer was not what the request asked
PACKET_ERRORS = {
    1: "unexpected frame returned: the slave answered with another mailbox service than the "
       "SDO asked for (it may not support this transfer, e.g. complete access, or the object)",
    3: "data container too small for the object's type",
}
#: Mailbox error replies (ETG.1000.4 mailbox error detail codes, SOEM ``ecx_mbxerror``)
MAILBOX_ERRORS = {
    1: "syntax of the 6-byte mailbox header is wrong",
    2: "the mailbox protocol is not supported by the slave",
    3: "channel field contains a wrong value",
    4: "the mailbox service is not supported by the slave",
    5: "the header of the mailbox protocol is wrong",
    6: "the received mailbox data is too short",
    7: "no more memory in the slave",
    8: "the length of the mailbox data is inconsistent",
}


def slave_label(master: Any, position: int) -> str:
    """``slave 1 (KickCAT drive, vendor 0x..., product 0x...)``: what an integrator can find."""
    try:
        s = master.slaves[position]
        name = str(getattr(s, "name", "") or "?")
        return f"slave {position} ({name}, vendor 0x{int(s.man):08X}, product 0x{int(s.id):08X})"
    except (AttributeError, IndexError, TypeError, ValueError):
        return f"slave {position}"


def _map_sdo_error(exc: Exception, position: int, index: int, subindex: int,
                   master: Any = None) -> EtherCATError:
    """A pysoem/SOEM error of one SDO transfer as an error an integrator can act on: the slave
    by position, name and identity, the object, and what the failure means."""
    pysoem = _import_pysoem()
    label = slave_label(master, position) if master is not None else f"slave {position}"
    where = f"SDO 0x{index:04X}:{subindex} on {label}"
    if isinstance(exc, pysoem.SdoError):
        return SdoAbortError(position, index, subindex, int(exc.abort_code), str(exc.desc), label=label)
    if isinstance(exc, pysoem.WkcError):
        return SdoTimeoutError(f"{where}: no answer (working counter {getattr(exc, 'wkc', '?')})")
    if isinstance(exc, pysoem.PacketError):
        code = int(getattr(exc, "error_code", 0))
        text = PACKET_ERRORS.get(code, "the answer did not fit the request")
        return SdoError(f"{where}: {text} (SOEM packet error {code})")
    if isinstance(exc, pysoem.MailboxError):
        code = int(getattr(exc, "error_code", 0))
        text = MAILBOX_ERRORS.get(code) or str(getattr(exc, "desc", "")) or "mailbox error"
        return SdoError(f"{where}: mailbox error: {text} (detail code {code})")
    return SdoError(f"{where}: {exc}")


def sdo_upload(master: Any, position: int, index: int, subindex: int, size: int = 256,
               complete_access: bool = False) -> bytes:
    """SDO upload with errors mapped to `SdoAbortError` / `SdoTimeoutError` / `SdoError`."""
    pysoem = _import_pysoem()
    slaves = master.slaves
    if not 0 <= position < len(slaves):
        raise ConfigurationError(f"no slave at position {position} ({len(slaves)} slaves)")
    try:
        return bytes(slaves[position].sdo_read(index, subindex, size, complete_access, release_gil=True))
    except (pysoem.SdoError, pysoem.WkcError, pysoem.MailboxError, pysoem.PacketError) as exc:
        raise _map_sdo_error(exc, position, index, subindex, master) from exc


def sdo_download(master: Any, position: int, index: int, subindex: int, data: bytes,
                 complete_access: bool = False) -> None:
    """SDO download with errors mapped as in `sdo_upload`."""
    pysoem = _import_pysoem()
    slaves = master.slaves
    if not 0 <= position < len(slaves):
        raise ConfigurationError(f"no slave at position {position} ({len(slaves)} slaves)")
    try:
        slaves[position].sdo_write(index, subindex, bytes(data), complete_access, release_gil=True)
    except (pysoem.SdoError, pysoem.WkcError, pysoem.MailboxError, pysoem.PacketError) as exc:
        raise _map_sdo_error(exc, position, index, subindex, master) from exc


def write_mapping(master: Any, position: int, mapping: PdoMapping) -> None:
    """Write `mapping` into the drive at `position` (must be in PRE-OP), CiA 301 order:
    assignment off, mapping off, entries, mapping count, assignment, assignment count."""

    def w(index: int, sub: int, fmt: str, value: int) -> None:
        sdo_download(master, position, index, sub, struct.pack(fmt, value))

    for assign, pdo, entries in ((0x1C12, mapping.rx_pdo, mapping.rx), (0x1C13, mapping.tx_pdo, mapping.tx)):
        if mapping.complete_access:
            sdo_download(master, position, assign, 0, struct.pack("<Bx", 0), complete_access=True)
            sdo_download(master, position, pdo, 0,
                         struct.pack(f"<Bx{len(entries)}I", len(entries), *(e.value for e in entries)),
                         complete_access=True)
            sdo_download(master, position, assign, 0, struct.pack("<BxH", 1, pdo), complete_access=True)
            continue
        w(assign, 0, "<B", 0)
        w(pdo, 0, "<B", 0)
        for k, e in enumerate(entries, start=1):
            w(pdo, k, "<I", e.value)
        w(pdo, 0, "<B", len(entries))
        w(assign, 1, "<H", pdo)
        w(assign, 0, "<B", 1)
    if mapping.dc_sync_mode:
        w(0x1C32, 1, "<H", 2)


def read_mapping(master: Any, position: int) -> dict[str, list[tuple[int, list[int]]]]:
    """The slave's PDO assignment and mapping: {"rx": [(pdo, [entry values])], "tx": [...]}."""
    out: dict[str, list[tuple[int, list[int]]]] = {"rx": [], "tx": []}
    for key, assign in (("rx", 0x1C12), ("tx", 0x1C13)):
        n = sdo_upload(master, position, assign, 0)[0]
        for k in range(1, n + 1):
            pdo = struct.unpack("<H", sdo_upload(master, position, assign, k)[:2])[0]
            m = sdo_upload(master, position, pdo, 0)[0]
            entries = [struct.unpack("<I", sdo_upload(master, position, pdo, j)[:4])[0]
                       for j in range(1, m + 1)]
            out[key].append((pdo, entries))
    return out


def slave_infos(master: Any) -> tuple[SlaveInfo, ...]:
    """Identity and AL state of every slave (reads the states first)."""
    master.read_state()
    infos = []
    for i, s in enumerate(master.slaves):
        infos.append(SlaveInfo(position=i, name=str(s.name), vendor_id=int(s.man), product_code=int(s.id),
                               revision=int(s.rev), state=AL_STATE_NAMES.get(int(s.state) & 0x0F, ""),
                               al_status_code=int(s.al_status)))
    return tuple(infos)


def state_report(master: Any, wanted: int) -> tuple[str, int, int]:
    """(text naming every slave not in `wanted`, first such position, its AL status code)."""
    master.read_state()
    parts = []
    first_pos, first_code = -1, 0
    for i, s in enumerate(master.slaves):
        st = int(s.state)
        if st & 0x0F != wanted or st & 0x10:
            code = int(s.al_status)
            parts.append(f"slave {i} ({s.name}) in {al_state_name(st)}, AL status code 0x{code:04X} "
                         f"{al_status_text(code)}")
            if first_pos < 0:
                first_pos, first_code = i, code
    return "; ".join(parts), first_pos, first_code


class SoemBus(Bus):
    """EtherCAT bus on pysoem. Options (keyword arguments, also via `make_bus("soem", ...)`):

    adapter: network interface name (required).
    mappings: (vendor id, product code) -> `PdoMapping`, over `DRIVE_MAPPINGS`.
    default_mapping: mapping for drive models not listed (`CSP_MAPPING`).
    dc: use distributed clocks (SYNC0 = cycle time on every slave).
    safeop_timeout_s / op_timeout_s / init_timeout_s: AL state change timeouts.
    receive_timeout_us: how long `exchange()` waits for the frame (SOEM's EC_TIMEOUTRET).
    """

    kind = "soem"

    def __init__(self, drives: Sequence[DriveSpec], cycle_time_s: float = 0.001, adapter: str = "",
                 mappings: Mapping[tuple[int, int], PdoMapping] | None = None,
                 default_mapping: PdoMapping = CSP_MAPPING, dc: bool = True,
                 safeop_timeout_s: float = 2.0, op_timeout_s: float = 3.0, init_timeout_s: float = 2.0,
                 receive_timeout_us: int = 2000, **_ignored: object) -> None:
        super().__init__(drives, cycle_time_s)
        self.adapter = adapter
        self.mappings: dict[tuple[int, int], PdoMapping] = {**DRIVE_MAPPINGS, **(mappings or {})}
        self.default_mapping = default_mapping
        self.dc = dc
        self.safeop_timeout_s = safeop_timeout_s
        self.op_timeout_s = op_timeout_s
        self.init_timeout_s = init_timeout_s
        self.receive_timeout_us = int(receive_timeout_us)
        self.master: Any = None
        self.n_slaves = 0
        self.warnings: list[str] = []       # SOEM error list entries judged harmless
        self.slave_mappings: dict[int, PdoMapping] = {}
        self._expected_wkc = 0
        self.wkc_errors = 0                 # cycles whose working counter was not the expected one
        self._io: list[DriveIo] = []
        self._dc_active = False
        self._io_ready = False              # True between a finished open() and close()

    # ------------------------------------------------------------------ start-up
    @property
    def expected_wkc(self) -> int:
        return self._expected_wkc

    def mapping_for(self, vendor_id: int, product_code: int) -> PdoMapping:
        return self.mappings.get((vendor_id, product_code), self.default_mapping)

    def _open(self) -> None:
        pysoem = _import_pysoem()
        self.master = open_master(self.adapter)
        try:
            self._configure(pysoem)
        except BaseException:
            self._shutdown()
            raise

    def _configure(self, pysoem: Any) -> None:
        master = self.master
        self.n_slaves = n = config_init(master, self.adapter)
        for d in self.drives:
            if d.position >= n:
                raise ConfigurationError(f"drive {d.axis_name} is configured at slave position {d.position}, "
                                         f"but only {n} slave(s) answered on {self.adapter!r}")
        # identity check (0 in the configuration = do not check that field)
        for d in self.drives:
            s = master.slaves[d.position]
            found = (int(s.man), int(s.id))
            if (d.vendor_id and d.vendor_id != found[0]) or (d.product_code and d.product_code != found[1]):
                raise SlaveIdentityError(d.position, (d.vendor_id, d.product_code), found)
        # PDO mapping in the PRE-OP -> SAFE-OP hook of each drive
        hook_errors: list[EtherCATError] = []
        for d in self.drives:
            s = master.slaves[d.position]
            mapping = self.mapping_for(int(s.man), int(s.id))
            self.slave_mappings[d.position] = mapping
            s.setup_func = self._make_hook(d.position, mapping, hook_errors)
        try:
            master.config_map()
        except pysoem.ConfigMapError as exc:
            self._judge_config_map_errors(list(getattr(exc, "error_list", []) or []))
        if hook_errors:
            raise hook_errors[0]
        self._build_io()
        # distributed clocks: SYNC0 = Ts on every slave
        if self.dc:
            if not master.config_dc():
                self.warnings.append("no slave supports distributed clocks; running without SYNC0")
            else:
                cycle_ns = int(round(self.cycle_time_s * 1e9))
                for s in master.slaves:
                    s.dc_sync(True, cycle_ns)
                self._dc_active = True
        self._wait_state(AL_SAFEOP, self.safeop_timeout_s, "SAFE-OP")
        # process data in SAFE-OP: inputs become valid, outputs safe (controlword 0)
        self.controlword[:] = 0
        self.modes_of_operation[:] = 8
        for _ in range(3):
            self._cycle()
            time.sleep(self.cycle_time_s)
        np.copyto(self.target_position, self.position_actual)
        self._request_op()
        np.copyto(self.target_position, self.position_actual)
        self._io_ready = True

    def _make_hook(self, position: int, mapping: PdoMapping,
                   errors: list[EtherCATError]) -> Callable[[Any], int]:
        def hook(_slave: Any) -> int:
            try:
                write_mapping(self.master, position, mapping)
            except EtherCATError as exc:
                errors.append(exc)
            return 0

        return hook

    def _judge_config_map_errors(self, error_list: list[Any]) -> None:
        """SOEM's error list after config_map: SDO/mailbox errors of configured drives are
        fatal (their mapping failed); the rest (e.g. emergencies) become warnings."""
        drive_positions = {d.position for d in self.drives}
        fatal = []
        for err in error_list:
            pos = int(getattr(err, "slave_pos", 0)) - 1      # SOEM counts slaves from 1
            text = f"slave {pos}: {type(err).__name__} {getattr(err, 'desc', err)}"
            if pos in drive_positions and hasattr(err, "abort_code"):
                fatal.append(SdoAbortError(pos, int(getattr(err, "index", 0)),
                                           int(getattr(err, "subindex", 0)), int(err.abort_code),
                                           f"during PDO mapping: {err.desc}"))
            else:
                self.warnings.append(text)
        if fatal:
            raise fatal[0]

    def _build_io(self) -> None:
        master = self.master
        self._io = []
        outputs_slaves = inputs_slaves = 0
        for s in master.slaves:
            outputs_slaves += 1 if len(s.output) else 0
            inputs_slaves += 1 if len(s.input) else 0
        for i, d in enumerate(self.drives):
            s = master.slaves[d.position]
            mapping = self.slave_mappings[d.position]
            rx, tx = mapping.rx_struct, mapping.tx_struct
            if len(s.output) != rx.size or len(s.input) != tx.size:
                raise ConfigurationError(
                    f"slave {d.position} ({s.name}): process data is {len(s.output)} output / {len(s.input)} "
                    f"input bytes, the PDO mapping needs {rx.size} / {tx.size}"
                    + (f" (SOEM reported: {'; '.join(self.warnings)})" if self.warnings else ""))
            self._io.append(DriveIo(self, i, s, mapping))
        self._expected_wkc = 2 * outputs_slaves + inputs_slaves
        reported = int(getattr(master, "expected_wkc", self._expected_wkc))
        if reported and reported != self._expected_wkc:
            self.warnings.append(f"SOEM expects working counter {reported}, computed {self._expected_wkc}")
            self._expected_wkc = reported

    def _wait_state(self, state: int, timeout_s: float, name: str) -> None:
        master = self.master
        deadline = time.monotonic() + timeout_s
        while True:
            if int(master.state_check(state, 50_000)) == state:
                master.read_state()
                if all(int(s.state) == state for s in master.slaves):
                    return
            if time.monotonic() > deadline:
                text, pos, code = state_report(master, state)
                raise AlStateTimeoutError(f"{name} not reached within {timeout_s:.1f} s: {text}", pos, code)

    def _request_op(self) -> None:
        master = self.master
        master.state = AL_OP
        master.write_state()
        deadline = time.monotonic() + self.op_timeout_s
        next_check = 0.0
        while True:
            t0 = time.monotonic()
            self._cycle()
            if t0 >= next_check:
                next_check = t0 + 0.01
                lowest = int(master.read_state())
                states = [int(s.state) for s in master.slaves]
                if lowest == AL_OP and all(st == AL_OP for st in states):
                    return
                if any(st & 0x10 for st in states):
                    text, pos, code = state_report(master, AL_OP)
                    raise AlStateError(f"OP refused: {text}", pos, code)
            if t0 > deadline:
                text, pos, code = state_report(master, AL_OP)
                raise AlStateTimeoutError(f"OP not reached within {self.op_timeout_s:.1f} s: {text}",
                                          pos, code)
            time.sleep(max(0.0, self.cycle_time_s - (time.monotonic() - t0)))

    # ------------------------------------------------------------------ cyclic
    def _exchange(self) -> int:
        if self._io_ready:
            return self._cycle()
        self._check_open()
        return self._cycle()

    def _cycle(self) -> int:
        master = self.master
        for io in self._io:
            io.write()
        master.send_processdata()
        wkc = int(master.receive_processdata(self.receive_timeout_us))
        if wkc == self._expected_wkc:
            for io in self._io:
                io.read()
        else:
            self.wkc_errors += 1            # inputs keep their last good values
        return wkc

    # ------------------------------------------------------------------ shutdown
    def _close(self) -> None:
        self._shutdown()

    def _shutdown(self) -> None:
        master = self.master
        if master is None:
            return
        self._io_ready = False
        try:
            if self._io:                    # drives: disable voltage before leaving OP
                self.controlword[:] = 0
                for _ in range(3):
                    self._cycle()
            if self._dc_active:
                for s in master.slaves:
                    s.dc_sync(False, 0)
                self._dc_active = False
            master.state = AL_INIT
            master.write_state()
            master.state_check(AL_INIT, int(self.init_timeout_s * 1e6))
        except Exception as exc:  # best effort: the adapter is released below in any case
            self.warnings.append(f"shutdown: {exc}")
        finally:
            self.master = None
            self._io = []
            master.close()

    # ------------------------------------------------------------------ acyclic
    def _slaves(self) -> tuple[SlaveInfo, ...]:
        return slave_infos(self.master)

    def _sdo_upload(self, position: int, index: int, subindex: int) -> bytes:
        return sdo_upload(self.master, position, index, subindex)

    def _sdo_download(self, position: int, index: int, subindex: int, data: bytes) -> None:
        sdo_download(self.master, position, index, subindex, data)

    def digital_outputs_mapped(self, index: int) -> bool:
        mapping = self.slave_mappings.get(self.drives[index].position)
        return mapping is not None and any(e.index == 0x60FE for e in mapping.rx)

    def lost_slaves(self) -> tuple[int, ...]:
        """Slaves that no longer answer (AL state unreadable), found by one state read."""
        if self.master is None:
            return ()
        self.master.read_state()
        return tuple(i for i, s in enumerate(self.master.slaves) if int(s.state) == 0)

    def recover_slaves(self, timeout_us: int = 50_000) -> tuple[int, ...]:
        """Bring slaves that came back (after a loss or a power cycle) to OP again, as
        SOEM's `ecatcheck` does: find them at their position, check their identity, write
        their sync managers, run the PDO mapping hook, restart SYNC0, request OP.
        Acyclic (tens of ms): call it from the thread that owns the bus between cycles
        while the others keep running. Returns the positions that were re-configured."""
        self._check_open()
        master = self.master
        master.read_state()
        recovered = []
        for i, s in enumerate(master.slaves):
            if int(s.state) == AL_OP:
                continue
            if int(s.state) == 0 and s.recover(timeout_us) <= 0:
                continue                       # still gone
            if int(s.reconfig(timeout_us)) not in (AL_SAFEOP, AL_SAFEOP | 0x10):
                continue
            if self._dc_active:
                s.dc_sync(True, int(round(self.cycle_time_s * 1e9)))
            s.state = AL_OP
            s.write_state()
            recovered.append(i)
        return tuple(recovered)

    def al_states(self) -> tuple[tuple[str, int], ...]:
        """(AL state name, AL status code) per slave, read now."""
        self._check_open()
        return tuple((s.state, s.al_status_code) for s in slave_infos(self.master))
