"""Value types the controller publishes: states, refusals, alarms, spindle, bus, tracking.

All frozen dataclasses (immutable snapshots), safe to pass through Qt signals as ``object``.
Units: positions mm (linear) / degrees (rotary), times s, speeds mm/s, spindle rpm.
"""

from __future__ import annotations

import enum
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np

    from app.program_lines import LineIndex
    from app.toolpath import ToolPath
    from planner.core.frames import Frame
    from planner.core.program import ProbeResult, Program
    from planner.motion.plan import Plan


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
class CommandResult:
    """Outcome of every controller command. Truthy when accepted; ``reason`` says why not.

    Commands never raise for an operator-level refusal (wrong state, not homed, soft limit,
    program errors): they return ``CommandResult(False, reason)`` and emit ``commandRefused``.
    """

    ok: bool
    action: str = ""
    reason: str = ""

    def __bool__(self) -> bool:
        return self.ok


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
class ProgramIssue:
    """One error of a program, located at its line (1-based) and column."""

    line: int
    col: int
    message: str
    axis: str = ""  # set for soft-limit errors

    def __str__(self) -> str:
        where = f"line {self.line}" + (f", axis {self.axis}" if self.axis else "")
        return f"{where}: {self.message}"


@dataclass(frozen=True, slots=True)
class ProgramInfo:
    """A loaded and checked program (emitted by ``programLoaded``)."""

    name: str
    path: str  # "" for text programs
    text: str
    line_count: int
    move_count: int
    cycle_time_s: float  # planner's estimate at 100 % override
    length_mm: float
    bounds_min: tuple[float, ...]  # machine coordinates, per axis, whole path (arcs included)
    bounds_max: tuple[float, ...]
    program: Program = field(repr=False, compare=False)
    # the plan (reduced limits); None for a long program, planned as it runs
    # (``app.machine.motion.plans.WINDOWED_RUN_MOVES``)
    plan: Plan | None = field(default=None, repr=False, compare=False)
    # the tool path of ``program``, made with the check off the GUI thread (seconds for
    # millions of moves): the preview draws it
    toolpath: ToolPath | None = field(default=None, repr=False, compare=False)
    # where each line of ``text`` starts, made with the check: the pages show the text
    # through it without copying it into a text widget
    line_starts: LineIndex | None = field(default=None, repr=False, compare=False)
    # G64 P: corners blended and fillets eased, and the largest distance from the programmed path
    blends: int = 0
    path_deviation_mm: float = 0.0
    # G38.x, M66: the program read again, from the same text and starting state, with the probe
    # results and the inputs' values (``planner.gcode.interpreter.parse_program(probe_results=,
    # input_results=)``), blended as ``program``
    reread: Callable[[tuple[ProbeResult | None, ...], tuple[float | None, ...]], Program] | None = field(
        default=None, repr=False, compare=False)
    # the plan's own end (planned time, without the spin-up waits ``cycle_time_s`` counts) and
    # its pause points, made with the check
    plan_end_s: float = 0.0
    stops: tuple[PausePoint, ...] = field(default=(), repr=False, compare=False)
    # what the operator confirms before it runs (a feed move with the spindle stopped after M6)
    warnings: tuple[ProgramIssue, ...] = ()


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


@dataclass(frozen=True, slots=True)
class Budget:
    """Share of the acceleration and jerk limits the plan may use (the rest is for sigma)."""

    k_a: float = 0.85
    k_j: float = 0.7


class PauseKind(enum.StrEnum):
    """Why the plan halts at a pause point: a program's stopping event (the values of
    ``planner.core.program.EventKind``), a block end in single block, or the program's end."""

    PAUSE = "pause"                     # M00
    OPTIONAL_PAUSE = "optional_pause"   # M01
    TOOL_CHANGE = "tool_change"         # M06
    DWELL = "dwell"                     # G04
    SPINDLE = "spindle"                 # M03/M04/M05/S
    END = "end"                         # M02/M30 or the last move
    TOOL_SET = "tool_set"               # M61
    OFFSETS = "offsets"                 # G10, G92, G52, G28.1 ...
    OUTPUT = "output"                   # M62-M65, user M-codes
    TOOL_DATA = "tool_data"             # G10 L1/L10/L11
    PROBE_START = "probe_start"         # before a G38.x move
    PROBE = "probe"                     # after it
    INPUT = "input"                     # M66
    TAPPING = "tapping"                 # a tap's overrides change
    SINGLE_BLOCK = "single_block"       # a block end in single block


@dataclass(frozen=True, slots=True)
class PausePoint:
    """A planned full stop where tau halts; ``value`` dwell s / spindle rpm / tool / the
    overrides from here (tapping) / an index into the program's tables (probes, inputs,
    parameter sets, tools) / an output (its number, or -(number + 1) to switch it off)."""

    tau_s: float
    kind: PauseKind     # a string of its values is taken as the kind
    line: int
    move: int
    value: float = 0.0
    message: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.kind, PauseKind):
            object.__setattr__(self, "kind", PauseKind(self.kind))


@dataclass(frozen=True, slots=True, eq=False)
class RestartPreview:
    """What a restart will do, shown to the operator before it moves (resume at the point
    where a program stopped, or run from a line): the line it goes on from and why it stopped
    there, the way there (machine coordinates, one row per corner, from where the machine
    stands: up, across, down), the clearance height it rises to (machine Z; -inf without Z),
    the spindle it starts (signed rpm, 0: off) and the tool it needs in the spindle."""

    line: int
    cause: str
    path: np.ndarray
    clearance_mm: float
    spindle_rpm: float
    tool: int


@dataclass(frozen=True, slots=True)
class ResumePoint:
    """Where a program stopped (fault, E-stop, stop alarm): move index and distance within it."""

    program: Program
    move_index: int
    u_mm: float
    line: int
    cause: str
    # what the run's probes and M66 read before it stopped (the program above is read with them)
    probe_results: tuple[ProbeResult | None, ...] = ()
    wait_results: tuple[float | None, ...] = ()


# ------------------------------------------------------------------ probing wizards
class ProbeWizard(enum.StrEnum):
    """What a wizard finds, by the routine that does it."""

    Z_SURFACE = "probe_z"
    EDGE = "probe_edge"
    OUTSIDE_CORNER = "probe_corner_outside"
    INSIDE_CORNER = "probe_corner_inside"
    BORE = "probe_bore"
    BOSS = "probe_boss"
    ANGLE = "probe_angle"


@dataclass(frozen=True, slots=True)
class ProbingRequest:
    """One wizard's inputs. ``system``: the coordinate system that takes the result ("" only
    reports it); ``axis`` and ``x_dir``/``y_dir``: which way the probe moves toward the face
    (edge, angle) or where the part or the walls are from the probe (corners), +1 or -1;
    ``diameter_mm`` and ``tolerance_mm``: a bore or boss as expected; ``depth_mm``: how far
    below the start a boss is probed; ``along_mm``: how far along the faces a corner is probed,
    or how far apart the angle's two points are; ``value``: what the point found reads after
    (X, Y, Z). The probe's feeds and distances default to ``[probe]`` (None)."""

    wizard: ProbeWizard
    system: str = ""
    axis: str = "X"
    x_dir: int = 1
    y_dir: int = 1
    diameter_mm: float = 20.0
    tolerance_mm: float = 1.0
    depth_mm: float = 5.0
    along_mm: float = 10.0
    value: tuple[float, float, float] = (0.0, 0.0, 0.0)
    search_mm: float | None = None
    clearance_mm: float | None = None
    fast_feed_mm_min: float | None = None
    slow_feed_mm_min: float | None = None
    retract_mm: float | None = None


@dataclass(frozen=True, slots=True)
class ProbingResult:
    """What a wizard found (program coordinates of the system in use before it wrote: "X", "Y",
    "Z", the diameter "D", the angle "A" in degrees) and the system it wrote ("" none)."""

    wizard: ProbeWizard
    values: dict[str, float] = field(default_factory=dict)
    written: str = ""

    def text(self) -> str:
        said = " ".join(f"{k}{v:.4f}" for k, v in self.values.items())
        return f"probed: {said}" + (f", written to {self.written}" if self.written else " (only reported)")
