"""Spread heavy GUI-thread reactions over several event-loop turns.

When a large program is loaded, the pages each take ~0.1 s in the GUI thread (editor text,
tool path, plots). Run back to back in one signal emission they would freeze the touchscreen
for their sum; ``run_soon`` queues them and runs one per event-loop turn instead, so input,
painting and timers get through between them. A newer call with the same key replaces a
queued one (a newer program supersedes an older one not yet shown).
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable

from PySide6.QtCore import QTimer

BIG_PROGRAM_LINES = 5000  # below this the pages react at once (a few ms)
LOAD_PROGRESS_MS = 250  # how often the pages show how far a program's check is

_queue: OrderedDict[str, Callable[[], None]] = OrderedDict()
_armed = False


def run_soon(key: str, fn: Callable[[], None]) -> None:
    """Run ``fn`` in a later event-loop turn, one queued function per turn, in order."""
    global _armed
    _queue.pop(key, None)
    _queue[key] = fn
    if not _armed:
        _armed = True
        QTimer.singleShot(0, _run_one)


def _run_one() -> None:
    global _armed
    _armed = False
    if not _queue:
        return
    _key, fn = _queue.popitem(last=False)
    if _queue:
        _armed = True
        QTimer.singleShot(0, _run_one)
    try:
        fn()
    except RuntimeError as exc:  # its widget was deleted meanwhile (window closed)
        if "already deleted" not in str(exc):
            raise


def pending() -> bool:
    """True while reactions are still queued (tests, benchmarks)."""
    return bool(_queue)


def is_big(info: object) -> bool:
    return int(getattr(info, "line_count", 0) or 0) >= BIG_PROGRAM_LINES


def cancel(key: str) -> None:
    """Drop a queued reaction (e.g. the program it would show was refused meanwhile)."""
    _queue.pop(key, None)
