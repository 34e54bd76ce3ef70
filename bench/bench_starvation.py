"""Set-points under load: the panel runs a big program while the CPU is busy, and then its
feeder is stalled on purpose.

    QT_QPA_PLATFORM=offscreen python -m bench.bench_starvation [--minutes 10] [--lines 1000000]
        [--busy 2] [--size 1280x800] [--switch-s 5]

Phase 1: the whole panel in demo mode (simulated drives, the real-time worker in its own
process, the feeder thread in the panel's), a ``--lines`` raster program loaded and running,
``--busy`` processes ``sh -c 'while :; do :; done'`` beside it, the page switched every
``--switch-s`` between Auto, Preview (the program's tool path drawn), Manual and Diagnostics
for ``--minutes``. Measured: the worker's underruns, braking tails run into ("set-points ran
out" alarms), and the least lead left (queued set-points ahead of the drives, before the tail;
a thread samples it every 2 ms).

Phase 2: the feeder stalled on purpose (the motion's lock held 1.5 s, as a GIL stall would):
the drives run into the braking tail. Measured: the alarm, the worker's underruns (none), and
the limit ratios of every set-point sent in the run (<= 1 holds).

Prints one JSON object.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import tempfile
import threading
import time
from pathlib import Path


def _wait(app: object, predicate: object, timeout_s: float) -> bool:
    t_end = time.monotonic() + timeout_s
    while time.monotonic() < t_end:
        app.processEvents()  # type: ignore[attr-defined]
        if predicate():  # type: ignore[operator]
            return True
        time.sleep(0.01)
    return False


def run(minutes: float, lines: int, busy: int, size: str, switch_s: float) -> dict[str, object]:
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from PySide6.QtWidgets import QApplication

    from app.application import apply_theme, create_window
    from app.context import PanelOptions
    from app.machine.model import MachineState
    from bench.bench_big import raster

    app = QApplication.instance() or QApplication([])
    apply_theme(app)  # type: ignore[arg-type]
    folder = Path(tempfile.mkdtemp(prefix="bench-starvation-"))
    program = folder / f"raster_{lines}.nc"
    program.write_text(raster(lines), encoding="utf-8")
    width, height = (int(v) for v in size.split("x"))
    window = create_window(PanelOptions(demo=True, program_path=program, state_dir=folder / "state",
                                        width_px=width, height_px=height))
    window.show()
    ctl = window.context.controller
    hogs = [subprocess.Popen(["sh", "-c", "while :; do :; done"]) for _ in range(busy)]
    result: dict[str, object] = {"lines": lines, "busy_processes": busy, "minutes": minutes, "size": size}
    try:
        t0 = time.monotonic()
        loaded = _wait(app, lambda: ctl.bus_status.connected and ctl.program_info is not None
                       and not ctl.loading, 600.0)
        result["load_s"] = round(time.monotonic() - t0, 1)
        if not loaded:
            raise SystemExit("the program did not load within 10 minutes")
        if not all(ctl.homed):                 # the demo machine homes to its switches
            ctl.home_all()
            if not _wait(app, lambda: all(ctl.homed) and ctl.state.value == "idle", 120.0):
                raise SystemExit(f"homing did not end within 2 minutes: {ctl.state_reason}")
        started = ctl.cycle_start()
        if not started:
            raise SystemExit(f"cycle start refused: {started.reason}")
        least = [1 << 30]
        sampling = threading.Event()

        def sample() -> None:
            while not sampling.wait(0.002):
                job = ctl.stream.job
                consumed = ctl.worker.samples_consumed() if ctl.worker is not None else None
                if job is not None and consumed is not None and job.pause is None:
                    least[0] = min(least[0], ctl.stream.pushed_total - consumed)

        sampler = threading.Thread(target=sample, daemon=True)
        sampler.start()
        pages = ("auto", "preview", "manual", "diagnostics")
        t_end = time.monotonic() + 60.0 * minutes
        next_switch, k = time.monotonic() + switch_s, 0
        while time.monotonic() < t_end and ctl.state is MachineState.RUNNING:
            app.processEvents()
            if time.monotonic() >= next_switch:
                k += 1
                window.show_page(pages[k % len(pages)], ask_password=False)
                next_switch += switch_s
            time.sleep(0.005)
        sampling.set()
        sampler.join()
        snap = ctl.worker.snapshot() if ctl.worker is not None else None
        codes = [a.code for a in ctl.alarms]
        result["phase1"] = {
            "ran_s": round(time.monotonic() - (t_end - 60.0 * minutes), 1),
            "still_running": ctl.state is MachineState.RUNNING,
            "worker_underruns": int(snap.underruns) if snap is not None else None,
            "ran_out_alarms": codes.count("setpoints_ran_out"),
            "least_lead_ms": least[0] if least[0] < (1 << 30) else None,
            "lead_ms": round(1000 * ctl.config.controller.lead_s),
            "page_switches": k,
        }
        if ctl.state is MachineState.RUNNING:
            underruns_before = int(snap.underruns) if snap is not None else 0
            stalled = threading.Event()

            def stall() -> None:
                with ctl.stream._lock:
                    stalled.set()
                    time.sleep(1.5)

            staller = threading.Thread(target=stall)
            staller.start()
            stalled.wait(5.0)
            staller.join()
            alarmed = _wait(app, lambda: "setpoints_ran_out" in [a.code for a in ctl.active_alarms], 10.0)
            _wait(app, lambda: ctl.stream.job is None, 10.0)
            snap = ctl.worker.snapshot()
            summary = ctl.last_run
            limits = summary.limits if summary is not None else {}
            result["phase2"] = {
                "ran_out_alarm": alarmed,
                "state": ctl.state.value,
                "worker_underruns_added": (int(snap.underruns) - underruns_before
                                           if snap is not None else None),
                "limit_ratios": {k: round(v, 4) for k, v in sorted(limits.items())
                                 if k in ("tangential_v", "tangential_a", "tangential_j", "axis_v",
                                          "axis_a", "axis_j")},
                "resume_line": ctl.resume_line,
            }
    finally:
        for hog in hogs:
            hog.kill()
            hog.wait()
        ctl.shutdown()
        window.close()
    return result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--minutes", type=float, default=10.0)
    parser.add_argument("--lines", type=int, default=1_000_000)
    parser.add_argument("--busy", type=int, default=2)
    parser.add_argument("--size", default="1280x800")
    parser.add_argument("--switch-s", type=float, default=5.0)
    ns = parser.parse_args()
    print(json.dumps(run(ns.minutes, ns.lines, ns.busy, ns.size, ns.switch_s), indent=1))


if __name__ == "__main__":
    main()
