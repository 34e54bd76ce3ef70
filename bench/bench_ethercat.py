"""Cycle timing of the EtherCAT worker on simulated drives: process vs plain thread, with and
without a CPU-bound Qt GUI load (a pyqtgraph plot redrawn offscreen as fast as it can) in
the parent process.

    QT_QPA_PLATFORM=offscreen python -m bench.bench_ethercat --seconds 20 [--json]

Prints one JSON object: per case (worker mode x load) the period, cycle start jitter
percentiles (p50/p99/p99.9/max), late cycles (start later than 1 ms), missed cycles,
working counter errors. Target (issue 5): jitter p99 <= 100 us, no cycle later than 1 ms.
"""

from __future__ import annotations

import argparse
import ctypes
import json
import os
import sys
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from ethercat.benchmark import run_bench


def _restore_singleton_refcounts(targets: dict[int, tuple[object, int]]) -> None:
    """Work around PySide6 6.12.0 on Python 3.11: every call of a void Qt method
    (QPolygonF.resize, QPainterPath.moveTo, QPointF.setX, ...) decrements None's reference
    count once (and bool results True/False's), so a redraw loop aborts with "Fatal Python
    error: none_dealloc" after about 16,000 such calls. Python >= 3.12 (immortal
    singletons) is not affected."""
    if sys.version_info >= (3, 12):
        return
    incref = ctypes.pythonapi.Py_IncRef
    incref.argtypes = [ctypes.py_object]
    for obj, target in targets.values():
        for _ in range(target - sys.getrefcount(obj)):
            incref(obj)


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
    none_refs = {id(o): (o, sys.getrefcount(o)) for o in (None, True, False)}

    def tick() -> None:
        t_end = time.perf_counter() + busy_s
        while time.perf_counter() < t_end:
            phase[0] += 0.1
            for k, c in enumerate(curves):
                c.setData(x, np.sin(x * (k + 1) + phase[0]))
            widget.grab()                      # full offscreen render
            app.processEvents()
        _restore_singleton_refcounts(none_refs)

    return tick


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seconds", type=float, default=10.0, help="duration of each case")
    ap.add_argument("--drives", type=int, default=4)
    ap.add_argument("--modes", default="process,thread")
    ap.add_argument("--loads", default="idle,gui")
    ap.add_argument("--json", action="store_true", help="JSON only (default prints a table too)")
    args = ap.parse_args(argv)
    load_tick = make_gui_load() if "gui" in args.loads.split(",") else None
    cases: list[dict[str, Any]] = []
    keys = ("jitter_p50_us", "jitter_p99_us", "jitter_p999_us", "jitter_max_us", "period_mean_us",
            "period_max_us", "late_cycles", "missed_cycles", "wkc_errors", "cycles", "exec_mean_us")
    for load in args.loads.split(","):
        for mode in args.modes.split(","):
            r = run_bench("sim", "", args.seconds, n_drives=args.drives, mode=mode,
                          on_tick=load_tick if load == "gui" else None)
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
