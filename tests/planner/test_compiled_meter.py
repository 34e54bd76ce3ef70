"""The limit meter's stencils in C (planner/motion/_meter.c) give the figures of the NumPy
form, which stays the reference (and the fallback where no compiler built the module):
maxima, ratios, violations with their counts, worst values and lines, joint jerk; on clean
plans, on planted violations of every kind, with rotary axes, chunked, with NaN samples."""

from __future__ import annotations

import json
import os

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import planner.motion.meter as meter_module
from cli.plan import build_machine
from planner.motion.meter import LimitMeter, PathSpeedLimits
from planner.motion.plan import plan_program
from tests.planner.motion_programs import parse, programs, xyza_machine

if meter_module._meter is None:
    if os.environ.get("CI"):
        raise AssertionError("planner.motion._meter is not built: `pip install -e .` compiles it (gcc)")
    pytest.skip("planner.motion._meter is not built here (no compiler?): NumPy measures",
                allow_module_level=True)


def _figures(m: LimitMeter) -> str:
    """Every figure of a meter (as text: NaN compares equal to NaN)."""
    return json.dumps({"ratios": m.ratios, "violations": m.violations, "joint": m.joint.as_dict(),
                       "tangential": m.tangential, "axes": m.axes, "samples": m.samples}, sort_keys=True)


def _both(machine, plan, q, s, move, line, chunk: int = 0, v_path=None, across: bool = True,  # noqa: ANN001
          tangential_accel: bool = True) -> tuple[str, str]:
    """The figures of the compiled meter and of the NumPy one over the same samples."""
    out = []
    for compiled in (True, False):
        m = LimitMeter(machine, plan.ts_s, plan.segment.v_prog if v_path is None else v_path,
                       across_joints=across, tangential_accel=tangential_accel)
        saved = meter_module._meter
        if not compiled:
            meter_module._meter = None
        try:
            step = chunk or len(q)
            for i in range(0, len(q), step):
                m.add(q[i:i + step], s[i:i + step], move[i:i + step], line[i:i + step])
        finally:
            meter_module._meter = saved
        out.append(_figures(m))
    return out[0], out[1]


@settings(max_examples=40, deadline=None)
@given(programs(max_blocks=12), st.sampled_from([0, 97, 4096]), st.booleans())
def test_the_compiled_meter_measures_as_numpy(text, chunk, across):
    machine = build_machine(None, 30.0, 1000.0, 10_000.0, 0.001)
    plan = plan_program(parse(text, machine), machine)
    c = plan.collect()
    compiled, reference = _both(machine, plan, c.q, c.s, c.move_index, c.line, chunk, across=across)
    assert compiled == reference


@settings(max_examples=30, deadline=None)
@given(programs(max_blocks=10), st.integers(0, 2**31), st.sampled_from([0.001, 1.0, 1000.0]))
def test_planted_violations_are_reported_alike(text, seed, scale):
    """Bumps of every size in random set-points, measured against a slower machine: every kind
    of violation, with its count, worst ratio, value and line the same."""
    machine = build_machine(None, 30.0, 1000.0, 10_000.0, 0.001)
    plan = plan_program(parse(text, machine), machine)
    c = plan.collect()
    rng = np.random.default_rng(seed)
    q = c.q.copy()
    k = rng.integers(0, len(q), max(len(q) // 50, 1))
    q[k, rng.integers(0, q.shape[1], k.size)] += rng.normal(0.0, 1e-3 * scale, k.size)
    slow = build_machine(None, 10.0, 300.0, 3000.0, 0.001)
    compiled, reference = _both(slow, plan, q, c.s, c.move_index, c.line, 500)
    assert compiled == reference


def test_every_kind_is_there_to_compare():
    """The planted case above reaches all six kinds and joint jerk (so the comparison covers
    each, not only empty records)."""
    machine = build_machine(None, 30.0, 1000.0, 10_000.0, 0.001)
    plan = plan_program(parse("G21 G90 G17 F1800\nG1 X20\nY15\nG2 X30 Y25 R10\nG1 X50 F1200\nM2\n",
                              machine), machine)
    c = plan.collect()
    q = c.q.copy()
    q[300, 0] += 0.2
    slow = build_machine(None, 10.0, 300.0, 3000.0, 0.001)
    compiled, reference = _both(slow, plan, q, c.s * 3.0, c.move_index, c.line, 700)
    figures = json.loads(compiled)
    assert set(figures["violations"]) == {"tangential_v", "tangential_a", "tangential_j", "axis_v",
                                          "axis_a", "axis_j"}
    assert figures["joint"]["count"] > 0
    assert compiled == reference


def test_rotary_axes_and_the_execution_limits():
    """An XYZA machine (stencils along the rotary distance), limits per move kind."""
    machine = xyza_machine()
    text = "G21 G90 G94 F600\nG0 X0 Y0 Z0 A0\nG1 A90\nG1 X10 A180\nG0 A0\nG1 Y5 Z-1\nM2\n"
    plan = plan_program(parse(text, machine), machine)
    c = plan.collect()
    rapid = plan.segment.table.is_rapid
    lim = machine.limits
    v_path = PathSpeedLimits(rapid, lim.rapid_mm_s, lim.v_max_mm_s)
    compiled, reference = _both(machine, plan, c.q, c.s, c.move_index, c.line, 333, v_path=v_path,
                                across=False)
    assert compiled == reference
    compiled, reference = _both(machine, plan, c.q, c.s, c.move_index, c.line, tangential_accel=False)
    assert compiled == reference


def test_nan_samples_are_measured_by_numpy():
    machine = build_machine(None, 30.0, 1000.0, 10_000.0, 0.001)
    plan = plan_program(parse("G21 G90 F1800\nG1 X20\nY15\nM2\n", machine), machine)
    c = plan.collect()
    q = c.q.copy()
    q[100, 1] = np.nan
    compiled, reference = _both(machine, plan, q, c.s, c.move_index, c.line, 64)
    assert compiled == reference


def test_bad_arguments_are_refused():
    q = np.zeros((5, 3))
    args = [q, np.zeros(5), np.zeros(5, np.int64), np.zeros(5, np.int64), np.zeros(4), np.ones(3, bool),
            np.ones((3, 3)), np.ones(4), np.zeros(12), np.zeros((3, 7, 7))]
    assert meter_module._meter.measure(*args) is True
    bad = list(args)
    bad[2] = np.zeros(5, np.int32)
    with pytest.raises(TypeError, match="move must be"):
        meter_module._meter.measure(*bad)
    bad = list(args)
    bad[9] = np.zeros((3, 6, 7))
    with pytest.raises(ValueError, match="shapes do not agree"):
        meter_module._meter.measure(*bad)
