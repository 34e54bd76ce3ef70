"""The look-ahead's passes in C (planner/_passes.c) give the very doubles of the Python ones,
which stay the reference (and the fallback where no compiler built the module)."""

from __future__ import annotations

import os

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import planner.motion.lookahead as lookahead
from planner.motion.lookahead import backward_pass, forward_pass
from planner.motion.plan import plan_program
from planner.motion.profile import reachable_speed_lower_bound, reachable_speed_scalar
from tests.planner.motion_programs import paper_machine, programs

if not lookahead.COMPILED:
    if os.environ.get("CI"):
        raise AssertionError("planner._passes is not built: `pip install -e .` compiles it (gcc)")
    pytest.skip("planner._passes is not built here (no compiler?): the Python passes run",
                allow_module_level=True)

from planner import _passes  # noqa: E402

speeds = st.floats(0.0, 500.0, allow_nan=False)
lengths = st.floats(1e-7, 50.0, allow_nan=False)


@settings(max_examples=400, deadline=None)
@given(speeds, lengths, st.floats(1.0, 1e5), st.floats(10.0, 1e7))
def test_reachable_speed_is_the_same_double(v0, length, a_max, j_max):
    ours = reachable_speed_scalar(v0, length, a_max, j_max)
    assert _passes.reachable_speed(v0, length, a_max, j_max) == ours


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(speeds, lengths), min_size=2, max_size=60), st.floats(100.0, 5000.0),
       st.floats(1000.0, 1e6), st.integers(0, 3))
def test_both_passes_give_the_same_speeds(rows, a_max, j_max, cut):
    n = len(rows)
    caps = np.array([0.0] + [c for c, _ in rows])
    length = np.array([L for _, L in rows])
    a_t, j_t = np.full(n, a_max), np.full(n, j_max)
    r0 = reachable_speed_lower_bound(length, a_t, j_t)
    k = max(1, n - cut)
    v_py = caps.tolist()
    backward_pass(v_py, caps.tolist(), length.tolist(), a_t.tolist(), j_t.tolist(), r0.tolist())
    forward_pass(v_py, length.tolist(), a_t.tolist(), j_t.tolist(), r0.tolist(), 0, k)
    v_c = caps.copy()
    _passes.backward_pass(v_c, caps, length, a_t, j_t, r0, 0)
    _passes.forward_pass(v_c, length, a_t, j_t, r0, 0, k)
    np.testing.assert_array_equal(v_c[: k + 1], np.array(v_py[: k + 1]))


@settings(max_examples=40, deadline=None)
@given(programs(max_blocks=14))
def test_plans_are_the_same_with_either_passes(text):
    from planner.gcode.interpreter import parse_program

    machine = paper_machine()
    program = parse_program(text, "g.ngc", machine)
    compiled = plan_program(program, machine, window=4)
    try:
        lookahead.COMPILED = False
        python = plan_program(program, machine, window=4)
    finally:
        lookahead.COMPILED = True
    np.testing.assert_array_equal(compiled.vs, python.vs)
    np.testing.assert_array_equal(compiled.ve, python.ve)
    assert compiled.cycle_time_s == python.cycle_time_s


def test_wrong_arrays_are_refused_not_overrun():
    v = np.zeros(5)
    with pytest.raises(TypeError):
        _passes.backward_pass(v, np.zeros(5, np.float32), np.ones(4), np.ones(4), np.ones(4), np.ones(4), 0)
    with pytest.raises(ValueError):
        _passes.backward_pass(v, np.zeros(5), np.ones(2), np.ones(4), np.ones(4), np.ones(4), 0)
    with pytest.raises(ValueError):
        _passes.forward_pass(v, np.ones(4), np.ones(4), np.ones(4), np.ones(4), 0, 9)
