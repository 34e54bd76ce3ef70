"""Time-scaling executor (feed override, rapid override, hold) without the worker: the
set-points stay on the path, end exactly at the programmed end and within every limit."""

from __future__ import annotations

import numpy as np
import pytest

from app.machine.config import load_config
from app.machine.motion.timescale import (
    SIGMA_MAX,
    Budget,
    PauseFeed,
    TimeScaledExecutor,
    pause_points,
    reduced_machine,
)
from planner.gcode.interpreter import parse_program
from planner.geometry.movetable import contour_error
from planner.motion.meter import check_limits
from planner.motion.plan import plan_program
from planner.motion.window import PlanWindow
from resources import shipped_machine

PROGRAM = """G0 X10 Y0
G1 X30 F1200
G3 X30 Y40 R20
G1 X0 Y40
G2 X-20 Y20 R20 Z-5
G1 Y0
G0 X0 Y0 Z0
M30
"""
TOL = 1e-6  # relative allowance on the limit ratios (rounding of finite differences)


@pytest.fixture(scope="module")
def machine():
    return load_config(shipped_machine("xyz_mill")).machine


def run(machine, program_text: str, actions: dict[int, tuple[str, float]], budget: Budget | None = None,
        window_moves: int | None = None, held: list[int] | None = None, chunk: int = 10,
        forget: bool = False):
    """The executor through ``program_text`` with ``actions`` at set-point numbers, ``chunk``
    set-points a call. With ``window_moves`` it plays a plan made as it runs, in segments of
    that many moves (``held`` collects how many moves the window holds at each step). With
    ``forget`` what it keeps from one call to the next is dropped before each."""
    budget = budget or Budget()
    prog = parse_program(program_text, machine=machine)
    if window_moves is None:
        plan = plan_program(prog, reduced_machine(machine, budget))
        ex = TimeScaledExecutor(plan, machine, budget, pause_points(plan, False, False))
    else:
        plan = PlanWindow(prog, reduced_machine(machine, budget), segment_moves=window_moves)
        ex = TimeScaledExecutor(plan, machine, budget, pause_feed=PauseFeed(prog, False, False))
    q, s, mv, sig, tau = [], [], [], [], []
    k = 0
    while not ex.finished:
        for at, (what, value) in list(actions.items()):
            if k >= at:
                actions.pop(at)
                if what == "feed":
                    ex.set_overrides(feed=value)
                elif what == "rapid":
                    ex.set_overrides(rapid=value)
                elif what == "hold":              # a stop, an alarm: at once
                    ex.hold, ex.hold_waits_for_tap = bool(value), False
                elif what == "feed_hold":         # the operator's: after a tap in the hole
                    ex.hold, ex.hold_waits_for_tap = bool(value), True
        if forget:
            forget_kept(ex)
        ch = ex.generate(chunk)
        if ch is None:
            assert ex.paused is not None
            ex.release_pause()
            continue
        if held is not None:
            held.append(len(ex.seg.table))
        q.append(ch.q)
        s.append(ch.s_mm)
        mv.append(ch.move)
        sig.append(ch.sigma)
        tau.append(ch.tau)
        k += len(ch.q)
        assert k < 200_000, "did not finish"
    return prog, plan, ex, np.vstack(q), np.concatenate(s), np.concatenate(mv), np.concatenate(sig), \
        np.concatenate(tau)


def forget_kept(ex: TimeScaledExecutor) -> None:
    """Drop the bounds, envelope and profile tables the executor and its plan keep between calls."""
    ex._bounds_memo = (None, ex._bounds)
    ex._envelope_memo = (None, None)
    ex.seg._tables_memo[0] = (-1, -1, ())


def assert_within(result: dict[str, float]) -> None:
    for key in ("tangential_v", "tangential_a", "tangential_j", "axis_v", "axis_a", "axis_j"):
        assert result[key] <= 1.0 + TOL, f"{key} = {result[key]:.6f} over its limit"


def test_plain_run_equals_the_plan(machine):
    prog, plan, ex, q, s, mv, sig, tau = run(machine, PROGRAM, {})
    ref = plan.collect().q[1:]  # the executor's first set-point is one period after the start
    n = min(len(ref), len(q))
    assert abs(len(ref) - len(q)) <= 1
    assert np.max(np.abs(q[:n] - ref[:n])) < 1e-9
    np.testing.assert_array_equal(q[-1], prog.end_position)


def test_override_changes_mid_move_no_jump_no_limit_exceeded(machine):
    actions = {800: ("feed", 1.5), 2000: ("feed", 0.3), 2600: ("rapid", 0.25), 3500: ("feed", 1.0),
               4200: ("feed", 0.0), 4700: ("feed", 1.2)}
    prog, plan, ex, q, s, mv, sig, tau = run(machine, PROGRAM, actions)
    np.testing.assert_allclose(q[-1], prog.end_position, atol=0, rtol=0)
    assert sig.max() <= 1.5 + 1e-12 and sig.max() > 1.2  # the override was applied
    assert np.all(np.diff(tau) >= -1e-15)  # never runs backwards
    result = check_limits(q, s, mv, machine, plan.ts_s, plan.segment.table.is_rapid)
    assert_within(result)
    # on the programmed geometry everywhere (exact evaluation)
    seg = plan.segment
    u = s - seg.s0[mv]
    assert float(contour_error(seg.table, mv, q, u).max()) < 1e-9


def test_hold_in_the_middle_of_an_arc_then_resume(machine):
    prog = parse_program(PROGRAM, machine=machine)
    plan = plan_program(prog, reduced_machine(machine, Budget()))
    arc_mid = 0.5 * (plan.t0[2] + plan.t1[2])  # third move is the G03 arc (line 3)
    k_hold = int(arc_mid / plan.ts_s)
    _, _, ex, q, s, mv, sig, tau = run(machine, PROGRAM, {k_hold: ("hold", 1), k_hold + 1500: ("hold", 0)})
    held = np.nonzero(sig == 0.0)[0]
    assert len(held) > 100  # it really stood still
    assert set(mv[held]) == {2}  # ... inside the arc
    np.testing.assert_array_equal(q[-1], prog.end_position)
    assert_within(check_limits(q, s, mv, machine, plan.ts_s, plan.segment.table.is_rapid))
    # the stop is short: from 30 mm/s it takes well under a second
    first_zero = held[0]
    slowing = np.nonzero(sig[:first_zero] < 1.0)[0]
    assert (first_zero - slowing[0]) * plan.ts_s < 0.5


def test_budget_leaves_room_for_the_ramps(machine):
    ex_budget = Budget(k_a=0.85, k_j=0.7)
    prog = parse_program(PROGRAM, machine=machine)
    plan = plan_program(prog, reduced_machine(machine, ex_budget))
    ex = TimeScaledExecutor(plan, machine, ex_budget)
    assert ex.d1_ref > 0.0 and ex.d2_ref > 0.0
    assert ex.time_to_ramp_s < 5.0


def random_program(rng: np.random.Generator, n: int) -> str:
    """Lines, rapids and arcs (XY, helix) inside +-80 mm, with varied feeds."""
    out = ["G0 X0 Y0 Z0"]
    x = y = 0.0
    for _ in range(n):
        kind = rng.integers(0, 4)
        f = int(rng.choice([300, 900, 1500, 1800, 2400]))
        tx, ty = (float(v) for v in np.round(rng.uniform(-80, 80, 2), 3))
        if kind == 0:
            out.append(f"G0 X{tx} Y{ty}")
        elif kind == 1:
            out.append(f"G1 X{tx} Y{ty} Z{float(np.round(rng.uniform(-5, 0), 3))} F{f}")
        else:
            chord = np.hypot(tx - x, ty - y)
            if chord < 1.0:
                continue
            r = float(np.round(chord / 2 * rng.uniform(1.01, 3.0), 3))
            g = "G2" if kind == 2 else "G3"
            out.append(f"{g} X{tx} Y{ty} R{r} F{f}")
        x, y = tx, ty
    out.append("M30")
    return "\n".join(out) + "\n"


@pytest.mark.parametrize(("chunk", "window_moves"), [(2, None), (37, 3)])
def test_what_the_executor_keeps_between_calls_changes_no_set_point(machine, chunk: int,
                                                                     window_moves: int | None) -> None:
    """The bounds and braking envelope kept for a window of blocks, and the profile tables kept
    for the moves last asked about, give the set-points made afresh at each call, bit for bit,
    through overrides, a hold and pause points, a few set-points a call as the feeder asks."""
    text = PROGRAM.replace("M30", "M0\nG0 X40 Y-10\nM30")
    # through the rapids, the arcs and the feeds: every kind of block meets a change
    actions = {60: ("rapid", 0.3), 1500: ("feed", 1.7), 3200: ("feed", 0.4), 4800: ("hold", 1.0),
               5300: ("hold", 0.0), 6500: ("feed", 1.2), 8000: ("rapid", 0.6)}
    kept = run(machine, text, dict(actions), window_moves=window_moves, chunk=chunk)
    fresh = run(machine, text, dict(actions), window_moves=window_moves, chunk=chunk, forget=True)
    for a, b in zip(kept[3:], fresh[3:], strict=True):
        np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("seed", range(6))
def test_random_programs_and_override_sequences_stay_within_limits(machine, seed: int) -> None:
    rng = np.random.default_rng(1000 + seed)
    text = random_program(rng, 6)
    actions: dict[int, tuple[str, float]] = {}
    k = 0
    for _ in range(6):
        k += int(rng.integers(100, 900))
        what = str(rng.choice(["feed", "feed", "rapid", "hold"]))
        if what == "feed":
            actions[k] = ("feed", float(rng.uniform(0.0, SIGMA_MAX)))
        elif what == "rapid":
            actions[k] = ("rapid", float(rng.uniform(0.05, 1.0)))
        else:
            actions[k] = ("hold", 1.0)
            actions[k + int(rng.integers(50, 400))] = ("hold", 0.0)
            k += 400
    actions[k + 500] = ("feed", 1.0)  # always finish
    actions[k + 501] = ("hold", 0.0)
    prog, plan, ex, q, s, mv, sig, tau = run(machine, text, actions)
    np.testing.assert_array_equal(q[-1], prog.end_position)
    assert sig.max() <= SIGMA_MAX + 1e-12 and np.all(np.diff(tau) >= -1e-15)
    assert_within(check_limits(q, s, mv, machine, plan.ts_s, plan.segment.table.is_rapid))
    seg = plan.segment
    assert float(contour_error(seg.table, mv, q, s - seg.s0[mv]).max()) < 1e-9
