"""The one bus interface (python-can style) and the backend registry.

A `Bus` owns the process data of N CiA 402 drives as preallocated NumPy arrays, one
element per drive (index = position in `drives`, not necessarily the slave position):

    outputs (RxPDO, master -> drive)   controlword u16, target_position i32, modes_of_operation i8,
                                       digital_outputs u32 (0x60FE:1)
    inputs  (TxPDO, drive -> master)   statusword u16, position_actual i32, following_error i32,
                                       error_code u16, modes_display i8, digital_inputs u32 (0x60FD)

Terminals beside the drives (``terminals``: couplers, digital I/O, encoders; see
``ethercat.terminals``) have one word per terminal in each direction: ``terminal_inputs``,
``terminal_outputs``, and an encoder's ``terminal_counts`` / ``terminal_latches`` /
``terminal_set_counts``; index = position in ``terminals``.

Spindle drives (``spindles``: CiA 402 drives in a velocity mode, not axes) have their own
arrays: ``spindle_controlword``, ``spindle_target_velocity`` (0x60FF), ``spindle_modes``
(0x6060) out; ``spindle_statusword``, ``spindle_velocity_actual`` (0x606C),
``spindle_error_code``, ``spindle_modes_display`` (0x6061) in; index = position in
``spindles``.

The worker writes the output arrays in place, calls `exchange()` once per cycle (send
and receive one frame; returns the working counter, -1 when no frame came back) and
reads the input arrays in place. Inputs are only updated when the frame came back.

    with make_bus("sim", drives, cycle_time_s=0.001) as bus:
        bus.controlword[:] = 0x06
        wkc = bus.exchange()
        assert wkc == bus.expected_wkc

Backends implement the transport only (`_open`, `_close`, `_exchange`, `_sdo_upload`,
`_sdo_download`, and `_slaves`); the base class does state checks, the context manager,
harmless double close, typed SDO helpers. Optional features are methods with a default here
(as python-can's ``BusABC``): ``lost_slaves`` (none known), ``recover_slaves`` (nothing to
do), ``digital_outputs_mapped`` (yes), ``inject`` (refused: only a simulation can fake faults).
Backends are chosen by name (`make_bus`) and
imported lazily: "sim" -> `ethercat.sim_bus.SimBus`, "soem" -> `ethercat.soem_bus.SoemBus`.

SDO transfers are acyclic and may take milliseconds on a real bus: the worker never calls
them from the cycle (its acyclic helper runs them beside it).
"""

from __future__ import annotations

import abc
import importlib
import struct
from collections.abc import Sequence
from dataclasses import dataclass
from types import TracebackType
from typing import Any

import numpy as np

from .errors import BusFeatureError, BusStateError, ConfigurationError
from .terminals import TerminalSpec, check_terminals


@dataclass(frozen=True, slots=True)
class DriveSpec:
    """One CiA 402 drive of the machine (from `[[bus.drives]]` / the axis definitions).

    position: slave position on the bus (0-based, in wiring order).
    counts_per_unit: encoder counts per mm (linear) or per degree (rotary), > 0.
    direction: +1 or -1 (sign between axis units and drive counts).
    following_error_window: largest |reference - actual| allowed, in axis units (mm|deg).
    vendor_id / product_code: expected identity (0 = do not check).
    """

    position: int
    axis_name: str
    counts_per_unit: float = 10_000.0
    direction: int = 1
    following_error_window: float = 1.0
    vendor_id: int = 0
    product_code: int = 0

    def __post_init__(self) -> None:
        if self.position < 0:
            raise ConfigurationError(f"drive {self.axis_name}: position must be >= 0, got {self.position}")
        if not self.counts_per_unit > 0.0:
            raise ConfigurationError(
                f"drive {self.axis_name}: counts_per_unit must be > 0, got {self.counts_per_unit}")
        if self.direction not in (1, -1):
            raise ConfigurationError(
                f"drive {self.axis_name}: direction must be +1 or -1, got {self.direction}")
        if not self.following_error_window > 0.0:
            raise ConfigurationError(
                f"drive {self.axis_name}: following_error_window must be > 0, "
                f"got {self.following_error_window}")


@dataclass(frozen=True, slots=True)
class SpindleDriveSpec:
    """A CiA 402 drive that turns the spindle in a velocity mode (``[spindle] drive``).

    position: slave position on the bus.
    velocity_per_rpm: the drive's velocity units (0x60FF, 0x606C) per spindle rpm (counts/s
    of a 10,000-count encoder on the spindle: 10000 / 60).
    mode: 9 cyclic synchronous velocity (the master ramps the speed) or 3 profile velocity
    (the drive ramps it with its 0x6083 and 0x6084).
    vendor_id / product_code: expected identity (0 = do not check).
    """

    position: int
    velocity_per_rpm: float = 10_000.0 / 60.0
    mode: int = 9
    vendor_id: int = 0
    product_code: int = 0

    def __post_init__(self) -> None:
        if self.position < 0:
            raise ConfigurationError(f"spindle drive: position must be >= 0, got {self.position}")
        if not (self.velocity_per_rpm > 0.0 and self.velocity_per_rpm < 1e9):
            raise ConfigurationError(f"spindle drive: velocity_per_rpm must be > 0, "
                                     f"got {self.velocity_per_rpm}")
        if self.mode not in (3, 9):
            raise ConfigurationError(f"spindle drive: mode {self.mode}: 9 (cyclic synchronous velocity) or 3 "
                                     "(profile velocity)")


@dataclass(frozen=True, slots=True)
class SlaveInfo:
    """Identity and state of one slave as found on the bus."""

    position: int
    name: str
    vendor_id: int
    product_code: int
    revision: int = 0
    serial: int = 0
    state: str = ""        # AL state: "INIT", "PRE-OP", "SAFE-OP", "OP", "" if unknown
    al_status_code: int = 0


def check_drives(drives: Sequence[DriveSpec]) -> tuple[DriveSpec, ...]:
    """Validate a drive list: at least one drive, distinct positions and axis names."""
    drives = tuple(drives)
    if not drives:
        raise ConfigurationError("no drives configured")
    positions = [d.position for d in drives]
    if len(set(positions)) != len(positions):
        raise ConfigurationError(f"duplicate drive positions: {positions}")
    names = [d.axis_name for d in drives]
    if len(set(names)) != len(names):
        raise ConfigurationError(f"duplicate axis names: {names}")
    return drives


class Bus(abc.ABC):
    """Abstract EtherCAT bus with N CiA 402 drives in CSP. See the module docstring."""

    #: registry name of the backend ("sim", "soem")
    kind: str = ""

    def __init__(self, drives: Sequence[DriveSpec], cycle_time_s: float = 0.001,
                 terminals: Sequence[TerminalSpec] = (), spindles: Sequence[SpindleDriveSpec] = ()) -> None:
        self.drives = check_drives(drives)
        self.spindles = tuple(spindles)
        taken = [d.position for d in self.drives] + [s.position for s in self.spindles]
        if len(set(taken)) != len(taken):
            raise ConfigurationError(f"a spindle drive's position is another drive's: {taken}")
        self.terminals = check_terminals(terminals, taken)
        #: what the start-up adapted to (a drive's own mapping, objects it lacks), one line each
        self.notes: list[str] = []
        if not 0.000_1 <= cycle_time_s <= 0.1:
            raise ConfigurationError(f"cycle_time_s must be within [0.0001, 0.1] s, got {cycle_time_s}")
        self.cycle_time_s = float(cycle_time_s)
        n = len(self.drives)
        # outputs (RxPDO)
        self.controlword = np.zeros(n, dtype=np.uint16)
        self.target_position = np.zeros(n, dtype=np.int32)
        self.modes_of_operation = np.full(n, 8, dtype=np.int8)
        self.digital_outputs = np.zeros(n, dtype=np.uint32)
        self.touch_probe_function = np.zeros(n, dtype=np.uint16)
        # inputs (TxPDO)
        self.statusword = np.zeros(n, dtype=np.uint16)
        self.position_actual = np.zeros(n, dtype=np.int32)
        self.following_error = np.zeros(n, dtype=np.int32)
        self.error_code = np.zeros(n, dtype=np.uint16)
        self.modes_display = np.zeros(n, dtype=np.int8)
        self.digital_inputs = np.zeros(n, dtype=np.uint32)
        self.touch_probe_status = np.zeros(n, dtype=np.uint16)
        self.touch_probe_value = np.zeros(n, dtype=np.int32)
        # terminals
        m = len(self.terminals)
        self.terminal_inputs = np.zeros(m, dtype=np.uint32)
        self.terminal_outputs = np.zeros(m, dtype=np.uint64)      # (4 analog channels of 16 bits)
        self.terminal_counts = np.zeros(m, dtype=np.int32)
        self.terminal_latches = np.zeros(m, dtype=np.int32)
        self.terminal_set_counts = np.zeros(m, dtype=np.int32)
        # spindle drives (velocity modes): outputs, then inputs
        k = len(self.spindles)
        self.spindle_controlword = np.zeros(k, dtype=np.uint16)
        self.spindle_target_velocity = np.zeros(k, dtype=np.int32)
        self.spindle_modes = np.array([s.mode for s in self.spindles], dtype=np.int8)
        self.spindle_statusword = np.zeros(k, dtype=np.uint16)
        self.spindle_velocity_actual = np.zeros(k, dtype=np.int32)
        self.spindle_error_code = np.zeros(k, dtype=np.uint16)
        self.spindle_modes_display = np.zeros(k, dtype=np.int8)
        self._is_open = False

    # ------------------------------------------------------------------ life cycle
    @property
    def n_drives(self) -> int:
        return len(self.drives)

    @property
    def n_terminals(self) -> int:
        return len(self.terminals)

    @property
    def is_open(self) -> bool:
        return self._is_open

    def open(self) -> None:
        """Bring the bus to OP with process data running (idempotent).

        After `open()` the inputs hold the first received values and the outputs hold
        `target_position = position_actual`, controlword 0, mode CSP.
        """
        if self._is_open:
            return
        self._open()
        self._is_open = True

    def close(self) -> None:
        """Back to INIT and release the adapter. Closing twice is harmless."""
        if not self._is_open:
            return
        self._is_open = False
        self._close()

    def __enter__(self) -> Bus:
        self.open()
        return self

    def __exit__(self, exc_type: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        self.close()

    def __del__(self) -> None:  # pragma: no cover - best effort
        try:
            self.close()
        except Exception:
            pass

    def _check_open(self) -> None:
        if not self._is_open:
            raise BusStateError(f"{type(self).__name__} is not open")

    # ------------------------------------------------------------------ cyclic
    @property
    @abc.abstractmethod
    def expected_wkc(self) -> int:
        """Working counter of one good cycle (2 per output slave + 1 per input slave for LRW)."""

    def exchange(self) -> int:
        """Send the outputs and receive the inputs (one cycle). Returns the working counter,
        -1 if no frame came back; inputs keep their previous values then. No allocation."""
        return self._exchange()

    # ------------------------------------------------------------------ acyclic
    def slaves(self) -> tuple[SlaveInfo, ...]:
        """All slaves found on the bus with identity and AL state, in bus order."""
        self._check_open()
        return self._slaves()

    def sdo_upload(self, position: int, index: int, subindex: int = 0) -> bytes:
        """CoE SDO upload (read) from the slave at bus `position`."""
        self._check_open()
        return self._sdo_upload(position, index, subindex)

    def sdo_download(self, position: int, index: int, subindex: int, data: bytes) -> None:
        """CoE SDO download (write) to the slave at bus `position`."""
        self._check_open()
        self._sdo_download(position, index, subindex, bytes(data))

    def sdo_read(self, position: int, index: int, subindex: int, fmt: str) -> Any:
        """Upload and unpack with a struct format ('<H', '<i', ...)."""
        return struct.unpack(fmt, self.sdo_upload(position, index, subindex))[0]

    def sdo_write(self, position: int, index: int, subindex: int, fmt: str, value: Any) -> None:
        """Pack with a struct format and download."""
        self.sdo_download(position, index, subindex, struct.pack(fmt, value))

    # ------------------------------------------------------------------ optional features
    def lost_slaves(self) -> tuple[int, ...]:
        """Positions of slaves known to be lost (diagnosis after a working counter error)."""
        return ()

    def recover_slaves(self) -> tuple[int, ...]:
        """Bring lost slaves that answer again back to OP; returns their positions. Called
        beside the cycle, never in it. Default: nothing to do (the bus recovers on its own)."""
        return ()

    def digital_outputs_mapped(self, index: int) -> bool:
        """Whether drive `index` receives ``digital_outputs`` (0x60FE:1) in its process data."""
        return True

    def maps_object(self, index: int, obj: int) -> bool:
        """Whether drive `index` has object `obj` (e.g. 0x603F error code) in its process data;
        when not, its array here is not updated and the value must be read by SDO."""
        return True

    def inject(self, name: str, index: int = 0, value: int = 0) -> None:
        """Fault injection by name (``sim_bus.INJECTIONS``); only a simulated bus can."""
        raise BusFeatureError(f"{type(self).__name__} cannot inject faults ({name!r}): use the simulated bus")

    # ------------------------------------------------------------------ backend
    @abc.abstractmethod
    def _open(self) -> None: ...

    @abc.abstractmethod
    def _close(self) -> None: ...

    @abc.abstractmethod
    def _exchange(self) -> int: ...

    @abc.abstractmethod
    def _slaves(self) -> tuple[SlaveInfo, ...]: ...

    @abc.abstractmethod
    def _sdo_upload(self, position: int, index: int, subindex: int) -> bytes: ...

    @abc.abstractmethod
    def _sdo_download(self, position: int, index: int, subindex: int, data: bytes) -> None: ...


#: backend name -> "module:Class", imported lazily by `make_bus`
BACKENDS: dict[str, str] = {
    "sim": "ethercat.sim_bus:SimBus",
    "soem": "ethercat.soem_bus:SoemBus",
}


def bus_class(kind: str) -> type[Bus]:
    """The backend class registered under `kind` (imported on first use)."""
    try:
        target = BACKENDS[kind]
    except KeyError:
        raise ConfigurationError(f"unknown bus kind {kind!r}; known: {sorted(BACKENDS)}") from None
    module_name, _, cls_name = target.partition(":")
    try:
        module = importlib.import_module(module_name)
    except ImportError as exc:
        raise ConfigurationError(f"bus backend {kind!r} is not available: {exc}") from exc
    backend: type[Bus] = getattr(module, cls_name)
    return backend


def make_bus(kind: str, drives: Sequence[DriveSpec], cycle_time_s: float = 0.001, **options: Any) -> Bus:
    """Create (not open) a bus by backend name. `options` go to the backend, e.g.
    `adapter="eth0"` for "soem", `drive_params=[...]` for "sim"."""
    return bus_class(kind)(drives, cycle_time_s=cycle_time_s, **options)
