"""Pausing Python's cyclic garbage collector while a program's objects are built.

A parse and a load allocate tens of thousands of small acyclic objects; the cyclic collector
re-scans them again and again (about 20 % of a parse) and, in a worker thread, a full
collection holds the GIL for 20-75 ms: the panel's stall. Parses and loads may overlap in
several threads (the program page checks as you type while the controller loads), so the pause
is counted: the collector comes back, as it was before the first pause began, only when the
last one ends. Nothing here is per sample or per cycle.
"""

from __future__ import annotations

import gc
import threading
from collections.abc import Iterator
from contextlib import contextmanager

_lock = threading.Lock()
_pausers = 0
_was_enabled = True
_freeze = False


@contextmanager
def gc_paused(freeze: bool = False) -> Iterator[None]:
    """No cyclic collection inside the block. ``freeze``: when the last pause ends, collect the
    garbage made meanwhile and move the surviving objects to the permanent generation
    (``gc.freeze``) so that no later collection scans them (a loaded program, kept for the
    whole run)."""
    global _pausers, _was_enabled, _freeze
    with _lock:
        if _pausers == 0:
            _was_enabled = gc.isenabled()
            _freeze = False
        _pausers += 1
        _freeze = _freeze or freeze
        gc.disable()
    try:
        yield
    finally:
        with _lock:
            _pausers -= 1
            if _pausers == 0 and _was_enabled:
                if _freeze:
                    # the cycles that became garbage during the pause first (a parse's interpreter
                    # holds its progress callback, and that the load and its program): frozen,
                    # they were never collected, and every program loaded since was kept
                    # (10,000,000 lines: 600 MB more at each load). With the collector off they
                    # are all in the young generations: those are scanned, not the panel's
                    # hundreds of thousands of objects (a full collection held the GIL 0.1 s)
                    gc.collect(1)
                    gc.freeze()
                gc.enable()
