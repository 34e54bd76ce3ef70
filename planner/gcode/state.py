"""The interpreter's state, as LinuxCNC's ``setup`` keeps it, in parts: what the machine fixes
for the run (``Setup``), the modal state M70 saves (``Modal``), the offsets (``Offsets``), the
canned cycles' sticky words (``CycleState``), an open curve (``CurveState``), the O-word call
stack (``CallStack``) and what the program has made so far (``Record``), plus the few values
of the motion itself on ``InterpBase``: the position, the motion mode, the tool.

``InterpBase`` holds these and the primitives every family of codes uses (errors, the
coordinate frames of the XY rotation, the offsets' composition); each family is a class on it
in its own module (``motion``, ``offsets``, ``tools``, ``cycles`` ...), put together by
``planner.gcode.interpreter.Interpreter`` as LinuxCNC's ``Interp`` is one class in many files.
"""

from __future__ import annotations

import re
from abc import ABC, abstractmethod
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from planner.core.errors import BlockError, PlannerError, SourceError
from planner.core.frames import Frame as CoordinateFrame
from planner.core.machine import MachineSpec
from planner.core.movestore import MoveBuffer
from planner.core.program import (
    FEED_HOLD_DEFERRED,
    FEED_OVERRIDE_OFF,
    SPINDLE_OVERRIDE_OFF,
    AnalogOutput,
    Curve,
    Event,
    FrameChange,
    InputRequest,
    MoveKind,
    ProbeRequest,
    ProbeResult,
    Program,
    SynchronisedMotion,
)
from planner.core.tools import Tool, ToolTable
from planner.gcode.codes import SYSTEMS, G, gname
from planner.gcode.cutter_comp import CutterComp
from planner.gcode.lexer import LexError, Params, compact, original_column
from planner.gcode.oword import Structure

__all__ = ["MAX_ERRORS", "PERSISTENT_PARAMETERS", "system_base", "Setup", "Modal", "Offsets", "CycleState",
           "CurveState", "CallStack", "Record", "Frame", "InterpBase"]

MAX_ERRORS = 100
VALUE_LIMIT = 1e9  # |word value| above this is rejected (also catches inf/nan)
#: F may go further: programs write F1e9 for "as fast as the machine goes" (LinuxCNC reads it,
#: and the feed is held to the machine's limits either way); 1e12 keeps inverse-time products
#: far from overflow
FEED_LIMIT = 1e12
# a tap's moves: the feed follows the spindle, so neither override may change one of them, and
# the operator's feed hold waits until the tap is out of the hole
TAP_LOCK = FEED_OVERRIDE_OFF | SPINDLE_OVERRIDE_OFF | FEED_HOLD_DEFERRED
MAX_TURNS = 10_000
ZERO_LEN = 1e-9  # moves shorter than this (mm, and deg on rotary axes) are dropped
ZERO_FEED = "feed rate is zero: program an F word before the first G01/G02/G03"
RAPID, LINE, ARC = MoveKind.RAPID, MoveKind.LINE, MoveKind.ARC
#: #5061-#5069: where the last probe move's input changed (program coordinates); #5070: 1 if it did
P_PROBE, P_PROBE_TRIPPED = 5061, 5070
#: #5399: the value M66 read (-1 when the wait timed out)
P_INPUT = 5399
#: LinuxCNC's parameters for the coordinate systems: each system has 20 numbers from #5221
#: (X Y Z A B C U V W, then the XY rotation); G92 #5211-#5219 (#5210: on); the G28 and G30
#: positions #5161- and #5181-; #5220 the system in use
PARAM_AXES = "XYZABCUVW"
P_G28, P_G30, P_G92_ON, P_G92, P_SYSTEM = 5161, 5181, 5210, 5211, 5220
#: parameters a program leaves for the next one (LinuxCNC keeps them in its var file)
PERSISTENT_PARAMETERS = (frozenset(range(5161, 5170)) | frozenset(range(5181, 5190))
                         | frozenset(range(5210, 5221))
                         | frozenset(p for k in range(9) for p in range(5221 + 20 * k, 5231 + 20 * k)))
FAST_NUM = r"[-+]?(?:\d{1,9}(?:\.\d*)?|\.\d+)"


def short_way(current: float, target: float) -> float:
    """Where a wrapped rotary axis (LinuxCNC's WRAPPED_ROTARY) goes for an absolute target: the
    target modulo 360, reached by a turn of at most half a turn (+180 for exactly half)."""
    d = (target - current) % 360.0
    return current + (d - 360.0 if d > 180.0 else d)


def system_base(code: int) -> int:
    """#5221 for G54, #5241 for G55 ... #5381 for G59.3."""
    return 5221 + 20 * SYSTEMS.index(code)


@dataclass(frozen=True, slots=True)
class Setup:
    """What the machine and the caller fix for the whole run."""

    axes: tuple[str, ...]
    rotary: tuple[bool, ...]
    start: tuple[float, ...]                 # machine position before the first move
    block_delete: bool
    max_errors: int
    spindle_max_rpm: float
    subroutine_dirs: tuple[str, ...]
    outputs: frozenset[int]                  # M62-M65 P: the digital outputs configured
    inputs: frozenset[int]                   # M66 P: the digital inputs configured
    mcodes: dict[int, tuple[str, str, int, bool]]   # M100-M199: (action, message, output, on)
    probe_results: tuple[ProbeResult | None, ...]   # what the machine's probe did on the first G38.x
    input_results: tuple[float | None, ...]  # what M66 read on the first waits
    blend_default_mm: float                  # G64 without P: the machine's path tolerance
    after_tool_change: str = ""              # an O-word call run after an M6 that changes the tool
    zero_length: float = ZERO_LEN
    n: int = field(init=False)
    axis_index: dict[str, int] = field(init=False)
    linear_idx: tuple[int, ...] = field(init=False)
    rotary_idx: tuple[int, ...] = field(init=False)
    all_linear: bool = field(init=False)
    axis_param: tuple[int, ...] = field(init=False)   # each axis's place in #5221's X Y Z A B C U V W
    fast_letters: frozenset[str] = field(init=False)
    fast_order: tuple[str, ...] = field(init=False)   # the letters of ``fast_re``'s groups after G
    wrapped: tuple[bool, ...] = ()           # per axis: LinuxCNC's WRAPPED_ROTARY
    any_wrapped: bool = field(init=False)
    fast_re: re.Pattern[str] = field(init=False)

    def __post_init__(self) -> None:
        n = len(self.axes)
        put = object.__setattr__
        put(self, "n", n)
        put(self, "axis_index", {a: i for i, a in enumerate(self.axes)})
        put(self, "linear_idx", tuple(i for i in range(n) if not self.rotary[i]))
        put(self, "rotary_idx", tuple(i for i in range(n) if self.rotary[i]))
        put(self, "all_linear", not self.rotary_idx)
        put(self, "axis_param", tuple(PARAM_AXES.index(a) for a in self.axes))
        put(self, "fast_letters", frozenset(self.axes) | frozenset("IJKRF"))
        put(self, "fast_order", (*self.axes, "I", "J", "K", "R", "F"))
        if len(self.wrapped) != n:
            put(self, "wrapped", (False,) * n)
        put(self, "any_wrapped", any(self.wrapped))
        # the usual CAM block, in the usual word order, as one regex; numbers below 1e9
        put(self, "fast_re", re.compile(
            r"(?:N\d+)?(?:G0*([0-3]))?"
            + "".join(f"(?:{a}({FAST_NUM}))?" for a in self.axes)
            + "".join(f"(?:{a}({FAST_NUM}))?" for a in "IJKRF")
            + r"\Z"
        ))


@dataclass(slots=True)
class Modal:
    """The modal state M70 saves and M72 restores (LinuxCNC 2.9's list; the motion mode is not
    part of it). LinuxCNC's reference set-up: G21 G17 G40 G49 G54 G80 G90 G94 G91.1 G64 G99."""

    inch: bool = False
    scale: float = 1.0                 # mm per program length unit
    plane: int = G.G17
    comp_code: int = G.G40
    absolute: bool = True              # G90
    arc_absolute: bool = False         # G90.1
    # feed mode: G94 units per minute, G93 inverse time (an F on every feed move: its duration
    # is 1/F minutes), G95 units per revolution of the programmed spindle speed
    feed_mode: int = G.G94
    feed_mm_s: float = 0.0
    feed_per_rev: float = 0.0          # G95: mm per revolution
    inverse_f: float = 0.0             # G93: the block's F (1/min)
    work_code: int = G.G54
    tlo_code: int = G.G49
    retract_r_plane: bool = True       # G99 (LinuxCNC starts in it), G98: back to the start level
    exact_stop: bool = False           # G61
    exact_path: bool = False           # G61.1
    # G64 P: the corner blends' tolerance (mm); G64 Q: LinuxCNC's naive CAM tolerance (runs of
    # G01 within Q of one line are one line), P's without Q
    blend_tol_mm: float = 0.0
    naive_cam_mm: float = 0.0
    spindle_rpm: float = 0.0
    spindle_dir: int = 0
    coolant: int = 0                   # bits: 1 mist (M7), 2 flood (M8); M9 both off
    diameter: bool = False             # G7: X words are diameters (halved as read), G8: radii
    # M48-M51: whether the operator's feed and spindle overrides act on what follows
    feed_override_on: bool = True
    spindle_override_on: bool = True
    feed_hold_on: bool = True          # M53: what LinuxCNC's #<_feed_hold> reads (no switch here)


@dataclass(slots=True)
class Offsets:
    """Program coordinates to the machine's: the coordinate systems' offsets (G54-G59.3) and
    the frame in force (``planner.core.frames.Frame``: the origin of the system in use and its
    XY rotation, G92/G52, the tool length offset), changed only by ``set_offset``; ``total``
    its sum (machine = program + total, rotation aside), kept for the moves' targets."""

    systems: dict[int, tuple[float, ...]]
    frame: CoordinateFrame
    total: tuple[float, ...] = ()

    def __post_init__(self) -> None:
        self.total = self.frame.total

    @property
    def work(self) -> tuple[float, ...]:
        return self.frame.g5x

    @property
    def g92(self) -> tuple[float, ...]:
        return self.frame.g92

    @property
    def tlo(self) -> tuple[float, ...]:
        return self.frame.tool

    @property
    def rotation(self) -> float:
        return self.frame.rotation_deg


@dataclass(slots=True)
class CycleState:
    """The canned cycles' sticky words (program units) and the level a sequence started from
    (G98 returns there; None: taken anew at the next cycle)."""

    il: float | None = None
    r_word: float = 0.0
    z_word: float = 0.0
    p: float = 0.0
    q: float = 0.0


@dataclass(slots=True)
class CurveState:
    """G05's first control point offset when I and J are left out (-P and -Q of the G05 before,
    program units; LinuxCNC keeps them in its canned cycles' I and J), and an open NURBS
    (G05.2 ... G05.3): its control points (x, y, weight), order and first line."""

    spline_ij: tuple[float, float] = (0.0, 0.0)
    nurbs: list[tuple[float, float, float]] | None = None
    order: int = 3
    line: int = 0


class Frame:
    """One level of the O-word call stack."""

    __slots__ = ("file", "lines", "structure", "return_pc", "call_line", "entry", "repeats", "saved_numbered",
                 "saved_named", "fanuc", "loops")

    def __init__(self, file: str, lines: list[str], structure: Structure, return_pc: int, call_line: int):
        self.file = file
        self.lines = lines
        self.structure = structure
        self.return_pc = return_pc
        self.call_line = call_line      # line of the call in the program (0 in the program itself)
        self.entry = 0
        self.repeats: dict[int, int] = {}
        self.saved_numbered: dict[int, float] = {}
        self.saved_named: dict[str, float] = {}
        self.fanuc = False              # an M98 call: no arguments, the caller's parameters shared
        self.loops = 1                  # M98 L: runs left, this one included

    def line_of(self, pc: int) -> int:
        return pc + 1


#: what M70 saves: the modal state, and the offsets in use as they were
SavedModal = tuple[Modal, tuple[float, ...], tuple[float, ...], float]


@dataclass(slots=True)
class CallStack:
    """Where the O-word flow is: the file and line run (G7x finds its profile there), the call
    level, the modal state M70/M73 saved by level (with M73's autorestore), the subroutine files
    read, and the places LinuxCNC 2.9 keeps per O-word name and per sub definition."""

    frame: Frame | None = None
    pc: int = 0
    level: int = 0
    saved_modal: dict[int, tuple[SavedModal, bool]] = field(default_factory=dict)
    sub_files: dict[str, tuple[str, list[str], Structure]] = field(default_factory=dict)
    oword_places: dict[str, tuple[str, int, str]] = field(default_factory=dict)
    sub_places: dict[tuple[str, str], int] = field(default_factory=dict)
    tool_changed: bool = False       # an M6 changed the tool on the line just read


@dataclass(slots=True)
class Record:
    """What the program made so far, as the ``Program`` will hold it: the moves (packed as they
    come), the events, and each change of the offsets, modal text and tolerances by the first
    move it applies to."""

    out: MoveBuffer
    frames: list[FrameChange]         # the offsets at the start and at each change
    modal_changes: list[tuple[int, str]]
    blend_changes: list[tuple[int, float]]
    naive_changes: list[tuple[int, float]]
    events: list[Event] = field(default_factory=list)
    parameter_sets: list[dict[int, float]] = field(default_factory=list)   # G10, G92, G28.1 ...
    tool_sets: list[Tool] = field(default_factory=list)       # tools changed by G10 L1/L10/L11
    probes: list[ProbeRequest] = field(default_factory=list)  # G38.x
    taps: list[int] = field(default_factory=list)             # G33.1: the moves into the hole
    synchronised: list[SynchronisedMotion] = field(default_factory=list)   # G33, G76
    analog_outputs: list[AnalogOutput] = field(default_factory=list)       # M67, M68
    splines: list[Curve] = field(default_factory=list)        # G05, G05.1, G05.2/G05.3
    inputs_read: list[InputRequest] = field(default_factory=list)          # M66
    override_bits: int = 0            # the OVERRIDES bits last written for the moves

    def build(self, name: str, setup: Setup, line_count: int) -> Program:
        moves = self.out.store()
        start = np.array(setup.start, dtype=float)
        start.setflags(write=False)
        return Program(
            name=name,
            axes=setup.axes,
            rotary=setup.rotary,
            moves=moves,
            events=tuple(self.events),
            start_position=start,
            line_count=line_count,
            modal=tuple(self.modal_changes),
            parameter_sets=tuple(self.parameter_sets),
            frames=tuple(self.frames),
            tool_sets=tuple(self.tool_sets),
            blend_tolerance=tuple(self.blend_changes),
            naive_cam_tolerance=tuple(self.naive_changes),
            probes=tuple(self.probes),
            inputs=tuple(self.inputs_read),
            taps=tuple(self.taps),
            splines=tuple(self.splines),
            synchronised=tuple(self.synchronised),
            analog_outputs=tuple(self.analog_outputs),
        )


class InterpBase(ABC):
    """The interpreter's state and the primitives all its families of codes use."""

    progress: Callable[[int, int], None] | None = None

    def __init__(self, name: str, machine: Any, start_position: Any, block_delete: bool, max_errors: int,
                 tools: ToolTable | None = None, tool_in_spindle: int = 0,
                 spindle: tuple[int, float] = (0, 0.0), subroutine_dirs: Sequence[str] = (),
                 parameters: dict[int, float] | None = None,
                 probe_results: Sequence[ProbeResult | None] = (),
                 input_results: Sequence[float | None] = (),
                 tool_offset: tuple[int, Sequence[float]] | None = None):
        if machine is None:
            machine = MachineSpec.default()
        axes = tuple(a.name.upper() for a in machine.axes)
        n = len(axes)
        if start_position is None:
            start = [0.0] * n
        else:
            start = [float(v) for v in np.asarray(start_position, dtype=float).ravel()]
            if len(start) != n:
                raise PlannerError(f"start_position has {len(start)} values for {n} axes")
        planner_settings = getattr(machine, "planner", None)
        blend_default_mm = float(getattr(planner_settings, "blend_tolerance_mm", 0.0) or 0.0)
        self.setup = Setup(
            axes=axes, rotary=tuple(bool(a.rotary) for a in machine.axes), start=tuple(start),
            block_delete=block_delete, max_errors=max_errors,
            spindle_max_rpm=float(getattr(machine, "spindle_max_rpm", 24000.0)),
            subroutine_dirs=tuple(subroutine_dirs) or tuple(machine.subroutine_paths()),
            outputs=frozenset(getattr(machine, "outputs", ()) or ()),
            inputs=frozenset(getattr(machine, "inputs", ()) or ()),
            mcodes=dict(getattr(machine, "mcodes", {}) or {}),
            probe_results=tuple(probe_results), input_results=tuple(input_results),
            blend_default_mm=blend_default_mm,
            after_tool_change=str(getattr(machine, "after_tool_change", "") or ""),
            wrapped=tuple(bool(getattr(a, "wrapped", False)) for a in machine.axes))
        setup = self.setup
        self.name = name
        self.params = Params()
        # the persistent parameters the machine kept from earlier programs (G92, G28/G30
        # positions, G59.1-G59.3), then the work offsets as the machine has them now
        num = self.params.numbered
        for number, value in (parameters or {}).items():
            if int(number) in PERSISTENT_PARAMETERS:
                num[int(number)] = float(value)
        machine_offsets = getattr(machine, "work_offsets", None) or {}
        systems: dict[int, tuple[float, ...]] = {}
        for code in SYSTEMS:
            key, base = gname(code), system_base(code)
            if key in machine_offsets:
                val = tuple(float(v) for v in machine_offsets[key])
                if len(val) != n:
                    raise PlannerError(f"machine work offset {key} has {len(val)} values for {n} axes")
                for i, v in enumerate(val):
                    num[base + setup.axis_param[i]] = v
            else:
                val = tuple(num.get(base + p, 0.0) for p in setup.axis_param)
            systems[code] = val
        on = num.get(P_G92_ON, 0.0) != 0.0
        num[P_SYSTEM] = 1.0
        # the tool length offset the machine has in force (LinuxCNC keeps it from one program
        # to the next): (G43 / G43.1 / G49, the offset per axis)
        tlo_code: int = G.G49
        tlo: tuple[float, ...] = (0.0,) * n
        if tool_offset is not None:
            tlo_code, tlo = tool_offset[0], tuple(float(v) for v in tool_offset[1])
            if len(tlo) != n or tlo_code not in (G.G43, G.G43_1, G.G43_2, G.G49):
                raise PlannerError(f"tool_offset {tool_offset!r}: G43, G43.1, G43.2 or G49 and {n} values")
        g92 = tuple(num.get(P_G92 + p, 0.0) if on else 0.0 for p in setup.axis_param)
        self.offsets = Offsets(systems, CoordinateFrame(setup.axes, systems[G.G54], g92, tlo,
                                                        num.get(system_base(G.G54) + 9, 0.0)))
        self.modal = Modal(blend_tol_mm=blend_default_mm, naive_cam_mm=blend_default_mm,
                           spindle_dir=int(spindle[0]), spindle_rpm=float(spindle[1]), tlo_code=tlo_code)
        self.cycle = CycleState()
        self.curve = CurveState()
        self.calls = CallStack()
        self.rec = Record(
            out=MoveBuffer(setup.start),
            frames=[FrameChange(0, 0, self.offsets.frame)], modal_changes=[],
            blend_changes=[(0, blend_default_mm)], naive_changes=[(0, blend_default_mm)])
        # the motion: where the tool is (machine coordinates), the motion mode (None: G80),
        # G96's speed counted (rpm: D, else the spindle's highest; None in G97)
        self.pos = list(start)
        self.motion: int | None = None
        self.css_max_rpm: float | None = None
        # None: no tool table (every tool number known, offsets 0: the reference set-up);
        # a table: a tool must be in it to be selected, loaded or used for an offset. Without
        # one, a G10 L1/L10/L11 makes the table of the tools it sets, and every other number is
        # still known (``any_tool``)
        self.tools = tools
        self.any_tool = tools is None
        self.tool = int(tool_in_spindle)   # in the spindle (M6, M61)
        self.selected = self.tool          # T word: prepared for the next M6
        self.comp = CutterComp()
        self.plane_cache: dict[int, tuple] = {}
        self.errors: list[SourceError] = []
        self.truncated = False
        self.ended = False
        self.started = False               # saw content or an opening '%'
        self.current_line = 0

    @abstractmethod
    def line(self, raw: str, line_no: int) -> bool:
        """Read one line (the driver's, ``Interpreter.line``): the O-word flow and the bulk
        reader hand it the lines they do not take; True when the program ends there."""

    # ------------------------------------------------------------------ errors
    def error(self, line: int, col: int, message: str) -> None:
        if len(self.errors) >= self.setup.max_errors:
            self.truncated = True
            return
        self.errors.append(SourceError(self.name, line, col, message))

    @staticmethod
    def column(raw: str, letter: str | None) -> int:
        """The column of word ``letter`` (or code such as "G28", "M6") in line ``raw``."""
        if not letter:
            return 1
        try:
            code = compact(raw)
        except LexError:
            return 1
        if len(letter) > 1:  # a code such as "G28", "G90.1", "M6": find that word
            whole, _, frac = letter[1:].partition(".")
            pat = rf"{letter[0]}0*{whole}" + (rf"\.{frac}0*(?![0-9])" if frac else r"(?![0-9]|\.[0-9])")
            m = re.search(pat, code)
            if m:
                return original_column(raw, m.start())
            letter = letter[0]
        i = code.find(letter)
        return original_column(raw, i) if i >= 0 else 1

    def comp_refuses(self, what: str, letter: str) -> None:
        """LinuxCNC refuses these while compensation is on (whatever the radius)."""
        if self.comp.side != 0:
            raise BlockError(f"cannot {what} with cutter compensation on ({gname(self.modal.comp_code)}): "
                             "program G40 first", letter)

    # ------------------------------------------------------------------ coordinates
    def set_offset(self, work: tuple[float, ...] | None = None, tlo: tuple[float, ...] | None = None,
                   g92: tuple[float, ...] | None = None, rotation: float | None = None) -> None:
        """The frame in force from the next move on: the origin of the system in use (``work``),
        the tool length offset, G92 and the XY rotation as given (the others as they are), in
        the coordinate system the modal state names; the program records the change."""
        o = self.offsets
        f = o.frame
        o.frame = CoordinateFrame(self.setup.axes, f.g5x if work is None else work,
                                  f.g92 if g92 is None else g92, f.tool if tlo is None else tlo,
                                  f.rotation_deg if rotation is None else rotation,
                                  SYSTEMS.index(self.modal.work_code) + 1)
        o.total = o.frame.total
        self.rec.frames.append(FrameChange(len(self.rec.out), self.current_line, o.frame))

    @property
    def frame(self) -> CoordinateFrame:
        """The frame in force."""
        return self.offsets.frame

    def prog_xy(self, pos: Sequence[float]) -> tuple[float, float]:
        """X and Y of a machine position in program coordinates (mm), the XY rotation undone
        (``Frame.xy_to_program`` of the frame in force)."""
        ix, iy = self.setup.axis_index["X"], self.setup.axis_index["Y"]
        return self.frame.xy_to_program(pos[ix], pos[iy])

    def machine_xy(self, x: float, y: float) -> tuple[float, float]:
        """Machine X and Y of program X and Y (mm) (``Frame.xy_to_machine``)."""
        return self.frame.xy_to_machine(x, y)

    def program_position(self, p: Sequence[float]) -> list[float]:
        """Program coordinates (mm, deg) of machine position ``p`` (``Frame.point_to_program``)."""
        return self.frame.point_to_program(p)
