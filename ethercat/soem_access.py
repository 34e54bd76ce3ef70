"""pysoem beneath the bus: opening the adapter, enumerating the slaves, SDO access with errors
that name the slave and the object, PDO mapping by SDO (0x1C12/0x1C13 assignment, 0x16xx/0x1Axx
entries, read back), AL states and their status texts. ``SoemBus`` (``ethercat.soem_bus``)
and ``cnc-ethercat`` build on these."""

from __future__ import annotations

import os
import struct
from collections.abc import Sequence
from typing import Any

from .bus import SlaveInfo
from .errors import (
    AdapterError,
    ConfigurationError,
    EtherCATError,
    EtherCATTimeoutError,
    SdoAbortError,
    SdoError,
    SdoTimeoutError,
)
from .pdo import PdoMapping

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


def import_pysoem() -> Any:
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
    pysoem = import_pysoem()
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
    pysoem = import_pysoem()
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
    pysoem = import_pysoem()
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
    pysoem = import_pysoem()
    slaves = master.slaves
    if not 0 <= position < len(slaves):
        raise ConfigurationError(f"no slave at position {position} ({len(slaves)} slaves)")
    try:
        slaves[position].sdo_write(index, subindex, bytes(data), complete_access, release_gil=True)
    except (pysoem.SdoError, pysoem.WkcError, pysoem.MailboxError, pysoem.PacketError) as exc:
        raise _map_sdo_error(exc, position, index, subindex, master) from exc


def write_assignment(master: Any, position: int, assign: int, pdos: Sequence[tuple[int, Sequence[int]]],
                     complete_access: bool = False) -> None:
    """Assign `pdos` (PDO index and its entry values) to the sync manager of `assign` (0x1C12
    or 0x1C13), in the order CoE requires (ETG.1000.6, CiA 301): assignment off, for each PDO
    mapping off, entries, entry count, then the PDO indices and the assignment count."""

    def w(index: int, sub: int, fmt: str, value: int) -> None:
        sdo_download(master, position, index, sub, struct.pack(fmt, value))

    if complete_access:
        sdo_download(master, position, assign, 0, struct.pack("<Bx", 0), complete_access=True)
        for pdo, entries in pdos:
            sdo_download(master, position, pdo, 0, struct.pack(f"<Bx{len(entries)}I", len(entries), *entries),
                         complete_access=True)
        sdo_download(master, position, assign, 0,
                     struct.pack(f"<Bx{len(pdos)}H", len(pdos), *(p for p, _ in pdos)), complete_access=True)
        return
    w(assign, 0, "<B", 0)
    for pdo, entries in pdos:
        w(pdo, 0, "<B", 0)
        for k, value in enumerate(entries, start=1):
            w(pdo, k, "<I", value)
        w(pdo, 0, "<B", len(entries))
    for k, (pdo, _) in enumerate(pdos, start=1):
        w(assign, k, "<H", pdo)
    w(assign, 0, "<B", len(pdos))


def write_mapping(master: Any, position: int, mapping: PdoMapping,
                  complete_access: bool | None = None) -> None:
    """Write `mapping` into the drive at `position` (must be in PRE-OP), RxPDO then TxPDO."""
    ca = mapping.complete_access if complete_access is None else complete_access
    write_assignment(master, position, 0x1C12, [(mapping.rx_pdo, [e.value for e in mapping.rx])], ca)
    write_assignment(master, position, 0x1C13, [(mapping.tx_pdo, [e.value for e in mapping.tx])], ca)
    if mapping.dc_sync_mode:
        sdo_download(master, position, 0x1C32, 1, struct.pack("<H", 2))


Found = dict[str, list[tuple[int, list[int]]]]


def read_mapping(master: Any, position: int) -> Found:
    """The slave's PDO assignment and mapping: {"rx": [(pdo, [entry values])], "tx": [...]}."""
    out: Found = {"rx": [], "tx": []}
    for key, assign in (("rx", 0x1C12), ("tx", 0x1C13)):
        n = sdo_upload(master, position, assign, 0)[0]
        for k in range(1, n + 1):
            pdo = struct.unpack("<H", sdo_upload(master, position, assign, k)[:2])[0]
            m = sdo_upload(master, position, pdo, 0)[0]
            entries = [struct.unpack("<I", sdo_upload(master, position, pdo, j)[:4])[0]
                       for j in range(1, m + 1)]
            out[key].append((pdo, entries))
    return out


def mapping_from_found(found: Found, velocity: bool = False) -> PdoMapping:
    """The mapping a drive has (every assigned PDO in order) as a `PdoMapping` (of a spindle's
    drive in a velocity mode when ``velocity``); raises `ConfigurationError` naming what is
    missing or unusable."""
    rx = [v for _, entries in found["rx"] for v in entries]
    tx = [v for _, entries in found["tx"] for v in entries]
    rx_pdo = found["rx"][0][0] if found["rx"] else 0x1600
    tx_pdo = found["tx"][0][0] if found["tx"] else 0x1A00
    return PdoMapping.from_values(rx, tx, rx_pdo, tx_pdo, velocity=velocity)


def found_matches(found: Found, mapping: PdoMapping) -> bool:
    """Whether the drive already has exactly `mapping` (one PDO each way, same entries)."""
    return (found["rx"] == [(mapping.rx_pdo, [e.value for e in mapping.rx])]
            and found["tx"] == [(mapping.tx_pdo, [e.value for e in mapping.tx])])


def has_object(master: Any, position: int, index: int, subindex: int) -> bool:
    """Whether the drive has the object (an SDO upload not aborted as 'does not exist')."""
    try:
        sdo_upload(master, position, index, subindex)
    except SdoAbortError as exc:
        return exc.abort_code not in (SdoAbortError.OBJECT_DOES_NOT_EXIST,
                                      SdoAbortError.SUBINDEX_DOES_NOT_EXIST)
    return True


def complete_access_fault(master: Any, position: int) -> str:
    """Why complete access cannot be used with this slave ('' when it works): its answer to a
    complete-access upload of the RxPDO assignment 0x1C12 must be sub-index 0 as 8 bits, one
    pad byte and the 16-bit entries (ETG.1000.6), the same values as read one by one."""
    pysoem = import_pysoem()
    n = sdo_upload(master, position, 0x1C12, 0)[0]
    entries = [struct.unpack("<H", sdo_upload(master, position, 0x1C12, k)[:2])[0] for k in range(1, n + 1)]
    want = struct.pack(f"<Bx{n}H", n, *entries)
    try:
        got = bytes(master.slaves[position].sdo_read(0x1C12, 0, 256, True, release_gil=True))
    except (pysoem.SdoError, pysoem.WkcError, pysoem.MailboxError, pysoem.PacketError) as exc:
        return (f"a complete-access upload of 0x1C12 failed "
                f"({_map_sdo_error(exc, position, 0x1C12, 0, master)})")
    finally:
        _resync_mailbox(master, position)
    if got[:len(want)] != want:
        return (f"its complete-access answer for 0x1C12 is {got.hex(' ')}, expected {want.hex(' ')} "
                "(sub-index 0, one pad byte, the entries)")
    return ""


def _resync_mailbox(master: Any, position: int) -> None:
    """After a failed or odd mailbox exchange, read the device type until an answer matches,
    so that a late answer is not taken for the next request's."""
    for _ in range(3):
        try:
            sdo_upload(master, position, 0x1000, 0)
            return
        except SdoError:
            continue


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
            parts.append(f"{slave_label(master, i)} in {al_state_name(st)}, AL status code 0x{code:04X} "
                         f"{al_status_text(code)}")
            if first_pos < 0:
                first_pos, first_code = i, code
    return "; ".join(parts), first_pos, first_code
