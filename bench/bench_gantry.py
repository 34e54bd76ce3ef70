"""What a gantry costs the 1 ms cycle.

    python -m bench.bench_gantry [--cycles 20000] [--repeats 5]

The worker on the simulated bus with four drives, stepped by hand in this process (so the
time is the cycle's own work and the simulated drives'), the same back-and-forth moves: once
as four independent axes, once as three axes whose second one is a gantry with the fourth
drive as its second side (its set-points made in the loop, its skew checked every cycle). The
best of ``--repeats`` runs of each, per cycle, and the difference. Prints one JSON object.
"""

from __future__ import annotations

import argparse
import json

import numpy as np

from bench.stepped import cycle_us, enabled
from ethercat.bus import DriveSpec
from ethercat.worker import CyclicWorker, GantrySpec, WorkerConfig, WorkerState


def _worker(gantry: bool) -> CyclicWorker:
    drives = tuple(DriveSpec(i, name) for i, name in enumerate(("X", "Y", "Z", "Y2" if gantry else "A")))
    spec = (GantrySpec(1, 3, 0.5),) if gantry else ()
    return enabled(WorkerConfig(drives, mode="manual", gantry=spec, trace_capacity=1 << 10))


def _per_cycle_us(w: CyclicWorker, cycles: int) -> float:
    t = np.arange(cycles) * 0.001
    path = np.repeat((5.0 * np.sin(2 * np.pi * t))[:, None], w.config.n_motion_axes, axis=1)
    return cycle_us(w, cycles, path)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m bench.bench_gantry")
    p.add_argument("--cycles", type=int, default=20_000)
    p.add_argument("--repeats", type=int, default=5)
    args = p.parse_args(argv)
    results = {}
    for name, gantry in (("four axes", False), ("gantry", True)):
        w = _worker(gantry)
        try:
            results[name] = min(_per_cycle_us(w, args.cycles) for _ in range(args.repeats))
            snap = w.snapshot()
        finally:
            w.stop()
        assert snap.state is WorkerState.ENABLED and not snap.alarms, snap.alarms
    print(json.dumps({"cycles": args.cycles, "repeats": args.repeats, "drives": 4,
                      "cycle_us_four_axes": round(results["four axes"], 2),
                      "cycle_us_gantry": round(results["gantry"], 2),
                      "gantry_adds_us": round(results["gantry"] - results["four axes"], 2)}))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
