"""Where the program turns the overrides off (G74/G84 and G33.1 tapping, M49, M50 P0, M51 P0),
the machine runs the program's own feed and spindle speed whatever the operator's knobs say,
as LinuxCNC does; elsewhere the knobs act as before. Every limit holds either way."""

from __future__ import annotations

import numpy as np
import pytest

from app.machine.config import load_config
from planner.core.machine import MachineSpec
from planner.core.program import FEED_OVERRIDE_OFF
from planner.motion.meter import check_limits
from resources import shipped_machine
from tests.machine.test_timescale import assert_within, run

TAPPING = """G21 G90 G0 X0 Y0 Z10
S500 M3
G1 X60 F900
G84 X80 Z-12 R2 F625
G80
G1 X140 F900
G33.1 Z-8 K1.25
G0 Z10
M2
"""


@pytest.fixture(scope="module")
def machine() -> MachineSpec:
    return load_config(shipped_machine("xyz_mill")).machine


def moves_where(prog, bit: int) -> set[int]:
    locks = prog.override_locks
    assert locks is not None
    return {int(i) for i in np.nonzero(locks & bit)[0]}


@pytest.mark.parametrize("override", [1.5, 0.5])
def test_taps_run_at_the_programmed_feed_whatever_the_feed_override(machine, override: float) -> None:
    prog, plan, ex, q, s, mv, sig, tau = run(machine, TAPPING, {0: ("feed", override)})
    taps = moves_where(prog, FEED_OVERRIDE_OFF)
    # the G84 feed in and out, the G33.1 move in and out
    assert [prog.moves[i].line for i in sorted(taps)] == [4, 4, 7, 7]
    # every set-point of the taps, from their start (at rest: a pause point, where the time
    # scale changes without moving) to their end, runs at the programmed feed: the tap's pitch
    # is the feed over the spindle speed
    seg = plan.segment
    in_tap = np.isin(mv, sorted(taps)) & (tau > seg.t0[mv] + 1e-12)
    assert in_tap.sum() > 3000
    assert np.all(np.abs(sig[in_tap] - 1.0) < 1e-12)
    # the plain G1 moves take the override
    plain = np.isin(mv, [i for i, m in enumerate(prog.moves) if m.line in (3, 6)])
    assert np.any(np.abs(sig[plain] - override) < 1e-9)
    assert_within(check_limits(q, s, mv, machine, plan.ts_s, plan.segment.table.is_rapid))
    np.testing.assert_array_equal(q[-1], prog.end_position)


def test_m49_and_m50_p0_hold_the_feed_until_m48_or_m50(machine) -> None:
    text = ("G21 G90 G0 X0 Y0 Z0\nG1 X40 F900\nM49\nG1 X80\nM48\nG1 X120\nM50 P0\nG1 X160\n"
            "M50\nG1 X200\nM2\n")
    prog, plan, ex, q, s, mv, sig, tau = run(machine, text, {0: ("feed", 1.6)})
    line_of = np.array([prog.moves[i].line for i in mv])
    for line, sigma in ((2, 1.6), (4, 1.0), (6, 1.6), (8, 1.0), (10, 1.6)):
        assert np.any(np.abs(sig[line_of == line] - sigma) < 1e-9), line
        assert sig[line_of == line].max() <= max(sigma, 1.6 if line in (2, 6, 10) else 1.0) + 1e-12
    assert_within(check_limits(q, s, mv, machine, plan.ts_s, plan.segment.table.is_rapid))


def _into_first_tap(machine, set_points: int) -> tuple[int, list[int]]:
    """The set-point ``set_points`` into the first tap's feed in, and the tap moves."""
    free = run(machine, TAPPING, {})
    prog, mv_free = free[0], free[5]
    taps = sorted(moves_where(prog, FEED_OVERRIDE_OFF))
    return int(np.nonzero(mv_free == taps[0])[0][0]) + set_points, taps


def test_a_feed_hold_in_a_tap_waits_until_the_tap_is_out_of_the_hole(machine) -> None:
    # axes standing with the tap in the hole while the spindle turns strip the thread or break
    # the tap: the hold takes effect where the tap ends, at rest above the hole (LinuxCNC holds
    # spindle-synchronised motion to its end, Fanuc a G84 to its return)
    k_in, taps = _into_first_tap(machine, 40)
    prog, plan, ex, q, s, mv, sig, tau = run(machine, TAPPING, {k_in: ("feed_hold", 1.0),
                                                                k_in + 3000: ("feed_hold", 0.0)})
    stood = np.nonzero(sig == 0.0)[0]
    stood = stood[stood > k_in]
    assert len(stood) > 100
    first = stood[0]
    tap_end = plan.segment.t0[taps[1]] + plan.segment.profiles.duration[taps[1]]
    assert tau[first] == pytest.approx(tap_end, abs=1e-12)     # at the end of the tap's way out
    # the tap ran at the programmed feed all the way out: never slowed by the hold
    inside = (mv > taps[0] - 1) & (mv <= taps[1]) & (np.arange(len(mv)) > k_in) & (tau < tap_end)
    assert inside.sum() > 100 and np.all(sig[inside] == 1.0)
    np.testing.assert_allclose(q[first][2], 2.0, atol=1e-9)       # at R, out of the hole
    np.testing.assert_array_equal(q[-1], prog.end_position)
    assert_within(check_limits(q, s, mv, machine, plan.ts_s, plan.segment.table.is_rapid))


def test_a_stop_in_a_tap_stops_it_at_once(machine) -> None:
    # a stop, an alarm or a probe's contact holds where the tool is, in a tap too
    k_in, taps = _into_first_tap(machine, 40)
    prog, plan, ex, q, s, mv, sig, tau = run(machine, TAPPING, {k_in: ("hold", 1.0),
                                                                k_in + 1500: ("hold", 0.0)})
    stood = np.nonzero(sig == 0.0)[0]
    stood = stood[stood > k_in]
    assert len(stood) > 0
    assert int(mv[stood[0]]) == taps[0]                          # it stood inside the tap
    np.testing.assert_array_equal(q[-1], prog.end_position)
    assert_within(check_limits(q, s, mv, machine, plan.ts_s, plan.segment.table.is_rapid))


def test_a_feed_hold_before_a_tap_stands_before_it(machine) -> None:
    # at rest above the hole, the tap not yet started: the hold takes effect there
    free = run(machine, TAPPING, {})
    prog, mv_free = free[0], free[5]
    taps = sorted(moves_where(prog, FEED_OVERRIDE_OFF))
    k_before = int(np.nonzero(mv_free == taps[0])[0][0]) - 30     # on the rapid down to R
    prog, plan, ex, q, s, mv, sig, tau = run(machine, TAPPING, {k_before: ("feed_hold", 1.0),
                                                                k_before + 2000: ("feed_hold", 0.0)})
    stood = np.nonzero(sig == 0.0)[0]
    stood = stood[stood > k_before]
    assert len(stood) > 100
    assert int(mv[stood[0]]) < taps[0]
    assert tau[stood[0]] <= plan.segment.t0[taps[0]] + 1e-12


def test_m53_p0_leaves_the_feed_hold_working(machine) -> None:
    # M53 switches LinuxCNC's feed stop input, which this machine does not have: the panel's
    # feed hold (LinuxCNC's pause) stops the motion whatever a program says
    text = "G21 G90 G0 X0 Y0 Z0\nM53 P0\nG1 X80 F900\nM2\n"
    prog, plan, ex, q, s, mv, sig, tau = run(machine, text, {200: ("hold", 1.0), 1200: ("hold", 0.0)})
    assert np.all(sig[900:1200] == 0.0)                        # held, standing on the path
    np.testing.assert_array_equal(q[-1], prog.end_position)


def test_the_machine_taps_at_the_programmed_speed_and_says_why(qapp, config_path, state_dir) -> None:
    """A run at 150 % feed and 120 % spindle override: the spindle turns at S while it taps (the
    reversal at the bottom too), the operator is told the feed override does not apply there,
    and after the tap both knobs act again."""
    from app.machine.model import SpindleState
    from tests.machine.conftest import make_controller, run_to_idle

    ctl = make_controller(config_path, state_dir)
    try:
        spindles: list[SpindleState] = []
        messages: list[str] = []
        notes: list[str] = []
        ctl.spindleChanged.connect(spindles.append)
        ctl.message.connect(messages.append)
        ctl.feedOverrideNote.connect(notes.append)
        text = "G21 G90 G0 X0 Y0 Z5\nS1000 M3\nG84 X20 Z-6 R1 F1250\nG80\nG1 X40 F600\nM5\nM2\n"
        assert ctl.load_program(text, "tap.ngc", wait=True)
        assert ctl.set_feed_override(150)
        assert ctl.set_spindle_override(120)
        assert ctl.cycle_start()
        run_to_idle(ctl)
        turning = [(s.direction, round(s.commanded_rpm)) for s in spindles if s.on]
        # on at 120 %; at S from where the tap starts (at rest above the hole), into the hole
        # forward, out reversed, forward again at its top; 120 % once the tap is done
        assert turning == [(1, 1200), (1, 1000), (-1, 1000), (1, 1000), (1, 1200)]
        assert any("not applied here: the program turned it off" in m for m in messages)
        # the Auto page's feed override says so while the tap runs, and nothing once it is done
        assert "runs 100 %: program" in notes and notes[-1] == ""
    finally:
        ctl.shutdown()


def test_mdi_takes_m48_to_m51_only_with_a_move(ctl) -> None:
    r = ctl.mdi("M49")
    assert not r and "put the code in the block with the move" in r.reason
    assert ctl.mdi("M49 G91 G1 X1 F300")


DEEP_TAP = "G21 G90 G0 X0 Y0 Z5\nS1000 M3\nG84 X20 Z-20 R1 F1250\nG80\nG1 X40 F600\nM5\nM2\n"


def _into_the_hole(ctl, below_mm: float, feed_pct: float = 100.0) -> None:
    """``DEEP_TAP`` loaded and started, the machine run until the tap is ``below_mm`` deep."""
    assert ctl.load_program(DEEP_TAP, "tap.ngc", wait=True)
    assert ctl.set_feed_override(feed_pct)
    assert ctl.cycle_start()
    assert ctl.run_until(lambda: ctl.current_line == 3 and ctl.machine_position[2] < -below_mm, 20)


def test_the_operator_is_told_a_feed_hold_waits_for_the_tap(qapp, config_path, state_dir) -> None:
    from app.machine.model import MachineState
    from tests.machine.conftest import make_controller, run_to_idle

    ctl = make_controller(config_path, state_dir)
    try:
        _into_the_hole(ctl, 8.0)
        assert ctl.feed_hold()
        assert ctl.state is MachineState.HOLD
        assert "the tap runs out of the hole first" in ctl.state_reason
        assert ctl.run_until(lambda: ctl.stream.job.executor.held
                             and ctl.stream.consumed() >= ctl.stream.pushed_total, 10)
        assert ctl.machine_position[2] == pytest.approx(1.0, abs=1e-6)   # at R, out of the hole
        assert ctl.spindle.on                                            # a feed hold only
        assert ctl.resume()
        run_to_idle(ctl)
        assert ctl.last_run.completed
    finally:
        ctl.shutdown()


def test_stop_after_a_waiting_feed_hold_stops_the_tap_at_once(qapp, config_path, state_dir) -> None:
    # the feed hold waits for the tap; the operator's stop does not wait for the feed hold
    from app.machine.model import MachineState
    from tests.machine.conftest import make_controller

    ctl = make_controller(config_path, state_dir)
    try:
        _into_the_hole(ctl, 6.0)
        assert ctl.feed_hold()
        ctl.advance(0.05)
        z = ctl.machine_position[2]
        assert ctl.stop()
        assert ctl.run_until(lambda: ctl.state is MachineState.IDLE, 5)
        assert ctl.machine_position[2] == pytest.approx(z, abs=2.0)
        assert not ctl.spindle.on
    finally:
        ctl.shutdown()


def test_a_tap_resumed_from_a_stop_inside_it_still_runs_at_the_programmed_feed(qapp, config_path,
                                                                             state_dir) -> None:
    """Stopped halfway into the hole by an alarm at 150 % feed override, then resumed from
    that point (the rest of the program planned again from it): the rest of the tap keeps the
    overrides off, though what turned them off lies behind that point."""
    from app.machine.model import MachineState
    from tests.machine.conftest import make_controller, run_to_idle

    ctl = make_controller(config_path, state_dir)
    try:
        _into_the_hole(ctl, 8.0, feed_pct=150)
        alarm_z = ctl.machine_position[2]
        ctl.alarm_log.alarm_stop("test: coolant pressure lost", "controller", "test")
        assert ctl.run_until(lambda: ctl.stream.job is None, 5)
        # an alarm stops at once, in the hole too (not at the bottom, nor out of it)
        assert ctl.machine_position[2] == pytest.approx(alarm_z, abs=2.0)
        assert ctl.reset()
        assert ctl.run_until(lambda: ctl.state is MachineState.IDLE, 5)
        assert ctl.resume()
        sigmas: list[float] = []
        for _ in range(3000):
            if ctl.state is MachineState.IDLE:
                break
            ctl.advance(0.02)
            job = ctl.stream.job
            if job is None:
                continue
            move = job.move_at(ctl.stream.consumed())
            tap_feed = move is not None and job.plan.program.moves[move].line == 3 \
                and job.plan.program.moves[move].kind.name == "LINE"
            if tap_feed and job.executor.sigma > 0.0:
                sigmas.append(job.executor.sigma)
        run_to_idle(ctl)
        assert ctl.last_run.completed
        assert len(sigmas) > 20                               # the rest of the tap, in and out
        assert max(sigmas) <= 1.0 + 1e-12
    finally:
        ctl.shutdown()
