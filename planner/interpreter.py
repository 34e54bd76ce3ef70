"""G-code interpreter: RS274/NGC text -> Program of exact moves, read the way LinuxCNC 2.9 does.

Supported (everything else is an error with file:line:col, never skipped):
  motion G00 G01 G02 G03 (R or I/J/K, P turns) in G17 G18 G19, G04 P (s), G20 G21, G90 G91,
  G90.1 G91.1, G53 (one block, with G00/G01), G61 G61.1 G64 (P/Q accepted);
  curves G05 (cubic), G05.1 (quadratic), G05.2/G05.3 (NURBS) in G17, run as LinuxCNC runs them
  (``planner.splines``);
  feed modes G93 (inverse time) G94 G95 (per revolution), G97;
  canned cycles G73 G74 G81-G86 G89, G98/G99, G80 (also beside another motion code);
  G33.1 rigid tapping (run as feed moves), G33 and the G76 threading cycle (read; recorded in
  ``Program.synchronised``, which a machine without a spindle encoder refuses to run);
  the lathe cycles G70, G71/G71.1/G71.2, G72/G72.1/G72.2 on a profile subroutine (``planner.g7x``);
  tool data G10 L1/L10/L11 (TOOL_DATA events);
  coordinate systems G54-G59.3, G10 L2 (with R: XY rotation)/L20, G92 G92.1 G92.2 G92.3, G52,
  G28/G28.1, G30/G30.1
  with LinuxCNC's parameters (``PERSISTENT_PARAMETERS``, OFFSETS events);
  cutter radius compensation G40, G41/G42 (tool table), G41.1/G42.1 (``planner.cutter_comp``);
  G43 / G43 H / G43.1 / G43.2 / G49 tool length offsets from the tool table (``planner.tools``);
  polar coordinates @ (distance) ^ (angle) in G17; F S T;
  M00 M01 M02 M30 M03 M04 M05 M06 M61 M07 M08 M09; M62-M65 and user M100-M199 as the machine
  configuration defines them ([[outputs]], [[mcodes]]);
  O-words (``planner.oword``: subroutines, subroutine files, if, while, do, repeat, break,
  continue, return values), expressions, #numbered / #<named> / #<_global> parameters,
  (MSG,) (DEBUG,) (PRINT,) messages, M70-M73 modal state save/restore;
  N line numbers, '/' block delete, ( ) and ; comments, % delimiters, Fanuc 'O0001' lines.
Set-up as LinuxCNC's reference run: G21 G17 G40 G49 G54 G80 G90 G94 G91.1 G64 G99, motion mode
none (axis words need a G00-G03 first).
"""

from __future__ import annotations

import codecs
import io
import math
import os
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from planner import g7x
from planner.arcs import (
    MM_PER_INCH,
    ArcError,
    center_from_radius,
    check_center_radii,
    sweep_angle,
)
from planner.bulk import newline_offsets, scan_plain
from planner.cutter_comp import LEFT, RIGHT, CutterComp
from planner.errors import BlockError as _BlockError
from planner.errors import PlannerError, ProgramError, SourceError
from planner.gcpause import gc_paused
from planner.heap import trim_heap
from planner.lexer import LexError, Params, compact, evaluate_brackets, original_column, read_line
from planner.movestore import MoveBuffer
from planner.oword import Statement, Structure, StructureError, has_control_flow, scan
from planner.program import (
    FEED_HOLD_DEFERRED,
    FEED_OVERRIDE_OFF,
    SPINDLE_OVERRIDE_OFF,
    AnalogOutput,
    Arc,
    Curve,
    Event,
    EventKind,
    InputRequest,
    MoveKind,
    ProbeRequest,
    ProbeResult,
    Program,
    SynchronisedMotion,
    WaitMode,
    _make_arc,
    spiral_length_mm,
)
from planner.splines import nurbs_pieces
from planner.tools import Tool, ToolTable

__all__ = ["parse_program", "parse_file", "read_program", "read_program_bytes",
           "MAX_ERRORS"]

MAX_ERRORS = 100
_VALUE_LIMIT = 1e9  # |word value| above this is rejected (also catches inf/nan)
#: F may go further: programs write F1e9 for "as fast as the machine goes" (LinuxCNC reads it,
#: and the feed is held to the machine's limits either way); 1e12 keeps inverse-time products
#: far from overflow
_FEED_LIMIT = 1e12
# a tap's moves: the feed follows the spindle, so neither override may change one of them, and
# the operator's feed hold waits until the tap is out of the hole
_TAP_LOCK = FEED_OVERRIDE_OFF | SPINDLE_OVERRIDE_OFF | FEED_HOLD_DEFERRED
_TRIM_BYTES = 32 << 20   # program bytes read in bulk between two trims of the heap


@dataclass
class _BulkState:
    """What the bulk reader carries from one piece of the program to the next."""

    scanned: bool = False  # a block was scanned (the first is small)
    skip: int = 0          # blocks left to read line by line: the last scan found few long runs
    trimmed_at: int = 0    # where the heap was last trimmed
_MAX_TURNS = 10_000
_ZERO_LEN = 1e-9  # moves shorter than this (mm, and deg on rotary axes) are dropped
#: a curve's arcs above this radius (1 km: LinuxCNC's biarc where the curve hardly bends) are
#: fed as the lines they nearly are: a stretch of 10 mm departs from such an arc by at most
#: 12.5 nm (100 mm: 1.25 um), and a centre that far away leaves the arc's own measure of its
#: contour error (a distance from the centre) rounding above a nanometre
_CURVE_MAX_RADIUS_MM = 1e6

# Modal groups of the supported G codes (code * 10 as int), RS274/NGC table 4.
_G_GROUP = {
    40: 0, 280: 0, 530: 0, 100: 0, 281: 0, 300: 0, 301: 0, 520: 0, 920: 0,
    921: 16, 922: 16, 923: 16,     # LinuxCNC 2.9: a group of their own, after group 0's code
    0: 1, 10: 1, 20: 1, 30: 1, 800: 1, 382: 1, 383: 1, 384: 1, 385: 1, 331: 1, 330: 1, 760: 1,
    700: 1, 710: 1, 711: 1, 712: 1, 720: 1, 721: 1, 722: 1,
    50: 1, 51: 1, 52: 1, 53: 0,
    170: 2, 180: 2, 190: 2,
    900: 3, 910: 3,
    901: 4, 911: 4,
    930: 5, 940: 5, 950: 5,
    960: 14, 970: 14,
    200: 6, 210: 6,
    400: 7, 410: 7, 420: 7, 411: 7, 421: 7,
    430: 8, 431: 8, 432: 8, 490: 8,
    540: 12, 550: 12, 560: 12, 570: 12, 580: 12, 590: 12, 591: 12, 592: 12, 593: 12,
    610: 13, 611: 13, 640: 13,
    730: 1, 740: 1, 810: 1, 820: 1, 830: 1, 840: 1, 850: 1, 860: 1, 890: 1,
    980: 10, 990: 10,
    70: 15, 80: 15,
}
#: canned cycles (motion group 1), as LinuxCNC 2.9 runs them (interp_cycles.cc)
_CYCLES = frozenset({730, 740, 810, 820, 830, 840, 850, 860, 890})
#: G38.2-G38.5, straight probe moves (motion group 1, modal as in LinuxCNC)
_PROBES = frozenset({382, 383, 384, 385})
#: #5061-#5069: where the last probe move's input changed (program coordinates); #5070: 1 if it did
_P_PROBE, _P_PROBE_TRIPPED = 5061, 5070
#: #5399: the value M66 read (-1 when the wait timed out)
_P_INPUT = 5399
#: the lathe cycles G70 (finishing), G71/G72 (roughing; .1 no pockets, .2 pockets only)
_G7X = frozenset({700, 710, 711, 712, 720, 721, 722})
#: G33, G33.1, G76: feed moves at the pitch (K, P) times the spindle speed; F is not theirs
_SYNCHRONISED = frozenset({330, 331, 760})
_CYCLE_NEEDS_P = frozenset({820, 860, 890})
_CYCLE_NEEDS_Q = frozenset({730, 830})
_CYCLE_TAKES_P = _CYCLE_NEEDS_P | {740, 840}
#: G73 backs off and G83 comes back down to this far above the last peck: LinuxCNC 2.9's
#: G83_RAPID_DELTA, 0.010 inch in every unit (later versions read it from their INI file)
_PECK_CLEARANCE_MM = 0.254
#: pecks or repeats of one block above this are refused (a typo such as Q0.0001 on a deep
#: hole would otherwise make millions of moves)
_MAX_CYCLE_MOVES = 100_000
_G_UNSUPPORTED = {
    870: "G87 back boring: it needs an oriented spindle stop (M19), which this machine's spindle "
         "does not have",
    880: "G88 boring with a manual retract: the operator would jog the spindle out during a "
         "program stop; use G86 or G89",
    150: "G15 polar coordinates",
    160: "G16 polar coordinates",
    680: "G68 coordinate rotation", 690: "G69 coordinate rotation",
    171: "G17.1 selects the UV plane, of U and V axes this machine does not have",
    181: "G18.1 selects the WU plane, of U and W axes this machine does not have",
    191: "G19.1 selects the VW plane, of V and W axes this machine does not have",
}
_SHOWN_GROUPS = frozenset({2, 3, 6, 7, 8, 12, 13, 15})  # the modal groups the panel shows
#: group 0 codes whose axis words are data, not a motion target
_AXIS_USERS = frozenset({100, 280, 300, 520, 920})
#: coordinate systems 1-9 (G54 ... G59.3) and LinuxCNC's parameters for them: each system has
#: 20 numbers from #5221 (X Y Z A B C U V W, then the XY rotation); G92 #5211-#5219 (#5210: on);
#: the G28 and G30 positions #5161- and #5181-; #5220 the system in use
_SYSTEMS = (540, 550, 560, 570, 580, 590, 591, 592, 593)
_PARAM_AXES = "XYZABCUVW"
_P_G28, _P_G30, _P_G92_ON, _P_G92, _P_SYSTEM = 5161, 5181, 5210, 5211, 5220
#: parameters a program leaves for the next one (LinuxCNC keeps them in its var file)
PERSISTENT_PARAMETERS = (frozenset(range(5161, 5170)) | frozenset(range(5181, 5190))
                         | frozenset(range(5210, 5221))
                         | frozenset(p for k in range(9) for p in range(5221 + 20 * k, 5231 + 20 * k)))


def system_base(code: int) -> int:
    """#5221 for G54, #5241 for G55 ... #5381 for G59.3."""
    return 5221 + 20 * _SYSTEMS.index(code)
_M_GROUP = {0: 4, 1: 4, 2: 4, 30: 4, 6: 6, 61: 6, 3: 7, 4: 7, 5: 7, 7: 8, 8: 8, 9: 8,
            62: 5, 63: 5, 64: 5, 65: 5, 66: 5, 67: 5, 68: 5, 70: 11, 71: 11, 72: 11, 73: 11,
            48: 9, 49: 9, 50: 9, 51: 9, 52: 9, 53: 9,
            **dict.fromkeys(range(100, 200), 10)}
_M_UNSUPPORTED = {19: "M19 orients the spindle, which this machine's spindle cannot",
                  60: "M60 exchanges pallets and pauses; this machine has no pallet shuttle"}
_WORD_LETTERS = set("FSTPQRIJKDHL")
_AXIS_LETTERS = "XYZABC"
# plane code -> (name, first, second, normal, centre letter of first, of second, letter not allowed)
_PLANES = {
    170: ("XY", "X", "Y", "Z", "I", "J", "K"),
    180: ("ZX", "Z", "X", "Y", "K", "I", "J"),
    190: ("YZ", "Y", "Z", "X", "J", "K", "I"),
}
_PLANE_G = {170: "G17", 180: "G18", 190: "G19"}
_RAPID, _LINE, _ARC = MoveKind.RAPID, MoveKind.LINE, MoveKind.ARC
_ZERO_FEED = "feed rate is zero: program an F word before the first G01/G02/G03"
_FAST_NUM = r"[-+]?(?:\d{1,9}(?:\.\d*)?|\.\d+)"
_FAST_G = {"0": 0, "00": 0, "1": 10, "01": 10, "2": 20, "02": 20, "3": 30, "03": 30}
_STOP_EVENTS = {0: EventKind.PAUSE, 1: EventKind.OPTIONAL_PAUSE, 2: EventKind.END, 30: EventKind.END}


_MESSAGE_RE = re.compile(r"\(\s*(MSG|DEBUG|PRINT|ABORT)\s*,([^)]*)\)", re.IGNORECASE)
_PARAM_TEXT_RE = re.compile(r"#<([^>]*)>|#(\d+)")
_MAX_EXECUTED = 10_000_000   # blocks run by one program with O-word loops
_MAX_CALL_DEPTH = 50
_RETURN = -2


class _Frame:
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


def _statement_col(raw: str, index: int) -> int:
    return original_column(raw, index) if index else 1


def _compact_or_none(raw: str) -> str | None:
    try:
        return compact(raw)
    except LexError:
        return None


def _percent_line(s: str) -> bool:
    """A stripped line that is a '%' alone (a comment beside it allowed)."""
    return s[0] == "%" and (s == "%" or _compact_or_none(s) == "%")


def _through_closing_percent(lines: list[str]) -> int:
    """How many lines the program has: up to and with its closing '%' (the first '%' line after
    content or after an opening '%'), else all: LinuxCNC ignores what follows it, subroutines
    defined there included."""
    started = False
    for i, raw in enumerate(lines):
        s = raw.strip()
        if not s:
            continue
        if _percent_line(s):
            if started:
                return i + 1
            started = True
        elif not started and _compact_or_none(s) != "":
            started = True
    return len(lines)


def _gname(code10: int) -> str:
    return f"G{code10 // 10}" if code10 % 10 == 0 else f"G{code10 // 10}.{code10 % 10}"


class _Interpreter:
    use_fast = True  # the fast paths (one regex per line; word fast path); tests compare both ways
    use_bulk = True  # plain coordinate lines read many at a time (planner.bulk); tests compare too
    BULK_LINES = 16_384  # lines scanned at once by the bulk reader (its arrays: ~40 MB)
    BULK_MIN_RUN = 24  # shorter runs of plain lines are read one by one (cheaper than the arrays)
    BULK_SKIP_BLOCKS = 4  # blocks read line by line after a scan that found few long runs
    BULK_PIECE = 16 << 20  # characters of the program indexed at a time by the bulk reader
    PROGRESS_LINES = 16_384  # the line reader reports its progress this often
    progress: Callable[[int, int], None] | None = None

    def __init__(self, name: str, machine, start_position, block_delete: bool, max_errors: int,
                 tools: ToolTable | None = None, tool_in_spindle: int = 0,
                 spindle: tuple[int, float] = (0, 0.0), subroutine_dirs: Sequence[str] = (),
                 parameters: dict[int, float] | None = None,
                 probe_results: Sequence[ProbeResult | None] = (),
                 input_results: Sequence[float | None] = ()):
        if machine is None:
            from planner.machine import MachineSpec

            machine = MachineSpec.default()
        self.name = name
        self.axes: tuple[str, ...] = tuple(a.name.upper() for a in machine.axes)
        self.rotary: tuple[bool, ...] = tuple(bool(a.rotary) for a in machine.axes)
        n = len(self.axes)
        self.n = n
        self.axis_index = {a: i for i, a in enumerate(self.axes)}
        self.linear_idx = tuple(i for i in range(n) if not self.rotary[i])
        self.rotary_idx = tuple(i for i in range(n) if self.rotary[i])
        self.all_linear = not self.rotary_idx
        offsets = getattr(machine, "work_offsets", None) or {}
        self.params = Params()
        # the persistent parameters the machine kept from earlier programs (G92, G28/G30
        # positions, G59.1-G59.3), then the work offsets as the machine has them now
        for number, value in (parameters or {}).items():
            if int(number) in PERSISTENT_PARAMETERS:
                self.params.numbered[int(number)] = float(value)
        self.axis_param = [_PARAM_AXES.index(a) for a in self.axes]
        self.work_offsets: dict[int, tuple[float, ...]] = {}
        for code in _SYSTEMS:
            key = _gname(code)
            base = system_base(code)
            if key in offsets:
                val = tuple(float(v) for v in offsets[key])
                if len(val) != n:
                    raise PlannerError(f"machine work offset {key} has {len(val)} values for {n} axes")
                for i, v in enumerate(val):
                    self.params.numbered[base + self.axis_param[i]] = v
            else:
                val = tuple(self.params.numbered.get(base + p, 0.0) for p in self.axis_param)
            self.work_offsets[code] = val
        on = self.params.numbered.get(_P_G92_ON, 0.0) != 0.0
        self.g92 = tuple(self.params.numbered.get(_P_G92 + p, 0.0) if on else 0.0 for p in self.axis_param)
        self.params.numbered[_P_SYSTEM] = 1.0
        # parameter sets to hand to the machine when the program passes them (G10, G92, G28.1 ...)
        self.parameter_sets: list[dict[int, float]] = []
        self.tool_sets: list[Tool] = []      # tools changed by G10 L1/L10/L11, by TOOL_DATA event
        # M70-M73: the saved modal state by call level (0: the program), with M73's autorestore
        self.saved_modal: dict[int, tuple[dict[str, object], bool]] = {}
        self.call_level = 0
        self.coolant = 0                     # bits: 1 mist (M7), 2 flood (M8); M9 both off
        if start_position is None:
            start = [0.0] * n
        else:
            start = [float(v) for v in np.asarray(start_position, dtype=float).ravel()]
            if len(start) != n:
                raise PlannerError(f"start_position has {len(start)} values for {n} axes")
        self.start = tuple(start)
        self.block_delete = block_delete
        self.max_errors = max_errors
        # Modal state (LinuxCNC reference set-up: G21 G17 G40 G49 G54 G80 G90 G94 G91.1).
        self.pos = list(start)
        self.motion: int | None = None
        self.plane = 170
        self.inch = False
        self.scale = 1.0  # mm per program length unit
        self.absolute = True
        self.arc_absolute = False
        # G7: X words are diameters (halved as they are read), G8 (the default): radii
        self.diameter = False
        # M48-M51: whether the operator's feed and spindle overrides act on what follows; the
        # OVERRIDES bits last written for the moves (tapping turns both off for its moves)
        self.feed_override_on = True
        self.spindle_override_on = True
        self.override_bits = 0
        self.feed_mm_s = 0.0
        self.work = self.work_offsets[540]       # G54-G59
        # XY rotation of the coordinate system in use (G10 L2 R, degrees, about its origin)
        self.rotation = self.params.numbered.get(system_base(540) + 9, 0.0)
        self.tlo = (0.0,) * n                      # tool length offset (G43...), machine units
        self.offset = tuple(w + g for w, g in zip(self.work, self.g92))   # program -> machine
        self.exact_stop = False
        self.exact_path = False
        # G64 path tolerance (mm): the machine's default until G64 P, G61 or G61.1 change it
        planner_settings = getattr(machine, "planner", None)
        self.blend_default_mm = float(getattr(planner_settings, "blend_tolerance_mm", 0.0) or 0.0)
        self.blend_tol_mm = self.blend_default_mm
        self.blend_changes: list[tuple[int, float]] = [(0, self.blend_tol_mm)]
        # G64 Q (LinuxCNC's naive CAM tolerance: runs of G01 within Q of one line are one line);
        # without Q it is P's, as in LinuxCNC
        self.naive_cam_mm = self.blend_default_mm
        self.naive_changes: list[tuple[int, float]] = [(0, self.naive_cam_mm)]
        # feed mode: G94 units per minute, G93 inverse time (an F on every feed move: its duration
        # is 1/F minutes), G95 units per revolution of the programmed spindle speed
        self.feed_mode = 940
        self.feed_per_rev = 0.0      # G95: mm per revolution
        self.inverse_f = 0.0         # G93: the block's F (1/min)
        # canned cycles: retract mode (LinuxCNC starts in G99, retract to the R plane), the
        # level the cycles started from (G98 returns there), the sticky R, bottom, P and Q
        self.retract_r_plane = True
        self.cycle_il: float | None = None
        self.cycle_r_word = 0.0
        self.cycle_z_word = 0.0
        self.cycle_p = 0.0
        self.cycle_q = 0.0
        self.spindle_dir = int(spindle[0])   # as the spindle is when the program starts
        self.spindle_rpm = float(spindle[1])
        # G96: the speed counted (rpm: D, else the spindle's highest); None in G97
        self.css_max_rpm: float | None = None
        self.spindle_max_rpm = float(getattr(machine, "spindle_max_rpm", 24000.0))
        # None: no tool table (every tool number known, offsets 0: the reference set-up);
        # a table: a tool must be in it to be selected, loaded or used for an offset
        self.tools = tools
        self.tool = int(tool_in_spindle)   # in the spindle (M6, M61)
        self.selected = self.tool          # T word: prepared for the next M6
        self.plane_cache: dict[int, tuple] = {}
        self.fast_letters = frozenset(self.axes) | frozenset("IJKRF")
        # The usual CAM block, in the usual word order, as one regex; numbers below 1e9.
        self.fast_re = re.compile(
            r"(?:N\d+)?(?:G0*([0-3]))?"
            + "".join(f"(?:{a}({_FAST_NUM}))?" for a in self.axes)
            + "".join(f"(?:{a}({_FAST_NUM}))?" for a in "IJKRF")
            + r"\Z"
        )
        # Output: columns, packed as they come (planner.movestore)
        self.out = MoveBuffer(self.start)
        self.offset_changes: list[tuple[int, tuple[float, ...]]] = [(0, self.offset)]  # (first move, offset)
        self.events: list[Event] = []
        self.work_code = 540
        # each change of an offset part, for --canon: (first move, line, system 1-9, G5x, G92, tool,
        # XY rotation in degrees)
        self.offset_parts: list[tuple[int, int, int, tuple[float, ...], tuple[float, ...],
                                      tuple[float, ...], float]] = [
            (0, 0, 1, self.work, self.g92, self.tlo, self.rotation)]
        self.comp_code = 400
        self.comp = CutterComp()
        self.zero_length = _ZERO_LEN
        self.tlo_code = 490
        self.modal_changes: list[tuple[int, str]] = [(0, self.modal_text())]
        self.errors: list[SourceError] = []
        self.truncated = False
        self.ended = False
        self.started = False
        self.current_line = 0
        self.params.system = self.system_parameter
        self.params.system_numbered = self.position_parameter
        self.subroutine_dirs: tuple[str, ...] = tuple(subroutine_dirs) or machine.subroutine_paths()
        # digital outputs (M62-M65 P) and user M-codes M100-M199 the machine configuration defines
        self.outputs: frozenset[int] = frozenset(getattr(machine, "outputs", ()) or ())
        self.mcodes: dict[int, tuple[str, str, int, bool]] = dict(getattr(machine, "mcodes", {}) or {})
        self.sub_files: dict[str, tuple[str, list[str], Structure]] = {}
        # G38.x: the moves read so far, and what the machine's probe did on the first ones (the
        # rest are read as LinuxCNC's preview reads them: to the programmed end point, no contact)
        self.probes: list[ProbeRequest] = []
        self.probe_results = tuple(probe_results)
        self.oword_places: dict[str, tuple[str, int, str]] = {}   # O-word name -> file, line, keyword
        self.sub_places: dict[tuple[str, str], int] = {}   # (file, sub label) -> the sub defined: its line
        self.taps: list[int] = []             # G33.1: the moves into the hole (back out: the next)
        self.frame: _Frame | None = None      # the file and line being run (G7x finds its profile there)
        self.frame_pc = 0
        self.synchronised: list[SynchronisedMotion] = []   # G33, G76
        self.analog_outputs: list[AnalogOutput] = []       # M67, M68
        # G05: the first control point's offset when I and J are left out, -P and -Q of the G05
        # before (program units; LinuxCNC keeps them in its canned cycles' I and J)
        self.spline_ij = (0.0, 0.0)
        # G05.2 ... G05.3: the control points so far (program units: x, y, weight), the order,
        # the line G05.2 began on; None when no NURBS is open
        self.nurbs: list[tuple[float, float, float]] | None = None
        self.nurbs_order = 3
        self.nurbs_line = 0
        self.splines: list[Curve] = []           # the curves read (G05, G05.1, G05.2/G05.3)
        # M66: the waits read so far and the values the machine read on the first ones
        self.inputs_read: list[InputRequest] = []
        self.input_results = tuple(input_results)
        self.inputs: frozenset[int] = frozenset(getattr(machine, "inputs", ()) or ())

    # ------------------------------------------------------------------ driver
    def run(self, text: str | None, utf8: bytes | None = None) -> Program:
        """Interpret ``text`` (``utf8``: the same text encoded, when the caller has it). With
        ``text`` None the program is ``utf8`` alone: a CAM program of plain lines is read from
        its bytes without its text beside them (250 MB at 10,000,000 lines); any other is
        decoded first."""
        if text is None:
            assert utf8 is not None
            if (not (self.use_bulk and self.use_fast) or utf8.startswith(b"\xef\xbb\xbf")
                    or _contains(utf8, b"\r\n") or has_control_flow(utf8)):
                # its text is read from now on: the bytes keep a mark and line ends it has not
                text, utf8 = _decode_utf8(utf8), None
            else:
                self.started = False
                self.run_bulk(None, utf8)
                return self._finish(_count_lines(utf8))
        if text.startswith("\ufeff"):
            # a byte-order mark, which Windows editors put before the first line: an encoding
            # marker, not G-code (LinuxCNC refuses it as a bad character), and no editor shows
            # it, so the columns of line 1 are counted without it
            text, utf8 = text[1:], None
        if _contains(text, "\r\n"):
            text = text.replace("\r\n", "\n")  # Windows line ends, once for the whole text
            utf8 = None
        self.started = False  # saw content or an opening '%'
        if has_control_flow(text):
            self.run_structured(text.split("\n"))
        elif not (self.use_bulk and self.use_fast and self.run_bulk(text, utf8)):
            line = self.line
            lines = text.split("\n")
            report, every = self.progress, self.PROGRESS_LINES
            for line_no, raw in enumerate(lines, 1):
                if line(raw, line_no):
                    break
                if report is not None and line_no % every == 0:
                    report(line_no, len(lines))
        return self._finish(_count_lines(text))

    def _finish(self, line_count: int) -> Program:
        if self.nurbs is not None and not self.ended:
            self.error(self.nurbs_line, 1, "the program ends with this NURBS (G05.2) not ended: program "
                       "G05.3 to run it")
        if self.errors:
            raise ProgramError(self.errors, self.truncated)
        return self.build(line_count)

    def line(self, raw: str, line_no: int) -> bool:
        """Read one line; True when the program ends here (closing '%', M2/M30, too many errors)."""
        # Fast path: one compiled-regex match of the usual CAM block. The regex admits only
        # N, G00-G03, axis and I J K R F words, so a comment, '%', '/', '[', '#', an O-word,
        # a tab or a CR never matches: such lines take the general path below.
        if self.use_fast:
            code = raw.replace(" ", "").upper()
            if not code:
                return False
            m = self.fast_re.match(code)
            if m is not None:
                self.started = True
                try:
                    if self.fast_line(m.groups(), line_no):
                        return False
                except _BlockError as e:
                    self.error(line_no, self.column(raw, e.letter), e.message)
                    return self.truncated
        if raw.endswith("\r"):
            raw = raw[:-1]
        s = raw.strip()
        if not s:
            return False
        if s[0] == "%":
            if not _percent_line(s):
                self.error(line_no, raw.index("%") + 1, "'%' must be alone on its line")
                return False
            if self.started:
                return True  # closing '%': the rest of the file is not part of the program
            self.started = True
            return False
        if not self.started and _compact_or_none(s) != "":
            self.started = True  # comment-only lines before an opening '%' do not count
        if s[0] == "/":
            if self.block_delete:
                return False
            raw = raw.replace("/", " ", 1)
        try:
            self.block(raw, line_no)
        except _BlockError as e:
            col = e.col if e.col is not None else self.column(raw, e.letter)
            self.error(line_no, col, e.message)
        except LexError as e:
            col = e.raw_col if e.raw_col is not None else original_column(raw, e.index)
            self.error(line_no, col, e.message)
        except RecursionError:
            self.error(line_no, 1, "expression nested too deeply")
        return self.ended or self.truncated

    # ------------------------------------------------------------------ O-words
    def run_structured(self, lines: list[str]) -> None:
        """Run a program with O-word subroutines and control flow (``planner.oword``): a
        program counter over the lines, a call stack of frames (the file's lines and structure,
        where to return, the caller's #1-#30 and local named parameters). A subroutine not in
        the file is read from ``<name>.ngc`` in the subroutine folders. Moves made in another
        file carry the line of the call in the program, so the panel shows where it is."""
        lines = lines[:_through_closing_percent(lines)]   # LinuxCNC ignores what follows it
        try:
            main = scan(lines)
        except StructureError as e:
            self.error(e.index + 1, e.col, e.message)
            return
        frame = _Frame(self.name, lines, main, return_pc=-1, call_line=0)
        frames: list[_Frame] = []
        pc = 0
        executed = 0
        while 0 <= pc < len(frame.lines):
            self.frame, self.frame_pc = frame, pc    # where a G7x cycle looks for its profile
            executed += 1
            if executed > _MAX_EXECUTED:
                self.error(frame.line_of(pc), 1, f"more than {_MAX_EXECUTED:,} blocks run (an endless loop?)")
                return
            stmt = frame.structure.statements.get(pc)
            raw = frame.lines[pc]
            line_no = pc + 1
            self.current_line = line_no
            if stmt is None:
                if frame.file != self.name:
                    stop = self.line_in_file(raw, line_no, frame)
                else:
                    stop = self.line(raw, line_no)
                if stop:
                    return
                pc += 1
                continue
            try:
                result = self.statement(stmt, frame, frames)
            except _BlockError as e:
                self.error_in(frame, line_no, e.col or 1, e.message)
                return
            except LexError as e:
                col = e.raw_col if e.raw_col is not None else _statement_col(raw, e.index)
                self.error_in(frame, line_no, col, e.message)
                return
            except RecursionError:
                self.error_in(frame, line_no, 1, "expression nested too deeply")
                return
            if isinstance(result, _Frame):    # a call: run the subroutine
                frames.append(frame)
                frame = result
                pc = frame.entry
                self.call_level += 1
            elif result == _RETURN:
                if not frames:
                    return
                pc = frame.return_pc
                if not frame.fanuc:
                    self.restore(frame)
                saved = self.saved_modal.pop(self.call_level, None)
                self.call_level -= 1
                if saved is not None and saved[1]:          # M73: back as it was at the call
                    self.restore_modal(saved[0], frame.return_pc)
                frame = frames.pop()
            else:
                pc = result

    def statement(self, st: Statement, frame: _Frame, frames: list[_Frame]) -> int | _Frame:
        """Run one control statement; returns the next line index, a frame to call, or _RETURN."""
        kw = st.keyword
        i = st.index
        if kw in ("IF", "REPEAT", "WHILE", "DO"):
            self.oword_place(st, frame)
        if kw == "SUB":                       # a definition in the flow: defined, then skipped
            self.define_sub(st, frame)
            return st.end + 1
        if kw in ("IF", "ELSEIF", "ELSE"):
            if kw != "IF":                    # reached by finishing the branch before it
                return st.end + 1
            branch = st
            while True:
                if branch.keyword == "ELSE" or self.condition(branch, frame):
                    return branch.index + 1
                if branch.target == branch.end:
                    return branch.end + 1
                branch = frame.structure.statements[branch.target]
        if kw == "ENDIF" or kw == "DO":
            return i + 1
        if kw == "WHILE":
            return i + 1 if self.condition(st, frame) else st.end + 1
        if kw == "ENDWHILE":
            return st.target
        if kw == "DOWHILE":
            return st.target + 1 if self.condition(st, frame) else i + 1
        if kw == "REPEAT":
            values = evaluate_brackets(st.rest, self.params, 0)
            if len(values) != 1:
                raise _BlockError(f"o{st.label} repeat needs one count in brackets", col=1)
            count = int(round(values[0]))
            if count <= 0:
                return st.end + 1
            frame.repeats[i] = count
            return i + 1
        if kw == "ENDREPEAT":
            left = frame.repeats.get(st.target, 1) - 1
            if left > 0:
                frame.repeats[st.target] = left
                return st.target + 1
            frame.repeats.pop(st.target, None)
            return i + 1
        if kw in ("BREAK", "CONTINUE"):
            loop = frame.structure.statements[st.loop]
            if kw == "BREAK":
                frame.repeats.pop(loop.index, None)
                return loop.end + 1
            if loop.keyword == "WHILE":
                return loop.index
            return loop.end                   # the do's closing while, or the endrepeat
        if kw in ("RETURN", "ENDSUB"):
            values = evaluate_brackets(st.rest, self.params, 0) if st.rest else []
            if frames or frame.return_pc >= 0:
                self.params.globals["_VALUE"] = values[0] if values else 0.0
                self.params.globals["_VALUE_RETURNED"] = 1.0 if values else 0.0
            return _RETURN
        if kw == "CALL":
            return self.call(st, frame, frames)
        if kw == "PROG":                      # a Fanuc subprogram's start, reached in the flow: into it
            return i + 1
        if kw == "M98":
            callee = self.call_program(st, frame, frames)
            return i + 1 if callee is None else callee
        if kw == "M99":
            if frames and frame.fanuc:
                if frame.loops > 1:           # M98 L: again from its start
                    frame.loops -= 1
                    return frame.entry
                return _RETURN
            if frames:
                raise _BlockError("M99 inside an O-word subroutine: it ends with its endsub or return", "M99")
            # the main program: LinuxCNC ends it here, as M02 does
            return -1 if self.line("M2", i + 1) else i + 1
        raise _BlockError(f"o{st.label} {kw.lower()} is not supported", col=1)

    def oword_place(self, st: Statement, frame: _Frame) -> None:
        """LinuxCNC 2.9 keeps one place per O-word name (a label qualified by the subroutine
        it is written in) for if, repeat, while and do, taken as each is first run: another
        statement run under a name already held is refused, except the while closing a do.
        Labels reused in branches not run, or in different subroutines, are accepted, as there."""
        place = (frame.file, st.index)
        held = self.oword_places.get(st.qname)
        if held is None:
            self.oword_places[st.qname] = (*place, st.keyword)
        elif held[:2] != place and st.keyword != "DO" and not (st.keyword == "WHILE" and held[2] == "DO"):
            where = f"line {held[1] + 1}" + ("" if held[0] == frame.file else f" of {held[0]}")
            raise _BlockError(f"duplicate O-word label: o{st.label} {st.keyword.lower()} uses the label of "
                              f"the {held[2].lower()} at {where}", col=1)

    def define_sub(self, st: Statement, frame: _Frame) -> None:
        """The program runs through a sub's definition: it is defined from here on. Met again
        (inside a loop, or after a call found it ahead), LinuxCNC 2.9 refuses it as "found in
        illegal location"; another definition of the label met, as "redefining sub"."""
        key = (frame.file, st.label)
        held = self.sub_places.get(key)
        if held is None:
            self.sub_places[key] = st.index
        elif held == st.index:
            raise _BlockError(f"o{st.label} sub met a second time: a sub is defined once, as the program "
                              "runs through it or a call finds it ahead (not inside a loop, nor after "
                              "a call to it)", col=1)
        else:
            raise _BlockError(f"o{st.label} sub is defined twice: already at line {held + 1}", col=1)

    def find_sub(self, label: str, call: Statement, frame: _Frame) -> tuple[int, int] | None:
        """The sub a call in this file runs: the one defined (run through, or found by an earlier
        call), else the first ahead of the call, which is then defined (LinuxCNC seeks it to the
        end of the file); None when there is neither."""
        definitions = frame.structure.subs.get(label, [])
        held = self.sub_places.get((frame.file, label))
        if held is not None:
            return next(d for d in definitions if d[0] == held)
        ahead = next((d for d in definitions if d[0] > call.index), None)
        if ahead is not None:
            self.sub_places[(frame.file, label)] = ahead[0]
        return ahead

    def condition(self, st: Statement, frame: _Frame) -> bool:
        values = evaluate_brackets(st.rest, self.params, 0)
        if len(values) != 1:
            word = "while" if st.keyword == "DOWHILE" else st.keyword.lower()
            raise _BlockError(f"o{st.label} {word} needs one condition "
                              "in brackets", col=1)
        return values[0] != 0.0

    def call(self, st: Statement, frame: _Frame, frames: list[_Frame]) -> _Frame:
        if len(frames) >= _MAX_CALL_DEPTH:
            raise _BlockError(f"subroutine calls nested deeper than {_MAX_CALL_DEPTH} (endless recursion?)",
                              col=1)
        args = evaluate_brackets(st.rest, self.params, 0)
        if len(args) > 30:
            raise _BlockError(f"o{st.label} call with {len(args)} arguments (at most 30: #1-#30)", col=1)
        label = st.label
        if label.startswith(("[", "#")):     # O[expression] call, O#<name> call: its number
            (value,) = evaluate_brackets(label if label.startswith("[") else f"[{label}]", self.params, 0)
            if value != round(value) or value < 0:
                raise _BlockError(f"o{label} call: the subroutine number {value:g} is not a whole number",
                                  col=1)
            label = str(int(round(value)))
        target = self.find_sub(label, st, frame)
        file, lines, structure = frame.file, frame.lines, frame.structure
        behind = structure.subs.get(label)
        if target is None and label.startswith("<"):
            file, lines, structure = self.subroutine_file(label[1:-1])
            found = structure.subs.get(label)
            if not found:
                raise _BlockError(f"{file} does not define o{label} sub", col=1)
            target = found[0]
        if target is None and behind:
            raise _BlockError(f"o{label} call: the o{label} sub at line {behind[0][0] + 1} is not defined "
                              "here: the program did not run through it (a sub inside an if is defined "
                              "only when that branch runs) and no other is ahead of the call", col=1)
        if target is None:
            raise _BlockError(f"o{label} call: no o{label} sub in this program", col=1)
        callee = _Frame(file, lines, structure, return_pc=st.index + 1,
                        call_line=frame.call_line or st.index + 1)
        callee.entry = target[0] + 1
        # the caller's #1-#30 and local named parameters come back when the subroutine returns
        numbered = self.params.numbered
        callee.saved_numbered = {k: numbered[k] for k in range(1, 31) if k in numbered}
        callee.saved_named = self.params.named
        for k in range(1, 31):
            self.params.numbered.pop(k, None)
        for k, v in enumerate(args, start=1):
            self.params.numbered[k] = v
        self.params.named = {}
        self.params.globals["_VALUE"] = 0.0
        self.params.globals["_VALUE_RETURNED"] = 0.0
        return callee

    def call_program(self, st: Statement, frame: _Frame, frames: list[_Frame]) -> _Frame | None:
        """M98 P<n> L<count>: run the Fanuc-style subprogram O<n> of this file count times (no
        arguments; it works on the caller's parameters), back after its M99; L0 runs it not
        at all (None), as in LinuxCNC."""
        if len(frames) >= _MAX_CALL_DEPTH:
            raise _BlockError(f"subprogram calls nested deeper than {_MAX_CALL_DEPTH} (endless recursion?)",
                              "M98")
        words, _ = read_line(st.rest, self.params)
        vals = {letter: float(v) for letter, v in words}
        unknown = sorted(set(vals) - {"P", "L"})
        if unknown:
            raise _BlockError(f"M98 takes only P and L words, not {' '.join(unknown)}", unknown[0])
        if "P" not in vals:
            raise _BlockError("M98 needs a P word (the number of the O subprogram to run)", "M98")
        p, loops = vals["P"], vals.get("L", 1.0)
        if p != int(p) or p < 0:
            raise _BlockError(f"M98 P{p:g}: a subprogram number is a whole number", "P")
        if loops != int(loops) or loops < 0:
            raise _BlockError(f"M98 L{loops:g}: the runs of a subprogram are a whole number of 0 or more",
                              "L")
        target = frame.structure.programs.get(str(int(p)))
        if target is None:
            raise _BlockError(f"M98 P{int(p)}: no O{int(p)} in this program", "P")
        if loops == 0:
            return None
        callee = _Frame(frame.file, frame.lines, frame.structure, return_pc=st.index + 1,
                        call_line=frame.call_line or st.index + 1)
        callee.entry = target + 1
        callee.fanuc = True
        callee.loops = int(loops)
        return callee

    def restore(self, frame: _Frame) -> None:
        for k in range(1, 31):
            self.params.numbered.pop(k, None)
        self.params.numbered.update(frame.saved_numbered)
        self.params.named = frame.saved_named

    def subroutine_file(self, name: str) -> tuple[str, list[str], Structure]:
        """``<name>.ngc`` from the subroutine folders, read and scanned once."""
        cached = self.sub_files.get(name)
        if cached is not None:
            return cached
        for folder in self.subroutine_dirs:
            path = os.path.join(folder, f"{name}.ngc")
            if os.path.isfile(path):
                try:
                    with open(path, "rb") as fh:
                        data = fh.read()
                except OSError as exc:
                    raise _BlockError(f"cannot read subroutine file {path}: {exc.strerror}", col=1) from None
                try:
                    text = data.decode("utf-8")
                except UnicodeDecodeError:
                    text = data.decode("latin-1")
                lines = text.replace("\r\n", "\n").split("\n")
                try:
                    structure = scan(lines)
                except StructureError as e:
                    raise _BlockError(f"{path}:{e.index + 1}:{e.col}: {e.message}", col=1) from None
                self.sub_files[name] = (path, lines, structure)
                return self.sub_files[name]
        where = (", ".join(self.subroutine_dirs) if self.subroutine_dirs
                 else "no subroutine folder is configured")
        raise _BlockError(f"o<{name}> call: no o<{name}> sub in this program and no {name}.ngc in the "
                          f"subroutine folders ({where})", col=1)

    def line_in_file(self, raw: str, line_no: int, frame: _Frame) -> bool:
        """A line of a subroutine file: errors name that file; moves carry the call's line."""
        name, errors_before = self.name, len(self.errors)
        self.name = frame.file
        try:
            return self.line(raw, frame.call_line)
        finally:
            self.name = name
            for k in range(errors_before, len(self.errors)):
                e = self.errors[k]
                self.errors[k] = SourceError(frame.file, line_no, e.col, e.message)

    def error_in(self, frame: _Frame, line: int, col: int, message: str) -> None:
        name = self.name
        self.name = frame.file
        try:
            self.error(line, col, message)
        finally:
            self.name = name

    def position_parameter(self, number: int) -> float | None:
        """#5420-#5428 the current position in program coordinates, #5021-#5029 the machine
        position (X Y Z A B C U V W), #5400 the tool in the spindle, #5401-#5409 its offsets in
        the tool table, #5410 its diameter; 0 for an axis the machine does not have."""
        if number >= 5420:
            return self.system_parameter("_" + _PARAM_AXES[number - 5420])
        if number <= 5029:
            letter = _PARAM_AXES[number - 5021]
            i = self.axis_index.get(letter)
            if i is None:
                return 0.0
            return self.pos[i] if self.rotary[i] else self.pos[i] / self.scale
        if number == 5400:
            return float(self.tool)
        tool = self.tools.get(self.tool) if self.tools is not None else None
        if tool is None:
            return 0.0
        if number == 5410:
            return tool.diameter_mm / self.scale
        letter = _PARAM_AXES[number - 5401]
        value = tool.offset(letter)
        return value if letter in "ABC" else value / self.scale

    def program_position(self, p: Sequence[float]) -> list[float]:
        """Program coordinates (mm, deg) of machine position ``p``: the offsets taken off, an XY
        rotation of the coordinate system undone."""
        q = [p[i] - self.offset[i] for i in range(self.n)]
        if self.rotation != 0.0:
            ix, iy = self.axis_index["X"], self.axis_index["Y"]
            q[ix], q[iy] = self.prog_xy(p)
        return q

    def system_parameter(self, name: str) -> float | None:
        """LinuxCNC's predefined named parameters the interpreter knows."""
        axis = name[1:]
        if name.startswith("_ABS_") and len(name) == 6 and name[5] in _PARAM_AXES:
            return self.position_parameter(5021 + _PARAM_AXES.index(name[5]))   # machine position
        if axis not in self.axis_index and len(axis) == 1 and axis in _PARAM_AXES:
            return 0.0                     # an axis this machine does not have reads 0, as LinuxCNC's
        if axis in self.axis_index:
            i = self.axis_index[axis]
            value = self.program_position(self.pos)[i]
            return value if self.rotary[i] else value / self.scale
        return {
            "_LINE": float(self.current_line),
            "_METRIC": 0.0 if self.inch else 1.0,
            "_IMPERIAL": 1.0 if self.inch else 0.0,
            "_ABSOLUTE": 1.0 if self.absolute else 0.0,
            "_INCREMENTAL": 0.0 if self.absolute else 1.0,
            "_FEED": self.feed_mm_s * 60.0 / self.scale,
            "_RPM": self.spindle_rpm,
            "_CURRENT_TOOL": float(self.tool),
            "_SELECTED_TOOL": float(self.selected),
            "_MOTION_MODE": float(self.motion if self.motion is not None else 800),
            "_PLANE": float(self.plane),
            "_RETRACT_R_PLANE": 1.0 if self.retract_r_plane else 0.0,
            "_RETRACT_OLD_Z": 0.0 if self.retract_r_plane else 1.0,
            "_LATHE_DIAMETER_MODE": 1.0 if self.diameter else 0.0,
            "_LATHE_RADIUS_MODE": 0.0 if self.diameter else 1.0,
            "_TASK": 1.0,
            "_VALUE": 0.0,
            "_VALUE_RETURNED": 0.0,
        }.get(name)

    def run_bulk(self, text: str | None, utf8: bytes | None = None) -> bool:
        """Read the program, plain coordinate lines in runs (``planner.bulk``), every other
        line by ``line``; ``utf8`` (the text's bytes) when given, else ``text``. A piece of
        the program (cut after a newline) at a time: the line index of a whole program of
        10,000,000 lines was 240 MB, its encoded text 250 MB more."""
        source: str | bytes = utf8 if utf8 is not None else (text or "")
        total = len(source)
        state = _BulkState()
        if isinstance(source, bytes):
            # read where they lie, in pieces 4 times as big: the bytes are held anyway (only a
            # piece's index is new), and a fresh process read a 2,000,000-line file 10 % slower
            # in 16 MB pieces (why was not found: the same blocks scan as fast alone)
            newline: Any = b"\n"
            whole = np.frombuffer(source, np.uint8)
            piece = 4 * self.BULK_PIECE
        else:
            newline, whole, piece = "\n", np.zeros(0, np.uint8), self.BULK_PIECE
        lo = 0
        first_line = 0     # lines of the program before this piece
        while True:
            hi = source.find(newline, lo + piece) if lo + piece < total else -1
            last = hi < 0
            hi = total if last else hi + 1
            if isinstance(source, bytes):
                data = whole[lo:hi]
            else:
                # "surrogatepass": a text with lone surrogates reads as it did when it was
                # split into lines whole (they stay in the lines read one by one)
                data = np.frombuffer(source[lo:hi].encode("utf-8", "surrogatepass"), np.uint8)
            nl = newline_offsets(data)
            starts = np.concatenate(([0], nl + 1))
            ends = np.concatenate((nl, [data.shape[0]]))
            if not last:    # the piece ends with its newline: no line starts after it
                starts, ends = starts[:-1], ends[:-1]
            if self._bulk_piece(data, starts, ends, first_line, lo, total, state, utf8 is None):
                return True
            if last:
                return True
            first_line += int(starts.shape[0])
            lo = hi

    def _bulk_piece(self, data: np.ndarray, starts: np.ndarray, ends: np.ndarray, first_line: int,
                    offset: int, total: int, state: _BulkState, surrogates: bool) -> bool:
        """Read the lines of one piece (``data``, lines from ``starts`` to ``ends``, the first
        being line ``first_line + 1`` of the program, at ``offset`` of its ``total``): True
        when the program ends there."""
        n_lines = int(starts.shape[0])
        letters = "".join(a for a, rot in zip(self.axes, self.rotary) if not rot) + "FGN"
        cols = [self.axis_index[a] for a in letters[:-3]]
        line = self.line
        min_run = self.BULK_MIN_RUN
        errors = "surrogatepass" if surrogates else "strict"

        def by_line(a: int, b: int) -> bool:
            """Lines a .. b - 1 by ``line`` (True when the program ends there)."""
            if a >= b:
                return False
            text = data[int(starts[a]):int(ends[b - 1])].tobytes().decode("utf-8", errors)
            for line_no, raw in enumerate(text.split("\n"), first_line + a + 1):
                if line(raw, line_no):
                    return True
            return False

        b1 = 0
        while b1 < n_lines:
            if offset + int(starts[b1]) - state.trimmed_at > _TRIM_BYTES:
                # each block's scan makes and frees arrays of megabytes, which stay in the heap
                # between the moves kept (360 MB of 1.1 GB after 10,000,000 lines): handed back
                trim_heap()
                state.trimmed_at = offset + int(starts[b1])
            # a small first block tells cheaply whether the program is made of long runs
            b0 = b1
            b1 = min(n_lines, b1 + (self.BULK_LINES if state.scanned else self.BULK_LINES // 8))
            state.scanned = True
            if state.skip:
                state.skip -= 1
                if by_line(b0, b1):
                    return True
                if self.progress is not None:
                    self.progress(offset + int(ends[b1 - 1]), total)
                continue
            base = int(starts[b0])
            block = scan_plain(data[base:int(ends[b1 - 1])], starts[b0:b1] - base, ends[b0:b1] - base,
                               letters)
            # runs of plain lines long enough to pay for the arrays; the lines between them
            # are read one by one, as a text of their own
            edges = np.flatnonzero(np.diff(np.concatenate(([0], block.plain.view(np.int8), [0]))))
            runs = [(b0 + int(r0), b0 + int(r1)) for r0, r1 in zip(edges[::2], edges[1::2])
                    if r1 - r0 >= min_run]
            if sum(r1 - r0 for r0, r1 in runs) < 0.25 * (b1 - b0):
                # a program of short runs (arcs between few lines): scanning costs more than it
                # saves; look again every few blocks, where the program may change its kind
                state.skip = self.BULK_SKIP_BLOCKS
            cursor = b0
            for r0, r1 in runs:
                if by_line(cursor, r0):
                    return True
                i = r0
                while i < r1:
                    i += self.bulk_lines(block.values[i - b0:r1 - b0], block.words[i - b0:r1 - b0],
                                         first_line + i + 1, cols)
                    if i < r1:  # a line the run cannot take: the line reader's
                        if by_line(i, i + 1):
                            return True
                        i += 1
                cursor = r1
            if by_line(cursor, b1):
                return True
            if self.progress is not None:
                self.progress(offset + int(ends[b1 - 1]), total)
        return False

    def bulk_lines(self, values: np.ndarray, words: np.ndarray, first_line: int, cols: list[int]) -> int:
        """Run plain lines (``planner.bulk``: values of the linear axes' words in ``cols``
        order, then F, G, N) as ``fast_line`` runs them one by one, from the first; stops before
        a line whose reading needs more (a state the fast path leaves to the general one, a zero
        feed, a move too short to keep) and returns how many lines it ran."""
        n_lines = values.shape[0]
        if (not n_lines or self.feed_mode != 940 or self.rotation or self.comp.busy
                or self.nurbs is not None or self.diameter):
            return 0
        n_ax = len(cols)
        ax = values[:, :n_ax]
        f_val, g_val = values[:, n_ax], values[:, n_ax + 1]
        has_axes = ~np.isnan(ax).all(axis=1)
        has_g = ~np.isnan(g_val)
        # where the line path must take over: a G without axis words, a negative F
        stop = (has_g & ~has_axes) | (f_val < 0.0)
        motion = self._ffill(g_val * 10.0, -1.0 if self.motion is None else float(self.motion))
        scale = self.scale
        feed = self._ffill(f_val * scale / 60.0, self.feed_mm_s)
        stop |= has_axes & ~((motion == 0.0) | ((motion == 10.0) & (feed > 0.0)))
        cut = int(np.argmax(stop)) if stop.any() else n_lines
        # targets: absent words keep the axis where the last line put it
        pos = self.pos
        targets = np.empty((cut + 1, self.n))
        targets[:] = pos
        if self.absolute:
            for c, i in enumerate(cols):
                given = ax[:cut, c] * scale + self.offset[i]
                targets[1:, i] = self._ffill(given, pos[i])
        else:
            for c, i in enumerate(cols):
                step = np.nan_to_num(ax[:cut, c] * scale, nan=0.0)
                targets[0, i] = pos[i]
                targets[1:, i] = step
                np.cumsum(targets[:, i], out=targets[:, i])
        lin = list(self.linear_idx)
        delta = np.diff(targets[:, lin], axis=0)
        length = np.sqrt(np.einsum("ij,ij->i", delta, delta))
        short = has_axes[:cut] & (length <= _ZERO_LEN)
        if short.any():
            cut = int(np.argmax(short))
        if cut == 0:
            return 0
        moving = np.flatnonzero(has_axes[:cut])
        if words[:cut].any():
            self.started = True
        if has_g[:cut].any():
            self.cycle_il = None
        self.motion = None if motion[cut - 1] < 0.0 else int(motion[cut - 1])
        self.feed_mm_s = float(feed[cut - 1])
        if moving.size:
            rapid = motion[moving] == 0.0
            self.out.extend(targets[1:][moving], moving + first_line, np.where(rapid, 0, 1),
                            np.where(rapid, math.inf, feed[moving]), length[moving], self.exact_stop)
            self.pos = targets[moving[-1] + 1].tolist()
        return cut

    @staticmethod
    def _ffill(values: np.ndarray, before: float) -> np.ndarray:
        """``values`` with each NaN replaced by the last value before it (``before`` at first)."""
        given = ~np.isnan(values)
        idx = np.where(given, np.arange(values.shape[0]), -1)
        np.maximum.accumulate(idx, out=idx)
        out = np.where(idx >= 0, values[np.maximum(idx, 0)], before)
        return out

    def fast_line(self, groups: tuple, line_no: int) -> bool:
        """A block matched by fast_re: [N] [G00-G03] axis words (machine order) [I J K R] [F].

        Returns False to hand the line to the general path (which also diagnoses errors).
        """
        n = self.n
        gtxt = groups[0]
        axis_vals = groups[1:n + 1]
        i_t, j_t, k_t, r_t, f_t = groups[n + 1:]
        ctr = i_t is not None or j_t is not None or k_t is not None or r_t is not None
        if f_t is not None and f_t[0] == "-":
            return False  # negative feed: diagnosed by the general path
        if axis_vals.count(None) == n:  # no axis words
            if gtxt is None and not ctr and self.feed_mode == 940:
                if f_t is not None:
                    self.feed_mm_s = float(f_t) * self.scale / 60.0
                return True
            return False
        motion = int(gtxt) * 10 if gtxt is not None else self.motion
        if (motion is None or motion > 30 or (ctr and motion < 20) or self.feed_mode != 940 or self.rotation
                or self.comp.busy or self.nurbs is not None or self.diameter):
            return False
        scale = self.scale
        if f_t is not None:
            self.feed_mm_s = float(f_t) * scale / 60.0
        if gtxt is not None:
            self.motion = motion
            self.cycle_il = None
        pos = self.pos
        target = pos.copy()
        rot = self.rotary
        if self.absolute:
            off = self.offset
            if self.all_linear:
                for i, v in enumerate(axis_vals):
                    if v is not None:
                        target[i] = float(v) * scale + off[i]
            else:
                for i, v in enumerate(axis_vals):
                    if v is not None:
                        target[i] = (float(v) if rot[i] else float(v) * scale) + off[i]
        else:
            for i, v in enumerate(axis_vals):
                if v is not None:
                    target[i] = pos[i] + (float(v) if rot[i] else float(v) * scale)
        if motion < 20:
            if self.all_linear:  # inline of straight() for the common machine
                feed = math.inf if motion == 0 else self.feed_mm_s
                if feed <= 0.0:             # a G01 with no feed, even to where the tool is
                    raise _BlockError(_ZERO_FEED, "G")
                length = math.dist(pos, target)
                if length <= _ZERO_LEN:
                    return True
                self.out.append(target, line_no, 0 if motion == 0 else 1, feed, length, None,
                                self.exact_stop)
                self.pos = target
            else:
                self.straight(target, motion == 0, line_no)
        else:
            vals = {}
            if i_t is not None:
                vals["I"] = float(i_t)
            if j_t is not None:
                vals["J"] = float(j_t)
            if k_t is not None:
                vals["K"] = float(k_t)
            if r_t is not None:
                vals["R"] = float(r_t)
            self.arc(target, vals, motion == 20, scale, line_no)
        return True

    def error(self, line: int, col: int, message: str) -> None:
        if len(self.errors) >= self.max_errors:
            self.truncated = True
            return
        self.errors.append(SourceError(self.name, line, col, message))

    @staticmethod
    def column(raw: str, letter: str | None) -> int:
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

    def modal_text(self) -> str:
        """The modal codes as LinuxCNC's panels list them (motion mode aside); G7 and the
        overrides turned off are shown when in force, as they change what X and the knobs do."""
        return " ".join((
            _PLANE_G[self.plane], "G20" if self.inch else "G21", "G90" if self.absolute else "G91",
            _gname(self.feed_mode),
            _gname(self.work_code), _gname(self.comp_code), _gname(self.tlo_code),
            "G61" if self.exact_stop else ("G61.1" if self.exact_path else self.g64_text()),
        )) + (" G7" if self.diameter else "") + self.override_text()

    def override_text(self) -> str:
        if self.feed_override_on and self.spindle_override_on:
            return ""
        if not (self.feed_override_on or self.spindle_override_on):
            return " M49"
        return " M50 P0" if not self.feed_override_on else " M51 P0"

    def overrides_event(self, line_no: int, after: int, text: str, lock: int = 0,
                        kind: EventKind = EventKind.OVERRIDES) -> None:
        """The OVERRIDES bits for the moves from ``after`` + 1 on: the program's M48-M51 state,
        and ``lock`` (tapping: both off for its moves; ``kind`` TAPPING, where the path stands)."""
        bits = ((0 if self.feed_override_on else FEED_OVERRIDE_OFF)
                | (0 if self.spindle_override_on else SPINDLE_OVERRIDE_OFF) | lock)
        if bits != self.override_bits:
            self.override_bits = bits
            self.events.append(Event(kind, line_no, after, float(bits), text))

    def override_codes(self, code: int, vals: dict[str, float], line_no: int, after: int) -> None:
        """M48-M53 as LinuxCNC 2.9 reads them (refused with compensation on, as there)."""
        on = vals.get("P", 1.0) != 0.0
        if self.comp.side != 0:
            verb = "enable" if code == 48 or (code != 49 and on) else "disable"
            raise _BlockError(f"cannot {verb} overrides with cutter radius compensation on "
                              f"({_gname(self.comp_code)}): program G40 first", f"M{code}")
        if code == 52 and on:
            raise _BlockError("M52 (adaptive feed) scales the feed by an input this machine does not have",
                              "M52")
        if code in (48, 49):
            self.feed_override_on = self.spindle_override_on = code == 48
        elif code == 50:
            self.feed_override_on = on
        elif code == 51:
            self.spindle_override_on = on
        # M52 P0: adaptive feed off, as it is; M53: the feed stop switch, which this machine
        # does not have (the panel's feed hold is LinuxCNC's pause, which M53 leaves alone)
        what = {48: "overrides on", 49: "overrides off: the program's own feed and speed",
                50: f"feed override {'on' if on else 'off'}", 51: f"spindle override {'on' if on else 'off'}"}
        self.overrides_event(line_no, after, f"M{code}: {what.get(code, '')}")
        self.note_modal()

    def g64_text(self) -> str:
        """G64 with the tolerances in force, in the program's units (as the operator wrote them)."""
        if self.blend_tol_mm <= 0.0 and self.naive_cam_mm <= 0.0:
            return "G64"
        text = f"G64 P{self.blend_tol_mm / self.scale:g}"
        if self.naive_cam_mm != self.blend_tol_mm:
            text += f" Q{self.naive_cam_mm / self.scale:g}"
        return text

    def note_modal(self) -> None:
        text = self.modal_text()
        first = len(self.out)
        if self.modal_changes[-1][1] == text:
            return
        if self.modal_changes[-1][0] == first:
            self.modal_changes[-1] = (first, text)
        else:
            self.modal_changes.append((first, text))

    def known_tool(self, number: int, letter: str) -> int:
        """``number`` if the tool table has it (T0, the empty spindle, always)."""
        if number and self.tools is not None and number not in self.tools:
            raise _BlockError(f"tool T{number} is not in the tool table (add it on the Tools page)", letter)
        return number

    def tool_label(self, number: int) -> str:
        return self.tools.label(number) if self.tools is not None else f"T{number}"

    def tool_offsets(self, number: int) -> tuple[float, ...]:
        tool = self.tools.get(number) if self.tools is not None else None
        if tool is None:
            return (0.0,) * self.n
        return tuple(tool.offset(a) for a in self.axes)

    def tool_length(self, code: int, vals: dict[str, float], axis_words: list[str], scale: float) -> None:
        """G43 (the tool in the spindle, or H's), G43.1 (the axis words), G43.2 (add H's or the
        axis words), G49 (none), as LinuxCNC 2.9 applies them."""
        if code == 490:
            self.set_offset(tlo=(0.0,) * self.n)
            return
        words = [0.0] * self.n
        for letter in axis_words:
            i = self.axis_index[letter]
            words[i] = vals[letter] if self.rotary[i] else vals[letter] * scale
        h = vals.get("H")
        if h is not None and (h < 0 or h != int(h)):
            raise _BlockError(f"tool number H{h:g} must be a whole number >= 0", "H")
        if code == 430:
            number = self.known_tool(int(h), "H") if h is not None else self.tool
            self.set_offset(tlo=self.tool_offsets(number))
        elif code == 431:
            self.set_offset(tlo=tuple(words))
        else:  # 432
            if h is None and not axis_words:
                raise _BlockError("G43.2 needs an H word or axis words (the offset to add)", "G43.2")
            add = self.tool_offsets(self.known_tool(int(h), "H")) if h is not None else tuple(words)
            self.set_offset(tlo=tuple(t + a for t, a in zip(self.tlo, add)))

    _MODAL_FIELDS = ("inch", "scale", "plane", "comp_code", "absolute", "arc_absolute", "feed_mode",
                     "feed_mm_s", "feed_per_rev", "inverse_f", "work_code", "work", "tlo_code", "tlo",
                     "retract_r_plane", "exact_stop", "exact_path", "blend_tol_mm", "naive_cam_mm",
                     "spindle_rpm", "spindle_dir", "coolant", "rotation", "diameter", "feed_override_on",
                     "spindle_override_on")

    def spindle_mode(self, code: int, vals: dict[str, float], line_no: int, after: int,
                     switched: bool) -> None:
        """G96 D S: constant surface speed, S the cutting speed (m/min, ft/min in G20) and D the
        highest speed (rpm); G97: S in rpm again. LinuxCNC on a mill sets the speed from the X
        radius; this spindle is switched by digital outputs and has no speed output, so G96 is
        kept as the mode LinuxCNC reads (the motion is the same) and the operator is told that
        its speed does not follow X. The speed shown and counted (spin-up) is what LinuxCNC
        commands near X0: D, else the spindle's highest speed."""
        if code == 970:
            self.css_max_rpm = None
            return
        d = vals.get("D")
        self.css_max_rpm = min(abs(d), self.spindle_max_rpm) if d else self.spindle_max_rpm
        if self.css_max_rpm != self.spindle_rpm:
            self.spindle_rpm = self.css_max_rpm
            if self.spindle_dir != 0 and not switched:   # an M3/M4/M5 here tells it
                rpm = self.spindle_dir * self.spindle_rpm
                self.events.append(Event(EventKind.SPINDLE, line_no, after, rpm))
        unit = "ft/min" if self.inch else "m/min"
        limit = f" up to {abs(d):g} rpm" if d else ""
        self.events.append(Event(EventKind.MESSAGE, line_no, after, 0.0,
                                 f"G96 constant surface speed S{vals['S']:g} {unit}{limit}: this spindle has "
                                 f"no speed output to follow X; counted at {self.spindle_rpm:g} rpm"))

    def note_blend_tolerance(self) -> None:
        first = len(self.out)
        for changes, value in ((self.blend_changes, self.blend_tol_mm),
                               (self.naive_changes, self.naive_cam_mm)):
            if changes[-1][1] == value:
                continue
            if changes[-1][0] == first:
                changes[-1] = (first, value)
            else:
                changes.append((first, value))

    def modal_memory(self, code: int, line_no: int) -> None:
        """M70 save the modal state at this call level, M71 forget it, M72 restore it, M73 save it
        to be restored when the subroutine returns (LinuxCNC 2.9; the motion mode is not part)."""
        level = self.call_level
        if code in (70, 73):
            if code == 73 and level == 0:
                raise _BlockError("M73 saves the state for the return of a subroutine: use M70 in the "
                                  "main program", "M73")
            self.saved_modal[level] = ({f: getattr(self, f) for f in self._MODAL_FIELDS}, code == 73)
        elif code == 71:
            self.saved_modal.pop(level, None)
        else:
            saved = self.saved_modal.get(level)
            if saved is None:
                raise _BlockError("M72: no modal state saved at this level (M70 or M73 first)", "M72")
            self.restore_modal(saved[0], line_no)

    def restore_modal(self, state: dict[str, object], line_no: int) -> None:
        spindle_before = (self.spindle_dir, self.spindle_rpm)
        coolant_before = self.coolant
        for f, v in state.items():
            setattr(self, f, v)
        self.set_offset()
        self.note_blend_tolerance()
        self.params.numbered[_P_SYSTEM] = float(_SYSTEMS.index(self.work_code) + 1)
        after = len(self.out) - 1
        if (self.spindle_dir, self.spindle_rpm) != spindle_before:
            self.events.append(Event(EventKind.SPINDLE, line_no, after, self.spindle_dir * self.spindle_rpm,
                                     "M72: spindle as saved"))
        if self.coolant != coolant_before:
            if coolant_before & ~self.coolant:    # something to switch off: all off, then back on
                self.events.append(Event(EventKind.COOLANT, line_no, after, 0.0, "M72: coolant as saved"))
                coolant_before = 0
            for bit in (1, 2):
                if self.coolant & bit and not coolant_before & bit:
                    self.events.append(Event(EventKind.COOLANT, line_no, after, float(bit),
                                             "M72: coolant as saved"))
        self.overrides_event(line_no, after, "M72: overrides as saved")
        self.note_modal()

    def wait_input(self, vals: dict[str, float], line_no: int) -> None:
        """M66 P L Q as LinuxCNC 2.9 reads it: the motion stops, digital input P is read now
        (L0) or waited for (L1 rise, L2 fall, L3 high, L4 low) for at most Q seconds, and #5399
        holds its value (-1 after the timeout). The machine's value is known for the first
        ``input_results``; for the others the awaited value is assumed."""
        p = vals.get("P")
        if p is None or round(p) < 0:
            raise _BlockError("M66 needs a P word (the number of a digital input)", "M66")
        number = round(p)
        if number not in self.inputs:
            known = ", ".join(f"P{k}" for k in sorted(self.inputs)) or "none: add [[inputs]]"
            raise _BlockError(f"M66 P{number}: no such digital input on this machine ({known})", "P")
        mode_n = round(vals.get("L", 0.0))
        if not 0 <= mode_n <= 4:
            raise _BlockError(f"M66 L{mode_n}: the wait mode is 0 (now), 1 (rise), 2 (fall), 3 (high) or "
                              "4 (low)", "L")
        timeout = vals.get("Q", 0.0)
        if mode_n > 0 and timeout <= 0.0:
            raise _BlockError("M66: zero timeout with a wait mode other than immediate (give Q, seconds)",
                              "Q" if "Q" in vals else "L")
        if self.comp.side != 0:
            raise _BlockError("cannot wait for a digital input (M66) with cutter radius compensation on",
                              "M66")
        self.comp.stop(self)
        k = len(self.inputs_read)
        value = self.input_results[k] if k < len(self.input_results) else None
        request = InputRequest(line_no, number, WaitMode(mode_n), timeout if mode_n else 0.0,
                               value is not None)
        self.inputs_read.append(request)
        self.events.append(Event(EventKind.INPUT, line_no, len(self.out) - 1, float(k),
                                 f"M66 P{number}"))
        self.params.numbered[_P_INPUT] = float(request.assumed_value if value is None else value)

    def output_event(self, number: int, on: bool, line_no: int, after: int, text: str) -> None:
        """An OUTPUT event: value = number for on, -(number + 1) for off."""
        self.events.append(Event(EventKind.OUTPUT, line_no, after, float(number if on else -(number + 1)),
                                 f"{text}: output {number} {'on' if on else 'off'}"))

    def polar(self, vals: dict[str, float]) -> None:
        """LinuxCNC's polar words: @ radius and ^ angle (degrees) about the origin of the
        program's coordinates in the XY plane, turned into X and Y here. A missing one keeps the
        current radius or angle; in G91 both are added to the current ones."""
        if self.plane != 170:
            raise _BlockError("polar coordinates (@ ^) only in the XY plane (G17)",
                              "@" if "@" in vals else "^")
        px, py = self.prog_xy(self.pos)
        x, y = px / self.scale, py / self.scale
        radius, theta = math.hypot(x, y), math.atan2(y, x)
        if self.absolute:
            radius = vals.pop("@", radius)
            theta = math.radians(vals.pop("^")) if "^" in vals else theta
        else:
            if radius == 0.0:
                raise _BlockError("incremental motion with polar coordinates is indeterminate at the origin",
                                  "@" if "@" in vals else "^")
            radius += vals.pop("@", 0.0)
            theta += math.radians(vals.pop("^", 0.0))
        px, py = radius * math.cos(theta), radius * math.sin(theta)
        vals["X"], vals["Y"] = (px, py) if self.absolute else (px - x, py - y)

    def prog_xy(self, pos: Sequence[float], work: Sequence[float] | None = None,
                rotation: float | None = None, g92: Sequence[float] | None = None) -> tuple[float, float]:
        """X and Y of a machine position in program coordinates (mm), the XY rotation undone:
        R(-rotation) (machine - G5x - tool) - G92, as LinuxCNC's canon composes them."""
        ix, iy = self.axis_index["X"], self.axis_index["Y"]
        work = self.work if work is None else work
        g92 = self.g92 if g92 is None else g92
        theta = math.radians(self.rotation if rotation is None else rotation)
        dx, dy = pos[ix] - work[ix] - self.tlo[ix], pos[iy] - work[iy] - self.tlo[iy]
        c, s = math.cos(theta), math.sin(theta)
        return c * dx + s * dy - g92[ix], -s * dx + c * dy - g92[iy]

    def machine_xy(self, x: float, y: float) -> tuple[float, float]:
        """Machine X and Y of program X and Y (mm): R(rotation) (program + G92) + G5x + tool."""
        ix, iy = self.axis_index["X"], self.axis_index["Y"]
        u, v = x + self.g92[ix], y + self.g92[iy]
        theta = math.radians(self.rotation)
        c, s = math.cos(theta), math.sin(theta)
        return (c * u - s * v + self.work[ix] + self.tlo[ix], s * u + c * v + self.work[iy] + self.tlo[iy])

    def comp_request(self, code: int, vals: dict[str, float], scale: float) -> None:
        """G41/G42 (radius from the tool table: D's tool, or the tool in the spindle without D
        or with D0) and G41.1/G42.1 (D is the diameter), as LinuxCNC 2.9 reads them."""
        name = _gname(code)
        if self.comp.side != 0:
            raise _BlockError(f"cannot turn cutter compensation on with {name} while it is on "
                              f"({_gname(self.comp_code)}): program G40 first", name)
        if self.plane not in (170, 180):
            raise _BlockError(f"cutter compensation works in the XY (G17) or XZ (G18) plane, not in "
                              f"{_PLANE_G[self.plane]}", name)
        if self.plane == 180 and self.rotation != 0.0:
            # LinuxCNC offsets in the plane of Z and the turned X; this engine offsets in machine
            # planes (G18 arcs in a rotated system are read, their compensation is not)
            raise _BlockError("cutter compensation in G18 with the XY plane rotated (G10 L2 R) is not "
                              "supported: cancel the rotation (G10 L2 R0) or program the tool centre's path",
                              name)
        d = vals.get("D")
        if code in (411, 421):
            if d is None:
                raise _BlockError(f"{name} needs a D word (the tool diameter)", name)
            if "L" in vals and vals["L"] not in (0, 9):
                raise _BlockError(f"{name} L{vals['L']:g}: lathe tool orientations are not supported on "
                                  "this machine (L0 or L9: the centre of the tool)", "L")
            radius = d * scale / 2.0
        else:
            if d is not None and (d < 0 or d != int(d)):
                raise _BlockError(f"{name} needs D to be a tool number (a whole number >= 0), got D{d:g}",
                                  "D")
            number = int(d) if d else self.tool
            if d:
                self.known_tool(number, "D")
            tool = self.tools.get(number) if self.tools is not None else None
            radius = tool.diameter_mm / 2.0 if tool is not None else 0.0
            orientation = dict(tool.lathe).get("Q", 0.0) if tool is not None else 0.0
            if orientation not in (0.0, 9.0) and radius > 0.0:
                # a lathe tool's controlled point is not its centre (LinuxCNC moves the path by
                # the orientation); offsetting the centre would cut a radius off
                raise _BlockError(f"{name} with the lathe tool {self.tool_label(number)} (orientation "
                                  f"Q{orientation:g}): lathe tool orientations are not supported on this "
                                  "machine", "D" if d else name)
        _pname, fa, sa, *_ = self.plane_axes()
        self.comp.turn_on(LEFT if code in (410, 411) else RIGHT, radius, (fa, sa))

    def comp_refuses(self, what: str, letter: str) -> None:
        """LinuxCNC refuses these while compensation is on (whatever the radius)."""
        if self.comp.side != 0:
            raise _BlockError(f"cannot {what} with cutter compensation on ({_gname(self.comp_code)}): "
                              "program G40 first", letter)

    def set_offset(self, work: tuple[float, ...] | None = None, tlo: tuple[float, ...] | None = None) -> None:
        """Change the work offset and/or the tool length offset; moves from now on use both."""
        if work is not None:
            self.work = work
        if tlo is not None:
            self.tlo = tlo
        offset = tuple(w + g + t for w, g, t in zip(self.work, self.g92, self.tlo))
        self.offset = offset
        first = len(self.out)
        self.offset_parts.append((first, self.current_line, _SYSTEMS.index(self.work_code) + 1, self.work,
                                  self.g92, self.tlo, self.rotation))
        if self.offset_changes[-1][0] == first:
            self.offset_changes[-1] = (first, offset)
        else:
            self.offset_changes.append((first, offset))

    def build(self, line_count: int) -> Program:
        moves = self.out.store()
        n_moves = len(moves)
        changes = self.offset_changes + [(n_moves, None)]
        if len(changes) == 2 and changes[0][0] == 0:
            # one offset for the whole program (the usual case): one row seen n times, not
            # 24 bytes a move
            offsets = np.broadcast_to(np.array(changes[0][1], dtype=float), (n_moves, self.n))
        else:
            offsets = np.empty((n_moves, self.n))
            for (first, off), (nxt, _) in zip(changes[:-1], changes[1:]):
                offsets[first:nxt] = off
            offsets.setflags(write=False)
        start = np.array(self.start, dtype=float)
        start.setflags(write=False)
        return Program(
            name=self.name,
            axes=self.axes,
            rotary=self.rotary,
            moves=moves,
            events=tuple(self.events),
            start_position=start,
            move_offsets=offsets,
            line_count=line_count,
            modal=tuple(self.modal_changes),
            parameter_sets=tuple(self.parameter_sets),
            offset_parts=tuple(self.offset_parts),
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

    # ------------------------------------------------------------------ one block
    def block(self, raw: str, line_no: int) -> None:
        self.current_line = line_no
        if "(" in raw:
            self.messages(raw, line_no)
        words, assigns = read_line(raw, self.params)
        if not words:
            self.assign(assigns)
            return
        if not assigns and self.use_fast and self.fast_block(words, line_no):
            return
        self.general_block(words, assigns, line_no)

    def fast_block(self, words: list, line_no: int) -> bool:
        """The common CAM line (optional N, one G00-G03, axis words, I/J/K/R, F) without checks
        that cannot fail for it. Returns False to let general_block handle (and diagnose) it."""
        vals: dict[str, float] = {}
        g = -1
        fast_letters = self.fast_letters
        for letter, t in words:
            if letter in fast_letters:
                if letter in vals:
                    return False
                v = float(t)
                if not -_VALUE_LIMIT < v < _VALUE_LIMIT:
                    return False
                vals[letter] = v
            elif letter == "G" and g < 0 and t in _FAST_G:
                g = _FAST_G[t]
            elif letter != "N" or vals or g >= 0:
                return False
        axis_index = self.axis_index
        axis_words = [letter for letter in vals if letter in axis_index]
        ctr = "I" in vals or "J" in vals or "K" in vals or "R" in vals
        if not axis_words:
            if g < 0 and not ctr and "F" in vals and vals["F"] >= 0.0 and self.feed_mode == 940:
                self.feed_mm_s = vals["F"] * self.scale / 60.0
                return True
            return False
        motion = g if g >= 0 else self.motion
        if (motion is None or motion > 30 or (ctr and motion < 20) or self.feed_mode != 940 or self.rotation
                or self.comp.busy or self.nurbs is not None or self.diameter):
            return False
        if "F" in vals:
            f = vals["F"]
            if f < 0.0:
                return False
            self.feed_mm_s = f * self.scale / 60.0
        if g >= 0:
            self.motion = g
            self.cycle_il = None
        target = self.target(vals, axis_words, self.scale, False)
        if motion < 20:
            self.straight(target, motion == 0, line_no)
        else:
            self.arc(target, vals, motion == 20, self.scale, line_no)
        return True

    def general_block(self, words: list, assigns: list, line_no: int) -> None:
        gcodes: list[int] = []
        mcodes: list[int] = []
        vals: dict[str, float] = {}
        first = True
        for letter, t in words:
            v = float(t)
            if not -_VALUE_LIMIT < v < _VALUE_LIMIT and not (letter == "F" and abs(v) < _FEED_LIMIT):
                limit = "1e12" if letter == "F" else "1e9"
                raise _BlockError(f"{letter} value {v:g} out of range (|value| < {limit})", letter)
            if letter == "G":
                c = round(v * 10.0)
                if abs(v * 10.0 - c) > 1e-6:
                    raise _BlockError(f"unknown G code G{v:g}", "G")
                gcodes.append(c)
            elif letter == "M":
                c = round(v)
                if abs(v - c) > 1e-9:
                    raise _BlockError(f"unknown M code M{v:g}", "M")
                mcodes.append(c)
            elif letter == "N":
                if not first:
                    raise _BlockError("N word (line number) must begin the block", "N")
            elif letter == "O":
                if len(words) != 1:
                    raise _BlockError("O-word program numbers must be alone on their line", "O")
                return  # Fanuc-style program number: nothing to do
            elif letter in vals:
                raise _BlockError(f"two {letter} words in one block", letter)
            else:
                vals[letter] = v
            first = False

        # ---- which codes are in this block, by modal group
        groups: dict[int, int] = {}
        for c in gcodes:
            g = _G_GROUP.get(c)
            if g is None:
                what = _G_UNSUPPORTED.get(c)
                if what:
                    raise _BlockError(f"{_gname(c)} is not supported ({what})", _gname(c))
                raise _BlockError(f"unknown G code {_gname(c)}", _gname(c))
            if g == 1 and g in groups and 800 in (c, groups[g]):
                # LinuxCNC reads G80 beside another motion code as nothing: the other one counts
                groups[g] = groups[g] if c == 800 else c
                continue
            if g in groups:
                raise _BlockError(
                    f"{_gname(groups[g])} and {_gname(c)} are in the same modal group (one per block)",
                    _gname(c),
                )
            groups[g] = c
        mgroups: dict[int, int] = {}
        for c in mcodes:
            g = _M_GROUP.get(c)
            if g is None:
                why = _M_UNSUPPORTED.get(c)
                raise _BlockError(f"M{c} is not supported" + (f" ({why})" if why else ""), f"M{c}")
            if g == 10 and c not in self.mcodes:
                raise _BlockError(f"M{c} is a user M-code this machine does not define (add it to "
                                  "[[mcodes]] in the machine configuration: a pause with a message, an "
                                  "output or nothing)", f"M{c}")
            if g in mgroups:          # M7 M8 too: LinuxCNC 2.9 refuses them in one block
                raise _BlockError(
                    f"M{mgroups[g]} and M{c} are in the same modal group (one per block)", f"M{c}"
                )
            mgroups[g] = c

        polar = "@" in vals or "^" in vals
        axis_words = []
        if polar:                         # X and Y come from them once the block's modes are set
            which = "@" if "@" in vals else "^"
            if "X" in vals or "Y" in vals:
                raise _BlockError("cannot use polar coordinates (@ ^) with X or Y words", which)
            if "X" not in self.axis_index or "Y" not in self.axis_index:
                raise _BlockError("polar coordinates (@ ^) need X and Y axes", which)
            axis_words = ["X", "Y"]
        for letter in vals:
            if letter in "@^":
                continue
            if letter in _AXIS_LETTERS:
                if letter not in self.axis_index:
                    raise _BlockError(
                        f"axis {letter} is not on this machine (axes: {' '.join(self.axes)})", letter
                    )
                axis_words.append(letter)
            elif letter not in _WORD_LETTERS:
                if letter == "E":
                    continue                  # its use is known once the motion is

                if letter in "UVW":
                    raise _BlockError(
                        f"axis {letter} is not on this machine (axes: {' '.join(self.axes)})", letter
                    )
                raise _BlockError(f"word {letter} is not supported", letter)

        g0 = groups.get(0)
        g1 = groups.get(1)
        if groups.get(8) in (431, 432) and axis_words:
            # the axis words are the offset: no motion in this block
            if g1 is not None and g1 != 800 or g0 == 280:
                raise _BlockError("cannot use two G codes that both use axis values "
                                  f"({_gname(groups[8])} and a motion code)", _gname(groups[8]))
            axis_words_offset = axis_words
            axis_words = []
        else:
            axis_words_offset = []
        axis_data = g0 in _AXIS_USERS       # G10, G28, G30, G52, G92: the axis words are data
        if g0 is not None and axis_data and g1 is not None and g1 != 800 and axis_words:
            raise _BlockError(
                f"cannot use two G codes that both use axis values ({_gname(g0)} and a motion code)",
                _gname(g0))
        if g1 == 800 and axis_words and not axis_data:
            raise _BlockError("cannot use axis values with G80", axis_words[0])
        motion: int | None
        if g1 is not None:
            motion = g1
        elif not axis_data and (
            axis_words
            or (self.motion in (20, 30) and ("I" in vals or "J" in vals or "K" in vals or "R" in vals))
        ):
            motion = self.motion  # LinuxCNC 2.9: centre words alone repeat a modal G02/G03
        else:
            motion = None
        if motion == 800:
            motion = None
        if polar and (motion is None or axis_data or axis_words_offset):
            # LinuxCNC: G10, G28, G30, G52, G92 and G43.1/G43.2 take no polar words either
            raise _BlockError("polar coordinates (@ ^) can only be used for motion",
                              "@" if "@" in vals else "^")
        if axis_words and motion is None and not axis_data:
            raise _BlockError(
                "axis words without a motion mode: program G00/G01/G02/G03 first", axis_words[0]
            )
        # G76: the taper; G33, G33.1 ignore it; M67, M68: the analog output
        if "E" in vals and motion not in _SYNCHRONISED and mgroups.get(5) not in (67, 68) and motion != 700:
            if mgroups.get(5) == 66:
                raise _BlockError("M66 E (an analog input): this machine has no analog inputs", "E")
            raise _BlockError("E word with no G33, G33.1, G76, M67 or M68 to use it", "E")
        is_arc = motion in (20, 30)
        is_cycle = motion in _CYCLES
        if g1 in (50, 51) and not axis_words:
            raise _BlockError(f"{_gname(g1)} needs X or Y (all axes missing with a motion code)", _gname(g1))
        if motion in (330, 331):
            name = _gname(motion)
            if "K" not in vals:
                raise _BlockError(f"{name} needs a K word (the thread pitch, length per turn)", name
                                  if g1 == motion else "K")
            if "F" in vals:
                raise _BlockError(f"F word with {name}: the feed is the pitch K times the spindle speed", "F")
        if motion == 760:
            if "P" not in vals:
                raise _BlockError("G76 needs a P word (the thread pitch, length per turn)",
                                  "G76" if g1 == 760 else axis_words[0] if axis_words else "G")
            missing = [letter for letter in "IJK" if letter not in vals]
            if missing:
                raise _BlockError(f"G76 needs I, J and K words (the thread's offset, first cut and depth): "
                                  f"{' '.join(missing)} missing",
                                  "G76" if g1 == 760 else axis_words[0] if axis_words else "G")
        for letter in ("I", "J", "K", "R"):
            if motion == 331 and letter in "IK" or motion == 330 and letter == "K" or motion == 760:
                continue
            if motion in _G7X and motion != 700 and letter in "IR":   # the depth of cut, the retract
                continue
            if letter in "IJ" and motion in (50, 51):
                continue
            if letter in vals and not is_arc and not (letter == "R" and (is_cycle or g0 == 100)):
                users = ("G02/G03 or canned cycle" if letter == "R"
                         else "G02/G03, G05 or G05.1" if letter in "IJ" else "G02/G03")
                raise _BlockError(f"{letter} word with no {users} to use it", letter)
        if "P" in vals and not (g0 in (40, 100) or is_arc or groups.get(13) == 640 or 9 in mgroups
                                or motion in _CYCLE_TAKES_P or 5 in mgroups or motion in (50, 52, 760, 700)):
            raise _BlockError("P word with no G code that uses it (G04, G02/G03, G05, G05.2, G64, G82, G84, "
                              "G86, G89)", "P")
        if ("Q" in vals and groups.get(13) != 640 and mgroups.get(6) != 61 and motion not in _CYCLE_NEEDS_Q
                and mgroups.get(5) not in (66, 67, 68) and motion not in (50, 760) and motion not in _G7X):
            raise _BlockError("Q word with no code that uses it (G05, G64, M61, G73, G76, G83, M66, M67, "
                              "M68)", "Q")
        if ("D" in vals and groups.get(7) not in (410, 420, 411, 421) and groups.get(14) != 960
                and motion not in _G7X):
            raise _BlockError("D word with no G41, G41.1, G42, G42.1 or G96 to use it", "D")
        if groups.get(14) == 960 and "S" not in vals:
            raise _BlockError("G96 needs an S word (the surface speed)", "G96")
        if ("L" in vals and not is_cycle and g0 != 100 and groups.get(7) not in (411, 421)
                and mgroups.get(5) != 66 and motion not in (52, 760)):
            raise _BlockError("L word with no canned cycle, G05.2, G10, G76 or M66 to use it", "L")
        if is_cycle:
            for letter in axis_words:
                if self.rotary[self.axis_index[letter]]:
                    raise _BlockError(f"cannot put an {letter} word in a canned cycle", letter)
        if "H" in vals and groups.get(8) not in (430, 432) and motion != 760:
            raise _BlockError("H word with no G43, G43.2 or G76 to use it", "H")

        # ---- execute in RS274/NGC order
        after = len(self.out) - 1
        ev = self.events
        m11 = mgroups.get(11)
        if m11 is not None:              # M70-M73 before the block's own changes
            self.modal_memory(m11, line_no)
        if 15 in groups:
            diameter = groups[15] == 70
            if motion == 760 and diameter != self.diameter:
                # LinuxCNC scales a G76's I J K as the mode changes in its block (and halves them
                # again in the cycle in G7): its arithmetic, kept so programs read the same
                for letter in "IJK":
                    vals[letter] *= 0.5 if diameter else 2.0
            self.diameter = diameter
        if self.diameter and "X" in vals:
            # LinuxCNC halves X as it reads it in G7 and undoes that for a G8 in the same
            # block: every use of the word (motion, G10, G92, G28, cycles) takes the radius
            vals["X"] *= 0.5
        if 6 in groups:  # units before anything that reads a length
            self.inch = groups[6] == 200
            self.scale = MM_PER_INCH if self.inch else 1.0
        scale = self.scale
        if 5 in groups:                 # LinuxCNC: G94 and G95 clear the feed rate, G93 does not
            self.feed_mode = groups[5]
            if self.feed_mode != 930:
                self.feed_mm_s = self.feed_per_rev = 0.0
        if "F" in vals:
            f = vals["F"]
            if f < 0.0:
                raise _BlockError(f"negative feed F{f:g}", "F")
            if self.feed_mode == 930:
                self.inverse_f = f
                self.feed_mm_s = 1.0 if f > 0.0 else 0.0   # the move's own feed comes in emit()
            elif self.feed_mode == 950:
                self.feed_per_rev = f * scale
                self.feed_mm_s = self.feed_per_rev * self.spindle_rpm / 60.0
            else:
                self.feed_mm_s = f * scale / 60.0
        if 14 in groups:
            self.spindle_mode(groups[14], vals, line_no, after, mgroups.get(7) is not None)
        if "S" in vals and self.css_max_rpm is not None:
            # a cutting speed: nothing to keep, the spindle's speed does not follow it here
            if vals["S"] < 0.0:
                raise _BlockError(f"negative surface speed S{vals['S']:g}", "S")
        elif "S" in vals:
            s = vals["S"]
            if s < 0.0:
                raise _BlockError(f"negative spindle speed S{s:g}", "S")
            changed = s != self.spindle_rpm
            self.spindle_rpm = s
            if self.feed_mode == 950:
                self.feed_mm_s = self.feed_per_rev * s / 60.0
            if changed and self.spindle_dir != 0 and mgroups.get(7) is None:
                ev.append(Event(EventKind.SPINDLE, line_no, after, self.spindle_dir * s))
        if "T" in vals:
            t = vals["T"]
            if t < 0 or t != int(t):
                raise _BlockError(f"tool number T{t:g} must be a whole number >= 0", "T")
            self.selected = self.known_tool(int(t), "T")
            ev.append(Event(EventKind.TOOL, line_no, after, float(t), f"tool T{int(t)} selected"))
        if mgroups.get(6) == 6:
            self.comp_refuses("change tools", "M6")
            self.tool = self.selected
            ev.append(
                Event(
                    EventKind.TOOL_CHANGE, line_no, after, float(self.tool),
                    f"M06: change to tool {self.tool_label(self.tool)} by hand, then press cycle start",
                )
            )
        elif mgroups.get(6) == 61:
            q = vals.get("Q")
            if q is None:
                raise _BlockError("M61 needs a Q word (the tool now in the spindle)", "M61")
            if q < 0 or q != int(q):
                raise _BlockError(f"tool number Q{q:g} must be a whole number >= 0", "Q")
            self.tool = self.selected = self.known_tool(int(q), "Q")
            ev.append(Event(EventKind.TOOL_SET, line_no, after, float(self.tool),
                            f"M61: tool {self.tool_label(self.tool)} is in the spindle"))
        m7 = mgroups.get(7)
        if m7 is not None:
            self.spindle_dir = {3: 1, 4: -1, 5: 0}[m7]
            ev.append(Event(EventKind.SPINDLE, line_no, after, self.spindle_dir * self.spindle_rpm,
                            f"M0{m7}"))
        m8 = [c for c in mcodes if c in (7, 8, 9)]
        for c in m8:
            ev.append(Event(EventKind.COOLANT, line_no, after, {7: 1.0, 8: 2.0, 9: 0.0}[c], f"M0{c}"))
            self.coolant = 0 if c == 9 else self.coolant | (1 if c == 7 else 2)
        m5 = mgroups.get(5)
        if m5 == 66:
            self.wait_input(vals, line_no)
            m5 = None
        if m5 in (67, 68):            # E the output's number, Q its value (LinuxCNC: -1 without Q)
            self.comp_refuses("set an analog output", f"M{m5}")
            e = vals.get("E")
            if e is None or math.floor(e + 0.5) < 0:
                raise _BlockError(f"M{m5} needs an E word, the analog output's number (0 or more)",
                                  "E" if e is not None else f"M{m5}")
            self.analog_outputs.append(AnalogOutput(f"M{m5}", line_no, math.floor(e + 0.5),
                                                    vals.get("Q", -1.0)))
        elif m5 is not None:          # M62/M64 on, M63/M65 off (all at this point of the path)
            self.comp_refuses("set a digital output", f"M{m5}")
            p = vals.get("P")
            if p is None or p != int(p) or int(p) not in self.outputs:
                known = ", ".join(f"P{k}" for k in sorted(self.outputs)) or "none: add [[outputs]]"
                raise _BlockError(f"M{m5} needs P with a configured output number ({known})",
                                  "P" if p is not None else f"M{m5}")
            self.output_event(int(p), m5 in (62, 64), line_no, after, f"M{m5}")
        if 9 in mgroups:
            self.override_codes(mgroups[9], vals, line_no, after)
        user = mgroups.get(10)
        if user is not None:
            action, message, output, on = self.mcodes[user]
            text = f"M{user}" + (f": {message}" if message else "")
            if action == "pause":
                ev.append(Event(EventKind.PAUSE, line_no, after, 0.0, text))
            elif action == "output":
                self.output_event(output, on, line_no, after, text)
            else:
                ev.append(Event(EventKind.MESSAGE, line_no, after, 0.0,
                                f"{text} (does nothing on this machine)"))
        if g0 == 40:
            p = vals.get("P")
            if p is None:
                raise _BlockError("G04 needs a P word (dwell time in seconds)", "G4")
            if p < 0.0:
                raise _BlockError(f"negative dwell time P{p:g}", "P")
            ev.append(Event(EventKind.DWELL, line_no, after, p, f"dwell {p:g} s"))
        if 2 in groups:
            if groups[2] != self.plane:
                self.comp_refuses("change the plane", _gname(groups[2]))
            self.plane = groups[2]
        if 7 in groups:                 # cutter compensation, then what it forbids to change
            if groups[7] == 400:
                self.comp.turn_off(self)
            else:
                self.comp_request(groups[7], vals, scale)
            self.comp_code = groups[7]
        if 8 in groups:
            self.comp_refuses("change the tool length offset", _gname(groups[8]))
            self.tool_length(groups[8], vals, axis_words_offset, scale)
        if 12 in groups:
            self.comp_refuses("change the coordinate system", _gname(groups[12]))
            self.work_code = groups[12]
            self.rotation = self.params.numbered.get(system_base(groups[12]) + 9, 0.0)
            self.set_offset(work=self.work_offsets[groups[12]])
            self.params.numbered[_P_SYSTEM] = float(_SYSTEMS.index(groups[12]) + 1)
        if 8 in groups:
            self.tlo_code = groups[8]
        if 13 in groups:
            self.comp_refuses("change the path control mode", _gname(groups[13]))
            self.exact_stop = groups[13] == 610
            # G61.1 keeps the programmed path without stopping at the joints; so does G64 unless
            # a tolerance lets the planner blend corners or join lines (planner.blend)
            self.exact_path = groups[13] == 611
            if groups[13] == 640:
                # G64 P: the tolerance of the corner blends; G64 alone: the machine's default;
                # G64 P0: the programmed path (no blends)
                p_tol = vals.get("P")
                self.blend_tol_mm = self.blend_default_mm if p_tol is None else max(p_tol, 0.0) * scale
                q_tol = vals.get("Q")
                self.naive_cam_mm = self.blend_tol_mm if q_tol is None or q_tol < 0.0 else q_tol * scale
            else:
                self.blend_tol_mm = 0.0
                self.naive_cam_mm = 0.0
            self.note_blend_tolerance()
        if 3 in groups:
            self.absolute = groups[3] == 900
        if 4 in groups:
            self.arc_absolute = groups[4] == 901
        if 10 in groups:
            self.comp_refuses("change the canned cycle retract mode", _gname(groups[10]))
            self.retract_r_plane = groups[10] == 990
        previous_motion = self.motion      # a cycle's words are required when it was not the mode
        if g1 is not None:
            self.motion = None if g1 == 800 else g1
        if not groups.keys().isdisjoint(_SHOWN_GROUPS):
            self.note_modal()

        # ---- offsets and stored positions (RS274/NGC order: after the modes, before motion)
        if g0 in (281, 301):
            self.comp_refuses("store the G28/G30 position", _gname(g0))
        elif g0 in (520, 920):
            self.comp_refuses("change the axis offsets (G52, G92)", _gname(g0))
        elif g0 in (280, 300):
            self.comp_refuses(f"use {_gname(g0)}", _gname(g0))
        if g0 in (100, 281, 301, 520, 920):
            self.data_code(g0, vals, axis_words, scale, line_no)
        g16 = groups.get(16)
        if g16 is not None:
            self.comp_refuses("change the axis offsets (G52, G92)", _gname(g16))
            self.data_code(g16, vals, [], scale, line_no)
        if g0 == 53:
            self.nurbs_end(g1, previous_motion, line_no)
        elif self.nurbs is not None and g1 is not None and g1 != 52:
            raise _BlockError(f"{_gname(g1)} before the NURBS begun at line {self.nurbs_line} is ended: "
                              "program G05.3 to run it first", _gname(g1))
        # ---- motion
        if motion in _PROBES and self.feed_mode != 940:
            mode = ("inverse time feed mode (G93)" if self.feed_mode == 930
                    else "feed per revolution mode (G95)")
            raise _BlockError(f"cannot probe ({_gname(motion)}) in {mode}: program G94 first", _gname(motion))
        if motion is not None and motion != 0 and motion not in _SYNCHRONISED and not axis_data:
            if self.feed_mode == 930:
                if motion in _CYCLES:
                    raise _BlockError("cannot use inverse time feed (G93) with canned cycles", "G93")
                if "F" not in vals:
                    raise _BlockError("G93 inverse time: every feed move needs its F word (1/F minutes)", "G")
            elif self.feed_mode == 950 and self.css_max_rpm is not None:
                raise _BlockError("G95 feed per revolution in G96: the speed would follow X, and this "
                                  "spindle has no speed output to follow it; program G97 and S in rpm", "G95"
                                  if 5 in groups else "G")
            elif self.feed_mode == 950 and self.spindle_rpm <= 0.0:
                raise _BlockError("G95 feed per revolution needs a spindle speed: S is 0", "G95"
                                  if 5 in groups else "G")
        if g1 == 800 or (motion is not None and motion not in _CYCLES):
            self.cycle_il = None            # a cycle sequence ends: G98's level is taken anew
        if g0 in (280, 300):
            self.g28(vals, axis_words, scale, line_no, _P_G28 if g0 == 280 else _P_G30)
        elif motion in _CYCLES:
            if g0 == 530:
                raise _BlockError("G53 needs G00 or G01", "G53")
            turn = None
            if polar and self.absolute:
                self.polar(vals)
            elif polar:                       # G91: the radius and angle step at every repeat
                if self.plane != 170:
                    raise _BlockError("polar coordinates (@ ^) only in the XY plane (G17)",
                                      "@" if "@" in vals else "^")
                turn = (vals.pop("@", 0.0) * scale, math.radians(vals.pop("^", 0.0)))
            self.canned_cycle(motion, previous_motion != motion, vals, axis_words, scale, line_no, turn)
        elif motion is not None:
            if g0 == 530:
                if motion not in (0, 10):
                    raise _BlockError("G53 needs G00 or G01", "G53")
                if self.comp.radius > 0.0:
                    raise _BlockError("cannot use G53 with cutter compensation on: program G40 first", "G53")
                if not self.absolute:
                    raise _BlockError("G53 cannot be used in incremental mode (G91)", "G53")
            if polar:
                self.polar(vals)
            if motion in (50, 51, 52):
                self.spline(motion, previous_motion, vals, axis_words, line_no)
                self.assign(assigns)
                return
            target = self.target(vals, axis_words, scale, g0 == 530)
            if motion in _PROBES:
                self.probe(motion, target, line_no)
            elif motion == 331:
                self.rigid_tap(target, vals, scale, line_no)
            elif motion == 330:
                self.synchronised_feed(target, vals, scale, line_no)
            elif motion == 760:
                self.thread_cycle(target, vals, scale, line_no)
            elif motion in _G7X:
                self.lathe_cycle(motion, vals, scale, line_no)
            elif motion in (0, 10):
                self.straight(target, motion == 0, line_no)
            else:
                self.arc(target, vals, motion == 20, scale, line_no)
        elif g0 == 530:
            raise _BlockError("G53 needs G00 or G01 with axis words", "G53")

        m4 = mgroups.get(4)
        if m4 is not None:
            self.comp.stop(self)
            kind = _STOP_EVENTS[m4]
            ev.append(Event(kind, line_no, len(self.out) - 1, 0.0, f"M{m4:02d}"))
            if kind is EventKind.END:
                if self.nurbs is not None:
                    raise _BlockError(f"the program ends with the NURBS begun at line {self.nurbs_line} "
                                      "not ended: program G05.3 to run it", f"M{m4}")
                self.ended = True
        self.assign(assigns)

    def messages(self, raw: str, line_no: int) -> None:
        """(MSG,text), (DEBUG,text) and (PRINT,text) comments as MESSAGE events; DEBUG and PRINT
        show parameter values (#123, #<name>) as LinuxCNC does, with six decimals. (ABORT,text)
        ends the program there with its text as the error, as in LinuxCNC 2.9."""
        for m in _MESSAGE_RE.finditer(raw):
            kind, text = m.group(1).upper(), m.group(2)
            if kind != "MSG":
                text = _PARAM_TEXT_RE.sub(self.param_text, text)
            if kind == "ABORT":
                raise _BlockError(f"the program aborts here (ABORT comment): {text.strip()}", col=1)
            self.events.append(Event(EventKind.MESSAGE, line_no, len(self.out) - 1, 0.0, text.strip()
                                     if kind == "MSG" else text))

    def param_text(self, m: re.Match[str]) -> str:
        if m.group(1) is not None:
            v = self.params.get_named(m.group(1).upper())
        else:
            n = int(m.group(2))
            v = self.params.get_numbered(n) if 1 <= n <= 5602 else None
        if v is not None and abs(v) < 5e-7:
            v = 0.0                        # round-off of a rotation must not print as -0.000000
        return "######" if v is None else f"{v:f}"

    def assign(self, assigns: Sequence[tuple[object, float]]) -> None:
        for key, value in assigns:
            if isinstance(key, str):
                self.params.set_named(key, value)
            else:
                self.params.numbered[key] = value  # type: ignore[index]

    # ------------------------------------------------------------------ motion helpers
    def target(
        self, vals: dict[str, float], axis_words: list[str], scale: float, machine: bool
    ) -> list[float]:
        pos = self.comp.base(self.pos)
        tgt = pos.copy()
        idx = self.axis_index
        rot = self.rotary
        off = self.offset
        absolute = self.absolute
        rotated = self.rotation != 0.0 and not machine and ("X" in axis_words or "Y" in axis_words)
        for letter in axis_words:
            if rotated and letter in "XY":
                continue
            i = idx[letter]
            v = vals[letter] if rot[i] else vals[letter] * scale
            if machine:
                tgt[i] = v
            elif absolute:
                tgt[i] = v + off[i]
            else:
                tgt[i] = pos[i] + v
        if rotated:                      # X and Y in the rotated system, then to the machine
            px, py = self.prog_xy(pos)
            for letter in ("X", "Y"):
                if letter in axis_words:
                    v = vals[letter] * scale
                    if letter == "X":
                        px = v if absolute else px + v
                    else:
                        py = v if absolute else py + v
            tgt[idx["X"]], tgt[idx["Y"]] = self.machine_xy(px, py)
        return tgt

    def path_length(self, a: Sequence[float], b: Sequence[float]) -> float:
        if self.all_linear:
            return math.dist(a, b)
        lin = self.linear_idx
        length = math.sqrt(sum((b[i] - a[i]) ** 2 for i in lin)) if lin else 0.0
        if length > _ZERO_LEN:
            return length
        rot = self.rotary_idx
        rot_len = math.sqrt(sum((b[i] - a[i]) ** 2 for i in rot))
        return rot_len if rot_len > _ZERO_LEN else length

    def straight(self, target: list[float], rapid: bool, line_no: int) -> None:
        comp = self.comp
        if comp.busy:
            if comp.radius > 0.0:
                if not rapid and self.feed_mm_s <= 0.0:
                    raise _BlockError(_ZERO_FEED, "G")
                comp.straight(self, target, rapid, line_no)
                return
            comp.straight_done()
        feed = math.inf if rapid else self.feed_mm_s
        if feed <= 0.0:                     # LinuxCNC: a G01 with no feed, even to where the tool is
            raise _BlockError(_ZERO_FEED, "G")
        length = self.path_length(self.pos, target)
        if length <= _ZERO_LEN:
            return  # zero-length move: dropped (position unchanged)
        self.emit(target, _RAPID if rapid else _LINE, feed, length, None, line_no)

    def probe(self, code: int, target: list[float], line_no: int) -> None:
        """G38.2-G38.5 as LinuxCNC 2.9 runs them: a straight move at the feed, the probe armed at
        rest before it; at rest after it, #5061-#5069 hold where the input changed (program
        coordinates) and #5070 whether it did, and the move ends where the machine stopped.
        What the machine did is known for the first ``probe_results``; the others are read as
        LinuxCNC's own preview and rs274 read them: the move goes to its programmed end point,
        #5061-#5069 hold that point and #5070 is 0 (a loop probing while #5070 says it touched
        ends; the run reads the rest again with the machine's result)."""
        name = _gname(code)
        if self.comp.side != 0:
            raise _BlockError(f"cannot probe ({name}) with cutter radius compensation on: program G40 "
                              "first", name)
        if self.feed_mm_s <= 0.0:
            raise _BlockError(f"cannot probe ({name}) with zero feed rate: program an F word", name)
        if self.comp.busy:
            self.comp.straight_done()
        if code in (382, 384) and all(abs(t - p) <= _ZERO_LEN for t, p in zip(target, self.pos)):
            raise _BlockError(f"{name}: start point too close to probe point (the move has no length)", name)
        k = len(self.probes)
        result = self.probe_results[k] if k < len(self.probe_results) else None
        known = result is not None
        if result is not None:
            if len(result.stop_position) != self.n or len(result.trip_position) != self.n:
                raise PlannerError(f"probe result {k} has positions for {len(result.stop_position)} axes, "
                                   f"the machine has {self.n}")
            end, trip, tripped = list(result.stop_position), list(result.trip_position), result.tripped
        else:
            end, trip, tripped = list(target), list(target), False
        self.events.append(Event(EventKind.PROBE_START, line_no, len(self.out) - 1, float(k),
                                 f"{name}: probe armed"))
        length = self.path_length(self.pos, end)
        moved = length > _ZERO_LEN
        if moved:
            self.emit(end, _LINE, self.feed_mm_s, length, None, line_no)
        self.probes.append(ProbeRequest(code, line_no, len(self.out) - 1 if moved else -1,
                                        tuple(float(v) for v in target), known))
        self.events.append(Event(EventKind.PROBE, line_no, len(self.out) - 1, float(k),
                                 f"{name}: probe result"))
        # #5061-#5069 in the coordinates of the system in use, in the program's units (an axis the
        # machine does not have reads 0)
        at = self.program_position(trip)
        for p, letter in enumerate(_PARAM_AXES):
            i = self.axis_index.get(letter)
            value = 0.0 if i is None else at[i] if self.rotary[i] else at[i] / self.scale
            self.params.numbered[_P_PROBE + p] = float(value)
        self.params.numbered[_P_PROBE_TRIPPED] = 1.0 if tripped else 0.0

    def rigid_tap(self, target: list[float], vals: dict[str, float], scale: float, line_no: int) -> None:
        """G33.1 X Y Z K I, LinuxCNC's rigid tapping, as feed moves: this spindle has no encoder to
        synchronise with, so the tap goes in at the pitch K times the programmed speed, the
        spindle reverses (I times faster, I >= 1) and it comes out the same way to where it
        started, where the spindle turns forward again (a floating tap holder takes up the
        difference)."""
        if self.css_max_rpm is not None:
            raise _BlockError("G33.1 in G96: the tap's pitch needs a known speed; program G97 and S in rpm",
                              "G33.1")
        if self.spindle_dir == 0 or self.spindle_rpm <= 0.0:
            raise _BlockError("spindle not turning in G33.1 (rigid tapping needs M3 or M4 and S)", "G33.1")
        if self.comp.side != 0:
            raise _BlockError("cannot tap (G33.1) with cutter radius compensation on: program G40 first",
                              "G33.1")
        if any(target[i] != self.pos[i] for i in self.rotary_idx):
            raise _BlockError("G33.1 moves the linear axes only", "G33.1")
        pitch = vals["K"] * scale
        if pitch <= 0.0:
            raise _BlockError(f"G33.1: the pitch K{vals['K']:g} must be above 0", "K")
        speed_up = max(vals.get("I", 1.0), 1.0)          # LinuxCNC: below 1 counts as 1
        start = list(self.pos)
        length = self.path_length(start, target)
        if length <= _ZERO_LEN:
            return
        if self.comp.busy:
            self.comp.straight_done()
        rpm = self.spindle_rpm
        into = pitch * rpm / 60.0
        self.taps.append(len(self.out))
        saved_stop, self.exact_stop = self.exact_stop, True
        # the tap's feed follows the spindle: neither override may change one without the other
        self.overrides_event(line_no, len(self.out) - 1,
                             "G33.1: feed and spindle overrides off while tapping",
                             _TAP_LOCK, EventKind.TAPPING)
        try:
            self.emit(target, _LINE, into, length, None, line_no, fixed_feed=True)
            self.events.append(Event(EventKind.SPINDLE, line_no, len(self.out) - 1,
                                     -self.spindle_dir * rpm * speed_up,
                                     "G33.1: spindle reversed to back the tap out (tapping as feed moves "
                                     "at the pitch, not synchronised with the spindle: use a floating tap "
                                     "holder)"))
            self.emit(start, _LINE, into * speed_up, length, None, line_no, fixed_feed=True)
            self.events.append(Event(EventKind.SPINDLE, line_no, len(self.out) - 1, self.spindle_dir * rpm,
                                     "G33.1: spindle turning forward again"))
        finally:
            self.overrides_event(line_no, len(self.out) - 1, "G33.1: overrides as before the tap",
                                 kind=EventKind.TAPPING)
            self.exact_stop = saved_stop

    def synchronised_speed(self, name: str) -> float:
        """The spindle speed (rpm) a G33 or G76 moves at: the spindle must turn (LinuxCNC's
        rule), and at a speed, or the feed it gives would be 0."""
        if self.spindle_dir == 0:
            raise _BlockError(f"spindle not turning in {name} (M3 or M4 first)", name)
        if self.spindle_rpm <= 0.0:
            raise _BlockError(f"{name} with the spindle at S0: the feed, the pitch times the speed, "
                              "would be 0", name)
        return self.spindle_rpm

    def synchronised_move(self, target: list[float], feed: float, line_no: int) -> None:
        """A feed move of G33 or G76 at ``feed`` (mm/s), whatever F and the feed mode say."""
        length = self.path_length(self.pos, target)
        if length > _ZERO_LEN:
            self.emit(target, _LINE, feed, length, None, line_no, fixed_feed=True)

    def synchronised_feed(self, target: list[float], vals: dict[str, float], scale: float,
                          line_no: int) -> None:
        """G33 X Y Z K, LinuxCNC's spindle-synchronised motion: a straight move at the pitch K
        (length per turn) times the spindle speed. Recorded in ``synchronised``: the machine,
        whose spindle has no encoder, refuses to run it (a thread's passes would not meet)."""
        rpm = self.synchronised_speed("G33")
        if self.comp.side != 0:
            raise _BlockError("cannot use G33 with cutter radius compensation on: program G40 first", "G33")
        pitch = vals["K"] * scale
        if pitch <= 0.0:
            raise _BlockError(f"G33: the pitch K{vals['K']:g} must be above 0", "K")
        if self.comp.busy:
            self.comp.straight_done()
        self.synchronised.append(SynchronisedMotion("G33", line_no))
        self.synchronised_move(target, pitch * rpm / 60.0, line_no)

    def thread_cycle(self, target: list[float], vals: dict[str, float], scale: float, line_no: int) -> None:
        """G76 P I J K [R Q H E L], LinuxCNC 2.9's threading cycle (interp_convert.cc), in X and
        Z from where the tool stands (the drive line): P the pitch; I the thread's offset from
        the drive line (negative: an outside thread, positive: boring); J the first cut's depth
        and K the thread's full depth; R the depth degression (the n-th pass cuts to
        J n^(1/R)); Q the compound slide angle (degrees); H spring passes at full depth; E the
        taper's length along Z, L which ends have it (1 entry, 2 exit, 3 both). Each pass goes
        back to the drive line, rapid in to its depth, feeds along Z at the pitch times the
        speed, and rapid out; the cycle ends with a rapid to the block's end point. In G7 I J K
        are diameters. Recorded in ``synchronised``: the machine refuses to run it."""
        rpm = self.synchronised_speed("G76")
        if any(target[i] != self.pos[i] for i in self.rotary_idx):
            raise _BlockError("cannot move rotary axes with G76", "G76")
        if "X" not in self.axis_index or "Z" not in self.axis_index:
            raise _BlockError(f"G76 threads along Z and cuts in X: this machine has no "
                              f"{'X' if 'X' not in self.axis_index else 'Z'} axis", "G76")
        if self.comp.side != 0:
            raise _BlockError("cannot use the G76 threading cycle with cutter radius compensation on: "
                              "program G40 first", "G76")
        i_w, j_w, k_w = vals["I"], vals["J"], vals["K"]
        if i_w == 0.0:
            raise _BlockError("G76: I (the thread's offset from the drive line) must not be 0", "I")
        if j_w <= 0.0:
            raise _BlockError("G76: J (the first cut's depth) must be greater than 0", "J")
        if k_w <= j_w:
            raise _BlockError("G76: K (the full thread depth) must be greater than J", "K")
        if vals["P"] <= 0.0:
            raise _BlockError(f"G76: the pitch P{vals['P']:g} must be above 0", "P")
        spring = vals.get("H", 0.0)
        if spring != int(spring) or spring < 0.0:
            raise _BlockError(f"G76: H{spring:g} (spring passes) must be a whole number of 0 or more", "H")
        flags = vals.get("L", 0.0)
        if flags != int(flags) or flags < 0.0:
            raise _BlockError(f"G76: L{flags:g} (taper ends) must be a whole number of 0 or more", "L")
        half = 0.5 if self.diameter else 1.0
        i_mm, j_mm, k_mm = i_w * scale * half, j_w * scale * half, k_w * scale * half
        ix, iz, iy = self.axis_index["X"], self.axis_index["Z"], self.axis_index.get("Y")
        here, end = self.program_position(self.pos), self.program_position(target)
        safe_x, start_z = here[ix], here[iz]
        start_y = here[iy] if iy is not None else 0.0
        boring = i_mm > 0.0
        full_dia_depth = abs(i_mm)
        cut_increment = abs(j_mm)
        full_threadheight = abs(k_mm)
        end_depth = full_threadheight + full_dia_depth
        pitch = vals["P"] * scale
        angle = vals.get("Q", 0.0)
        angle = math.radians(0.0 if angle == -1.0 else angle)    # LinuxCNC reads Q-1 as no Q
        if end[iz] > start_z:
            angle = -angle
        degression = vals.get("R", 1.0)
        degression = max(degression, 1.0)
        taper_dist = max(vals.get("E", 0.0) * scale, 0.0)
        taper_pitch = (pitch * math.hypot(taper_dist, full_threadheight) / taper_dist if taper_dist > 0.0
                       else pitch)
        if end[iz] > start_z:
            taper_dist = -taper_dist
        entry_taper, exit_taper = int(flags) & 1, int(flags) & 2
        target_z = end[iz] + full_threadheight * math.tan(angle)
        # the passes' depths: J n^(1/R) below the first, then the full depth 1 + H times
        depths = []
        depth, n = full_dia_depth + cut_increment, 1
        while depth < end_depth:
            depths.append(depth)
            if len(depths) > _MAX_CYCLE_MOVES // 6:
                raise _BlockError(f"G76: J{j_w:g} to K{k_w:g} (R{degression:g}) makes more than "
                                  f"{_MAX_CYCLE_MOVES // 6} passes", "J")
            n += 1
            depth = full_dia_depth + cut_increment * n ** (1.0 / degression)
        if len(depths) + spring + 1 > _MAX_CYCLE_MOVES // 6:
            raise _BlockError(f"G76: H{spring:g} makes more than {_MAX_CYCLE_MOVES // 6} passes", "H")
        depths += [end_depth] * (int(spring) + 1)
        off = self.offset
        rotated = self.rotation != 0.0

        def point(x: float, z: float) -> list[float]:
            q = self.program_position(self.pos)
            q[ix], q[iz] = x, z
            if iy is not None:
                q[iy] = start_y
            out = list(self.pos)
            if rotated and iy is not None:     # the XY rotation turns X (and Y) with the system
                out[ix], out[iy] = self.machine_xy(q[ix], q[iy])
            else:
                out[ix] = q[ix] + off[ix]
                if iy is not None:
                    out[iy] = q[iy] + off[iy]
            out[iz] = q[iz] + off[iz]
            return out

        sign = 1.0 if boring else -1.0
        feed = pitch * rpm / 60.0
        taper_feed = taper_pitch * rpm / 60.0
        self.synchronised.append(SynchronisedMotion("G76", line_no))
        saved_stop, self.exact_stop = self.exact_stop, True
        try:
            for depth in depths:
                zoff = (depth - full_dia_depth) * math.tan(angle)
                at_depth = safe_x + sign * depth
                clear = safe_x + sign * (depth - end_depth)
                top = safe_x + sign * (depth - full_threadheight)
                self.straight(point(clear, start_z - zoff), True, line_no)            # back
                if taper_dist and entry_taper:
                    self.synchronised_move(point(top, start_z - zoff), taper_feed, line_no)       # in
                    self.synchronised_move(point(at_depth, start_z - zoff - taper_dist), taper_feed,
                                           line_no)                                          # angled in
                else:
                    self.straight(point(at_depth, start_z - zoff), True, line_no)     # in
                if taper_dist and exit_taper:
                    self.synchronised_move(point(at_depth, target_z - zoff + taper_dist), feed, line_no)
                    self.synchronised_move(point(top, target_z - zoff), taper_feed, line_no)  # angled out
                else:
                    self.synchronised_move(point(at_depth, target_z - zoff), feed, line_no)   # over
                self.straight(point(clear, target_z - zoff), True, line_no)          # out
            self.straight(target, True, line_no)
        finally:
            self.exact_stop = saved_stop

    def lathe_cycle(self, motion: int, vals: dict[str, float], scale: float, line_no: int) -> None:
        """G70 (finishing), G71 (roughing along Z) and G72 (along X), with .1 (no pockets) and .2
        (the pockets only), as LinuxCNC 2.9 runs them (``planner.g7x``): a rapid to the block's
        X Z, then the profile of the numbered subroutine Q (G0-G3 blocks with X Z, U W
        incremental, I K or R, A a round and C a chamfer at its end) is cut from there: G71/G72
        in passes of depth I (default 1), retracting R (0.5), down to D from the profile moved by
        U W; G70 in P passes from D to E. In G18 only."""
        name = _gname(motion)
        cycle, variant = motion // 10, motion % 10
        if "Q" not in vals:
            raise _BlockError(f"{name} requires a Q word (the number of the subroutine with the profile)",
                              name)
        if self.comp.side != 0:
            raise _BlockError(f"{name} cannot be used with cutter compensation enabled: program G40 first",
                              name)
        if self.plane != 180:
            raise _BlockError(f"{name} can only be used in the XZ plane (G18)", name)
        if "X" not in self.axis_index or "Z" not in self.axis_index:
            raise _BlockError(f"{name} cuts in X and Z: this machine has no "
                              f"{'X' if 'X' not in self.axis_index else 'Z'} axis", name)
        ix, iz = self.axis_index["X"], self.axis_index["Z"]
        here = self.program_position(self.pos)
        x, z = here[ix] / scale, here[iz] / scale           # program units, as LinuxCNC works
        incremental = not self.absolute
        if incremental:
            x, z = x + vals.get("X", 0.0), z + vals.get("Z", 0.0)
        else:
            x, z = vals.get("X", x), vals.get("Z", z)
        arc_absolute, absolute = self.arc_absolute, self.absolute
        last_mode = [0]

        def target(p: complex) -> list[float]:
            return self.target({"X": p.imag, "Z": p.real}, ["X", "Z"], scale, False)

        def straight(p: complex, rapid: bool) -> None:
            self.straight(target(p), rapid, line_no)
            last_mode[0] = 0 if rapid else 10

        def arc(ccw: bool, center: complex, p: complex) -> None:
            now = self.program_position(self.pos)
            if abs(now[iz] / scale - p.real) >= 1e-4 or abs(now[ix] / scale - p.imag) >= 1e-4:
                self.arc(target(p), {"X": p.imag, "Z": p.real, "I": center.imag, "K": center.real}, not ccw,
                         scale, line_no)
                last_mode[0] = 30 if ccw else 20

        # LinuxCNC reads the cycle's own moves, and the block's X Z for the rapid, as absolute
        self.absolute, self.arc_absolute = True, True
        try:
            axes: list[str] = [a for a in ("X", "Z") if a in vals]
            self.straight(self.target(vals, list(axes), scale, False), True, line_no)
            segments = self.lathe_profile(vals["Q"], complex(z, x), incremental, arc_absolute, name)
            if len(segments) <= 1:
                return
            i = vals.get("I", 1.0)
            if i <= 0:
                raise _BlockError(f"{name}: I (the depth of cut) must be greater than zero", "I")
            out = g7x.Motion(lambda p: straight(p, False), lambda p: straight(p, True), arc)
            profile = g7x.Profile(segments)
            if cycle == 70:
                profile.g70(out, x, z, vals.get("D", 0.0), vals.get("E", 0.0), vals.get("P", 1.0))
            else:
                profile.g71(out, variant, x, z, vals.get("U", 0.0), vals.get("W", 0.0), vals.get("D", 0.0), i,
                            vals.get("R", 0.5), rotate=cycle == 72)
        except g7x.G7xError as e:
            raise _BlockError(f"{name}: {e}", name) from None
        except (ZeroDivisionError, ValueError, OverflowError):
            # LinuxCNC's arithmetic goes on with infinities here and draws nonsense
            raise _BlockError(f"{name}: the profile cannot be offset or cut (a segment of no length, or "
                              "the cycle's start on the profile)", name) from None
        finally:
            self.absolute, self.arc_absolute = absolute, arc_absolute
        self.motion = last_mode[0]

    def lathe_profile(self, q: float, start: complex, incremental: bool, centre_absolute: bool,
                      name: str) -> list[Any]:
        """The profile of subroutine ``o<q>`` as LinuxCNC's G7x reads it (program units, points
        as z + 1j x): each block's G0-G3, X Z or U W, I K or R, A (round) and C (chamfer);
        other words are not the profile's. Parameters are set as the blocks are read."""
        if q != int(q) or q < 0:
            raise _BlockError(f"{name} Q{q:g}: the profile's subroutine number is a whole number", "Q")
        frame = self.frame
        label = str(int(q))
        found = None
        if frame is not None:
            found = self.find_sub(label, Statement(self.frame_pc, label, "CALL", ""), frame)
        if frame is None or found is None:
            raise _BlockError(f"{name} Q{q:g}: no o{label} sub in this program (the profile)", "Q")
        segments: list[Any] = []
        mode = 0                                  # the rapid to the start was the last move
        scale = self.scale
        saved_pos = self.pos
        k, steps = found[0] + 1, 0
        try:
            while k < found[1]:
                steps += 1
                if steps > _MAX_EXECUTED:
                    raise _BlockError(f"{name}: more than {_MAX_EXECUTED:,} profile blocks read (an endless "
                                      "loop?)", "Q")
                where = f"line {k + 1}, in the profile"
                st = frame.structure.statements.get(k)
                if st is not None:                # loops and branches run as the profile is read
                    if st.keyword == "RETURN":
                        break
                    if st.keyword not in ("IF", "ELSEIF", "ELSE", "ENDIF", "WHILE", "ENDWHILE", "DO",
                                          "DOWHILE", "REPEAT", "ENDREPEAT", "BREAK", "CONTINUE"):
                        raise _BlockError(f"{name}: o{st.label} {st.keyword.lower()} ({where}) is not "
                                          "supported: a profile's calls are written out", "Q")
                    try:
                        nxt = self.statement(st, frame, [])
                    except _BlockError as e:
                        raise _BlockError(f"{name}: {where}: {e.message}", "Q") from None
                    assert isinstance(nxt, int)
                    k = nxt
                    continue
                k += 1
                text = frame.lines[k - 1].strip()
                if not text or text.startswith("%") or (text.startswith("/") and self.block_delete):
                    continue
                try:
                    words, assigns = read_line(text.lstrip("/"), self.params)
                except LexError as e:
                    raise _BlockError(f"{name}: {where}: {e.message}", "Q") from None
                mode, start = self._profile_block(words, mode, start, incremental, centre_absolute, segments,
                                                  f"{name}: ", f" ({where})")
                # #<_x>, #<_z> read where the profile has got to, as in LinuxCNC
                self.pos = self.target({"X": start.imag, "Z": start.real}, ["X", "Z"], scale, False)
                self.assign(assigns)
        finally:
            self.pos = saved_pos
        return segments

    def _profile_block(self, words: list, mode: int, start: complex, incremental: bool, centre_absolute: bool,
                       segments: list[Any], head: str, where: str) -> tuple[int, complex]:
        """One block of a G7x profile: its segment (and round or chamfer) appended; the motion
        mode and the point it ends at returned."""
        w: dict[str, float] = {}
        for letter, value in words:
            if letter == "G" and float(value) in (0.0, 1.0, 2.0, 3.0):
                mode = int(float(value)) * 10
            else:
                w[letter] = float(value)
        end = complex(0.0, 0.0) if incremental else start
        for word, axis in (("U", "X"), ("W", "Z")):
            if word in w:
                if incremental:
                    raise _BlockError(f"{head}cannot use {word} in incremental mode (G91){where}", "Q")
                if axis in w:
                    raise _BlockError(f"{head}cannot use {word} and {axis} in the same block{where}", "Q")
        if "U" in w:
            end += 1j * (w["U"] / 2 if self.diameter else w["U"])
        elif "X" in w:
            end = complex(end.real, w["X"] / 2 if self.diameter else w["X"])
        if "W" in w:
            end += w["W"]
        elif "Z" in w:
            end = complex(w["Z"], end.imag)
        center = complex(w.get("K", 0.0), w.get("I", 0.0))
        if incremental:
            end += start
        if end == start:
            return mode, start
        if mode in (0, 10):
            segments.append(g7x.StraightSegment(start, end))
        elif "R" in w:
            if "I" in w or "K" in w:
                raise _BlockError(f"{head}both R and I or K for an arc{where}", "Q")
            r, chord = w["R"], abs(end - start) ** 2
            if r * r < chord / 4:
                raise _BlockError(f"{head}radius R{r:g} too small for the arc{where}", "Q")
            d = 1j * math.sqrt((r * r - chord / 4) / chord) * (end - start)
            segments.append(g7x.RoundSegment(mode == 30, start, (start + end) / 2 + (d if mode == 30 else -d),
                                             end))
        else:
            if "I" not in w and "K" not in w:
                raise _BlockError(f"{head}either I or K must be present for an arc{where}", "Q")
            segments.append(g7x.RoundSegment(mode == 30, start, center if centre_absolute else center + start,
                                             end))
        if "A" in w and "C" in w:
            raise _BlockError(f"{head}both A and C on a corner{where}", "Q")
        if "A" in w:
            segments.append(g7x.fillet(w["A"], end))
        if "C" in w:
            segments.append(g7x.chamfer(w["C"], end))
        return mode, end

    def emit(self, target: list[float], kind: MoveKind, feed: float, length: float, arc: Arc | None,
             line_no: int, fixed_feed: bool = False) -> None:
        if self.feed_mode == 930 and kind is not _RAPID and not fixed_feed:
            feed = length * self.inverse_f / 60.0      # the move takes 1/F minutes
        self.out.append(target, line_no, kind, feed, length, arc, self.exact_stop)
        self.pos = target

    def drop_move(self, i: int) -> None:
        """Remove move ``i`` (cutter compensation cut it to nothing); what refers to later moves
        by index moves down one."""
        self.out.delete(i)
        self.pos = self.out.last_end()
        self.events[:] = [replace(e, after_move=e.after_move - 1) if e.after_move >= i else e
                          for e in self.events]
        self.offset_changes[:] = [(f - 1 if f > i else f, o) for f, o in self.offset_changes]
        self.offset_parts[:] = [(p[0] - 1 if p[0] > i else p[0], *p[1:]) for p in self.offset_parts]
        self.modal_changes[:] = [(f - 1 if f > i else f, t) for f, t in self.modal_changes]
        self.taps[:] = [t - 1 if t > i else t for t in self.taps]
        self.probes[:] = [replace(p, move_index=p.move_index - 1) if p.move_index > i else p
                          for p in self.probes]

    def canned_cycle(self, motion: int, first: bool, vals: dict[str, float], axis_words: list[str],
                     scale: float, line_no: int, turn: tuple[float, float] | None = None) -> None:
        """G73, G74, G81-G86, G89 as LinuxCNC 2.9 runs them (interp_cycles.cc): in the selected
        plane, the hole axis is the plane's normal; R, the bottom, P and Q are sticky while the
        same cycle stays the motion mode; L repeats (incremental G91 steps the position each
        time); G98 returns to the level the cycles started from (or R if that is higher), G99 to
        R. Every move of the cycle is an exact stop, as LinuxCNC's exact path mode. ``first``: the
        cycle was not the motion mode before this block, so R, the bottom, P and Q must be given.
        ``turn``: G91 polar words (radius step in mm, angle step in radians): each repeat's hole
        is the one before moved out by the radius and turned by the angle about the origin."""
        name = _gname(motion)
        if self.feed_mm_s <= 0.0:
            raise _BlockError(_ZERO_FEED, name)
        if self.comp_code != 400:
            raise _BlockError("cannot use canned cycles with cutter compensation on "
                              f"({_gname(self.comp_code)})", name)
        pname, fa, sa, na, *_ = self.plane_axes()
        plane_g = _PLANE_G[self.plane]
        normal = _PLANES[self.plane][3]
        if na < 0:
            raise _BlockError(f"{plane_g} canned cycle is not possible on a machine without {normal} axis",
                              name)
        first_l, second_l = _PLANES[self.plane][1], _PLANES[self.plane][2]
        if "R" in vals:
            self.cycle_r_word = vals["R"] * scale
        elif first:
            raise _BlockError(f"{name} needs an R word (the retract plane) the first time", name)
        if normal in vals:
            self.cycle_z_word = vals[normal] * scale
        elif first:
            raise _BlockError(f"{name} needs a {normal} word (the bottom of the hole) the first time "
                              f"in {plane_g}", name)
        repeats = vals.get("L", 1.0)
        if repeats != int(repeats) or repeats < 1:
            raise _BlockError(f"L{repeats:g}: the repeats of a cycle are a whole number of 1 or more", "L")
        if repeats > _MAX_CYCLE_MOVES:
            raise _BlockError(f"L{repeats:g}: more than {_MAX_CYCLE_MOVES} repeats in one block", "L")
        if motion in _CYCLE_TAKES_P:
            if "P" in vals:
                if vals["P"] < 0.0:
                    raise _BlockError(f"negative dwell time P{vals['P']:g}", "P")
                self.cycle_p = vals["P"]
            elif first and motion in _CYCLE_NEEDS_P:
                raise _BlockError(f"{name} needs a P word (the dwell at the bottom, s) the first time", name)
        if motion in _CYCLE_NEEDS_Q:
            if "Q" in vals:
                self.cycle_q = vals["Q"] * scale
            elif first:
                raise _BlockError(f"{name} needs a Q word (the peck depth) the first time", name)
            if self.cycle_q <= 0.0:
                raise _BlockError(f"{name}: negative or zero Q (peck depth)", "Q")
        if motion in (740, 840):
            want = -1 if motion == 740 else 1
            if self.spindle_dir == 0:
                raise _BlockError(f"spindle not turning in {name} (tapping needs M0{3 if want > 0 else 4})",
                                  name)
            if self.spindle_dir != want:
                raise _BlockError(f"spindle turning {'clockwise' if want < 0 else 'counterclockwise'} in "
                                  f"{name}", name)
        if motion == 860 and self.spindle_dir == 0:
            raise _BlockError("spindle not turning in G86", name)
        off = self.offset
        pos = self.pos
        rotated = self.rotation != 0.0
        ix, iy = self.axis_index.get("X", -1), self.axis_index.get("Y", -1)
        # in G18/G19 of a rotated system the hole axis or the plane's second axis is a turned X or Y
        here_prog = self.program_position(pos)
        current_cc = here_prog[na]
        if self.cycle_il is None:
            self.cycle_il = current_cc
        old_cc = self.cycle_il
        if self.absolute:
            aa_inc = bb_inc = 0.0
            r = self.cycle_r_word
            cc = self.cycle_z_word
            cur_a, cur_b = here_prog[fa], here_prog[sa]
            aa = vals[first_l] * scale if first_l in vals else cur_a
            bb = vals[second_l] * scale if second_l in vals else cur_b
        else:
            aa_inc = vals.get(first_l, 0.0) * scale
            bb_inc = vals.get(second_l, 0.0) * scale
            r = self.cycle_r_word + old_cc
            cc = r + self.cycle_z_word
            aa, bb = here_prog[fa], here_prog[sa]
        if r < cc:
            raise _BlockError(f"R ({r / scale:g}) below the bottom {normal} ({cc / scale:g}) of the canned "
                              f"cycle in {plane_g}", "R" if "R" in vals else name)
        delta = self.cycle_q
        rapid_delta = _PECK_CLEARANCE_MM
        if motion in _CYCLE_NEEDS_Q and repeats * (r - cc) / delta > _MAX_CYCLE_MOVES:
            raise _BlockError(f"{name}: Q{delta / scale:g} over a depth of {(r - cc) / scale:g} makes more "
                              f"than {_MAX_CYCLE_MOVES} pecks", "Q")

        def go(a: float, b: float, c: float, rapid: bool) -> None:
            target = self.pos.copy()
            if rotated:                      # the plane's point in program coordinates, then turned
                q = self.program_position(self.pos)
                q[fa], q[sa], q[na] = a, b, c
                target[ix], target[iy] = self.machine_xy(q[ix], q[iy])
                for i in (fa, sa, na):
                    if i not in (ix, iy):
                        target[i] = q[i] + off[i]
            else:
                target[fa] = a + off[fa]
                target[sa] = b + off[sa]
                target[na] = c + off[na]
            self.straight(target, rapid, line_no)

        def event(kind: EventKind, value: float, text: str) -> None:
            self.events.append(Event(kind, line_no, len(self.out) - 1, value, text))

        if old_cc < r:                         # below the R plane: straight up to it first
            go(here_prog[fa], here_prog[sa], r, True)
            old_cc = current_cc = r
        clear_cc = r if self.retract_r_plane else old_cc
        saved_stop = self.exact_stop
        self.exact_stop = True
        rpm = self.spindle_dir * self.spindle_rpm
        try:
            for k in range(int(repeats)):
                aa += aa_inc
                bb += bb_inc
                for step, letter in zip(turn or (), "@^"):
                    if not step:                # LinuxCNC: a zero step is no step
                        continue
                    if aa == 0.0 and bb == 0.0:
                        raise _BlockError("incremental motion with polar coordinates is indeterminate at "
                                          "the origin", letter)
                    radius, theta = math.hypot(aa, bb), math.atan2(bb, aa)
                    radius, theta = (radius + step, theta) if letter == "@" else (radius, theta + step)
                    aa, bb = radius * math.cos(theta), radius * math.sin(theta)
                if k == 0 and current_cc > r:
                    go(aa, bb, current_cc, True)
                    go(aa, bb, r, True)
                else:
                    go(aa, bb, clear_cc, True)
                    if clear_cc > r:
                        go(aa, bb, r, True)
                if motion in (730, 830):
                    if self.comp.busy or (rotated and na in (ix, iy)):   # pecks along a turned axis
                        depth = r - delta
                        while depth > cc:
                            go(aa, bb, depth, False)
                            if motion == 830:
                                go(aa, bb, r, True)
                            go(aa, bb, depth + rapid_delta, True)
                            depth -= delta
                    else:
                        self.pecks(na, off[na], r, cc, delta, rapid_delta, motion == 830, line_no)
                    go(aa, bb, cc, False)
                    go(aa, bb, clear_cc, True)
                elif motion in (740, 840):
                    # LinuxCNC turns both overrides off for the tap: its feed is the pitch times
                    # the speed
                    self.overrides_event(line_no, len(self.out) - 1, f"{name}: feed and spindle overrides "
                                         "off while tapping", _TAP_LOCK,
                                         EventKind.TAPPING)
                    go(aa, bb, cc, False)
                    event(EventKind.SPINDLE, -rpm, f"{name}: spindle reversed to back the tap out (tapping "
                          "as feed moves at F, not synchronised with the spindle: use a floating tap holder)")
                    if self.cycle_p > 0.0:
                        event(EventKind.DWELL, self.cycle_p, f"dwell {self.cycle_p:g} s")
                    go(aa, bb, clear_cc, False)
                    event(EventKind.SPINDLE, rpm, f"{name}: spindle turning forward again")
                    self.overrides_event(line_no, len(self.out) - 1, f"{name}: overrides as before the tap",
                                         kind=EventKind.TAPPING)
                else:
                    go(aa, bb, cc, False)
                    if motion in (820, 860, 890) and self.cycle_p > 0.0:
                        event(EventKind.DWELL, self.cycle_p, f"dwell {self.cycle_p:g} s")
                    if motion == 850:
                        go(aa, bb, r, False)
                        go(aa, bb, clear_cc, True)
                    elif motion == 860:
                        event(EventKind.SPINDLE, 0.0, "G86: spindle stopped to retract")
                        go(aa, bb, clear_cc, True)
                        event(EventKind.SPINDLE, rpm, "G86: spindle restarted")
                    elif motion == 890:
                        go(aa, bb, clear_cc, False)
                    else:                      # G81, G82
                        go(aa, bb, clear_cc, True)
        finally:
            self.exact_stop = saved_stop

    def pecks(self, na: int, off_na: float, r: float, cc: float, delta: float, rapid_delta: float,
              out_to_r: bool, line_no: int) -> None:
        """The pecks of G73 / G83 (``out_to_r``) above the bottom ``cc``, from the R plane ``r``,
        all at once: feed down by ``delta`` each time, then back off (G73: ``rapid_delta`` up;
        G83: out to R and rapid back down to ``rapid_delta`` above the peck). The depths are
        LinuxCNC's, by the same repeated subtraction; moves of no length are left out, as
        ``straight`` leaves them out. Thousands of pecks (a small Q on a deep hole) take
        milliseconds instead of seconds."""
        n_est = int((r - cc) / delta) + 2
        depths = np.subtract.accumulate(np.concatenate(([r], np.full(n_est, delta))))[1:]
        depths = depths[depths > cc]
        if not len(depths):
            return
        if self.feed_mm_s <= 0.0:
            raise _BlockError(_ZERO_FEED, "G")
        per = 3 if out_to_r else 2
        z = np.empty(len(depths) * per)
        z[0::per] = depths
        if out_to_r:
            z[1::per] = r
        z[per - 1::per] = depths + rapid_delta
        ends = np.repeat(np.asarray([self.pos], dtype=float), len(z), axis=0)
        ends[:, na] = z + off_na
        before = np.concatenate(([self.pos[na]], ends[:-1, na]))
        length = np.abs(ends[:, na] - before)
        rapid = np.ones(len(z), dtype=bool)
        rapid[0::per] = False
        keep = length > _ZERO_LEN
        if not keep.all():
            # a move left out leaves the tool where it was, and the next one starts there (rare:
            # a back-off landing within 1e-9 mm of the R plane): measured one by one
            at = self.pos[na]
            for i in range(len(z)):
                length[i] = abs(ends[i, na] - at)
                keep[i] = length[i] > _ZERO_LEN
                if keep[i]:
                    at = ends[i, na]
        feed = np.where(rapid, math.inf, self.feed_mm_s)
        self.out.extend(ends[keep], np.full(int(keep.sum()), line_no), np.where(rapid[keep], 0, 1),
                        feed[keep], length[keep], True)
        self.pos = ends[-1].tolist()

    def g28(self, vals: dict[str, float], axis_words: list[str], scale: float, line_no: int,
            base: int = _P_G28) -> None:
        """G28 / G30: rapid to the programmed point (if any), then to the stored position of
        those axes (#5161- for G28, #5181- for G30, machine coordinates, set by G28.1 / G30.1;
        machine zero until then). No axis words: every axis goes there."""
        stored = [self.params.numbered.get(base + p, 0.0) for p in self.axis_param]
        if axis_words:
            mid = self.target(vals, axis_words, scale, False)
            self.straight(mid, True, line_no)
            home = self.pos.copy()
            for letter in axis_words:
                i = self.axis_index[letter]
                home[i] = stored[i]
            if self.rotation != 0.0 and ("X" in axis_words) != ("Y" in axis_words):
                # LinuxCNC keeps the other axis's program coordinate, which a rotated system
                # couples to both machine axes: X (or Y) of the stored point, the rest as it is
                sx, sy = self.prog_xy(stored)
                cx, cy = self.prog_xy(self.pos)
                px, py = (sx, cy) if "X" in axis_words else (cx, sy)
                ix, iy = self.axis_index["X"], self.axis_index["Y"]
                home[ix], home[iy] = self.machine_xy(px, py)
        else:
            home = stored
        self.straight(home, True, line_no)

    def data_code(self, code: int, vals: dict[str, float], axis_words: list[str], scale: float,
                  line_no: int) -> None:
        """G10 L2/L20 (coordinate system data), G28.1/G30.1 (store the position), G52 and G92
        (axis offsets), G92.1/.2/.3, as LinuxCNC 2.9 sets its parameters."""
        num = self.params.numbered

        def value(letter: str) -> float:
            i = self.axis_index[letter]
            return vals[letter] if self.rotary[i] else vals[letter] * scale

        if code == 100:
            l_word = vals.get("L")
            if l_word is None:
                raise _BlockError("G10 needs an L word (L2 or L20: coordinate system; L1, L10, L11: tool "
                                  "table)", "G10")
            if l_word in (1, 10, 11):
                self.g10_tool(int(l_word), vals, axis_words, scale, line_no)
                return
            if l_word == 0:
                # LinuxCNC reloads its tool table file, which G10 L1/L10/L11 have already
                # written: here the table the program reads is the machine's, kept up to date
                # the same way, so there is nothing to reload; LinuxCNC's refusal is kept
                if self.tool > 0:
                    raise _BlockError(f"G10 L0 (reload the tool table) with tool {self.tool} in the spindle: "
                                      "unload it first (M6 T0 or M61 Q0)", "L")
                return
            if l_word not in (2, 20):
                raise _BlockError(f"G10 L{l_word:g} is not a G10 this control knows (L0, L1, L2, L10, L11, "
                                  "L20)", "L")
            p = vals.get("P")
            if p is None or p != int(p) or not 0 <= p <= 9:
                raise _BlockError("G10 L2/L20 needs P0-P9 (0: the system in use, 1: G54 ... 9: G59.3)", "P")
            system = self.work_code if p == 0 else _SYSTEMS[int(p) - 1]
            base = system_base(system)
            if "R" in vals:
                if l_word == 20:
                    raise _BlockError("R not allowed in G10 L20 (the rotation is set with G10 L2 R)", "R")
                if "X" not in self.axis_index or "Y" not in self.axis_index:
                    raise _BlockError("G10 L2 R rotates the XY plane: this machine has no X and Y", "R")
                num[base + 9] = vals["R"]
            if self.comp_code != 400 and system == self.work_code:
                raise _BlockError("cannot change the offsets of the coordinate system in use with cutter "
                                  "compensation on", "G10")
            new = list(self.work_offsets[system])
            theta = num.get(base + 9, 0.0)
            for letter in axis_words:
                i = self.axis_index[letter]
                if l_word == 2:
                    new[i] = value(letter)
                elif theta == 0.0 or letter not in "XY":
                    # L20: the current position reads the given value in that system
                    new[i] = self.pos[i] - self.g92[i] - self.tlo[i] - value(letter)
            if l_word == 20 and theta != 0.0 and ("X" in axis_words or "Y" in axis_words):
                # in a rotated system X and Y go together: the position read there keeps the
                # axis not given, and the origin moves so that both read as wanted
                ix, iy = self.axis_index["X"], self.axis_index["Y"]
                px, py = self.prog_xy(self.pos, work=self.work_offsets[system], rotation=theta)
                px = value("X") if "X" in axis_words else px
                py = value("Y") if "Y" in axis_words else py
                u, v = px + self.g92[ix], py + self.g92[iy]
                c, s = math.cos(math.radians(theta)), math.sin(math.radians(theta))
                new[ix] = self.pos[ix] - self.tlo[ix] - (c * u - s * v)
                new[iy] = self.pos[iy] - self.tlo[iy] - (s * u + c * v)
            for i, p_index in enumerate(self.axis_param):
                num[base + p_index] = new[i]
            self.work_offsets[system] = tuple(new)
            if system == self.work_code:
                self.rotation = theta
                self.set_offset(work=tuple(new))
            self.parameters_changed(line_no, f"G10 L{l_word:g}: {_gname(system)} offsets set")
        elif code in (281, 301):
            base = _P_G28 if code == 281 else _P_G30
            for i, p in enumerate(self.axis_param):
                num[base + p] = self.pos[i]
            self.parameters_changed(line_no, f"{_gname(code)}: position stored for {_gname(code - 1)}")
        elif code in (520, 920):
            g92 = list(self.g92)
            unrotated = self.prog_xy(self.pos, g92=(0.0,) * self.n) if self.rotation != 0.0 else None
            for letter in axis_words:
                i = self.axis_index[letter]
                if code == 520:         # G52: the offset itself
                    g92[i] = value(letter)
                elif unrotated is not None and letter in "XY":
                    g92[i] = unrotated["XY".index(letter)] - value(letter)
                else:                   # G92: the current position reads the given value
                    g92[i] = self.pos[i] - self.work[i] - self.tlo[i] - value(letter)
            self.set_g92(tuple(g92), True)
            self.parameters_changed(line_no, f"{_gname(code)}: axis offsets set")
        elif code == 921:               # G92.1: offsets and their parameters to zero
            self.set_g92((0.0,) * self.n, False)
            self.parameters_changed(line_no, "G92.1: axis offsets cleared")
        elif code == 922:               # G92.2: offsets off, parameters kept
            self.g92 = (0.0,) * self.n
            num[_P_G92_ON] = 0.0
            self.set_offset()
            self.parameters_changed(line_no, "G92.2: axis offsets suspended")
        else:                           # G92.3: back from the parameters
            self.g92 = tuple(num.get(_P_G92 + p, 0.0) for p in self.axis_param)
            num[_P_G92_ON] = 1.0
            self.set_offset()
            self.parameters_changed(line_no, "G92.3: axis offsets restored")

    def g10_tool(self, l_word: int, vals: dict[str, float], axis_words: list[str], scale: float,
                 line_no: int) -> None:
        """G10 L1 (tool data as given: offsets, R = radius), L10 (offsets so that the current
        position reads the given values with that tool), L11 (the same in G59.3, without G92),
        as LinuxCNC 2.9; later G43s use them, and the machine keeps them (TOOL_DATA events)."""
        p = vals.get("P")
        if p is None or p != int(p) or p < 1:
            raise _BlockError(f"G10 L{l_word} needs P with the tool number (1 or more)", "P")
        number = int(p)
        if self.tools is None:
            self.tools = ToolTable()
        tool = self.tools.get(number)
        if tool is None:
            raise _BlockError(f"G10 L{l_word} P{number}: tool T{number} is not in the tool table (add it "
                              "on the Tools page first)", "P")
        if l_word == 11:
            work, g92 = self.work_offsets[593], (0.0,) * self.n
            rotation = self.params.numbered.get(system_base(593) + 9, 0.0)
        else:
            work, g92 = self.work, self.g92
            rotation = self.rotation
        xy = l_word != 1 and ("X" in axis_words or "Y" in axis_words) and "X" in self.axis_index \
            and "Y" in self.axis_index
        for letter in axis_words:
            if xy and letter in "XY":
                continue
            i = self.axis_index[letter]
            given = vals[letter] if self.rotary[i] else vals[letter] * scale
            # L10/L11: the position in that system without any tool offset, minus the value
            value = given if l_word == 1 else self.pos[i] - work[i] - g92[i] - given
            tool = tool.with_offset(letter, value)
        if xy:
            # X and Y as LinuxCNC's convert_setup_tool: the position read in the (possibly
            # rotated) system without tool offset, minus the values, turned back to the machine's
            # frame; an axis not given keeps the old offset's component along it
            ix, iy = self.axis_index["X"], self.axis_index["Y"]
            c, s = math.cos(math.radians(rotation)), math.sin(math.radians(rotation))
            dx, dy = self.pos[ix] - work[ix], self.pos[iy] - work[iy]
            tx, ty = c * dx + s * dy - g92[ix], -s * dx + c * dy - g92[iy]
            ox, oy = tool.offset("X"), tool.offset("Y")
            old_u, old_v = c * ox + s * oy, -s * ox + c * oy          # the old offset, system frame
            u = tx - vals["X"] * scale if "X" in axis_words else old_u
            v = ty - vals["Y"] * scale if "Y" in axis_words else old_v
            tool = tool.with_offset("X", c * u - s * v).with_offset("Y", s * u + c * v)
        if "R" in vals:
            if vals["R"] < 0:
                raise _BlockError(f"G10 L{l_word} R{vals['R']:g}: the tool radius cannot be negative", "R")
            tool = replace(tool, diameter_mm=2.0 * vals["R"] * scale)
        try:
            self.tools = self.tools.with_tool(tool)
        except PlannerError as exc:
            raise _BlockError(str(exc).split(": ", 1)[-1], "P") from None
        self.tool_sets.append(tool)
        text = f"G10 L{l_word}: {tool.label()} offsets set"
        self.events.append(Event(EventKind.TOOL_DATA, line_no, len(self.out) - 1,
                                 float(len(self.tool_sets) - 1), text))

    def set_g92(self, g92: tuple[float, ...], on: bool) -> None:
        self.g92 = g92
        num = self.params.numbered
        for i, p in enumerate(self.axis_param):
            num[_P_G92 + p] = g92[i]
        num[_P_G92_ON] = 1.0 if on else 0.0
        self.set_offset()

    def parameters_changed(self, line_no: int, text: str) -> None:
        """An OFFSETS event: the machine takes the persistent parameters as they are now when
        the program passes this point (LinuxCNC keeps them in its var file)."""
        num = self.params.numbered
        self.parameter_sets.append({p: num.get(p, 0.0) for p in sorted(PERSISTENT_PARAMETERS)})
        self.events.append(Event(EventKind.OFFSETS, line_no, len(self.out) - 1,
                                 float(len(self.parameter_sets) - 1), text))

    def plane_axes(self) -> tuple:
        """(name, first, second, normal column, centre letters, forbidden letter, axis letters) of the
        current plane, cached per plane; raises if the machine lacks one of the plane's axes."""
        info = self.plane_cache.get(self.plane)
        if info is None:
            pname, fl, sl, nl, fc, sc, bad = _PLANES[self.plane]
            fa = self.axis_index.get(fl)
            sa = self.axis_index.get(sl)
            if fa is None or sa is None:
                raise _BlockError(
                    f"arc in plane {_PLANE_G[self.plane]} ({pname}) needs axes {fl} and {sl}; "
                    f"this machine has {' '.join(self.axes)}",
                    "G",
                )
            info = (pname, fa, sa, self.axis_index.get(nl, -1), fc, sc, bad, (fl, sl))
            self.plane_cache[self.plane] = info
        return info

    def arc_turns(self, vals: dict[str, float]) -> int:
        """The P word of an arc: whole turns, 1 without it."""
        if "P" not in vals:
            return 1
        p = vals["P"]
        if p != int(p) or p < 1:
            raise _BlockError(f"P (number of turns) must be a whole number >= 1, got P{p:g}", "P")
        if p > _MAX_TURNS:
            raise _BlockError(f"P{p:g}: more than {_MAX_TURNS} turns", "P")
        return int(p)

    def arc_center(self, x0: float, y0: float, x1: float, y1: float, vals: dict[str, float], cw: bool,
                   scale: float) -> tuple[float, float, float, float]:
        """Centre and (start, end) radius of the arc from (x0, y0) to (x1, y1) in the plane's
        machine coordinates, from R or the centre words, checked as LinuxCNC checks them."""
        pname, fa, sa, na, fc, sc, bad, letters = self.plane_axes()
        try:
            r_val = vals.get("R")
            if r_val is not None:
                if "I" in vals or "J" in vals or "K" in vals:
                    raise _BlockError("mixed radius (R) and centre (I/J/K) format for arc", "R")
                cx, cy = center_from_radius(x0, y0, x1, y1, r_val * scale, cw)
                r0 = r1 = math.hypot(x0 - cx, y0 - cy)
                return cx, cy, r0, r1
            if bad in vals:
                raise _BlockError(
                    f"{bad} word given for arc in the {pname} plane ({_PLANE_G[self.plane]})", bad
                )
            ci = vals.get(fc)
            cj = vals.get(sc)
            if ci is None and cj is None:
                raise _BlockError("arc needs R or a centre: R, I, J and K words all missing", "G")
            turned = self.rotation != 0.0 and self.plane != 170
            if self.arc_absolute:
                if ci is None or cj is None:
                    raise _BlockError(f"G90.1 (absolute arc centre) needs both {fc} and {sc}",
                                      fc if ci is None else sc)
                if turned:
                    cx, cy = self.frame_centre(fa, sa, ci * scale, cj * scale)
                elif self.rotation != 0.0:
                    cx, cy = self.machine_xy(ci * scale, cj * scale)
                else:
                    cx = ci * scale + self.offset[fa]
                    cy = cj * scale + self.offset[sa]
            else:
                di = ci * scale if ci is not None else 0.0
                dj = cj * scale if cj is not None else 0.0
                if self.rotation != 0.0 and not turned:   # the centre offset turns with the system
                    theta = math.radians(self.rotation)
                    di, dj = (di * math.cos(theta) - dj * math.sin(theta),
                              di * math.sin(theta) + dj * math.cos(theta))
                cx = x0 + di
                cy = y0 + dj
            r0, r1 = check_center_radii(x0, y0, x1, y1, cx, cy, self.inch, letters)
            if abs(r1 - r0) <= 1e-12 * r0:
                r1 = r0
            return cx, cy, r0, r1
        except ArcError as e:
            raise _BlockError(str(e), "R" if "R" in vals else "G") from None

    def frame_centre(self, fa: int, sa: int, first: float, second: float) -> tuple[float, float]:
        """An absolute arc centre (G90.1) of a G18/G19 arc in a rotated system, from program
        coordinates to the arc's frame (the machine's X and Y turned back by the rotation):
        there the plane's X or Y is the program's plus a constant, and Z the machine's."""
        ix, iy = self.axis_index["X"], self.axis_index["Y"]
        out = []
        for col, value in ((fa, first), (sa, second)):
            if col == ix:
                out.append(self.frame_xy(*self.machine_xy(value, 0.0))[0])
            elif col == iy:
                out.append(self.frame_xy(*self.machine_xy(0.0, value))[1])
            else:
                out.append(value + self.offset[col])
        return out[0], out[1]

    def frame_xy(self, x: float, y: float) -> tuple[float, float]:
        """Machine X and Y turned back by the XY rotation: the frame of a G18/G19 arc there."""
        theta = math.radians(self.rotation)
        c, s = math.cos(theta), math.sin(theta)
        return c * x + s * y, -s * x + c * y

    def arc(self, target: list[float], vals: dict[str, float], cw: bool, scale: float, line_no: int) -> None:
        pname, fa, sa, na, fc, sc, bad, letters = self.plane_axes()
        feed = self.feed_mm_s
        if feed <= 0.0:
            raise _BlockError(_ZERO_FEED, "G")
        turns = self.arc_turns(vals)
        if self.comp.arc_banned:
            raise _BlockError("the move just after turning cutter compensation off (G40) must be a "
                              "straight line, not an arc", "G")
        if self.comp.radius > 0.0:
            self.comp.arc(self, target, vals, cw, turns, scale, line_no)
            return
        pos = self.pos
        turn = 0.0
        frame_pos, frame_target = pos, target
        if self.rotation != 0.0 and self.plane != 170:
            # a G18/G19 arc in a rotated system: its plane holds Z and a turned X or Y, so it is
            # made in the frame turned with the system, where that plane is an axis plane
            turn = math.radians(self.rotation)
            ix, iy = self.axis_index["X"], self.axis_index["Y"]
            frame_pos, frame_target = list(pos), list(target)
            frame_pos[ix], frame_pos[iy] = self.frame_xy(pos[ix], pos[iy])
            frame_target[ix], frame_target[iy] = self.frame_xy(target[ix], target[iy])
        x0 = frame_pos[fa]
        y0 = frame_pos[sa]
        x1 = frame_target[fa]
        y1 = frame_target[sa]
        if "R" in vals and ("I" in vals or "J" in vals or "K" in vals):
            raise _BlockError("mixed radius (R) and centre (I/J/K) format for arc", "R")
        if ("R" in vals and (x0 != x1 or y0 != y1) and vals["R"] > 0.0
                and self.path_length(pos, target) <= _ZERO_LEN):
            return  # a short R arc between points within 1e-9 mm: a zero-length move
        cx, cy, r0, r1 = self.arc_center(x0, y0, x1, y1, vals, cw, scale)
        try:
            a0, sweep = sweep_angle(x0, y0, x1, y1, cx, cy, cw, turns)
        except ArcError as e:
            raise _BlockError(str(e), "R" if "R" in vals else "G") from None
        rise = frame_target[na] - frame_pos[na] if na >= 0 else 0.0
        arc = _make_arc(pname, fa, sa, na, (cx, cy), r0, r1, a0, sweep, rise, turns, turn)
        length = math.hypot(r0 * sweep, rise) if r0 == r1 else spiral_length_mm(r0, r1, sweep, rise)
        self.emit(target, _ARC, feed, length, arc, line_no)

    # ------------------------------------------------------------------ G05, G05.1, G05.2/G05.3
    def spline(self, motion: int, previous_motion: int | None, vals: dict[str, float], axis_words: list[str],
               line_no: int) -> None:
        """G05 (cubic: I J the first control point from the start, P Q the second from the end),
        G05.1 (quadratic: I J the middle control point) and G05.2 (one NURBS control point, weight
        P, order L) as LinuxCNC 2.9 reads them; the curve is run as LinuxCNC runs it
        (``planner.splines``). Control points in program units and coordinates."""
        name = _gname(motion)
        if self.comp.radius > 0.0:
            # LinuxCNC refuses G05/G05.1 so and runs a G05.2 NURBS uncompensated
            raise _BlockError(f"cannot run a curve ({name}) with cutter radius compensation on: program G40 "
                              "first", name)
        if self.feed_mode == 930:
            raise _BlockError(f"{name} in inverse time feed mode (G93): program G94 or G95 for curves", name)
        if self.plane != 170:
            raise _BlockError(f"{name}: curves only in the XY plane (G17)", name)
        for letter in axis_words:
            if letter not in "XY":
                raise _BlockError(f"{name}: a curve moves in X and Y only, not {letter}", letter)
        if self.feed_mm_s <= 0.0:
            raise _BlockError(_ZERO_FEED, name)
        px, py = self.prog_xy(self.pos)
        x0, y0 = px / self.scale, py / self.scale

        def end(letter: str, here: float) -> float:
            if letter not in vals:
                return here
            return vals[letter] if self.absolute else here + vals[letter]

        if motion == 52:
            self.nurbs_point(previous_motion, vals, x0, y0, end, line_no)
            return
        x3, y3 = end("X", x0), end("Y", y0)
        if motion == 51:
            if "I" not in vals or "J" not in vals:
                raise _BlockError("G05.1 needs both I and J (the middle control point, from the start)",
                                  "I" if "I" in vals else "J" if "J" in vals else "G5.1")
            points = [(x0, y0, 1.0), (x0 + vals["I"], y0 + vals["J"], 1.0), (x3, y3, 1.0)]
            self.nurbs_feed(points, 3, line_no)
            return
        if ("I" in vals) != ("J" in vals):
            raise _BlockError("G05 needs both I and J, or neither (then the first control point mirrors the "
                              "last G05's P and Q)", "I" if "I" in vals else "J")
        i, j = (vals["I"], vals["J"]) if "I" in vals else self.spline_ij
        if "P" not in vals or "Q" not in vals:
            raise _BlockError("G05 needs both P and Q (the second control point, from the end point)",
                              "P" if "P" in vals else "Q" if "Q" in vals else "G5")
        p, q = vals["P"], vals["Q"]
        points = [(x0, y0, 1.0), (x0 + i, y0 + j, 1.0), (x3 + p, y3 + q, 1.0), (x3, y3, 1.0)]
        self.nurbs_feed(points, 4, line_no)
        self.spline_ij = (-p, -q)

    def nurbs_point(self, previous_motion: int | None, vals: dict[str, float], x0: float, y0: float,
                    end: Callable[[str, float], float], line_no: int) -> None:
        """A G05.2 block: the first one opens the NURBS at the current point (weight P when the
        block has no X and Y, else 1); X and Y add a control point of weight P. In G91 every
        point counts from where the curve begins: the tool does not move until G05.3."""
        has_x, has_y = "X" in vals, "Y" in vals
        if has_x != has_y:
            raise _BlockError("G05.2 needs both X and Y for a control point", "Y" if has_x else "X")
        weight = vals.get("P")
        if self.nurbs is None or previous_motion != 52:
            self.nurbs = [(x0, y0, weight if weight is not None and weight > 0.0 and not has_x else 1.0)]
            self.nurbs_order = 3
            self.nurbs_line = line_no
        elif not has_x and weight is not None:
            raise _BlockError("a weight P without X and Y only on the block that begins the NURBS", "P")
        if "L" in vals:
            order = vals["L"]
            if order != int(order):
                raise _BlockError(f"L (the NURBS order) must be a whole number, got L{order:g}", "L")
            if order > 3:                       # LinuxCNC: L3 or less leaves the order at 3
                self.nurbs_order = int(order)
        if has_x:
            if weight is None or weight <= 0.0:
                # LinuxCNC takes a missing P on the first control point as weight -1
                raise _BlockError("every NURBS control point needs a positive weight P",
                                  "P" if weight is not None else "X")
            self.nurbs.append((end("X", x0), end("Y", y0), weight))
        self.motion = 52

    def nurbs_end(self, g1: int | None, previous_motion: int | None, line_no: int) -> None:
        """G05.3: run the NURBS of the G05.2 blocks before it."""
        if g1 not in (None, 52):
            raise _BlockError(f"{_gname(g1)} beside G05.3: between G05.2 and G05.3 only G05.2 blocks",
                              _gname(g1))
        if self.nurbs is None or previous_motion != 52:
            raise _BlockError("G05.3 without G05.2 before it: there is no NURBS to end", "G5.3")
        points, order = self.nurbs, self.nurbs_order
        if len(points) < order:
            raise _BlockError(f"a NURBS of order L = {order} needs at least {order} control points, the "
                              f"start included; it has {len(points)}", "G5.3")
        if self.comp.radius > 0.0:
            raise _BlockError("cannot run a NURBS with cutter radius compensation on: program G40 first",
                              "G5.3")
        if self.feed_mm_s <= 0.0:
            raise _BlockError(_ZERO_FEED, "G5.3")
        self.nurbs = None
        self.motion = None if g1 is None else 52   # LinuxCNC: no motion mode after G05.3
        self.nurbs_feed(points, order, line_no)

    def nurbs_feed(self, points: list[tuple[float, float, float]], order: int, line_no: int) -> None:
        """The arcs and lines LinuxCNC's motion layer makes of the curve, in machine coordinates."""
        pname, fa, sa, na, *_ = self.plane_axes()
        scale = self.scale
        feed = self.feed_mm_s
        first = len(self.out)
        pieces = nurbs_pieces(np.array(points, dtype=float), order)
        last_x, last_y = points[-1][0], points[-1][1]
        for k, piece in enumerate(pieces):
            ex, ey = piece.end
            if k == len(pieces) - 1 and math.hypot(ex - last_x, ey - last_y) <= 1e-9 * max(1.0, abs(last_x),
                                                                                             abs(last_y)):
                ex, ey = last_x, last_y            # the curve ends on its last control point
            target = list(self.pos)
            target[fa], target[sa] = self.machine_xy(ex * scale, ey * scale)
            length = self.path_length(self.pos, target)
            if length <= _ZERO_LEN:
                continue
            if piece.center is None:
                self.emit(target, _LINE, feed, length, None, line_no)
                continue
            cx, cy = self.machine_xy(piece.center[0] * scale, piece.center[1] * scale)
            x0, y0 = self.pos[fa], self.pos[sa]
            r0 = math.hypot(x0 - cx, y0 - cy)
            if r0 > _CURVE_MAX_RADIUS_MM:
                # where the curve hardly bends, LinuxCNC's biarc is an arc of kilometres: the
                # line it nearly is
                self.emit(target, _LINE, feed, length, None, line_no)
                continue
            r1 = math.hypot(target[fa] - cx, target[sa] - cy)
            if abs(r1 - r0) <= 1e-9 * r0:
                r1 = r0
            a0, sweep = sweep_angle(x0, y0, target[fa], target[sa], cx, cy, not piece.ccw, 1)
            arc = _make_arc(pname, fa, sa, na, (cx, cy), r0, r1, a0, sweep, 0.0, 1)
            length = r0 * abs(sweep) if r0 == r1 else spiral_length_mm(r0, r1, sweep, 0.0)
            self.emit(target, _ARC, feed, length, arc, line_no)
        in_mm = tuple((x * scale, y * scale, w) for x, y, w in points)
        self.splines.append(Curve(first, len(self.out), in_mm, order))


def parse_program(
    text: str | None,
    name: str = "<string>",
    machine=None,
    start_position=None,
    *,
    block_delete: bool = False,
    max_errors: int = MAX_ERRORS,
    tools: ToolTable | None = None,
    tool_in_spindle: int = 0,
    spindle: tuple[int, float] = (0, 0.0),
    subroutine_dirs: Sequence[str] = (),
    parameters: dict[int, float] | None = None,
    progress: Callable[[int, int], None] | None = None,
    utf8: bytes | None = None,
    probe_results: Sequence[ProbeResult | None] = (),
    input_results: Sequence[float | None] = (),
) -> Program:
    """Interpret a whole program; raises ProgramError listing every error (up to max_errors).

    ``machine``: a planner.machine.MachineSpec (axes, work offsets); default 3-axis XYZ.
    ``start_position``: machine position before the first move (default all zeros).
    ``block_delete``: the operator's block delete switch: lines starting with '/' are skipped
    (on) or run (off, as LinuxCNC starts and as rs274 reads).
    ``tools``: the tool table (None: any tool number, all offsets 0, as LinuxCNC's reference
    runs); ``tool_in_spindle``: the tool loaded when the program starts (G43 without H uses it);
    ``spindle``: (direction, rpm) when it starts (an S word alone then changes a running spindle).
    ``subroutine_dirs``: folders where ``o<name> call`` finds ``<name>.ngc`` when the program
    does not define the subroutine itself.
    ``parameters``: the persistent parameters the machine kept (``PERSISTENT_PARAMETERS``: G92,
    G28/G30 positions, coordinate systems); the machine's work offsets take precedence for G54-G59.
    ``progress(done, total)`` is called now and then while a long program is read (lines read
    of all the lines, or characters of the text in bulk: ``done / total`` is what is read).
    ``utf8``: the text's own UTF-8 bytes when at hand: the bulk reader scans
    them instead of encoding the text again; with ``text`` None they are the program
    (``read_program_bytes``), read without its text where it is plain lines.
    ``probe_results``: what the machine's probe did on the program's G38.x moves, in order
    (``Program.probes``; None for one not run, as before a run from a later line); the others
    are read as run to their end point without a contact (#5070 = 0). ``input_results``: the
    values M66 read, the same way (-1: the wait timed out); the others are read as the awaited
    value.
    """
    interp = _Interpreter(name, machine, start_position, block_delete, max_errors, tools, tool_in_spindle,
                          spindle, subroutine_dirs, parameters, probe_results, input_results)
    with gc_paused():  # tens of thousands of small acyclic objects (planner/gcpause.py)
        interp.progress = progress
        try:
            return interp.run(text, utf8)
        finally:
            # the interpreter is cyclic garbage once it returns: it must not keep the caller's
            # callback (and what that holds) until a collection finds it
            interp.progress = None


def read_program_bytes(path: str | os.PathLike[str]) -> tuple[str | None, bytes | None]:
    """A G-code file as ``parse_program(None, ..., utf8=)`` reads it: (None, its bytes) when
    they are UTF-8, else (its Latin-1 text, None). Raises PlannerError naming the file and
    why."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as exc:
        raise PlannerError(f"{path}: cannot read: {exc.strerror or exc}") from None
    if data.isascii() or _is_utf8(data):
        return None, data
    return data.decode("latin-1"), None


def _is_utf8(data: bytes) -> bool:
    """Whether ``data`` decodes as UTF-8, a piece (cut after a newline) at a time."""
    view = memoryview(data)
    lo = 0
    try:
        while lo < len(data):
            hi = data.find(b"\n", min(lo + _DECODE_PIECE, len(data)))
            hi = len(data) if hi < 0 else hi + 1
            str(view[lo:hi], "utf-8")
            lo = hi
    except UnicodeDecodeError:
        return False
    return True


def read_program(path: str | os.PathLike[str]) -> str:
    """A G-code file's text (UTF-8 without a byte-order mark, falling back to Latin-1) with
    Windows line ends made "\n", read and decoded a piece at a time: the file's bytes are
    never held whole beside the text (250 MB each at 10,000,000 lines), nor the text twice to
    change its line ends or drop the mark (the reader did that to a whole text), and no one
    decode holds the GIL long. Raises PlannerError naming the file and why."""
    try:
        with open(path, "rb") as f:
            try:
                # "utf-8-sig": a byte-order mark (Windows editors put one before the first
                # line) is no part of the text, and the text is not copied to drop it
                return _decoded(f, codecs.getincrementaldecoder("utf-8-sig")())
            except UnicodeDecodeError:
                f.seek(0)
                return _decoded(f, codecs.getincrementaldecoder("latin-1")())
    except OSError as exc:
        raise PlannerError(f"{path}: cannot read: {exc.strerror or exc}") from None


def _decoded(f: Any, decoder: codecs.IncrementalDecoder) -> str:
    """The rest of file ``f`` through ``decoder``, "\r\n" made "\n", a piece at a time."""
    pieces = []
    carry = ""           # a piece's last "\r": its "\n" may start the next piece
    while True:
        block = f.read(_DECODE_PIECE)
        piece = carry + decoder.decode(block, final=not block)
        carry = "\r" if block and piece.endswith("\r") else ""
        if carry:
            piece = piece[:-1]
        # the search for two characters takes 3 ms a 4 MB piece, the one for "\r" alone 0.05 ms:
        # most programs have no Windows line end, and the GUI thread waits out each hold
        pieces.append(piece.replace("\r\n", "\n") if "\r" in piece else piece)
        if not block:
            break
    text = "".join(pieces)
    del pieces
    return text


# bytes decoded at a time: a piece's decoding (3 ms for 4 MB) holds the GIL, which the GUI
# thread waits for at each of its calls into Qt while a file is read
_DECODE_PIECE = 1 << 20


def _contains(text: Any, needle: Any, piece: int = 1 << 22) -> bool:
    """``needle in text``, a piece at a time: one search through a 250 MB program held the GIL,
    and with it the panel's GUI thread, for 0.18 s. A piece is first looked through for the
    needle's first character alone (a ``memchr``, ten times faster than the search for two):
    "\r\n" in a program of "\n" line ends took 3 ms a 4 MB piece, and the GUI thread, painting
    meanwhile, waited that long for the GIL at each of its hundreds of calls into Qt (a
    quarter of a second as a 10,000,000-line program was checked again)."""
    first, n, k = needle[:1], len(text), len(needle)
    for lo in range(0, n, piece):
        hi = min(n, lo + piece)
        at = text.find(first, lo, hi)
        if at >= 0 and text.find(needle, at, min(n, hi + k - 1)) >= 0:
            return True
    return False


def _count_lines(text: Any, piece: int = 1 << 22) -> int:
    """The lines of ``text`` (str or bytes; none when empty), counted a piece at a time: one
    count through a 250 MB program held the GIL, and the panel's GUI thread, for 60 ms."""
    newline = b"\n" if isinstance(text, bytes) else "\n"
    count = sum(text.count(newline, lo, lo + piece) for lo in range(0, len(text), piece))
    return count + 1 if text else 0


def _decode_utf8(data: bytes) -> str:
    """``data`` as ``read_program`` reads a UTF-8 file: without a byte-order mark, Windows
    line ends made "\n", decoded a piece at a time (one decode of a 250 MB program held the
    GIL, and with it the panel's GUI thread, for 0.12 s; changing the line ends of the whole
    text, 0.6 s and a second text)."""
    return _decoded(io.BytesIO(data), codecs.getincrementaldecoder("utf-8-sig")())


def parse_file(path: str | os.PathLike[str], machine=None, **kwargs) -> Program:
    """Read and interpret a G-code file (UTF-8, from its bytes alone; falling back to Latin-1)."""
    text, utf8 = read_program_bytes(path)
    return parse_program(text, str(path), machine, utf8=utf8, **kwargs)
