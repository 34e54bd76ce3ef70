"""A plan taken segment by segment is the whole plan: the same timeline, the same limit report
and the same figures per move, so that cnc-plan can report on a program of millions of moves
in memory bounded by a segment.
"""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import example, given, settings

from cli.plan import main
from planner.gcode.interpreter import parse_file, parse_program
from planner.motion.plan import plan_program, plan_segments, report_segments
from tests.planner.motion_programs import paper_machine, programs, random_program, xyza_machine


def _reports_equal(a: dict, b: dict) -> None:
    assert a.keys() == b.keys()
    for key, value in a.items():
        if isinstance(value, dict):
            _reports_equal(value, b[key])
        elif isinstance(value, float):
            assert value == pytest.approx(b[key], rel=1e-9, abs=1e-12), key
        else:
            assert value == b[key], key


def _check(program, machine, segment_moves: int, granular: bool = True) -> None:
    whole = plan_program(program, machine)
    segs = list(plan_segments(program, machine, window=4, segment_moves=segment_moves))
    assert sum(len(s.table) for s in segs) == len(program.moves)
    if segs and granular:
        assert len(segs) >= len(program.moves) // (4 * segment_moves)
        np.testing.assert_array_equal(np.concatenate([s.t0 for s in segs]), whole.t0)
        assert segs[-1].t_end == whole.cycle_time_s
    streamed = report_segments(program, machine, whole.interpolation, iter(segs))
    _reports_equal(streamed.to_dict(), whole.limit_report().to_dict())


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("segment_moves", [1, 3, 17])
def test_segments_are_the_whole_plan(seed, segment_moves):
    machine = xyza_machine() if seed % 2 else paper_machine()
    program = parse_program(random_program(seed, n_blocks=40, rotary=bool(seed % 2)), "r.ngc", machine)
    assert len(program.moves) > 20
    _check(program, machine, segment_moves)


GO_SLOWER_AT_A_SEGMENT_JOINT = (
    "G21 G90 G94 G17 F1800\nG00 X0 Y0 Z0\nG04 P0.05\nG01 X0 Y0 Z1 F1800\nG01 X0 Y0 Z2 F1800\n"
    "G01 X1 Y0 Z2 F1800\nG01 X6 Y0 Z2 F300\nG01 X6 Y0 Z3 F1800\nM30\n")


@settings(max_examples=40, deadline=None)
@example(GO_SLOWER_AT_A_SEGMENT_JOINT)  # once reported a speed violation the whole plan has not
@given(programs(max_blocks=14))
def test_generated_programs_report_the_same_in_segments(text):
    # a drawn program can be one stretch of short moves (a small curve's arcs) none of whose
    # speeds is final before its end: one segment, so the count of segments is not checked
    machine = paper_machine()
    _check(parse_program(text, "g.ngc", machine), machine, 2, granular=False)


def test_violations_are_found_in_segments_as_in_the_whole_plan():
    # planned for a fast machine, measured against a slow one: the meter must find every
    # violation and its worst line in whichever segment it falls
    fast = paper_machine()
    slow = fast.with_limits(v_max_mm_s=10.0, a_max_mm_s2=300.0, j_max_mm_s3=3000.0)
    zigzag = "".join(f"X{i * 0.5:.1f} Y{(i % 2) * 0.5:.1f}\n" for i in range(1, 80))
    program = parse_program("G1 F1800\n" + zigzag + "G0 X0 Y0\n", "v.ngc", fast)
    whole = replace(plan_program(program, fast), machine=slow).limit_report()
    assert whole.violations
    segments = plan_segments(program, fast, window=4, segment_moves=5)
    streamed = report_segments(program, slow, "exact", segments)
    _reports_equal(streamed.to_dict(), whole.to_dict())


def test_empty_program_reports_one_still_sample():
    machine = paper_machine()
    program = parse_program("M2\n", "e.ngc", machine)
    rep = report_segments(program, machine, "exact", plan_segments(program, machine))
    assert rep.samples == 1 and rep.ok


def test_cli_json_is_the_whole_plans(tmp_path, capsys):
    """cnc-plan --json plans and measures segment by segment; its figures are the whole plan's."""
    path = tmp_path / "p.ngc"
    path.write_text(random_program(3, n_blocks=60))
    assert main([str(path), "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    machine_program = parse_file(path)
    from cli.plan import build_machine

    machine = build_machine(None, None, None, None, None)
    from planner.motion.blending import blend_program

    plan = plan_program(blend_program(parse_file(path, machine), machine), machine)
    assert got["moves"] == len(plan.program.moves) and len(machine_program.moves) > 30
    assert got["cycle_time_s"] == plan.cycle_time_s
    assert got["samples"] == plan.n_samples
    assert got["move_list"] == plan.moves_summary()
    _reports_equal({k: got[k] for k in ("tangential", "axes", "violations", "contour_error_mm")},
                   {k: plan.limit_report().to_dict()[k] for k in ("tangential", "axes", "violations",
                                                                  "contour_error_mm")})


def test_feed_changes_at_every_segment_joint_report_as_the_whole_plan():
    # a sample pair across a segment's first joint belongs to two moves and is held to the
    # faster one's feed, which only the segment before knows
    machine = paper_machine()
    lines = "".join(f"G1 X{i * 2.0:.1f} Y{(i % 2) * 0.3:.1f} F{(600, 1800)[i % 2]}\n" for i in range(1, 60))
    program = parse_program(lines, "f.ngc", machine)
    whole = plan_program(program, machine).limit_report()
    assert whole.ok
    segments = plan_segments(program, machine, window=2, segment_moves=1)
    streamed = report_segments(program, machine, "exact", segments)
    _reports_equal(streamed.to_dict(), whole.to_dict())


def test_cli_json_with_samples_written_reports_the_same(tmp_path, capsys):
    """With --csv the whole plan is kept (its samples are written); the JSON is the same."""
    path = tmp_path / "p.ngc"
    path.write_text(random_program(5, n_blocks=30))
    assert main([str(path), "--json"]) == 0
    streamed = json.loads(capsys.readouterr().out)
    assert main([str(path), "--json", "--csv", str(tmp_path / "s.csv")]) == 0
    whole = json.loads(capsys.readouterr().out)
    for key in ("moves", "cycle_time_s", "samples", "move_list", "violations", "ok", "blends"):
        assert streamed[key] == whole[key], key
    _reports_equal(streamed["axes"], whole["axes"])
    assert (tmp_path / "s.csv").read_text().count("\n") == whole["samples"] + 1


@pytest.mark.parametrize("with_json", [False, True])
def test_sample_files_hold_the_whole_plans_samples(tmp_path, capsys, with_json):
    """--samples and --csv are written chunk by chunk as the samples are made (with --json, by
    the limit report's own pass); they hold exactly the whole plan's samples."""
    from cli.plan import build_machine
    from planner.motion.blending import blend_program

    path = tmp_path / "p.ngc"
    path.write_text(random_program(11, n_blocks=40))
    npz, csv = tmp_path / "s.npz", tmp_path / "s.csv"
    extra = ["--json"] if with_json else []
    assert main([str(path), "--samples", str(npz), "--csv", str(csv), *extra]) == 0
    capsys.readouterr()
    machine = build_machine(None, None, None, None, None)
    want = plan_program(blend_program(parse_file(path, machine), machine), machine).collect()
    got = np.load(npz)
    for name in ("t", "q", "s", "line"):
        np.testing.assert_array_equal(got[name], getattr(want, name), err_msg=name)
    rows = csv.read_text().splitlines()
    assert len(rows) == len(want) + 1 > 1000
    assert rows[-1].split(",")[-1] == str(int(want.line[-1]))


def test_plan_program_reports_the_moves_planned():
    machine = paper_machine()
    raster = "".join(f"X{(i % 500) * 0.1:.1f} Y{(i // 500) * 0.2:.1f}\n" for i in range(150_000))
    program = parse_program("G1 F600\n" + raster, "r.ngc", machine)
    seen: list[tuple[int, int]] = []
    plan_program(program, machine, progress=lambda done, total: seen.append((done, total)))
    n = len(program.moves)
    assert seen[-1] == (n, n) and len(seen) >= 2
    assert [d for d, _ in seen] == sorted(d for d, _ in seen)


def test_a_plan_of_many_segments_joined_is_the_streamed_one():
    """plan_program joins segments of 16,384 moves, its table's ends views of the program's own
    positions: its samples are the stream's, one by one."""
    from planner.motion.plan import stream_program

    machine = paper_machine()
    raster = "".join(f"X{(i % 400) * 0.1:.1f} Y{(i // 400) * 0.2:.1f}\n" for i in range(40_000))
    program = parse_program("G1 F1800\n" + raster, "r.ngc", machine)
    plan = plan_program(program, machine)
    table = plan.segment.table
    np.testing.assert_array_equal(table.end, program.moves.positions[1:])
    np.testing.assert_array_equal(table.start, program.moves.positions[:-1])
    whole = plan.collect()
    streamed = [c for c in stream_program(program, machine)]
    q = np.concatenate([c.q for c in streamed])
    assert len(whole) == len(q) > 100_000
    np.testing.assert_array_equal(whole.q, q)


def _fields_equal(a, b, path: str) -> None:
    for name in type(a).__slots__:
        x, y = getattr(a, name), getattr(b, name)
        if hasattr(x, "__slots__"):
            _fields_equal(x, y, f"{path}.{name}")
        elif isinstance(x, np.ndarray):
            np.testing.assert_array_equal(x, y, err_msg=f"{path}.{name}")
            assert x.dtype == y.dtype, f"{path}.{name}"
            repeated = bool(y.ndim and y.shape[0] > 1 and y.strides[0] == 0)
            assert (x.ndim and x.shape[0] > 1 and x.strides[0] == 0) == repeated, f"{path}.{name}"
        else:
            assert x == y, f"{path}.{name}"


@pytest.mark.parametrize("segment_moves", [1, 4, 9])
def test_segments_joined_as_they_come_are_the_segment_of_all_blocks(segment_moves):
    """A plan joined segment by segment (each let go once added) is the one segment made of all
    blocks at once, column by column: columns of one repeated row (no arcs yet) filled in once
    the first arc comes, and stay one repeated row where no segment has any."""
    from planner.motion.interpolate import SegmentJoin

    machine = paper_machine()
    lines = "".join(f"G1 X{i % 5} Y{i // 5 * 0.5:.1f}\n" for i in range(12))
    text = "G21 G90 G17 F900\n" + lines + "G2 X3 Y1 I1 J0\nG1 X0 Y0\nG3 X2 Y0 I1 J0\n"
    program = parse_program(text, "a.ngc", machine)
    whole = next(iter(plan_segments(program, machine, window=4, segment_moves=10**9)))
    assert len(whole.table) == len(program.moves)
    assert bool(whole.table.is_arc.any()) and not bool(whole.table.is_arc[: segment_moves + 1].any())
    parts = list(plan_segments(program, machine, window=4, segment_moves=segment_moves))
    assert len(parts) >= 2
    join = SegmentJoin(len(program.moves))
    for seg in parts:
        join.add(seg)
    _fields_equal(join.result(), whole, "segment")


def test_a_plans_speeds_are_held_once_where_they_are_the_same_numbers():
    """A move ends at the speed the next starts with, and the cruise cap is the programmed speed
    where the path does not lower it: a plan of millions of moves keeps these once (16 bytes a
    move), as views of one array, joined from segments or not, with the same numbers."""
    from planner.motion.interpolate import SegmentJoin, shared_speeds

    machine = paper_machine()
    text = "G21 G90 G17 F900\n" + "".join(f"G1 X{i % 7} Y{i // 7 * 0.5:.1f}\n" for i in range(60))
    program = parse_program(text, "s.ngc", machine)
    join = SegmentJoin(len(program.moves))
    parts = list(plan_segments(program, machine, window=8, segment_moves=10))
    for part in parts:
        join.add(part)
    assert len(parts) > 3
    for seg in (plan_program(program, machine).segment, join.result()):
        prof = seg.profiles
        assert np.shares_memory(prof.vs, prof.ve) and prof.vs.base is prof.ve.base
        assert np.array_equal(prof.ve[:-1], prof.vs[1:]) and prof.vc is seg.v_prog
    # where they differ, each keeps its own numbers
    odd = replace(prof, ve=prof.ve + 1.0, vc=seg.v_prog * 0.5)
    kept = shared_speeds(odd, seg.v_prog)
    assert kept is odd and not np.shares_memory(kept.vs, kept.ve)


def test_a_joined_plan_takes_the_programs_own_columns_where_they_are_its_rows():
    """The table's line, kind and exact-stop columns are the program's own arrays while every
    segment's rows are the program's; a column some segment differs from is joined from the
    segments, its earlier rows taken from the program."""
    from planner.motion.interpolate import SegmentJoin

    machine = paper_machine()
    text = "G21 G90 G17 F900\n" + "".join(f"G1 X{i % 7} Y{i // 7 * 0.5:.1f}\n" for i in range(60))
    program = parse_program(text, "s.ngc", machine)
    cols = program.moves.columns()
    parts = list(plan_segments(program, machine, window=8, segment_moves=10))
    whole = next(iter(plan_segments(program, machine, window=8, segment_moves=10**9)))
    given = {name: getattr(cols, name) for name in SegmentJoin.PROGRAM_COLUMNS}
    # a program whose line numbers differ from the plan's from row 25 on
    odd_lines = cols.line.copy()
    odd_lines[25:] += 1
    cases = ((given, set(given)), ({**given, "line": odd_lines}, set(given) - {"line"}))
    for program_columns, shared in cases:
        join = SegmentJoin(len(program.moves), program.moves.positions, program_columns)
        for part in parts:
            join.add(part)
        table = join.result().table
        for name in SegmentJoin.PROGRAM_COLUMNS:
            np.testing.assert_array_equal(getattr(table, name), getattr(whole.table, name))
            assert np.shares_memory(getattr(table, name), program_columns[name]) == (name in shared), name
