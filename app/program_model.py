"""The loaded program as the pages see it: text, geometry (planner Program), tool path, errors.

Fed by the controller's ``programLoaded`` / ``programErrors`` signals. The geometry is the
controller's own (``ProgramInfo.program``); only if it is missing is the text interpreted here.
"""

from __future__ import annotations

from collections.abc import Iterable

from PySide6.QtCore import QObject, Signal

from app.format import with_column
from app.machine.model import ProgramIssue
from app.program_lines import line_text
from app.toolpath import ToolPath, build_toolpath
from planner.core.errors import PlannerError, ProgramError
from planner.core.machine import MachineSpec
from planner.core.program import Program


def interpret(text: str, name: str, machine: MachineSpec | None) -> Program:
    """``text`` read as the editor shows it: the one load (``planner.pipeline.load``) without the
    machine's state, refusals, blending or travel (those are the controller's check's)."""
    from planner.pipeline import load

    return load(text, name, machine or MachineSpec.default(), lambda p: p, blend=False, check_travel=False,
                require_motion=False).program


def errors_by_line(exc: PlannerError) -> dict[int, str]:
    """{line: message} from a ProgramError (the first message per line, its column in front)
    or any planner error."""
    out: dict[int, str] = {}
    if isinstance(exc, ProgramError):
        for e in exc.errors:
            out.setdefault(e.line, with_column(e.col, e.message))
    else:
        out[getattr(exc, "line", 1) or 1] = str(exc)
    return out


#: A program shown of at least this many moves is let go when the controller lets it go for a
#: check again of itself: its moves, tool path and preview copies are about 50 MB a million
#: moves of a CAM raster, and kept on screen while its successor was read the panel held two
#: programs. Smaller ones stay on screen through their check again, which comes within seconds.
LET_GO_MOVES = 1_000_000


class ProgramModel(QObject):
    """Emits ``changed`` when a program is loaded (geometry + tool path) or rejected."""

    changed = Signal()
    errorsChanged = Signal(object)  # dict[int, str]: line -> message
    lineRequested = Signal(int)  # a page asks to show this source line in the program editor

    def __init__(self, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.name = ""
        self.path = ""
        self.text = ""
        self.info: object | None = None   # controller's ProgramInfo
        self.program: Program | None = None
        self.toolpath: ToolPath | None = None
        self.errors: dict[int, str] = {}
        self._pending: tuple[str, str] = ("", "")
        self._expected = False

    def move_at_line(self, line: int) -> int:
        """Index of the first move at or after ``line`` (len(moves) past the end, -1 if none)."""
        if self.toolpath is None:
            return -1
        import numpy as np

        lines = self.toolpath.move_lines
        # the line as the column's own type: a Python int made NumPy copy 10,000,000 lines to
        # 64 bits on every call (18 ms, 90 ms with the panel busy)
        return int(np.searchsorted(lines, lines.dtype.type(line), side="left"))

    def line(self, number: int) -> str:
        """The text of line ``number`` (1-based; "" beyond the program), through the loaded
        program's line index when there is one: a program of millions of lines is not split
        into millions of strings for one line."""
        text = self.text
        if number < 1:
            return ""
        starts = getattr(self.info, "line_starts", None)
        if starts is not None and getattr(self.info, "text", None) is text:
            return line_text(text, starts, number - 1) if number < len(starts) else ""
        lo = 0
        for _ in range(number - 1):
            lo = text.find("\n", lo) + 1
            if lo == 0:
                return ""
        hi = text.find("\n", lo)
        line = text[lo:] if hi < 0 else text[lo:hi]
        return line[:-1] if line.endswith("\r") else line

    def expect(self, text: str, name: str) -> None:
        """The panel is about to load this text: shown with its errors if the controller refuses it."""
        self._pending = (text, name)
        self._expected = True       # a program the panel asked for: not a check again

    def set_loaded(self, info: object, machine: MachineSpec | None) -> None:
        self._expected = False
        self.info = info
        self.name = str(getattr(info, "name", ""))
        self.path = str(getattr(info, "path", ""))
        self.text = str(getattr(info, "text", ""))
        try:
            program = getattr(info, "program", None)  # the controller's checked geometry
            if not isinstance(program, Program):
                program = interpret(self.text, self.name or "<program>", machine)
            self.program = program
            made = getattr(info, "toolpath", None)  # made with the check, off the GUI thread
            self.toolpath = made if isinstance(made, ToolPath) else build_toolpath(program)
            self.errors = {}
        except PlannerError as exc:  # the controller accepted it: should not happen
            self.program, self.toolpath = None, None
            self.errors = errors_by_line(exc)
        self.errorsChanged.emit(self.errors)
        self.changed.emit()

    def let_go(self, successor: str) -> bool:
        """The controller has let the loaded program go (a load or a check again started). When
        another program comes (the panel asked for one, ``expect``, or ``successor``, the name of
        the program being checked, is another's), all of it goes: nothing of the old one is shown
        as if it were the new one (its name, text, path, line). A check again of the same program
        keeps it on screen, but for a big one's geometry. ``changed`` tells the pages. True when
        something went."""
        another = self._expected or successor != self.name
        big = self.toolpath is not None and self.toolpath.move_count >= LET_GO_MOVES
        if not another and not big:
            return False
        self.info, self.program, self.toolpath = None, None, None
        if another:
            self.text, self.name, self.path = "", successor, ""
            self.errors = {}
            self.errorsChanged.emit(self.errors)
        self.changed.emit()
        return True

    def set_read_again(self, program: object) -> None:
        """The running program read again with what a probe or M66 read: its path from there
        on is the one the machine takes (the loaded text and its checked plan stay)."""
        if not isinstance(program, Program) or self.info is None:
            return
        self.program = program
        self.toolpath = build_toolpath(program)
        self.changed.emit()

    def set_errors(self, issues: Iterable[ProgramIssue] | None, text: str = "", name: str = "") -> None:
        """The controller refused a program: keep its text and the errors per line."""
        self._expected = False
        self.info, self.program, self.toolpath = None, None, None
        if not text:
            text, name = self._pending
        if text:
            self.text = text
        if name:
            self.name = name
        errors: dict[int, str] = {}
        for issue in issues or ():
            errors.setdefault(int(issue.line or 1), issue.message)
        self.errors = errors
        self.errorsChanged.emit(self.errors)
        self.changed.emit()
