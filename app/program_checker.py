"""Check G-code as the operator types: interpret in a background thread, report errors per line.

Only the newest request's result is delivered (``app.background``), so typing fast never
queues up stale checks. The GUI thread never waits for the interpreter.
"""

from __future__ import annotations

from PySide6.QtCore import QObject, QTimer, Signal

from app.background import Background
from app.program_model import errors_by_line, interpret
from planner.core.errors import PlannerError
from planner.core.machine import MachineSpec


class ProgramChecker(QObject):
    checked = Signal(object)   # dict[int, str]: line -> message (empty: the program is fine)

    def __init__(self, machine: MachineSpec | None, delay_ms: int = 400,
                 parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.machine = machine
        self._work = Background("gcode-check", self._deliver, self)
        self._text = ""
        self._timer = QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(delay_ms)
        self._timer.timeout.connect(self._start)

    @property
    def busy(self) -> bool:
        return self._work.busy

    def request(self, text: str) -> None:
        self._text = text
        self._timer.start()

    def check_now(self, text: str) -> None:
        self._text = text
        self._timer.stop()
        self._start()

    def cancel(self) -> None:
        """Forget pending and running checks (their results are dropped)."""
        self._timer.stop()
        self._work.cancel()

    def _start(self) -> None:
        text, machine = self._text, self.machine

        def work() -> dict[int, str]:
            try:
                interpret(text, "<editor>", machine)
            except PlannerError as exc:
                return errors_by_line(exc)
            return {}

        self._work.submit(work)

    def _deliver(self, result: object) -> None:
        if isinstance(result, Exception):  # an interpreter bug: shown, never kills the panel
            result = {1: f"internal error while checking: {result!r}"}
        self.checked.emit(result)
