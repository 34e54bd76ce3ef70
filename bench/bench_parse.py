"""Benchmark: G-code parse + exact arc geometry of a 35,000-line CAM-like program.

    python -m bench.bench_parse [--lines 35000] [--repeat 3] [--profile]

Prints one JSON object: lines, moves, arcs, best/median wall time and best CPU time of a
parse (s), lines per second (wall, best run) and per CPU second, peak traced memory
(tracemalloc, MB) during one parse. Target on the 2-core machine: >= 100,000 lines/s.
On a shared machine the wall figures vary with load; the CPU figure is steadier.
"""

from __future__ import annotations

import argparse
import json
import math
import random
import statistics
import sys
import time
import tracemalloc

from planner.gcode.interpreter import parse_program


def generate_program(n_lines: int = 35_000, seed: int = 1) -> str:
    """A finishing-pass-like program: G01 segments and G02/G03 arcs (I/J and R forms).

    Coordinates with 4 decimals as CAM posts write them; modal lines without G words;
    about 40 % of the lines are arcs, half of them in the R form.
    """
    rng = random.Random(seed)
    out = ["%", "(bench: generated CAM-like finishing program)", "G21 G17 G90 G94 G64", "G54",
           "T1 M06", "S12000 M03", "G00 X0 Y0 Z5", "G01 Z-1 F600"]
    x = y = 0.0
    z = -1.0
    mode = 1
    while len(out) < n_lines - 2:
        k = rng.random()
        if k < 0.6:  # straight segment
            x1 = round(x + rng.uniform(-2.0, 2.0), 4)
            y1 = round(y + rng.uniform(-2.0, 2.0), 4)
            words = []
            if mode != 1:
                words.append("G01")
                mode = 1
            words.append(f"X{x1:.4f} Y{y1:.4f}")
            if rng.random() < 0.3:
                z = round(z + rng.uniform(-0.05, 0.05), 4)
                words.append(f"Z{z:.4f}")
            if rng.random() < 0.05:
                words.append(f"F{rng.choice((400, 600, 900))}")
            out.append(" ".join(words))
            x, y = x1, y1
        else:  # arc of radius 1-20 mm, 10-170 degrees
            r = rng.uniform(1.0, 20.0)
            g = rng.choice((2, 3))
            a0 = rng.uniform(-math.pi, math.pi)
            cx, cy = x - r * math.cos(a0), y - r * math.sin(a0)
            sweep = math.radians(rng.uniform(10.0, 170.0)) * (-1 if g == 2 else 1)
            x1 = round(cx + r * math.cos(a0 + sweep), 4)
            y1 = round(cy + r * math.sin(a0 + sweep), 4)
            words = [f"G0{g}"] if mode != g or rng.random() < 0.5 else []
            mode = g
            words.append(f"X{x1:.4f} Y{y1:.4f}")
            if rng.random() < 0.5:
                words.append(f"I{cx - x:.4f} J{cy - y:.4f}")
            else:
                words.append(f"R{r:.4f}")
            out.append(" ".join(words))
            x, y = x1, y1
    out += ["G00 Z5", "M05", "M30", "%"]
    return "\n".join(out[: n_lines - 1] + ["%"]) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lines", type=int, default=35_000)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--profile", action="store_true", help="print a cProfile of one parse to stderr")
    args = ap.parse_args(argv)

    text = generate_program(args.lines)
    n_lines = text.count("\n")
    times, cpu_times = [], []
    program = None
    for _ in range(args.repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        program = parse_program(text, "bench.nc")
        times.append(time.perf_counter() - t0)
        cpu_times.append(time.process_time() - c0)
    assert program is not None
    tracemalloc.start()
    parse_program(text, "bench.nc")
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    if args.profile:
        import cProfile
        import pstats

        pr = cProfile.Profile()
        pr.enable()
        parse_program(text, "bench.nc")
        pr.disable()
        pstats.Stats(pr, stream=sys.stderr).sort_stats("tottime").print_stats(15)
    best = min(times)
    result = {
        "benchmark": "parse+geometry",
        "lines": n_lines,
        "moves": len(program.moves),
        "arcs": sum(1 for m in program.moves if m.arc is not None),
        "parse_s_best": round(best, 4),
        "parse_s_median": round(statistics.median(times), 4),
        "cpu_s_best": round(min(cpu_times), 4),
        "lines_per_s": round(n_lines / best),
        "lines_per_cpu_s": round(n_lines / min(cpu_times)),
        "target_lines_per_s": 100_000,
        "peak_memory_mb": round(peak / 1e6, 2),
    }
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
