"""The planner's data model: a G-code program as an exact list of moves (paper section 2).

Units: lengths mm, angles of arcs rad, rotary axis positions degrees (as in G-code),
feed mm/s. Every move is parametrised by its path length u in [0, length_mm]:
``Move.evaluate(u)`` gives position, unit tangent dq/du and curvature, exactly (closed
form for lines, circles and helices; spirals by their exact arc length, inverted by
Newton's method).

Arc convention (RS274/NGC, LinuxCNC): the plane's (first, second) axes are XY for G17,
ZX for G18 (first axis Z!), YZ for G19; the angle is measured in that frame, so a
positive sweep is counter-clockwise (G03) seen from the positive end of the normal axis.
"""

from __future__ import annotations

import bisect
import enum
import functools
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np

from planner.core.curves import Blend, blend_eval
from planner.core.errors import PlannerError
from planner.core.frames import Frame

if TYPE_CHECKING:
    from planner.core.movestore import MoveStore

__all__ = [
    "AnalogOutput",
    "Arc",
    "Coolant",
    "CoolantSwitch",
    "Curve",
    "Dwell",
    "Event",
    "EventKind",
    "FrameChange",
    "EventPayload",
    "FEED_HOLD_DEFERRED",
    "FEED_OVERRIDE_OFF",
    "SPINDLE_OVERRIDE_OFF",
    "InputRequest",
    "Move",
    "MoveKind",
    "OutputLevel",
    "OverrideLocks",
    "PAYLOAD_OF",
    "PayloadT",
    "ProbeRequest",
    "ProbeResult",
    "Program",
    "STOPPING_EVENTS",
    "SpindleSpeed",
    "SynchronisedMotion",
    "TableRef",
    "ToolNumber",
    "arc_length_mm",
    "arc_param_at_length",
    "spiral_length_mm",
    "turn_xy",
    "WaitMode",
]


class MoveKind(enum.IntEnum):
    RAPID = 0
    LINE = 1
    ARC = 2
    BLEND = 3  # a corner blend under G64 P (planner.geometry.blend): a pair of clothoids between two lines


@dataclass(frozen=True, slots=True)
class Arc:
    """Exact circle / helix / spiral geometry of one G02/G03 move."""

    plane: str  # "XY" (G17), "ZX" (G18: first axis Z, second X), "YZ" (G19)
    first_axis: int  # column index into Program.axes
    second_axis: int
    normal_axis: int  # column index, -1 if the machine has no such axis
    center: tuple[float, float]  # absolute centre (first, second), machine coords, mm
    radius_start_mm: float
    radius_end_mm: float  # differs from radius_start_mm only for spirals
    start_angle_rad: float  # angle of the start point around the centre, (first, second) frame
    sweep_rad: float  # signed: + counter-clockwise (G03) seen from + normal; includes whole turns
    rise_mm: float  # helix: change of the normal axis over the arc
    turns: int = 1  # P word (LinuxCNC's |rotation|); sweep already includes the extra turns
    # A G18/G19 arc while the XY plane is rotated (G10 L2 R) lies in a plane turned about Z:
    # its centre, angles and axes (X and Y of the turned system) are in a frame whose X and Y are
    # the machine's turned by this angle, machine (X, Y) = R(xy_turn_rad) (frame X, Y). Zero for
    # every other arc (a G17 arc turns with the system in its own plane).
    xy_turn_rad: float = 0.0

    @property
    def clockwise(self) -> bool:
        return self.sweep_rad < 0.0

    @property
    def turned_xy(self) -> tuple[int, int] | None:
        """The machine's X and Y columns of an arc in a turned frame (G18: the second axis and
        the normal, G19: the normal and the first axis), None for an arc in a machine plane."""
        if self.xy_turn_rad == 0.0:
            return None
        if self.plane == "ZX":
            return self.second_axis, self.normal_axis
        return self.normal_axis, self.first_axis


def turn_xy(q: np.ndarray, ix: Any, iy: Any, angle_rad: Any, rows: Any = slice(None)) -> None:
    """Turn columns ``ix``, ``iy`` of ``q[rows]`` by ``angle_rad`` about Z, in place (scalars, or
    one value a row: ``rows`` an index array)."""
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    x = q[rows, ix]
    y = q[rows, iy]
    x, y = c * x - s * y, s * x + c * y      # both made before either column is written
    q[rows, ix] = x
    q[rows, iy] = y


# 16-point Gauss-Legendre rule on [0, 1] for the arc length of near-circular spirals.
_GL_X, _GL_W = np.polynomial.legendre.leggauss(16)
_GL_X = (_GL_X + 1.0) * 0.5
_GL_W = _GL_W * 0.5


def _spiral_speed(arc: Arc, t: np.ndarray) -> np.ndarray:
    """|dp/dt| of the linear-axis curve, t in [0, 1] the normalised angle parameter."""
    dr = arc.radius_end_mm - arc.radius_start_mm
    r = arc.radius_start_mm + dr * t
    return np.sqrt(dr * dr + (r * arc.sweep_rad) ** 2 + arc.rise_mm * arc.rise_mm)


def _spiral_s(arc: Arc, t: np.ndarray) -> np.ndarray:
    """Arc length from t = 0 to t (exact: closed form, or Gauss-Legendre where it cancels)."""
    r0 = arc.radius_start_mm
    dr = arc.radius_end_mm - r0
    w_abs = abs(arc.sweep_rad)
    if abs(dr) > 1e-3 * r0:
        # s = (F(w(t)) - F(w0)) / (|W| dr), w = |W| r(t), F(w) = (w sqrt(w^2+k^2) + k^2 asinh(w/k))/2
        k2 = dr * dr + arc.rise_mm * arc.rise_mm
        k = math.sqrt(k2)

        def f(w):
            return 0.5 * (w * np.sqrt(w * w + k2) + k2 * np.arcsinh(w / k))

        return (f(w_abs * (r0 + dr * t)) - f(w_abs * r0)) / (w_abs * dr)
    # Nearly a circle: the integrand is almost constant, 16 Gauss points are exact to rounding.
    t = np.asarray(t, dtype=float)
    pts = t[..., None] * _GL_X
    return t * (_spiral_speed(arc, pts) @ _GL_W)


# 4-point Gauss-Legendre on [0, 1] (scalar path): exact to rounding for |dr| <= 1e-3 r0.
_GL4 = tuple(zip(((np.polynomial.legendre.leggauss(4)[0] + 1.0) * 0.5).tolist(),
                 (np.polynomial.legendre.leggauss(4)[1] * 0.5).tolist()))


def spiral_length_mm(r0: float, r1: float, sweep_rad: float, rise_mm: float) -> float:
    """Exact length of a circle/helix (r0 == r1) or linear spiral, with floats only."""
    dr = r1 - r0
    if dr == 0.0:
        return math.hypot(r0 * sweep_rad, rise_mm)
    w = abs(sweep_rad)
    if abs(dr) > 1e-3 * r0:
        k2 = dr * dr + rise_mm * rise_mm
        k = math.sqrt(k2)
        wa, wb = w * r0, w * r1
        fa = 0.5 * (wa * math.sqrt(wa * wa + k2) + k2 * math.asinh(wa / k))
        fb = 0.5 * (wb * math.sqrt(wb * wb + k2) + k2 * math.asinh(wb / k))
        return (fb - fa) / (w * dr)
    c = dr * dr + rise_mm * rise_mm
    total = 0.0
    for x, wt in _GL4:
        r = r0 + dr * x
        total += wt * math.sqrt(c + r * r * w * w)
    return total


def arc_length_mm(arc: Arc) -> float:
    """Exact length of an arc, helix or spiral over its linear axes."""
    return spiral_length_mm(arc.radius_start_mm, arc.radius_end_mm, arc.sweep_rad, arc.rise_mm)


def arc_param_at_length(arc: Arc, u_mm: np.ndarray, length_mm: float) -> np.ndarray:
    """Normalised angle parameter t in [0, 1] at path length u (exact inverse of the length)."""
    u = np.clip(np.atleast_1d(np.asarray(u_mm, dtype=float)), 0.0, length_mm)
    if arc.radius_end_mm == arc.radius_start_mm or length_mm <= 0.0:
        return u / length_mm if length_mm > 0.0 else np.zeros_like(u)
    t = u / length_mm
    for _ in range(12):  # Newton on s(t) = u; ds/dt varies slowly, converges in 2-4 steps
        step = (_spiral_s(arc, t) - u) / _spiral_speed(arc, t)
        t = np.clip(t - step, 0.0, 1.0)
        if not np.any(np.abs(step) > 1e-15):
            break
    t[u >= length_mm] = 1.0  # the ends exactly
    t[u <= 0.0] = 0.0
    return t


@dataclass(frozen=True, slots=True, eq=False)
class Move:
    """One motion block: a rapid, a straight feed or an arc/helix/spiral, or a corner blend."""

    index: int
    line: int  # 1-based source line
    kind: MoveKind
    start: np.ndarray  # (n_axes,), machine coords, mm / deg
    end: np.ndarray
    feed_mm_s: float  # programmed feed (rapids: math.inf; the planner applies the rapid limit)
    length_mm: float  # u runs over [0, length_mm]; linear-axis length, rotary degrees if none
    arc: Arc | None
    exact_stop: bool  # G61 active -> full stop at the end of this move
    blend: Blend | None = None  # for kind BLEND (its clothoids, arc or transition), else None

    def evaluate(self, u_mm: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Position (N, n_axes), unit tangent dq/du (N, n_axes) and curvature 1/mm (N,) at u.

        u is clipped to [0, length_mm]; at u = length_mm the position is exactly ``end``.
        The tangent's linear-axis part has unit norm; rotary components ride along
        (deg per mm of path). Curvature is that of the linear-axis path.
        """
        u = np.atleast_1d(np.asarray(u_mm, dtype=float)).ravel()
        length = self.length_mm
        n_pts = u.shape[0]
        start = self.start
        delta = self.end - start
        arc = self.arc
        if self.blend is not None:
            return blend_eval(self, u)
        if arc is None:
            if length > 0.0:
                t = np.clip(u, 0.0, length) / length
                tangent = np.broadcast_to(delta / length, (n_pts, start.shape[0])).copy()
            else:
                t = np.zeros(n_pts)
                tangent = np.zeros((n_pts, start.shape[0]))
            pos = start + t[:, None] * delta
            pos[t >= 1.0] = self.end
            return pos, tangent, np.zeros(n_pts)

        u = np.clip(u, 0.0, length)
        t = arc_param_at_length(arc, u, length)
        f, s, nrm = arc.first_axis, arc.second_axis, arc.normal_axis
        w = arc.sweep_rad
        dr = arc.radius_end_mm - arc.radius_start_mm
        r = arc.radius_start_mm + dr * t
        theta = arc.start_angle_rad + w * t
        c, sn = np.cos(theta), np.sin(theta)

        # Axes other than the plane's move linearly in t (helix axis, rotary axes).
        pos = start + t[:, None] * delta
        turned = arc.turned_xy
        if turned is not None:     # into the arc's frame (a linear map: start + t delta there too)
            turn_xy(pos, turned[0], turned[1], -arc.xy_turn_rad)
        pos[:, f] = arc.center[0] + r * c
        pos[:, s] = arc.center[1] + r * sn
        if turned is not None:
            turn_xy(pos, turned[0], turned[1], arc.xy_turn_rad)
        elif nrm >= 0:
            pos[:, nrm] = start[nrm] + arc.rise_mm * t
        pos[u >= length] = self.end

        # Derivatives with respect to t.
        d1f = dr * c - r * w * sn
        d1s = dr * sn + r * w * c
        d2f = -2.0 * dr * w * sn - r * w * w * c
        d2s = 2.0 * dr * w * c - r * w * w * sn
        rise = arc.rise_mm
        speed = np.sqrt(d1f * d1f + d1s * d1s + rise * rise)  # ds/dt > 0 (radius > 0)
        tangent = np.empty((n_pts, start.shape[0]))
        tangent[:] = delta
        tangent /= speed[:, None]
        if turned is not None:
            turn_xy(tangent, turned[0], turned[1], -arc.xy_turn_rad)
        tangent[:, f] = d1f / speed
        tangent[:, s] = d1s / speed
        if nrm >= 0:
            tangent[:, nrm] = rise / speed
        if turned is not None:
            turn_xy(tangent, turned[0], turned[1], arc.xy_turn_rad)
        # |p' x p''| / |p'|^3 with p = (first, second, normal), p''_normal = 0.
        cx = -rise * d2s
        cy = rise * d2f
        cz = d1f * d2s - d1s * d2f
        curvature = np.sqrt(cx * cx + cy * cy + cz * cz) / speed**3
        return pos, tangent, curvature

    @property
    def is_arc(self) -> bool:
        return self.arc is not None


class EventKind(enum.Enum):
    DWELL = "dwell"  # G04 P (value: seconds)
    PAUSE = "pause"  # M00
    OPTIONAL_PAUSE = "optional_pause"  # M01
    END = "end"  # M02 / M30
    TOOL_CHANGE = "tool_change"  # M06 (no tool changer: a stop with a message)
    SPINDLE = "spindle"  # M03/M04/M05 or S change (value: rpm, + CW, - CCW, 0 off)
    TOOL = "tool"  # T word (value: tool number)
    COOLANT = "coolant"  # addition: M07 mist (value 1), M08 flood (2), M09 off (0); not stopping
    TOOL_SET = "tool_set"  # M61 Q: the tool now in the spindle, without a change (value: number)
    MESSAGE = "message"  # (MSG,...), (DEBUG,...), (PRINT,...): text for the operator; not stopping
    OFFSETS = "offsets"  # G10, G92, G52, G28.1 ...: Program.parameter_sets[value] is what the machine keeps
    OUTPUT = "output"  # M62-M65, a user M-code: value = output number (on) or -(number + 1) (off)
    TOOL_DATA = "tool_data"  # G10 L1/L10/L11: Program.tool_sets[value] is the tool as it is now
    # G38.2-G38.5 (value: index into Program.probes): the probe is armed at rest before its move
    # and read at rest after it; what follows depends on the result, so the run stops at both
    PROBE_START = "probe_start"
    PROBE = "probe"
    # M66 (value: index into Program.inputs): the motion stops, the input is read (waited for)
    # there; what follows depends on it
    INPUT = "input"
    # M48-M51: the overrides the motion from here follows (value: 1 the feed override is off,
    # 2 the spindle override is off, 3 both, 0 both on; 4 the feed hold waits, set by taps
    # only); not stopping, as in LinuxCNC
    OVERRIDES = "overrides"
    # the same for a tap's feed moves (G74/G84, G33.1: both off, the feed hold deferred to the
    # tap's end), which start and end at rest:
    # the overrides change where the path stands, never on the way
    TAPPING = "tapping"


#: OVERRIDES bits
FEED_OVERRIDE_OFF = 1
SPINDLE_OVERRIDE_OFF = 2
#: a tap is in the hole: the operator's feed hold waits until it is out (LinuxCNC holds
#: spindle-synchronised motion to its end, Fanuc a G84 to its return): axes standing while the
#: spindle turns would strip the thread or break the tap
FEED_HOLD_DEFERRED = 4


STOPPING_EVENTS = frozenset(
    {
        EventKind.DWELL,
        EventKind.PAUSE,
        EventKind.OPTIONAL_PAUSE,
        EventKind.END,
        EventKind.TOOL_CHANGE,
        EventKind.SPINDLE,
        EventKind.TOOL_SET,
        EventKind.OFFSETS,     # LinuxCNC synchronises the motion on G10 and G92 too
        EventKind.OUTPUT,      # the output switches where the path is (M62/M63 as M64/M65)
        EventKind.TOOL_DATA,
        EventKind.PROBE_START,
        EventKind.PROBE,
        EventKind.INPUT,
        EventKind.TAPPING,
    }
)


class WaitMode(enum.IntEnum):
    """M66 L: how the input is waited for."""

    IMMEDIATE = 0   # read it now
    RISE = 1        # until it goes from 0 to 1
    FALL = 2        # until it goes from 1 to 0
    HIGH = 3        # until it reads 1
    LOW = 4         # until it reads 0


@dataclass(frozen=True, slots=True)
class InputRequest:
    """One M66 of a program: digital input ``number`` waited for as ``mode`` for at most
    ``timeout_s`` (#5399 then reads -1), as the interpreter read it."""

    line: int
    number: int
    mode: WaitMode
    timeout_s: float
    known: bool            # read with the machine's value; else the awaited value was assumed

    @property
    def assumed_value(self) -> float:
        """What the check reads: the awaited level (0 for an immediate read)."""
        return 1.0 if self.mode in (WaitMode.RISE, WaitMode.HIGH) else 0.0


@dataclass(frozen=True, slots=True)
class ProbeResult:
    """What a probe move did on the machine (machine coordinates, mm / deg)."""

    tripped: bool                     # the input changed (G38.2/.3: contact; G38.4/.5: contact lost)
    trip_position: tuple[float, ...]  # where it changed (the end point when it did not)
    stop_position: tuple[float, ...]  # where the probe move came to rest


@dataclass(frozen=True, slots=True)
class Curve:
    """A G05, G05.1 or G05.2/G05.3 curve as read: the moves it runs as (``first`` up to
    ``end``, indexes into the interpreter's moves), its control points in program coordinates
    (x and y in mm, weight) and its order."""

    first: int
    end: int
    points: tuple[tuple[float, float, float], ...]
    order: int


@dataclass(frozen=True, slots=True)
class SynchronisedMotion:
    """A G33 move or G76 threading cycle: motion that LinuxCNC ties to the spindle's turning
    (each pass of a thread must start at the same spindle angle)."""

    code: str                 # "G33" or "G76"
    line: int


@dataclass(frozen=True, slots=True)
class AnalogOutput:
    """An M67 (with the next move) or M68 (at once) setting analog output ``index`` to
    ``value``, as LinuxCNC reads it."""

    code: str                 # "M67" or "M68"
    line: int
    index: int
    value: float


@dataclass(frozen=True, slots=True)
class ProbeRequest:
    """One G38.2-G38.5 move of a program, as the interpreter read it."""

    code: int                 # 382, 383, 384, 385 (G38.2 ...)
    line: int
    # the probe move as read (-1 when it has no length: already at the end point); blending
    # renumbers the moves, the PROBE event's ``after_move`` follows
    move_index: int
    target: tuple[float, ...]  # the programmed end point, machine coordinates
    known: bool               # read with the machine's result; else read as run to the target, no contact

    @property
    def name(self) -> str:
        return f"G38.{self.code - 380}"

    @property
    def toward(self) -> bool:
        """G38.2/G38.3 move until the probe touches; G38.4/G38.5 until it no longer does."""
        return self.code in (382, 383)

    @property
    def error_without_trip(self) -> bool:
        """G38.2/G38.4: reaching the end point without the change is an error."""
        return self.code in (382, 384)


class Coolant(enum.Enum):
    """What a coolant event switches: M7 mist on, M8 flood on (the other stays as it is), M9
    both off."""

    MIST_ON = "M7"
    FLOOD_ON = "M8"
    ALL_OFF = "M9"


@dataclass(frozen=True, slots=True)
class Dwell:
    """G4 P: the motion stands ``seconds``."""

    seconds: float


@dataclass(frozen=True, slots=True)
class SpindleSpeed:
    """The spindle from here: ``direction`` +1 clockwise (M3), -1 counter-clockwise (M4), 0
    stopped; ``rpm`` its speed, 0 when stopped."""

    direction: int
    rpm: float

    def __post_init__(self) -> None:
        if self.direction not in (-1, 0, 1) or not self.rpm >= 0.0:
            raise PlannerError(f"spindle direction {self.direction} and speed {self.rpm} rpm: "
                               "the direction is -1, 0 or 1 and the speed at least 0")
        if self.direction == 0:
            object.__setattr__(self, "rpm", 0.0)

    @property
    def signed_rpm(self) -> float:
        """The speed with the direction's sign (the way the DRO and a restart's preview show it)."""
        return self.direction * self.rpm


@dataclass(frozen=True, slots=True)
class ToolNumber:
    """A tool by its number: selected (T), changed to (M6) or in the spindle (M61)."""

    number: int


@dataclass(frozen=True, slots=True)
class CoolantSwitch:
    """M7, M8 or M9."""

    switch: Coolant


@dataclass(frozen=True, slots=True)
class OutputLevel:
    """M62-M65 or a user M-code: digital output ``number`` switched ``on`` or off."""

    number: int
    on: bool


@dataclass(frozen=True, slots=True)
class TableRef:
    """An entry of one of the program's tables, which the event's kind names: OFFSETS
    ``Program.parameter_sets``, TOOL_DATA ``tool_sets``, PROBE_START and PROBE ``probes``,
    INPUT ``inputs``."""

    index: int


@dataclass(frozen=True, slots=True)
class OverrideLocks:
    """M48-M53 and taps: the overrides the motion follows from here, as the OVERRIDES bits
    (``FEED_OVERRIDE_OFF``, ``SPINDLE_OVERRIDE_OFF``, ``FEED_HOLD_DEFERRED``; 0 all on)."""

    bits: int


#: what an event carries besides its kind, line and text
EventPayload = Dwell | SpindleSpeed | ToolNumber | CoolantSwitch | OutputLevel | TableRef | OverrideLocks

#: the payload each kind of event carries (None: only its text)
PAYLOAD_OF: dict[EventKind, type[EventPayload] | None] = {
    EventKind.DWELL: Dwell,
    EventKind.PAUSE: None,
    EventKind.OPTIONAL_PAUSE: None,
    EventKind.END: None,
    EventKind.TOOL_CHANGE: ToolNumber,
    EventKind.SPINDLE: SpindleSpeed,
    EventKind.TOOL: ToolNumber,
    EventKind.COOLANT: CoolantSwitch,
    EventKind.TOOL_SET: ToolNumber,
    EventKind.MESSAGE: None,
    EventKind.OFFSETS: TableRef,
    EventKind.OUTPUT: OutputLevel,
    EventKind.TOOL_DATA: TableRef,
    EventKind.PROBE_START: TableRef,
    EventKind.PROBE: TableRef,
    EventKind.INPUT: TableRef,
    EventKind.OVERRIDES: OverrideLocks,
    EventKind.TAPPING: OverrideLocks,
}

#: one kind of payload, as a caller asks for it
PayloadT = TypeVar("PayloadT", bound=EventPayload)


def check_payload(kind: enum.Enum, payload: EventPayload | None, want: type[EventPayload] | None) -> None:
    """Refuses a payload that is not the one ``kind`` carries (a programming error)."""
    if (payload is None) if want is None else type(payload) is want:
        return
    raise PlannerError(f"internal error: a {kind.value} event carries "
                       f"{want.__name__ if want else 'no payload'}, not {payload!r}")


def payload_as(kind: enum.Enum, payload: EventPayload | None, cls: type[PayloadT]) -> PayloadT:
    """``payload`` as ``cls``, which the caller knows ``kind`` carries."""
    if not isinstance(payload, cls):
        raise PlannerError(f"internal error: a {kind.value} event carries {payload!r}, not {cls.__name__}")
    return payload


@dataclass(frozen=True, slots=True)
class Event:
    """A non-motion action between moves; stopping kinds force a full stop after ``after_move``.
    ``payload`` is what the kind carries (``PAYLOAD_OF``), checked when made."""

    kind: EventKind
    line: int
    after_move: int  # index of the move before it, -1 if none
    payload: EventPayload | None = None
    message: str = ""

    def __post_init__(self) -> None:
        check_payload(self.kind, self.payload, PAYLOAD_OF[self.kind])

    @property
    def stops(self) -> bool:
        return self.kind in STOPPING_EVENTS

    def payload_as(self, cls: type[PayloadT]) -> PayloadT:
        """The payload as ``cls`` (the one this kind carries, ``PAYLOAD_OF``)."""
        return payload_as(self.kind, self.payload, cls)


@dataclass(frozen=True, slots=True)
class FrameChange:
    """The offsets a program sets on source ``line``, in force from move ``first`` on."""

    first: int
    line: int
    frame: Frame


@dataclass(frozen=True, eq=False)
class Program:
    """An interpreted, fully checked program."""

    name: str
    axes: tuple[str, ...]
    rotary: tuple[bool, ...]
    # the moves as columns (``planner.core.movestore``); Move objects given are stored so
    moves: MoveStore
    events: tuple[Event, ...]
    start_position: np.ndarray  # machine position before the first move
    # Additions (not in the minimal contract):
    line_count: int = 0  # number of source lines
    # the active modal codes as the operator reads them ("G17 G21 G90 G94 G54 G40 G49 G64"),
    # from move ``first`` on: ((first, text), ...) at each change
    modal: tuple[tuple[int, str], ...] = ()
    # the persistent parameters (planner.gcode.interpreter.PERSISTENT_PARAMETERS) after each OFFSETS
    # event, by the event's value
    parameter_sets: tuple[dict[int, float], ...] = ()
    # the offsets in force (``Frame``: the coordinate system, G5x, G92, tool length offset, XY
    # rotation), one entry at the start and one at each change, as LinuxCNC's canonical calls
    # set them; a move runs in the last one whose ``first`` is at or before it (``move_frames``)
    frames: tuple[FrameChange, ...] = ()
    # tools changed by G10 L1/L10/L11, by the TOOL_DATA event's value (planner.core.tools.Tool)
    tool_sets: tuple[Any, ...] = ()
    # the G64 P path tolerance (mm) from move ``first`` on: ((first, tolerance), ...) at each
    # change; 0 keeps the programmed path (G61, G61.1, G64 without a tolerance)
    blend_tolerance: tuple[tuple[int, float], ...] = ()
    # G64 Q, LinuxCNC's naive CAM tolerance (mm), the same way: G01 runs within it of one line
    # are run as that line (Q defaults to P)
    naive_cam_tolerance: tuple[tuple[int, float], ...] = ()
    # G38.2-G38.5 moves in program order (PROBE_START / PROBE events name them by index). The
    # moves after the first one not ``known`` are read as if it ran to its end point without a
    # contact (#5070 = 0, as LinuxCNC's preview reads it): the run stops there and reads the
    # rest again with the machine's result.
    probes: tuple[ProbeRequest, ...] = ()
    # M66 waits in program order (INPUT events name them by index), the same way: the moves
    # after the first one not ``known`` assume the awaited value
    inputs: tuple[InputRequest, ...] = ()
    # G33.1: the index of each tap's move into the hole as read (the next move backs it out);
    # LinuxCNC writes the pair as one RIGID_TAP call
    taps: tuple[int, ...] = ()
    # G33 and G76, in program order: read as LinuxCNC reads them, their feed moves at the pitch
    # times the programmed speed; a machine whose spindle has no encoder refuses to run them
    synchronised: tuple[SynchronisedMotion, ...] = ()
    # M67/M68 in program order: read as LinuxCNC reads them; a machine without analog outputs
    # refuses to run them
    analog_outputs: tuple[AnalogOutput, ...] = ()
    # G05, G05.1, G05.2/G05.3: each curve, the arcs and lines it is run as; LinuxCNC writes it
    # as one NURBS_FEED call (moves as read: indexes into the interpreter's moves, before path
    # blending)
    splines: tuple[Curve, ...] = ()

    def __post_init__(self) -> None:
        from planner.core.movestore import MoveStore  # that module reads Move from this one

        if not isinstance(self.moves, MoveStore):    # Move objects given (a test's): as columns
            object.__setattr__(self, "moves", MoveStore.from_moves(tuple(self.moves), self.start_position))

    @functools.cached_property
    def override_locks(self) -> np.ndarray | None:
        """Per move, the OVERRIDES bits in force for it (``FEED_OVERRIDE_OFF``,
        ``SPINDLE_OVERRIDE_OFF``); None when the program never turns an override off. Made
        once: the run's time scale and its spindle both read it."""
        changes = [(e.after_move + 1, e.payload_as(OverrideLocks).bits) for e in self.events
                   if e.kind in (EventKind.OVERRIDES, EventKind.TAPPING)]
        if not any(bits for _, bits in changes):
            return None
        changes.sort(key=lambda c: c[0])     # stable: of changes at one move the later wins
        firsts = np.array([max(f, 0) for f, _ in changes], dtype=np.int64)
        bits = np.array([0] + [b for _, b in changes], dtype=np.uint8)
        return bits[np.searchsorted(firsts, np.arange(len(self.moves)), side="right")]

    @functools.cached_property
    def rapid_moves(self) -> np.ndarray:
        """Per move, whether it is a rapid (G0): the limits the run holds it to differ."""
        moves = self.moves
        columns = getattr(moves, "columns", None)
        if columns is not None:            # a MoveStore: its kind column as it is
            return np.asarray(columns().kind) == int(MoveKind.RAPID)
        return np.fromiter((m.kind is MoveKind.RAPID for m in moves), bool, len(moves))

    @functools.cached_property
    def move_lines(self) -> np.ndarray:
        """Per move, its source line (a MoveStore's line column as it is)."""
        moves = self.moves
        columns = getattr(moves, "columns", None)
        if columns is not None:
            return np.asarray(columns().line)
        return np.fromiter((m.line for m in moves), np.int64, len(moves))

    @functools.cached_property
    def rotary_only_moves(self) -> np.ndarray:
        """Per move, whether only rotary axes move in it: its feed is in deg/min along the
        rotary distance, and the angular path limits hold it (LinuxCNC 2.9's rule)."""
        rotary = np.array(self.rotary, dtype=bool) if self.rotary else np.zeros(len(self.axes), bool)
        n = len(self.moves)
        if not rotary.any() or not n:
            return np.zeros(n, dtype=bool)
        moves = self.moves
        positions = getattr(moves, "positions", None)
        if positions is not None:          # a MoveStore: its positions as they are
            delta = np.abs(np.diff(np.asarray(positions), axis=0))
        else:
            delta = np.abs(np.array([np.asarray(m.end) - np.asarray(m.start) for m in moves], dtype=float))
        return np.asarray(~(delta[:, ~rotary] > 0.0).any(axis=1) & (delta[:, rotary] > 0.0).any(axis=1))

    @functools.cached_property
    def move_frames(self) -> np.ndarray | None:
        """Per move, the index into ``frames`` of the offsets it runs in; None when the
        program recorded none (machine coordinates)."""
        if not self.frames:
            return None
        n = len(self.moves)
        # the changes' firsts never go down: each frame runs up to the next change's first (a
        # frame changed again before any move runs none)
        firsts = np.clip([c.first for c in self.frames], 0, n)
        firsts[0] = 0
        runs = np.diff(np.append(firsts, n))
        return np.repeat(np.arange(len(self.frames), dtype=np.int32), runs)

    def frame_at(self, index: int) -> Frame:
        """The offsets in force for move ``index`` (before the first move: at the start), as
        the program set them (``frames``); no offsets when it recorded none."""
        return self._frame_in_force(index, math.inf)

    def frame_before(self, index: int, line: int) -> Frame:
        """The offsets in force at a stop on ``line`` before move ``index`` runs (an M6, an M0):
        those set before the stop, not those the lines after it set for that move (the G43 of
        the new tool after an M6)."""
        return self._frame_in_force(index, line)

    def _frame_in_force(self, index: int, line: float) -> Frame:
        """The last frame for move ``index`` set on or before ``line`` (the first one before
        any move)."""
        changes = self.frames
        if not changes:
            return Frame.identity(self.axes)
        k = bisect.bisect_right([c.first for c in changes], max(index, 0)) - 1
        while k > 0 and changes[k].first == index and changes[k].line > line:
            k -= 1
        return changes[max(k, 0)].frame

    def modal_at_move(self, index: int) -> str:
        """The modal codes in force for move ``index`` ("" when not recorded)."""
        text = ""
        for first, t in self.modal:
            if first > index:
                break
            text = t
        return text

    @property
    def end_position(self) -> np.ndarray:
        return self.moves[-1].end if self.moves else self.start_position

    def axis_index(self, name: str) -> int:
        return self.axes.index(name.upper())


# Fast constructors for the interpreter (frozen slotted dataclasses set fields one by one
# through object.__setattr__; these set the slots directly, about 2x faster).
_new = object.__new__
_MOVE_SET = tuple(getattr(Move, f).__set__ for f in Move.__dataclass_fields__)
_ARC_SET = tuple(getattr(Arc, f).__set__ for f in Arc.__dataclass_fields__)


def _make_move(index, line, kind, start, end, feed_mm_s, length_mm, arc, exact_stop, _new=_new, _cls=Move,
               _s0=_MOVE_SET[0], _s1=_MOVE_SET[1], _s2=_MOVE_SET[2], _s3=_MOVE_SET[3], _s4=_MOVE_SET[4],
               _s5=_MOVE_SET[5], _s6=_MOVE_SET[6], _s7=_MOVE_SET[7], _s8=_MOVE_SET[8],
               _s9=_MOVE_SET[9]) -> Move:
    m = _new(_cls)
    _s0(m, index)
    _s1(m, line)
    _s2(m, kind)
    _s3(m, start)
    _s4(m, end)
    _s5(m, feed_mm_s)
    _s6(m, length_mm)
    _s7(m, arc)
    _s8(m, exact_stop)
    _s9(m, None)
    return m


def _make_arc(plane, first_axis, second_axis, normal_axis, center, r0, r1, a0, sweep, rise, turns, turn=0.0,
              _new=_new, _cls=Arc, _s0=_ARC_SET[0], _s1=_ARC_SET[1], _s2=_ARC_SET[2], _s3=_ARC_SET[3],
              _s4=_ARC_SET[4], _s5=_ARC_SET[5], _s6=_ARC_SET[6], _s7=_ARC_SET[7], _s8=_ARC_SET[8],
              _s9=_ARC_SET[9], _s10=_ARC_SET[10], _s11=_ARC_SET[11]) -> Arc:
    a = _new(_cls)
    _s0(a, plane)
    _s1(a, first_axis)
    _s2(a, second_axis)
    _s3(a, normal_axis)
    _s4(a, center)
    _s5(a, r0)
    _s6(a, r1)
    _s7(a, a0)
    _s8(a, sweep)
    _s9(a, rise)
    _s10(a, turns)
    _s11(a, turn)
    return a
