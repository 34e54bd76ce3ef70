"""Interpolation at Ts: exact / taylor / classic, chunked streaming, vectorised geometry."""

from __future__ import annotations

import time

import numpy as np
import pytest

from planner.geometry.movetable import MoveTable
from planner.motion.interpolate import SampleChunk
from planner.motion.plan import plan_program, stream_program
from tests.planner.motion_programs import paper_machine, parse, random_program, sample_program


def test_vectorised_geometry_equals_move_evaluate():
    m = paper_machine()
    moves = []
    for seed in range(10):
        moves += parse(random_program(seed, n_blocks=40), m).moves
    table = MoveTable.from_moves(moves, 3)
    assert table.spiral.any() and table.is_arc.any()  # CAM-like rounding gives spirals
    rng = np.random.default_rng(0)
    row = rng.integers(0, len(moves), 20000)
    u = rng.uniform(0, 1, row.size) * table.length[row]
    u[:50] = table.length[row[:50]]
    u[50:100] = 0.0
    q = table.positions(row, u)
    for i in np.unique(row):
        sel = row == i
        ref = moves[i].evaluate(u[sel])[0]
        np.testing.assert_allclose(q[sel], ref, rtol=0, atol=1e-9)
    # End tangents too.
    t_start, t_end = table.end_tangents()
    for i, mv in enumerate(moves):
        _, tan, _ = mv.evaluate(np.array([0.0, mv.length_mm]))
        np.testing.assert_allclose(t_start[i], tan[0], atol=1e-9)
        np.testing.assert_allclose(t_end[i], tan[1], atol=1e-9)


@pytest.mark.parametrize("interp, tol", [("exact", 0.0), ("classic", 0.0), ("taylor", 1e-5)])
@pytest.mark.parametrize("mode", ["lookahead", "paper"])
def test_streaming_equals_whole_plan(interp, tol, mode):
    m = paper_machine()
    prog = parse(random_program(3, n_blocks=60), m)
    whole = plan_program(prog, m, mode=mode, interpolation=interp).collect()
    chunks = list(stream_program(prog, m, mode=mode, interpolation=interp, chunk_samples=3000, window=5))
    assert max(len(c) for c in chunks) <= 3000
    got = SampleChunk.concat(chunks, 3)
    assert len(got) == len(whole)
    np.testing.assert_array_equal(got.t, whole.t)
    np.testing.assert_allclose(got.q, whole.q, rtol=0, atol=max(tol, 1e-12))
    if interp != "taylor":  # Taylor's path length may sit on either side of a joint there
        np.testing.assert_array_equal(got.line, whole.line)


def test_chunks_are_bounded_and_restart_mid_program():
    m = paper_machine()
    plan = plan_program(parse(random_program(4, n_blocks=50), m), m)
    full = plan.collect()
    sizes = [len(c) for c in plan.iter_chunks(chunk_samples=1000)]
    assert max(sizes) <= 1000 and sum(sizes) == len(full) == plan.n_samples
    late = SampleChunk.concat(list(plan.iter_chunks(1000, t_start_s=1.2345)), 3)
    k = int(np.ceil(1.2345 / plan.ts_s))
    np.testing.assert_allclose(late.q, full.q[k:], rtol=0, atol=1e-12)  # SIMD ulps
    assert full.t[0] == 0.0 and full.t[-1] >= plan.cycle_time_s
    np.testing.assert_array_equal(full.q[0], plan.program.start_position)
    np.testing.assert_array_equal(full.q[-1], plan.program.end_position)


def test_samples_carry_line_move_and_cumulative_path_length():
    m = paper_machine()
    prog = sample_program("fig7_circle.nc", m)
    plan = plan_program(prog, m)
    c = plan.collect()
    assert set(np.unique(c.line)) == {mv.line for mv in prog.moves}
    assert np.all(np.diff(c.s) >= -1e-12)
    assert c.s[-1] == pytest.approx(sum(mv.length_mm for mv in prog.moves))
    assert np.all(np.diff(c.move_index) >= 0)


def test_classic_runs_every_move_at_constant_speed_in_whole_samples():
    m = paper_machine()
    prog = sample_program("fig9_helix.nc", m)
    plan = plan_program(prog, m, interpolation="classic")
    c = plan.collect()
    seg = plan.segment
    for i in range(len(seg.table)):
        ts = plan.ts_s
        n_steps = round((plan.t0[i + 1] - plan.t0[i]) / ts) if i + 1 < len(seg.table) else None
        if n_steps is not None:
            assert n_steps == int(np.ceil(seg.table.length[i] / (seg.v_prog[i] * ts) - 1e-9))
    # Eq. 17: constant increment -> the speed jumps from 0 to Vmax in one sample.
    speed = np.diff(c.s) / plan.ts_s
    assert speed[0] == pytest.approx(30.0, rel=1e-9) or speed[1] == pytest.approx(30.0, rel=1e-9)
    rep = plan.limit_report()
    assert "axis_a" in rep.violations


def test_taylor_stays_on_the_path_and_close_to_exact():
    m = paper_machine()
    prog = sample_program("pocket.nc", m)
    exact = plan_program(prog, m).collect()
    plan = plan_program(prog, m, interpolation="taylor")
    taylor = plan.collect()
    assert len(taylor) == len(exact)
    assert np.max(np.abs(taylor.s - exact.s)) < 1e-3  # Eq. 16 drops the jerk term
    rep = plan.limit_report()
    assert rep.contour_error_mm <= 1e-9 and not rep.nan and rep.time_increasing
    assert rep.end_error_mm < 1e-3


def test_first_set_point_comes_quickly_whatever_the_length():
    m = paper_machine()
    lines = ["G21 G90 F1800"]
    for i in range(20000):
        lines.append(f"G01 X{(i % 2) * 0.5 + i * 0.01:.3f} Y{i * 0.3:.3f}")
    prog = parse("\n".join(lines) + "\nM30\n", m)
    started = time.perf_counter()
    gen = stream_program(prog, m, chunk_samples=4096)
    first = next(gen)
    latency = time.perf_counter() - started
    gen.close()
    assert len(first) > 0
    assert latency < 0.25, latency  # bench_plan measures it precisely (target 50 ms)


def test_empty_program_and_dwells():
    m = paper_machine()
    empty = plan_program(parse("M30\n", m), m)
    c = empty.collect()
    assert len(c) == 1 and empty.cycle_time_s == 0.0 and empty.limit_report().ok
    prog = parse("G21 G90 F600\nG04 P0.2\nG01 X1\nG04 P0.3\nG01 X2\nM30\n", m)
    plan = plan_program(prog, m)
    assert plan.t0[0] == pytest.approx(0.2)  # a dwell before the first move delays it
    assert plan.t0[1] - plan.t1[0] == pytest.approx(0.3)
    c = plan.collect()
    still = (c.t >= plan.t1[0]) & (c.t < plan.t0[1])
    assert still.sum() >= 299 and np.all(c.q[still] == [1.0, 0.0, 0.0])
    assert np.all(c.q[c.t <= 0.2] == 0.0)
    assert plan.limit_report().ok


def test_spiral_polynomial_parameter_equals_newton():
    from planner.geometry.movetable import _spiral_newton

    m = paper_machine()
    moves = []
    for seed in range(10):
        moves += [mv for mv in parse(random_program(seed, n_blocks=40), m).moves if mv.arc is not None]
    table = MoveTable.from_moves(moves, 3)
    rows = np.nonzero(table.spiral_poly_ok)[0]
    assert rows.size > 10
    row = np.repeat(rows, 50)
    u = np.tile(np.linspace(0, 1, 50), rows.size) * table.length[row]
    t_poly = table.spiral_param(row, u)
    t_newton = _spiral_newton(table.r0[row], table.r1[row], table.sweep[row], table.rise[row],
                              table.length[row], u)
    assert np.max(np.abs(t_poly - t_newton) * table.length[row]) < 1e-12


def test_plane_frames_are_what_each_move_evaluates():
    """Row by row, MoveTable.plane_frames gives what Move.evaluate gives on lines and plane arcs
    (CAM's spirals among them): position, unit tangent, curvature signed by the arc's turn, and
    the arc's angle fraction at u."""
    from planner.core.program import MoveKind, arc_param_at_length

    m = paper_machine()
    moves = []
    for seed in range(8):
        moves += [mv for mv in parse(random_program(seed, n_blocks=40), m).moves
                  if mv.kind in (MoveKind.LINE, MoveKind.ARC)
                  and (mv.arc is None or (mv.arc.rise_mm == 0.0 and mv.arc.xy_turn_rad == 0.0))]
    n_arcs = sum(mv.arc is not None for mv in moves)
    assert n_arcs > 20 and len(moves) - n_arcs > 20
    assert any(mv.arc is not None and mv.arc.radius_end_mm != mv.arc.radius_start_mm for mv in moves)
    table = MoveTable.from_moves(moves, 3)
    x = np.array([0.0, 0.013, 0.31, 0.5, 0.77, 0.999])
    row = np.repeat(np.arange(len(moves)), x.size)
    u = np.tile(x, len(moves)) * table.length[row]
    pos, tangent, kappa, frac = table.plane_frames(row, u)
    for i, mv in enumerate(moves):
        k = slice(i * x.size, (i + 1) * x.size)
        p, t, c = mv.evaluate(u[k])
        np.testing.assert_allclose(pos[k], p, rtol=0, atol=1e-9 * (1.0 + np.abs(p).max()))
        np.testing.assert_allclose(tangent[k], t, rtol=0, atol=1e-12)
        if mv.arc is None:
            assert (kappa[k] == 0.0).all() and frac[k] == pytest.approx(x, abs=1e-15)
        else:
            np.testing.assert_allclose(kappa[k], np.sign(mv.arc.sweep_rad) * c, rtol=1e-9)
            np.testing.assert_allclose(frac[k], arc_param_at_length(mv.arc, u[k], mv.length_mm), atol=1e-12)
