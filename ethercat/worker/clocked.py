"""The loop on its clock: one cycle per period on absolute deadlines, with its timing records.

Sleeps to ``spin_s`` before each deadline (clock_nanosleep on an absolute CLOCK_MONOTONIC
deadline) and busy-waits the rest; records period, jitter (start - deadline), execution time
and the jitter histogram in the live record; a cycle that overran by whole periods skips
them (counted as missed) and the loop stays on its grid. A cycle that raises ends the loop
with a BUS_ERROR alarm and the state ERROR.
"""

from __future__ import annotations

import time
from typing import TYPE_CHECKING

from .realtime import AbsoluteSleep, set_timer_slack_ns
from .shared import HIST_BIN_S, HIST_BINS
from .types import AlarmCode, WorkerState

if TYPE_CHECKING:
    from .cycle import CycleLoop

__all__ = ["run_clocked"]


def run_clocked(loop: CycleLoop, default_spin_s: float = 0.0) -> None:
    """The cyclic loop on absolute deadlines until Command.STOP."""
    cfg = loop.cfg
    ts = cfg.ts_s
    spin = cfg.spin_s if cfg.spin_s is not None else default_spin_s
    min_sleep = cfg.min_sleep_s
    late_s = cfg.late_threshold_s
    lv = loop.lv
    hist = lv.hist
    perf = time.perf_counter
    sleep_until = AbsoluteSleep().until
    set_timer_slack_ns(1)                    # normal threads: 50 us slack by default
    inv_bin = 1.0 / HIST_BIN_S
    last_bin = HIST_BINS - 1
    every = loop.snapshot_every
    deadline = perf() + ts
    prev_start = 0.0
    k_snap = 0
    missed = 0
    loop.publish_now = True                  # publish after the first cycle
    while not loop.stop_requested:
        # sleep to `spin` before the deadline (absolute), and always at least min_sleep,
        # then busy-wait the rest: bounded by `spin`, none when already late
        wake = deadline - spin
        earliest = perf() + min_sleep
        sleep_until(wake if wake > earliest else earliest)
        while perf() < deadline:
            pass
        start = perf()
        jitter = start - deadline
        if missed:
            lv.missed[...] = int(lv.missed) + missed   # counted when the deadline after them starts
            missed = 0
        try:
            loop.cycle()
        except Exception as exc:  # noqa: BLE001 - any bus failure ends the loop with an alarm
            loop.block.write_msg(f"{type(exc).__name__}: {exc}")
            loop._alarm(AlarmCode.BUS_ERROR)
            loop._set_state(WorkerState.ERROR)
            loop.publish()
            return
        end = perf()
        # timing records
        if prev_start > 0.0:
            period = start - prev_start
            lv.period_sum[...] = float(lv.period_sum) + period
            if period < lv.period_min:
                lv.period_min[...] = period
            if period > lv.period_max:
                lv.period_max[...] = period
            lv.timed[...] = int(lv.timed) + 1
            b = int(jitter * inv_bin)
            hist[b if b < last_bin else last_bin] += 1
            if jitter > lv.jitter_max:
                lv.jitter_max[...] = jitter
            if jitter > late_s:
                lv.late[...] = int(lv.late) + 1
            ex = end - start
            lv.exec_sum[...] = float(lv.exec_sum) + ex
            if ex > lv.exec_max:
                lv.exec_max[...] = ex
        else:
            lv.first_start[...] = start
        lv.last_start[...] = start
        prev_start = start
        deadline += ts
        if end - deadline >= ts:              # overran by whole periods: skip them, stay on grid
            missed = int((end - deadline) / ts)
            deadline += missed * ts
        k_snap += 1
        if k_snap >= every or loop.publish_now:
            k_snap = 0
            loop.publish_now = False
            loop.publish()
    loop.publish()
