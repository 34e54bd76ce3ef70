"""Cycle timing benchmark of the worker (used by `cnc-ethercat bench` and bench/bench_ethercat.py).

`run_bench("sim", "", 10.0)` starts a `CyclicWorker` on `n_drives` drives, enables them,
streams a slow sine motion through the set-point buffer for `seconds` and returns the
timing figures (period, start jitter percentiles, late cycles, missed cycles, working
counter errors) as a JSON-able dict.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from .bus import DriveSpec
from .worker import PROCESS_SPIN_S, CyclicWorker, WorkerConfig, WorkerState


def run_bench(bus_kind: str = "sim", ifname: str = "", seconds: float = 10.0, *, n_drives: int = 4,
              mode: str = "process", ts_s: float = 0.001, spin_s: float | None = None,
              rt_priority: int | None = None, cpu: int | None = -1, min_sleep_s: float | None = None,
              amplitude_units: float = 5.0, on_tick: Any = None) -> dict[str, Any]:
    """Run the worker for `seconds` with a moving set-point stream; return figures.

    bus_kind "sim" | "soem" (`ifname` = adapter for "soem"); mode "process" | "thread".
    spin_s, rt_priority, cpu, min_sleep_s: as `WorkerConfig` (None = its default).
    `on_tick()` (optional) is called about every 20 ms from the calling thread while the
    benchmark runs (used to add GUI-like load in the same thread).
    """
    drives = tuple(DriveSpec(i, f"A{i}", counts_per_unit=10_000.0, following_error_window=5.0)
                   for i in range(n_drives))
    kwargs: dict[str, Any] = {}
    for name, value in (("spin_s", spin_s), ("rt_priority", rt_priority), ("min_sleep_s", min_sleep_s)):
        if value is not None:
            kwargs[name] = value
    if mode == "thread" and rt_priority is None:
        kwargs["rt_priority"] = 0          # the plain thread in the caller's process
    cfg = WorkerConfig(drives=drives, ts_s=ts_s, bus_kind=bus_kind, adapter=ifname, mode=mode,
                       cpu=cpu if mode == "process" else None, buffer_capacity=1000, trace_capacity=0,
                       wkc_error_limit=1_000_000, **kwargs)
    worker = CyclicWorker(cfg)
    worker.start()
    try:
        worker.enable()
        worker.wait_for(WorkerState.ENABLED, timeout_s=5.0)
        q0 = worker.snapshot().actual_position.copy()
        worker.reset_tracking()
        k = 0
        period_s = 2.0
        t_end = time.monotonic() + seconds
        while time.monotonic() < t_end:
            free = worker.free_space()
            if free > 100:
                t = (np.arange(k, k + free) * ts_s)[:, None]
                q = q0 + amplitude_units * (1.0 - np.cos(2.0 * math.pi * t / period_s)) * np.ones(n_drives)
                k += worker.push(q)
            if on_tick is not None:
                on_tick()
            time.sleep(0.02)
        snap = worker.snapshot()
        worker.events()                    # collected while the worker still runs
    finally:
        worker.stop()
    out: dict[str, Any] = {
        "bus": bus_kind, "ifname": ifname, "mode": mode, "drives": n_drives, "seconds": seconds,
        "ts_us": ts_s * 1e6, "realtime": worker.realtime_applied or "none",
        "spin_us": (cfg.spin_s if cfg.spin_s is not None else
                    (PROCESS_SPIN_S if mode == "process" else 0.0)) * 1e6,
        "min_sleep_us": cfg.min_sleep_s * 1e6,
        "bus_notes": list(worker.bus_notes),
    }
    out.update(snap.timing.as_dict())
    out.update({
        "wkc_errors": snap.wkc_errors, "expected_wkc": snap.expected_wkc, "underruns": snap.underruns,
        "alarms": [a.message for a in snap.alarms],
        "events": [e.message for e in worker.events()],
        "tracking_rmse_max_units": max(snap.tracking.rmse) if snap.tracking.rmse else 0.0,
    })
    return out
