"""Value types the controller publishes: refusals, the loaded program, pause and restart
points, probing requests and results; and, from ``machine_status`` (the status snapshot the
panel and the OPC UA server both read), its states, alarms, spindle, bus and tracking.

All frozen dataclasses (immutable snapshots), safe to pass through Qt signals as ``object``.
Units: positions mm (linear) / degrees (rotary), times s, speeds mm/s, spindle rpm.
"""

from __future__ import annotations

import enum
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from machine_status import (
    Activity,
    Alarm,
    AlarmState,
    BusStatus,
    ControllerSnapshot,
    HoldKind,
    MachineState,
    Prompt,
    RunSummary,
    Severity,
    SpindleState,
    TrackingReport,
)
from planner.core.program import PAYLOAD_OF, EventKind, EventPayload, PayloadT, check_payload, payload_as

if TYPE_CHECKING:
    import numpy as np

    from app.program_lines import LineIndex
    from app.toolpath import ToolPath
    from planner.core.program import ProbeResult, Program
    from planner.motion.plan import Plan
    from planner.pipeline import Reread

__all__ = ["WIZARD", "WIZARDS", "WizardAim", "WizardSpec",
           "Activity", "Alarm", "AlarmState", "Budget", "BusStatus", "CommandResult", "ControllerSnapshot",
           "HANDWHEEL_SCALES", "HandwheelStatus", "HoldKind", "MachineState", "PauseKind", "PausePoint",
           "ProbeWizard", "ProbingRequest", "ProbingResult", "ProgramInfo", "ProgramIssue", "Prompt",
           "RestartPreview", "ResumePoint", "RunSummary", "Severity", "SignalReading", "SpindleState",
           "TrackingReport"]


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
    # results and the inputs' values, through the load's stages (``planner.pipeline.Reread``)
    reread: Reread | None = field(default=None, repr=False, compare=False)
    # the plan's own end (planned time, without the spin-up waits ``cycle_time_s`` counts) and
    # its pause points, made with the check
    plan_end_s: float = 0.0
    stops: tuple[PausePoint, ...] = field(default=(), repr=False, compare=False)
    # what the operator confirms before it runs (a feed move with the spindle stopped after M6)
    warnings: tuple[ProgramIssue, ...] = ()


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


#: the pause points a program's event makes (the others: a block end, the program's end)
_EVENT_PAUSES = frozenset(k for k in PauseKind if k.value in {e.value for e in EventKind})


@dataclass(frozen=True, slots=True)
class PausePoint:
    """A planned full stop where tau halts; ``payload`` what the program's event there carries
    (``planner.core.program.PAYLOAD_OF``: the dwell, the spindle, the tool, an output, the
    overrides from here, an entry of the program's tables), None for a block end."""

    tau_s: float
    kind: PauseKind     # a string of its values is taken as the kind
    line: int
    move: int
    payload: EventPayload | None = None
    message: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.kind, PauseKind):
            object.__setattr__(self, "kind", PauseKind(self.kind))
        want = PAYLOAD_OF[EventKind(self.kind.value)] if self.kind in _EVENT_PAUSES else None
        check_payload(self.kind, self.payload, want)

    def payload_as(self, cls: type[PayloadT]) -> PayloadT:
        """The payload as ``cls`` (the one the program's event of this kind carries)."""
        return payload_as(self.kind, self.payload, cls)


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


class WizardAim(enum.Enum):
    """Which way a wizard is aimed: not at all (straight down, all around), toward a face along
    an axis (the axis and its sign), or at a corner (where the part or the walls are: the X and
    Y signs)."""

    NONE = "none"
    ALONG_AXIS = "along_axis"
    CORNER = "corner"


@dataclass(frozen=True, slots=True)
class WizardSpec:
    """One probing wizard, declared once (``WIZARDS``): its routine (``resources/subroutines/
    <wizard>.ngc``), its button's title, its name in the operator's sentences ("probing an
    edge: ..."), the inputs it takes beside the probe's distances and feeds, how it is aimed and
    what the aim's buttons mean, and the routine's own arguments (after the distances, feeds and
    the system that takes the result). ``one_value``: it reads one coordinate, the one of the
    axis it probes along; ``along_title``: what its "along" input means, where not the default."""

    wizard: ProbeWizard
    title: str
    name: str
    inputs: frozenset[str]
    aim: WizardAim
    prompt: str
    args: Callable[[ProbingRequest], tuple[float, ...]]
    one_value: bool = False
    along_title: str = ""


def _along(req: ProbingRequest) -> tuple[int, int]:
    """An edge's or a face's axis (0 X, 1 Y) and the sign it moves toward the face."""
    return (0, req.x_dir) if req.axis == "X" else (1, req.y_dir)


#: every probing wizard, in the order the panel offers them
WIZARDS: tuple[WizardSpec, ...] = (
    WizardSpec(ProbeWizard.Z_SURFACE, title="Z surface", name="the Z surface", inputs=frozenset({"z"}),
               aim=WizardAim.NONE, prompt="", args=lambda r: (r.value[2],)),
    WizardSpec(ProbeWizard.EDGE, title="Edge", name="an edge", inputs=frozenset({"x", "y"}),
               aim=WizardAim.ALONG_AXIS, prompt="The probe moves toward the face:",
               args=lambda r: (*_along(r), r.value[_along(r)[0]]), one_value=True),
    WizardSpec(ProbeWizard.OUTSIDE_CORNER, title="Outside corner", name="an outside corner",
               inputs=frozenset({"along", "x", "y"}), aim=WizardAim.CORNER,
               prompt="Where the part is from the probe:",
               args=lambda r: (r.x_dir, r.y_dir, r.along_mm, r.value[0], r.value[1])),
    WizardSpec(ProbeWizard.INSIDE_CORNER, title="Inside corner", name="an inside corner",
               inputs=frozenset({"x", "y"}), aim=WizardAim.CORNER,
               prompt="Where the walls are from the probe:",
               args=lambda r: (r.x_dir, r.y_dir, 0.0, r.value[0], r.value[1])),
    WizardSpec(ProbeWizard.BORE, title="Bore centre", name="a bore",
               inputs=frozenset({"diameter", "tolerance", "x", "y"}), aim=WizardAim.NONE, prompt="",
               args=lambda r: (r.diameter_mm, r.tolerance_mm, r.value[0], r.value[1])),
    WizardSpec(ProbeWizard.BOSS, title="Boss centre", name="a boss",
               inputs=frozenset({"diameter", "tolerance", "depth", "x", "y"}), aim=WizardAim.NONE, prompt="",
               args=lambda r: (r.diameter_mm, r.tolerance_mm, r.depth_mm, r.value[0], r.value[1])),
    WizardSpec(ProbeWizard.ANGLE, title="Angle of a face", name="the angle of a face",
               inputs=frozenset({"along"}), aim=WizardAim.ALONG_AXIS,
               prompt="The probe moves toward the face (the second point is along it):",
               args=lambda r: (*_along(r), r.along_mm), along_title="Points apart along the face"),
)
WIZARD: dict[ProbeWizard, WizardSpec] = {w.wizard: w for w in WIZARDS}


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
    """What a wizard found (machine positions "X", "Y", "Z", the diameter "D", the angle "A" of
    a face against the machine's X axis, degrees: the same whatever system it wrote) and the
    system it wrote ("" none)."""

    wizard: ProbeWizard
    values: dict[str, float] = field(default_factory=dict)
    written: str = ""

    def said(self, diameter: str = "diameter", angle: str = "angle") -> str:
        """The values as the operator reads them: positions by their axis, the diameter and the
        angle by name (an "A" would read as the A axis of a machine that has one); the names in
        the panel's language when it gives them."""
        named = {"D": (diameter, ""), "A": (angle, "°")}
        said = []
        for key, value in self.values.items():
            name, unit = named.get(key, (key, ""))
            said.append(f"{name} {value:.4f}{unit}")
        return " ".join(said)

    def text(self) -> str:
        where = f", written to {self.written}" if self.written else " (only reported)"
        return f"probed (machine): {self.said()}{where}"


@dataclass(frozen=True, slots=True)
class SignalReading:
    """One signal as the Diagnostics page lists it: key, direction, where it is wired (the
    slave's name, its channel or bit), and its state now (None: not known, the bus is down)."""

    key: str
    direction: str
    where: str
    wire: str
    value: bool | None
    meaning: str
    hal: str


#: the handwheel's step selector positions, as the pendant names them
HANDWHEEL_SCALES = ("x1", "x10", "x100")


@dataclass(frozen=True, slots=True)
class HandwheelStatus:
    """The handwheel as the Manual page shows it: whether the machine has one, the axis it is
    given ("" none), its step per detent (mm or deg) and which of x1/x10/x100 that is, whether
    it moves the axis now (``live``) and why not while an axis is given, and whether the
    pendant's selector inputs choose axis and step (the panel's buttons then only show them)."""

    configured: bool = False
    axis: str = ""
    step: float = 0.0
    scale_index: int = 0
    live: bool = False
    why: str = ""
    selector: bool = False
