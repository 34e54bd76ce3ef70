"""Running a long program from a plan made as it runs: the machine's executor over a
``PlanWindow``.

    python -m bench.bench_window [--program FILE] [--lines 2000000] [--seconds 20] [--call-samples 20]

Parses the program (default: ``bench_big``'s raster, 200 mm wide, inside the shipped XYZ
mill's travel) for the shipped XYZ mill, then lets the executor make set-points in calls of
20 (the most the controller's feeder asks for at once; in real time it wakes every 2 ms and
asks for the 2 or 3 the drives took meanwhile: ``--call-samples 2``) for ``--seconds`` of wall
time. Prints one JSON object:
motion made per wall second (the real-time ratio), the mean, p99 and longest call (the longest
is a call that plans the window's next segment: the feeder keeps ``lead_s``, 0.5 s, of
set-points queued ahead of the drives, so a call must stay well under it), and the most moves
the window held.
"""

from __future__ import annotations

import argparse
import json
import tempfile
import time
from pathlib import Path

import numpy as np

CALL_SAMPLES = 20  # what the feeder asks the executor for at a time (app.machine.motion.feeding.CHUNK)


def _program(path: str | None, lines: int) -> Path:
    if path:
        return Path(path)
    from bench.bench_big import raster

    out = Path(tempfile.gettempdir()) / "cnc-bench-window" / f"raster_{lines}_200mm.ngc"
    if not out.is_file():
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(raster(lines, 0.1, 200.0), encoding="utf-8")
    return out


def run(program: Path, seconds: float, call_samples: int = CALL_SAMPLES) -> dict:
    from app.machine.config import load_config
    from app.machine.motion.timescale import Budget, PauseFeed, TimeScaledExecutor, reduced_machine
    from planner.gcode.interpreter import parse_file
    from planner.motion.window import PlanWindow
    from resources import shipped_machine

    machine = load_config(shipped_machine("xyz_mill")).machine
    t0 = time.perf_counter()
    prog = parse_file(program, machine=machine)
    parse_s = time.perf_counter() - t0
    budget = Budget()
    window = PlanWindow(prog, reduced_machine(machine, budget))
    t0 = time.perf_counter()
    ex = TimeScaledExecutor(window, machine, budget, pause_feed=PauseFeed(prog, False, True))
    first_s = time.perf_counter() - t0
    calls: list[float] = []
    made = 0
    most = 0
    stop_at = time.perf_counter() + seconds
    started = time.perf_counter()
    while time.perf_counter() < stop_at:
        t = time.perf_counter()
        chunk = ex.generate(call_samples)
        calls.append(time.perf_counter() - t)
        most = max(most, len(window.segment.table))
        if chunk is None:
            if ex.finished:
                break
            ex.release_pause()
            continue
        made += len(chunk.q)
    wall = time.perf_counter() - started
    c = np.array(calls)
    motion_s = made * window.ts_s
    return {
        "benchmark": "window_run",
        "program": program.name,
        "moves": len(prog.moves),
        "call_samples": call_samples,
        "parse_s": round(parse_s, 3),
        "executor_ready_s": round(first_s, 4),
        "motion_s": round(motion_s, 1),
        "wall_s": round(wall, 2),
        "real_time_ratio": round(motion_s / wall, 1),
        "calls": len(calls),
        "call_mean_ms": round(1e3 * float(c.mean()), 3),
        "call_p99_ms": round(1e3 * float(np.quantile(c, 0.99)), 3),
        "call_max_ms": round(1e3 * float(c.max()), 2),
        "segments_made": window.segments_made,
        "most_moves_held": most,
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--program", default=None, help="G-code file (default: a 200 mm raster)")
    parser.add_argument("--lines", type=int, default=2_000_000)
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--call-samples", type=int, default=CALL_SAMPLES,
                        help="set-points asked for a call (the feeder: 20 at most, 2-3 in real time)")
    ns = parser.parse_args(argv)
    if ns.call_samples < 1:
        parser.error("--call-samples: at least 1")
    print(json.dumps(run(_program(ns.program, ns.lines), ns.seconds, ns.call_samples)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
