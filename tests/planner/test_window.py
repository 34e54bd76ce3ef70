"""A plan made as the run reaches it (``PlanWindow``) is the whole plan, piece by piece: the
same samples, the same end; it holds only the segments around where it is read, and says so
when asked for a move it no longer (or not yet) holds."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.core.errors import PlannerError
from planner.gcode.interpreter import parse_program
from planner.motion.interpolate import SampleChunk
from planner.motion.plan import plan_program
from planner.motion.window import PlanWindow
from tests.planner.motion_programs import paper_machine, programs, random_program, short_move_raster


def _collect(win: PlanWindow, let_go: bool) -> SampleChunk:
    return SampleChunk.concat(list(win.iter_chunks(chunk_samples=97, let_go=let_go)), len(win.program.axes))


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("segment_moves", [1, 5, 64])
def test_a_window_samples_the_whole_plan(seed: int, segment_moves: int) -> None:
    machine = paper_machine()
    program = parse_program(random_program(seed, n_blocks=40), "r.ngc", machine)
    whole = plan_program(program, machine).collect()
    win = PlanWindow(program, machine, segment_moves=segment_moves)
    got = _collect(win, let_go=True)
    for name in SampleChunk.__slots__:
        np.testing.assert_array_equal(getattr(got, name), getattr(whole, name), err_msg=name)
    assert win.done and win.t_end == plan_program(program, machine).cycle_time_s


@settings(max_examples=30, deadline=None)
@given(st.sampled_from([0.001, 1.0, 1000.0]).flatmap(lambda scale: programs(max_blocks=12, scale=scale)),
       st.sampled_from([1, 3, 16]))
def test_drawn_programs_at_any_scale_plan_alike_in_a_window(text: str, segment_moves: int) -> None:
    # each move's start time, speeds and phase times as the whole plan's, to the bit (the
    # samples follow from them; compared above on programs of ordinary length)
    machine = paper_machine()
    program = parse_program(text, "g.ngc", machine)
    whole = plan_program(program, machine).segment
    win = PlanWindow(program, machine, segment_moves=segment_moves)
    seen: list = []
    win.on_segment = seen.append
    win.ensure(math.inf)
    assert win.done
    if not len(whole.table):
        assert not seen
        return
    for name in ("t0", "s0"):
        np.testing.assert_array_equal(np.concatenate([getattr(g, name) for g in seen]), getattr(whole, name))
    for name in ("vs", "ve", "duration"):
        np.testing.assert_array_equal(np.concatenate([getattr(g.profiles, name) for g in seen]),
                                      getattr(whole.profiles, name))
    assert win.t_end == whole.t_end




def test_a_pass_that_lets_go_holds_a_few_segments_whatever_the_program() -> None:
    machine = paper_machine()
    most = []
    for rows in (40, 160):
        win = PlanWindow(parse_program(short_move_raster(rows), "r.ngc", machine), machine, segment_moves=32)
        held = 0
        for _ in win.iter_chunks(chunk_samples=200, let_go=True):
            held = max(held, len(win.segment.table))
        assert win.done
        most.append(held)
    assert most[1] <= most[0]
    assert most[1] < 0.1 * 21 * 160


def test_until_its_last_segment_the_end_is_not_known_and_the_estimate_stands_for_it() -> None:
    machine = paper_machine()
    program = parse_program(short_move_raster(30), "r.ngc", machine)
    win = PlanWindow(program, machine, segment_moves=16, estimate_s=123.0)
    win.ensure(0.5)
    assert not win.done and math.isinf(win.t_end) and win.cycle_time_s == 123.0
    without = PlanWindow(program, machine, segment_moves=16)
    without.ensure(0.5)
    assert without.cycle_time_s == without.covered_until > 0.5
    win.ensure(math.inf)
    assert win.done and win.cycle_time_s == win.t_end == plan_program(program, machine).cycle_time_s


def test_a_move_outside_the_window_is_refused_with_where_the_window_is() -> None:
    machine = paper_machine()
    program = parse_program(short_move_raster(30), "r.ngc", machine)
    win = PlanWindow(program, machine, segment_moves=16)
    win.ensure(2.0)
    beyond = int(win.segment.table.index[-1]) + 1
    with pytest.raises(PlannerError, match=rf"move {beyond} is not in the planned window \(moves 0\.\."):
        win.move_start_s(beyond)
    win.ensure(8.0)
    win.release(6.0)
    assert win.first_move > 0
    assert win.move_start_s(win.first_move) == pytest.approx(float(win.segment.s0[0]))
    with pytest.raises(PlannerError, match="is not in the planned window"):
        win.move_start_s(0)


def test_a_window_needs_segments_of_a_move_at_least() -> None:
    machine = paper_machine()
    program = parse_program(short_move_raster(2), "r.ngc", machine)
    with pytest.raises(PlannerError, match="at least one move"):
        PlanWindow(program, machine, segment_moves=0)


def test_a_program_without_moves_is_one_still_sample() -> None:
    machine = paper_machine()
    win = PlanWindow(parse_program("G4 P1\nM2\n", "e.ngc", machine), machine)
    assert win.done and win.t_end == 0.0
    (chunk,) = list(win.iter_chunks())
    assert len(chunk) == 1
