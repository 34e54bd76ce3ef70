"""Planner benchmark: the paper's three experiment programs.

    python -m bench.bench_plan [--only NAME] [--ts 0.001]

For each generated program (bench/gen_programs.py): parse time, plan time (joint speeds,
profiles, timeline), interpolation time (exact and taylor, all set-points, 1 ms), set-points
per second, ratio to real time (cycle time / (plan + interpolation)), time to the first
set-point when streaming (plan window by window, from the parsed program) and peak memory
(RSS, in a fresh process that parses and streams the whole program). Wall-clock figures
suffer from other load on a shared machine; the CPU-time ratio is printed beside them.
The last line printed is the JSON result. Targets: finishing >= 2000x real time, first set-point < 50 ms, peak
memory while streaming < 300 MB.
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import time

from bench.gen_programs import PROGRAMS
from cli.plan import build_machine
from planner.gcode.interpreter import parse_program
from planner.motion.plan import plan_program, stream_program

STREAM_CHUNK = 4096


def _drain(chunks) -> int:
    n = 0
    for c in chunks:
        n += len(c)
    return n


def stream_child(name: str, ts: float) -> None:
    """Run in a fresh process: parse, stream every set-point, report latency and peak RSS."""
    machine = build_machine(None, None, None, None, ts)
    text = PROGRAMS[name]()
    program = parse_program(text, name, machine)
    del text
    started = time.perf_counter()
    gen = stream_program(program, machine, chunk_samples=STREAM_CHUNK)
    first = next(gen)
    first_s = time.perf_counter() - started
    n = len(first) + _drain(gen)
    total_s = time.perf_counter() - started
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(json.dumps({"first_setpoint_ms": first_s * 1e3, "stream_s": total_s, "samples": n,
                      "peak_rss_mb": peak_mb}))


def bench_one(name: str, ts: float) -> dict:
    machine = build_machine(None, None, None, None, ts)
    text = PROGRAMS[name]()
    lines = text.count("\n")
    t = time.perf_counter()
    program = parse_program(text, name, machine)
    parse_s = time.perf_counter() - t
    arcs = sum(1 for mv in program.moves if mv.arc is not None)

    t, c = time.perf_counter(), time.process_time()
    plan = plan_program(program, machine, interpolation="exact")
    plan_s, plan_cpu_s = time.perf_counter() - t, time.process_time() - c
    t, c = time.perf_counter(), time.process_time()
    samples = _drain(plan.iter_chunks())
    interp_exact_s, interp_cpu_s = time.perf_counter() - t, time.process_time() - c

    taylor = plan_program(program, machine, interpolation="taylor")
    t = time.perf_counter()
    samples_taylor = _drain(taylor.iter_chunks())
    interp_taylor_s = time.perf_counter() - t

    child = subprocess.run([sys.executable, "-m", "bench.bench_plan", "--stream-child", name,
                            "--ts", str(ts)], capture_output=True, text=True, check=True)
    stream = json.loads(child.stdout.strip().splitlines()[-1])
    work_s = plan_s + interp_exact_s
    return {
        "lines": lines, "moves": len(program.moves), "arcs": arcs,
        "cycle_time_s": plan.cycle_time_s, "cycle_time_min": plan.cycle_time_s / 60.0,
        "samples": samples, "samples_taylor": samples_taylor,
        "parse_s": parse_s, "plan_s": plan_s, "parse_plus_plan_s": parse_s + plan_s,
        "interp_exact_s": interp_exact_s, "interp_taylor_s": interp_taylor_s,
        "setpoints_per_s": samples / work_s,
        "realtime_ratio": plan.cycle_time_s / work_s,
        "plan_cpu_s": plan_cpu_s, "interp_exact_cpu_s": interp_cpu_s,
        "realtime_ratio_cpu": plan.cycle_time_s / (plan_cpu_s + interp_cpu_s),
        "realtime_ratio_taylor": plan.cycle_time_s / (plan_s + interp_taylor_s),
        "realtime_ratio_incl_parse": plan.cycle_time_s / (parse_s + work_s),
        "first_setpoint_ms": stream["first_setpoint_ms"],
        "stream_s": stream["stream_s"],
        "stream_samples": stream["samples"],
        "peak_rss_mb_streaming": stream["peak_rss_mb"],
    }


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m bench.bench_plan")
    p.add_argument("--only", choices=sorted(PROGRAMS))
    p.add_argument("--ts", type=float, default=0.001)
    p.add_argument("--stream-child", choices=sorted(PROGRAMS), help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    if args.stream_child:
        stream_child(args.stream_child, args.ts)
        return 0
    results = {}
    for name in ([args.only] if args.only else list(PROGRAMS)):
        r = bench_one(name, args.ts)
        results[name] = r
        print(f"{name:17s} {r['lines']:6d} lines {r['arcs']:5d} arcs  cycle {r['cycle_time_min']:5.1f} min  "
              f"{r['samples'] / 1e6:5.2f} M set-points | parse {r['parse_s']:.3f} s  "
              f"plan {r['plan_s']:.3f} s  "
              f"interp exact {r['interp_exact_s']:.3f} s  taylor {r['interp_taylor_s']:.3f} s | "
              f"{r['setpoints_per_s'] / 1e6:.2f} M/s  x{r['realtime_ratio']:.0f} real time "
              f"(CPU time: x{r['realtime_ratio_cpu']:.0f}) | "
              f"first set-point {r['first_setpoint_ms']:.1f} ms  peak {r['peak_rss_mb_streaming']:.0f} MB",
              flush=True)
    fin = results.get("sphere_finishing")
    if fin:
        results["targets"] = {
            "finishing_realtime_ratio_ge_2000": fin["realtime_ratio"] >= 2000,
            "first_setpoint_lt_50ms": all(r["first_setpoint_ms"] < 50 for r in results.values()
                                          if isinstance(r, dict) and "first_setpoint_ms" in r),
            "peak_streaming_lt_300mb": all(r["peak_rss_mb_streaming"] < 300 for r in results.values()
                                           if isinstance(r, dict) and "peak_rss_mb_streaming" in r),
        }
    print(json.dumps(results))
    return 0


if __name__ == "__main__":
    sys.exit(main())
