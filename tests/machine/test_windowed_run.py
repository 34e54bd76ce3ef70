"""A long program runs from a plan made as it runs (``planner.motion.window``), holding a few segments
around the point it executes instead of the whole plan: every set-point is the one the whole
plan gives, with overrides, holds, pause points and taps, and the held plan stays bounded."""

from __future__ import annotations

import numpy as np
import pytest

from app.machine.config import load_config
from planner.core.machine import MachineSpec
from planner.motion.meter import check_limits
from resources import shipped_machine
from tests.machine.test_timescale import assert_within, run
from tests.planner.motion_programs import short_move_raster


@pytest.fixture(scope="module")
def machine() -> MachineSpec:
    return load_config(shipped_machine("xyz_mill")).machine


def zigzag(rows: int, step_mm: float = 0.4, width_mm: float = 12.0) -> str:
    """A raster of short lines with a stop, a dwell, a spindle change and a tap on the way."""
    out = ["G21 G90 G0 X0 Y0 Z5", "S800 M3", "G1 Z0 F900"]
    for r in range(rows):
        y = r * step_mm
        out.append(f"G1 X{width_mm if r % 2 == 0 else 0.0:.3f} Y{y:.3f} F{1200 + 300 * (r % 3)}")
        out.append(f"G1 Y{y + step_mm / 2:.3f}")
        if r == rows // 4:
            out.append("M0")
        if r == rows // 2:
            out.append("G4 P0.2\nS1200")
        if r == 3 * rows // 4:
            out.append("G0 Z5\nG84 X6 Y1 Z-4 R2 F1500\nG80\nG1 Z0 F900")
    out.append("G0 Z5\nM2")
    return "\n".join(out) + "\n"


ACTIONS = {300: ("feed", 1.6), 1500: ("hold", 1.0), 2200: ("hold", 0.0), 4000: ("feed", 0.4),
           6000: ("feed", 1.0), 9000: ("feed_hold", 1.0), 9600: ("feed_hold", 0.0)}


@pytest.mark.parametrize("window_moves", [8, 64])
def test_a_window_plays_the_very_set_points_of_the_whole_plan(machine, window_moves: int) -> None:
    text = zigzag(120)
    whole = run(machine, text, dict(ACTIONS))
    held: list[int] = []
    win = run(machine, text, dict(ACTIONS), window_moves=window_moves, held=held)
    prog = whole[0]
    assert len(prog.moves) > 240
    for a, b in zip(whole[3:], win[3:], strict=True):          # q, s, move, sigma, tau
        np.testing.assert_array_equal(a, b)
    plan = win[1]
    # segments of whole look-ahead blocks, at least ``window_moves`` moves each
    assert plan.done and plan.segments_made >= len(prog.moves) // (3 * window_moves) >= 1
    assert 0 < max(held) < len(prog.moves)          # never the whole plan (bounds: below)
    np.testing.assert_array_equal(win[3][-1], prog.end_position)
    assert_within(check_limits(win[3], win[4], win[5], machine, plan.ts_s, prog.rapid_moves))


def test_a_feed_hold_in_a_tap_waits_in_a_window_too(machine) -> None:
    text = zigzag(40)
    free = run(machine, text, {}, window_moves=8)
    prog, mv = free[0], free[5]
    tap_in = next(i for i, m in enumerate(prog.moves) if m.line > 0 and prog.override_locks is not None
                  and prog.override_locks[i])
    k = int(np.nonzero(mv == tap_in)[0][0]) + 30
    held = run(machine, text, {k: ("feed_hold", 1.0), k + 3000: ("feed_hold", 0.0)}, window_moves=8)
    sig, tau, plan = held[6], held[7], held[1]
    stood = np.nonzero(sig == 0.0)[0]
    stood = stood[stood > k]
    assert len(stood) > 100
    # at rest where the tap ends, out of the hole
    assert plan.done
    assert prog.moves[tap_in + 1].end[2] == pytest.approx(2.0)
    np.testing.assert_allclose(held[3][stood[0]], prog.moves[tap_in + 1].end, atol=1e-9)
    assert np.all(sig[k:stood[0]] == 1.0)
    assert tau[stood[0]] > tau[k]




def test_the_plan_held_is_bounded_by_the_time_around_the_run_not_the_program(machine) -> None:
    # held: three seconds of plan behind, ahead as far as the braking and its statistics look (a few
    # seconds), in segments of 64 moves; twice the program, the same held
    most = []
    for rows in (60, 120):
        held: list[int] = []
        out = run(machine, short_move_raster(rows), {}, window_moves=64, held=held)
        assert len(out[0].moves) == 21 * rows
        np.testing.assert_array_equal(out[3][-1], out[0].end_position)
        most.append(max(held))
    assert most[1] <= most[0] + 64
    assert most[1] < 0.5 * 21 * 120


# -- the machine: a long program is checked through once and run from a window -------------
def _part(rows: int) -> str:
    """The raster with the spindle on, and an M0 and a way home at its end."""
    text = short_move_raster(rows).replace("G1 F1200", "S1000 M3\nG1 F1200", 1)
    return text.replace("M2", "M0\nG0 X0 Y0\nM2")


PART = _part(40)


@pytest.fixture
def windowed(monkeypatch):
    """Every program counts as long: planned as it runs."""
    from app.machine.motion import plans
    from planner.motion import window

    monkeypatch.setattr(plans, "WINDOWED_RUN_MOVES", 0)
    monkeypatch.setattr(window, "WINDOW_SEGMENT_MOVES", 32)     # segments of a short program


def _job_window(ctl):
    job = ctl.stream.job
    return None if job is None else job.executor.window


def test_a_long_program_is_checked_without_holding_its_plan(qapp, config_path, state_dir,
                                                            monkeypatch) -> None:
    from tests.machine.conftest import make_controller

    ctl = make_controller(config_path, state_dir)
    try:
        assert ctl.load_program(PART, "part.ngc", wait=True)
        whole = ctl.program_info
        from app.machine.motion import plans

        monkeypatch.setattr(plans, "WINDOWED_RUN_MOVES", 0)
        assert ctl.load_program(PART, "part.ngc", wait=True)
        long = ctl.program_info
        assert whole.plan is not None and long.plan is None
        # the check pass plans it the same way: the same time, length and stops
        assert long.plan_end_s == whole.plan_end_s == whole.plan.cycle_time_s
        assert long.cycle_time_s == whole.cycle_time_s
        assert long.length_mm == pytest.approx(whole.length_mm, rel=1e-12)
        assert [(p.tau_s, p.kind) for p in long.stops] == [(p.tau_s, p.kind) for p in whole.stops]
    finally:
        ctl.shutdown()


def test_a_long_program_runs_holds_and_ends_exactly(qapp, config_path, state_dir, windowed) -> None:
    from app.machine.model import MachineState
    from tests.machine.conftest import make_controller, run_to_idle
    from tests.machine.test_controller import assert_within_limits

    ctl = make_controller(config_path, state_dir)
    try:
        # held: some 14 s of motion around the point it runs (braking statistics ahead); the
        # program runs 55 s
        assert ctl.load_program(_part(90), "part.ngc", wait=True)
        n = ctl.program_info.move_count
        assert ctl.cycle_start()
        assert isinstance(ctl.stream.job.plan, type(_job_window(ctl)))
        ctl.advance(1.0)
        assert ctl.feed_hold()
        assert ctl.run_until(lambda: ctl.stream.job.executor.held
                             and ctl.stream.consumed() >= ctl.stream.pushed_total, 5)
        held_at = np.array(ctl.machine_position)
        ctl.advance(0.5)
        np.testing.assert_array_equal(ctl.machine_position, held_at)    # standing on the path
        assert ctl.resume()
        most = 0
        for _ in range(2000):
            if ctl.state is MachineState.HOLD:                         # the M0 near the end
                assert "M00" in ctl.state_reason
                assert ctl.cycle_start()
            if ctl.state is MachineState.IDLE:
                break
            ctl.advance(0.05)
            win = _job_window(ctl)
            if win is not None:
                most = max(most, len(win.segment.table))
        run_to_idle(ctl)
        assert ctl.last_run.completed
        assert_within_limits(ctl.last_run.limits)
        np.testing.assert_allclose(ctl.machine_position, [0.0, 0.0, 0.0], atol=1e-9)
        assert 0 < most < n / 2                                         # never the whole plan
        assert ctl.last_run.estimated_s == pytest.approx(ctl.program_info.cycle_time_s, abs=1e-9)
    finally:
        ctl.shutdown()


def test_a_long_program_in_single_block_starts_at_once(qapp, config_path, state_dir, windowed) -> None:
    from app.machine.model import HoldKind, MachineState
    from tests.machine.conftest import make_controller

    ctl = make_controller(config_path, state_dir)
    try:
        assert ctl.load_program(PART, "part.ngc", wait=True)
        assert ctl.set_single_block(True)
        assert ctl.cycle_start()
        assert not ctl.loading                     # nothing to plan first: it plans as it runs
        assert ctl.state is MachineState.RUNNING
        assert ctl.run_until(lambda: ctl.state is MachineState.HOLD, 10)
        assert ctl.hold_kind is HoldKind.SINGLE_BLOCK
        first = ctl.current_line
        assert ctl.cycle_start()
        assert ctl.run_until(lambda: ctl.state is MachineState.HOLD, 10)
        assert ctl.current_line > first
        assert ctl.stop() and ctl.run_until(lambda: ctl.state is MachineState.IDLE, 5)
    finally:
        ctl.shutdown()


def test_a_long_program_stopped_by_an_alarm_resumes_where_it_stopped(qapp, config_path, state_dir,
                                                                    windowed) -> None:
    from app.machine.model import MachineState
    from tests.machine.conftest import make_controller, run_to_idle

    ctl = make_controller(config_path, state_dir)
    try:
        assert ctl.load_program(PART, "part.ngc", wait=True)
        assert ctl.cycle_start()
        ctl.advance(2.0)
        ctl.alarm_log.alarm_stop("test: coolant pressure lost", "controller", "test")
        assert ctl.run_until(lambda: ctl.stream.job is None, 5)
        stopped_line = ctl.current_line
        assert stopped_line > 3
        assert ctl.reset() and ctl.run_until(lambda: ctl.state is MachineState.IDLE, 5)
        lines: list[int] = []
        ctl.lineChanged.connect(lines.append)
        assert ctl.resume()
        for _ in range(600):
            if ctl.state is MachineState.HOLD:
                assert ctl.cycle_start()
            if ctl.state is MachineState.IDLE:
                break
            ctl.advance(0.1)
        run_to_idle(ctl)
        assert ctl.last_run.completed
        np.testing.assert_allclose(ctl.machine_position, [0.0, 0.0, 0.0], atol=1e-9)
        assert lines and min(lines) >= stopped_line                     # on from where it stopped
    finally:
        ctl.shutdown()


def test_a_window_already_moved_cannot_give_its_pause_points(machine) -> None:
    # they come from each segment as it is made: a window planned ahead already would miss some
    from app.machine.motion.timescale import Budget, PauseFeed, TimeScaledExecutor, reduced_machine
    from planner.gcode.interpreter import parse_program
    from planner.motion.window import PlanWindow

    prog = parse_program(zigzag(10), machine=machine)
    win = PlanWindow(prog, reduced_machine(machine, Budget()), segment_moves=8)
    win.ensure(1.0)
    with pytest.raises(ValueError, match="not yet moved"):
        TimeScaledExecutor(win, machine, Budget(), pause_feed=PauseFeed(prog, False, True))


def test_the_window_benchmark_asks_for_the_set_points_it_is_told(tmp_path) -> None:
    from bench import bench_window

    program = tmp_path / "square.ngc"
    program.write_text("G1 X10 F600\nG1 Y10\nG1 X0\nG1 Y0\nM30\n", encoding="utf-8")
    report = bench_window.run(program, 60.0, call_samples=3)
    # 40 mm at 10 mm/s with three stops: a little over 4 s of motion, all of it, 3 set-points a call
    assert report["call_samples"] == 3 and 4.0 < report["motion_s"] < 5.0
    assert report["calls"] >= report["motion_s"] / (3 * 0.001)
    with pytest.raises(SystemExit):
        bench_window.main(["--program", str(program), "--call-samples", "0"])
