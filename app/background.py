"""Work off the GUI thread whose result comes back to it, newest request only.

Checking G-code as the operator types, planning a program's speed profile for the
diagnostics page and checking a loaded program all take from milliseconds to seconds and must
never hold the GUI thread. Each is one ``Background``: ``submit`` runs the work in a daemon
thread; when it finishes, the result is delivered in the thread that owns the ``Background``
(a queued signal), and only if no newer work was submitted (or ``cancel`` called) meanwhile,
so fast typing or a quick second load never shows a stale result. Exceptions of the work are
delivered as the result: a bug in the interpreter or planner is reported, never kills the
panel. A result arriving after the owner was deleted (window closed) is dropped.
"""

from __future__ import annotations

import threading
from collections.abc import Callable

from PySide6.QtCore import QObject, Signal

__all__ = ["Background"]


class Background(QObject):
    _finished = Signal(int, object)   # (generation, result or the exception raised)

    def __init__(self, name: str, deliver: Callable[[object], None], parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.name = name
        self._deliver = deliver
        self._generation = 0
        self._running = 0                 # generation of the newest work not yet delivered
        self._finished.connect(self._on_finished)

    @property
    def busy(self) -> bool:
        """Work submitted and neither delivered nor cancelled."""
        return self._running == self._generation and self._running > 0

    def submit(self, work: Callable[[], object]) -> int:
        """Run ``work()`` in a new thread; its result (or exception) goes to ``deliver`` unless
        superseded. Returns the generation of this submission."""
        self._generation += 1
        generation = self._running = self._generation

        def run() -> None:
            try:
                result: object = work()
            except Exception as exc:  # noqa: BLE001 - delivered to the owner, who reports it
                result = exc
            try:
                self._finished.emit(generation, result)
            except RuntimeError:          # the owner was deleted meanwhile
                pass

        threading.Thread(target=run, name=f"{self.name}-{generation}", daemon=True).start()
        return generation

    def cancel(self) -> None:
        """Drop the result of whatever is running."""
        self._generation += 1

    def _on_finished(self, generation: int, result: object) -> None:
        if generation != self._generation:
            return
        self._running = 0
        self._deliver(result)
