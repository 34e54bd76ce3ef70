"""The handwheel in the 1 ms loop: its set-point generator alone (every sampled velocity,
acceleration and jerk within the limits, landing exactly), and through the worker on the
simulated bus with an EL5101 (position mode ends at the sum of the steps to one count at any
turning speed, velocity mode stops within its stop distance, counters wrap, soft limits
stop it, a jump or a lost terminal moves nothing)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bench.stepped import enabled as enabled_worker
from ethercat.bus import DriveSpec
from ethercat.terminals import TerminalSpec
from ethercat.worker import (
    AlarmCode,
    CyclicWorker,
    HandwheelMode,
    HandwheelSpec,
    WheelState,
    WorkerConfig,
    WorkerState,
    stop_distance,
)
from ethercat.worker.handwheel import Follower, Handwheel

TS = 0.001
TERMINALS = (TerminalSpec(2, "EK1100"), TerminalSpec(3, "EL5101"))
DRIVES = (DriveSpec(0, "X"), DriveSpec(1, "Z", direction=-1))
COUNTS_PER_MM = 10_000.0            # the drives' default scale: one count = 0.0001 mm
WHEEL = 1                           # the EL5101's index among the terminals
V, A, J = 50.0, 1500.0, 30_000.0    # the axis' limits (mm/s, mm/s^2, mm/s^3)
LIMITS = (V, A, J, -100.0, 100.0)
SCALE = 0.01 / 4                    # x10: 0.01 mm a detent, 4 counts a detent


def _sampled(y: np.ndarray) -> tuple[float, float, float]:
    v = np.diff(y) / TS
    a = np.diff(v) / TS
    j = np.diff(a) / TS
    return tuple(float(np.abs(x).max(initial=0.0)) for x in (v, a, j))  # type: ignore[return-value]


def _within(y: np.ndarray, v: float, a: float, j: float) -> None:
    """Every sample within the limits (a relative 1e-9 for the rounding of the differences,
    and what the positions' own rounding adds to the third difference)."""
    got_v, got_a, got_j = _sampled(y)
    eps = 8.0 * np.finfo(float).eps * max(1.0, float(np.abs(y).max())) / TS**3
    assert got_v <= v * (1 + 1e-9), (got_v, v)
    assert got_a <= a * (1 + 1e-9) + eps * TS, (got_a, a)
    assert got_j <= j * (1 + 1e-9) + eps, (got_j, j)


# ------------------------------------------------------------------------------ the generator
@settings(max_examples=60, deadline=None)
@given(scale=st.sampled_from([0.001, 1.0, 1000.0]), v=st.floats(0.5, 200.0), a=st.floats(5.0, 5000.0),
       j=st.floats(500.0, 1e6), jumps=st.lists(st.tuples(st.integers(0, 400), st.floats(-20.0, 20.0)),
                                                min_size=1, max_size=12))
def test_the_follower_keeps_every_limit_and_lands_exactly(scale: float, v: float, a: float, j: float,
                                                          jumps: list[tuple[int, float]]) -> None:
    """Targets that jump anywhere at any time, at the scales x0.001 to x1000: each sample
    within v, a and j, and at rest exactly on the last target."""
    v, a, j = v * scale, a * scale, j * scale
    f = Follower(TS)
    f.start(3.0 * scale, v, a, j)
    target, ys = 3.0 * scale, [3.0 * scale]
    for hold, to in jumps:
        target = to * scale
        ys += [f.step(target) for _ in range(hold)]
    d = abs(target - ys[-1])
    settle = int(2 * (d / v + v / a + a / j + math.sqrt(d / a)) / TS) + 2 * f.n + 100
    for _ in range(settle):
        ys.append(f.step(target))
        if f.at_rest:
            break
    assert f.at_rest and ys[-1] == target
    _within(np.array(ys), v, a, j)


def test_the_stop_distance_bounds_what_the_follower_travels_from_top_speed() -> None:
    """At top speed the target jumps to where velocity mode keeps it (its lead ahead of the
    first stage): what the output still travels is within ``stop_distance``."""
    f = Follower(TS)
    f.start(0.0, V, A, J)
    for _ in range(400):
        f.step(1e6)                       # on at top speed
    y0 = f.y
    target = f.p + f.lead
    while not f.at_rest:
        f.step(target)
    assert f.y - y0 <= stop_distance(V, A, J, TS) + 1e-12
    assert f.y - y0 >= 0.5 * stop_distance(V, A, J, TS)    # and the bound is not loose by much


# ------------------------------------------------------------------------------ in the loop
def _worker(bits: int = 16, **kw: object) -> CyclicWorker:
    cfg = WorkerConfig(DRIVES, mode="manual", terminals=TERMINALS, handwheel=HandwheelSpec(WHEEL, bits), **kw)  # type: ignore[arg-type]
    w = enabled_worker(cfg)
    w.drain_trace()
    return w


def _turn(w: CyclicWorker, per_cycle: list[int]) -> None:
    for n in per_cycle:
        if n:
            w.inject("encoder_add", WHEEL, n)
        w.step(1)


def _settle(w: CyclicWorker, axis: int = 0, most: int = 20_000) -> None:
    """Until the axis' set-point stands for 50 cycles."""
    last, still = None, 0
    for _ in range(most):
        w.step(1)
        ref = float(w.snapshot().reference_position[axis])
        still = still + 1 if ref == last else 0
        last = ref
        if still >= 50:
            return
    raise AssertionError("the axis did not come to rest")


@pytest.mark.parametrize("seed", range(6))
def test_position_mode_ends_at_the_sum_of_the_steps_at_any_speed(seed: int) -> None:
    """Random detent sequences turned at random speeds (up to 30 counts a cycle, six times
    what the axis can follow at this step): the axis ends at the sum of the steps to one
    count, every sample within v, a, j."""
    rng = np.random.default_rng(seed)
    w = _worker()
    try:
        assert w.handwheel(0, HandwheelMode.POSITION, SCALE, LIMITS)
        total = 0
        for _ in range(int(rng.integers(3, 8))):
            detents = int(rng.integers(-60, 61))
            speed = int(rng.integers(1, 31))
            counts = 4 * detents
            per = [int(math.copysign(min(speed, abs(counts) - k), counts))
                   for k in range(0, abs(counts), speed)]
            total += sum(per)
            _turn(w, per + [0] * int(rng.integers(0, 200)))
        _settle(w)
        ref = w.drain_trace().reference[:, 0]
        assert abs(float(ref[-1]) - total * SCALE) <= 1.0 / COUNTS_PER_MM
        _within(ref, V, A, J)
        assert w.snapshot().handwheel_state == WheelState.LIVE
    finally:
        w.stop()


def test_velocity_mode_stops_within_the_stop_distance_when_the_wheel_stops() -> None:
    """Turned far faster than the axis follows, then stopped: the counts it could not follow
    are dropped, so the axis stops within ``stop_distance`` of where it was when the wheel
    stopped (position mode goes on for all the counts), every sample within v, a, j."""
    w = _worker()
    try:
        assert w.handwheel(0, HandwheelMode.VELOCITY, 0.1 / 4, LIMITS)     # x100: 0.1 mm a detent
        _turn(w, [100] * 600)                                               # 2,500 mm/s asked
        at_stop = float(w.snapshot().reference_position[0])
        _settle(w)
        end = float(w.snapshot().reference_position[0])
        assert 0.0 <= end - at_stop <= stop_distance(V, A, J, TS) + 1e-9
        assert end < 600 * 100 * 0.1 / 4 / 10                               # most counts were dropped
        _within(w.drain_trace().reference[:, 0], V, A, J)
    finally:
        w.stop()


def test_a_16_bit_counter_wraps_without_a_jump() -> None:
    w = _worker()
    try:
        w.inject("encoder_add", WHEEL, 65_530)
        w.step(2)
        assert w.handwheel(0, HandwheelMode.POSITION, SCALE, LIMITS)
        _turn(w, [4] * 10)                       # 65530 -> 65535 -> 0 -> 34: 40 counts
        _settle(w)
        assert w.snapshot().terminal_counts[WHEEL] == 34
        assert float(w.snapshot().reference_position[0]) == pytest.approx(40 * SCALE, abs=1e-12)
        _turn(w, [-8] * 10)                      # back through the wrap: -80 counts
        _settle(w)
        assert float(w.snapshot().reference_position[0]) == pytest.approx(-40 * SCALE, abs=1e-12)
    finally:
        w.stop()


@pytest.mark.parametrize("bits", [16, 32])
def test_a_counter_of_16_or_32_bits_wraps_without_a_jump(bits: int) -> None:
    """The wheel alone, its counter near the top of its range and turned over it both ways."""
    wheel = Handwheel(TS, bits, 256)
    ref = np.zeros(1)
    top = (1 << bits) - 3
    assert wheel.arm(0, 0, SCALE, np.array(LIMITS), 0.0, top)
    for k in range(1, 11):
        assert wheel.step((top + 4 * k) % (1 << bits), ref)
    for _ in range(2000):
        wheel.step((top + 40) % (1 << bits), ref)
    assert ref[0] == pytest.approx(40 * SCALE, abs=1e-12)
    for k in range(1, 21):
        assert wheel.step((top + 40 - 4 * k) % (1 << bits), ref)
    for _ in range(2000):
        wheel.step((top - 40) % (1 << bits), ref)
    assert ref[0] == pytest.approx(-40 * SCALE, abs=1e-12)


def test_the_soft_limit_stops_it_and_the_first_count_back_moves_it_away() -> None:
    w = _worker()
    try:
        assert w.handwheel(0, HandwheelMode.POSITION, 0.1 / 4, (V, A, J, -100.0, 0.5))
        _turn(w, [4] * 20)                      # 2 mm asked, 0.5 mm allowed
        _settle(w)
        assert float(w.snapshot().reference_position[0]) == pytest.approx(0.5, abs=1e-12)
        _turn(w, [-4])                          # one detent back: 0.1 mm from the limit
        _settle(w)
        assert float(w.snapshot().reference_position[0]) == pytest.approx(0.4, abs=1e-12)
    finally:
        w.stop()


def test_a_jump_of_the_counter_moves_nothing_and_stops_the_wheel() -> None:
    w = _worker()
    try:
        assert w.handwheel(0, HandwheelMode.POSITION, SCALE, LIMITS)
        _turn(w, [4] * 5)
        _settle(w)
        before = float(w.snapshot().reference_position[0])
        _turn(w, [20_000])
        _settle(w)
        snap = w.snapshot()
        assert float(snap.reference_position[0]) == before
        assert snap.handwheel_state == WheelState.OFF and snap.state is WorkerState.ENABLED
        (alarm,) = [a for a in snap.alarms if a.code is AlarmCode.HANDWHEEL]
        assert "jumped by 20000 counts" in alarm.message
        _turn(w, [4] * 5)                        # off: turning moves nothing
        _settle(w)
        assert float(w.snapshot().reference_position[0]) == before
    finally:
        w.stop()


def test_a_lost_terminal_stops_the_machine_and_coming_back_moves_nothing() -> None:
    """The EL5101 stops answering while the wheel is live: the working counter says so, the
    axes quick-stop with the wheel named; it comes back powered again (its counter at 0), and
    the wheel armed again follows from there without a jump."""
    w = _worker(wkc_error_limit=3)
    try:
        assert w.handwheel(0, HandwheelMode.POSITION, SCALE, LIMITS)
        _turn(w, [4] * 50)
        _settle(w)
        w.inject("lose_terminal", WHEEL)
        w.step(10)
        snap = w.snapshot()
        assert snap.state is WorkerState.QUICK_STOP and snap.handwheel_state == WheelState.OFF
        assert any(a.code is AlarmCode.HANDWHEEL and "stopped answering" in a.message for a in snap.alarms)
        w.inject("restore_terminal", WHEEL)
        w.step(5)
        w.fault_reset()
        w.step(20)
        w.enable()
        w.step(20)
        at = float(w.snapshot().reference_position[0])
        assert w.snapshot().terminal_counts[WHEEL] == 0
        assert w.handwheel(0, HandwheelMode.POSITION, SCALE, LIMITS)
        _turn(w, [4] * 5)
        _settle(w)
        assert float(w.snapshot().reference_position[0]) == pytest.approx(at + 20 * SCALE, abs=1e-12)
    finally:
        w.stop()


def test_letting_go_waits_for_rest_and_queued_set_points_wait_for_the_wheel() -> None:
    """Let go while it moves: refused, it brakes and lets go once it stands; let go at rest:
    at once. Set-points queued while it is on stop it, and are taken once the axis stands."""
    w = _worker()
    try:
        assert w.handwheel(0, HandwheelMode.POSITION, SCALE, LIMITS)
        _turn(w, [40] * 10)                       # 1 mm, moving
        assert not w.handwheel_off()
        assert w.snapshot().handwheel_state == WheelState.STOPPING
        _settle(w)
        assert w.snapshot().handwheel_state == WheelState.OFF
        assert w.handwheel(0, HandwheelMode.POSITION, SCALE, LIMITS)
        assert w.handwheel_off()                   # at rest: let go at once
        assert w.snapshot().handwheel_state == WheelState.OFF
        assert w.handwheel(0, HandwheelMode.POSITION, SCALE, LIMITS)
        _turn(w, [40] * 10)
        here = np.array(w.snapshot().reference_position)
        consumed = w.samples_consumed()
        w.push(np.tile(here, (5, 1)))
        w.step(1)
        assert w.snapshot().handwheel_state == WheelState.STOPPING and w.samples_consumed() == consumed
        _settle(w)
        assert w.snapshot().handwheel_state == WheelState.OFF and w.samples_consumed() == consumed + 5
    finally:
        w.stop()


def test_without_a_handwheel_or_outside_its_limits_it_is_refused() -> None:
    cfg = WorkerConfig(DRIVES, mode="manual", terminals=TERMINALS)
    w = CyclicWorker(cfg)
    w.start()
    try:
        w.step(3)
        w.enable()
        w.step(20)
        assert not w.handwheel(0, HandwheelMode.POSITION, SCALE, LIMITS)
    finally:
        w.stop()
    w = _worker()
    try:
        assert not w.handwheel(0, HandwheelMode.POSITION, SCALE, (V, A, J, 1.0, 2.0))   # it stands at 0
        assert not w.handwheel(0, HandwheelMode.POSITION, 0.0, LIMITS)
        assert w.snapshot().handwheel_state == WheelState.OFF
    finally:
        w.stop()


@settings(max_examples=40, deadline=None)
@given(scale=st.sampled_from([0.001, 1.0, 1000.0]), bits=st.sampled_from([16, 32]),
       start=st.integers(0, (1 << 16) - 1),
       bursts=st.lists(st.tuples(st.integers(-40, 40), st.integers(1, 300), st.integers(0, 300)),
                       min_size=1, max_size=8),
       velocity=st.booleans())
def test_any_turning_of_the_wheel_keeps_the_limits_and_ends_where_its_mode_says(
        scale: float, bits: int, start: int, bursts: list[tuple[int, int, int]], velocity: bool) -> None:
    """The wheel alone at the scales x0.001 to x1000: bursts of counts per cycle (for some
    cycles, then still for some), its counter starting anywhere and wrapping. Position mode
    ends at the sum of the counts times the step; velocity mode, once the wheel stops, goes
    on no further than ``stop_distance``; every sample within v, a, j either way."""
    v, a, j = V * scale, A * scale, J * scale
    step = SCALE * scale
    wheel = Handwheel(TS, bits, 256)
    ref = np.zeros(1)
    count, total = start, 0
    assert wheel.arm(0, int(velocity), step, np.array((v, a, j, -1e9, 1e9)), 0.0, count)
    ys = [0.0]
    for per_cycle, cycles, still in bursts:
        for _ in range(cycles):
            count = (count + per_cycle) % (1 << bits)
            total += per_cycle
            wheel.step(count, ref)
            ys.append(float(ref[0]))
        at_stop = float(ref[0])
        for _ in range(still):
            wheel.step(count, ref)
            ys.append(float(ref[0]))
    f = wheel.follower
    for _ in range(int(2 * (abs(total) * step / v + v / a + a / j) / TS) + 4 * f.n + 100):
        if f.at_rest:
            break
        wheel.step(count, ref)
        ys.append(float(ref[0]))
    assert f.at_rest
    if velocity:
        assert abs(float(ref[0]) - at_stop) <= stop_distance(v, a, j, TS) * (1 + 1e-9) + 1e-12 * scale
    else:
        assert float(ref[0]) == pytest.approx(total * step, abs=1e-9 * scale)
    _within(np.array(ys), v, a, j)


def test_another_axis_waits_for_the_first_to_stand() -> None:
    """The wheel given to Z while X still moves: refused, X brakes to rest within its limits
    (no set-point left behind mid-motion), and Z is taken once X stands."""
    w = _worker()
    try:
        assert w.handwheel(0, HandwheelMode.POSITION, SCALE, LIMITS)
        _turn(w, [40] * 20)                                  # 2 mm asked, moving
        assert not w.handwheel(1, HandwheelMode.POSITION, SCALE, LIMITS)
        assert w.snapshot().handwheel_state == WheelState.STOPPING
        _settle(w)
        _within(w.drain_trace().reference[:, 0], V, A, J)
        assert w.handwheel(1, HandwheelMode.POSITION, SCALE, LIMITS)
        _turn(w, [4] * 10)
        _settle(w, axis=1)
        assert float(w.snapshot().reference_position[1]) == pytest.approx(40 * SCALE, abs=1e-12)
    finally:
        w.stop()
