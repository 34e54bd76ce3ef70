"""Program loading benchmark: how long the GUI thread stalls while a large program is loaded.

    QT_QPA_PLATFORM=offscreen python -m bench.bench_load [--program FILE] [--settle-s 1.5]
        [--mode sync|controller|panel|cycle_start|config|all] [--again check|open]

Loads the paper's 35,000-line sphere finishing program (``bench.gen_programs``; or FILE)
through ``MachineController.load_program`` while a 10 ms QTimer in the GUI thread records the
gaps between its ticks. ``sync``: the controller alone, ``load_program(..., wait=True)`` (the
headless path: all work in the calling thread, as every load was before it moved to a worker
thread); ``controller``: the controller alone, loading in its worker thread (parse, soft-limit
check, plan);
``cycle_start`` / ``config``: the program is loaded first (``wait=True``) on a connected
controller (simulated drives, manual clock; also timed: the cycle start call and the making of
the first chunk of set-points); then ``cycle_start()`` resp. ``update_config``
(a small acceleration change: the program is checked again) is called from the GUI thread and
the longest gap is recorded until cycle start is possible again (the re-check done; for
``config`` a cycle start follows, so both stalls count); ``panel``: the whole panel (main
window on the real controller, manual worker clock), so the
pages' reactions to ``programLoaded`` (editors, tool path, v/a/j profile) count too; with
``--again check|open`` the loaded program is then checked again (a configuration change) or
opened again on the Program page, and the peak memory counts both loads. Prints one
JSON object: total load time (call -> ``programLoaded``), time spent inside the call itself,
the longest GUI-thread gap before ``programLoaded`` and until the panel settled, the p99 gap,
and the process's peak resident memory until loaded and until settled.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import tempfile
import time
from pathlib import Path
from typing import Any

TICK_MS = 10


def _peak_rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def _program_file(path: str | None) -> Path:
    if path:
        return Path(path)
    from bench.gen_programs import sphere_finishing

    out = Path(tempfile.gettempdir()) / "cnc-bench-load" / "sphere_finishing.nc"
    if not out.is_file():
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(sphere_finishing(), encoding="utf-8")
    return out


def _slower(cfg: Any) -> Any:
    """``cfg`` with a tenth less path acceleration: a configuration change after which the
    loaded program is checked again."""
    from dataclasses import replace

    return replace(cfg, machine=cfg.machine.with_limits(a_max_mm_s2=cfg.machine.limits.a_max_mm_s2 * 0.9))


def run(program: Path, mode: str, settle_s: float, again: str = "") -> dict:
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from PySide6.QtCore import QEventLoop, QTimer
    from PySide6.QtWidgets import QApplication

    from app.machine.controller import MachineController

    app = QApplication.instance() or QApplication([])
    state_dir = Path(tempfile.mkdtemp(prefix="cnc-bench-load-"))
    controller = MachineController(None, state_dir=state_dir, worker_mode="manual")
    window = None
    if mode == "panel":
        from app.application import apply_theme
        from app.context import PanelOptions
        from app.context_factory import build_context
        from app.main_window import MainWindow

        apply_theme(app)
        options = PanelOptions(state_dir=state_dir)
        window = MainWindow(options, build_context(options, controller=controller))
        window.resize(1280, 800)
        window.show()
    for _ in range(20):  # let the window settle before measuring
        app.processEvents()
        time.sleep(0.01)

    gaps: list[float] = []
    marks: dict[str, float] = {}
    last = [time.perf_counter()]

    def tick() -> None:
        now = time.perf_counter()
        gaps.append(now - last[0])
        last[0] = now

    def done(kind: str, _payload: object) -> None:
        if "again" in marks:            # the second load's outcome
            marks.setdefault("again_done", time.perf_counter())
            marks["again_ok"] = 1.0 if kind == "loaded" else 0.0
            return
        marks.setdefault("done", time.perf_counter())
        marks.setdefault("gaps_at_done", float(len(gaps)))
        marks.setdefault("peak_at_done_mb", _peak_rss_mb())
        marks["ok"] = 1.0 if kind == "loaded" else 0.0

    controller.programLoaded.connect(lambda info: done("loaded", info))
    controller.programErrors.connect(lambda issues: done("errors", issues))
    timer = QTimer()
    timer.setInterval(TICK_MS)
    timer.timeout.connect(tick)

    def start_load() -> None:
        marks["start"] = time.perf_counter()
        controller.load_program(program, wait=mode == "sync")
        marks["returned"] = time.perf_counter()

    loop = QEventLoop()
    timer.start()
    QTimer.singleShot(200, start_load)

    def load_again() -> None:
        """The loaded program checked again (a small acceleration change: the same program),
        or opened again on the Program page as an operator opens the next one."""
        marks["again"] = time.perf_counter()
        if again == "check":
            controller.update_config(_slower(controller.config))
        else:
            assert window is not None
            window.page("program").open_program(program)

    def check_finished() -> None:
        now = time.perf_counter()
        if again and "done" in marks and "again" not in marks and now - marks["done"] >= settle_s:
            load_again()
            QTimer.singleShot(20, check_finished)
        elif again and "again" in marks and "again_done" not in marks and now - marks["again"] <= 120.0:
            QTimer.singleShot(20, check_finished)
        elif "done" in marks and now - marks.get("again_done", marks["done"]) >= settle_s:
            loop.quit()
        elif time.perf_counter() - marks.get("start", time.perf_counter()) > 120.0:
            loop.quit()
        else:
            QTimer.singleShot(20, check_finished)

    QTimer.singleShot(250, check_finished)
    last[0] = time.perf_counter()
    loop.exec()
    timer.stop()
    n_done = int(marks.get("gaps_at_done", len(gaps)))
    # Gaps from the load call on (the tick the call sits in included).
    t = marks["start"]
    times, acc = [], last[0] - sum(gaps)
    for g in gaps:
        acc += g
        times.append(acc)
    during = [g for g, at in zip(gaps, times) if at >= t]
    to_done = [g for g, at in zip(gaps[:n_done + 1], times[:n_done + 1]) if at >= t]
    during_sorted = sorted(during)
    p99 = during_sorted[min(len(during_sorted) - 1, int(0.99 * len(during_sorted)))] if during else 0.0
    info = controller.program_info
    result = {
        "benchmark": "program_load_gui_stall",
        "mode": mode,
        "program": program.name,
        "lines": info.line_count if info else 0,
        "moves": info.move_count if info else 0,
        "loaded": bool(marks.get("ok")),
        "tick_ms": TICK_MS,
        "load_total_s": round(marks.get("done", float("nan")) - t, 4),
        "call_blocked_s": round(marks["returned"] - t, 4),
        "max_gui_gap_until_loaded_ms": round(1000 * max(to_done, default=0.0), 1),
        "max_gui_gap_ms": round(1000 * max(during, default=0.0), 1),
        "p99_gui_gap_ms": round(1000 * p99, 1),
        "settle_s": settle_s,
        # the whole process's peak resident memory: until the program was loaded, and until
        # the panel had settled after it (the pages' tool path and preview included)
        "peak_rss_at_loaded_mb": round(marks.get("peak_at_done_mb", float("nan"))),
        "peak_rss_mb": round(_peak_rss_mb()),
    }
    if again:
        # the peak above then counts the second load too: two programs were once held at once
        result["again"] = again
        result["again_loaded"] = bool(marks.get("again_ok"))
        end, begun = marks.get("again_done", float("nan")), marks.get("again", float("nan"))
        result["again_total_s"] = round(end - begun, 4)
    if window is not None:
        window.close()
    controller.shutdown()
    return result


def run_action(program: Path, action: str, settle_s: float) -> dict:
    """GUI-thread stall of ``cycle_start()`` (``action="cycle_start"``) or of a configuration
    change followed by cycle start (``"config"``), on a connected controller (manual clock)."""
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from PySide6.QtCore import QEventLoop, QTimer
    from PySide6.QtWidgets import QApplication

    from app.machine.controller import MachineController

    app = QApplication.instance() or QApplication([])
    state_dir = Path(tempfile.mkdtemp(prefix="cnc-bench-load-"))
    controller = MachineController(None, state_dir=state_dir, worker_mode="manual")
    assert controller.connect_bus(), "connect failed"
    assert controller.set_machine_zero_here()
    loaded = controller.load_program(program, wait=True)
    assert loaded, loaded.reason
    for _ in range(20):
        app.processEvents()
        time.sleep(0.01)
    gaps: list[tuple[float, float]] = []  # (time of the tick, gap before it)
    marks: dict[str, float] = {}
    last = [time.perf_counter()]
    calls: list[tuple[str, float, bool, str]] = []

    def tick() -> None:
        now = time.perf_counter()
        gaps.append((now, now - last[0]))
        last[0] = now

    def timed(name: str, fn) -> bool:  # noqa: ANN001
        t0 = time.perf_counter()
        res = fn()
        calls.append((name, time.perf_counter() - t0, bool(res), getattr(res, "reason", "")))
        return bool(res)

    def step() -> None:
        if "start" not in marks:
            marks["start"] = time.perf_counter()
            if action == "config":
                new = _slower(controller.config)
                timed("update_config", lambda: controller.update_config(new))
        if "started" not in marks:
            if controller.refusal("cycle_start"):
                QTimer.singleShot(10, step)
                return
            if timed("cycle_start", controller.cycle_start):
                marks["started"] = time.perf_counter()
            elif time.perf_counter() - marks["start"] > 60.0:
                marks["started"] = float("nan")
            else:
                QTimer.singleShot(10, step)
                return
        job = controller.stream.job
        if "first_chunk_s" not in marks and job is not None:
            # the first set-points the feeder makes for the worker (the manual clock feeds on
            # demand: made here once and the executor put back as it was)
            from app.machine.motion.feeding import CHUNK

            state = job.executor.save_state()
            t0 = time.perf_counter()
            job.executor.generate(CHUNK)
            marks["first_chunk_s"] = time.perf_counter() - t0
            job.executor.restore_state(state)
        QTimer.singleShot(round(settle_s * 1000), loop.quit)

    timer = QTimer()
    timer.setInterval(TICK_MS)
    timer.timeout.connect(tick)
    loop = QEventLoop()
    timer.start()
    QTimer.singleShot(200, step)
    last[0] = time.perf_counter()
    loop.exec()
    timer.stop()
    t = marks["start"]
    end = marks.get("started", float("nan"))
    during = [g for at, g in gaps if at >= t]
    to_start = [g for at, g in gaps if t <= at <= end + 0.05]
    result = {
        "benchmark": "program_load_gui_stall",
        "mode": action,
        "program": program.name,
        "lines": controller.program_info.line_count if controller.program_info else 0,
        "started": end == end,
        "start_after_s": round(end - t, 4),
        # cycle start's call and the making of the first chunk of set-points after it
        "first_setpoints_after_s": round(calls[-1][1] + marks.get("first_chunk_s", float("nan")), 4)
        if calls else float("nan"),
        "calls": [{"call": n, "blocked_s": round(d, 4), "ok": ok, "reason": r} for n, d, ok, r in calls],
        "max_gui_gap_until_started_ms": round(1000 * max(to_start, default=0.0), 1),
        "max_gui_gap_ms": round(1000 * max(during, default=0.0), 1),
        "settle_s": settle_s,
    }
    controller.estop("bench done")
    controller.shutdown()
    return result


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--program", default=None, help="G-code file (default: 35,000-line finishing)")
    parser.add_argument("--mode", choices=("sync", "controller", "panel", "cycle_start", "config", "all"),
                        default="all")
    parser.add_argument("--settle-s", type=float, default=1.5)
    parser.add_argument("--again", choices=("check", "open"), default="",
                        help="panel: once loaded and settled, check the program again (a configuration "
                             "change) or open it again on the Program page; the peak counts both loads")
    ns = parser.parse_args(argv)
    if ns.again and ns.mode != "panel":
        parser.error("--again needs --mode panel")
    program = _program_file(ns.program)
    modes = ("sync", "controller", "panel") if ns.mode == "all" else (ns.mode,)
    results = [run_action(program, m, ns.settle_s) if m in ("cycle_start", "config")
               else run(program, m, ns.settle_s, ns.again) for m in modes]
    print(json.dumps(results[0] if len(results) == 1 else {"benchmark": "program_load_gui_stall",
                                                          "runs": results}))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
