"""The time-optimal jerk-limited stop along the path (planner.motion.stopping) used by feed hold and
stop: time-optimal in 1-D (against Ruckig), no limit exceeded on the executed set-points,
shorter than the time-scaling ramp, and hold-then-resume still ends exactly at the end."""

from __future__ import annotations

import numpy as np
import pytest

from app.machine.config import load_config
from app.machine.motion.timescale import Budget, TimeScaledExecutor, pause_points, reduced_machine
from planner.gcode.interpreter import parse_program
from planner.geometry.movetable import contour_error
from planner.motion.meter import check_limits
from planner.motion.plan import plan_program
from planner.motion.stopping import stop_profile
from resources import shipped_machine
from tests.machine.test_timescale import PROGRAM, assert_within, random_program


@pytest.fixture(scope="module")
def machine():
    return load_config(shipped_machine("xyz_mill")).machine


def run(machine, text: str, actions: dict[int, tuple[str, float]], path_stops: bool = True,
        hold_at_s: float | None = None, hold_for: int = 900):
    """Execute ``text`` with actions at sample numbers (and a hold when the path passes
    ``hold_at_s`` mm, released ``hold_for`` samples later); returns program, plan, executor
    and the set-points (q, s, move, sigma)."""
    budget = Budget()
    prog = parse_program(text, machine=machine)
    plan = plan_program(prog, reduced_machine(machine, budget))
    ex = TimeScaledExecutor(plan, machine, budget, pause_points(plan, False, False))
    ex.path_stops = path_stops
    out: list[tuple] = []
    k = 0
    while not ex.finished:
        for at, (what, value) in list(actions.items()):
            if k >= at:
                actions.pop(at)
                if what == "hold":
                    ex.hold = bool(value)
                else:
                    ex.set_overrides(feed=value)
        ch = ex.generate(7)
        if ch is None:
            ex.release_pause()
            continue
        out.append((ch.q, ch.s_mm, ch.move, ch.sigma))
        k += len(ch.q)
        if hold_at_s is not None and ch.s_mm[-1] >= hold_at_s:
            hold_at_s = None
            ex.hold = True
            actions[k + hold_for] = ("hold", 0.0)
            run.k_hold = k  # type: ignore[attr-defined]
        assert k < 200_000, "did not finish"
    q, s, mv, sig = (np.concatenate([o[i] for o in out]) for i in range(4))
    return prog, plan, ex, q, s, mv, sig


def check_run(prog, plan, machine, q, s, mv) -> None:
    np.testing.assert_array_equal(q[-1], prog.end_position)  # exactly the programmed end
    assert_within(check_limits(q, s, mv, machine, plan.ts_s, plan.segment.table.is_rapid))
    seg = plan.segment
    assert float(contour_error(seg.table, mv, q, s - seg.s0[mv]).max()) < 1e-9  # on the path


# ---------------------------------------------------------------------------- 1-D profile
def test_stop_profile_reaches_rest_within_the_limits() -> None:
    rng = np.random.default_rng(7)
    for _ in range(300):
        a_max, j_max = rng.uniform(100, 3000), rng.uniform(1000, 50_000)
        v0, a0 = rng.uniform(0, 100), rng.uniform(-a_max, a_max)
        p = stop_profile(v0, a0, a_max, j_max)
        if p is None:
            assert a0 < 0 and v0 < a0 * a0 / (2 * j_max)  # rest out of reach without reversing
            continue
        t = np.linspace(0.0, p.duration_s, 4001)
        s, v, a = p.evaluate(t)
        assert v.min() >= -1e-9 and np.abs(a).max() <= a_max * (1 + 1e-12)
        assert np.abs(np.diff(a) / np.diff(t)).max() <= j_max * (1 + 1e-6)
        assert v[-1] == 0.0 and a[-1] == 0.0 and s[-1] == pytest.approx(p.distance)
        assert np.all(np.diff(s) >= -1e-12)
    assert stop_profile(10.0, 2000.0, 1000.0, 1e4) is None  # |a0| over its limit


def test_stop_profile_is_time_optimal() -> None:
    ruckig = pytest.importorskip("ruckig")
    rng = np.random.default_rng(11)
    for _ in range(200):
        a_max, j_max = rng.uniform(100, 3000), rng.uniform(1000, 50_000)
        v0, a0 = rng.uniform(0, 100), rng.uniform(-a_max, a_max)
        p = stop_profile(v0, a0, a_max, j_max)
        if p is None:
            continue
        inp = ruckig.InputParameter(1)
        inp.control_interface = ruckig.ControlInterface.Velocity
        inp.current_position, inp.current_velocity, inp.current_acceleration = [0.0], [v0], [a0]
        inp.target_velocity, inp.target_acceleration = [0.0], [0.0]
        inp.max_velocity, inp.max_acceleration, inp.max_jerk = [1e9], [a_max], [j_max]
        traj = ruckig.Trajectory(1)
        ruckig.Ruckig(1).calculate(inp, traj)
        assert p.duration_s == pytest.approx(traj.duration, rel=1e-9, abs=1e-12)


# ---------------------------------------------------------------------------- along the path
@pytest.mark.parametrize("feed", [0.4, 1.0, 1.5])
def test_hold_mid_arc_stops_shorter_within_limits_and_resumes_to_the_end(machine, feed: float) -> None:
    prog = parse_program(PROGRAM, machine=machine)
    plan = plan_program(prog, reduced_machine(machine, Budget()))
    seg = plan.segment
    s_mid = float(seg.s0[2] + 0.3 * seg.table.length[2])  # third move: the G03 arc
    dist = {}
    for path_stops in (True, False):
        prog, plan, ex, q, s, mv, sig = run(machine, PROGRAM, {0: ("feed", feed)}, path_stops, s_mid)
        check_run(prog, plan, machine, q, s, mv)
        held = np.nonzero(sig == 0.0)[0]
        assert len(held) > 100 and set(mv[held]) == {2}  # stood still inside the arc
        dist[path_stops] = s[held[0]] - s[run.k_hold - 1]  # type: ignore[attr-defined]
        assert ex.stops_taken == (1 if path_stops else 0)
    assert dist[True] < 0.6 * dist[False]  # the time-scaling ramp needs about twice the distance


def test_no_path_stop_across_a_corner(machine) -> None:
    # a 0.003 degree kink (a CAM program's rounding), passed at speed within the jerk limit
    text = "G1 X20 F1800\nG1 X40 Y0.001\nM30\n"
    prog = parse_program(text, machine=machine)
    plan = plan_program(prog, reduced_machine(machine, Budget()))
    assert plan.ve[0] > 5.0
    prog, plan, ex, q, s, mv, sig = run(machine, text, {}, True, 19.5, 500)  # 0.5 mm before it
    assert ex.stops_taken == 0  # the stop would cross the corner: the time-scaling ramp is kept
    check_run(prog, plan, machine, q, s, mv)
    prog, plan, ex, q, s, mv, sig = run(machine, text, {}, True, 10.0, 500)  # well before it
    assert ex.stops_taken == 1
    check_run(prog, plan, machine, q, s, mv)


@pytest.mark.parametrize("seed", range(4))
def test_random_programs_with_holds_stay_within_limits(machine, seed: int) -> None:
    rng = np.random.default_rng(2000 + seed)
    text = random_program(rng, 6)
    actions: dict[int, tuple[str, float]] = {}
    k = 0
    for _ in range(5):
        k += int(rng.integers(150, 900))
        actions[k] = ("feed", float(rng.uniform(0.2, 1.5)))
        actions[k + int(rng.integers(10, 300))] = ("hold", 1.0)
        actions[k + 700] = ("hold", 0.0)
        k += 700
    actions[k + 1] = ("feed", 1.0)
    prog, plan, ex, q, s, mv, sig = run(machine, text, actions)
    check_run(prog, plan, machine, q, s, mv)
