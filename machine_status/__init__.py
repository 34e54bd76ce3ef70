"""The machine's status as the controller publishes it: its states, alarms, spindle, bus and
the snapshot of them all (``ControllerSnapshot``).

Below the panel and the OPC UA server, which both read it, and above the planner, whose frame
of offsets it carries. All frozen dataclasses and enums (immutable snapshots), safe to pass
between threads. Units: positions mm (linear) / degrees (rotary), times s, speeds mm/s,
spindle rpm.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from planner.core.frames import Frame

__all__ = ["Activity", "Alarm", "AlarmState", "BusStatus", "ControllerSnapshot", "HoldKind", "MachineState",
           "Prompt", "RunSummary", "Severity", "SpindleState", "TrackingReport"]


class MachineState(enum.Enum):
    """Machine states. Legal transitions: see ``controller.TRANSITIONS``."""

    DISCONNECTED = "disconnected"  # worker not running / bus not in OP
    IDLE = "idle"  # drives enabled, nothing moving (jog, MDI and program start allowed)
    HOMING = "homing"  # one or more axes homing (drive method or set-here)
    RUNNING = "running"  # program, MDI block or jog in motion (see ``Activity``)
    HOLD = "hold"  # feed hold: stopped on the path, resumable
    ALARM = "alarm"  # an alarm stopped motion; reset (after acknowledging) returns to idle
    ESTOP = "estop"  # emergency stop: drives quick-stopped and disabled

    @property
    def label(self) -> str:
        return {"estop": "E-stop"}.get(self.value, self.value.capitalize())


class HoldKind(enum.Enum):
    """Why the machine is in HOLD, so the operator sees the stop named for what it is."""

    NONE = "none"                     # not in HOLD
    FEED_HOLD = "feed_hold"           # the operator's feed hold
    SINGLE_BLOCK = "single_block"     # single block: the end of a block
    PROGRAM_STOP = "program_stop"     # M00
    OPTIONAL_STOP = "optional_stop"   # M01 with optional stop on
    TOOL_CHANGE = "tool_change"       # M06
    STOPPING = "stopping"             # Stop pressed: braking along the path, then IDLE


@dataclass(frozen=True, slots=True)
class Prompt:
    """What a program stop asks of the operator (M00, M01, M06, single block): shown until
    the machine leaves HOLD."""

    kind: HoldKind
    line: int          # the program line that stopped (the M6 line for a tool change)
    tool: int = 0      # the tool to insert (tool change)
    text: str = ""

    def as_dict(self) -> dict[str, object]:
        return {"line": self.line, "kind": self.kind.value, "tool": self.tool, "text": self.text}


class Activity(enum.Enum):
    """What the machine is doing while RUNNING / HOLD."""

    NONE = "none"
    PROGRAM = "program"
    MDI = "mdi"
    JOG = "jog"
    APPROACH = "approach"  # safe move to the start of a run-from-line / resume point
    HOMING = "homing"


class Severity(enum.IntEnum):
    """How an alarm stops motion."""

    INFO = 0  # recorded only
    WARNING = 1  # recorded; motion continues (e.g. configuration fell back to backup)
    STOP = 2  # jerk-limited stop along the path, program abandoned, state ALARM
    QUICK_STOP = 3  # drives' quick stop at once (fault, following error, bus loss), state ALARM
    ESTOP = 4  # emergency stop, state ESTOP


class AlarmState(enum.Enum):
    ACTIVE = "active"
    ACKNOWLEDGED = "acknowledged"


@dataclass(frozen=True, slots=True)
class Alarm:
    """One alarm entry (persisted in ``<state_dir>/alarms.json``)."""

    id: int
    time_s: float  # UNIX time
    source: str  # "worker", "drive X", "bus", "planner", "controller", "operator", "config"
    cause: str  # human-readable cause
    severity: Severity
    state: AlarmState = AlarmState.ACTIVE
    code: str = ""  # short machine-readable code, e.g. "drive_fault", "following_error"

    @property
    def active(self) -> bool:
        return self.state is AlarmState.ACTIVE


@dataclass(frozen=True, slots=True)
class SpindleState:
    """Spindle: ``direction`` +1 CW (M03), -1 CCW (M04), 0 off; ``rpm`` the programmed speed
    (S), ``override_pct`` the operator's spindle override."""

    direction: int = 0
    rpm: float = 0.0
    override_pct: float = 100.0

    @property
    def commanded_rpm(self) -> float:
        """The speed the spindle is asked to turn at: S times the override."""
        return self.rpm * self.override_pct / 100.0

    @property
    def on(self) -> bool:
        return self.direction != 0


@dataclass(frozen=True, slots=True)
class BusStatus:
    """Bus / worker state as seen by the panel."""

    kind: str = "sim"  # "sim" | "soem"
    connected: bool = False
    state: str = "disconnected"  # worker state text
    drive_states: tuple[str, ...] = ()  # CiA 402 state per axis
    buffer_level: int = 0  # set-points queued in the worker
    late_cycles: int = 0
    period_p99_us: float = 0.0
    message: str = ""
    jitter_hist_bin_us: float = 0.0  # width of one bin of the cycle-start jitter histogram
    jitter_hist_counts: tuple[int, ...] = ()  # counts per bin from 0 us (last bin = overflow)
    jitter_max_us: float = 0.0
    probe: str = ""  # the probe input (G38.x): "touching", "free", "" when the machine has none
    spindle_state: str = ""  # CiA 402 state of the spindle's own drive ("" when it has none)
    gantry_skew: tuple[float, ...] = ()  # per drive: a gantry's second side's skew (0 elsewhere)
    compensation: tuple[float, ...] = ()  # per axis: the leadscrew correction sent (() without any)


@dataclass(frozen=True, slots=True)
class TrackingReport:
    """Reference vs actual per axis over the last (or current) run: paper Eq. 18, Table 4."""

    axes: tuple[str, ...] = ()
    samples: int = 0
    rmse: tuple[float, ...] = ()  # per axis, mm or deg
    mse: tuple[float, ...] = ()  # per axis, mm^2 or deg^2
    max_abs: tuple[float, ...] = ()  # per axis, largest |reference - actual|
    trace_path: str = ""  # NPZ trace of the last run ("" if none): keys t (N,) s, reference (N, n_axes),
    # actual (N, n_axes) machine coordinates, axes (names), rmse, mse (per axis)


@dataclass(frozen=True, slots=True)
class RunSummary:
    """End of a program run (emitted by ``programFinished``)."""

    name: str
    completed: bool  # False when stopped, reset, aborted by an alarm
    cycle_time_s: float  # measured (worker samples consumed * Ts)
    estimated_s: float
    last_line: int
    tracking: TrackingReport = field(default_factory=TrackingReport)
    limits: dict[str, float] = field(default_factory=dict)  # measured maxima of the reference
    reason: str = ""


@dataclass(frozen=True, slots=True)
class ControllerSnapshot:
    """The machine's status in one immutable object (``MachineController.snapshot()``, and
    ``statusChanged`` when anything in it changed): what the panel shows, what ``cnc-run
    --json`` reports and what a monitoring client reads. Positions in machine coordinates
    (``machine_pos``, the drives' actual; ``reference_pos``, the last set-point) and read in
    the offsets in force (``work_pos`` = ``frame.to_program(machine_pos)``)."""

    state: MachineState
    activity: Activity
    axes: tuple[str, ...]
    machine_pos: tuple[float, ...]
    work_pos: tuple[float, ...]
    homed: tuple[bool, ...]
    active_offset: str
    line: int
    progress: float
    remaining_s: float
    path_speed_mm_s: float
    feed_override_pct: float
    rapid_override_pct: float
    single_block: bool
    optional_stop: bool
    block_delete: bool
    spindle: SpindleState
    alarms: tuple[Alarm, ...]
    bus: BusStatus
    state_reason: str = ""
    hold_kind: HoldKind = HoldKind.NONE
    prompt: Prompt | None = None
    reference_pos: tuple[float, ...] = ()
    frame: Frame | None = None            # the offsets in force
    tool_in_spindle: int = 0
    program_name: str = ""                # "" when none is loaded
    program_path: str = ""
    program_lines: int = 0
    estimated_cycle_s: float = 0.0
    loading: bool = False                 # a program is being checked or planned
    resume_line: int = 0                  # where a stopped program would resume (0: none)
    last_run: RunSummary | None = None
    time_s: float = 0.0                   # UNIX time it was taken
    sequence: int = 0                     # one more at every publication

    @property
    def active_alarms(self) -> tuple[Alarm, ...]:
        return tuple(a for a in self.alarms if a.active)
