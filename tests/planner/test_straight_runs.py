"""The recorder of straight runs: many moves at once (``straight_runs``: peck cycles, runs of
plain lines) are recorded as the same moves one at a time (``straight_one``) would be: a move
no longer than 1e-9 mm left out with the tool staying where it was, G93's feed from each
move's length, the modal exact stop; on machines with rotary axes, a move that only turns is
measured in degrees. Drawn at the scales x0.001 to x1000."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from planner.core.machine import AxisSpec, MachineSpec
from planner.gcode.codes import G
from planner.gcode.interpreter import Interpreter
from planner.gcode.state import LINE, RAPID, ZERO_LEN


def _interpreter(machine: MachineSpec, inverse_time: bool, exact: bool) -> Interpreter:
    it = Interpreter("runs.ngc", machine, None, False, 1)
    it.modal.feed_mm_s = 10.0
    if inverse_time:
        it.modal.feed_mode = G.G93
        it.modal.inverse_f = 120.0
    it.modal.exact_stop = exact
    return it


def _machine(rotary: bool) -> MachineSpec:
    base = MachineSpec.default()
    if not rotary:
        return base
    return replace(base, axes=(*base.axes, AxisSpec("A", rotary=True, drive_position=3)), work_offsets={})


@st.composite
def runs(draw: st.DrawFn) -> tuple[bool, list[list[float]], list[bool]]:
    rotary = draw(st.booleans())
    n_axes = 4 if rotary else 3
    scale = draw(st.sampled_from([0.001, 1.0, 1000.0]))
    step = st.one_of(st.just(0.0), st.just(ZERO_LEN / 2), st.floats(-5.0, 5.0, allow_nan=False))
    here = [0.0] * n_axes
    ends, rapid = [], []
    for _ in range(draw(st.integers(1, 25))):
        moved = [v + draw(step) * scale for v in here] if draw(st.booleans()) else list(here)
        k = draw(st.integers(0, n_axes - 1))
        moved[k] = here[k] + draw(step) * scale          # often only one axis: a peck, a short step
        ends.append(moved)
        rapid.append(draw(st.booleans()))
        here = moved
    return rotary, ends, rapid


@given(runs(), st.booleans(), st.booleans())
def test_many_at_once_are_recorded_as_one_at_a_time(case, inverse_time: bool, exact: bool) -> None:  # type: ignore[no-untyped-def]
    rotary, ends, rapid = case
    machine = _machine(rotary)
    assert len(machine.axes) == len(ends[0])
    at_once = _interpreter(machine, inverse_time, exact)
    one_by_one = _interpreter(machine, inverse_time, exact)
    lines = np.arange(1, len(ends) + 1)
    kept = at_once.straight_runs(np.array(ends, dtype=float), np.array(rapid), lines,
                                 np.full(len(ends), 10.0))
    recorded = sum(one_by_one.straight_one(list(e), RAPID if r else LINE, math.inf if r else 10.0, int(line))
                   for e, r, line in zip(ends, rapid, lines))
    assert kept == recorded
    a, b = at_once.rec.out.store(), one_by_one.rec.out.store()
    np.testing.assert_array_equal(a.positions, b.positions)
    ca, cb = a.columns(), b.columns()
    for name in ("line", "kind", "exact_stop"):
        np.testing.assert_array_equal(getattr(ca, name), getattr(cb, name), err_msg=name)
    np.testing.assert_allclose(ca.length, cb.length, rtol=4.5e-16, atol=0)   # math.dist vs sqrt
    np.testing.assert_allclose(ca.feed, cb.feed, rtol=4.5e-16, atol=0)
    assert at_once.pos == one_by_one.pos
    assert all(length > ZERO_LEN for length in ca.length)


def test_a_peck_back_off_landing_where_it_started_is_left_out() -> None:
    it = _interpreter(MachineSpec.default(), False, True)
    ends = np.array([[0.0, 0.0, -1.0], [0.0, 0.0, -1.0 + ZERO_LEN / 4], [0.0, 0.0, -2.0]])
    assert it.straight_runs(ends, np.array([False, True, False]), np.array([7, 7, 7]), np.full(3, 5.0)) == 2
    cols = it.rec.out.store().columns()
    np.testing.assert_array_equal(cols.length, [1.0, 1.0])   # the third measured from where the first ended
    assert it.pos == [0.0, 0.0, -2.0]
