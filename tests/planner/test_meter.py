"""The limit meter, the oracle behind every "no limit exceeded" check: shown to flag planted
violations of each kind where they are, to leave clean motion alone, to measure a stream in
chunks exactly as in one piece, and to keep joint jerk apart from the jerk limits."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cli.plan import build_machine
from planner.gcode.interpreter import parse_program
from planner.motion.meter import LimitMeter, check_limits, path_vaj
from planner.motion.plan import plan_program

PROGRAM = "G21 G90 G17\nG1 X20 F1800\nG1 X20 Y15\nG2 X30 Y25 R10\nG1 X50 F1200\nM30\n"


@pytest.fixture(scope="module")
def run():
    machine = build_machine(None, 30.0, 1000.0, 10_000.0, 0.001)
    plan = plan_program(parse_program(PROGRAM, "m.nc", machine), machine)
    c = plan.collect()
    return machine, plan, c


def meter_of(machine, plan, q, s, move, line) -> LimitMeter:  # noqa: ANN001
    m = LimitMeter(machine, plan.ts_s, plan.segment.v_prog, across_joints=True)
    m.add(q, s, move, line)
    return m


def test_clean_plan_has_no_violation(run) -> None:  # noqa: ANN001
    machine, plan, c = run
    m = meter_of(machine, plan, c.q, c.s, c.move_index, c.line)
    assert m.violations == {}
    assert max(m.ratios.values()) <= 1.0 + 1e-6
    assert plan.limit_report().ok


@given(k=st.integers(100, 3000), axis=st.integers(0, 1), bump_mm=st.floats(0.002, 0.5))
@settings(max_examples=40, deadline=None)
def test_a_planted_bump_is_flagged_at_its_line(run, k: int, axis: int, bump_mm: float) -> None:  # noqa: ANN001
    """One set-point moved by a bump: its second difference is 2 bump / Ts^2, far over any
    acceleration limit here (>= 4,000 mm/s^2 against 1,000)."""
    machine, plan, c = run
    q = c.q.copy()
    q[k, axis] += bump_mm
    m = meter_of(machine, plan, q, c.s, c.move_index, c.line)
    assert "axis_a" in m.violations
    assert m.violations["axis_a"]["line"] in {int(c.line[k - 1]), int(c.line[k]), int(c.line[k + 1])}
    assert m.ratios["axis_a"] > 1.0
    assert check_limits(q, c.s, c.move_index, machine, plan.ts_s)["axis_a"] > 1.0


def test_each_kind_is_flagged(run) -> None:  # noqa: ANN001
    machine, plan, c = run
    # velocity: the same path in half the time
    fast = meter_of(machine, plan, c.q[::2], c.s[::2], c.move_index[::2], c.line[::2])
    assert {"axis_v", "tangential_v"} <= set(fast.violations)
    # path acceleration: a step in the path length alone
    s = c.s.copy()
    s[2000:] += 0.05
    assert "tangential_a" in meter_of(machine, plan, c.q, s, c.move_index, c.line).violations
    # jerk inside a move: a velocity step of 0.03 mm/s on X, 50 samples into a move; its
    # acceleration (30 mm/s^2 for one sample) is within the limit, its jerk (3e4 mm/s^3) is not
    q = c.q.copy()
    mid = int(np.argmax(c.move_index == c.move_index[len(c.q) // 2]))
    q[mid + 50:, 0] += 3e-5 * np.arange(len(q) - mid - 50)
    jm = meter_of(machine, plan, q, c.s, c.move_index, c.line)
    assert "axis_j" in jm.violations and "axis_a" not in jm.violations


def test_jerk_across_a_joint_is_joint_jerk_not_a_violation(run) -> None:  # noqa: ANN001
    """The 90-degree corner between the first two lines: the axes' jerk there is the joint's
    figure (reported), never an axis jerk violation."""
    machine, plan, c = run
    m = meter_of(machine, plan, c.q, c.s, c.move_index, c.line)
    assert "axis_j" not in m.violations
    assert max(a["j_joint"] for a in m.axes.values()) > 0.0


def test_chunks_measure_as_one_piece(run) -> None:  # noqa: ANN001
    machine, plan, c = run
    whole = meter_of(machine, plan, c.q, c.s, c.move_index, c.line)
    parts = LimitMeter(machine, plan.ts_s, plan.segment.v_prog, across_joints=True)
    for lo in range(0, len(c.q), 777):
        sl = slice(lo, lo + 777)
        parts.add(c.q[sl], c.s[sl], c.move_index[sl], c.line[sl])
    assert parts.ratios == whole.ratios and parts.axes == whole.axes
    assert parts.samples == whole.samples == len(c.q)


def test_path_vaj_of_a_constant_acceleration() -> None:
    t = np.arange(0, 1.0, 0.001)
    v, a, j = path_vaj(0.5 * 200.0 * t * t, 0.001)
    np.testing.assert_allclose(v[5:-5], 200.0 * t[5:-5], rtol=1e-9)
    np.testing.assert_allclose(a[5:-5], 200.0, rtol=1e-6)
    np.testing.assert_allclose(j[5:-5], 0.0, atol=1e-3)
