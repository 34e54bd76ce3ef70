"""Where the program turns the overrides off (G74/G84 and G33.1 tapping, M49, M50 P0, M51 P0),
the machine runs the program's own feed and spindle speed whatever the operator's knobs say,
as LinuxCNC does; elsewhere the knobs act as before. Every limit holds either way."""

from __future__ import annotations

import numpy as np
import pytest

from app.machine.config import load_config
from planner.machine import MachineSpec
from planner.meter import check_limits
from planner.program import FEED_OVERRIDE_OFF
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


def test_holding_a_tap_still_stops_it(machine) -> None:
    # the operator's feed hold is never turned off: a tap stops on the path when held
    free = run(machine, TAPPING, {})
    prog, mv_free = free[0], free[5]
    taps = sorted(moves_where(prog, FEED_OVERRIDE_OFF))
    k_in = int(np.nonzero(mv_free == taps[0])[0][0]) + 40      # 40 set-points into the G84's feed
    prog, plan, ex, q, s, mv, sig, tau = run(machine, TAPPING, {k_in: ("hold", 1.0),
                                                                k_in + 1500: ("hold", 0.0)})
    stood = np.nonzero(sig == 0.0)[0]
    stood = stood[stood > k_in]
    assert len(stood) > 0
    assert int(mv[stood[0]]) == taps[0]                          # it stood inside the tap
    np.testing.assert_array_equal(q[-1], prog.end_position)
    assert_within(check_limits(q, s, mv, machine, plan.ts_s, plan.segment.table.is_rapid))


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


def test_a_tap_planned_again_from_a_hold_inside_it_still_runs_at_the_programmed_feed(qapp, config_path,
                                                                                    state_dir) -> None:
    """Held halfway into the hole at 150 % feed override, single block switched on (the rest
    of the program is planned again from the point it stands at), then resumed: the rest of
    the tap keeps the overrides off, though what turned them off lies behind that point."""
    from app.machine.model import MachineState
    from tests.machine.conftest import make_controller, run_to_idle

    ctl = make_controller(config_path, state_dir)
    try:
        text = "G21 G90 G0 X0 Y0 Z5\nS1000 M3\nG84 X20 Z-20 R1 F1250\nG80\nG1 X40 F600\nM5\nM2\n"
        assert ctl.load_program(text, "tap.ngc", wait=True)
        assert ctl.set_feed_override(150)
        assert ctl.cycle_start()
        assert ctl.run_until(lambda: ctl.current_line == 3 and ctl.machine_position[2] < -8.0, 20)
        assert ctl.feed_hold()
        assert ctl.run_until(lambda: ctl.state is MachineState.HOLD and ctl.stream.job.executor.standing
                             and ctl.stream.consumed() >= ctl.stream.pushed_total, 10)
        held_at = ctl.stream.job
        assert ctl.set_single_block(True)
        ctl.loader.wait_run_plan(None)
        assert ctl.resume()
        ctl.advance(0.05)
        assert ctl.stream.job is not held_at                  # the rest, planned again from the hold
        sigmas: list[float] = []
        for _ in range(2000):
            if ctl.state is MachineState.IDLE:
                break
            if ctl.state is MachineState.HOLD:                # single block: each block's end
                assert ctl.cycle_start()
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
        assert len(sigmas) > 20                               # the rest of the tap, in and out
        assert max(sigmas) <= 1.0 + 1e-12
    finally:
        ctl.shutdown()
