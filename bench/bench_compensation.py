"""What leadscrew compensation costs the 1 ms cycle.

    python -m bench.bench_compensation [--cycles 20000] [--repeats 5] [--lines 256]

The worker on the simulated bus (three drives, stepped by hand in this process, so the time is
the cycle's own work and the simulated drives'), the same back-and-forth moves of every axis
(a reversal every 0.5 s) without compensation and with a pitch-error table of ``--lines``
lines on all three axes, switched on: the best of ``--repeats`` runs of each, per cycle, and
the difference. Prints one JSON object.
"""

from __future__ import annotations

import argparse
import json

import numpy as np

from bench.stepped import cycle_us, enabled
from ethercat.bus import DriveSpec
from ethercat.screw_comp import CompCurve, ScrewComp, take_up_limits
from ethercat.worker import CompSpec, CyclicWorker, WorkerConfig

RATED = (100.0, 2000.0, 40_000.0)
TRAVEL = (-250.0, 250.0)


def _table(lines: int) -> ScrewComp:
    x = np.linspace(*TRAVEL, lines)
    ripple = 0.004 * np.sin(x / 37.0)
    return ScrewComp(CompCurve.through(x, ripple + 0.01), CompCurve.through(x, ripple - 0.01), "bench")


def _worker(lines: int) -> CyclicWorker:
    drives = tuple(DriveSpec(i, "XYZ"[i]) for i in range(3))
    comp: tuple[CompSpec, ...] = ()
    if lines:
        table = _table(lines)
        take = take_up_limits(table, TRAVEL, RATED, 0.1, 0.001)
        comp = tuple(CompSpec(i, table, take) for i in range(3))
    w = enabled(WorkerConfig(drives, mode="manual", compensation=comp, trace_capacity=1 << 10))
    for i in range(len(comp)):
        assert w.compensate(i, True, 0.0)
    return w


def _per_cycle_us(w: CyclicWorker, cycles: int) -> float:
    t = np.arange(cycles) * 0.001
    path = np.repeat((5.0 * np.sin(2 * np.pi * t))[:, None], 3, axis=1)    # reversals every 0.5 s
    return cycle_us(w, cycles, path)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m bench.bench_compensation")
    p.add_argument("--cycles", type=int, default=20_000)
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--lines", type=int, default=256)
    args = p.parse_args(argv)
    results = {}
    for name, lines in (("off", 0), ("on", args.lines)):
        w = _worker(lines)
        try:
            results[name] = min(_per_cycle_us(w, args.cycles) for _ in range(args.repeats))
            on = w.snapshot().compensation_on
        finally:
            w.stop()
        assert all(on) == bool(lines)
    print(json.dumps({"cycles": args.cycles, "repeats": args.repeats, "table_lines": args.lines, "axes": 3,
                      "cycle_us_without": round(results["off"], 2), "cycle_us_with": round(results["on"], 2),
                      "compensation_adds_us": round(results["on"] - results["off"], 2)}))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
