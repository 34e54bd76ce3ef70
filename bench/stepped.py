"""The 1 ms loop stepped by hand in the caller's own process: for the benches that measure what
a feature adds to the cycle (the time is the cycle's own work and the simulated drives', not
the client's per-call overhead or a clock's sleeps), and for the tests of what runs in the
loop (``enabled``: a worker in mode "manual" started with its drives enabled)."""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np

from ethercat.worker import CyclicWorker, WorkerConfig, WorkerState

__all__ = ["cycle_us", "enabled"]


def enabled(cfg: WorkerConfig) -> CyclicWorker:
    """``cfg``'s worker (mode "manual") started with its drives enabled."""
    w = CyclicWorker(cfg)
    w.start()
    w.step(3)
    w.enable()
    w.step(20)
    assert w.state() is WorkerState.ENABLED
    return w


def cycle_us(w: CyclicWorker, cycles: int, path: np.ndarray | None = None,
             before: Callable[[], None] | None = None) -> float:
    """Microseconds a cycle over ``cycles`` cycles: following ``path`` (a set-point a cycle,
    pushed a thousand at a time) when given, with ``before`` called ahead of every cycle."""
    loop = w._loop
    assert loop is not None
    t0 = time.perf_counter()
    for start in range(0, cycles, 1000):
        n = min(1000, cycles - start)
        if path is not None:
            assert w.push(path[start:start + n]) == n
        for _ in range(n):
            if before is not None:
                before()
            loop.cycle()
    elapsed = time.perf_counter() - t0
    loop.publish()                      # the snapshot as the cycles left it
    return elapsed / cycles * 1e6
