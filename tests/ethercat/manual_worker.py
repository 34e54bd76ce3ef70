"""A worker in mode "manual" (no clock: a test steps it) on the simulated bus, started and its
drives enabled, for the tests of what runs in the 1 ms loop."""

from __future__ import annotations

from ethercat.worker import CyclicWorker, WorkerConfig, WorkerState


def enabled_worker(cfg: WorkerConfig) -> CyclicWorker:
    """``cfg``'s worker started, stepped until its drives are enabled (ENABLED asserted)."""
    w = CyclicWorker(cfg)
    w.start()
    w.step(3)
    w.enable()
    w.step(20)
    assert w.state() is WorkerState.ENABLED
    return w
