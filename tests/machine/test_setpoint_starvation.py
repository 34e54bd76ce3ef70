"""Set-points that run out: behind the last set-point pushed the worker's queue always holds a
braking tail (a stop along the path within every limit, ``app.machine.motion.feeding``). When
the feeder falls behind (the panel's process stalled longer than the lead), the drives play the
tail and come to rest on the path; the controller stops the program there with an alarm that
says so, and keeps the point to resume from. Without the tail the worker would hold the last
set-point: a velocity step to zero at full speed."""

from __future__ import annotations

import threading
import time
from pathlib import Path

import numpy as np
import pytest

from app.machine.controller import MachineController
from app.machine.model import MachineState
from tests.machine.test_controller import assert_within_limits
from tests.machine.test_hold_latency import assert_continuous

ARC = "G1 X60 F1800\nG3 X60 Y40 R20\nM30\n"     # the arc: centre (60, 20), radius 20


def _record(ctl: MachineController) -> list[np.ndarray]:
    """Every reference set-point the drives received (machine XY), in order."""
    rows: list[np.ndarray] = []
    ctl.stream.add_trace_sink(lambda _cycles, ref, _act, _lines: rows.append(np.array(ref[:, :2])))
    return rows


def _on_the_arc(ctl: MachineController) -> None:
    held = np.array(ctl.reference_position[:2])
    assert np.hypot(held[0] - 60.0, held[1] - 20.0) == pytest.approx(20.0, abs=1e-6)
    assert 0.0 < held[1] < 40.0                          # inside the arc, not at one of its ends


def _alarm_codes(ctl: MachineController) -> list[str]:
    return [a.code for a in ctl.active_alarms]


def test_the_queue_ends_at_rest_wherever_the_run_is(ctl: MachineController) -> None:
    """At every moment of a run the last set-points queued come to rest: the tail ends there
    (or the run stands at a pause point)."""
    assert ctl.load_program(ARC, wait=True) and ctl.cycle_start(wait=True)
    w = ctl.worker
    checked = 0
    while ctl.state is MachineState.RUNNING:
        ctl.advance(0.037)
        level = w.buffer_level()
        if level < 3:
            continue
        block, cap = w._block, w.config.buffer_capacity
        last = block.ring[(int(block.ctl.head) - 1 - np.arange(3)) % cap]
        np.testing.assert_array_equal(last[0], last[1])          # standing at the end
        assert np.abs(last[1] - last[2]).max() / 0.001 < 1.0       # reached from below 1 mm/s
        checked += 1
    assert checked > 30


def test_a_stalled_feeder_brakes_along_the_path_and_says_so(ctl: MachineController) -> None:
    rows = _record(ctl)
    assert ctl.load_program(ARC, wait=True) and ctl.cycle_start(wait=True)
    while ctl.current_line != 2:
        ctl.advance(0.01)
    ctl.advance(0.2)                                       # on the arc at 30 mm/s
    pushed = ctl.stream.pushed_total
    # the panel's process stalls: the drives run 1.5 s with nothing pushed and nothing polled
    ctl.worker.step(1500)
    assert ctl.worker.samples_consumed() > pushed          # they ran into the tail
    ctl.advance(0.5)                                       # the process comes back
    assert "setpoints_ran_out" in _alarm_codes(ctl)
    assert "underrun" not in _alarm_codes(ctl)             # the worker never held a moving axis
    cause = next(a.cause for a in ctl.active_alarms if a.code == "setpoints_ran_out")
    assert "braked to rest along the path" in cause
    assert ctl.state is MachineState.ALARM
    _on_the_arc(ctl)
    ref = np.concatenate(rows)
    assert_continuous(ref, 0, len(ref))                   # no velocity step anywhere
    np.testing.assert_array_equal(ref[-200:], np.repeat(ref[-1:], 200, axis=0))   # at rest
    assert_within_limits(ctl.last_run.limits)
    assert ctl.resume_line == 2                            # resumable from where it stopped on the arc


def test_after_the_tail_the_program_resumes_from_where_it_stopped(ctl: MachineController) -> None:
    assert ctl.load_program(ARC, wait=True) and ctl.cycle_start(wait=True)
    while ctl.current_line != 2:
        ctl.advance(0.01)
    ctl.advance(0.2)
    ctl.worker.step(1500)
    ctl.advance(0.5)
    assert ctl.state is MachineState.ALARM
    assert ctl.reset()
    assert ctl.state is MachineState.IDLE and ctl.resume_line == 2
    assert not ctl.cycle_start()                           # the operator chooses: resume or restart
    assert ctl.resume()
    t_end = 60.0
    while ctl.state is not MachineState.IDLE and t_end > 0:
        ctl.advance(0.1)
        t_end -= 0.1
    assert ctl.last_run is not None and ctl.last_run.completed
    assert ctl.reference_position[:2] == pytest.approx((60.0, 40.0), abs=1e-9)


def test_a_real_time_stall_of_the_feeder_brakes_on_the_path(qapp, config_path: Path, state_dir: Path) -> None:
    """The worker in real time (a thread); the feeder thread stalled for 1.5 s (its lock held,
    as a long GIL stall would): the drives come to rest on the arc within every limit."""
    ctl = MachineController(config_path, state_dir=state_dir, worker_mode="thread")
    try:
        rows = _record(ctl)
        assert ctl.connect_bus() and ctl.set_machine_zero_here()
        assert ctl.load_program(ARC, wait=True) and ctl.cycle_start()
        t_end = time.monotonic() + 20.0
        while ctl.current_line != 2 and time.monotonic() < t_end:
            time.sleep(0.01)
            qapp.processEvents()
        assert ctl.current_line == 2
        stalled = threading.Event()

        def stall() -> None:
            with ctl.stream._lock:
                stalled.set()
                time.sleep(1.5)

        staller = threading.Thread(target=stall)
        staller.start()
        assert stalled.wait(5.0)
        staller.join()
        t_end = time.monotonic() + 10.0
        while "setpoints_ran_out" not in _alarm_codes(ctl) and time.monotonic() < t_end:
            time.sleep(0.01)
            qapp.processEvents()
        assert "setpoints_ran_out" in _alarm_codes(ctl)
        assert "underrun" not in _alarm_codes(ctl)
        while ctl.stream.job is not None and time.monotonic() < t_end:
            time.sleep(0.01)
            qapp.processEvents()
        ctl.poller.poll()
        _on_the_arc(ctl)
        ref = np.concatenate(rows)
        assert_continuous(ref, 0, len(ref))
        assert_within_limits(ctl.last_run.limits)
    finally:
        ctl.shutdown()
