"""A gantry in the 1 ms loop: axis Y on two drives (Y and its follower Y2), each with its own
home switch. Homing squares the two sides however skewed they start; the follower then takes
its leader's set-points plus the pair's offset; a skew beyond the window stops both drives
with its own alarm."""

from __future__ import annotations

import numpy as np
import pytest

from bench.stepped import enabled as enabled_worker
from ethercat.bus import DriveSpec
from ethercat.errors import ConfigurationError
from ethercat.sim_io import SimSwitch
from ethercat.terminals import TerminalSpec
from ethercat.worker import (
    AlarmCode,
    CyclicWorker,
    GantrySpec,
    HomingState,
    HomingStep,
    SwitchHoming,
    WorkerConfig,
    WorkerState,
)

COUNTS = 10_000.0                  # counts per mm (DriveSpec's default)
COUNT = 1.0 / COUNTS
TERMINALS = (TerminalSpec(3, "EK1100"), TerminalSpec(4, "EL1008"))
IN = 3 + 1                         # the EL1008's input word (after the three drives)
EDGE_Y, EDGE_Y2 = 5.0, 6.5         # where each side's switch closes (the drive's own count)
SWITCH_OFFSET = 0.3                # Y2's switch is this much further along the axis than Y's
SKEW_WINDOW = 0.2
FE_WINDOW = 5.0                    # wider than the skew window: the skew alarm is the one seen


def _drives() -> tuple[DriveSpec, ...]:
    return (DriveSpec(0, "X", following_error_window=FE_WINDOW),
            DriveSpec(1, "Y", following_error_window=FE_WINDOW),
            DriveSpec(2, "Y2", direction=-1, following_error_window=FE_WINDOW))


def _homing(axis: int, bit: int, latch_vel: float) -> SwitchHoming:
    return SwitchHoming(axis, IN, bit, True, 20.0, latch_vel, 40.0, 2000.0, 400_000.0)


def _worker(y0: float, y2_0: float, latch_vel: float = -0.5) -> CyclicWorker:
    """Y at ``y0`` and Y2 at ``y2_0`` (their drives' own counts, Y2's motor turned the other way)."""
    switches = (SimSwitch(1, 0, EDGE_Y, 1e9, terminal=1), SimSwitch(2, 1, EDGE_Y2, 1e9, terminal=1))
    cfg = WorkerConfig(
        _drives(), mode="manual", terminals=TERMINALS,
        switch_homing=(_homing(1, 0, latch_vel), _homing(2, 1, latch_vel)),
        gantry=(GantrySpec(1, 2, SKEW_WINDOW, SWITCH_OFFSET),),
        bus_options=(("switches", switches),
                     ("initial_positions_counts", (0.0, y0 * COUNTS, -y2_0 * COUNTS))),
    )
    return enabled_worker(cfg)


def _home(w: CyclicWorker) -> tuple[list[np.ndarray], set[HomingStep]]:
    """Home Y (the worker adds Y2): every cycle's set-points and the follower's steps seen."""
    w.home_to_switches(["Y"])
    refs, steps = [], set()
    for _ in range(30_000):
        w.step(1)
        s = w.snapshot()
        refs.append(np.array(s.reference_position))
        steps.add(s.homing_steps[2])
        if w.state() is not WorkerState.HOMING:
            break
    return refs, steps


def test_homing_squares_two_sides_started_skewed_to_one_count() -> None:
    """Ten random starts, the two sides up to 3 mm apart (some on their switches): each side
    latches its own switch; the follower then moves alone until the pair stands as the two
    latches less the switches' offset, to one count; on the switches' true edges, within the
    latch's reach (the latch velocity times the cycle); within the limits of its homing."""
    rng = np.random.default_rng(52)
    for _ in range(10):
        y0 = float(rng.uniform(-10.0, 7.0))
        y2_0 = y0 + float(rng.uniform(-3.0, 3.0))
        w = _worker(y0, y2_0)
        try:
            refs, steps = _home(w)
            s = w.snapshot()
            assert s.state is WorkerState.ENABLED, s.alarms
            assert s.homing[1] is HomingState.DONE and s.homing[2] is HomingState.DONE
            assert HomingStep.SQUARE in steps
            latch_y, latch_y2 = s.home_latched[1], s.home_latched[2]
            assert abs(latch_y - EDGE_Y) <= 0.5e-3 + COUNT and abs(latch_y2 - EDGE_Y2) <= 0.5e-3 + COUNT
            want = latch_y2 - latch_y - SWITCH_OFFSET
            y, y2 = s.reference_position[1], s.reference_position[2]
            assert abs((y2 - y) - want) <= 1e-9, (y0, y2_0, y2 - y, want)
            w.step(50)                                  # the drives settle on their set-points
            s = w.snapshot()
            assert abs((s.actual_position[2] - s.actual_position[1]) - want) <= COUNT
            # the follower's set-points moved within its homing limits (2000 mm/s^2, 20 mm/s)
            q = np.array(refs)[:, 2]
            v = np.diff(q) / 1e-3
            a = np.diff(v) / 1e-3
            assert np.abs(v).max() <= 20.0 + 1e-6 and np.abs(a).max() <= 2000.0 * 1.001
            # and the pair moves as one from there on, square
            w.push(np.column_stack([np.zeros(500), y + np.linspace(0.0, -2.0, 500)]))
            w.push(np.column_stack([np.zeros(200), np.full(200, y - 2.0)]))
            w.step(900)
            s = w.snapshot()
            assert s.state is WorkerState.ENABLED, s.alarms
            assert abs((s.actual_position[2] - s.actual_position[1]) - want) <= COUNT
            assert abs(s.actual_position[1] - (y - 2.0)) <= COUNT
        finally:
            w.stop()


def _ramp_move(start: float, length: float, n: int = 1000) -> np.ndarray:
    """Y from ``start`` by ``length`` in ``n`` cycles on a smooth (cosine) velocity profile."""
    s = (1.0 - np.cos(np.linspace(0.0, np.pi, n))) / 2.0
    s = np.concatenate([s, np.ones(50)])              # and standing there
    return np.column_stack([np.zeros(len(s)), start + length * s])


@pytest.mark.parametrize("jam", [False, True])
def test_a_side_that_stops_while_the_gantry_moves_stops_both_drives_with_the_alarm(jam: bool) -> None:
    """Y moves 20 mm (up to 31 mm/s); with Y2 jammed half-way, the skew passes the 0.2 mm
    window within a few cycles and both drives quick-stop with the gantry's alarm, long before
    Y2's following error (5 mm window) would; unjammed, the pair moves as one, square."""
    w = _worker(1.0, 2.5)
    try:
        d = w.snapshot().reference_position[2] - w.snapshot().reference_position[1]
        w.push(_ramp_move(1.0, 20.0))
        w.step(500)
        if jam:
            w.inject("jam", "Y2")
        w.step(600)
        s = w.snapshot()
        if not jam:
            assert s.state is WorkerState.ENABLED and not s.alarms
            assert abs(s.actual_position[1] - 21.0) <= COUNT
            assert abs(s.actual_position[2] - s.actual_position[1] - d) <= COUNT
            assert abs(s.gantry_skew[2]) <= COUNT
            return
        assert s.state is WorkerState.QUICK_STOP
        alarm = s.alarms[-1]
        assert alarm.code is AlarmCode.GANTRY_SKEW and alarm.axis == "Y2", s.alarms
        assert "gantry Y" in alarm.message and "window 0.2" in alarm.message
        assert not any(a.code is AlarmCode.FOLLOWING_ERROR for a in s.alarms)
        # raised within a few cycles of passing the window (~31 mm/s: 0.03 mm a cycle)
        assert SKEW_WINDOW < abs(s.gantry_skew[2]) < SKEW_WINDOW + 0.2
        # both drives stopped: Y stands well short of its target
        here = s.actual_position[1]
        w.step(200)
        assert w.snapshot().actual_position[1] == pytest.approx(here, abs=0.5)
        assert here < 20.0
    finally:
        w.stop()


def test_a_side_asked_to_home_alone_is_refused_with_the_reason() -> None:
    w = _worker(0.0, 0.5)
    try:
        with pytest.raises(Exception, match="homes only together with its other side"):
            w.home_to_switches(["Y2"])
    finally:
        w.stop()


def test_the_gantry_is_configured_with_its_follower_last_and_set_points_without_its_column() -> None:
    drives = _drives()
    with pytest.raises(ConfigurationError, match="last 1 of 3"):
        WorkerConfig(drives, mode="manual", gantry=(GantrySpec(2, 1, SKEW_WINDOW),))
    with pytest.raises(ConfigurationError, match="skew_window"):
        GantrySpec(1, 2, 0.0)
    w = _worker(0.0, 0.5)
    try:
        with pytest.raises(ConfigurationError, match=r"\(N, 2\)"):
            w.push(np.zeros((5, 3)))
        assert w.push(np.zeros((5, 2))) == 5
    finally:
        w.stop()
