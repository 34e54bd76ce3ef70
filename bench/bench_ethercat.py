"""Cycle timing of the EtherCAT worker on simulated drives: process vs plain thread, with and
without a CPU-bound Qt GUI load (a pyqtgraph plot redrawn offscreen as fast as it can) in
the parent process.

    QT_QPA_PLATFORM=offscreen python -m bench.bench_ethercat --seconds 20 [--json]
        [--modes process,thread] [--loads idle,gui] [--link 3 | --ifname IF]
        [--spin-us US] [--rt-priority P] [--min-sleep-us US] [--cpu N]

Prints one JSON object: per case (worker mode x load) the period, cycle start jitter
percentiles (p50/p99/p99.9/max), late cycles (start later than 1 ms), missed cycles,
working counter errors. Target (issue 5): jitter p99 <= 100 us, no cycle later than 1 ms.
`--link N` runs on real frames: an `EmulatedLink` of N emulated drives (root, ip netns),
removed afterwards. The other flags override `WorkerConfig` defaults (for comparisons).
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import sys
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from ethercat.benchmark import run_bench


def make_gui_load(busy_s: float = 0.05) -> Callable[[], None]:
    """A pyqtgraph PlotWidget with 200,000 points, redrawn offscreen for `busy_s` per call:
    what the panel's preview and diagnostics plots do to the GUI thread."""
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    import pyqtgraph as pg
    from PySide6 import QtWidgets

    app = QtWidgets.QApplication.instance() or QtWidgets.QApplication([])
    widget = pg.PlotWidget()
    widget.resize(1280, 800)
    curves = [widget.plot(pen=pg.mkPen(c)) for c in ("c", "g", "y")]
    x = np.linspace(0.0, 100.0, 200_000)
    widget.show()
    phase = [0.0]

    def tick() -> None:
        t_end = time.perf_counter() + busy_s
        while time.perf_counter() < t_end:
            phase[0] += 0.1
            for k, c in enumerate(curves):
                c.setData(x, np.sin(x * (k + 1) + phase[0]))
            widget.grab()                      # full offscreen render
            app.processEvents()

    return tick


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seconds", type=float, default=10.0, help="duration of each case")
    ap.add_argument("--drives", type=int, default=4)
    ap.add_argument("--modes", default="process,thread")
    ap.add_argument("--loads", default="idle,gui")
    ap.add_argument("--json", action="store_true", help="JSON only (default prints a table too)")
    ap.add_argument("--link", type=int, default=0, help="bench on an emulated link of N drives")
    ap.add_argument("--ifname", default="", help="bench on this adapter (SoemBus)")
    ap.add_argument("--spin-us", type=float, default=None)
    ap.add_argument("--rt-priority", type=int, default=None)
    ap.add_argument("--min-sleep-us", type=float, default=None)
    ap.add_argument("--cpu", type=int, default=-1)
    args = ap.parse_args(argv)
    with contextlib.ExitStack() as stack:
        bus, ifname = "sim", ""
        if args.link:
            from ethercat.emulator.link import EmulatedLink

            link = stack.enter_context(EmulatedLink(args.link, realtime=True))
            bus, ifname, args.drives = "soem", link.master_ifname, args.link
        elif args.ifname:
            bus, ifname = "soem", args.ifname
        return _run(args, bus, ifname)


def _run(args: argparse.Namespace, bus: str, ifname: str) -> int:
    overrides: dict[str, Any] = {"cpu": args.cpu}
    if args.spin_us is not None:
        overrides["spin_s"] = args.spin_us * 1e-6
    if args.rt_priority is not None:
        overrides["rt_priority"] = args.rt_priority
    if args.min_sleep_us is not None:
        overrides["min_sleep_s"] = args.min_sleep_us * 1e-6
    load_tick = make_gui_load() if "gui" in args.loads.split(",") else None
    cases: list[dict[str, Any]] = []
    keys = ("jitter_p50_us", "jitter_p99_us", "jitter_p999_us", "jitter_max_us", "period_mean_us",
            "period_max_us", "late_cycles", "missed_cycles", "wkc_errors", "cycles", "exec_mean_us")
    for load in args.loads.split(","):
        for mode in args.modes.split(","):
            r = run_bench(bus, ifname, args.seconds, n_drives=args.drives, mode=mode,
                          on_tick=load_tick if load == "gui" else None, **overrides)
            r["load"] = load
            r.pop("alarms", None)
            cases.append(r)
            if not args.json:
                figures = " ".join(f"{k}={r[k]:.0f}" if isinstance(r[k], float) else f"{k}={r[k]}"
                                   for k in keys)
                print(f"# {mode:7s} {load:4s} {r['realtime']:20s} {figures}", file=sys.stderr)
    print(json.dumps({"bench": "ethercat", "seconds_per_case": args.seconds, "cpus": os.cpu_count(),
                      "cases": cases}, indent=None if args.json else 1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
