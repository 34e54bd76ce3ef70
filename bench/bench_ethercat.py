"""Cycle timing of the EtherCAT worker on simulated drives: process vs plain thread, with and
without a CPU-bound Qt GUI load (a pyqtgraph plot redrawn offscreen as fast as it can) in
the parent process.

    QT_QPA_PLATFORM=offscreen python -m bench.bench_ethercat --seconds 20 [--json]
        [--modes process,thread] [--loads idle,gui] [--link 3 | --ifname IF]
        [--spin-us US] [--rt-priority P] [--min-sleep-us US] [--cpu N]

Prints one JSON object: per case (worker mode x load) the period, cycle start jitter
percentiles (p50/p99/p99.9/max), late cycles (start later than 1 ms), missed cycles,
working counter errors. Target: jitter p99 <= 100 us, no cycle later than 1 ms.
`--link N` runs on real frames: an `EmulatedLink` of N emulated drives (root, ip netns),
removed afterwards. The other flags override `WorkerConfig` defaults (for comparisons).

    python -m bench.bench_ethercat --probe 20 [--cpu 1] [--rt-priority 49] [--spin-us 0]

runs no worker: a bare Python loop of absolute clock_nanosleep wake-ups every 1 ms (what
the worker's timing rests on) and attributes every wake-up later than 200 us: the guest
run-queue delay of the thread (/proc/thread-self/schedstat: another task or the RT
throttle held the CPU), its involuntary context switches, and the CPU's steal time (the
hypervisor did not run this virtual CPU; /proc/stat, 10 ms ticks).
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


def probe(seconds: float, cpu: int, rt_priority: int, spin_s: float) -> dict[str, Any]:
    """Wake-up lateness of a bare clock_nanosleep loop, with the cause of each late one."""
    from ethercat.worker.realtime import AbsoluteSleep, set_timer_slack_ns

    applied = []
    if cpu >= 0:
        os.sched_setaffinity(0, {cpu})
        applied.append(f"cpu{cpu}")
    else:
        cpu = -1
    if rt_priority > 0:
        os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(rt_priority))
        applied.append(f"fifo{rt_priority}")
    set_timer_slack_ns(1)
    sched = open("/proc/thread-self/schedstat", "rb", buffering=0)   # noqa: SIM115
    status_path = "/proc/thread-self/status"
    stat = open("/proc/stat", "rb", buffering=0)                     # noqa: SIM115

    def run_delay_ns() -> int:
        sched.seek(0)
        return int(sched.read().split()[1])

    def cpu_ticks() -> tuple[int, int]:
        """(steal, irq + softirq) of the probe's CPU, in 10 ms ticks."""
        stat.seek(0)
        prefix = f"cpu{cpu} ".encode() if cpu >= 0 else b"cpu "
        for line in stat.read().splitlines():
            if line.startswith(prefix):
                f = line.split()
                return int(f[8]), int(f[6]) + int(f[7])
        return 0, 0

    def nonvoluntary() -> int:
        with open(status_path, "rb") as f:
            for line in f:
                if line.startswith(b"nonvoluntary_ctxt_switches"):
                    return int(line.split()[1])
        return 0

    n = int(seconds * 1000)
    late = np.zeros(n)
    stalls: list[dict[str, float]] = []
    until = AbsoluteSleep().until
    perf = time.perf_counter
    rd0, (st0, irq0), nv0 = run_delay_ns(), cpu_ticks(), nonvoluntary()
    steal_start = st0
    deadline = perf() + 0.001
    for k in range(n):
        until(deadline - spin_s)
        while perf() < deadline:
            pass
        lat = perf() - deadline
        late[k] = lat
        rd1, (st1, irq1), nv1 = run_delay_ns(), cpu_ticks(), nonvoluntary()
        if lat > 200e-6:
            stalls.append({"late_us": round(lat * 1e6), "runqueue_wait_us": round((rd1 - rd0) / 1e3),
                           "involuntary_switches": nv1 - nv0, "steal_ms": (st1 - st0) * 10,
                           "irq_softirq_ms": (irq1 - irq0) * 10})
        rd0, st0, irq0, nv0 = rd1, st1, irq1, nv1
        deadline += 0.001
        now = perf()
        if now > deadline:
            deadline += ((now - deadline) // 0.001 + 1) * 0.001
    us = late * 1e6
    big = [x for x in stalls if x["late_us"] > 1000]
    return {
        "probe": "clock_nanosleep", "applied": ",".join(applied) or "none", "spin_us": spin_s * 1e6,
        "cycles": n, "p50_us": float(np.percentile(us, 50)), "p99_us": float(np.percentile(us, 99)),
        "p999_us": float(np.percentile(us, 99.9)), "max_us": float(us.max()),
        "over_100us": int((us > 100).sum()), "over_1ms": int((us > 1000).sum()),
        "steal_ms_total": (cpu_ticks()[0] - steal_start) * 10,
        "over_1ms_late_ms_sum": round(sum(x["late_us"] for x in big) / 1e3, 1),
        "over_1ms_runqueue_wait_ms_sum": round(sum(x["runqueue_wait_us"] for x in big) / 1e3, 1),
        "over_1ms_steal_ms_sum": sum(x["steal_ms"] for x in big),
        "over_1ms_irq_softirq_ms_sum": sum(x["irq_softirq_ms"] for x in big),
        "worst": sorted(stalls, key=lambda x: -x["late_us"])[:8],
    }


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
    ap.add_argument("--probe", type=float, default=0.0, metavar="SECONDS",
                    help="no worker: attribute the late wake-ups of a bare clock_nanosleep loop")
    ap.add_argument("--versus-probe", action="store_true",
                    help="with --link/--ifname: the worker in its process beside the bare loop, "
                         "measured in the same run (half the probe before, half after)")
    args = ap.parse_args(argv)
    if args.probe:
        prio = 49 if args.rt_priority is None else args.rt_priority
        spin = 0.0 if args.spin_us is None else args.spin_us * 1e-6
        print(json.dumps(probe(args.probe, args.cpu, prio, spin)))
        return 0
    with contextlib.ExitStack() as stack:
        bus, ifname = "sim", ""
        if args.link:
            from ethercat.emulator.link import EmulatedLink

            link = stack.enter_context(EmulatedLink(args.link, realtime=True))
            bus, ifname, args.drives = "soem", link.master_ifname, args.link
        elif args.ifname:
            bus, ifname = "soem", args.ifname
        if args.versus_probe:
            return _versus_probe(args, bus, ifname)
        return _run(args, bus, ifname)


def _versus_probe(args: argparse.Namespace, bus: str, ifname: str) -> int:
    """Late cycles of the worker (1 ms loop on the link) against late wake-ups of a bare
    SCHED_FIFO clock_nanosleep loop on the same machine in the same run: what the machine
    allows, next to what the worker achieves. Same priority and spin as the worker's defaults."""
    half = args.seconds / 2.0
    before = probe(half, args.cpu, 49, 0.0001)
    worker = run_bench(bus, ifname, args.seconds, n_drives=args.drives, mode="process", cpu=args.cpu)
    after = probe(half, args.cpu, 49, 0.0001)
    bare_cycles = before["cycles"] + after["cycles"]
    bare_late = before["over_1ms"] + after["over_1ms"]
    out = {
        "bench": "ethercat-versus-probe", "seconds": args.seconds, "bus": bus,
        "worker": {k: worker[k] for k in ("cycles", "late_cycles", "missed_cycles", "wkc_errors",
                                          "jitter_p50_us", "jitter_p99_us", "jitter_p999_us", "jitter_max_us",
                                          "realtime")},
        "bare_loop": {"cycles": bare_cycles, "late_over_1ms": bare_late,
                      "p99_us": max(before["p99_us"], after["p99_us"]),
                      "max_us": max(before["max_us"], after["max_us"]),
                      "steal_ms_total": before["steal_ms_total"] + after["steal_ms_total"]},
    }
    rate_w = worker["late_cycles"] / max(1, worker["cycles"])
    rate_b = bare_late / max(1, bare_cycles)
    out["late_per_1e6_worker"] = round(rate_w * 1e6, 1)
    out["late_per_1e6_bare_loop"] = round(rate_b * 1e6, 1)
    print(json.dumps(out, indent=None if args.json else 1))
    return 0


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
