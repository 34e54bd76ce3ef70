"""Check G-code as the operator types: interpret in a background thread, report errors per line.

Only the newest request's result is delivered (a generation counter), so typing fast never
queues up stale checks. The GUI thread never waits for the interpreter.
"""

from __future__ import annotations

import threading

from PySide6.QtCore import QObject, QTimer, Signal

from app.program_model import errors_by_line, interpret
from planner.errors import PlannerError
from planner.machine import MachineSpec


class ProgramChecker(QObject):
    checked = Signal(object)   # dict[int, str]: line -> message (empty: the program is fine)
    _done = Signal(int, object)

    def __init__(self, machine: MachineSpec | None, delay_ms: int = 400,
                 parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.machine = machine
        self._generation = 0
        self._text = ""
        self._timer = QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(delay_ms)
        self._timer.timeout.connect(self._start)
        self._done.connect(self._deliver)
        self.busy = False

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
        self._generation += 1
        self.busy = False

    def _start(self) -> None:
        self._generation += 1
        generation, text, machine = self._generation, self._text, self.machine
        self.busy = True

        def work() -> None:
            try:
                interpret(text, "<editor>", machine)
                errors: dict[int, str] = {}
            except PlannerError as exc:
                errors = errors_by_line(exc)
            except Exception as exc:  # noqa: BLE001 - an interpreter bug must not kill the panel
                errors = {1: f"internal error while checking: {exc!r}"}
            try:
                self._done.emit(generation, errors)
            except RuntimeError:  # the checker was deleted meanwhile (window closed)
                pass

        threading.Thread(target=work, name="gcode-check", daemon=True).start()

    def _deliver(self, generation: int, errors: object) -> None:
        if generation == self._generation:
            self.busy = False
            self.checked.emit(errors)
