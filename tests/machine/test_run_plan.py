"""Cycle start runs the plan made at load time (no planning in the GUI thread); what makes it
stale (configuration, work offsets, a move since loading, single block) is checked or planned
again in the worker thread, cycle start refused meanwhile, with the synchronous path's result."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

import app.machine.motion.plans as plans
from app.machine.controller import MachineController
from app.machine.model import Activity, MachineState
from tests.machine.conftest import run_to_idle
from tests.machine.test_program_load import big_program

SHORT = "G0 X5 Y0\nG1 X20 F1800\nG3 X20 Y20 R10\nG1 X5\nM30\n"


@pytest.fixture
def plan_calls(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """Counts the planner calls of the controller (load, re-check, jobs)."""
    calls: list[int] = []
    real = plans.plan_program

    def counting(program, machine, *args, **kwargs):  # noqa: ANN001, ANN002, ANN003
        calls.append(len(program.moves))
        return real(program, machine, *args, **kwargs)

    monkeypatch.setattr(plans, "plan_program", counting)
    return calls


def same_plan(a, b) -> None:  # noqa: ANN001
    assert a.cycle_time_s == b.cycle_time_s
    np.testing.assert_array_equal(a.t0, b.t0)
    np.testing.assert_array_equal(a.t1, b.t1)


def test_cycle_start_reuses_the_load_time_plan(ctl: MachineController, plan_calls: list[int]) -> None:
    # 150 lines of 3 degree kinks, each crossed within the jerk limit: 28 s of motion
    assert ctl.load_program(big_program(150), wait=True)
    assert len(plan_calls) == 1
    assert ctl.cycle_start()
    assert len(plan_calls) == 1  # nothing planned at cycle start
    assert ctl.stream.job is not None and ctl.stream.job.plan is ctl.plan
    run_to_idle(ctl, 60)
    assert ctl.last_run.completed


def test_config_change_rechecks_in_the_background(qtbot, ctl: MachineController,
                                                  plan_calls: list[int]) -> None:
    text = big_program(400)
    assert ctl.load_program(text, name="big.nc", wait=True)
    old = ctl.program_info
    cfg = ctl.config
    new = replace(cfg, machine=cfg.machine.with_limits(a_max_mm_s2=cfg.machine.limits.a_max_mm_s2 * 0.8))
    with qtbot.waitSignal(ctl.programLoaded, timeout=20_000) as blocker:
        assert ctl.update_config(new)
        assert ctl.loading and ctl.loading_name == "big.nc"
        r = ctl.cycle_start()
        assert not r and "being checked" in r.reason
        assert ctl.program_info is None  # let go as the check starts: its outcome replaces it
    info = blocker.args[0]
    assert not ctl.loading and ctl.program_info is info and info is not old
    assert len(plan_calls) == 2
    # the synchronous path gives the same result
    assert ctl.loader.load_text(text, "big.nc", "")
    sync = ctl.program_info
    assert sync == info and sync is not info
    same_plan(sync.plan, info.plan)
    assert ctl.cycle_start() and len(plan_calls) == 3  # the plan of the check is run
    assert ctl.stream.job.plan is sync.plan


def test_update_config_wait_rechecks_synchronously(ctl: MachineController, plan_calls: list[int]) -> None:
    assert ctl.load_program(SHORT, wait=True)
    cfg = ctl.config
    new = replace(cfg, machine=cfg.machine.with_limits(a_max_mm_s2=700.0))
    assert ctl.update_config(new, wait=True)
    assert not ctl.loading and len(plan_calls) == 2
    assert ctl.cycle_start() and len(plan_calls) == 2


def test_moved_since_loading_rechecks_in_the_background(qtbot, ctl: MachineController,
                                                        plan_calls: list[int]) -> None:
    assert ctl.load_program(SHORT, wait=True)
    assert ctl.mdi("G0 X1 Y2")
    run_to_idle(ctl)
    n = len(plan_calls)  # the MDI block was planned
    messages: list[str] = []
    ctl.message.connect(messages.append)
    with qtbot.waitSignal(ctl.programLoaded, timeout=10_000) as blocker:
        assert ctl.cycle_start()  # accepted once: it starts by itself when checked again
        assert ctl.state is MachineState.IDLE and ctl.loading
        assert "being checked" in ctl.refusal("cycle_start")
    assert any("moved since it was loaded" in m and "starts when ready" in m for m in messages)
    info = blocker.args[0]
    np.testing.assert_allclose(info.program.start_position, (1.0, 2.0, 0.0), atol=1e-9)
    assert ctl.state is MachineState.RUNNING  # no second press
    assert len(plan_calls) == n + 1
    run_to_idle(ctl)
    np.testing.assert_array_equal(ctl.reference_position, (5.0, 20.0, 0.0))


def test_moved_since_loading_with_wait_is_synchronous(ctl: MachineController, plan_calls: list[int]) -> None:
    assert ctl.load_program(SHORT, wait=True)
    assert ctl.mdi("G0 X1 Y2")
    run_to_idle(ctl)
    n = len(plan_calls)
    assert ctl.cycle_start(wait=True)
    assert not ctl.loading and len(plan_calls) == n + 1  # checked again here, its plan run
    assert ctl.stream.job.plan is ctl.plan


def test_offset_change_makes_the_program_stale(qtbot, ctl: MachineController) -> None:
    text = "G0 X5 Y0\nG1 X10 F1800\nM30\n"
    assert ctl.load_program(text, wait=True)
    assert ctl.set_work_offset("G54", (2.0, 0.0, 0.0))
    with qtbot.waitSignal(ctl.programLoaded, timeout=10_000) as blocker:
        assert ctl.cycle_start()
    assert blocker.args[0].bounds_max[0] == pytest.approx(12.0)
    assert ctl.state is MachineState.RUNNING
    run_to_idle(ctl)
    np.testing.assert_array_equal(ctl.reference_position, (12.0, 0.0, 0.0))


def test_single_block_plan_is_made_in_the_background(qtbot, ctl: MachineController,
                                                     plan_calls: list[int]) -> None:
    assert ctl.load_program(SHORT, wait=True)
    loading: list[tuple[bool, str]] = []
    ctl.loadingChanged.connect(lambda on, name: loading.append((on, name)))
    with qtbot.waitSignal(ctl.loadingChanged, timeout=10_000, check_params_cb=lambda on, _n: not on):
        assert ctl.set_single_block(True)  # planned at once, in the worker thread
        assert ctl.loading
        r = ctl.cycle_start()
        assert not r and "planned for single block" in r.reason
    assert not ctl.loading and loading == [(True, "<text>"), (False, "<text>")]
    assert len(plan_calls) == 2
    assert ctl.cycle_start() and len(plan_calls) == 2
    job_plan = ctl.stream.job.plan
    assert all(m.exact_stop for m in job_plan.program.moves)
    sync = plans.plan_program(plans.single_block_program(ctl.program_info.program),
                               plans.reduced_machine(ctl.coordinates.machine(), ctl.settings.budget))
    same_plan(job_plan, sync)
    stops = 0
    while ctl.state is not MachineState.IDLE:
        assert ctl.run_until(lambda: ctl.state in (MachineState.HOLD, MachineState.IDLE), 10)
        if ctl.state is MachineState.HOLD:
            stops += 1
            assert ctl.cycle_start()
    assert stops == 3
    assert ctl.set_single_block(False)
    assert ctl.cycle_start()  # moved: accepted, checked again (off-thread) first ...
    assert ctl.state is MachineState.IDLE and "being checked" in ctl.refusal("cycle_start")
    assert ctl.wait_loaded(None)  # ... and started as soon as that check is done
    assert ctl.state is MachineState.RUNNING


def test_a_waiting_cycle_start_is_cancelled_by_stop_and_by_a_failed_check(
        qtbot, ctl: MachineController) -> None:
    assert ctl.load_program(SHORT, wait=True)
    assert ctl.mdi("G0 X1 Y2")
    run_to_idle(ctl)
    with qtbot.waitSignal(ctl.programLoaded, timeout=10_000):
        assert ctl.cycle_start()
        assert ctl.stop()  # the operator changes their mind while it is checked again
    assert ctl.state is MachineState.IDLE
    # a re-check that fails (the move made the program cross a soft limit) starts nothing
    assert ctl.load_program("G91 G1 X240 F1800\nM30\n", wait=True)
    with qtbot.waitSignal(ctl.programErrors, timeout=10_000):
        assert ctl.cycle_start()  # first run from X1: fine, then ...
        run_to_idle(ctl)
        assert ctl.cycle_start()  # ... from X241 the same incremental move leaves the travel
    assert ctl.state is MachineState.IDLE and ctl.program_info is None


def test_run_from_line_after_a_move_is_pressed_once(qtbot, ctl: MachineController) -> None:
    """After a stop the machine has moved: run from line checks the program again and then
    starts from that line by itself: the operator presses once."""
    assert ctl.load_program("G0 X5 Y0\nG1 X10 F600\nG1 Y10\nM30\n", wait=True)
    assert ctl.mdi("G0 X1 Y2")
    run_to_idle(ctl)
    messages: list[str] = []
    ctl.message.connect(messages.append)
    with qtbot.waitSignal(ctl.programLoaded, timeout=10_000):
        assert ctl.run_from_line(3)
        assert ctl.state is MachineState.IDLE and ctl.loading
    assert any("starts when ready" in m for m in messages)
    assert ctl.state is MachineState.RUNNING and ctl.activity is Activity.APPROACH   # no second press
    run_to_idle(ctl, 30)
    np.testing.assert_allclose(ctl.reference_position, (10.0, 10.0, 0.0), atol=1e-9)
