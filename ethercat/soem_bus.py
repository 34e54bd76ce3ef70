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

import contextlib
import struct
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from .bus import Bus, DriveSpec, SlaveInfo, SpindleDriveSpec
from .drive_setup import DriveSetup, MappingPolicy, StartupStep
from .errors import (
    AlStateError,
    AlStateTimeoutError,
    ConfigurationError,
    EtherCATError,
    SdoAbortError,
    SlaveIdentityError,
)
from .pdo import (
    CSP_MAPPING,
    DRIVE_MAPPINGS,
    OPTIONAL_OBJECTS,
    VELOCITY_MAPPING,
    DriveIo,
    PdoMapping,
)
from .soem_access import (
    AL_INIT,
    AL_OP,
    AL_PREOP,
    AL_SAFEOP,
    complete_access_fault,
    config_init,
    found_matches,
    has_object,
    import_pysoem,
    mapping_from_found,
    open_master,
    read_mapping,
    sdo_download,
    sdo_upload,
    slave_infos,
    slave_label,
    state_report,
    write_assignment,
    write_mapping,
)
from .terminals import TerminalIo, TerminalSpec

DEFAULT_SETUP = DriveSetup()

class SoemBus(Bus):
    """EtherCAT bus on pysoem. Options (keyword arguments, also via `make_bus("soem", ...)`):

    adapter: network interface name (required).
    mappings: (vendor id, product code) -> `PdoMapping`, over `DRIVE_MAPPINGS`.
    default_mapping: mapping for drive models not listed (`CSP_MAPPING`).
    dc: use distributed clocks (SYNC0 = cycle time on every slave).
    safeop_timeout_s / op_timeout_s / init_timeout_s: AL state change timeouts.
    receive_timeout_us: how long `exchange()` waits for the frame (SOEM's EC_TIMEOUTRET).
    setups: slave position -> `DriveSetup` (mapping policy, start-up SDOs, DC settings).
    mode_timeout_s: how long a drive may take to show CSP in 0x6061 after OP.
    """

    kind = "soem"

    def __init__(self, drives: Sequence[DriveSpec], cycle_time_s: float = 0.001, adapter: str = "",
                 mappings: Mapping[tuple[int, int], PdoMapping] | None = None,
                 default_mapping: PdoMapping = CSP_MAPPING, dc: bool = True,
                 safeop_timeout_s: float = 2.0, op_timeout_s: float = 3.0, init_timeout_s: float = 2.0,
                 receive_timeout_us: int = 2000,
                 setups: Mapping[int, DriveSetup] | Sequence[tuple[int, DriveSetup]] | None = None,
                 mode_timeout_s: float = 1.0, terminals: Sequence[TerminalSpec] = (),
                 spindles: Sequence[SpindleDriveSpec] = (), **_ignored: object) -> None:
        super().__init__(drives, cycle_time_s, terminals, spindles)
        #: every CiA 402 drive's slave position (the axes', then the spindle's) and a spindle's spec
        self._drive_positions = [d.position for d in self.drives] + [s.position for s in self.spindles]
        self._spindle_at = {s.position: s for s in self.spindles}
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
        self.slave_mappings: dict[int, PdoMapping] = {}      # by slave position: what runs
        self.written_mappings: dict[int, PdoMapping] = {}    # what this master wrote
        self.setups: dict[int, DriveSetup] = dict(setups or {})
        self.mode_timeout_s = mode_timeout_s
        self.complete_access: dict[int, bool] = {}
        self.step: StartupStep | None = None
        self._expected_wkc = 0
        self.wkc_errors = 0                 # cycles whose working counter was not the expected one
        self._io: list[DriveIo] = []
        self._terminal_io: list[TerminalIo] = []
        self._dc_active = False
        self._io_ready = False              # True between a finished open() and close()

    # ------------------------------------------------------------------ start-up
    @property
    def expected_wkc(self) -> int:
        return self._expected_wkc

    def mapping_for(self, vendor_id: int, product_code: int) -> PdoMapping:
        return self.mappings.get((vendor_id, product_code), self.default_mapping)

    def setup_for(self, position: int) -> DriveSetup:
        return self.setups.get(position, DEFAULT_SETUP)

    @contextlib.contextmanager
    def _step(self, step: StartupStep) -> Iterator[None]:
        """Name the start-up step in any error raised inside it (once, innermost wins)."""
        self.step = step
        try:
            yield
        except EtherCATError as exc:
            if exc.step is None:
                exc.step = step
                if exc.args:
                    exc.args = (f"{step.value}: {exc.args[0]}", *exc.args[1:])
            raise

    def _open(self) -> None:
        pysoem = import_pysoem()
        with self._step(StartupStep.ADAPTER):
            self.master = open_master(self.adapter)
        try:
            self._configure(pysoem)
        except BaseException:
            self._shutdown()
            raise

    def _configure(self, pysoem: Any) -> None:
        master = self.master
        with self._step(StartupStep.SCAN):
            self.n_slaves = n = config_init(master, self.adapter)
            named = [(f"drive {d.axis_name}", d.position) for d in self.drives]
            for what, position in named + [("the spindle's drive", s.position) for s in self.spindles]:
                if position >= n:
                    raise ConfigurationError(f"{what} is configured at slave position {position}, but only "
                                             f"{n} slave(s) answered on {self.adapter!r}")
            for t in self.terminals:
                if t.position >= n:
                    raise ConfigurationError(f"terminal {t.label} is configured at slave position "
                                             f"{t.position}, but only {n} slave(s) answered on "
                                             f"{self.adapter!r}")
            self._wait_state(AL_PREOP, self.safeop_timeout_s, "PRE-OP")
        # identity check (0 in the configuration = do not check that field)
        with self._step(StartupStep.IDENTITY):
            self._check_identities()
        with self._step(StartupStep.MAILBOX):
            for position in self._drive_positions:
                self._check_complete_access(position)
        with self._step(StartupStep.MAPPING):
            for position in self._drive_positions:
                self.slave_mappings[position] = self._choose_mapping(position)
        with self._step(StartupStep.STARTUP_SDO):
            for position in self._drive_positions:
                self._startup_sdos(position)
                self._write_watchdog(position)
        with self._step(StartupStep.PROCESS_DATA):
            try:
                master.config_map()
            except pysoem.ConfigMapError as exc:
                self._judge_config_map_errors(list(getattr(exc, "error_list", []) or []))
            self._build_io()
            # a slave that lost its settings (power cycle) gets them again when it is recovered
            for position in self._drive_positions:
                master.slaves[position].setup_func = self._make_hook(position)
        # distributed clocks: SYNC0 = Ts on every slave (unless a drive's setup turns it off)
        with self._step(StartupStep.DC):
            if self.dc:
                if not master.config_dc():
                    self.warnings.append("no slave supports distributed clocks; running without SYNC0")
                else:
                    cycle_ns = int(round(self.cycle_time_s * 1e9))
                    for pos, s in enumerate(master.slaves):
                        setup = self.setup_for(pos)
                        if setup.dc:
                            s.dc_sync(True, cycle_ns, setup.sync0_shift_ns)
                    self._dc_active = True
        with self._step(StartupStep.SAFEOP):
            self._wait_state(AL_SAFEOP, self.safeop_timeout_s, "SAFE-OP")
            # process data in SAFE-OP: inputs become valid, outputs safe (controlword 0)
            self.controlword[:] = 0
            self.spindle_controlword[:] = 0
            self.modes_of_operation[:] = 8
            for _ in range(3):
                self._cycle()
                time.sleep(self.cycle_time_s)
            # the target follows the actual position from the first frame on: a drive that
            # takes the target when it is enabled must not see 0 (or a stale value)
            np.copyto(self.target_position, self.position_actual)
        with self._step(StartupStep.OP):
            self._request_op()
        np.copyto(self.target_position, self.position_actual)
        with self._step(StartupStep.MODE):
            self._wait_csp_mode()
            self._wait_spindle_modes()
        self._io_ready = True

    def _check_identities(self) -> None:
        """Every configured drive is what its table says (0: not checked) and every terminal is
        of its type, by vendor id and product code."""
        master = self.master
        for d in self.drives:
            s = master.slaves[d.position]
            found = (int(s.man), int(s.id))
            if ((d.vendor_id and d.vendor_id != found[0])
                    or (d.product_code and d.product_code != found[1])):
                raise SlaveIdentityError(d.position, (d.vendor_id, d.product_code), found)
        for sp in self.spindles:
            s = master.slaves[sp.position]
            found = (int(s.man), int(s.id))
            if ((sp.vendor_id and sp.vendor_id != found[0])
                    or (sp.product_code and sp.product_code != found[1])):
                raise SlaveIdentityError(sp.position, (sp.vendor_id, sp.product_code), found)
        for t in self.terminals:
            s = master.slaves[t.position]
            found = (int(s.man), int(s.id))
            if found != (t.type.vendor_id, t.type.product_code):
                raise SlaveIdentityError(t.position, (t.type.vendor_id, t.type.product_code), found)

    def _check_complete_access(self, position: int) -> None:
        """SOEM reads a drive's PDO mapping with complete access when the drive's SII says it
        can; a drive that says so but answers wrongly derails the whole mapping. Tried once
        here (unless the drive's setup decides), and turned off for SOEM when it fails."""
        setup = self.setup_for(position)
        slave = self.master.slaves[position]
        if setup.complete_access is None:
            why = complete_access_fault(self.master, position)
            self.complete_access[position] = not why
            if why:
                self.notes.append(f"{slave_label(self.master, position)}: SDO complete access not used: "
                                  f"{why}")
        else:
            self.complete_access[position] = setup.complete_access
        if not self.complete_access[position] and hasattr(slave, "_disable_complete_access"):
            slave._disable_complete_access()

    def _choose_mapping(self, position: int) -> PdoMapping:
        """The mapping this drive runs with (see `MappingPolicy`); notes say what was done."""
        master = self.master
        setup = self.setup_for(position)
        label = slave_label(master, position)
        found = read_mapping(master, position)
        velocity = position in self._spindle_at
        try:
            own: PdoMapping | None = mapping_from_found(found, velocity)
            own_problem = ""
        except ConfigurationError as exc:
            own, own_problem = None, str(exc)
        if setup.policy is MappingPolicy.KEEP:
            if own is None:
                raise ConfigurationError(f"{label}: the drive's own PDO mapping cannot be used: "
                                         f"{own_problem}")
            self.notes.append(f"{label}: using the drive's own PDO mapping (kept by configuration)")
            return own
        s = master.slaves[position]
        wanted = setup.mapping or (VELOCITY_MAPPING if velocity
                                   else self.mapping_for(int(s.man), int(s.id)))
        if setup.policy is MappingPolicy.ADAPT:
            optional = {(e.index, e.subindex) for e in wanted.rx + wanted.tx
                        if not e.is_padding and e.index not in wanted.mandatory}
            missing = {index for index, sub in sorted(optional)
                       if not has_object(master, position, index, sub)}
            if missing:
                wanted = wanted.without(missing)
                for index in sorted(missing):
                    self.notes.append(f"{label}: no object 0x{index:04X}: "
                                      f"{OPTIONAL_OBJECTS.get(index, 'not mapped')}")
        if found_matches(found, wanted):
            return replace(wanted, complete_access=self.complete_access.get(position, False))
        ca = wanted.complete_access and self.complete_access.get(position, False)
        try:
            write_mapping(master, position, wanted, complete_access=ca)
            self.written_mappings[position] = wanted
            return wanted
        except EtherCATError as exc:
            refused = exc
        # restore what the drive had, so a half-written mapping is not left behind
        try:
            if read_mapping(master, position) != found:
                write_assignment(master, position, 0x1C12, found["rx"])
                write_assignment(master, position, 0x1C13, found["tx"])
            restored = read_mapping(master, position) == found
        except EtherCATError:
            restored = False
        if setup.policy is MappingPolicy.WRITE or own is None:
            if own is None:
                refused.args = (f"{refused.args[0]}; the drive's own mapping cannot be used either: "
                                f"{own_problem}",)
            raise refused
        if not restored:
            raise ConfigurationError(f"{label}: the drive refused the PDO mapping ({refused}) and its own "
                                     "mapping could not be restored")
        self.notes.append(f"{label}: the drive refused the PDO mapping ({refused}); using its own: "
                          + ", ".join(e.text() for e in own.rx + own.tx))
        return own

    def _startup_sdos(self, position: int) -> None:
        """The drive's configured start-up SDOs, then what the mapping leaves out: the mode
        (0x6060 = 8 when it is not in the process data) and the SM2 sync mode (0x1C32:1)."""
        setup = self.setup_for(position)
        for sdo in setup.startup_sdos:
            sdo_download(self.master, position, sdo.index, sdo.subindex, sdo.data)
        mapping = self.slave_mappings[position]
        spindle = self._spindle_at.get(position)
        if 0x6060 not in mapping.objects:
            sdo_download(self.master, position, 0x6060, 0, struct.pack("<b", spindle.mode if spindle else 8))
        if setup.sync_mode is not None:
            sdo_download(self.master, position, 0x1C32, 1, struct.pack("<H", setup.sync_mode))

    def _write_watchdog(self, position: int) -> None:
        """The configured process data watchdog (0x0420, in units of the drive's divider at
        0x0400), read back: a drive that keeps its own time would fault on a shorter stall
        than the integrator set, or not fault when it should."""
        ms = self.setup_for(position).watchdog_ms
        if ms is None:
            return
        slave = self.master.slaves[position]
        label = slave_label(self.master, position)
        try:
            longest_ms = float(slave.get_max_watchdog_time())
            if ms > longest_ms:
                raise ConfigurationError(f"{label}: process data watchdog {ms:g} ms is longer than the "
                                         f"{longest_ms:g} ms its divider (0x0400) allows")
            slave.set_watchdog("processdata", ms)
            got_ms = float(slave.get_watchdog("processdata"))
        except ConfigurationError:
            raise
        except Exception as exc:                    # pysoem: a register access without an answer
            raise ConfigurationError(f"{label}: writing the process data watchdog (0x0420) failed: "
                                     f"{exc}") from exc
        if abs(got_ms - ms) > max(0.1, 0.01 * ms):
            raise ConfigurationError(f"{label}: the process data watchdog reads {got_ms:g} ms after "
                                     f"{ms:g} ms was written to 0x0420")

    def _wait_csp_mode(self) -> None:
        """Each drive must show cyclic synchronous position (0x6061 = 8). Some drives report it
        late: keep the process data running and look again until `mode_timeout_s` (in the
        process data every cycle, by SDO every 20 ms when the drive does not map 0x6061)."""
        deadline = time.monotonic() + self.mode_timeout_s
        pending = set(range(len(self.drives)))
        shown: dict[int, int | None] = dict.fromkeys(pending)
        next_sdo = 0.0
        while pending:
            t0 = time.monotonic()
            self._cycle()
            ask = t0 >= next_sdo
            if ask:
                next_sdo = t0 + 0.02
            for i in sorted(pending):
                position = self.drives[i].position
                if 0x6061 in self.slave_mappings[position].objects:
                    shown[i] = int(self.modes_display[i])
                elif ask:
                    try:
                        shown[i] = struct.unpack("<b", sdo_upload(self.master, position, 0x6061, 0)[:1])[0]
                    except SdoAbortError as exc:
                        if exc.abort_code != SdoAbortError.OBJECT_DOES_NOT_EXIST:
                            raise
                        self.notes.append(f"{slave_label(self.master, position)}: no mode display 0x6061; "
                                          "cyclic synchronous position assumed")
                        pending.discard(i)
                        continue
                if shown[i] == 8:
                    self.modes_display[i] = 8
                    pending.discard(i)
            if pending and t0 > deadline:
                i = min(pending)
                position = self.drives[i].position
                raise ConfigurationError(
                    f"{slave_label(self.master, position)} (axis {self.drives[i].axis_name}) shows mode "
                    f"{shown[i]} in 0x6061 after {self.mode_timeout_s:.1f} s, not 8 (cyclic synchronous "
                    "position): the drive may not support CSP, or needs a start-up SDO")
            time.sleep(max(0.0, self.cycle_time_s - (time.monotonic() - t0)))

    def _wait_spindle_modes(self) -> None:
        """A spindle's drive shows its velocity mode in 0x6061 (when mapped) within `mode_timeout_s`."""
        deadline = time.monotonic() + self.mode_timeout_s
        for k, sp in enumerate(self.spindles):
            if 0x6061 not in self.slave_mappings[sp.position].objects:
                continue
            while int(self.spindle_modes_display[k]) != sp.mode:
                if time.monotonic() > deadline:
                    raise ConfigurationError(
                        f"{slave_label(self.master, sp.position)} (the spindle) shows mode "
                        f"{int(self.spindle_modes_display[k])} in 0x6061 after {self.mode_timeout_s:.1f} s, "
                        f"not {sp.mode}: the drive may not support it, or needs a start-up SDO")
                self._cycle()
                time.sleep(self.cycle_time_s)

    def _make_hook(self, position: int) -> Callable[[Any], int]:
        """Run by SOEM when it re-configures a slave that came back: the mapping written at
        start-up and the start-up SDOs, again (errors end up in SOEM's list)."""
        def hook(_slave: Any) -> int:
            try:
                mapping = self.written_mappings.get(position)
                if mapping is not None:
                    ca = mapping.complete_access and self.complete_access.get(position, False)
                    write_mapping(self.master, position, mapping, complete_access=ca)
                self._startup_sdos(position)
                self._write_watchdog(position)
            except EtherCATError as exc:
                self.warnings.append(f"re-configuring {slave_label(self.master, position)}: {exc}")
            return 0

        return hook

    def _judge_config_map_errors(self, error_list: list[Any]) -> None:
        """SOEM's error list after config_map: SDO/mailbox errors of configured drives are
        fatal (their mapping failed); the rest (e.g. emergencies) become warnings."""
        drive_positions = set(self._drive_positions)
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
        for k, sp in enumerate(self.spindles):
            s = master.slaves[sp.position]
            mapping = self.slave_mappings[sp.position]
            if len(s.output) != mapping.rx_struct.size or len(s.input) != mapping.tx_struct.size:
                raise ConfigurationError(f"slave {sp.position} ({s.name}): process data is {len(s.output)} "
                                         f"output / {len(s.input)} input bytes, the spindle's PDO mapping "
                                         f"needs {mapping.rx_struct.size} / {mapping.tx_struct.size}")
            self._io.append(DriveIo(self, k, s, mapping))
        self._terminal_io = []
        for k, t in enumerate(self.terminals):
            s = master.slaves[t.position]
            if len(s.output) != t.type.rx_bytes or len(s.input) != t.type.tx_bytes:
                raise ConfigurationError(
                    f"slave {t.position} ({s.name}): process data is {len(s.output)} output / {len(s.input)} "
                    f"input bytes; a {t.type.name} has {t.type.rx_bytes} / {t.type.tx_bytes} in its default "
                    "PDO assignment")
            self._terminal_io.append(TerminalIo(self, k, s, t.type))
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
        for tio in self._terminal_io:
            tio.write()
        master.send_processdata()
        wkc = int(master.receive_processdata(self.receive_timeout_us))
        if wkc == self._expected_wkc:
            for io in self._io:
                io.read()
            for tio in self._terminal_io:
                tio.read()
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
            self._terminal_io = []
            master.close()

    # ------------------------------------------------------------------ acyclic
    def _slaves(self) -> tuple[SlaveInfo, ...]:
        return slave_infos(self.master)

    def _sdo_upload(self, position: int, index: int, subindex: int) -> bytes:
        return sdo_upload(self.master, position, index, subindex)

    def _sdo_download(self, position: int, index: int, subindex: int, data: bytes) -> None:
        sdo_download(self.master, position, index, subindex, data)

    def maps_object(self, index: int, obj: int) -> bool:
        mapping = self.slave_mappings.get(self.drives[index].position)
        return mapping is not None and obj in mapping.objects

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
