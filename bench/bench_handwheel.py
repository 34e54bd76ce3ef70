"""What the handwheel costs the 1 ms cycle.

    python -m bench.bench_handwheel [--cycles 20000] [--repeats 5]

The worker on the simulated bus (three drives, a coupler and an EL5101, stepped by hand in
this process, so the time is the cycle's own work and the simulated drives'): ``--cycles``
cycles with the wheel off, then as many with the wheel live on one axis and turned by 8 counts
every cycle (the axis moving all the time). The best of ``--repeats`` runs of each, per cycle,
and the difference: what following the wheel adds to a cycle. Prints one JSON object.
"""

from __future__ import annotations

import argparse
import json

from bench.stepped import cycle_us, enabled
from ethercat.bus import DriveSpec
from ethercat.terminals import TerminalSpec
from ethercat.worker import CyclicWorker, HandwheelMode, HandwheelSpec, WorkerConfig

WHEEL = 1


def _worker() -> CyclicWorker:
    drives = tuple(DriveSpec(i, "XYZ"[i]) for i in range(3))
    terminals = (TerminalSpec(3, "EK1100"), TerminalSpec(4, "EL5101"))
    cfg = WorkerConfig(drives, mode="manual", terminals=terminals, handwheel=HandwheelSpec(WHEEL),
                       trace_capacity=1 << 10)
    return enabled(cfg)


def _per_cycle_us(w: CyclicWorker, cycles: int, turning: bool) -> float:
    assert w._loop is not None and w._loop.bus is not None
    bus = w._loop.bus
    return cycle_us(w, cycles, before=(lambda: bus.inject("encoder_add", WHEEL, 8)) if turning else None)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m bench.bench_handwheel")
    p.add_argument("--cycles", type=int, default=20_000)
    p.add_argument("--repeats", type=int, default=5)
    args = p.parse_args(argv)
    w = _worker()
    try:
        off = min(_per_cycle_us(w, args.cycles, True) for _ in range(args.repeats))
        assert w.handwheel(0, HandwheelMode.POSITION, 0.01 / 4, (100.0, 2000.0, 40_000.0, -1e6, 1e6))
        live = min(_per_cycle_us(w, args.cycles, True) for _ in range(args.repeats))
        moved = float(w.snapshot().reference_position[0])
    finally:
        w.stop()
    print(json.dumps({"cycles": args.cycles, "repeats": args.repeats, "cycle_us_wheel_off": round(off, 2),
                      "cycle_us_wheel_live": round(live, 2), "wheel_adds_us": round(live - off, 2),
                      "axis_moved_mm": round(moved, 4)}))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
