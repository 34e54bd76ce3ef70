"""O-words: subroutines (in the program, in ``<name>.ngc`` files), if/elseif/else, while, do,
repeat, break, continue, return values, Fanuc M98/M99 subprograms, run as LinuxCNC 2.9 runs
them: a program counter over the lines and a call stack of ``Frame``s.
"""

from __future__ import annotations

import os

from planner.core.errors import BlockError, SourceError
from planner.gcode.lexer import LexError, evaluate_brackets, read_line
from planner.gcode.modes import ModeCodes
from planner.gcode.oword import Statement, Structure, StructureError, scan
from planner.gcode.source import statement_col, through_closing_percent
from planner.gcode.state import (
    VALUE_LIMIT,
    Frame,
)

MAX_EXECUTED = 10_000_000   # blocks run by one program with O-word loops
#: blocks run in a row that make nothing (no move, no event): a loop that only counts or
#: tests is taken for an endless one after about 2 s of reading, not the 40 s of MAX_EXECUTED
MAX_IDLE = 1 << 19
_IDLE_CHECK = 1 << 15        # blocks between two looks at what was made
MAX_CALL_DEPTH = 50
#: a count or a number an expression gives (repeats, M98 P and L, O[...] call) is held to the
#: bound every word of a block has: a whole number a run can hold
MAX_COUNT = VALUE_LIMIT
RETURN = -2                  # ``statement``: the subroutine returns


class FlowCodes(ModeCodes):
    """The O-word flow over the lines; each line is read by the driver's ``line``."""

    def run_structured(self, lines: list[str]) -> None:
        """Run a program with O-word subroutines and control flow (``planner.gcode.oword``): a
        program counter over the lines, a call stack of frames (the file's lines and structure,
        where to return, the caller's #1-#30 and local named parameters). A subroutine not in
        the file is read from ``<name>.ngc`` in the subroutine folders. Moves made in another
        file carry the line of the call in the program, so the panel shows where it is."""
        lines = lines[:through_closing_percent(lines)]   # LinuxCNC ignores what follows it
        try:
            main = scan(lines)
        except StructureError as e:
            self.error(e.index + 1, e.col, e.message)
            return
        frame = Frame(self.name, lines, main, return_pc=-1, call_line=0)
        frames: list[Frame] = []
        pc = 0
        executed = 0
        made, idle_since = -1, 0      # what had been made at the last look, and since which block
        while 0 <= pc < len(frame.lines):
            self.calls.frame, self.calls.pc = frame, pc    # where a G7x cycle looks for its profile
            executed += 1
            if executed > MAX_EXECUTED:
                self.error(frame.line_of(pc), 1, f"more than {MAX_EXECUTED:,} blocks run (an endless loop?)")
                return
            if executed % _IDLE_CHECK == 0:
                now = len(self.rec.out) + len(self.rec.events)
                if now != made:
                    made, idle_since = now, executed
                elif executed - idle_since >= MAX_IDLE:
                    self.error(frame.line_of(pc), 1, f"{executed - idle_since:,} blocks run without a move "
                               "(an endless loop?)")
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
                if self.calls.tool_changed:      # the machine's routine after the tool change
                    self.calls.tool_changed = False
                    try:
                        callee = self.call_after_tool_change(frame, frames, pc, line_no)
                    except BlockError as e:
                        self.error_in(frame, line_no, e.col or 1, e.message)
                        return
                    except LexError as e:
                        self.error_in(frame, line_no, 1, e.message)
                        return
                    frames.append(frame)
                    frame = callee
                    pc = frame.entry
                    self.calls.level += 1
                continue
            try:
                result = self.statement(stmt, frame, frames)
            except BlockError as e:
                self.error_in(frame, line_no, e.col or 1, e.message)
                return
            except LexError as e:
                col = e.raw_col if e.raw_col is not None else statement_col(raw, e.index)
                self.error_in(frame, line_no, col, e.message)
                return
            except RecursionError:
                self.error_in(frame, line_no, 1, "expression nested too deeply")
                return
            if isinstance(result, Frame):    # a call: run the subroutine
                frames.append(frame)
                frame = result
                pc = frame.entry
                self.calls.level += 1
            elif result == RETURN:
                if not frames:
                    return
                pc = frame.return_pc
                if not frame.fanuc:
                    self.restore(frame)
                saved = self.calls.saved_modal.pop(self.calls.level, None)
                self.calls.level -= 1
                if saved is not None and saved[1]:          # M73: back as it was at the call
                    self.restore_modal(saved[0], frame.return_pc)
                frame = frames.pop()
            else:
                pc = result

    def statement(self, st: Statement, frame: Frame, frames: list[Frame]) -> int | Frame:
        """Run one control statement; returns the next line index, a frame to call, or RETURN."""
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
                raise BlockError(f"o{st.label} repeat needs one count in brackets", col=1)
            if not abs(values[0]) < MAX_COUNT:         # nan and inf too
                raise BlockError(f"o{st.label} repeat [{values[0]:g}]: the count is out of range "
                                 f"(|count| < 1e9)", col=1)
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
            return RETURN
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
                return RETURN
            if frames:
                raise BlockError("M99 inside an O-word subroutine: it ends with its endsub or return", "M99")
            # the main program: LinuxCNC ends it here, as M02 does
            return -1 if self.line("M2", i + 1) else i + 1
        raise BlockError(f"o{st.label} {kw.lower()} is not supported", col=1)

    def oword_place(self, st: Statement, frame: Frame) -> None:
        """LinuxCNC 2.9 keeps one place per O-word name (a label qualified by the subroutine
        it is written in) for if, repeat, while and do, taken as each is first run: another
        statement run under a name already held is refused, except the while closing a do.
        Labels reused in branches not run, or in different subroutines, are accepted, as there."""
        place = (frame.file, st.index)
        held = self.calls.oword_places.get(st.qname)
        if held is None:
            self.calls.oword_places[st.qname] = (*place, st.keyword)
        elif held[:2] != place and st.keyword != "DO" and not (st.keyword == "WHILE" and held[2] == "DO"):
            where = f"line {held[1] + 1}" + ("" if held[0] == frame.file else f" of {held[0]}")
            raise BlockError(f"duplicate O-word label: o{st.label} {st.keyword.lower()} uses the label of "
                             f"the {held[2].lower()} at {where}", col=1)

    def define_sub(self, st: Statement, frame: Frame) -> None:
        """The program runs through a sub's definition: it is defined from here on. Met again
        (inside a loop, or after a call found it ahead), LinuxCNC 2.9 refuses it as "found in
        illegal location"; another definition of the label met, as "redefining sub"."""
        key = (frame.file, st.label)
        held = self.calls.sub_places.get(key)
        if held is None:
            self.calls.sub_places[key] = st.index
        elif held == st.index:
            raise BlockError(f"o{st.label} sub met a second time: a sub is defined once, as the program "
                             "runs through it or a call finds it ahead (not inside a loop, nor after "
                             "a call to it)", col=1)
        else:
            raise BlockError(f"o{st.label} sub is defined twice: already at line {held + 1}", col=1)

    def find_sub(self, label: str, call: Statement, frame: Frame) -> tuple[int, int] | None:
        """The sub a call in this file runs: the one defined (run through, or found by an earlier
        call), else the first ahead of the call, which is then defined (LinuxCNC seeks it to the
        end of the file); None when there is neither."""
        definitions = frame.structure.subs.get(label, [])
        held = self.calls.sub_places.get((frame.file, label))
        if held is not None:
            return next(d for d in definitions if d[0] == held)
        ahead = next((d for d in definitions if d[0] > call.index), None)
        if ahead is not None:
            self.calls.sub_places[(frame.file, label)] = ahead[0]
        return ahead

    def condition(self, st: Statement, frame: Frame) -> bool:
        values = evaluate_brackets(st.rest, self.params, 0)
        if len(values) != 1:
            word = "while" if st.keyword == "DOWHILE" else st.keyword.lower()
            raise BlockError(f"o{st.label} {word} needs one condition "
                             "in brackets", col=1)
        return values[0] != 0.0

    def call(self, st: Statement, frame: Frame, frames: list[Frame]) -> Frame:
        if len(frames) >= MAX_CALL_DEPTH:
            raise BlockError(f"subroutine calls nested deeper than {MAX_CALL_DEPTH} (endless recursion?)",
                             col=1)
        args = evaluate_brackets(st.rest, self.params, 0)
        if len(args) > 30:
            raise BlockError(f"o{st.label} call with {len(args)} arguments (at most 30: #1-#30)", col=1)
        label = st.label
        if label.startswith(("[", "#")):     # O[expression] call, O#<name> call: its number
            (value,) = evaluate_brackets(label if label.startswith("[") else f"[{label}]", self.params, 0)
            if not abs(value) < MAX_COUNT or value != round(value) or value < 0:
                raise BlockError(f"o{label} call: the subroutine number {value:g} is not a whole number "
                                 f"from 0 to 1e9", col=1)
            label = str(int(round(value)))
        target = self.find_sub(label, st, frame)
        file, lines, structure = frame.file, frame.lines, frame.structure
        behind = structure.subs.get(label)
        if target is None and label.startswith("<"):
            file, lines, structure = self.subroutine_file(label[1:-1])
            found = structure.subs.get(label)
            if not found:
                raise BlockError(f"{file} does not define o{label} sub", col=1)
            target = found[0]
        if target is None and behind:
            raise BlockError(f"o{label} call: the o{label} sub at line {behind[0][0] + 1} is not defined "
                             "here: the program did not run through it (a sub inside an if is defined "
                             "only when that branch runs) and no other is ahead of the call", col=1)
        if target is None:
            raise BlockError(f"o{label} call: no o{label} sub in this program", col=1)
        callee = Frame(file, lines, structure, return_pc=st.index + 1,
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

    def call_after_tool_change(self, frame: Frame, frames: list[Frame], return_pc: int,
                               line_no: int) -> Frame:
        """The machine's call after an M6 that changed the tool (``Setup.after_tool_change``, as
        LinuxCNC's REMAP of M6 runs an ngc): a call statement run as if it stood after the line,
        its moves carrying the M6's line."""
        text = self.setup.after_tool_change
        try:
            structure = scan([text])
        except StructureError as e:
            raise BlockError(f"the routine after a tool change ({text}): {e.message}", col=1) from None
        st = structure.statements.get(0)
        if st is None or st.keyword != "CALL":
            raise BlockError(f"the routine after a tool change ({text}) is not an O-word call", col=1)
        callee = self.call(st, frame, frames)
        callee.return_pc = return_pc
        callee.call_line = frame.call_line or line_no
        return callee

    def call_program(self, st: Statement, frame: Frame, frames: list[Frame]) -> Frame | None:
        """M98 P<n> L<count>: run the Fanuc-style subprogram O<n> of this file count times (no
        arguments; it works on the caller's parameters), back after its M99; L0 runs it not
        at all (None), as in LinuxCNC."""
        if len(frames) >= MAX_CALL_DEPTH:
            raise BlockError(f"subprogram calls nested deeper than {MAX_CALL_DEPTH} (endless recursion?)",
                             "M98")
        words, _ = read_line(st.rest, self.params)
        vals = {letter: float(v) for letter, v in words}
        unknown = sorted(set(vals) - {"P", "L"})
        if unknown:
            raise BlockError(f"M98 takes only P and L words, not {' '.join(unknown)}", unknown[0])
        if "P" not in vals:
            raise BlockError("M98 needs a P word (the number of the O subprogram to run)", "M98")
        p, loops = vals["P"], vals.get("L", 1.0)
        if not abs(p) < MAX_COUNT or p != int(p) or p < 0:      # nan and inf first: int() takes neither
            raise BlockError(f"M98 P{p:g}: a subprogram number is a whole number from 0 to 1e9",
                             "P")
        if not abs(loops) < MAX_COUNT or loops != int(loops) or loops < 0:
            raise BlockError(f"M98 L{loops:g}: the runs of a subprogram are a whole number from 0 to "
                             f"1e9",
                             "L")
        target = frame.structure.programs.get(str(int(p)))
        if target is None:
            raise BlockError(f"M98 P{int(p)}: no O{int(p)} in this program", "P")
        if loops == 0:
            return None
        callee = Frame(frame.file, frame.lines, frame.structure, return_pc=st.index + 1,
                       call_line=frame.call_line or st.index + 1)
        callee.entry = target + 1
        callee.fanuc = True
        callee.loops = int(loops)
        return callee

    def restore(self, frame: Frame) -> None:
        for k in range(1, 31):
            self.params.numbered.pop(k, None)
        self.params.numbered.update(frame.saved_numbered)
        self.params.named = frame.saved_named

    def subroutine_file(self, name: str) -> tuple[str, list[str], Structure]:
        """``<name>.ngc`` from the subroutine folders, read and scanned once."""
        cached = self.calls.sub_files.get(name)
        if cached is not None:
            return cached
        for folder in self.setup.subroutine_dirs:
            path = os.path.join(folder, f"{name}.ngc")
            if os.path.isfile(path):
                try:
                    with open(path, "rb") as fh:
                        data = fh.read()
                except OSError as exc:
                    raise BlockError(f"cannot read subroutine file {path}: {exc.strerror}", col=1) from None
                try:
                    text = data.decode("utf-8")
                except UnicodeDecodeError:
                    text = data.decode("latin-1")
                lines = text.replace("\r\n", "\n").split("\n")
                try:
                    structure = scan(lines)
                except StructureError as e:
                    raise BlockError(f"{path}:{e.index + 1}:{e.col}: {e.message}", col=1) from None
                self.calls.sub_files[name] = (path, lines, structure)
                return self.calls.sub_files[name]
        where = (", ".join(self.setup.subroutine_dirs) if self.setup.subroutine_dirs
                 else "no subroutine folder is configured")
        raise BlockError(f"o<{name}> call: no o<{name}> sub in this program and no {name}.ngc in the "
                         f"subroutine folders ({where})", col=1)

    def line_in_file(self, raw: str, line_no: int, frame: Frame) -> bool:
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

    def error_in(self, frame: Frame, line: int, col: int, message: str) -> None:
        name = self.name
        self.name = frame.file
        try:
            self.error(line, col, message)
        finally:
            self.name = name
