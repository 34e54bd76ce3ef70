"""Preview benchmark: open and draw a 35,000-line program (target: under one second).

    QT_QPA_PLATFORM=offscreen python -m bench.bench_preview [--lines 35000] [--arc-share 0.3]

Generates a sphere-finishing-like program (G01 steps with G02/G03 arcs between them, a few
rapids), then times: interpret (planner), build the tool path (vectorised), hand it to the
pyqtgraph items and render one frame; then zooms to the middle quarter and records the frames
drawn and the GUI thread's longest gap until the new level of detail is shown; then draws the
part run so far at five points of a run (a frame each). Prints one JSON object.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time


def generate_program(lines: int = 35_000, arc_share: float = 0.3, seed: int = 7) -> str:
    """Concentric rings down a hemisphere: each ring of short G01 chords and G02/G03 arcs."""
    import numpy as np

    rng = np.random.default_rng(seed)
    out = ["%", "(generated: sphere finishing style, for the preview benchmark)", "G21 G17 G90 G94 G54",
           "M03 S12000", "G00 Z5", "G00 X40 Y0", "G01 Z0 F600"]
    radius_mm, x, y, z = 40.0, 40.0, 0.0, 0.0
    angle = 0.0
    while len(out) < lines - 3:
        if rng.random() < arc_share:
            sweep = math.radians(rng.uniform(5.0, 40.0))
            angle += sweep
            nx, ny = radius_mm * math.cos(angle), radius_mm * math.sin(angle)
            out.append(f"G03 X{nx:.4f} Y{ny:.4f} I{-x:.4f} J{-y:.4f} F1200")
        else:
            angle += math.radians(2.0)
            nx, ny = radius_mm * math.cos(angle), radius_mm * math.sin(angle)
            out.append(f"G01 X{nx:.4f} Y{ny:.4f} F1500")
        x, y = nx, ny
        if angle > 2 * math.pi:  # next ring, lower and smaller
            angle -= 2 * math.pi
            z -= 0.05
            radius_mm = max(1.0, radius_mm * 0.995)
            x, y = radius_mm * math.cos(angle), radius_mm * math.sin(angle)
            out.append(f"G01 X{x:.4f} Y{y:.4f} Z{z:.4f}")
    out += ["G00 Z5", "M30", "%"]
    return "\n".join(out[:lines]) + "\n"


def run(lines: int, arc_share: float) -> dict:
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from PySide6.QtWidgets import QApplication

    from app.toolpath import build_toolpath
    from app.widgets.preview_plot import PreviewPlot
    from planner.core.machine import MachineSpec
    from planner.core.program import MoveKind
    from planner.gcode.interpreter import parse_program

    app = QApplication.instance() or QApplication([])
    text = generate_program(lines, arc_share)
    machine = MachineSpec.default()
    plot = PreviewPlot()
    plot.resize(1100, 600)
    plot.show()
    app.processEvents()

    t0 = time.perf_counter()
    program = parse_program(text, name="bench.nc", machine=machine)
    t1 = time.perf_counter()
    path = build_toolpath(program)
    t2 = time.perf_counter()
    plot.set_toolpath(path)
    t_set = time.perf_counter()
    gap_open, last = 0.0, t_set
    while plot.detail_pending:  # a big path's thinned copies are made off the GUI thread
        app.processEvents()
        now = time.perf_counter()
        gap_open, last = max(gap_open, now - last), now
        time.sleep(0.005)
    t3 = time.perf_counter()
    plot.grab()  # render one full frame of every item
    t4 = time.perf_counter()
    # a zoom to the middle quarter: the frame drawn at once (the old detail moved), the new
    # detail made off the GUI thread; the GUI thread's longest gap meanwhile
    (x0, x1), (y0, y1) = plot.getViewBox().viewRange()
    cx, cy, w, h = (x0 + x1) / 2, (y0 + y1) / 2, (x1 - x0) / 4, (y1 - y0) / 4
    started = time.perf_counter()
    plot.getViewBox().setRange(xRange=(cx - w, cx + w), yRange=(cy - h, cy + h), padding=0)
    frames, worst, last = [], 0.0, time.perf_counter()
    while plot.detail_pending or time.perf_counter() - started < 0.1:
        app.processEvents()
        f0 = time.perf_counter()
        plot.grab()
        frames.append(time.perf_counter() - f0)
        now = time.perf_counter()
        worst, last = max(worst, now - last), now
        time.sleep(0.005)
    detail_s = time.perf_counter() - started
    # a run: the part run so far drawn over the path as lines are reached, a frame each
    run_frames = []
    for k in range(1, 6):
        f0 = time.perf_counter()
        plot.set_executed(k * len(program.moves) // 6)
        plot.grab()
        run_frames.append(time.perf_counter() - f0)
    return {
        "benchmark": "preview_open_and_draw",
        "lines": text.count("\n"),
        "moves": len(program.moves),
        "arcs": path.kinds[MoveKind.ARC].count,
        "lines_g01": path.kinds[MoveKind.LINE].count,
        "points_drawn": int(len(path.all.points)),
        "interpret_s": round(t1 - t0, 4),
        "toolpath_s": round(t2 - t1, 4),
        "set_toolpath_call_s": round(t_set - t2, 4),
        "set_data_s": round(t3 - t2, 4),
        "open_gui_gap_max_s": round(max(gap_open, t_set - t2), 4),
        "render_s": round(t4 - t3, 4),
        "draw_s": round(t4 - t1, 4),
        "total_open_and_draw_s": round(t4 - t0, 4),
        "drawn_as": "image" if plot.raster_item.isVisible() else "vectors",
        "zoom_frame_max_s": round(max(frames), 4),
        "zoom_gui_gap_max_s": round(worst, 4),
        "zoom_detail_s": round(detail_s, 4),
        "run_frame_max_s": round(max(run_frames), 4),
        "target_s": 1.0,
        "pass": (t4 - t0) < 1.0,
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lines", type=int, default=35_000)
    parser.add_argument("--arc-share", type=float, default=0.3)
    ns = parser.parse_args(argv)
    print(json.dumps(run(ns.lines, ns.arc_share)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
