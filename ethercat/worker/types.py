"""The worker's vocabulary: states, alarm and event codes, the records it reports, and its
configuration. Plain data only; nothing here runs."""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..bus import DriveSpec, SpindleDriveSpec, check_drives
from ..cia402 import Cia402State
from ..errors import ConfigurationError
from ..terminals import TerminalKind, TerminalSpec, check_terminals
from .compensation import CompSpec
from .gantry import GantrySpec, check_gantries

__all__ = [
    "Alarm", "AlarmCode", "DriveSpec", "EventCode", "HomingState", "HomingStep", "InputWatch", "SwitchHoming",
    "WatchAction", "ReplaceResult", "TimingStats",
    "TraceChunk", "TrackingStats", "WorkerConfig", "WorkerEvent", "WorkerSnapshot", "WorkerState",
    "REF_HISTORY",
]

#: reference positions kept per axis, so the actual position of cycle k is compared with the
#: set-point of cycle k - tracking_delay_cycles (the bus's transport delay)
REF_HISTORY = 8


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
    ESTOP_CHAIN = 12       # the machine's E-stop chain (safety relay) opened
    LIMIT_SWITCH = 13      # an axis ran onto a limit switch (a: +1 / -1 the side)
    HOMING_SWITCH = 14     # homing to the switch failed (a: the step, b: why)
    HANDWHEEL = 15         # the handwheel stopped (a: ``WheelFault``, b: the counts of a jump)
    SPINDLE = 16           # the spindle's drive (a: ``spindle.SpindleFault``, b: 0x603F or its state)
    GANTRY_SKEW = 17       # a gantry's sides apart beyond its window (axis: the follower, f: the skew)


class EventCode(enum.IntEnum):
    """Things worth telling the operator that are not alarms (codes share the alarm ring, >= 100)."""

    SLAVE_RECOVERED = 101
    STARTUP_FAULT_RESET = 102      # a drive was in FAULT when the bus came up: reset once
    DRIVE_ERROR_CODE = 103         # a faulted drive's 0x603F, read by SDO (not in its PDO)


class HomingState(enum.IntEnum):
    IDLE = 0
    RUNNING = 1
    DONE = 2
    ERROR = 3


class HomingStep(enum.IntEnum):
    """Where an axis homing to its switch is (LinuxCNC's homing sequence)."""

    IDLE = 0
    OFF_SWITCH = 1     # it started on the switch: moving off it against the search direction
    SEARCH = 2         # moving at the search velocity until the switch trips
    BACK_OFF = 3       # off the switch again (latch in the search direction)
    LATCH = 4          # at the latch velocity until the switch edge: the position latched
    DONE = 5
    INDEX = 6          # on at the latch velocity past the edge to the encoder's index: latched there
    SQUARE = 7         # a gantry's follower, latched: moving alone until the pair is square


class WatchAction(enum.IntEnum):
    """What the loop does, in the cycle it reads an input, about a stop condition."""

    ESTOP_CHAIN = 1    # active = the chain is open: quick stop, no enable while it stays open
    LIMIT = 2          # active = the axis is on its limit switch: quick stop unless overridden


@dataclass(frozen=True, slots=True)
class InputWatch:
    """One input the loop watches every cycle: bit ``bit`` of input word ``word`` (words
    0..n-1 the drives' 0x60FD, n.. the terminals' inputs) is *active* when it reads
    ``level``. ``axis`` and ``side`` (+1 positive, -1 negative end) for a limit switch."""

    action: WatchAction
    word: int
    bit: int
    level: bool = True
    axis: int = -1
    side: int = 0
    name: str = ""


@dataclass(frozen=True, slots=True)
class SwitchHoming:
    """How one axis homes to its switch in position mode (LinuxCNC's HOME_* keys), velocities in
    axis units/s with their signs: search (the direction to the switch), latch (the same sign:
    off the switch and back onto it slowly; opposite: latched as it leaves the switch).
    ``max_travel`` bounds every move; ``accel``/``jerk`` the ramps. The switch is bit ``bit`` of
    input word ``word`` (as ``InputWatch``), closed when it reads ``level``. ``use_index``
    (LinuxCNC's HOME_USE_INDEX): past the switch edge the axis goes on at the latch velocity to
    the next index pulse of its drive's encoder, latched by the drive's touch probe 1."""

    axis: int
    word: int
    bit: int
    level: bool
    search_vel: float
    latch_vel: float
    max_travel: float
    accel: float
    jerk: float
    ignore_limits: bool = False
    use_index: bool = False

    def __post_init__(self) -> None:
        if self.search_vel == 0.0 or self.latch_vel == 0.0:
            raise ConfigurationError(f"homing of axis {self.axis}: search and latch velocities must not be 0")
        if not (self.max_travel > 0.0 and self.accel > 0.0 and self.jerk > 0.0):
            raise ConfigurationError(f"homing of axis {self.axis}: travel, acceleration and jerk must be > 0")


@dataclass(frozen=True, slots=True)
class HandwheelSpec:
    """The handwheel's encoder: terminal ``terminal`` (an index into ``WorkerConfig.terminals``,
    an encoder terminal), its counter's width, and the largest change of the counter in one
    cycle that is a turn of the wheel (more is a jump: the wheel stops, nothing moves)."""

    terminal: int
    counter_bits: int = 16
    max_counts_per_cycle: int = 256

    def __post_init__(self) -> None:
        if self.counter_bits not in (16, 32):
            raise ConfigurationError(f"handwheel counter of {self.counter_bits} bits: 16 or 32")
        if not 1 <= self.max_counts_per_cycle < 1 << (self.counter_bits - 1):
            raise ConfigurationError(f"handwheel max_counts_per_cycle {self.max_counts_per_cycle}: "
                                     f"1 .. {(1 << (self.counter_bits - 1)) - 1}")


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


class ProbeLatch(enum.IntEnum):
    OFF = 0
    ARMED = 1
    TRIPPED = 2


@dataclass(frozen=True, slots=True)
class ProbeState:
    """The probe input as the loop watched it (``CyclicWorker.arm_probe``)."""

    latch: ProbeLatch = ProbeLatch.OFF
    consumed: int = 0                          # set-points consumed in the cycle it tripped
    position: tuple[float, ...] = ()           # actual positions of that cycle (axis units)


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
    digital_inputs: tuple[int, ...] = ()   # 0x60FD per drive, from the process data
    probe: ProbeState = ProbeState()       # the probe input's latch (``CyclicWorker.arm_probe``)
    terminal_inputs: tuple[int, ...] = ()  # per terminal: its input bits (an encoder's status)
    terminal_outputs: tuple[int, ...] = ()
    terminal_counts: tuple[int, ...] = ()  # per terminal: an encoder's counter (0 otherwise)
    watches_active: tuple[bool, ...] = ()  # per ``WorkerConfig.watches``: active this cycle
    limits_overridden: bool = False        # ``CyclicWorker.override_limits`` in force
    homing_steps: tuple[HomingStep, ...] = ()    # per axis: the step of its homing to a switch
    home_latched: tuple[float, ...] = ()         # per axis: the position latched at the switch
    handwheel_state: int = 0           # ``handwheel.WheelState``: off, live, stopping
    handwheel_axis: int = -1           # the axis it moves (-1: none)
    compensation: tuple[float, ...] = ()       # per axis: the leadscrew correction sent last
    compensation_on: tuple[bool, ...] = ()     # per axis: compensation on (the axis homed)
    spindle_state: int = 0             # ``spindle.SpindleState`` of the spindle's own drive
    spindle_drive_state: Cia402State | None = None   # its CiA 402 state (None: no spindle drive)
    spindle_rpm_command: float = 0.0   # the speed sent (rpm, signed)
    spindle_rpm_actual: float = 0.0    # the speed its drive reads (0x606C, rpm)
    spindle_error_code: int = 0
    gantry_skew: tuple[float, ...] = ()        # per axis: a gantry follower's skew (0 elsewhere)

    @property
    def enabled(self) -> bool:
        return self.state is WorkerState.ENABLED


@dataclass(frozen=True, slots=True)
class TraceChunk:
    """Per-cycle reference and actual positions drained from the worker (axis units).

    `reference[k]` is the set-point the actual position of cycle `cycle[k]` answers
    (`tracking_delay_cycles` earlier), so `reference - actual` is the tracking error of Eq. 18;
    `serial[k]` is that set-point's serial (the k-th taken since start; -1 before the first): a
    producer tells from it which of its set-points each row is.
    """

    cycle: np.ndarray          # (N,) int64
    reference: np.ndarray      # (N, n_axes)
    actual: np.ndarray         # (N, n_axes)
    dropped: int               # cycles overwritten before they were drained
    serial: np.ndarray | None = None   # (N,) int64


@dataclass(frozen=True, slots=True)
class WorkerConfig:
    """Configuration of the cyclic worker.

    drives: the machine's drives (axis order = column order of `push`); a gantry's second
    drives (``gantry``) come last, and `push` has no column for them.
    ts_s: cycle time; bus_kind "sim" | "soem"; adapter: network interface for "soem".
    wkc_error_limit: working counter may be wrong for this many consecutive cycles.
    buffer_capacity: set-points the ring holds (2000 = 2 s ahead at 1 ms).
    following_error_cycles: |ref - actual| over the window for more than this many cycles.
    enable_confirm_cycles: a drive counts as enabled after showing OPERATION ENABLED this many
    cycles in a row (its statusword lags the controlword by a cycle or more).
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
    enable_confirm_cycles: int = 5
    fault_reset_timeout_s: float = 0.5
    homing_timeout_s: float = 120.0
    start_timeout_s: float = 20.0
    command_timeout_s: float = 2.0
    trace_capacity: int = 1 << 16
    bus_options: tuple[tuple[str, Any], ...] = field(default=())
    terminals: tuple[TerminalSpec, ...] = ()
    watches: tuple[InputWatch, ...] = ()
    switch_homing: tuple[SwitchHoming, ...] = ()
    handwheel: HandwheelSpec | None = None
    compensation: tuple[CompSpec, ...] = ()
    spindle: SpindleDriveSpec | None = None
    gantry: tuple[GantrySpec, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "drives", check_drives(self.drives))
        check_gantries(self.gantry, len(self.drives))
        taken = [d.position for d in self.drives] + ([self.spindle.position] if self.spindle else [])
        if len(set(taken)) != len(taken):
            raise ConfigurationError(f"the spindle drive's position is an axis drive's: {taken}")
        object.__setattr__(self, "terminals", check_terminals(self.terminals, taken))
        wheel = self.handwheel
        if wheel is not None and not (0 <= wheel.terminal < len(self.terminals)
                                      and self.terminals[wheel.terminal].kind is TerminalKind.ENCODER):
            raise ConfigurationError(f"the handwheel's terminal {wheel.terminal} is not an encoder terminal")
        axes = [c.axis for c in self.compensation]
        if len(set(axes)) != len(axes) or any(i >= len(self.drives) for i in axes):
            raise ConfigurationError(f"compensation for axes {axes}: at most one each, of "
                                     f"{len(self.drives)} axes")
        n_words = len(self.drives) + len(self.terminals)
        inputs: list[InputWatch | SwitchHoming] = [*self.watches, *self.switch_homing]
        for w in inputs:
            if not 0 <= w.word < n_words or not 0 <= w.bit < 32:
                raise ConfigurationError(f"{w}: input word {w.word} bit {w.bit} does not exist "
                                         f"({n_words} input words of 32 bits)")
            if w.axis >= len(self.drives):
                raise ConfigurationError(f"{w}: axis {w.axis} does not exist")
        if not 0.0001 <= self.ts_s <= 0.1:
            raise ConfigurationError(f"ts_s must be within [0.0001, 0.1] s, got {self.ts_s}")
        if self.mode not in ("process", "thread", "manual"):
            raise ConfigurationError(f"mode must be 'process', 'thread' or 'manual', got {self.mode!r}")
        if self.buffer_capacity < 2:
            raise ConfigurationError(f"buffer_capacity must be >= 2, got {self.buffer_capacity}")
        if self.wkc_error_limit < 0 or self.following_error_cycles < 0:
            raise ConfigurationError("wkc_error_limit and following_error_cycles must be >= 0")
        if not 0 <= self.tracking_delay_cycles < REF_HISTORY:
            raise ConfigurationError(f"tracking_delay_cycles must be within [0, {REF_HISTORY - 1}]")
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
    def n_motion_axes(self) -> int:
        """The axes set-points are pushed for: every axis but the gantries' followers (the
        last ones), whose set-points the loop makes from their leaders'."""
        return len(self.drives) - len(self.gantry)

    @property
    def n_terminals(self) -> int:
        return len(self.terminals)

    @property
    def axis_names(self) -> tuple[str, ...]:
        return tuple(d.axis_name for d in self.drives)


class ReplaceResult(enum.Enum):
    """What ``CyclicWorker.replace`` did. ``TOO_LATE``: the loop had already taken
    ``from_serial`` (retry from a later serial); ``BEYOND_END``: ``from_serial`` is past the
    queue's end (the queue was dropped: quick stop, flush). Nothing changed in either case."""

    DONE = "done"
    TOO_LATE = "too_late"
    BEYOND_END = "beyond_end"
