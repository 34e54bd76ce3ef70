"""What happens at a pause point is the business of the part it belongs to: the probe's (G38.x),
the inputs' (M66), the outputs' (M62-M65), the tools' (M61, G10 L1), the coordinates' (G10, G92).
Each registers its handler here when it is built; the streamer asks at every pause point."""

from __future__ import annotations

from collections.abc import Callable

from app.machine.motion.jobs import Job
from app.machine.motion.timescale import PauseKind, PausePoint
from ethercat.worker import WorkerSnapshot

__all__ = ["PauseHandler", "PauseHandlers", "why_stopped"]

#: a pause point's handler: at rest there, True when the motion goes on at once
PauseHandler = Callable[[Job, PausePoint, WorkerSnapshot], bool]


class PauseHandlers:
    """The handlers by kind of pause point (one each)."""

    def __init__(self) -> None:
        self._handlers: dict[PauseKind, PauseHandler] = {}

    def on(self, kind: PauseKind, handler: PauseHandler) -> None:
        if kind in self._handlers:
            raise ValueError(f"pause points of kind {kind} are handled already")
        self._handlers[kind] = handler

    def get(self, kind: PauseKind) -> PauseHandler | None:
        return self._handlers.get(kind)


def why_stopped(kind: PauseKind, line: int, label: str, measured: bool) -> str:
    """What the operator is told at a stop that waits for cycle start (M00, M01, M06 of the
    tool ``label``, then ``measured`` on the setter, single block)."""
    reason = {
        PauseKind.PAUSE: f"program paused (M00, line {line}): press cycle start",
        PauseKind.OPTIONAL_PAUSE: f"optional stop (M01, line {line}): press cycle start",
        PauseKind.TOOL_CHANGE: f"tool change (M06, line {line}): insert tool {label} and press cycle start",
        PauseKind.SINGLE_BLOCK: f"single block: end of line {line}",
    }.get(kind, str(kind))
    if kind is PauseKind.TOOL_CHANGE and measured:
        reason += f"; {label} is then measured on the tool setter"
    return reason
