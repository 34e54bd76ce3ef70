"""The worker's own process: entry point, parent watch, and a spawn that does not re-run the
caller's main script."""

from __future__ import annotations

import contextlib
import gc
import os
import sys
import threading
import time
import types
from multiprocessing import shared_memory
from typing import Any

from .cycle import CycleLoop
from .realtime import PROCESS_SPIN_S, set_realtime
from .shared import SharedBlock, Status
from .types import WorkerConfig

__all__ = ["process_main", "start_without_main"]


def process_main(cfg: WorkerConfig, shm_name: str, layout: tuple[int, ...], parent_pid: int) -> None:
    """Run the loop in this (spawned) process until told to stop or orphaned.

    ``parent_pid`` is the process that started it, told by that process: one that died while
    this one was starting (a panel killed during its start-up) leaves it orphaned already, and
    the parent it would find for itself is then init or a subreaper, never seen to go."""
    shm = shared_memory.SharedMemory(name=shm_name)
    block = SharedBlock(shm.buf, *layout)
    loop = CycleLoop(cfg, block)
    lock_fd: int | None = None
    try:
        if os.getppid() != parent_pid:      # orphaned before the bus was opened: nothing to do
            block.write_msg(f"the process that started the worker ({parent_pid}) is gone")
            block.ctl.status[...] = Status.FAILED
            return
        try:
            applied, lock_fd = set_realtime(cfg)
            loop.open_bus()
        except Exception as exc:  # noqa: BLE001 - reported to the parent as text
            block.write_msg(f"{type(exc).__name__}: {exc}")
            block.ctl.status[...] = Status.FAILED
            return
        # first line: the real-time settings applied; then what the bus start-up adapted to
        block.write_msg("\n".join([applied, *(loop.bus.notes if loop.bus is not None else [])]))
        block.ctl.pid[...] = os.getpid()
        loop.publish()
        block.ctl.status[...] = Status.RUNNING
        gc.collect()
        gc.freeze()
        gc.disable()
        # helper threads (parent watch, acyclic calls) must not keep the GIL from the cycle
        # for the default 5 ms switch interval
        sys.setswitchinterval(0.0002)
        watcher = threading.Thread(target=_parent_watch, args=(loop, parent_pid), daemon=True)
        watcher.start()
        loop.run_realtime(default_spin_s=PROCESS_SPIN_S)
    finally:
        with contextlib.suppress(Exception):
            loop.close_bus()
        if int(block.ctl.status) != Status.FAILED:     # the parent reads why it failed
            block.ctl.status[...] = Status.STOPPED
        del block, loop
        shm.close()
        if lock_fd is not None:
            os.close(lock_fd)                # the core is free for the next worker


def _parent_watch(loop: CycleLoop, parent_pid: int) -> None:
    """Stop the loop when the parent process is gone (checked at once, then every 0.2 s)."""
    while not loop.stop_requested:
        if os.getppid() != parent_pid:
            loop.stop_requested = True
            break
        time.sleep(0.2)


def start_without_main(process: Any) -> None:
    """Start a spawn process without re-running the caller's ``__main__`` in the child.

    spawn normally re-imports the main script, which starts the worker again in scripts
    without an ``if __name__ == "__main__"`` guard. The child only needs this package, so the
    main module is hidden while the preparation data is taken.
    """
    main = sys.modules.get("__main__")
    sys.modules["__main__"] = types.ModuleType("__main__")
    try:
        process.start()
    finally:
        if main is not None:
            sys.modules["__main__"] = main
