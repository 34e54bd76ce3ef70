"""G-code interpreter: RS274/NGC text -> Program of exact moves, read the way LinuxCNC 2.9 does.

Supported (everything else is an error with file:line:col, never skipped):
  motion G00 G01 G02 G03 (R or I/J/K, P turns) in G17 G18 G19, G04 P (s), G20 G21, G90 G91,
  G90.1 G91.1, G53 (one block, with G00/G01), G61 G61.1 G64 (P/Q accepted);
  curves G05 (cubic), G05.1 (quadratic), G05.2/G05.3 (NURBS) in G17, run as LinuxCNC runs them
  (``planner.geometry.splines``);
  feed modes G93 (inverse time) G94 G95 (per revolution), G97;
  canned cycles G73 G74 G81-G86 G89, G98/G99, G80 (also beside another motion code);
  G33.1 rigid tapping (run as feed moves), G33 and the G76 threading cycle (read; recorded in
  ``Program.synchronised``, which a machine without a spindle encoder refuses to run);
  the lathe cycles G70, G71/G71.1/G71.2, G72/G72.1/G72.2 on a profile subroutine (``planner.gcode.g7x``);
  tool data G10 L1/L10/L11 (TOOL_DATA events);
  coordinate systems G54-G59.3, G10 L2 (with R: XY rotation)/L20, G92 G92.1 G92.2 G92.3, G52,
  G28/G28.1, G30/G30.1
  with LinuxCNC's parameters (``PERSISTENT_PARAMETERS``, OFFSETS events);
  cutter radius compensation G40, G41/G42 (tool table), G41.1/G42.1 (``planner.gcode.cutter_comp``);
  G43 / G43 H / G43.1 / G43.2 / G49 tool length offsets from the tool table (``planner.core.tools``);
  polar coordinates @ (distance) ^ (angle) in G17; F S T;
  M00 M01 M02 M30 M03 M04 M05 M06 M61 M07 M08 M09; M62-M65 and user M100-M199 as the machine
  configuration defines them ([[outputs]], [[mcodes]]);
  O-words (``planner.gcode.oword``: subroutines, subroutine files, if, while, do, repeat, break,
  continue, return values), expressions, #numbered / #<named> / #<_global> parameters,
  (MSG,) (DEBUG,) (PRINT,) messages, M70-M73 modal state save/restore;
  N line numbers, '/' block delete, ( ) and ; comments, % delimiters, Fanuc 'O0001' lines.
Set-up as LinuxCNC's reference run: G21 G17 G40 G49 G54 G80 G90 G94 G91.1 G64 G99, motion mode
none (axis words need a G00-G03 first).

The interpreter is split as LinuxCNC's rs274ngc is: the state (``state``), the codes by name
(``codes``), reading and checking a block (``reader``), executing it in RS274 order
(``execute``), one module per family of codes (``motion``, ``offsets``, ``tools``, ``cycles``,
``lathe``, ``curves``, ``modes``, ``flow``), the fast paths for plain CAM lines (``fast``), the
program's text (``source``); ``Interpreter`` here reads a program line by line through them.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Sequence
from typing import Any

from planner.core.errors import BlockError, ProgramError
from planner.core.gcpause import gc_paused
from planner.core.program import ProbeResult, Program
from planner.core.tools import ToolTable
from planner.gcode.execute import Executor
from planner.gcode.fast import FastPaths
from planner.gcode.lexer import LexError, original_column, read_line
from planner.gcode.oword import has_control_flow
from planner.gcode.reader import read_block
from planner.gcode.source import (
    compact_or_none,
    contains,
    count_lines,
    decode_utf8,
    percent_line,
    read_program,
    read_program_bytes,
)
from planner.gcode.state import MAX_ERRORS, PERSISTENT_PARAMETERS, system_base

# an M6 word (not M60-M69): a program with one goes through the O-word flow when the machine
# calls a routine after a tool change
M6_TEXT = re.compile(r"[mM]\s*0*6(?![\s]*[0-9])")
M6_BYTES = re.compile(rb"[mM]\s*0*6(?![\s]*[0-9])")
__all__ = ["parse_program", "parse_file", "read_program", "read_program_bytes", "MAX_ERRORS",
           "PERSISTENT_PARAMETERS", "system_base", "Interpreter"]


class Interpreter(Executor, FastPaths):
    """One program read: ``run`` it once."""

    def __init__(self, name: str, machine: Any, start_position: Any, block_delete: bool, max_errors: int,
                 tools: ToolTable | None = None, tool_in_spindle: int = 0,
                 spindle: tuple[int, float] = (0, 0.0), subroutine_dirs: Sequence[str] = (),
                 parameters: dict[int, float] | None = None,
                 probe_results: Sequence[ProbeResult | None] = (),
                 input_results: Sequence[float | None] = (),
                 tool_offset: tuple[int, Sequence[float]] | None = None):
        super().__init__(name, machine, start_position, block_delete, max_errors, tools, tool_in_spindle,
                         spindle, subroutine_dirs, parameters, probe_results, input_results, tool_offset)
        self.rec.modal_changes.append((0, self.modal_text()))
        self.params.system = self.system_parameter
        self.params.system_numbered = self.position_parameter

    def run(self, text: str | None, utf8: bytes | None = None) -> Program:
        """Interpret ``text`` (``utf8``: the same text encoded, when the caller has it). With
        ``text`` None the program is ``utf8`` alone: a CAM program of plain lines is read from
        its bytes without its text beside them (250 MB at 10,000,000 lines); any other is
        decoded first."""
        if text is None:
            assert utf8 is not None
            if (not (self.use_bulk and self.use_fast) or utf8.startswith(b"\xef\xbb\xbf")
                    or contains(utf8, b"\r\n") or has_control_flow(utf8) or self._calls_after_m6(utf8)):
                # its text is read from now on: the bytes keep a mark and line ends it has not
                text, utf8 = decode_utf8(utf8), None
            else:
                self.started = False
                self.run_bulk(None, utf8)
                return self._finish(count_lines(utf8))
        if text.startswith("\ufeff"):
            # a byte-order mark, which Windows editors put before the first line: an encoding
            # marker, not G-code (LinuxCNC refuses it as a bad character), and no editor shows
            # it, so the columns of line 1 are counted without it
            text, utf8 = text[1:], None
        if contains(text, "\r\n"):
            text = text.replace("\r\n", "\n")  # Windows line ends, once for the whole text
            utf8 = None
        self.started = False  # saw content or an opening '%'
        if has_control_flow(text) or self._calls_after_m6(text):
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
        return self._finish(count_lines(text))

    def _calls_after_m6(self, text: str | bytes) -> bool:
        """Whether an M6 may call the machine's routine (``Setup.after_tool_change``): then the
        program runs through the O-word flow, which makes the call."""
        if not self.setup.after_tool_change:
            return False
        if isinstance(text, bytes):
            return M6_BYTES.search(text) is not None
        return M6_TEXT.search(text) is not None

    def _finish(self, line_count: int) -> Program:
        if self.curve.nurbs is not None and not self.ended:
            self.error(self.curve.line, 1, "the program ends with this NURBS (G05.2) not ended: program "
                       "G05.3 to run it")
        if self.errors:
            raise ProgramError(self.errors, self.truncated)
        return self.rec.build(self.name, self.setup, line_count)

    def line(self, raw: str, line_no: int) -> bool:
        """Read one line; True when the program ends here (closing '%', M2/M30, too many errors)."""
        # Fast path: one compiled-regex match of the usual CAM block. The regex admits only
        # N, G00-G03, axis and I J K R F words, so a comment, '%', '/', '[', '#', an O-word,
        # a tab or a CR never matches: such lines take the general path below.
        if self.use_fast:
            code = raw.replace(" ", "").upper()
            if not code:
                return False
            m = self.setup.fast_re.match(code)
            if m is not None:
                self.started = True
                try:
                    if self.fast_line(m.groups(), line_no):
                        return False
                except BlockError as e:
                    self.error(line_no, self.column(raw, e.letter), e.message)
                    return self.truncated
        if raw.endswith("\r"):
            raw = raw[:-1]
        s = raw.strip()
        if not s:
            return False
        if s[0] == "%":
            if not percent_line(s):
                self.error(line_no, raw.index("%") + 1, "'%' must be alone on its line")
                return False
            if self.started:
                return True  # closing '%': the rest of the file is not part of the program
            self.started = True
            return False
        if not self.started and compact_or_none(s) != "":
            self.started = True  # comment-only lines before an opening '%' do not count
        if s[0] == "/":
            if self.setup.block_delete:
                return False
            raw = raw.replace("/", " ", 1)
        try:
            self.block(raw, line_no)
        except BlockError as e:
            col = e.col if e.col is not None else self.column(raw, e.letter)
            self.error(line_no, col, e.message)
        except LexError as e:
            col = e.raw_col if e.raw_col is not None else original_column(raw, e.index)
            self.error(line_no, col, e.message)
        except RecursionError:
            self.error(line_no, 1, "expression nested too deeply")
        return self.ended or self.truncated

    def block(self, raw: str, line_no: int) -> None:
        """One line that is a block: its messages, its words read, the plain CAM line by the
        fast path, any other read and checked (``reader``) and executed (``execute``)."""
        self.current_line = line_no
        if "(" in raw:
            self.messages(raw, line_no)
        words, assigns = read_line(raw, self.params)
        if not words:
            self.assign(assigns)
            return
        if not assigns and self.use_fast and self.fast_block(words, line_no):
            return
        block = read_block(words, assigns, line_no, self.setup, self.motion)
        if block is not None:
            self.execute(block)


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
    tool_offset: tuple[int, Sequence[float]] | None = None,
) -> Program:
    """Interpret a whole program; raises ProgramError listing every error (up to max_errors).

    ``machine``: a planner.core.machine.MachineSpec (axes, work offsets); default 3-axis XYZ.
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
    value. ``tool_offset``: the tool length offset in force when the program starts, (G43,
    G43.1 or G49 as ``codes.G``, the offset per axis in machine units), as the machine keeps
    it from the program or MDI before (LinuxCNC does); None: G49.
    """
    interp = Interpreter(name, machine, start_position, block_delete, max_errors, tools, tool_in_spindle,
                         spindle, subroutine_dirs, parameters, probe_results, input_results, tool_offset)
    with gc_paused():  # tens of thousands of small acyclic objects (planner/core/gcpause.py)
        interp.progress = progress
        try:
            return interp.run(text, utf8)
        finally:
            # the interpreter is cyclic garbage once it returns: it must not keep the caller's
            # callback (and what that holds) until a collection finds it
            interp.progress = None


def parse_file(path: str | os.PathLike[str], machine=None, **kwargs) -> Program:
    """Read and interpret a G-code file (UTF-8, from its bytes alone; falling back to Latin-1)."""
    text, utf8 = read_program_bytes(path, machine.planner.max_program_bytes) if machine is not None \
        else read_program_bytes(path)
    return parse_program(text, str(path), machine, utf8=utf8, **kwargs)
