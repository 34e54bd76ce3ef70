"""LinuxCNC's own interpreter as an oracle: ``rs274`` (Debian's linuxcnc-uspace, installed by
`make test` as root) reads a program and prints its canonical calls; this module runs it and
turns the calls into comparable motion records (millimetres). The tests use it on generated
programs (``run_linuxcnc``), ``tools.against_linuxcnc`` on folders of real ones
(``run_linuxcnc_file``)."""

from __future__ import annotations

import fcntl
import functools
import math
import re
import shutil
import subprocess
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass, replace
from pathlib import Path

from planner.core.program import Program
from planner.core.tools import ToolTable, format_tbl
from planner.gcode.canon import canon_records

RS274 = shutil.which("rs274")
RS274_TIMEOUT_S = 60
# "12 N..... STRAIGHT_FEED(...)": the counter, the block's N number (dots without one), the call;
# rs274 pads the number to five places, so a longer one runs into the call ("N100100STRAIGHT_FEED")
_CALL = re.compile(r"^\s*\d+\s+N(?:\.+|\d+)\s*([A-Z_][A-Z_0-9]*)\((.*)\)\s*$")


@dataclass(frozen=True)
class OracleResult:
    # ("straight_traverse" | "straight_feed" | "straight_probe", (x, y, z)) or arcs
    motion: list[tuple]
    error: str                   # LinuxCNC's error text, "" when the program ran to its end
    error_block: str             # the block LinuxCNC printed after the error
    every: tuple[tuple, ...] = ()  # the motion calls, moves to where the tool is included
    # where each call of ``motion`` ends in machine coordinates (X, Y, Z: the offsets, the XY
    # rotation and the tool's length applied, as LinuxCNC's canon applies them)
    machine: tuple[tuple[float, ...], ...] = ()


_EXPECTED_CALL = re.compile(r"^\s*(?:N\.+\s+)?([A-Z_]+)\((.*)\)\s*$")


def canon_calls(text: str, stop_at: str | None = None) -> Iterator[tuple[str, list[str], float]]:
    """(call, its arguments, mm per program unit) for each canonical call of LinuxCNC's output
    (an ``expected`` file of its interpreter tests), up to a line holding ``stop_at``."""
    scale = 1.0
    for line in text.splitlines():
        if stop_at is not None and stop_at in line:
            return
        m = _EXPECTED_CALL.match(line)
        if not m:
            continue
        name, args = m.group(1), [a.strip() for a in m.group(2).split(",")] if m.group(2) else []
        if name == "USE_LENGTH_UNITS":
            scale = 25.4 if "INCHES" in args[0] else 1.0
        yield name, args, scale


def _tbl_for_rs274(tools: ToolTable) -> str:
    """The stand-alone rs274 reads its tool table in inches: millimetre tools are written so."""
    return format_tbl(ToolTable({t.number: replace(t, diameter_mm=t.diameter_mm / 25.4,
                                                   offsets_mm=tuple((a, v / 25.4) for a, v in t.offsets_mm))
                                 for t in tools}))


def _rs274(program: Path, tools: ToolTable | None, tmp: str, subroutine_dirs: tuple[str, ...] = (),
           cwd: str | None = None) -> str:
    """rs274's output for ``program`` (``tmp``: a folder for its tool table and INI file)."""
    assert RS274 is not None
    args = [RS274, "-g"]
    if tools is not None:
        (Path(tmp) / "t.tbl").write_text(_tbl_for_rs274(tools))
        args += ["-t", str(Path(tmp) / "t.tbl")]
    if subroutine_dirs:
        (Path(tmp) / "x.ini").write_text("[RS274NGC]\nSUBROUTINE_PATH = " + ":".join(subroutine_dirs) + "\n")
        args += ["-i", str(Path(tmp) / "x.ini")]
    # errors go to stderr: one stream keeps them where they happened. Two rs274 at once
    # (two test processes) sometimes print nothing at all (measured: 1 run in 10 with three
    # in parallel, none alone), so runs are serialised across processes by a lock file.
    with open(Path(tempfile.gettempdir()) / "cnc-panel-rs274.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            return subprocess.run(args + [str(program)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                  text=True, errors="replace", timeout=RS274_TIMEOUT_S, cwd=cwd or tmp,
                                  stdin=subprocess.DEVNULL).stdout
        except subprocess.TimeoutExpired:          # an endless loop: LinuxCNC never ends it either
            return f"rs274 did not finish within {RS274_TIMEOUT_S} s (an endless loop?)\n"


def refused_alike(text: str, machine=None) -> tuple[str, str]:
    """The block rs274 refuses ``text`` at and the line this interpreter refuses it at, both as
    written (equal when they refuse the same block; raises when either reads it)."""
    from planner.core.errors import ProgramError
    from planner.gcode.interpreter import parse_program

    theirs = run_linuxcnc(text)
    assert theirs.error, f"rs274 reads it:\n{text}"
    try:
        parse_program(text, machine=machine)
    except ProgramError as exc:
        return theirs.error_block, text.splitlines()[exc.errors[0].line - 1]
    raise AssertionError(f"this interpreter reads it:\n{text}")


def motion_alike(text: str, abs_mm: float = 0.003) -> None:
    """Raises unless rs274 and this interpreter read ``text`` to the same motion calls, their
    end points within ``abs_mm`` (rs274 prints 4 decimals). Moves shorter than what it prints
    are left out on this side too, as ``read_output`` leaves rs274's out."""
    from planner.gcode.interpreter import parse_program
    from tools.against_linuxcnc import call_ends, without_short_moves

    theirs = run_linuxcnc(text)
    assert not theirs.error, f"rs274 refuses it: {theirs.error}\n{text}"
    program = parse_program(text)
    ours = without_short_moves(project_motion(program), call_ends(program))
    assert [c for c, _ in ours] == [c for c, _ in theirs.motion], text
    for (call, a), (_, b) in zip(ours, theirs.motion, strict=True):
        assert max(abs(x - y) for x, y in zip(a, b, strict=True)) <= abs_mm, (call, a, b, text)


def run_linuxcnc(text: str, tools: ToolTable | None = None) -> OracleResult:
    with tempfile.TemporaryDirectory() as tmp:
        prog = Path(tmp) / "p.ngc"
        prog.write_text(text)
        out = _rs274(prog, tools, tmp)
    assert out.strip() not in ("", "executing"), f"rs274 printed nothing for:\n{text}"
    return read_output(out)


# rs274 prints what (PRINT,...), (DEBUG,...) and (LOG,...) say as lines of their own, which
# would read as its error: a program is given to it without them (they move nothing)
_MESSAGE_COMMENT = re.compile(r"(?i)\((print|debug|log|logopen|logappend|logclose),")


def run_linuxcnc_file(path: Path, tools: ToolTable | None = None,
                      subroutine_dirs: tuple[str, ...] = ()) -> OracleResult:
    """rs274 on a program file where it lies (its folder and ``subroutine_dirs`` searched for
    subroutine files)."""
    text = path.read_text(errors="replace")
    with tempfile.TemporaryDirectory() as tmp:
        program = path
        if _MESSAGE_COMMENT.search(text):
            program = Path(tmp) / path.name
            program.write_text(_MESSAGE_COMMENT.sub("(", text))
        dirs = (str(path.parent.resolve()), *subroutine_dirs)
        out = _rs274(program.resolve(), tools, tmp, dirs, cwd=str(path.parent.resolve()))
    return read_output(out)


def read_output(out: str) -> OracleResult:
    """Motion and the first error of rs274's output."""
    motion: list[tuple] = []
    machine: list[tuple] = []    # each motion call's end in machine coordinates (zero moves)
    scale = 1.0
    g5x: tuple[float, ...] = (0.0, 0.0, 0.0)
    g92: tuple[float, ...] = (0.0, 0.0, 0.0)
    tool: tuple[float, ...] = (0.0, 0.0, 0.0)
    rotation = 0.0
    plane = "XY"
    error = block = ""

    def to_machine(p: tuple) -> tuple:
        """LinuxCNC's canon: G92 added, turned by the XY rotation, then G5x and tool offsets."""
        x, y, z = (p[i] + g92[i] for i in range(3))
        c, s_ = math.cos(math.radians(rotation)), math.sin(math.radians(rotation))
        x, y = c * x - s_ * y, s_ * x + c * y
        return (x + g5x[0] + tool[0], y + g5x[1] + tool[1], z + g5x[2] + tool[2])

    lines = out.splitlines()
    for k, line in enumerate(lines):
        m = _CALL.match(line)
        if not m:
            if line.startswith("Oops ("):
                continue     # G7x's offsetting prints where it drops a segment, and goes on
            if line.strip() and line.strip() != "executing" and not error:
                error = line.strip()
                # the block follows; a message ending in a newline of its own leaves a blank
                # line between them
                block = next((after.strip() for after in lines[k + 1:k + 3]
                              if after.strip() and not _CALL.match(after)), "")
            continue
        if error:
            continue
        name, args_t = m.group(1), [a.strip() for a in m.group(2).split(",")] if m.group(2) else []
        if name == "USE_LENGTH_UNITS":
            scale = 25.4 if "INCHES" in args_t[0] else 1.0
        elif name == "SET_G5X_OFFSET":
            g5x = tuple(float(v) * scale for v in args_t[1:4])
        elif name == "SET_G92_OFFSET":
            g92 = tuple(float(v) * scale for v in args_t[0:3])
        elif name == "SELECT_PLANE":
            plane = args_t[0].rsplit("_", 1)[-1]
        elif name == "SET_XY_ROTATION":
            rotation = float(args_t[0])
        elif name == "USE_TOOL_LENGTH_OFFSET":
            tool = tuple(float(v) * scale for v in args_t[0].split()[:3])
        elif name in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "STRAIGHT_PROBE"):
            end = tuple(float(v) * scale for v in args_t[:3])
            motion.append((name.lower(), end))
            machine.append(to_machine(end))
        elif name == "RIGID_TAP":
            # in and back out to where it started: the tool stays where it was
            end = tuple(float(v) * scale for v in args_t[:3])
            motion.append(("rigid_tap", end))
            machine.append(machine[-1] if machine else (0.0, 0.0, 0.0))
        elif name == "NURBS_FEED":
            # G05, G05.1, G05.2: rs274 prints the number of the curve's control points only
            # ("NURBS_FEED(4, ...)"), not the points nor where the curve ends (so the move after
            # it is kept even when it goes where the tool already is)
            motion.append(("nurbs_feed", (float(args_t[0]),)))
            machine.append((math.nan, math.nan, math.nan))
        elif name == "ARC_FEED":
            v = [float(a) for a in args_t[:6]]
            motion.append(("arc_feed", (v[0] * scale, v[1] * scale, v[2] * scale, v[3] * scale, v[4],
                                        v[5] * scale)))
            first, second, normal = v[0] * scale, v[1] * scale, v[5] * scale
            xyz = {"XY": (first, second, normal), "YZ": (normal, first, second),
                   "XZ": (second, normal, first)}[plane]
            machine.append(to_machine(xyz))
    kept = _without_zero_moves(motion, machine)
    return OracleResult([motion[k] for k in kept], error, block, tuple(motion),
                        tuple(machine[k] for k in kept))


def _without_zero_moves(motion: list[tuple], machine: list[tuple]) -> list[int]:
    """LinuxCNC writes moves to where the tool already is; a Program has none. Compared in
    machine coordinates (an offset change moves the program's point, not the tool), within
    what LinuxCNC prints (four decimals of an inch in G20); the generated programs move on a
    0.1 mm grid, so no real move is this short. The places of the calls kept."""
    out = []
    last = (0.0, 0.0, 0.0)                      # both start at the origin
    for k, (call, here) in enumerate(zip(motion, machine)):
        if call[0] not in ("arc_feed", "rigid_tap") and max(abs(a - b) for a, b in zip(here, last)) < 0.003:
            continue
        out.append(k)
        last = here
    return out


def motion_calls(program: Program) -> list[tuple[tuple, tuple[float, ...]]]:
    """The program's motion calls as ``read_output`` gives rs274's, each with where it ends
    (machine coordinates): a G33.1 is one call (RIGID_TAP) for its two moves, in and back out,
    and a curve (G05, G05.1, G05.2) one ("nurbs_feed", (control points,)) for all of its moves
    (none when it moves nowhere), as rs274 prints them."""
    out: list[tuple[tuple, tuple[float, ...]]] = []
    curves = sorted(program.splines, key=lambda curve: curve.first)
    c = 0
    back_out = {i + 1 for i in program.taps}
    moves = [i for i in range(len(program.moves)) if i not in back_out]
    last = tuple(float(v) for v in program.start_position)
    skip_to = -1
    for i, rec in zip(moves, canon_records(program), strict=True):
        while c < len(curves) and curves[c].first == i == curves[c].end:       # a curve of no moves
            out.append((("nurbs_feed", (float(len(curves[c].points)),)), last))
            c += 1
        end = tuple(float(v) for v in program.moves[i].end)
        if i < skip_to:
            last = end
            continue
        a = rec["args"]
        if c < len(curves) and curves[c].first == i:
            skip_to = curves[c].end
            out.append((("nurbs_feed", (float(len(curves[c].points)),)),
                        tuple(float(v) for v in program.moves[skip_to - 1].end)))
            c += 1
        elif rec["call"] == "arc_feed":
            out.append((("arc_feed", (a[0], a[1], a[2], a[3], float(a[4]), a[5])), end))
        else:
            out.append(((rec["call"], tuple(a[:3])), end))
        last = end
    out.extend((("nurbs_feed", (float(len(curve.points)),)), last) for curve in curves[c:])
    return out


def project_motion(program: Program) -> list[tuple]:
    """The program's motion calls as ``read_output`` gives rs274's (``motion_calls``)."""
    return [call for call, _ in motion_calls(program)]


# LinuxCNC's preview (AXIS's ``gcode`` module, in the same Debian package) draws a curve
# (G05, G05.1, G05.2) as straight lines through points of it: 15 a control point, evaluated by
# the interpreter's own NURBS code. Those points are LinuxCNC's curve, which rs274 does not
# print; the module runs under the system Python it was built for.
SYSTEM_PYTHON = "/usr/bin/python3"
_PREVIEW_SCRIPT = r'''
import gcode, json, os, sys, tempfile
class Canon:
    def __init__(self, var):
        self.parameter_file = var
        self.out = []
    def __getattr__(self, name):
        return lambda *args: None
    def get_external_angular_units(self): return 1.0
    def get_external_length_units(self): return 1.0 / 25.4
    def get_axis_mask(self): return 7
    def get_block_delete(self): return False
    def check_abort(self): return False
    def get_tool(self, pocket): return (-1,) + (0.0,) * 12 + (0,)
    def straight_traverse(self, *a): self.out.append(("straight_traverse", a[:3]))
    def straight_feed(self, *a): self.out.append(("straight_feed", a[:3]))
    def arc_feed(self, *a): self.out.append(("arc_feed", a[:6]))
tmp = tempfile.mkdtemp()
var = os.path.join(tmp, "p.var")
open(var, "w").close()
ini = os.path.join(tmp, "p.ini")
open(ini, "w").write("[RS274NGC]\nPARAMETER_FILE = " + var + "\n")
os.environ["INI_FILE_NAME"] = ini
canon = Canon(var)
gcode.parse(sys.argv[1], canon, "G21", "")   # a millimetre machine, as rs274 runs
print(json.dumps(canon.out))
'''


@functools.cache
def preview_available() -> bool:
    """Whether LinuxCNC's preview module can be run (``make test`` installs it as root); asked
    once a process."""
    if not Path(SYSTEM_PYTHON).exists():
        return False
    found = subprocess.run([SYSTEM_PYTHON, "-c", "import gcode"], capture_output=True,
                           stdin=subprocess.DEVNULL)
    return found.returncode == 0


def run_linuxcnc_preview(text: str) -> list[tuple[str, tuple[float, ...]]]:
    """The moves LinuxCNC's preview draws for ``text``, in millimetres: ("straight_feed" or
    "straight_traverse", (x, y, z)) and ("arc_feed", (first end, second end, first centre,
    second centre, turns, normal end)). It works in inches whatever the program's units. A
    program it refuses raises RuntimeError."""
    import json

    with tempfile.TemporaryDirectory() as tmp:
        prog = Path(tmp) / "p.ngc"
        prog.write_text(text)
        done = subprocess.run([SYSTEM_PYTHON, "-c", _PREVIEW_SCRIPT, str(prog)], capture_output=True,
                              text=True, timeout=RS274_TIMEOUT_S, cwd=tmp, stdin=subprocess.DEVNULL)
    if done.returncode != 0:
        raise RuntimeError(f"LinuxCNC's preview refused the program: {done.stderr.strip()[-300:]}")
    out = []
    for call, args in json.loads(done.stdout.splitlines()[-1]):
        if call == "arc_feed":
            out.append((call, tuple(v * 25.4 if k != 4 else v for k, v in enumerate(args))))
        else:
            out.append((call, tuple(v * 25.4 for v in args)))
    return out
