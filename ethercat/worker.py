"""The cyclic worker: one EtherCAT cycle every Ts on absolute deadlines, fed set-points by
the controller through a bounded buffer, with supervision, tracking and timing records.

Controller-facing API (the contract of app/machine):

    cfg = WorkerConfig(drives=(DriveSpec(0, "X", 10_000.0), DriveSpec(1, "Y", 10_000.0)))
    w = CyclicWorker(cfg)
    w.start()                      # bus open, cyclic loop running, drives DISABLED
    w.enable()                     # CiA 402 walk to OPERATION ENABLED, target := actual
    n = w.push(q_mm)               # (N, n_axes) set-points in axis units; returns how many fit
    s = w.snapshot()               # WorkerSnapshot, read at <= 30 Hz by the panel
    w.quick_stop("operator")       # quick stop all axes + alarm naming the cause
    w.fault_reset(); w.enable()
    w.stop()                       # drives disabled, bus closed, process joined

Modes (`WorkerConfig.mode`):
  "process"  the loop runs in its own process (multiprocessing spawn), pinned to a core
             no other worker holds (`WorkerConfig.cpu`), SCHED_FIFO 49 when permitted,
             memory locked, GC disabled; set-points, commands and snapshots cross through
             one `multiprocessing.shared_memory` block (an SPSC ring, a staging area for
             `replace`, a command mailbox, a seqlock snapshot). Default: a busy Qt GUI in
             the parent does not disturb it.
             Each cycle sleeps on an absolute deadline (clock_nanosleep) to 0.1 ms before
             it and busy-waits the rest, and always sleeps at least `min_sleep_s`: a
             real-time loop that never sleeps would starve its core (and another worker).
  "thread"   the same loop as a plain thread in the calling process (for comparison).
  "manual"   no thread: `step(n)` runs n cycles at once (simulated time; for tests and
             headless fast-forward with `bus_kind="sim"`).

Set-point serials: the k-th set-point the loop takes since start has serial k;
`samples_consumed()` (live, not the snapshot) is the serial taken next. `replace(from_serial,
q)` swaps the queued tail from a serial on, atomically between two cycles (feed hold within a
cycle or two instead of after the queued lead; protocol in its docstring).

Per cycle (`_Loop.cycle`): command mailbox -> outputs (set-point from the ring when
ENABLED, else target := actual) -> `bus.exchange()` -> supervision (working counter,
drive faults, following error over its window for `following_error_cycles`) ->
tracking (e = reference - actual per axis, paper Eq. 18: MSE = sum(e^2)/n, RMSE = sqrt(MSE),
total and over `tracking_window_s`) -> timing (period, start jitter histogram, late
cycles) -> every 1/30 s, and right after a cycle that applied a command, a snapshot copy
(it carries the command's sequence number: `wait_for` judges only snapshots at least as new
as the last command). Slave loss: an alarm per lost slave (SLAVE_LOST, with the working
counter reaction); while lost, the bus's `recover_slaves()` (SoemBus) is tried every
`recover_interval_s` in a helper thread; when every slave answers again, an event
SLAVE_RECOVERED (`CyclicWorker.events()`). Reactions: underrun while moving holds the last
position (alarm UNDERRUN; not a quick stop); working counter wrong for more than
`wkc_error_limit` cycles, a drive fault, a following error or E-stop: quick stop of all
axes, the set-point buffer flushed, and an alarm naming the cause.
Nothing in the cycle allocates arrays or logs; alarm texts are built by the reader.
"""

from __future__ import annotations

import atexit
import collections
import contextlib
import ctypes
import enum
import gc
import math
import multiprocessing as mp
import os
import sys
import threading
import time
import types
from collections.abc import Sequence
from dataclasses import dataclass, field
from multiprocessing import shared_memory
from typing import Any

import numpy as np

from . import cia402
from .bus import Bus, DriveSpec, check_drives, make_bus
from .cia402 import Cia402State
from .errors import ConfigurationError, EtherCATError, WorkerError, WorkerTimeoutError

__all__ = [
    "Alarm", "AlarmCode", "CyclicWorker", "DriveSpec", "EventCode", "HomingState", "TimingStats",
    "TraceChunk", "TrackingStats", "WorkerConfig", "WorkerEvent", "WorkerSnapshot", "WorkerState",
]


class WorkerState(enum.IntEnum):
    """State of the worker as a whole (all axes)."""

    STOPPED = 0        # not started / stopped
    STARTING = 1       # bus being opened
    DISABLED = 2       # bus in OP, drives not enabled (target := actual)
    ENABLING = 3       # walking every drive to OPERATION ENABLED
    ENABLED = 4        # following set-points (or holding the last one)
    HOMING = 5         # one drive in mode 6 running its homing method
    QUICK_STOP = 6     # after a quick stop (reaction or request): needs fault_reset/enable
    FAULT = 7          # a drive is in FAULT: needs fault_reset
    FAULT_RESET = 8    # fault reset edge being applied
    ERROR = 9          # the loop failed (bus error): stop() and start again


class AlarmCode(enum.IntEnum):
    UNDERRUN = 1
    WORKING_COUNTER = 2
    DRIVE_FAULT = 3
    FOLLOWING_ERROR = 4
    ESTOP = 5
    QUICK_STOP = 6
    ENABLE_TIMEOUT = 7
    HOMING_ERROR = 8
    BUS_ERROR = 9
    FAULT_RESET_FAILED = 10
    SLAVE_LOST = 11


class EventCode(enum.IntEnum):
    """Things worth telling the operator that are not alarms (codes share the alarm ring, >= 100)."""

    SLAVE_RECOVERED = 101


class HomingState(enum.IntEnum):
    IDLE = 0
    RUNNING = 1
    DONE = 2
    ERROR = 3


@dataclass(frozen=True, slots=True)
class Alarm:
    """One alarm raised by the worker. `axis` is the axis name, "" for all axes."""

    code: AlarmCode
    message: str
    axis: str
    cycle: int
    time_s: float          # worker time (cycle * Ts) when raised
    wall_time: float       # time.time() when the reader picked it up


@dataclass(frozen=True, slots=True)
class WorkerEvent:
    """One event reported by the worker (not an alarm: nothing to acknowledge)."""

    code: EventCode
    message: str
    axis: str
    cycle: int
    time_s: float
    wall_time: float


@dataclass(frozen=True, slots=True)
class TimingStats:
    """Cycle timing since start. Jitter = cycle start - its absolute deadline (>= 0)."""

    cycles: int
    period_mean_s: float
    period_min_s: float
    period_max_s: float
    jitter_p50_s: float
    jitter_p99_s: float
    jitter_p999_s: float
    jitter_max_s: float
    late_cycles: int                 # start later than `late_threshold_s`
    missed_cycles: int               # deadlines skipped because a cycle overran
    exec_mean_s: float               # time from cycle start to the end of its work
    exec_max_s: float
    span_s: float                    # last cycle start - first cycle start (wall clock)
    histogram_bin_s: float
    jitter_histogram: tuple[int, ...]   # counts per bin, last bin = overflow

    def as_dict(self) -> dict[str, Any]:
        us = 1e6
        return {
            "cycles": self.cycles, "period_mean_us": self.period_mean_s * us,
            "period_min_us": self.period_min_s * us, "period_max_us": self.period_max_s * us,
            "jitter_p50_us": self.jitter_p50_s * us, "jitter_p99_us": self.jitter_p99_s * us,
            "jitter_p999_us": self.jitter_p999_s * us, "jitter_max_us": self.jitter_max_s * us,
            "late_cycles": self.late_cycles, "missed_cycles": self.missed_cycles,
            "exec_mean_us": self.exec_mean_s * us, "exec_max_us": self.exec_max_s * us,
        }


@dataclass(frozen=True, slots=True)
class TrackingStats:
    """Tracking error e = reference - actual per axis (axis units), paper Eq. 18 / Table 4."""

    samples: int
    rmse: tuple[float, ...]
    mse: tuple[float, ...]
    max_abs: tuple[float, ...]
    window_samples: int
    window_rmse: tuple[float, ...]
    window_mse: tuple[float, ...]


@dataclass(frozen=True, slots=True)
class WorkerSnapshot:
    """What the panel and the controller read (<= 30 Hz). Arrays are read-only copies."""

    state: WorkerState
    cycle: int
    time_s: float
    axis_names: tuple[str, ...]
    drive_states: tuple[Cia402State, ...]
    statuswords: tuple[int, ...]
    error_codes: tuple[int, ...]
    actual_position: np.ndarray        # axis units (mm | deg)
    reference_position: np.ndarray     # axis units, the set-point sent last
    following_error: np.ndarray        # reference - actual, axis units
    buffer_level: int
    buffer_capacity: int
    samples_consumed: int              # set-points taken from the buffer since start
    underruns: int
    wkc: int
    expected_wkc: int
    wkc_errors: int
    homing: tuple[HomingState, ...]
    homed: tuple[bool, ...]
    alarms: tuple[Alarm, ...]          # active (not yet cleared by fault_reset)
    timing: TimingStats
    tracking: TrackingStats
    digital_outputs: tuple[int, ...]
    command_seq: int = 0               # sequence number of the last command the loop applied
    lost_slaves: tuple[int, ...] = ()  # slave positions lost and not yet back
    events: tuple[WorkerEvent, ...] = ()   # recent events (e.g. slave recovered), oldest first

    @property
    def enabled(self) -> bool:
        return self.state is WorkerState.ENABLED


@dataclass(frozen=True, slots=True)
class TraceChunk:
    """Per-cycle reference and actual positions drained from the worker (axis units).

    `reference[k]` is the set-point the actual position of cycle `cycle[k]` answers
    (`tracking_delay_cycles` earlier), so `reference - actual` is the tracking error of Eq. 18.
    """

    cycle: np.ndarray          # (N,) int64
    reference: np.ndarray      # (N, n_axes)
    actual: np.ndarray         # (N, n_axes)
    dropped: int               # cycles overwritten before they were drained


@dataclass(frozen=True, slots=True)
class WorkerConfig:
    """Configuration of the cyclic worker.

    drives: the machine's drives (axis order = column order of `push`).
    ts_s: cycle time; bus_kind "sim" | "soem"; adapter: network interface for "soem".
    wkc_error_limit: working counter may be wrong for this many consecutive cycles.
    buffer_capacity: set-points the ring holds (2000 = 2 s ahead at 1 ms).
    following_error_cycles: |ref - actual| over the window for more than this many cycles.
    mode: "process" | "thread" | "manual".
    cpu (mode "process"): core to pin the loop to. -1 = automatic: the highest-numbered
    core no other worker holds (each worker process holds an flock on
    /dev/shm/cnc-ethercat-cpu<N>.lock while it runs); when every core is held the new
    worker runs unpinned with normal scheduling, so two workers (parallel tests, a bench
    beside the demo) never share one core at real-time priority. An explicit core >= 0 is
    honoured even when held (`realtime_applied` then says which pid shares it).
    None = no pinning.
    rt_priority: SCHED_FIFO priority when permitted (0 = normal scheduling). Default 49:
    below the threaded interrupt handlers of a PREEMPT_RT kernel (50), whose NIC interrupt
    the cycle waits on; above every normal task.
    spin_s: the loop sleeps to `spin_s` before each deadline (clock_nanosleep on an
    absolute CLOCK_MONOTONIC deadline) and busy-waits the rest; never longer, and not at
    all when the deadline has passed. None = 0.1 ms in mode "process" (measured here:
    SCHED_FIFO wake-up latency p50 35 us, p99 60 us), 0 in mode "thread" (spinning would
    hold the GIL against the GUI).
    min_sleep_s: the loop sleeps at least this long before every cycle, even when late,
    so an overrunning loop at real-time priority never monopolises its core (a worker
    that never sleeps starves everything else on that core, including another worker).
    recover_interval_s: while slaves are lost, the bus's `recover_slaves()` (if it has
    one) is tried this often (in a helper thread, so the cycle keeps running).
    tracking_delay_cycles: the actual position read in cycle k answers the set-point of
    cycle k - d (bus transport: 1 on SimBus, where inputs are latched before outputs apply).
    underrun_velocity_units_s: the buffer running empty is an underrun only when the last
    set-points moved faster than this (a jerk-limited stop ends far below it).
    bus_options: extra keyword arguments for the bus backend, as (name, value) pairs.
    """

    drives: tuple[DriveSpec, ...]
    ts_s: float = 0.001
    bus_kind: str = "sim"
    adapter: str = ""
    wkc_error_limit: int = 3
    buffer_capacity: int = 2000
    following_error_cycles: int = 3
    mode: str = "process"
    cpu: int | None = -1
    rt_priority: int = 49
    spin_s: float | None = None
    min_sleep_s: float = 0.00005
    recover_interval_s: float = 0.1
    late_threshold_s: float = 0.001
    snapshot_hz: float = 30.0
    tracking_window_s: float = 600.0
    tracking_delay_cycles: int = 1
    underrun_velocity_units_s: float = 0.01
    enable_timeout_s: float = 1.0
    fault_reset_timeout_s: float = 0.5
    homing_timeout_s: float = 120.0
    start_timeout_s: float = 20.0
    command_timeout_s: float = 2.0
    trace_capacity: int = 1 << 16
    bus_options: tuple[tuple[str, Any], ...] = field(default=())

    def __post_init__(self) -> None:
        object.__setattr__(self, "drives", check_drives(self.drives))
        if not 0.0001 <= self.ts_s <= 0.1:
            raise ConfigurationError(f"ts_s must be within [0.0001, 0.1] s, got {self.ts_s}")
        if self.mode not in ("process", "thread", "manual"):
            raise ConfigurationError(f"mode must be 'process', 'thread' or 'manual', got {self.mode!r}")
        if self.buffer_capacity < 2:
            raise ConfigurationError(f"buffer_capacity must be >= 2, got {self.buffer_capacity}")
        if self.wkc_error_limit < 0 or self.following_error_cycles < 0:
            raise ConfigurationError("wkc_error_limit and following_error_cycles must be >= 0")
        if not 0 <= self.tracking_delay_cycles < _REF_HISTORY:
            raise ConfigurationError(f"tracking_delay_cycles must be within [0, {_REF_HISTORY - 1}]")
        if not 0.0 < self.snapshot_hz <= 1000.0:
            raise ConfigurationError(f"snapshot_hz must be within (0, 1000], got {self.snapshot_hz}")
        if self.spin_s is not None and not 0.0 <= self.spin_s <= 0.5 * self.ts_s:
            raise ConfigurationError(f"spin_s must be within [0, ts_s / 2], got {self.spin_s}")
        if not 0.0 <= self.min_sleep_s <= 0.5 * self.ts_s:
            raise ConfigurationError(f"min_sleep_s must be within [0, ts_s / 2], got {self.min_sleep_s}")
        if not 0 <= self.rt_priority <= 99:
            raise ConfigurationError(f"rt_priority must be within [0, 99], got {self.rt_priority}")

    @property
    def n_axes(self) -> int:
        return len(self.drives)

    @property
    def axis_names(self) -> tuple[str, ...]:
        return tuple(d.axis_name for d in self.drives)


# ---------------------------------------------------------------------- shared layout
_REF_HISTORY = 8
PROCESS_SPIN_S = 0.0001
_FAULTED_LUT = np.array([s in (Cia402State.FAULT, Cia402State.FAULT_REACTION_ACTIVE) for s in Cia402State])
_NOT_ENABLED_LUT = np.array([s is not Cia402State.OPERATION_ENABLED for s in Cia402State])
_HIST_BIN_S = 5e-6
_HIST_BINS = 401              # 0 .. 2 ms in 5 us bins, last = overflow
_ALARM_SLOTS = 64
_EVENTS_KEPT = 32
_MSG_BYTES = 1024

# ctl (int64) indices: mailbox and rings, outside the snapshot
C_STATUS, C_CMD_SEQ, C_CMD_ACK, C_CMD_CODE, C_CMD_A, C_CMD_B, C_CMD_RESULT = range(7)
C_HEAD, C_TAIL, C_SNAP_SEQ, C_ALARMS, C_TRACE_HEAD, C_PID = range(7, 13)
C_SIZE = 16
# child status
ST_STARTING, ST_RUNNING, ST_STOPPED, ST_FAILED = range(4)
# live int64 scalars (li) indices
I_CYCLE, I_STATE, I_CONSUMED, I_UNDERRUNS, I_WKC, I_WKC_EXP, I_WKC_ERRORS, I_LATE, I_MISSED, \
    I_TRACK_N, I_WIN_N, I_TIMED, I_CMD_APPLIED, I_LOST = range(14)
I_SIZE = 16
# live float64 scalars (lf) indices
F_TIME, F_PERIOD_SUM, F_PERIOD_MIN, F_PERIOD_MAX, F_JITTER_MAX, F_EXEC_SUM, F_EXEC_MAX, F_FIRST_START, \
    F_LAST_START = range(9)
F_SIZE = 10
# commands
(CMD_NONE, CMD_ENABLE, CMD_DISABLE, CMD_FAULT_RESET, CMD_QUICK_STOP, CMD_ESTOP, CMD_HOME, CMD_DOUT,
 CMD_INJECT, CMD_FLUSH, CMD_RESET_TRACKING, CMD_STOP, CMD_REPLACE) = range(13)
INJECT_NAMES = ("drive_fault", "persistent_fault", "clear_fault", "jam", "unjam", "drop_frames",
                "lose_slave", "restore_slave")
RESULT_OK, RESULT_REFUSED, RESULT_TOO_LATE, RESULT_BEYOND_END = 1, 2, 3, 4
# CyclicWorker.replace() return values when nothing was changed
REPLACE_TOO_LATE = -1        # from_serial was already taken by the loop: retry from a later serial
REPLACE_BEYOND_END = -2      # from_serial is past the last queued set-point


class _Layout:
    """Offsets of every array in the one shared block (8-byte aligned)."""

    def __init__(self, n: int, capacity: int, trace_capacity: int) -> None:
        self.n = n
        self.capacity = capacity
        self.trace_capacity = trace_capacity
        head = [("ctl", np.int64, (C_SIZE,)), ("msg", np.uint8, (_MSG_BYTES,))]
        live = [
            ("li", np.int64, (I_SIZE,)), ("lf", np.float64, (F_SIZE,)),
            ("drive_state", np.int64, (n,)), ("statusword", np.int64, (n,)), ("error_code", np.int64, (n,)),
            ("homing", np.int64, (n,)), ("homed", np.int64, (n,)), ("dout", np.int64, (n,)),
            ("act", np.float64, (n,)), ("ref", np.float64, (n,)), ("fe", np.float64, (n,)),
            ("sum_e2", np.float64, (n,)), ("win_e2", np.float64, (n,)), ("max_e", np.float64, (n,)),
            ("hist", np.int64, (_HIST_BINS,)),
        ]
        tail = [("ring", np.float64, (capacity, n)), ("stage", np.float64, (capacity, n)),
                ("alarm", np.int64, (_ALARM_SLOTS, 6)),
                ("alarm_f", np.float64, (_ALARM_SLOTS,)), ("trace", np.float64, (trace_capacity, 1 + 2 * n))]
        self.fields: dict[str, tuple[int, Any, tuple[int, ...]]] = {}
        off = 0
        for name, dt, shape in head:
            off = self._add(name, dt, shape, off)
        self.live_start = off
        for name, dt, shape in live:
            off = self._add(name, dt, shape, off)
        self.live_end = off
        for name, dt, shape in live:
            o, _, _ = self.fields[name]
            self.fields["snap_" + name] = (o - self.live_start + off, dt, shape)
        off += self.live_end - self.live_start
        for name, dt, shape in tail:
            off = self._add(name, dt, shape, off)
        self.size = off

    def _add(self, name: str, dt: Any, shape: tuple[int, ...], off: int) -> int:
        self.fields[name] = (off, dt, shape)
        nbytes = int(np.dtype(dt).itemsize * math.prod(shape))
        return off + ((nbytes + 7) // 8) * 8

    def views(self, buf: Any) -> dict[str, np.ndarray]:
        out = {name: np.ndarray(shape, dtype=dt, buffer=buf, offset=o)
               for name, (o, dt, shape) in self.fields.items()}
        raw = np.ndarray(self.size, dtype=np.uint8, buffer=buf)
        out["live_bytes"] = raw[self.live_start:self.live_end]
        snap0 = self.fields["snap_li"][0]
        out["snap_bytes"] = raw[snap0:snap0 + self.live_end - self.live_start]
        return out


# ---------------------------------------------------------------------- the loop
class _Loop:
    """The cycle, run in the worker process or thread. Owns the bus."""

    def __init__(self, config: WorkerConfig, v: dict[str, np.ndarray]) -> None:
        self.cfg = config
        self.v = v
        n = config.n_axes
        self.n = n
        self.ctl = v["ctl"]
        self.li = v["li"]
        self.lf = v["lf"]
        self.ring = v["ring"]
        self.cap = config.buffer_capacity
        self.bus: Bus | None = None
        scales = tuple(cia402.AxisScale(d.counts_per_unit, d.direction) for d in config.drives)
        self.gain, self.offset = cia402.scale_arrays(scales)
        self.window = np.array([d.following_error_window for d in config.drives], dtype=np.float64)
        # preallocated work arrays
        self.ref = v["ref"]
        self.act = v["act"]
        self.fe = v["fe"]
        self.prev_ref = np.zeros(n)
        self.ref_hist = np.zeros((_REF_HISTORY, n))
        # row views made once, so the cycle indexes lists instead of creating array views
        self.ref_rows = [self.ref_hist[i] for i in range(_REF_HISTORY)]
        self.ring_rows = [self.ring[i] for i in range(config.buffer_capacity)]
        self.tmp = np.zeros(n)
        self.tmp2 = np.zeros(n)
        self.states = np.zeros(n, dtype=np.int8)
        self.scratch_i = np.zeros(n, dtype=np.int64)
        self.fe_count = np.zeros(n, dtype=np.int64)
        self.fault_seen = np.zeros(n, dtype=bool)
        self.bool_tmp = np.zeros(n, dtype=bool)
        block = max(1, int(round(1.0 / config.ts_s)))          # 1 s blocks for the window
        self.block_cycles = block
        n_blocks = max(1, int(math.ceil(config.tracking_window_s / (block * config.ts_s))))
        self.blocks = np.zeros((n_blocks, n))
        self.blocks_n = np.zeros(n_blocks, dtype=np.int64)
        self.block_acc = np.zeros(n)
        self.block_acc_n = 0
        self.block_index = 0
        self.e = np.zeros(n)
        self.eps_units = config.underrun_velocity_units_s * config.ts_s   # per cycle
        self.snapshot_every = max(1, int(round(1.0 / (config.snapshot_hz * config.ts_s))))
        self.state = WorkerState.STARTING
        self.state_cycles = 0
        self.moving = False
        self.wkc_bad_run = 0
        self.wkc_alarmed = False
        self.cmd_seen = int(self.ctl[C_CMD_SEQ])
        self.homing_axis = -1
        self.homing_phase = 0
        self.homing_wait = 0
        self.fault_reset_cycle = 0
        self.trace_cap = config.trace_capacity
        self.trace = v["trace"]
        self.stop_requested = False
        self.publish_now = False           # a command was applied: publish after this cycle
        # slave loss and recovery (bus.recover_slaves when the backend has it)
        self.lost_mask = 0
        self.recover_every = max(1, int(round(config.recover_interval_s / config.ts_s)))
        self.recover_countdown = 0
        self.recovered_mask = 0            # written by the recovery helper thread
        self.recover_calls = 0
        self.recover_busy = False          # a recover_slaves() attempt is under way
        self._recover_event: threading.Event | None = None
        self._recover_thread: threading.Thread | None = None

    # ------------------------------------------------------------------ bus
    def open_bus(self) -> None:
        cfg = self.cfg
        options = dict(cfg.bus_options)
        if cfg.bus_kind == "soem":
            options.setdefault("adapter", cfg.adapter)
        self.bus = make_bus(cfg.bus_kind, cfg.drives, cycle_time_s=cfg.ts_s, **options)
        self.bus.open()
        bus = self.bus
        self.li[I_WKC_EXP] = bus.expected_wkc
        bus.modes_of_operation[:] = cia402.CSP
        self._read_actual()
        np.copyto(self.ref, self.act)
        np.copyto(self.prev_ref, self.act)
        self._target_from_actual()
        self.lf[F_PERIOD_MIN] = math.inf
        self._set_state(WorkerState.DISABLED)

    def close_bus(self) -> None:
        bus = self.bus
        if bus is None:
            return
        self.stop_requested = True
        helper = self._recover_thread
        if helper is not None:
            assert self._recover_event is not None
            self._recover_event.set()
            helper.join(timeout=5.0)
            self._recover_thread = None
        try:
            if bus.is_open:
                for _ in range(5):          # leave drives disabled (best effort)
                    np.take(cia402.DISABLE_LUT, self.states, out=bus.controlword)
                    bus.target_position[:] = bus.position_actual
                    bus.exchange()
                    cia402.decode_states(bus.statusword, self.states, self.scratch_i)
        except Exception:  # noqa: BLE001 - the bus is closed below whatever happened
            pass
        finally:
            bus.close()
            self.bus = None

    # ------------------------------------------------------------------ helpers
    def _set_state(self, st: WorkerState) -> None:
        self.state = st
        self.state_cycles = 0
        self.li[I_STATE] = int(st)

    def _read_actual(self) -> None:
        assert self.bus is not None
        cia402.counts_to_units(self.bus.position_actual, self.gain, self.offset, self.act)

    def _target_from_actual(self) -> None:
        assert self.bus is not None
        np.copyto(self.bus.target_position, self.bus.position_actual)

    def _alarm(self, code: AlarmCode | EventCode, axis: int = -1, a: int = 0, b: int = 0,
               f: float = 0.0) -> None:
        k = int(self.ctl[C_ALARMS])
        row = self.v["alarm"][k % _ALARM_SLOTS]
        row[0] = int(code)
        row[1] = axis
        row[2] = int(self.li[I_CYCLE])
        row[3] = a
        row[4] = b
        row[5] = self.cmd_seen             # the command behind it (quick stop reason lookup)
        self.v["alarm_f"][k % _ALARM_SLOTS] = f
        self.ctl[C_ALARMS] = k + 1

    def _flush(self) -> None:
        self.ctl[C_TAIL] = self.ctl[C_HEAD]
        self.moving = False

    def _hold_actual(self) -> None:
        np.copyto(self.ref, self.act)
        np.copyto(self.prev_ref, self.act)
        self.ref_hist[:] = self.act
        self._target_from_actual()

    def _reaction(self, code: AlarmCode, axis: int = -1, a: int = 0, b: int = 0, f: float = 0.0,
                  state: WorkerState = WorkerState.QUICK_STOP) -> None:
        """Quick stop of all axes, buffer flushed, alarm raised."""
        self._alarm(code, axis, a, b, f)
        self._flush()
        self.homing_axis = -1
        if self.bus is not None:
            self.bus.modes_of_operation[:] = cia402.CSP
        self._set_state(state)

    # ------------------------------------------------------------------ commands
    def poll_command(self) -> None:
        seq = int(self.ctl[C_CMD_SEQ])
        if seq == self.cmd_seen:
            return
        self.cmd_seen = seq
        result = self._command(int(self.ctl[C_CMD_CODE]), int(self.ctl[C_CMD_A]), int(self.ctl[C_CMD_B]))
        self.ctl[C_CMD_RESULT] = result
        self.li[I_CMD_APPLIED] = seq         # snapshots published from now on show its effect
        self.publish_now = True
        self.ctl[C_CMD_ACK] = seq

    def _command(self, code: int, a: int, b: int) -> int:
        st = self.state
        bus = self.bus
        assert bus is not None
        if code == CMD_ENABLE:
            if st in (WorkerState.ENABLED, WorkerState.ENABLING):
                return RESULT_OK
            if st not in (WorkerState.DISABLED, WorkerState.QUICK_STOP) or self.fault_seen.any():
                return RESULT_REFUSED
            self._flush()
            self.fe_count[:] = 0
            bus.modes_of_operation[:] = cia402.CSP
            self._set_state(WorkerState.ENABLING)
        elif code == CMD_DISABLE:
            self._flush()
            bus.modes_of_operation[:] = cia402.CSP
            self.homing_axis = -1
            if st not in (WorkerState.FAULT, WorkerState.FAULT_RESET, WorkerState.ERROR):
                self._set_state(WorkerState.DISABLED)
        elif code == CMD_FAULT_RESET:
            self._flush()
            self.fault_reset_cycle = 0
            self.wkc_bad_run = 0
            self.wkc_alarmed = False
            self._set_state(WorkerState.FAULT_RESET)
        elif code in (CMD_QUICK_STOP, CMD_ESTOP):
            self._reaction(AlarmCode.ESTOP if code == CMD_ESTOP else AlarmCode.QUICK_STOP,
                           state=WorkerState.FAULT if st is WorkerState.FAULT else WorkerState.QUICK_STOP)
        elif code == CMD_HOME:
            if st is not WorkerState.ENABLED or self.moving or not 0 <= a < self.n:
                return RESULT_REFUSED
            self._flush()
            try:
                bus.sdo_write(self.cfg.drives[a].position, 0x6098, 0, "<b", b)
            except EtherCATError:
                return RESULT_REFUSED
            self.homing_axis = a
            self.homing_phase = 0
            self.v["homing"][a] = HomingState.RUNNING
            self.v["homed"][a] = 0
            bus.modes_of_operation[a] = cia402.HOMING
            self._set_state(WorkerState.HOMING)
        elif code == CMD_DOUT:
            if not 0 <= a < self.n:
                return RESULT_REFUSED
            try:
                bus.set_digital_outputs(a, b)
            except EtherCATError:
                return RESULT_REFUSED
            self.v["dout"][a] = b
        elif code == CMD_INJECT:
            inject = getattr(bus, "inject", None)
            name_index = b & 0xFF
            if inject is None or not 0 <= name_index < len(INJECT_NAMES):
                return RESULT_REFUSED
            inject(INJECT_NAMES[name_index], a, b >> 8)
        elif code == CMD_FLUSH:
            self._flush()
        elif code == CMD_REPLACE:
            return self._replace(a, b)
        elif code == CMD_RESET_TRACKING:
            self._reset_tracking()
        elif code == CMD_STOP:
            self.stop_requested = True
        else:
            return RESULT_REFUSED
        return RESULT_OK

    def _replace(self, from_serial: int, n: int) -> int:
        """CMD_REPLACE, applied between two cycles: the queued set-points with serial >=
        `from_serial` are dropped and the `n` staged ones take their place. Serial k = the k-th
        set-point taken since start (`I_CONSUMED` is the serial taken next; it sits at ring
        index `C_TAIL`). Refused (nothing changed) when that serial was already taken or lies
        past the queue's end. Runs once per command (not per cycle); the copy is at most
        two block copies of the staging area into the ring (wrap-around)."""
        ctl = self.ctl
        consumed = int(self.li[I_CONSUMED])
        tail = int(ctl[C_TAIL])
        head = int(ctl[C_HEAD])
        if from_serial < consumed:
            return RESULT_TOO_LATE
        start = tail + (from_serial - consumed)
        if start > head:
            return RESULT_BEYOND_END
        cap = self.cap
        n = max(0, min(n, cap - (start - tail)))
        i0 = start % cap
        first = min(n, cap - i0)
        stage = self.v["stage"]
        if first > 0:
            np.copyto(self.ring[i0:i0 + first], stage[:first])
        if n > first:
            np.copyto(self.ring[:n - first], stage[first:n])
        ctl[C_HEAD] = start + n            # the producer waits for our ack before touching head
        return RESULT_OK

    def _axis_of(self, position: int) -> int:
        for i, d in enumerate(self.cfg.drives):
            if d.position == position:
                return i
        return -1

    # ------------------------------------------------------------------ slave recovery
    def _try_recover(self) -> None:
        """Every `recover_interval_s` while slaves are lost: the bus's `recover_slaves()`
        (SoemBus: find the slave again, check identity, remap, SYNC0, OP; tens of ms when
        it came back) in a helper thread, so the cycle goes on for the others (as SOEM's
        ecatcheck). Inline in mode "manual". Buses without it recover on their own."""
        if self.recover_countdown > 0:
            self.recover_countdown -= 1
            return
        self.recover_countdown = self.recover_every
        bus = self.bus
        if bus is None or getattr(bus, "recover_slaves", None) is None:
            return
        if self.cfg.mode == "manual":
            self._recover_once()
            return
        if self._recover_thread is None:
            self._recover_event = threading.Event()
            self._recover_thread = threading.Thread(target=self._recover_main, name="ethercat-recover",
                                                    daemon=True)
            self._recover_thread.start()
        assert self._recover_event is not None
        self._recover_event.set()

    def _recover_once(self) -> None:
        bus = self.bus
        if bus is None:
            return
        self.recover_calls += 1
        # While an attempt runs, the cycle may already see the working counter right again:
        # it waits for the attempt to finish so the event says how the slave came back.
        self.recover_busy = True
        try:
            got = bus.recover_slaves()  # type: ignore[attr-defined]
        except Exception:  # noqa: BLE001 - a failed attempt is retried at the next interval
            return
        else:
            for pos in got:
                self.recovered_mask |= 1 << min(int(pos), 62)
        finally:
            self.recover_busy = False

    def _recover_main(self) -> None:
        event = self._recover_event
        assert event is not None
        while not self.stop_requested:
            if not event.wait(0.2):
                continue
            event.clear()
            if self.stop_requested:
                break
            self._recover_once()

    def _reset_tracking(self) -> None:
        v = self.v
        v["sum_e2"][:] = 0.0
        v["win_e2"][:] = 0.0
        v["max_e"][:] = 0.0
        self.blocks[:] = 0.0
        self.blocks_n[:] = 0
        self.block_acc[:] = 0.0
        self.block_acc_n = 0
        self.li[I_TRACK_N] = 0
        self.li[I_WIN_N] = 0

    # ------------------------------------------------------------------ the cycle
    def cycle(self) -> None:
        """One cycle: commands, outputs, exchange, supervision, tracking. No allocation."""
        bus = self.bus
        assert bus is not None
        self.poll_command()
        li = self.li
        cycle = int(li[I_CYCLE]) + 1
        li[I_CYCLE] = cycle
        self.lf[F_TIME] = cycle * self.cfg.ts_s
        self.state_cycles += 1
        st = self.state
        states = self.states
        # ---- outputs
        if st is WorkerState.ENABLED:
            head = int(self.ctl[C_HEAD])
            tail = int(self.ctl[C_TAIL])
            np.copyto(self.prev_ref, self.ref)
            if head > tail:
                np.copyto(self.ref, self.ring_rows[tail % self.cap])
                self.ctl[C_TAIL] = tail + 1
                li[I_CONSUMED] += 1
                np.subtract(self.ref, self.prev_ref, out=self.tmp)
                np.abs(self.tmp, out=self.tmp)
                self.moving = bool(self.tmp.max() > self.eps_units)
            elif self.moving:
                # underrun while moving: hold the last set-point, alarm (issue 5)
                self.moving = False
                li[I_UNDERRUNS] += 1
                self._alarm(AlarmCode.UNDERRUN, -1, int(li[I_CONSUMED]))
            cia402.units_to_counts(self.ref, self.gain, self.offset, bus.target_position, self.tmp2)
            bus.controlword.fill(cia402.CW_ENABLE_OPERATION)
        elif st is WorkerState.HOMING:
            self._homing_outputs()
        else:
            self._target_from_actual()
            if st is WorkerState.ENABLING:
                np.take(cia402.ENABLE_LUT, states, out=bus.controlword)
            elif st is WorkerState.DISABLED:
                np.take(cia402.DISABLE_LUT, states, out=bus.controlword)
            elif st is WorkerState.FAULT_RESET:
                self.fault_reset_cycle += 1
                cw = cia402.fault_reset_controlword(self.fault_reset_cycle)
                for i in range(self.n):
                    faulted = states[i] == Cia402State.FAULT
                    bus.controlword[i] = cw if faulted else cia402.DISABLE_LUT[states[i]]
            else:  # QUICK_STOP, FAULT, ERROR
                np.take(cia402.QUICK_STOP_LUT, states, out=bus.controlword)
        np.copyto(self.ref_rows[cycle % _REF_HISTORY], self.ref)
        # ---- exchange
        wkc = bus.exchange()
        li[I_WKC] = wkc
        if wkc != li[I_WKC_EXP]:
            li[I_WKC_ERRORS] += 1
            self.wkc_bad_run += 1
            if self.wkc_bad_run == 1:
                self.wkc_alarmed = False       # a new burst may alarm again
            if self.wkc_bad_run > self.cfg.wkc_error_limit and not self.wkc_alarmed:
                self.wkc_alarmed = True
                lost = 0
                for pos in bus.lost_slaves():
                    lost |= 1 << min(pos, 62)
                self._reaction(AlarmCode.WORKING_COUNTER, -1, wkc, lost, float(li[I_WKC_EXP]))
                new = lost & ~self.lost_mask
                self.lost_mask |= lost
                li[I_LOST] = self.lost_mask
                for pos in range(63):
                    if new >> pos & 1:
                        self._alarm(AlarmCode.SLAVE_LOST, self._axis_of(pos), pos)
                self.recover_countdown = 0
            if self.lost_mask:
                self._try_recover()
            return
        self.wkc_bad_run = 0
        if self.lost_mask and not self.recover_busy:  # every slave answers again
            self._alarm(EventCode.SLAVE_RECOVERED, -1, self.lost_mask, self.recovered_mask)
            self.lost_mask = 0
            self.recovered_mask = 0
            li[I_LOST] = 0
        # ---- inputs and supervision
        cia402.decode_states(bus.statusword, states, self.scratch_i)
        self._read_actual()
        np.copyto(self.v["statusword"], bus.statusword)
        np.copyto(self.v["error_code"], bus.error_code)
        np.copyto(self.v["drive_state"], states)
        # following error against the set-point this actual position answers (bus delay)
        np.subtract(self.ref_rows[(cycle - self.cfg.tracking_delay_cycles) % _REF_HISTORY], self.act,
                    out=self.fe)
        # drive faults (FAULT or FAULT REACTION ACTIVE)
        np.take(_FAULTED_LUT, states, out=self.bool_tmp)
        if self.bool_tmp.any():
            for i in range(self.n):
                if self.bool_tmp[i] and not self.fault_seen[i]:
                    self.fault_seen[i] = True
                    self._reaction(AlarmCode.DRIVE_FAULT, i, int(bus.error_code[i]), state=WorkerState.FAULT)
            if self.state is not WorkerState.FAULT and self.state is not WorkerState.FAULT_RESET:
                self._set_state(WorkerState.FAULT)
        st = self.state
        if st is WorkerState.ENABLED or st is WorkerState.HOMING:
            # following error over its window for more than N cycles
            np.abs(self.fe, out=self.tmp)
            np.greater(self.tmp, self.window, out=self.bool_tmp)
            if st is WorkerState.HOMING:
                self.bool_tmp[self.homing_axis] = False
            np.add(self.fe_count, 1, out=self.fe_count)
            np.multiply(self.fe_count, self.bool_tmp, out=self.fe_count)   # reset where within
            if self.fe_count.max() > self.cfg.following_error_cycles:
                i = int(self.fe_count.argmax())
                self._reaction(AlarmCode.FOLLOWING_ERROR, i, f=float(self.fe[i]))
            elif st is WorkerState.ENABLED:
                # a drive leaving OPERATION ENABLED on its own (e.g. quick stop input)
                np.take(_NOT_ENABLED_LUT, states, out=self.bool_tmp)
                if self.bool_tmp.any():
                    i = int(np.argmax(self.bool_tmp))
                    self._reaction(AlarmCode.DRIVE_FAULT, i, int(bus.error_code[i]), int(states[i]) + 1)
                else:
                    self._track()
            if self.state is WorkerState.HOMING:
                self._homing_inputs()
        elif st is WorkerState.ENABLING:
            np.take(_NOT_ENABLED_LUT, states, out=self.bool_tmp)
            if not self.bool_tmp.any():
                self._hold_actual()
                self.moving = False
                self._set_state(WorkerState.ENABLED)
            elif self.state_cycles * self.cfg.ts_s > self.cfg.enable_timeout_s:
                i = int(np.argmax(self.bool_tmp))
                self._reaction(AlarmCode.ENABLE_TIMEOUT, i, int(states[i]), state=WorkerState.DISABLED)
        elif st is WorkerState.FAULT_RESET:
            np.take(_FAULTED_LUT, states, out=self.bool_tmp)
            if not self.bool_tmp.any():
                self.fault_seen[:] = False
                self._hold_actual()
                self._set_state(WorkerState.DISABLED)
            elif self.state_cycles * self.cfg.ts_s > self.cfg.fault_reset_timeout_s:
                i = int(np.argmax(states == Cia402State.FAULT))
                self._alarm(AlarmCode.FAULT_RESET_FAILED, i, int(bus.error_code[i]))
                self._set_state(WorkerState.FAULT)
        if self.state is not WorkerState.ENABLED and self.state is not WorkerState.HOMING:
            np.copyto(self.ref, self.act)
            self.fe.fill(0.0)

    def _track(self) -> None:
        """Tracking error per axis against the set-point of `tracking_delay_cycles` ago (Eq. 18)."""
        cycle = int(self.li[I_CYCLE])
        ref_d = self.ref_rows[(cycle - self.cfg.tracking_delay_cycles) % _REF_HISTORY]
        e = self.e
        np.copyto(e, self.fe)                      # = ref_d - act, computed in cycle()
        v = self.v
        np.abs(e, out=self.tmp)
        np.maximum(v["max_e"], self.tmp, out=v["max_e"])
        np.multiply(e, e, out=e)
        np.add(v["sum_e2"], e, out=v["sum_e2"])
        self.li[I_TRACK_N] += 1
        np.add(self.block_acc, e, out=self.block_acc)
        self.block_acc_n += 1
        if self.block_acc_n >= self.block_cycles:
            k = self.block_index % len(self.blocks)
            self.blocks[k] = self.block_acc
            self.blocks_n[k] = self.block_acc_n
            self.block_index += 1
            self.block_acc[:] = 0.0
            self.block_acc_n = 0
            self.blocks.sum(axis=0, out=v["win_e2"])
            self.li[I_WIN_N] = int(self.blocks_n.sum())
        if self.trace_cap:
            h = int(self.ctl[C_TRACE_HEAD])
            row = self.trace[h % self.trace_cap]
            row[0] = cycle
            row[1:1 + self.n] = ref_d
            row[1 + self.n:] = self.act
            self.ctl[C_TRACE_HEAD] = h + 1

    def _homing_outputs(self) -> None:
        bus = self.bus
        assert bus is not None
        a = self.homing_axis
        cia402.units_to_counts(self.ref, self.gain, self.offset, bus.target_position, self.tmp2)
        bus.controlword[:] = cia402.CW_ENABLE_OPERATION
        bus.target_position[a] = bus.position_actual[a]
        if 1 <= self.homing_phase <= 2:
            bus.controlword[a] = cia402.CW_ENABLE_OPERATION | cia402.CW_HOMING_START

    def _homing_inputs(self) -> None:
        bus = self.bus
        assert bus is not None
        a = self.homing_axis
        sw = int(bus.statusword[a])
        self.ref[a] = self.act[a]
        self.fe[a] = 0.0
        if self.homing_phase == 0:
            if int(bus.modes_display[a]) == cia402.HOMING:
                self.homing_phase = 1            # mode active: raise bit 4 next cycle
        elif self.homing_phase == 1:
            self.homing_phase = 2                # bit 4 sent; wait for the result
            self.homing_wait = 0
        elif self.homing_phase == 2 and self.homing_wait < 2:
            self.homing_wait += 1                # let the drive see the edge before judging
        elif self.homing_phase == 2:
            attained = sw & cia402.SW_HOMING_ATTAINED and sw & cia402.SW_TARGET_REACHED
            error = sw & cia402.SW_HOMING_ERROR
            timeout = self.state_cycles * self.cfg.ts_s > self.cfg.homing_timeout_s
            if attained or error or timeout:
                ok = bool(attained) and not error
                self.v["homing"][a] = HomingState.DONE if ok else HomingState.ERROR
                self.v["homed"][a] = 1 if ok else 0
                bus.modes_of_operation[a] = cia402.CSP
                self.homing_phase = 3
                if not ok:
                    self._alarm(AlarmCode.HOMING_ERROR, a, 1 if timeout else 0)
        elif self.homing_phase == 3:
            if int(bus.modes_display[a]) == cia402.CSP:
                self.homing_axis = -1
                self._hold_actual()
                self._set_state(WorkerState.ENABLED)

    # ------------------------------------------------------------------ snapshot / run
    def publish(self) -> None:
        """Seqlock copy of the live block into the snapshot block."""
        c = self.ctl
        c[C_SNAP_SEQ] += 1
        np.copyto(self.v["snap_bytes"], self.v["live_bytes"])
        c[C_SNAP_SEQ] += 1

    def run_manual(self, n_cycles: int) -> None:
        for _ in range(n_cycles):
            self.cycle()
        self.publish()

    def run_realtime(self, default_spin_s: float = 0.0) -> None:
        """The cyclic loop on absolute deadlines until CMD_STOP."""
        cfg = self.cfg
        ts = cfg.ts_s
        spin = cfg.spin_s if cfg.spin_s is not None else default_spin_s
        min_sleep = cfg.min_sleep_s
        late_s = cfg.late_threshold_s
        li, lf, hist = self.li, self.lf, self.v["hist"]
        perf = time.perf_counter
        sleep_until = _AbsoluteSleep().until
        _set_timer_slack_ns(1)                   # normal threads: 50 us slack by default
        inv_bin = 1.0 / _HIST_BIN_S
        last_bin = _HIST_BINS - 1
        every = self.snapshot_every
        deadline = perf() + ts
        prev_start = 0.0
        k_snap = 0
        missed = 0
        self.publish_now = True                  # publish after the first cycle
        while not self.stop_requested:
            # sleep to `spin` before the deadline (absolute), and always at least min_sleep,
            # then busy-wait the rest: bounded by `spin`, none when already late
            wake = deadline - spin
            earliest = perf() + min_sleep
            sleep_until(wake if wake > earliest else earliest)
            while perf() < deadline:
                pass
            start = perf()
            jitter = start - deadline
            li[I_MISSED] += missed               # counted when the deadline after them starts
            missed = 0
            try:
                self.cycle()
            except Exception as exc:  # noqa: BLE001 - any bus failure ends the loop with an alarm
                _write_msg(self.v, f"{type(exc).__name__}: {exc}")
                self._alarm(AlarmCode.BUS_ERROR)
                self._set_state(WorkerState.ERROR)
                self.publish()
                return
            end = perf()
            # timing records
            if prev_start > 0.0:
                period = start - prev_start
                lf[F_PERIOD_SUM] += period
                if period < lf[F_PERIOD_MIN]:
                    lf[F_PERIOD_MIN] = period
                if period > lf[F_PERIOD_MAX]:
                    lf[F_PERIOD_MAX] = period
                li[I_TIMED] += 1
                b = int(jitter * inv_bin)
                hist[b if b < last_bin else last_bin] += 1
                if jitter > lf[F_JITTER_MAX]:
                    lf[F_JITTER_MAX] = jitter
                if jitter > late_s:
                    li[I_LATE] += 1
                ex = end - start
                lf[F_EXEC_SUM] += ex
                if ex > lf[F_EXEC_MAX]:
                    lf[F_EXEC_MAX] = ex
            else:
                lf[F_FIRST_START] = start
            lf[F_LAST_START] = start
            prev_start = start
            deadline += ts
            if end - deadline >= ts:              # overran by whole periods: skip them, stay on grid
                missed = int((end - deadline) / ts)
                deadline += missed * ts
            k_snap += 1
            if k_snap >= every or self.publish_now:
                k_snap = 0
                self.publish_now = False
                self.publish()
        self.publish()


# ---------------------------------------------------------------------- timing helpers
class _Timespec(ctypes.Structure):
    _fields_ = [("tv_sec", ctypes.c_long), ("tv_nsec", ctypes.c_long)]


class _AbsoluteSleep:
    """Sleep until an absolute `time.perf_counter()` instant: clock_nanosleep(CLOCK_MONOTONIC,
    TIMER_ABSTIME) through ctypes where perf_counter is CLOCK_MONOTONIC (Linux), so the
    time spent between reading the clock and going to sleep does not shift the wake-up;
    `time.sleep` of the remainder elsewhere. ctypes releases the GIL while sleeping."""

    def __init__(self) -> None:
        self._fn: Any = None
        with contextlib.suppress(Exception):
            if "CLOCK_MONOTONIC" in time.get_clock_info("perf_counter").implementation:
                fn = ctypes.CDLL(None, use_errno=True).clock_nanosleep
                fn.argtypes = [ctypes.c_int, ctypes.c_int, ctypes.POINTER(_Timespec), ctypes.c_void_p]
                fn.restype = ctypes.c_int
                self._ts = _Timespec()
                self._ref = ctypes.byref(self._ts)
                self._fn = fn

    def until(self, t: float) -> None:
        fn = self._fn
        if fn is None:
            remaining = t - time.perf_counter()
            if remaining > 0.0:
                time.sleep(remaining)
            return
        sec = int(t)
        ts = self._ts
        ts.tv_sec = sec
        ts.tv_nsec = int((t - sec) * 1e9)
        while fn(1, 1, self._ref, None) == 4:    # CLOCK_MONOTONIC, TIMER_ABSTIME; EINTR: again
            pass


def _set_timer_slack_ns(ns: int) -> None:
    """prctl(PR_SET_TIMERSLACK) for the calling thread (real-time threads have none anyway)."""
    if sys.platform.startswith("linux"):
        with contextlib.suppress(Exception):
            ctypes.CDLL(None, use_errno=True).prctl(29, ctypes.c_ulong(ns), 0, 0, 0)


# ---------------------------------------------------------------------- process entry
CPU_LOCK_DIR = "/dev/shm"


def _cpu_lock_path(cpu: int) -> str:
    return os.path.join(CPU_LOCK_DIR, f"cnc-ethercat-cpu{cpu}.lock")


def _try_lock_cpu(cpu: int) -> tuple[int | None, str]:
    """Take the per-core lock (flock, released by the kernel when the process ends).
    Returns (fd or None, holder pid text when held by another worker)."""
    import fcntl

    try:
        fd = os.open(_cpu_lock_path(cpu), os.O_RDWR | os.O_CREAT, 0o666)
    except OSError:
        return None, ""
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        holder = os.pread(fd, 32, 0).decode("ascii", "replace").strip() or "?"
        os.close(fd)
        return None, holder
    os.ftruncate(fd, 0)
    os.pwrite(fd, str(os.getpid()).encode(), 0)
    return fd, ""


def _pinned_rt_tasks() -> dict[int, list[str]]:
    """User-space processes (not kernel threads, not this one) running SCHED_FIFO/RR pinned
    to a single core: {core: ["pid<N>:fifo<P>", ...]}. Catches workers that hold no core
    lock (older versions) and other real-time programs. One /proc scan, at start-up only."""
    out: dict[int, list[str]] = {}
    me = os.getpid()
    try:
        pids = [int(d) for d in os.listdir("/proc") if d.isdigit()]
    except OSError:
        return out
    for pid in pids:
        if pid == me:
            continue
        try:
            with open(f"/proc/{pid}/stat", "rb") as f:
                fields = f.read().rsplit(b")", 1)[1].split()
            policy, prio = int(fields[38]), int(fields[37])   # stat fields 41 and 40
            if policy not in (1, 2):                         # SCHED_FIFO, SCHED_RR
                continue
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                if not f.read(1):                            # kernel thread
                    continue
            cpus = os.sched_getaffinity(pid)
        except (OSError, ValueError, IndexError):
            continue
        if len(cpus) == 1:
            out.setdefault(next(iter(cpus)), []).append(f"pid{pid}:{'fifo' if policy == 1 else 'rr'}{prio}")
    return out


def _set_realtime(cfg: WorkerConfig) -> tuple[str, int | None]:
    """Choose and pin a core, SCHED_FIFO when permitted, lock memory.
    Returns (what was applied, fd of the core lock to keep open)."""
    done: list[str] = []
    lock_fd: int | None = None
    realtime_ok = True
    if cfg.cpu is not None and hasattr(os, "sched_setaffinity"):
        cpus = sorted(os.sched_getaffinity(0))
        if cfg.cpu >= 0:                       # explicit: honoured even when shared
            cpu = cfg.cpu if cfg.cpu in cpus else cpus[-1]
            lock_fd, holder = _try_lock_cpu(cpu)
            if holder:
                done.append(f"shared-with-pid{holder}")
        else:                                  # automatic: a core no other worker holds
            cpu = -1
            held = []
            rt_tasks = _pinned_rt_tasks()
            for c in reversed(cpus):
                if c in rt_tasks:               # a real-time task (an older worker?) is pinned there
                    held.append(f"cpu{c}:{'+'.join(rt_tasks[c])}")
                    continue
                lock_fd, holder = _try_lock_cpu(c)
                if lock_fd is not None:
                    cpu = c
                    break
                if holder:
                    held.append(f"cpu{c}:pid{holder}")
            if cpu < 0 and held:
                realtime_ok = False            # every core has a worker: do not compete with it
                done.append("no-free-cpu(" + ",".join(held) + ")")
            elif cpu < 0:
                cpu = cpus[-1]                 # locks unavailable: previous behaviour
        if cpu >= 0:
            with contextlib.suppress(OSError):
                os.sched_setaffinity(0, {cpu})
                done.append(f"cpu{cpu}")
    if realtime_ok and cfg.rt_priority > 0 and hasattr(os, "sched_setscheduler"):
        try:
            os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(cfg.rt_priority))
            done.append(f"fifo{cfg.rt_priority}")
        except (OSError, PermissionError):
            done.append("fifo-denied")
    with contextlib.suppress(Exception):
        libc = ctypes.CDLL(None, use_errno=True)
        if libc.mlockall(3) == 0:            # MCL_CURRENT | MCL_FUTURE
            done.append("mlock")
    return ",".join(done), lock_fd


def _write_msg(v: dict[str, np.ndarray], text: str) -> None:
    data = text.encode("utf-8", "replace")[: _MSG_BYTES - 1]
    msg = v["msg"]
    msg[:] = 0
    msg[: len(data)] = np.frombuffer(data, dtype=np.uint8)


def _read_msg(v: dict[str, np.ndarray]) -> str:
    return bytes(v["msg"]).split(b"\0", 1)[0].decode("utf-8", "replace")


def _process_main(cfg: WorkerConfig, shm_name: str, layout_args: tuple[int, int, int]) -> None:
    shm = shared_memory.SharedMemory(name=shm_name)
    v = _Layout(*layout_args).views(shm.buf)
    loop = _Loop(cfg, v)
    lock_fd: int | None = None
    try:
        try:
            applied, lock_fd = _set_realtime(cfg)
            loop.open_bus()
        except Exception as exc:  # noqa: BLE001 - reported to the parent as text
            _write_msg(v, f"{type(exc).__name__}: {exc}")
            v["ctl"][C_STATUS] = ST_FAILED
            return
        _write_msg(v, applied)
        v["ctl"][C_PID] = os.getpid()
        loop.publish()
        v["ctl"][C_STATUS] = ST_RUNNING
        gc.collect()
        gc.freeze()
        gc.disable()
        # helper threads (parent watch, slave recovery) must not keep the GIL from the cycle
        # for the default 5 ms switch interval
        sys.setswitchinterval(0.0002)
        parent = os.getppid()
        watcher = threading.Thread(target=_parent_watch, args=(loop, parent), daemon=True)
        watcher.start()
        loop.run_realtime(default_spin_s=PROCESS_SPIN_S)
    finally:
        with contextlib.suppress(Exception):
            loop.close_bus()
        v["ctl"][C_STATUS] = ST_STOPPED
        del v, loop
        shm.close()
        if lock_fd is not None:
            os.close(lock_fd)                # the core is free for the next worker


def _parent_watch(loop: _Loop, parent_pid: int) -> None:
    """Stop the loop when the parent process is gone (checked every 0.2 s)."""
    while not loop.stop_requested:
        time.sleep(0.2)
        if os.getppid() != parent_pid:
            loop.stop_requested = True


def _start_without_main(process: Any) -> None:
    """Start a spawn process without re-running the caller's `__main__` in the child.

    spawn normally re-imports the main script, which starts the worker again in scripts
    without an `if __name__ == "__main__"` guard. The child only needs `ethercat.worker`,
    so the main module is hidden while the preparation data is taken.
    """
    main = sys.modules.get("__main__")
    sys.modules["__main__"] = types.ModuleType("__main__")
    try:
        process.start()
    finally:
        if main is not None:
            sys.modules["__main__"] = main


# ---------------------------------------------------------------------- the API
class CyclicWorker:
    """The controller-facing handle of the cyclic worker. See the module docstring.

    All methods are called from one controller thread (or guarded by the caller); they
    never block for more than `command_timeout_s`.
    """

    def __init__(self, config: WorkerConfig) -> None:
        self.config = config
        n = config.n_axes
        self._layout = _Layout(n, config.buffer_capacity, config.trace_capacity)
        self._shm: shared_memory.SharedMemory | None = None
        self._buf: bytearray | None = None
        self._v: dict[str, np.ndarray] | None = None
        self._loop: _Loop | None = None
        self._thread: threading.Thread | None = None
        self._process: Any = None
        self._lock = threading.RLock()   # one command in flight; push/replace own C_HEAD
        self._alarms: list[Alarm] = []
        self._events: collections.deque[WorkerEvent] = collections.deque(maxlen=_EVENTS_KEPT)
        self._alarms_read = 0
        self._cmd_sent = 0                      # sequence number of the last command sent
        self._reasons: dict[int, str] = {}      # command seq -> quick stop / E-stop reason
        self._trace_read = 0
        self._started = False
        self.realtime_applied = ""

    # ------------------------------------------------------------------ life cycle
    @property
    def running(self) -> bool:
        return self._started

    def start(self) -> None:
        """Open the bus and start the cycle; returns when the drives are DISABLED and
        process data runs. Raises `WorkerError` (with the bus error text) on failure."""
        if self._started:
            return
        cfg = self.config
        self._alarms.clear()
        self._events.clear()
        self._alarms_read = 0
        self._cmd_sent = 0
        self._trace_read = 0
        self._reasons.clear()
        if cfg.mode == "process":
            self._shm = shared_memory.SharedMemory(create=True, size=self._layout.size)
            self._v = self._layout.views(self._shm.buf)
        else:
            self._buf = bytearray(self._layout.size)
            self._v = self._layout.views(self._buf)
        self._v["ctl"][:] = 0
        args = (self._layout.n, self._layout.capacity, self._layout.trace_capacity)
        try:
            if cfg.mode == "process":
                ctx = mp.get_context("spawn")
                self._process = ctx.Process(target=_process_main, args=(cfg, self._shm.name, args),  # type: ignore[union-attr]
                                            name="ethercat-worker", daemon=True)
                _start_without_main(self._process)
                self._wait_status(cfg.start_timeout_s)
                self.realtime_applied = _read_msg(self._v)
            else:
                self._loop = _Loop(cfg, self._v)
                self._loop.open_bus()
                self._loop.publish()
                if cfg.mode == "thread":
                    self._thread = threading.Thread(target=self._thread_main, name="ethercat-worker",
                                                    daemon=True)
                    self._thread.start()
        except BaseException:
            self._cleanup()
            raise
        self._started = True
        atexit.register(self.stop)             # drives disabled and bus closed at interpreter exit

    def _thread_main(self) -> None:
        assert self._loop is not None
        try:
            self._loop.run_realtime()
        finally:
            self._loop.close_bus()

    def _wait_status(self, timeout_s: float) -> None:
        assert self._v is not None
        t_end = time.monotonic() + timeout_s
        ctl = self._v["ctl"]
        while time.monotonic() < t_end:
            status = int(ctl[C_STATUS])
            if status == ST_RUNNING:
                return
            if status == ST_FAILED:
                raise WorkerError(f"worker failed to start: {_read_msg(self._v)}")
            if self._process is not None and not self._process.is_alive():
                raise WorkerError(f"worker process exited with code {self._process.exitcode}")
            time.sleep(0.005)
        raise WorkerTimeoutError(f"worker did not start within {timeout_s} s")

    def stop(self) -> None:
        """Disable the drives, close the bus, end the loop. Stopping twice is harmless."""
        if not self._started:
            return
        atexit.unregister(self.stop)
        try:
            with contextlib.suppress(WorkerError):
                self._command(CMD_STOP)
            if self._thread is not None:
                self._thread.join(timeout=5.0)
            if self._process is not None:
                self._process.join(timeout=5.0)
                if self._process.is_alive():
                    self._process.terminate()
                    self._process.join(timeout=2.0)
            if self.config.mode == "manual" and self._loop is not None:
                self._loop.close_bus()
        finally:
            self._started = False
            self._cleanup()

    def _cleanup(self) -> None:
        self._thread = None
        self._process = None
        if self._shm is not None:
            shm = self._shm
            self._v = None
            self._shm = None
            with contextlib.suppress(Exception):
                shm.close()
            with contextlib.suppress(Exception):
                shm.unlink()

    def __enter__(self) -> CyclicWorker:
        self.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()

    def __del__(self) -> None:  # pragma: no cover - best effort
        with contextlib.suppress(Exception):
            self.stop()

    # ------------------------------------------------------------------ commands
    def _views(self) -> dict[str, np.ndarray]:
        if not self._started or self._v is None:
            raise WorkerError("worker is not running: call start() first")
        return self._v

    def _command(self, code: int, a: int = 0, b: int = 0, reason: str = "") -> bool:
        return self._command_result(code, a, b, reason) == RESULT_OK

    def _command_result(self, code: int, a: int = 0, b: int = 0, reason: str = "") -> int:
        v = self._v
        if v is None:
            raise WorkerError("worker is not running")
        with self._lock:
            ctl = v["ctl"]
            ctl[C_CMD_CODE] = code
            ctl[C_CMD_A] = a
            ctl[C_CMD_B] = b
            seq = int(ctl[C_CMD_SEQ]) + 1
            if reason:
                self._reasons[seq] = reason
            self._cmd_sent = seq
            ctl[C_CMD_SEQ] = seq
            if self.config.mode == "manual":
                assert self._loop is not None
                self._loop.poll_command()
                self._loop.publish()
            else:
                t_end = time.monotonic() + self.config.command_timeout_s
                while int(ctl[C_CMD_ACK]) != seq:
                    if time.monotonic() > t_end:
                        raise WorkerTimeoutError(f"worker did not acknowledge command {code} "
                                                 f"within {self.config.command_timeout_s} s")
                    if int(ctl[C_STATUS]) in (ST_STOPPED, ST_FAILED) and self._process is not None:
                        raise WorkerError("worker process has stopped")
                    if self._thread is not None and not self._thread.is_alive():
                        raise WorkerError("worker thread has stopped")
                    time.sleep(0.0005)
            return int(ctl[C_CMD_RESULT])

    def enable(self) -> None:
        """Walk every drive to OPERATION ENABLED (target := actual first). Returns at once;
        watch `snapshot().state` for ENABLED. Refused (WorkerError) in FAULT: fault_reset()."""
        self._views()
        if not self._command(CMD_ENABLE):
            raise WorkerError(f"enable refused in state {self.state().name}")

    def disable(self) -> None:
        """Shut the drives down to READY TO SWITCH ON; the buffer is flushed."""
        self._views()
        self._command(CMD_DISABLE)

    def fault_reset(self) -> None:
        """Fault reset edge to faulted drives, clear the worker's alarms -> DISABLED."""
        self._views()
        self.snapshot()              # collect alarms raised so far, then clear them
        self._command(CMD_FAULT_RESET)
        self._alarms.clear()

    def quick_stop(self, reason: str = "quick stop requested") -> None:
        """Quick stop of all axes, buffer flushed, alarm QUICK_STOP with `reason`."""
        self._views()
        self._command(CMD_QUICK_STOP, reason=reason or "requested")

    def estop(self, reason: str = "E-stop") -> None:
        """E-stop input: quick stop of all axes and alarm ESTOP."""
        self._views()
        self._command(CMD_ESTOP, reason=reason or "E-stop")

    def home(self, axis: int | str, method: int = 35) -> None:
        """Start the drive's own homing (CiA 402 mode 6, method 0x6098) on one axis.
        Only when ENABLED and at rest; watch `snapshot().homing[axis]`."""
        self._views()
        i = self._axis_index(axis)
        if not self._command(CMD_HOME, i, int(method)):
            raise WorkerError(f"homing axis {self.config.axis_names[i]} refused in state {self.state().name} "
                              "(needs ENABLED, buffer empty, method accepted by the drive)")

    def set_digital_output(self, axis: int | str, value: int) -> None:
        """Write the drive's digital outputs 0x60FE:1 (spindle on/direction bits)."""
        self._views()
        if not self._command(CMD_DOUT, self._axis_index(axis), int(value)):
            raise WorkerError("digital output refused")

    def inject(self, name: str, axis: int | str = 0, value: int = 0) -> None:
        """SimBus fault injection through the worker (any mode): names as
        `sim_bus.INJECTIONS`; `value` = error code or frame count."""
        self._views()
        if name not in INJECT_NAMES:
            raise ConfigurationError(f"unknown injection {name!r}; known: {INJECT_NAMES}")
        code = INJECT_NAMES.index(name) | (int(value) << 8)
        if not self._command(CMD_INJECT, self._axis_index(axis), code):
            raise WorkerError(f"injection {name!r} needs bus_kind='sim'")

    def flush(self) -> None:
        """Drop the set-points not yet sent."""
        self._views()
        self._command(CMD_FLUSH)

    def reset_tracking(self) -> None:
        """Zero the RMSE/MSE accumulators (start of a run)."""
        self._views()
        self._command(CMD_RESET_TRACKING)

    def _axis_index(self, axis: int | str) -> int:
        if isinstance(axis, str):
            try:
                return self.config.axis_names.index(axis)
            except ValueError:
                raise ConfigurationError(f"unknown axis {axis!r}; axes: {self.config.axis_names}") from None
        if not 0 <= axis < self.config.n_axes:
            raise ConfigurationError(f"axis index {axis} out of range")
        return int(axis)

    # ------------------------------------------------------------------ set-points
    def free_space(self) -> int:
        """Set-points `push` can accept now."""
        ctl = self._views()["ctl"]
        return self.config.buffer_capacity - int(ctl[C_HEAD] - ctl[C_TAIL])

    def buffer_level(self) -> int:
        ctl = self._views()["ctl"]
        return int(ctl[C_HEAD] - ctl[C_TAIL])

    def push(self, q: np.ndarray) -> int:
        """Append set-points (N, n_axes) in axis units (mm | deg), one per cycle. Returns how
        many were accepted (the ring is bounded: push the rest later). They are consumed
        only while ENABLED; `enable()`, `disable()`, `fault_reset()` and every reaction
        (quick stop) flush the buffer, so push after `enable()`, starting at the actual
        position."""
        v = self._views()
        q = np.asarray(q, dtype=np.float64)
        if q.ndim == 1:
            q = q.reshape(1, -1)
        if q.ndim != 2 or q.shape[1] != self.config.n_axes:
            raise ConfigurationError(f"push expects (N, {self.config.n_axes}) set-points, got {q.shape}")
        if not np.isfinite(q).all():
            raise ConfigurationError("push: set-points must be finite")
        ctl = v["ctl"]
        cap = self.config.buffer_capacity
        with self._lock:                # head is ours, except while a replace() is in flight
            head = int(ctl[C_HEAD])
            n = min(len(q), cap - (head - int(ctl[C_TAIL])))
            if n <= 0:
                return 0
            ring = v["ring"]
            start = head % cap
            first = min(n, cap - start)
            ring[start:start + first] = q[:first]
            if n > first:
                ring[: n - first] = q[first:n]
            ctl[C_HEAD] = head + n      # publish after the data (x86: stores in order)
        return n

    def replace(self, from_serial: int, q: np.ndarray) -> int:
        """Atomically drop every queued set-point with serial >= `from_serial` and queue `q`
        (N, n_axes) in their place. Serial k is the k-th set-point the loop takes since
        `start()` (`samples_consumed()` is the serial it takes next; a flush drops queued
        serials without taking them, so the next push continues at `samples_consumed()`).

        The loop applies it between two cycles: the drives see the old set-points up to
        `from_serial - 1`, then `q[0]`, never a gap or a mix. Returns how many of `q` were
        queued (the ring is bounded: push the rest later), or `REPLACE_TOO_LATE` (-1) when
        the loop had already taken `from_serial` (retry from a later serial), or
        `REPLACE_BEYOND_END` (-2) when `from_serial` is past the queue's end; nothing changed
        then. Blocks until the loop acknowledges (about one cycle; at once in "manual").

        Protocol (shared memory, single producer = this handle, single consumer = the loop):
        `q` goes to the staging area; then the command mailbox (code, from_serial, n) and
        last its sequence number. The loop reads the mailbox at the top of a cycle, checks
        `from_serial` against its own consumed count, copies the staging area into the ring
        at the matching index and sets `C_HEAD` itself, then writes result and ack. While the
        command is in flight the producer holds `_lock` (push() waits), so `C_HEAD` has one
        writer at any time and the staging area is never read and written at once. Ordering
        relies on x86-64 total store order (stores are seen in program order) as the ring
        does; NumPy copies and int64 stores of aligned slots are not reordered by Python.
        """
        v = self._views()
        q = np.asarray(q, dtype=np.float64)
        if q.ndim == 1:
            q = q.reshape(1, -1)
        if q.ndim != 2 or q.shape[1] != self.config.n_axes:
            raise ConfigurationError(f"replace expects (N, {self.config.n_axes}) set-points, got {q.shape}")
        if not np.isfinite(q).all():
            raise ConfigurationError("replace: set-points must be finite")
        from_serial = int(from_serial)
        cap = self.config.buffer_capacity
        with self._lock:
            # room from from_serial on, judged now; the loop only makes more by consuming
            kept = max(0, from_serial - int(v["li"][I_CONSUMED]))
            n = max(0, min(len(q), cap - kept))
            v["stage"][:n] = q[:n]
            result = self._command_result(CMD_REPLACE, from_serial, n)
        if result == RESULT_OK:
            return n
        if result == RESULT_TOO_LATE:
            return REPLACE_TOO_LATE
        if result == RESULT_BEYOND_END:
            return REPLACE_BEYOND_END
        raise WorkerError(f"replace refused (result {result})")

    def samples_consumed(self) -> int:
        """Live serial the loop takes next (= set-points taken since start), read from the
        shared block at once (not the 30 Hz snapshot). One aligned int64 load."""
        return int(self._views()["li"][I_CONSUMED])

    # ------------------------------------------------------------------ manual mode
    def step(self, n_cycles: int = 1) -> None:
        """Manual mode only: run `n_cycles` cycles now (simulated time)."""
        if self.config.mode != "manual":
            raise WorkerError("step() is only available in mode='manual'")
        self._views()
        assert self._loop is not None
        self._loop.run_manual(int(n_cycles))

    # ------------------------------------------------------------------ reading
    def state(self) -> WorkerState:
        if not self._started or self._v is None:
            return WorkerState.STOPPED
        return WorkerState(int(self._v["snap_li"][I_STATE]))

    @property
    def command_seq(self) -> int:
        """Sequence number of the last command sent (compare `WorkerSnapshot.command_seq`)."""
        return self._cmd_sent

    def wait_for(self, states: WorkerState | Sequence[WorkerState], timeout_s: float = 2.0) -> WorkerState:
        """Wait (polling snapshots) until the worker is in one of `states`, judged only on
        snapshots taken after at least one cycle ran and after the loop applied the last
        command sent through this handle: a snapshot published before that (they come at
        `snapshot_hz`, plus one right after each command) is stale and ignored."""
        wanted = (states,) if isinstance(states, WorkerState) else tuple(states)
        t_end = time.monotonic() + timeout_s
        need = self._cmd_sent
        while True:
            if self.config.mode == "manual":
                self.step(10)
            li = self._read_snapshot_li()
            st = WorkerState(int(li[I_STATE]))
            fresh = int(li[I_CMD_APPLIED]) >= need and int(li[I_CYCLE]) > 0
            if fresh and st in wanted:
                return st
            if time.monotonic() > t_end:
                stale = "" if fresh else f" (no snapshot yet after command {need})"
                names = [s.name for s in wanted]
                raise WorkerTimeoutError(f"worker in state {st.name}{stale}, wanted {names}")
            if self.config.mode != "manual":
                time.sleep(0.002)

    def _read_snapshot_li(self) -> np.ndarray:
        """Seqlock read of the snapshot's integer scalars only (cheap, for polling)."""
        v = self._views()
        ctl = v["ctl"]
        for _ in range(1000):
            s1 = int(ctl[C_SNAP_SEQ])
            if s1 & 1:
                time.sleep(0)
                continue
            li = v["snap_li"].copy()
            if int(ctl[C_SNAP_SEQ]) == s1:
                return li
        raise WorkerTimeoutError("snapshot: writer never stable")

    def _read_snapshot_block(self) -> dict[str, np.ndarray]:
        v = self._views()
        ctl = v["ctl"]
        out: dict[str, np.ndarray] = {}
        for _ in range(1000):
            s1 = int(ctl[C_SNAP_SEQ])
            if s1 & 1:
                time.sleep(0)
                continue
            raw = v["snap_bytes"].copy()
            if int(ctl[C_SNAP_SEQ]) == s1:
                lay = self._layout
                base = lay.fields["snap_li"][0]
                for name in ("li", "lf", "drive_state", "statusword", "error_code", "homing", "homed", "dout",
                             "act", "ref", "fe", "sum_e2", "win_e2", "max_e", "hist"):
                    o, dt, shape = lay.fields["snap_" + name]
                    arr = np.ndarray(shape, dtype=dt, buffer=raw, offset=o - base)
                    arr.setflags(write=False)
                    out[name] = arr
                return out
        raise WorkerTimeoutError("snapshot: writer never stable")

    def _collect_alarms(self) -> None:
        v = self._v
        assert v is not None
        total = int(v["ctl"][C_ALARMS])
        start = max(self._alarms_read, total - _ALARM_SLOTS)
        names = self.config.axis_names
        ts = self.config.ts_s
        for k in range(start, total):
            row = v["alarm"][k % _ALARM_SLOTS].copy()
            f = float(v["alarm_f"][k % _ALARM_SLOTS])
            axis_i, cycle, a, b = int(row[1]), int(row[2]), int(row[3]), int(row[4])
            axis = names[axis_i] if 0 <= axis_i < len(names) else ""
            if int(row[0]) >= 100:
                ecode = EventCode(int(row[0]))
                self._events.append(WorkerEvent(ecode, self._event_message(ecode, a, b), axis, cycle,
                                                cycle * ts, time.time()))
                continue
            code = AlarmCode(int(row[0]))
            commanded = code in (AlarmCode.ESTOP, AlarmCode.QUICK_STOP)
            reason = self._reasons.pop(int(row[5]), "") if commanded else ""
            msg = self._alarm_message(code, axis, axis_i, a, b, f, reason)
            self._alarms.append(Alarm(code, msg, axis, cycle, cycle * ts, time.time()))
        self._alarms_read = total

    def _slave_text(self, position: int) -> str:
        for d in self.config.drives:
            if d.position == position:
                return f"slave {position} (axis {d.axis_name})"
        return f"slave {position}"

    def _event_message(self, code: EventCode, a: int, b: int) -> str:
        if code is EventCode.SLAVE_RECOVERED:
            back = ", ".join(self._slave_text(p) for p in range(63) if a >> p & 1)
            how = " (re-configured to OP by recover_slaves)" if b else ""
            return (f"{back} answering again{how}: working counter as expected; "
                    "fault reset and enable to resume")
        return code.name

    def _alarm_message(self, code: AlarmCode, axis: str, axis_i: int, a: int, b: int, f: float,
                       reason: str = "") -> str:
        cfg = self.config
        if code is AlarmCode.UNDERRUN:
            return f"set-point buffer underrun after {a} set-points: holding the last position"
        if code is AlarmCode.WORKING_COUNTER:
            lost = [p for p in range(63) if b >> p & 1]
            tail = f"; slaves not answering: {lost}" if lost else ""
            return (f"working counter {a} instead of {int(f)} for more than {cfg.wkc_error_limit} cycles: "
                    f"quick stop of all axes{tail}")
        if code is AlarmCode.DRIVE_FAULT:
            pos = cfg.drives[axis_i].position
            if b:
                return (f"drive of axis {axis} (slave {pos}) left OPERATION ENABLED "
                        f"({Cia402State(b - 1).name}): quick stop of all axes")
            return (f"drive fault on axis {axis} (slave {pos}): error code 0x{a:04X} {error_code_text(a)}: "
                    "quick stop of all axes")
        if code is AlarmCode.FOLLOWING_ERROR:
            w = cfg.drives[axis_i].following_error_window
            return (f"following error on axis {axis}: {f:+.4f} exceeds window {w:g} for more than "
                    f"{cfg.following_error_cycles} cycles: quick stop of all axes")
        if code is AlarmCode.ESTOP:
            return f"E-stop: quick stop of all axes ({reason or 'E-stop'})"
        if code is AlarmCode.QUICK_STOP:
            return f"quick stop of all axes: {reason or 'requested'}"
        if code is AlarmCode.ENABLE_TIMEOUT:
            state = Cia402State(a).name if 0 <= a < len(Cia402State) else str(a)
            return (f"axis {axis} did not reach OPERATION ENABLED within {cfg.enable_timeout_s} s "
                    f"(drive state {state})")
        if code is AlarmCode.HOMING_ERROR:
            return f"homing of axis {axis} failed ({'timeout' if a else 'drive reported homing error'})"
        if code is AlarmCode.FAULT_RESET_FAILED:
            return (f"fault reset of axis {axis} failed: error code 0x{a:04X} {error_code_text(a)} "
                    "still present")
        if code is AlarmCode.SLAVE_LOST:
            return (f"{self._slave_text(a)} lost: not answering process data; "
                    "trying to recover it when it comes back")
        if code is AlarmCode.BUS_ERROR:
            detail = _read_msg(self._v) if self._v is not None else ""
            return f"bus error in the cyclic loop ({detail}): worker stopped"
        return code.name

    def alarms(self) -> tuple[Alarm, ...]:
        """Active alarms (cleared by `fault_reset`)."""
        if self._v is not None:
            self._collect_alarms()
        return tuple(self._alarms)

    def events(self) -> tuple[WorkerEvent, ...]:
        """Recent events (the last 32; not cleared by `fault_reset`), oldest first."""
        if self._v is not None:
            self._collect_alarms()
        return tuple(self._events)

    def snapshot(self) -> WorkerSnapshot:
        """A consistent copy of the worker's state (seqlock read; about 20 us)."""
        cfg = self.config
        s = self._read_snapshot_block()
        self._collect_alarms()
        li, lf = s["li"], s["lf"]
        v = self._views()
        ctl = v["ctl"]
        timed = int(li[I_TIMED])
        hist = s["hist"]
        timing = TimingStats(
            cycles=int(li[I_CYCLE]),
            period_mean_s=float(lf[F_PERIOD_SUM]) / timed if timed else 0.0,
            period_min_s=float(lf[F_PERIOD_MIN]) if timed else 0.0,
            period_max_s=float(lf[F_PERIOD_MAX]) if timed else 0.0,
            jitter_p50_s=_percentile(hist, 0.50), jitter_p99_s=_percentile(hist, 0.99),
            jitter_p999_s=_percentile(hist, 0.999), jitter_max_s=float(lf[F_JITTER_MAX]),
            late_cycles=int(li[I_LATE]), missed_cycles=int(li[I_MISSED]),
            exec_mean_s=float(lf[F_EXEC_SUM]) / timed if timed else 0.0, exec_max_s=float(lf[F_EXEC_MAX]),
            span_s=float(lf[F_LAST_START] - lf[F_FIRST_START]) if timed else 0.0,
            histogram_bin_s=_HIST_BIN_S, jitter_histogram=tuple(int(x) for x in hist),
        )
        n_track = int(li[I_TRACK_N])
        n_win = int(li[I_WIN_N])
        mse = s["sum_e2"] / n_track if n_track else np.zeros(cfg.n_axes)
        wmse = s["win_e2"] / n_win if n_win else mse
        tracking = TrackingStats(
            samples=n_track, rmse=tuple(float(x) for x in np.sqrt(mse)), mse=tuple(float(x) for x in mse),
            max_abs=tuple(float(x) for x in s["max_e"]), window_samples=n_win if n_win else n_track,
            window_rmse=tuple(float(x) for x in np.sqrt(wmse)), window_mse=tuple(float(x) for x in wmse),
        )
        level = int(ctl[C_HEAD] - ctl[C_TAIL])
        return WorkerSnapshot(
            state=WorkerState(int(li[I_STATE])), cycle=int(li[I_CYCLE]), time_s=float(lf[F_TIME]),
            axis_names=cfg.axis_names,
            drive_states=tuple(Cia402State(int(x)) for x in s["drive_state"]),
            statuswords=tuple(int(x) for x in s["statusword"]),
            error_codes=tuple(int(x) for x in s["error_code"]),
            actual_position=s["act"], reference_position=s["ref"], following_error=s["fe"],
            buffer_level=level, buffer_capacity=cfg.buffer_capacity, samples_consumed=int(li[I_CONSUMED]),
            underruns=int(li[I_UNDERRUNS]), wkc=int(li[I_WKC]), expected_wkc=int(li[I_WKC_EXP]),
            wkc_errors=int(li[I_WKC_ERRORS]),
            homing=tuple(HomingState(int(x)) for x in s["homing"]), homed=tuple(bool(x) for x in s["homed"]),
            alarms=tuple(self._alarms), timing=timing, tracking=tracking,
            digital_outputs=tuple(int(x) for x in s["dout"]),
            command_seq=int(li[I_CMD_APPLIED]),
            lost_slaves=tuple(p for p in range(63) if int(li[I_LOST]) >> p & 1),
            events=tuple(self._events),
        )

    def drain_trace(self) -> TraceChunk:
        """Per-cycle (reference, actual) recorded while ENABLED since the last drain."""
        v = self._views()
        n = self.config.n_axes
        cap = self.config.trace_capacity
        head = int(v["ctl"][C_TRACE_HEAD])
        start = max(self._trace_read, head - cap)
        dropped = start - self._trace_read
        idx = np.arange(start, head) % cap if cap else np.zeros(0, dtype=np.int64)
        rows = v["trace"][idx].copy() if cap else np.zeros((0, 1 + 2 * n))
        self._trace_read = head
        return TraceChunk(rows[:, 0].astype(np.int64), rows[:, 1:1 + n], rows[:, 1 + n:], dropped)


_ERROR_TEXT = {
    0x2310: "continuous over-current",
    0x3210: "DC link over-voltage",
    0x4310: "drive temperature",
    0x7305: "encoder",
    0x8611: "following error",
    0x8700: "sync / process data lost",
}


def error_code_text(code: int) -> str:
    """Short text of a CiA 402 error code (0x603F)."""
    return _ERROR_TEXT.get(code, "")


def _percentile(hist: np.ndarray, q: float) -> float:
    total = int(hist.sum())
    if total == 0:
        return 0.0
    idx = int(np.searchsorted(np.cumsum(hist), q * total, side="left"))
    return (idx + 1) * _HIST_BIN_S        # upper edge of the bin (conservative)
